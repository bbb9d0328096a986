//! What the renderer can use: the checks on the parts of a [`SceneDescription`] that their
//! types do not already make, and the bounds that keep any scene's memory and work finite.
//! They are the checked constructors of the description's parts:
//! [`Checked::new`](crate::description::Checked::new) runs a part's [`Check`], whose impls
//! (at the bottom of this file) call the functions here, once, when the part is made. The
//! XML loader makes each part where it reads the element (so its errors name file, line and
//! element); a description built in code goes through the same constructors. A
//! [`SceneDescription`] holds only [`Checked`](crate::description::Checked) parts, so
//! nothing downstream, [`Renderer::new`](crate::render::Renderer::new) included, walks it to
//! check it again: the renderer checks only the total [`work`], which depends on the
//! render's overrides (`render/samples.rs`). A roughness ([`Roughness`]), a sample count
//! ([`SampleCount`]), a colour ([`Colour`]: every reflectance, transmittance, conductor
//! index and emitted colour) and an index of refraction ([`Ior`]) are checked when they are
//! made, and never again; the integrators' parameters are checked against their one
//! definition each (`param_defs`).
//!
//! [`SceneDescription`]: crate::description::SceneDescription
//!
//! The bounds, also listed in `docs/scene-format.md`:
//!
//! | what | bound |
//! |---|---|
//! | film pixels, width × height | [`MAX_FILM_PIXELS`] = 2²⁵ (8K UHD fits) |
//! | `sample_count` | [`MAX_SAMPLE_COUNT`] = 2²⁴ |
//! | `emitter_samples`, `bsdf_samples` | [`MAX_SHADING_SAMPLES`] = 2¹⁶ each |
//! | pixels × spp × max(1, emitter + bsdf samples) | [`MAX_WORK`] = 2⁴² |
//! | roughness α | [[`MIN_ROUGHNESS`], 10] ([`Roughness`]); the loader clamps smaller α to 10⁻⁴ as Mitsuba 3 does |

use crate::description::{
    BsdfDesc, Check, Colour, EmitterDesc, FilmDesc, FilterDesc, IntegratorDesc, Ior, Projection,
    Roughness, SampleCount, SensorDesc, ShapeDesc, ShapeGroupDesc, ShapeKind,
};
use glam::{Mat4, Vec3, Vec4};

/// Largest film, in pixels: 2²⁵ (33.5 M, e.g. 8192 × 4096 or 7680 × 4320). The film keeps
/// about 64 bytes per pixel (sums, squares, counts and the output image), so at most about
/// 2 GiB.
pub const MAX_FILM_PIXELS: u64 = 1 << 25;

/// Largest `sample_count` (samples per pixel): 2²⁴ ([`SampleCount::MAX`]).
pub const MAX_SAMPLE_COUNT: u32 = SampleCount::MAX;

pub use crate::param_defs::integrator::{MAX_MLT_DEPTH, MAX_SHADING_SAMPLES};

/// Largest total work, pixels × spp × max(1, emitter + bsdf samples): 2⁴² (4.4 · 10¹²,
/// about a day at 50 M samples per second).
pub const MAX_WORK: u64 = 1 << 42;

/// Smallest microfacet roughness the renderer takes (Mitsuba 3 clamps to the same value;
/// [`Roughness::MIN`]).
pub const MIN_ROUGHNESS: f32 = Roughness::MIN;

/// Largest microfacet roughness the renderer takes ([`Roughness::MAX`]).
pub const MAX_ROUGHNESS: f32 = Roughness::MAX;

pub use crate::invalid::Invalid;

/// π in f64, for the bounds on the lights' power.
const PI64: f64 = std::f64::consts::PI;

#[cfg(test)]
thread_local! {
    /// How many of the checks here have run on this thread: the test that preparing a
    /// render checks no part of its description reads it.
    pub(crate) static CHECKS_RUN: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// Counts a check in [`CHECKS_RUN`] (nothing outside the unit tests).
#[inline]
fn tally() {
    #[cfg(test)]
    CHECKS_RUN.with(|c| c.set(c.get() + 1));
}

fn invalid(param: &'static str, message: impl Into<String>) -> Invalid {
    Invalid::new(param, message)
}

/// An emitted quantity `v` whose power, `factor` times its mean channel (for a scene of unit
/// size), must be a finite `f32`: past that, the light's power, by which lights are
/// chosen, overflows (issue 26: such a light was dropped without a word).
pub fn emission_power(param: &'static str, v: Vec3, factor: f64) -> Result<(), Invalid> {
    let mean = (f64::from(v.x) + f64::from(v.y) + f64::from(v.z)) / 3.0;
    let max = f64::from(f32::MAX);
    if factor * mean <= max {
        return Ok(());
    }
    Err(invalid(
        param,
        format!(
            "has mean {mean:e}: the light's power, {factor:.4} × that, exceeds the largest \
             f32, {:e} (the mean may be at most {:.4e})",
            f32::MAX,
            max / factor
        ),
    ))
}

/// An object-to-world transform: finite, affine (last row 0 0 0 1) and invertible.
pub fn transform(param: &'static str, m: &Mat4) -> Result<(), Invalid> {
    tally();
    if !m.is_finite() {
        return Err(invalid(param, "is not finite"));
    }
    if m.row(3).distance(Vec4::W) > 1e-6 {
        return Err(invalid(
            param,
            "is projective (its last row is not 0 0 0 1); only affine transforms are supported",
        ));
    }
    let det = glam::Mat3::from_mat4(*m).determinant();
    if det == 0.0 || !det.is_finite() {
        return Err(invalid(param, "is singular"));
    }
    Ok(())
}

/// A film: non-empty, at most [`MAX_FILM_PIXELS`], with a usable filter.
fn film(f: &FilmDesc) -> Result<(), Invalid> {
    tally();
    let pixels = f.width as u64 * f.height as u64;
    if pixels == 0 {
        return Err(invalid("width", "and height must be positive"));
    }
    if pixels > MAX_FILM_PIXELS {
        return Err(invalid(
            "width",
            format!(
                "× height = {} × {} = {pixels} pixels exceeds the limit of {MAX_FILM_PIXELS}",
                f.width, f.height
            ),
        ));
    }
    if let FilterDesc::Gaussian { stddev } = f.filter {
        if !(stddev > 0.0 && stddev <= 16.0) {
            return Err(invalid("stddev", "must lie in (0, 16] pixels"));
        }
    }
    if let FilterDesc::Tent { radius } = f.filter {
        if !(radius > 0.0 && radius <= 16.0) {
            return Err(invalid("radius", "must lie in (0, 16] pixels"));
        }
    }
    let w = f.window();
    let fits = |o: u32, n: u32, full: u32| n > 0 && o.checked_add(n).is_some_and(|e| e <= full);
    if !fits(w.offset_x, w.width, f.width) {
        return Err(invalid(
            "crop_width",
            format!(
                "and crop_offset_x: the window [{}, {} + {}) must be non-empty and lie within the width {}",
                w.offset_x, w.offset_x, w.width, f.width
            ),
        ));
    }
    if !fits(w.offset_y, w.height, f.height) {
        return Err(invalid(
            "crop_height",
            format!(
                "and crop_offset_y: the window [{}, {} + {}) must be non-empty and lie within the height {}",
                w.offset_y, w.offset_y, w.height, f.height
            ),
        ));
    }
    Ok(())
}

/// The integrator's parameters, each against its definition (`param_defs::integrator`).
fn integrator(i: &IntegratorDesc) -> Result<(), Invalid> {
    tally();
    crate::param_defs::integrator::check(i)
}

/// The total work of a render: pixels × spp × max(1, emitter + bsdf samples) at most
/// [`MAX_WORK`].
pub fn work(pixels: u64, spp: u32, i: &IntegratorDesc) -> Result<(), Invalid> {
    let per_sample = match *i {
        IntegratorDesc::Direct(d) => (d.emitter_samples as u64 + d.bsdf_samples as u64).max(1),
        IntegratorDesc::Path(_)
        | IntegratorDesc::Bdpt(_)
        | IntegratorDesc::Ptracer(_)
        | IntegratorDesc::Guided(_) => 1,
        // The bootstrap's paths and normalisation samples, spread over the pixels.
        IntegratorDesc::Mlt(m) => {
            1 + (m.bootstrap_samples as u64 * (m.max_depth.max(1) as u64 + 1)) / pixels.max(1)
        }
    };
    let w = pixels.saturating_mul(spp as u64).saturating_mul(per_sample);
    if w > MAX_WORK {
        return Err(invalid(
            "sample_count",
            format!(
                "× pixels × shading samples = {w} exceeds the limit of {MAX_WORK} \
                 (no machine finishes it)"
            ),
        ));
    }
    Ok(())
}

/// A material that has passed its rules and those of every material nested in it: one
/// the loader made ([`bsdf_element`]), which a shape takes without checking it again
/// ([`shape_with`]).
pub(crate) struct CheckedBsdf(BsdfDesc);

impl CheckedBsdf {
    /// The material, to nest it in another or to put it in a shape.
    pub(crate) fn into_inner(self) -> BsdfDesc {
        self.0
    }
}

impl std::ops::Deref for CheckedBsdf {
    type Target = BsdfDesc;
    fn deref(&self) -> &BsdfDesc {
        &self.0
    }
}

/// The material of one element of a scene file: `b`'s own rules ([`bsdf_own`]) and, when
/// `b` is a texture list, those of the material it wraps (both made from the one element),
/// but not those of the materials nested in it: each of those must be a [`CheckedBsdf`]
/// already (the loader reads them first, each at its own element), so every material is
/// checked once.
pub(crate) fn bsdf_element(b: BsdfDesc) -> Result<CheckedBsdf, Invalid> {
    bsdf_own(&b)?;
    if let BsdfDesc::Textured { inner, .. } = &b {
        bsdf_own(inner)?;
    }
    Ok(CheckedBsdf(b))
}

/// A material and every material nested in it, each by [`bsdf_own`], outer before inner
/// and in their written order (a description built in code; the loader checks each
/// material at its element, [`bsdf_element`]).
fn bsdf(b: &BsdfDesc) -> Result<(), Invalid> {
    bsdf_own(b)?;
    nested(b).into_iter().flatten().try_for_each(bsdf)
}

/// The materials nested directly in `b`, in their written order (a material not listed
/// nests none; [`bsdf_own`] lists every kind).
fn nested(b: &BsdfDesc) -> [Option<&BsdfDesc>; 2] {
    match b {
        BsdfDesc::Blend { first, second, .. } => [Some(first), Some(second)],
        BsdfDesc::Mask { inner, .. }
        | BsdfDesc::TwoSided(inner)
        | BsdfDesc::Perturbed { inner, .. }
        | BsdfDesc::Textured { inner, .. } => [Some(inner), None],
        _ => [None, None],
    }
}

#[cfg(test)]
thread_local! {
    /// How many materials [`bsdf_own`] has checked on this thread: the test that loading
    /// a scene checks each material once.
    pub(crate) static BSDF_CHECKS_RUN: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// A material's own rules, not those of the materials nested in it: what its types do not
/// hold already (its colours are [`Colour`]s and its indices [`Ior`]s, checked when they
/// were made): a plastic's internal scattering, a blend's weight, a mask's opacity, a
/// principled material's parameters, a normal or bump map's texture, and where textures
/// are attached.
fn bsdf_own(b: &BsdfDesc) -> Result<(), Invalid> {
    tally();
    #[cfg(test)]
    BSDF_CHECKS_RUN.with(|c| c.set(c.get() + 1));
    match b {
        BsdfDesc::Diffuse { .. }
        | BsdfDesc::Conductor { .. }
        | BsdfDesc::RoughConductor { .. }
        | BsdfDesc::Dielectric { .. }
        | BsdfDesc::ThinDielectric { .. }
        | BsdfDesc::RoughDielectric { .. }
        | BsdfDesc::TwoSided(_) => Ok(()),
        BsdfDesc::Plastic {
            int_ior,
            ext_ior,
            diffuse_reflectance,
            nonlinear,
            ..
        }
        | BsdfDesc::RoughPlastic {
            int_ior,
            ext_ior,
            diffuse_reflectance,
            nonlinear,
            ..
        } => plastic(*int_ior, *ext_ior, *diffuse_reflectance, *nonlinear),
        BsdfDesc::Principled(params) => principled(params),
        BsdfDesc::Blend { weight, .. } => unit_interval("weight", *weight),
        BsdfDesc::Mask { opacity, .. } => unit_interval("opacity", *opacity),
        BsdfDesc::Perturbed { perturbation, .. } => perturbation_values(perturbation),
        BsdfDesc::Textured { inner, textures } => {
            if matches!(**inner, BsdfDesc::TwoSided(_) | BsdfDesc::Textured { .. }) {
                return Err(invalid(
                    "textures",
                    "must be attached to a material, not to twosided or another texture list",
                ));
            }
            for (i, (param, texture)) in textures.iter().enumerate() {
                if !inner.has_param(*param) {
                    return Err(invalid(param.name(), "is not a parameter of this material"));
                }
                if textures[..i].iter().any(|(p, _)| p == param) {
                    return Err(invalid(param.name(), "is textured twice"));
                }
                texture_values(param.name(), texture)?;
            }
            Ok(())
        }
    }
}

/// A normal or bump map: a bitmap (Mitsuba 3.9.1 cannot take a checkerboard's RGB normals
/// nor its gradient: it fails when rendering), with finite numbers and a finite `scale`.
fn perturbation_values(p: &crate::description::Perturbation) -> Result<(), Invalid> {
    use crate::description::NormalSource;
    use crate::texture::Texture;
    let name = match p.source {
        NormalSource::NormalMap(_) => "normalmap",
        NormalSource::BumpMap { scale, .. } => {
            if !scale.is_finite() {
                return Err(invalid("scale", "must be finite"));
            }
            "texture"
        }
    };
    if !matches!(p.texture(), Texture::Bitmap(_)) {
        return Err(invalid(
            name,
            "must be a bitmap (Mitsuba 3.9.1 cannot evaluate a checkerboard's normals or \
             gradient)",
        ));
    }
    texture_values(name, p.texture())
}

/// A texture's own numbers: finite colours and a finite `to_uv`.
fn texture_values(param: &'static str, t: &crate::texture::Texture) -> Result<(), Invalid> {
    use crate::texture::Texture;
    let ok = match t {
        Texture::Bitmap(b) => b.to_uv.is_finite(),
        Texture::Checkerboard(c) => {
            c.to_uv.is_finite() && c.color0.is_finite() && c.color1.is_finite()
        }
    };
    if ok {
        Ok(())
    } else {
        Err(invalid(
            param,
            "has a texture with a non-finite colour or to_uv",
        ))
    }
}

/// A blend weight or an opacity: in [0, 1] (outside, Mitsuba's probabilities would turn
/// negative).
/// A principled material: [`PrincipledParams::check`](crate::bsdf::PrincipledParams::check),
/// its error named by the parameter.
fn principled(p: &crate::bsdf::PrincipledParams) -> Result<(), Invalid> {
    p.check().map_err(|e| match e {
        mcrt::sampling::SamplingError::InvalidParameter { name, expected, .. } => {
            invalid(name, format!("must be {expected}"))
        }
        other => invalid("principled", other.to_string()),
    })
}

fn unit_interval(param: &'static str, v: f32) -> Result<(), Invalid> {
    if (0.0..=1.0).contains(&v) {
        Ok(())
    } else {
        Err(invalid(param, "must lie in [0, 1]"))
    }
}

/// A coated material. Its diffuse albedo after internal scattering, `ρ / (1 − F_dr)` (or
/// `ρ / (1 − ρ F_dr)` when `nonlinear`), must stay finite: `F_dr` < 1 for every index
/// the fits cover, and an albedo above 1 with `nonlinear` could reach the pole, so it is
/// refused (Mitsuba would render infinities).
fn plastic(int_ior: Ior, ext_ior: Ior, diffuse: Colour, nonlinear: bool) -> Result<(), Invalid> {
    if nonlinear && diffuse.max_element() > 1.0 {
        return Err(invalid(
            "diffuse_reflectance",
            "must not exceed 1 with nonlinear (the internal scattering would diverge)",
        ));
    }
    let fdr = crate::bsdf::fresnel_diffuse_reflectance(ext_ior.get() / int_ior.get());
    if !(fdr < 1.0 && fdr.is_finite()) {
        return Err(invalid(
            "int_ior",
            "over ext_ior is outside the range where the coating's internal reflectance \
             is below 1",
        ));
    }
    Ok(())
}

/// An emitter that is not attached to a shape.
fn emitter(e: &EmitterDesc) -> Result<(), Invalid> {
    tally();
    match e {
        EmitterDesc::Point {
            position,
            intensity,
        } => {
            if !position.is_finite() {
                return Err(invalid("position", "must be finite"));
            }
            emission_power("intensity", intensity.get(), 4.0 * PI64)
        }
        EmitterDesc::Constant { radiance } => {
            emission_power("radiance", radiance.get(), 4.0 * PI64 * PI64)
        }
        EmitterDesc::EnvMap {
            scale, to_world, ..
        } => {
            if !(scale.is_finite() && *scale >= 0.0) {
                return Err(invalid("scale", "must be finite and non-negative"));
            }
            emission_power("scale", Vec3::splat(*scale), 4.0 * PI64 * PI64)?;
            transform("to_world", to_world)?;
            if !is_rotation(to_world) {
                return Err(invalid(
                    "to_world",
                    "must be a rotation (with any translation): Mitsuba 3 looks an environment \
                     map up along a scaled or sheared direction without normalising it",
                ));
            }
            Ok(())
        }
        EmitterDesc::Spot {
            intensity,
            cutoff_angle,
            beam_width,
            to_world,
        } => {
            if !(cutoff_angle.is_finite() && *cutoff_angle > 0.0 && *cutoff_angle <= 180.0) {
                return Err(invalid("cutoff_angle", "must lie in (0, 180] degrees"));
            }
            if !(beam_width.is_finite() && *beam_width >= 0.0) {
                return Err(invalid("beam_width", "must be finite and non-negative"));
            }
            transform("to_world", to_world)?;
            if !is_similarity(to_world) {
                return Err(invalid(
                    "to_world",
                    "must be a rotation, uniform scale and translation for a spot light",
                ));
            }
            emission_power("intensity", intensity.get(), 4.0 * PI64)
        }
        EmitterDesc::Directional {
            irradiance,
            direction,
        } => {
            if !(direction.is_finite() && (direction.length() - 1.0).abs() < 1e-3) {
                return Err(invalid("direction", "must be a finite unit vector"));
            }
            emission_power("irradiance", irradiance.get(), PI64)
        }
        EmitterDesc::Textured { inner, .. } => {
            if !matches!(**inner, EmitterDesc::Spot { .. }) {
                return Err(invalid("texture", "is a parameter of spot lights only"));
            }
            emitter(inner)
        }
        EmitterDesc::Projector {
            scale,
            x_fov,
            to_world,
            ..
        } => {
            if !(x_fov.is_finite() && *x_fov > 0.0 && *x_fov < 180.0) {
                return Err(invalid("fov", "must lie in (0, 180) degrees"));
            }
            if !(scale.is_finite() && *scale >= 0.0) {
                return Err(invalid("scale", "must be finite and non-negative"));
            }
            transform("to_world", to_world)?;
            if !is_similarity(to_world) {
                return Err(invalid(
                    "to_world",
                    "must be a rotation, uniform scale and translation for a projector",
                ));
            }
            Ok(())
        }
    }
}

/// Whether the linear part of `m` is a rotation or reflection (orthonormal columns), to
/// a relative tolerance of 10⁻⁴.
fn is_rotation(m: &Mat4) -> bool {
    let s = glam::Mat3::from_mat4(*m).x_axis.length_squared();
    is_similarity(m) && (s - 1.0).abs() < 1e-4
}

/// Whether the linear part of `m` has orthogonal columns of one length (a rotation or
/// reflection times a uniform scale), to a relative tolerance of 10⁻⁴.
pub(crate) fn is_similarity(m: &Mat4) -> bool {
    let r = glam::Mat3::from_mat4(*m);
    let g = r.transpose() * r;
    let s = g.x_axis.x;
    s > 0.0
        && s.is_finite()
        && (g - glam::Mat3::from_diagonal(Vec3::splat(s)))
            .to_cols_array()
            .iter()
            .all(|v| v.abs() < 1e-4 * s)
}

/// A shape: its own rules ([`shape_own`]) and its material.
fn shape(s: &ShapeDesc) -> Result<(), Invalid> {
    shape_own(s)?;
    bsdf(&s.bsdf)
}

/// The shape `s` with the material `bsdf`, checked already (the loader's, at its element):
/// the shape's own rules only, so the material is not checked twice.
pub(crate) fn shape_with(
    mut s: ShapeDesc,
    bsdf: CheckedBsdf,
) -> Result<crate::description::Checked<ShapeDesc>, Invalid> {
    s.bsdf = bsdf.into_inner();
    crate::description::Checked::assembled(s, shape_own)
}

/// A shape's geometry, transform and area emitter, not its material.
fn shape_own(s: &ShapeDesc) -> Result<(), Invalid> {
    tally();
    if let ShapeKind::Sphere { center, radius } = s.kind {
        if !center.is_finite() {
            return Err(invalid("center", "must be finite"));
        }
        if !(radius.is_finite() && radius > 0.0) {
            return Err(invalid("radius", "must be finite and positive"));
        }
    }
    if let ShapeKind::Cylinder { p0, p1, radius } = s.kind {
        if !(p0.is_finite() && p1.is_finite()) {
            return Err(invalid("p0", "and p1 must be finite"));
        }
        if p0 == p1 {
            return Err(invalid("p1", "must differ from p0"));
        }
        if !(radius.is_finite() && radius > 0.0) {
            return Err(invalid("radius", "must be finite and positive"));
        }
    }
    transform("to_world", &s.to_world)?;
    if let ShapeKind::Instance(_) = s.kind {
        if s.flip_normals {
            return Err(invalid(
                "flip_normals",
                "is not supported on an instance (as in Mitsuba 3)",
            ));
        }
        if s.emitter.is_some() {
            return Err(invalid(
                "emitter",
                "an instance cannot carry an emitter (as in Mitsuba 3)",
            ));
        }
    }
    // The area emitter's radiance is a [`Colour`]; its power was checked by the loader (a
    // description built in code meets `Lights::new`'s check).
    Ok(())
}

/// The rules of a shape group for a shape in it (a checked shape, so its own checks have
/// passed): neither an instance nor an emitter (Mitsuba 3's `shapegroup.cpp` refuses both).
fn grouped_shape(s: &ShapeDesc) -> Result<(), Invalid> {
    tally();
    if let ShapeKind::Instance(_) = s.kind {
        return Err(invalid(
            "type",
            "an instance inside a shape group: nested instancing is not supported (as in \
             Mitsuba 3)",
        ));
    }
    if s.emitter.is_some() {
        return Err(invalid(
            "emitter",
            "shapes in a shape group cannot emit: instancing of emitters is not supported (as \
             in Mitsuba 3)",
        ));
    }
    Ok(())
}

// The checks above are the checked constructors of the description's parts
// (`Checked::new`): each part is checked once, when it is made, and trusted after.

impl Check for FilmDesc {
    fn check(&self) -> Result<(), Invalid> {
        film(self)
    }
}

/// The sensor's transform (its film is a checked one already); an orthographic sensor has
/// no lens.
impl Check for SensorDesc {
    fn check(&self) -> Result<(), Invalid> {
        transform("to_world", &self.to_world)?;
        if self.projection == Projection::Orthographic && self.lens.is_some() {
            return Err(invalid(
                "aperture_radius",
                "an orthographic sensor has no lens (Mitsuba 3's orthographic reads none)",
            ));
        }
        Ok(())
    }
}

impl Check for IntegratorDesc {
    fn check(&self) -> Result<(), Invalid> {
        integrator(self)
    }
}

impl Check for ShapeDesc {
    fn check(&self) -> Result<(), Invalid> {
        shape(self)
    }
}

/// The group's rules for each of its shapes (each a checked one already).
impl Check for ShapeGroupDesc {
    fn check(&self) -> Result<(), Invalid> {
        self.shapes.iter().try_for_each(|s| grouped_shape(s))
    }
}

impl Check for EmitterDesc {
    fn check(&self) -> Result<(), Invalid> {
        emitter(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::description::Checked;

    #[test]
    fn the_shipped_defaults_pass_and_hostile_values_fail() {
        let d = crate::cornell_box::cornell_box();
        assert_eq!(d.integrator.check(), Ok(()));
        assert!(d.shapes.iter().all(|s| s.check().is_ok()));
        // Colours and indices cannot even be made invalid.
        for bad in [f32::NAN, f32::INFINITY, -1.0] {
            let e = Colour::named("reflectance", Vec3::new(0.5, bad, 0.5)).unwrap_err();
            assert_eq!(
                e.to_string(),
                "\"reflectance\" must be finite and non-negative"
            );
        }
        for bad in [0.0, f32::NAN, -1.5, f32::INFINITY] {
            assert!(Ior::new(bad).is_err(), "{bad}");
        }
        let bad = IntegratorDesc::Path(crate::description::PathParams {
            rr_depth: 0,
            ..Default::default()
        });
        assert_eq!(Checked::new(bad).unwrap_err().param, "rr_depth");
        let mut f = *d.sensor.film;
        f.filter = FilterDesc::Gaussian { stddev: f32::NAN };
        assert_eq!(Checked::new(f).unwrap_err().param, "stddev");
        let mut f = *d.sensor.film;
        f.width = 32768;
        f.height = 32768;
        assert!(Checked::new(f).unwrap_err().message.contains("pixels"));
        let spp = SampleCount::new(SampleCount::MAX).unwrap();
        assert!(work(768 * 576, spp.get(), &d.integrator).is_err());
        let mut p = Mat4::IDENTITY;
        p.w_axis.w = 2.0;
        p.x_axis.w = 0.5;
        assert!(transform("to_world", &p)
            .unwrap_err()
            .message
            .contains("projective"));
    }

    /// The materials in `b`: it and every one nested in it.
    fn materials(b: &BsdfDesc) -> usize {
        1 + nested(b)
            .into_iter()
            .flatten()
            .map(materials)
            .sum::<usize>()
    }

    #[test]
    fn loading_a_scene_checks_each_material_once() {
        let xml = r#"<scene version="3.0.0">
            <shape type="cube"><bsdf type="diffuse"/></shape>
            <shape type="sphere"><bsdf type="blendbsdf"><float name="weight" value="0.3"/>
                <bsdf type="roughplastic"/>
                <bsdf type="twosided"><bsdf type="conductor"/></bsdf>
            </bsdf></shape>
            <shape type="rectangle"><bsdf type="mask"><bsdf type="dielectric"/></bsdf></shape>
            <shape type="disk"><bsdf type="diffuse">
                <texture type="checkerboard" name="reflectance"/>
            </bsdf></shape>
            <shape type="cube"/>
        </scene>"#;
        let count = || BSDF_CHECKS_RUN.with(|c| c.get());
        let before = count();
        let d = crate::loader::parse_scene(xml, None, &[]).unwrap();
        let checks = count() - before;
        let made: usize = d.shapes.iter().map(|s| materials(&s.bsdf)).sum();
        // diffuse 1, blend of roughplastic and twosided conductor 4, mask of dielectric 2,
        // textured diffuse 2, the default diffuse 1.
        assert_eq!(made, 10);
        assert_eq!(checks, made);
    }

    #[test]
    fn a_shape_made_in_code_has_its_nested_materials_checked() {
        let mut s = ShapeDesc::new(ShapeKind::Cube);
        s.bsdf = BsdfDesc::Blend {
            weight: 0.5,
            first: Box::default(),
            second: Box::new(BsdfDesc::Mask {
                opacity: 2.0,
                inner: Box::default(),
            }),
        };
        assert_eq!(Checked::new(s).unwrap_err().param, "opacity");
    }
}
