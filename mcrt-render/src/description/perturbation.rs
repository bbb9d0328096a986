//! Mitsuba 3's `normalmap` and `bumpmap`: a nested material seen in a shading frame whose
//! normal a texture perturbs ([`BsdfDesc::Perturbed`](super::BsdfDesc::Perturbed)). The
//! renderer forms the perturbed normal per hit (`bsdf::Perturbed`); the derivation of the
//! bump-mapped normal is in `docs/bsdf-models.md`, "Normal and bump maps".

use super::Texture;

/// Where the perturbed shading normal comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum NormalSource {
    /// `normalmap`: an RGB texture holding tangent-space normals as `(n + 1)/2` (read as
    /// its `bitmap` says: sRGB-decoded unless `raw`, as in Mitsuba 3), relative to the
    /// shading frame whose `s` axis is the tangent `dp/du`.
    NormalMap(Texture),
    /// `bumpmap`: a height field whose gradient along (u, v), times `scale`, tilts the
    /// surface (Blinn 1978); a bitmap's gradient is that of its bilinear interpolation.
    BumpMap {
        /// The height field (its luminance, for an RGB image).
        height: Texture,
        /// Mitsuba's `scale` on the gradient (default 1; any finite value).
        scale: f32,
    },
}

/// A perturbation of the shading normal, with Mitsuba 3.9.1's two options.
#[derive(Debug, Clone, PartialEq)]
pub struct Perturbation {
    /// The texture and how it is read.
    pub source: NormalSource,
    /// `flip_invalid_normals` (default true): a perturbed normal on the other side of the
    /// viewing direction than the shading normal is mirrored about the shading normal
    /// (its tangential part negated; Schüssler et al. 2017, "Microfacet-based Normal
    /// Mapping for Robust Monte Carlo Path Tracing", ACM TOG 36(6)).
    pub flip_invalid_normals: bool,
    /// `use_shadowing_function` (default true): the material's value is scaled by a
    /// microfacet shadowing term of the perturbation (Estevez, Kulla, Kohl 2019, "A
    /// Microfacet-Based Shadowing Function to Solve the Bump Terminator Problem", Ray
    /// Tracing Gems).
    pub use_shadowing_function: bool,
}

impl Perturbation {
    /// A perturbation from `source` with Mitsuba 3.9.1's default options (both true).
    pub fn new(source: NormalSource) -> Self {
        Self {
            source,
            flip_invalid_normals: true,
            use_shadowing_function: true,
        }
    }

    /// The texture.
    pub fn texture(&self) -> &Texture {
        match &self.source {
            NormalSource::NormalMap(t) | NormalSource::BumpMap { height: t, .. } => t,
        }
    }
}
