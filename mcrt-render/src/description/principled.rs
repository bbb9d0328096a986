//! The parameters of Mitsuba 3's `principled` BSDF, with Mitsuba 3.9's defaults.

use glam::Vec3;
use mcrt::sampling::SamplingError;

/// The parameters of [`Principled`](crate::bsdf::Principled), named and defaulted as in
/// Mitsuba 3.9's `principled` plugin (the scalars are weights in \[0, 1\]).
///
/// Mitsuba takes either `eta` or `specular`; [`PrincipledParams::eta_from_specular`]
/// turns the second into the first, which is what is stored here.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrincipledParams {
    /// Colour of the diffuse, sheen tint and metallic lobes, linear RGB (default 0.5).
    pub base_color: Vec3,
    /// Roughness of the main specular lobe and of the retro-reflection (default 0.5).
    pub roughness: f32,
    /// Anisotropy of the main specular lobe, 0 isotropic (default 0).
    pub anisotropic: f32,
    /// Blend from dielectric to metal (default 0).
    pub metallic: f32,
    /// Specular transmission weight (default 0).
    pub spec_trans: f32,
    /// Relative index of refraction (default 1.5, from Mitsuba's default `specular` 0.5).
    pub eta: f32,
    /// Tint of the dielectric specular reflection toward the base colour (default 0).
    pub spec_tint: f32,
    /// Weight of the sheen lobe (default 0).
    pub sheen: f32,
    /// Tint of the sheen toward the base colour (default 0).
    pub sheen_tint: f32,
    /// Blend of the diffuse lobe toward the flat, subsurface-like lobe (default 0).
    pub flatness: f32,
    /// Weight of the clearcoat lobe (default 0).
    pub clearcoat: f32,
    /// Glossiness of the clearcoat, 0 rough, 1 sharp (default 0).
    pub clearcoat_gloss: f32,
    /// Relative probability of sampling the diffuse lobe (default 1).
    pub diffuse_reflectance_sampling_rate: f32,
    /// Relative probability of sampling the main specular lobe (default 1).
    pub main_specular_sampling_rate: f32,
    /// Relative probability of sampling the clearcoat lobe (default 1).
    pub clearcoat_sampling_rate: f32,
}

impl Default for PrincipledParams {
    fn default() -> Self {
        Self {
            base_color: Vec3::splat(0.5),
            roughness: 0.5,
            anisotropic: 0.0,
            metallic: 0.0,
            spec_trans: 0.0,
            eta: Self::eta_from_specular(0.5),
            spec_tint: 0.0,
            sheen: 0.0,
            sheen_tint: 0.0,
            flatness: 0.0,
            clearcoat: 0.0,
            clearcoat_gloss: 0.0,
            diffuse_reflectance_sampling_rate: 1.0,
            main_specular_sampling_rate: 1.0,
            clearcoat_sampling_rate: 1.0,
        }
    }
}

/// Largest `specular` with a finite index: the normal-incidence reflectance
/// `0.08 · specular` must stay below 1.
pub const MAX_SPECULAR: f32 = 12.5;

impl PrincipledParams {
    /// The index of refraction whose normal-incidence Fresnel reflectance is
    /// `0.08 · specular`: `η = 2 / (1 − √(0.08 s)) − 1` (Burley 2012, "Physically Based
    /// Shading at Disney", SIGGRAPH course notes, §5.5: `specular` maps \[0, 1\] to
    /// reflectances \[0, 0.08\]). Meaningful for `specular` in [0, [`MAX_SPECULAR`]).
    #[must_use]
    pub fn eta_from_specular(specular: f32) -> f32 {
        2.0 / (1.0 - (0.08 * specular).sqrt()) - 1.0
    }

    /// Checks every parameter: finite; the weights in \[0, 1\]; `eta` > 0; the sampling
    /// rates ≥ 0.
    ///
    /// # Errors
    /// The first parameter out of range, by its scene-file name.
    pub fn check(&self) -> Result<(), SamplingError> {
        let bad = |name, value: f32, expected| {
            Err(SamplingError::InvalidParameter {
                name,
                value: f64::from(value),
                expected,
            })
        };
        let c = self.base_color;
        if !(c.is_finite() && c.min_element() >= 0.0) {
            return bad("base_color", c.min_element(), "finite and non-negative");
        }
        for (name, v) in [
            ("roughness", self.roughness),
            ("anisotropic", self.anisotropic),
            ("metallic", self.metallic),
            ("spec_trans", self.spec_trans),
            ("spec_tint", self.spec_tint),
            ("sheen", self.sheen),
            ("sheen_tint", self.sheen_tint),
            ("flatness", self.flatness),
            ("clearcoat", self.clearcoat),
            ("clearcoat_gloss", self.clearcoat_gloss),
        ] {
            if !(0.0..=1.0).contains(&v) {
                return bad(name, v, "in [0, 1]");
            }
        }
        if !(self.eta.is_finite() && self.eta > 0.0) {
            return bad("eta", self.eta, "finite and > 0");
        }
        for (name, v) in [
            (
                "diffuse_reflectance_sampling_rate",
                self.diffuse_reflectance_sampling_rate,
            ),
            (
                "main_specular_sampling_rate",
                self.main_specular_sampling_rate,
            ),
            ("clearcoat_sampling_rate", self.clearcoat_sampling_rate),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return bad(name, v, "finite and >= 0");
            }
        }
        Ok(())
    }
}
