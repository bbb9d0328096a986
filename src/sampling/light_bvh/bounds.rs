//! What the BVH needs to know of one light ([`LightBounds`]), its validation, and the error
//! of [`super::LightBvh::new`].

use std::fmt;

use glam::Vec3;

/// The bounds of one light as the [`super::LightBvh`] sees it: where it is, which way its
/// surface normals point, how far beyond its normals it emits, and how much it emits.
///
/// Fill the fields or use a constructor ([`LightBounds::point`], [`LightBounds::spot`],
/// [`LightBounds::planar`]). A light emits from points of the box `[min, max]` whose
/// normals `m` lie within `θ_o` of `axis` (and of `−axis` too when `two_sided`), and only in
/// directions within `θ_e` of its normal `m`: the emission cone of pbrt-v4's `LightBounds`.
/// [`super::LightBvh::new`] checks every field.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightBounds {
    /// The corner of the bounding box with the smallest coordinates (finite).
    pub min: Vec3,
    /// The corner of the bounding box with the largest coordinates (finite, `≥ min`).
    pub max: Vec3,
    /// The axis of the cone of normals (finite; any length but zero, normalised by the
    /// BVH; may be zero when `cos_theta_o == -1`).
    pub axis: Vec3,
    /// `cos θ_o`, in `[−1, 1]`: every normal lies within `θ_o` of `axis`. `1` for a
    /// planar light, `−1` (every direction) for a point light.
    pub cos_theta_o: f32,
    /// `cos θ_e`, in `[−1, 1]`: light leaves a point with normal `m` only in directions
    /// within `θ_e` of `m` (strictly: `cos(angle) > cos θ_e`). `0` (`θ_e = π/2`) for a
    /// diffuse emitter.
    pub cos_theta_e: f32,
    /// Whether the light emits on both sides (normals `±m`).
    pub two_sided: bool,
    /// Its power (any scalar measure consistent over the lights, e.g. the luminance of its
    /// flux): finite and `≥ 0`. Lights of power 0 are never chosen.
    pub power: f32,
}

impl LightBounds {
    /// An isotropic point light at `position`: a box of size 0 emitting in every direction.
    pub fn point(position: Vec3, power: f32) -> Self {
        Self {
            min: position,
            max: position,
            axis: Vec3::Z,
            cos_theta_o: -1.0,
            cos_theta_e: 0.0,
            two_sided: false,
            power,
        }
    }

    /// A spot light at `position` shining along `axis`, its intensity falling off between
    /// the cosines `cos_falloff_start ≥ cos_falloff_end` (pbrt-v4's bounds: `θ_o` is the
    /// start of the falloff and `θ_e` the rest, so that `θ_o + θ_e` is its end).
    pub fn spot(
        position: Vec3,
        axis: Vec3,
        cos_falloff_start: f32,
        cos_falloff_end: f32,
        power: f32,
    ) -> Self {
        let start = cos_falloff_start.clamp(-1.0, 1.0).acos();
        let end = cos_falloff_end.clamp(-1.0, 1.0).acos();
        Self {
            min: position,
            max: position,
            axis,
            cos_theta_o: cos_falloff_start,
            cos_theta_e: (end - start).max(0.0).cos(),
            two_sided: false,
            power,
        }
    }

    /// A diffuse planar emitter (a triangle, a quad) inside the box `[min, max]` with the
    /// normal `normal`: `θ_o = 0`, `θ_e = π/2`.
    pub fn planar(min: Vec3, max: Vec3, normal: Vec3, two_sided: bool, power: f32) -> Self {
        Self {
            min,
            max,
            axis: normal,
            cos_theta_o: 1.0,
            cos_theta_e: 0.0,
            two_sided,
            power,
        }
    }

    /// The first field of light `index` that is not usable, as an error.
    pub(super) fn validate(&self, index: usize) -> Result<(), LightBvhError> {
        let bad = |field, expected| {
            Err(LightBvhError::InvalidLight {
                index,
                field,
                expected,
            })
        };
        if !self.min.is_finite() {
            return bad("min", "finite coordinates");
        }
        if !self.max.is_finite() || !self.max.cmpge(self.min).all() {
            return bad("max", "finite coordinates, each >= min");
        }
        if !(self.cos_theta_o.is_finite() && (-1.0..=1.0).contains(&self.cos_theta_o)) {
            return bad("cos_theta_o", "in [-1, 1]");
        }
        if !(self.cos_theta_e.is_finite() && (-1.0..=1.0).contains(&self.cos_theta_e)) {
            return bad("cos_theta_e", "in [-1, 1]");
        }
        let full_sphere = self.cos_theta_o == -1.0;
        let len2 = self.axis.as_dvec3().length_squared();
        if !(self.axis.is_finite() && (full_sphere || len2 > 0.0)) {
            return bad(
                "axis",
                "finite and nonzero (zero only when cos_theta_o = -1)",
            );
        }
        if !(self.power.is_finite() && self.power >= 0.0) {
            return bad("power", "finite and >= 0");
        }
        Ok(())
    }
}

/// Why [`super::LightBvh::new`] refused its lights.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum LightBvhError {
    /// A field of a light is NaN, infinite or out of its range.
    InvalidLight {
        /// The light's index in the slice given.
        index: usize,
        /// The field's name in [`LightBounds`].
        field: &'static str,
        /// What the field must be, in words.
        expected: &'static str,
    },
}

impl fmt::Display for LightBvhError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidLight {
                index,
                field,
                expected,
            } => write!(f, "light {index}: `{field}` must be {expected}"),
        }
    }
}

impl std::error::Error for LightBvhError {}
