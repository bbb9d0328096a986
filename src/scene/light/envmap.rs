//! An environment map: radiance from a latitude–longitude EXR image at infinity (Mitsuba's
//! `envmap`), sampled in proportion to its luminance with a [`PiecewiseConstant2D`].

use crate::integrator::is_positive;
use crate::sampling::distribution::PiecewiseConstant2D;
use crate::scene::film::read_exr;
use glam::{Mat3, Mat4, Vec2, Vec3};
use std::f32::consts::PI;
use std::path::Path;

/// A latitude–longitude environment map. In its own frame, texel `(u, v)` holds the radiance
/// arriving from the direction `(sin θ sin φ, cos θ, −sin θ cos φ)` with `φ = 2πu`,
/// `θ = πv` (Mitsuba 3's convention: `+y` up, `u = 0` toward `−z`). Texels are piecewise
/// constant (Mitsuba interpolates bilinearly; the difference is below a texel).
///
/// Sampling draws `(u, v)` from a table of luminance × `sin θ` of the row centre, so the
/// density per steradian is `p(ω) = p(u, v) / (2π² sin θ)`.
#[derive(Debug, Clone, PartialEq)]
pub struct EnvMap {
    width: usize,
    height: usize,
    texels: Vec<Vec3>,
    dist: PiecewiseConstant2D,
    to_world: Mat3,
    to_local: Mat3,
}

fn luminance(c: Vec3) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

impl EnvMap {
    /// Reads the map from an EXR file, with a scale on its radiance and a map-to-world
    /// rotation.
    pub fn load(path: &Path, scale: f32, to_world: Mat4) -> Result<Self, String> {
        let (w, h, px) = read_exr(path).map_err(|e| e.to_string())?;
        let texels: Vec<Vec3> = px
            .iter()
            .map(|p| (*p * scale).max(Vec3::ZERO))
            .map(|p| if p.is_finite() { p } else { Vec3::ZERO })
            .collect();
        Self::from_texels(w as usize, h as usize, texels, to_world)
    }

    /// A map from texels (row-major, row 0 at the top, θ = 0).
    pub fn from_texels(
        width: usize,
        height: usize,
        texels: Vec<Vec3>,
        to_world: Mat4,
    ) -> Result<Self, String> {
        let weights: Vec<f32> = texels
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let theta = PI * ((i / width.max(1)) as f32 + 0.5) / height as f32;
                luminance(*t).max(0.0) * theta.sin()
            })
            .collect();
        let dist = PiecewiseConstant2D::new(&weights, width, height)
            .map_err(|e| format!("environment map: {e}"))?;
        let m = Mat3::from_mat4(to_world);
        let to_local = m.inverse();
        if !to_local.is_finite() {
            return Err("environment map: to_world is not invertible".into());
        }
        Ok(Self {
            width,
            height,
            texels,
            dist,
            to_world: m,
            to_local,
        })
    }

    fn uv(&self, dir_world: Vec3) -> Vec2 {
        let d = (self.to_local * dir_world).normalize_or_zero();
        let u = d.x.atan2(-d.z) / (2.0 * PI);
        let u = u - u.floor();
        let v = d.y.clamp(-1.0, 1.0).acos() / PI;
        Vec2::new(u, v)
    }

    fn texel(&self, uv: Vec2) -> Vec3 {
        let x = ((uv.x * self.width as f32) as usize).min(self.width - 1);
        let y = ((uv.y * self.height as f32) as usize).min(self.height - 1);
        self.texels[y * self.width + x]
    }

    /// Radiance arriving from the world direction `-ray_dir`'s source, i.e. seen looking
    /// along `ray_dir`.
    pub fn eval(&self, ray_dir: Vec3) -> Vec3 {
        self.texel(self.uv(ray_dir))
    }

    /// Samples a world direction: `(direction, radiance, pdf per steradian)`.
    pub fn sample(&self, u: Vec2) -> Option<(Vec3, Vec3, f32)> {
        let (uv, pdf_uv, _) = self.dist.sample(u);
        let (st, ct) = (PI * uv.y).sin_cos();
        if !is_positive(st) {
            return None;
        }
        let (sp, cp) = (2.0 * PI * uv.x).sin_cos();
        let local = Vec3::new(st * sp, ct, -st * cp);
        let dir = (self.to_world * local).normalize();
        Some((dir, self.texel(uv), pdf_uv / (2.0 * PI * PI * st)))
    }

    /// Density per steradian with which [`EnvMap::sample`] returns `dir`.
    pub fn pdf(&self, dir: Vec3) -> f32 {
        let uv = self.uv(dir);
        let st = (PI * uv.y).sin();
        if !is_positive(st) {
            return 0.0;
        }
        self.dist.pdf(uv) / (2.0 * PI * PI * st)
    }

    /// Total luminance-weighted radiance integrated over the sphere, ∫ L dω (for the light's
    /// power).
    pub fn integral(&self) -> f32 {
        let mut s = 0.0f64;
        for (i, t) in self.texels.iter().enumerate() {
            let theta = PI * ((i / self.width) as f32 + 0.5) / self.height as f32;
            s += ((t.x + t.y + t.z) / 3.0 * theta.sin()) as f64;
        }
        (s * (2.0 * std::f64::consts::PI / self.width as f64)
            * (std::f64::consts::PI / self.height as f64)) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sun_map() -> EnvMap {
        let (w, h) = (32, 16);
        let mut t = vec![Vec3::splat(0.1); w * h];
        t[5 * w + 20] = Vec3::splat(500.0);
        EnvMap::from_texels(w, h, t, Mat4::from_rotation_y(0.3)).expect("valid map")
    }

    #[test]
    fn sample_pdf_and_eval_agree() {
        let m = sun_map();
        let mut s = 1u32;
        for _ in 0..2000 {
            s = s.wrapping_mul(747796405).wrapping_add(2891336453);
            let a = (s >> 8) as f32 / 16_777_216.0;
            s = s.wrapping_mul(747796405).wrapping_add(2891336453);
            let b = (s >> 8) as f32 / 16_777_216.0;
            let Some((d, l, pdf)) = m.sample(Vec2::new(a, b)) else {
                continue;
            };
            let p2 = m.pdf(d);
            assert!(pdf.is_finite() && p2.is_finite() && pdf > 0.0);
            assert!((pdf - p2).abs() <= 1e-3 * pdf, "{pdf} vs {p2}");
            assert_eq!(l, m.eval(d));
        }
    }

    #[test]
    fn pdf_integrates_to_one() {
        let m = sun_map();
        let (nt, np) = (400, 800);
        let mut sum = 0.0f64;
        for i in 0..nt {
            let th = (i as f32 + 0.5) * PI / nt as f32;
            for j in 0..np {
                let ph = (j as f32 + 0.5) * 2.0 * PI / np as f32;
                let d = Vec3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos());
                sum += (m.pdf(d) * th.sin()) as f64;
            }
        }
        let integral = sum * (PI as f64 / nt as f64) * (2.0 * PI as f64 / np as f64);
        assert!(
            integral.is_finite() && (integral - 1.0).abs() < 0.01,
            "{integral}"
        );
    }
}
