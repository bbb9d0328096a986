//! A spot light (Mitsuba 3's `spot`): a point light whose intensity falls off with the
//! angle `θ` to its axis (local +z):
//!
//! ```text
//! I(θ) = I₀                              θ ≤ β  (beam_width)
//!        I₀ (γ − θ)/(γ − β)              β < θ < γ
//!        0                               θ ≥ γ  (cutoff_angle)
//! ```
//!
//! linear in the angle, as Mitsuba 3's `spotlight.cpp` evaluates it (checked against its
//! `sample_direction` at 5°–25°, `scripts/mitsuba_emitter_facts.py`). A beam wider than the
//! cutoff is the cutoff (Mitsuba's formula then never reaches the linear part). The
//! emitted power is `Φ = I₀ ∫ f dω = 2π I₀ (1 − (sin γ − sin β)/(γ − β))` (derived in
//! `docs/scene-format.md`, "Spot light"), `2π I₀ (1 − cos γ)` when `β = γ`. Light subpaths
//! leave it uniformly in the cone `θ ≤ γ`, as Mitsuba's `sample_ray` does.

use super::LightError;
use crate::texture::Texture;
use crate::validate::is_similarity;
use glam::{Mat3, Mat4, Vec2, Vec3};
use mcrt::sampling::warp::{UniformCone, Warp};
use mcrt::sampling::Frame;
use std::f32::consts::PI;

/// A spot light: position, axis, peak intensity and its angular falloff.
#[derive(Debug, Clone, PartialEq)]
pub struct Spot {
    position: Vec3,
    /// The frame whose `n` is the axis the light shines along.
    frame: Frame,
    intensity: Vec3,
    /// Cutoff and beam half-angles in radians (`beam ≤ cutoff`).
    cutoff: f32,
    beam: f32,
    cos_cutoff: f32,
    cos_beam: f32,
    /// Directions of light subpaths: uniform in the cutoff cone.
    cone: UniformCone,
    /// The `texture` multiplying the intensity, if any, and world-to-light directions
    /// (its image coordinates are in the frame of `to_world`, not of `frame`).
    texture: Option<(Texture, Mat3)>,
}

impl Spot {
    /// The spot light of Mitsuba's parameters: peak `intensity` (W/sr), `cutoff_angle` and
    /// `beam_width` in degrees, and `to_world`, whose origin is the light's position and
    /// whose +z its axis.
    ///
    /// # Errors
    /// [`LightError::Spot`] when the cutoff is not in (0°, 180°], the beam width is
    /// negative, or `to_world` is not a rotation with a uniform scale and translation.
    pub fn new(
        intensity: Vec3,
        cutoff_angle: f32,
        beam_width: f32,
        to_world: Mat4,
    ) -> Result<Self, LightError> {
        let bad = |what: &str| Err(LightError::Spot(what.to_string()));
        if !(cutoff_angle > 0.0 && cutoff_angle <= 180.0) {
            return bad("cutoff_angle must lie in (0, 180] degrees");
        }
        if !(beam_width.is_finite() && beam_width >= 0.0) {
            return bad("beam_width must be finite and non-negative");
        }
        if !(to_world.is_finite() && is_similarity(&to_world)) {
            return bad("to_world must be a rotation, uniform scale and translation");
        }
        let cutoff = cutoff_angle.to_radians();
        let beam = beam_width.to_radians().min(cutoff);
        let axis = to_world.transform_vector3(Vec3::Z).normalize();
        let cone = UniformCone::from_angle(cutoff).map_err(|e| LightError::Spot(e.to_string()))?;
        Ok(Self {
            position: to_world.transform_point3(Vec3::ZERO),
            frame: Frame::from_normal(axis),
            intensity,
            cutoff,
            beam,
            cos_cutoff: cutoff.cos(),
            cos_beam: beam.cos(),
            cone,
            texture: None,
        })
    }

    /// This spot with Mitsuba 3's `texture`: an image spread over the cutoff cone,
    /// multiplying the intensity. A direction `d` of the light's frame (`to_world`'s axes)
    /// looks it up at `u = ½ + ½ d_x/(d_z tan γ)`, `v = ½ + ½ d_y/(d_z tan γ)` (γ the cutoff),
    /// as Mitsuba's `spot` does.
    #[must_use]
    pub fn with_texture(mut self, texture: Texture, to_world: Mat4) -> Self {
        let to_local = Mat3::from_mat4(to_world).inverse();
        self.texture = Some((texture, to_local));
        self
    }

    /// The light's position.
    pub fn position(&self) -> Vec3 {
        self.position
    }

    /// Its bounds for the light BVH, of power `power`: full intensity within the beam
    /// width, falling off to 0 at the cutoff angle.
    pub(crate) fn light_bounds(&self, power: f32) -> mcrt::sampling::light_bvh::LightBounds {
        mcrt::sampling::light_bvh::LightBounds::spot(
            self.position,
            self.frame.n,
            self.cos_beam,
            self.cos_cutoff,
            power,
        )
    }

    /// The share of the peak intensity sent at angle `θ` to the axis, from `cos θ`: 1
    /// inside the beam, falling linearly in `θ` to 0 at the cutoff, 0 beyond.
    pub fn falloff(&self, cos_theta: f32) -> f32 {
        // NaN falls through to 0.
        if cos_theta >= self.cos_beam && cos_theta > self.cos_cutoff {
            1.0
        } else if cos_theta > self.cos_cutoff {
            let theta = cos_theta.clamp(-1.0, 1.0).acos();
            ((self.cutoff - theta) / (self.cutoff - self.beam)).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }

    /// Intensity (W/sr) along the unit world direction `dir` leaving the light.
    pub fn intensity_toward(&self, dir: Vec3) -> Vec3 {
        let f = self.falloff(self.frame.n.dot(dir));
        match &self.texture {
            Some((t, to_local)) if f > 0.0 => {
                let d = *to_local * dir;
                let k = 0.5 / (d.z * self.cutoff.tan());
                let uv = Vec2::new(0.5 + d.x * k, 0.5 + d.y * k);
                let i = self.intensity * t.eval(uv) * f;
                if i.is_finite() {
                    i
                } else {
                    Vec3::ZERO
                }
            }
            _ => self.intensity * f,
        }
    }

    /// Emitted power's channel mean, `mean(I₀) ∫ f dω`.
    pub fn power(&self) -> f32 {
        let (c, b) = (self.cutoff, self.beam);
        let solid = if c - b > 1e-4 {
            2.0 * PI * (1.0 - (c.sin() - b.sin()) / (c - b))
        } else {
            self.cone.solid_angle()
        };
        let texture = self
            .texture
            .as_ref()
            .map_or(1.0, |(t, _)| t.mean().max(0.0));
        super::mean(self.intensity).max(0.0) * solid * texture
    }

    /// A direction of a light subpath, uniform in the cutoff cone: the unit world
    /// direction, the intensity along it and its density per steradian.
    pub fn sample_direction(&self, u: Vec2) -> (Vec3, Vec3, f32) {
        let (local, pdf) = self.cone.sample_with_pdf(u);
        let dir = self.frame.to_world(local);
        (dir, self.intensity_toward(dir), pdf)
    }

    /// Density per steradian with which [`Spot::sample_direction`] returns the unit world
    /// direction `dir`.
    pub fn pdf_direction(&self, dir: Vec3) -> f32 {
        self.cone.pdf(self.frame.to_local(dir))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spot(cutoff: f32, beam: f32) -> Spot {
        Spot::new(Vec3::new(1.0, 2.0, 4.0), cutoff, beam, Mat4::IDENTITY).unwrap()
    }

    /// Mitsuba 3.9.1's `spot` (cutoff 20°, its default beam 15°) at angles 0°–25°: the
    /// share of the peak its `sample_direction` returned (`scripts/mitsuba_emitter_facts.py`).
    #[test]
    fn falloff_matches_mitsuba_at_hand_computed_angles() {
        let s = spot(20.0, 15.0);
        for (deg, want) in [
            (0.0, 1.0),
            (10.0, 1.0),
            (14.9, 1.0),
            (15.1, 0.98),
            (16.0, 0.8),
            (17.5, 0.5),
            (19.0, 0.2),
            (19.9, 0.02),
            (20.1, 0.0),
            (25.0, 0.0),
        ] {
            let got = s.falloff(f32::to_radians(deg).cos());
            assert!(
                got.is_finite() && (got - want).abs() < 2e-4,
                "{deg}°: {got}"
            );
        }
        // A beam wider than the cutoff is the cutoff: full intensity up to it.
        let wide = spot(20.0, 30.0);
        assert_eq!(wide.falloff(f32::to_radians(19.5).cos()), 1.0);
        assert_eq!(wide.falloff(f32::to_radians(20.5).cos()), 0.0);
    }

    /// The power's closed form against a midpoint rule over θ.
    #[test]
    fn power_is_the_integral_of_the_intensity() {
        for (c, b) in [
            (20.0, 15.0),
            (30.0, 10.0),
            (120.0, 90.0),
            (45.0, 45.0),
            (180.0, 0.0),
        ] {
            let s = spot(c, b);
            let n = 200_000;
            let mut sum = 0.0f64;
            for i in 0..n {
                let theta = (i as f64 + 0.5) / n as f64 * std::f64::consts::PI;
                sum += f64::from(s.falloff(theta.cos() as f32)) * theta.sin();
            }
            let want = sum * std::f64::consts::PI / n as f64 * 2.0 * std::f64::consts::PI;
            let got = f64::from(s.power()) / (7.0 / 3.0);
            assert!(
                got.is_finite() && (got / want - 1.0).abs() < 1e-3,
                "{c} {b}: {got} {want}"
            );
        }
    }

    #[test]
    fn samples_stay_in_the_cone_with_their_density() {
        let m = Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0)) * Mat4::from_rotation_x(1.0);
        let s = Spot::new(Vec3::ONE, 30.0, 10.0, m).unwrap();
        let axis = m.transform_vector3(Vec3::Z);
        for u in [Vec2::new(0.1, 0.2), Vec2::new(0.99, 0.7), Vec2::ZERO] {
            let (dir, i, pdf) = s.sample_direction(u);
            let cos = dir.dot(axis);
            assert!(cos.is_finite() && cos >= f32::to_radians(30.0).cos() - 1e-5);
            let p = s.pdf_direction(dir);
            assert!(pdf.is_finite() && pdf > 0.0 && (p - pdf).abs() < 1e-4 * pdf);
            let err = (i - Vec3::ONE * s.falloff(cos)).abs().max_element();
            assert!(err.is_finite() && err < 1e-4, "{err}");
        }
        assert_eq!(s.pdf_direction(-axis), 0.0);
        assert_eq!(s.position(), Vec3::new(1.0, 2.0, 3.0));
    }

    #[test]
    fn bad_parameters_are_refused() {
        let i = Vec3::ONE;
        assert!(Spot::new(i, 0.0, 0.0, Mat4::IDENTITY).is_err());
        assert!(Spot::new(i, 181.0, 0.0, Mat4::IDENTITY).is_err());
        assert!(Spot::new(i, f32::NAN, 0.0, Mat4::IDENTITY).is_err());
        assert!(Spot::new(i, 20.0, -1.0, Mat4::IDENTITY).is_err());
        let squash = Mat4::from_scale(Vec3::new(1.0, 2.0, 1.0));
        assert!(Spot::new(i, 20.0, 10.0, squash).is_err());
        assert!(Spot::new(i, 20.0, 10.0, Mat4::from_scale(Vec3::splat(3.0))).is_ok());
    }
}
