//! An environment map: radiance from a latitude–longitude EXR image at infinity (Mitsuba 3's
//! `envmap`), interpolated bilinearly as Mitsuba 3 does, and sampled piecewise constantly
//! from a [`PiecewiseConstant2D`] over the interpolation cells, each weighted by the largest
//! luminance among the four texels it reads.

use crate::integrator::is_positive;
use crate::sampling::distribution::PiecewiseConstant2D;
use crate::scene::film::read_exr;
use glam::{Mat3, Mat4, Vec2, Vec3};
use std::f32::consts::PI;
use std::path::Path;

#[cfg(test)]
mod tests;

/// A latitude–longitude environment map. In its own frame, the map coordinates `(u, v)`
/// belong to the direction `(sin θ sin φ, cos θ, −sin θ cos φ)` with `φ = 2πu`, `θ = πv`
/// (Mitsuba 3's convention: `+y` up, `u = 0` toward `−z`).
///
/// **Lookup** (as Mitsuba 3's `envmap`): radiance is interpolated bilinearly. Column `x`
/// sits at `u = (x + ½)/width` (its centre), and interpolation wraps around in `u`; row `y`
/// sits at `v = y/(height − 1)`, so the first row is the north pole (`θ = 0`), the last the
/// south pole, and no clamping is needed in `v` (a one-row map is constant in `v`).
///
/// **Sampling** is piecewise constant over the interpolation cells (between neighbouring
/// columns and rows: `width × (height − 1)` cells, shifted by half a texel in `u`). A cell's
/// weight is the largest luminance among its four corner texels times the mean of `sin θ`
/// over the cell, so the density is positive wherever the interpolated radiance is. The
/// density per steradian is `p(ω) = p(u, v) / (2π² max(sin θ, ε))`, `ε = f32::EPSILON`
/// (it differs from `p(u, v) / (2π² sin θ)` only at the poles, which have no solid angle).
///
/// Reference: Pharr, Jakob & Humphreys, 2023, *Physically Based Rendering* (4th ed.),
/// section 12.5, "Infinite Area Lights" (importance-sampled image lights).
///
/// ```
/// use mcrt::glam::{Mat4, Vec2, Vec3};
/// use mcrt::scene::light::EnvMap;
///
/// // Two columns, black and white: halfway between their centres the radiance is ½.
/// let m = EnvMap::from_texels(2, 1, vec![Vec3::ZERO, Vec3::ONE], Mat4::IDENTITY).unwrap();
/// let (dir, radiance, pdf) = m.sample(Vec2::new(0.3, 0.6)).unwrap();
/// assert!(pdf > 0.0 && (m.pdf(dir) - pdf).abs() < 1e-3 * pdf);
/// assert!((m.eval(dir) - radiance).abs().max_element() < 1e-4);
/// ```
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

/// `x` modulo 1, in `[0, 1)` (a result that rounds up to 1 wraps to 0).
fn wrap_unit(x: f32) -> f32 {
    let y = x - x.floor();
    if y < 1.0 {
        y
    } else {
        0.0
    }
}

/// `p(ω) = p(u, v) / (2π² sin θ)`, with `sin θ` at least `f32::EPSILON` (as Mitsuba 3
/// does), so that a sample at a pole, where `v` is exactly 0 or 1, keeps a finite density
/// instead of being lost (the poles have no solid angle, so this changes no integral).
fn solid_angle_pdf(pdf_uv: f32, sin_theta: f32) -> f32 {
    pdf_uv / (2.0 * PI * PI * sin_theta.abs().max(f32::EPSILON))
}

/// Interpolation along one axis: `(lower index, upper index, weight of the upper)`.
type Lerp = (usize, usize, f32);

impl EnvMap {
    /// Reads the map from an EXR file, with a scale on its radiance and a map-to-world
    /// rotation.
    pub fn load(path: &Path, scale: f32, to_world: Mat4) -> Result<Self, String> {
        let (w, h, px) = read_exr(path).map_err(|e| e.to_string())?;
        let texels: Vec<Vec3> = px.iter().map(|p| *p * scale).collect();
        Self::from_texels(w as usize, h as usize, texels, to_world)
    }

    /// A map from texels (row-major, row 0 at the top, θ = 0). Negative channels and
    /// non-finite texels are replaced by 0.
    pub fn from_texels(
        width: usize,
        height: usize,
        texels: Vec<Vec3>,
        to_world: Mat4,
    ) -> Result<Self, String> {
        if width == 0 || height == 0 || texels.len() != width.saturating_mul(height) {
            return Err(format!(
                "environment map: {} texels for {width} × {height}",
                texels.len()
            ));
        }
        let texels: Vec<Vec3> = texels
            .into_iter()
            .map(|t| {
                if t.is_finite() {
                    t.max(Vec3::ZERO)
                } else {
                    Vec3::ZERO
                }
            })
            .collect();
        let mut weights = cell_weights(width, height, &texels);
        // A black map (or `scale` 0) is a black environment: sample it by solid angle;
        // every sample then carries zero radiance.
        if weights.iter().all(|&w| w <= 0.0) {
            weights.fill(1.0);
        }
        let dist = PiecewiseConstant2D::new(&weights, width, cell_rows(height))
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

    /// Map coordinates `(u, v)` of a world direction and its `sin θ`. `θ` comes from
    /// `atan2(sin θ, cos θ)`, which keeps its precision near the poles (unlike `acos`).
    fn uv(&self, dir_world: Vec3) -> (Vec2, f32) {
        let d = (self.to_local * dir_world).normalize_or_zero();
        let u = wrap_unit(d.x.atan2(-d.z) / (2.0 * PI));
        let sin_theta = (d.x * d.x + d.z * d.z).sqrt();
        let v = (sin_theta.atan2(d.y) / PI).clamp(0.0, 1.0);
        (Vec2::new(u, v), sin_theta)
    }

    /// Half a texel in `u`: the interpolation cells (and the sampling table) start at the
    /// centre of column 0.
    fn half_texel(&self) -> f32 {
        0.5 / self.width as f32
    }

    /// Bilinear interpolation at map coordinates `uv ∈ [0,1]²`.
    fn lookup(&self, uv: Vec2) -> Vec3 {
        let (x0, x1, tx) = columns(self.width, wrap_unit(uv.x - self.half_texel()));
        let (y0, y1, ty) = rows(self.height, uv.y);
        let at = |x: usize, y: usize| self.texels[y * self.width + x];
        let top = at(x0, y0).lerp(at(x1, y0), tx);
        let bottom = at(x0, y1).lerp(at(x1, y1), tx);
        top.lerp(bottom, ty)
    }

    /// Radiance arriving from the world direction `-ray_dir`'s source, i.e. seen looking
    /// along `ray_dir`, interpolated bilinearly.
    pub fn eval(&self, ray_dir: Vec3) -> Vec3 {
        self.lookup(self.uv(ray_dir).0)
    }

    /// Samples a world direction: `(direction, radiance, pdf per steradian)`.
    pub fn sample(&self, u: Vec2) -> Option<(Vec3, Vec3, f32)> {
        let (cell_uv, pdf_uv, _) = self.dist.sample(u);
        let uv = Vec2::new(wrap_unit(cell_uv.x + self.half_texel()), cell_uv.y);
        if !is_positive(pdf_uv) {
            return None;
        }
        let (st, ct) = (PI * uv.y).sin_cos();
        let (sp, cp) = (2.0 * PI * uv.x).sin_cos();
        let local = Vec3::new(st * sp, ct, -st * cp);
        let dir = (self.to_world * local).normalize();
        Some((dir, self.lookup(uv), solid_angle_pdf(pdf_uv, st)))
    }

    /// Density per steradian with which [`EnvMap::sample`] returns `dir`.
    pub fn pdf(&self, dir: Vec3) -> f32 {
        let (uv, st) = self.uv(dir);
        let cell_uv = Vec2::new(wrap_unit(uv.x - self.half_texel()), uv.y);
        solid_angle_pdf(self.dist.pdf(cell_uv), st)
    }

    /// The interpolated radiance's channel mean integrated over the sphere, `∫ L dω` (for
    /// the light's power). Exact for the bilinear lookup: along `u` it is the mean of the
    /// columns; along `v` each row weighs `∫ hat(θ) sin θ dθ` of its interpolation hat.
    pub fn integral(&self) -> f32 {
        let row_weights = row_weights(self.height);
        let mut s = 0.0f64;
        for (row, weight) in self.texels.chunks_exact(self.width).zip(row_weights) {
            let sum: f64 = row.iter().map(|t| f64::from(t.x + t.y + t.z) / 3.0).sum();
            s += sum / self.width as f64 * weight;
        }
        (s * 2.0 * std::f64::consts::PI) as f32
    }
}

/// The column interpolation at a `u` already shifted by half a texel: columns `x` and
/// `x + 1` (wrapping).
fn columns(width: usize, u_cell: f32) -> Lerp {
    let s = u_cell * width as f32;
    let x0 = (s as usize).min(width - 1);
    let t = (s - x0 as f32).clamp(0.0, 1.0);
    (x0, (x0 + 1) % width, t)
}

/// The row interpolation at `v`: rows sit at `v = y/(height − 1)`.
fn rows(height: usize, v: f32) -> Lerp {
    if height < 2 {
        return (0, 0, 0.0);
    }
    let s = v.clamp(0.0, 1.0) * (height - 1) as f32;
    let y0 = (s as usize).min(height - 2);
    let t = (s - y0 as f32).clamp(0.0, 1.0);
    (y0, y0 + 1, t)
}

/// Rows of interpolation cells (one for a one-row map).
fn cell_rows(height: usize) -> usize {
    (height - 1).max(1)
}

/// The sampling table: per interpolation cell, the largest luminance of its four corner
/// texels times the mean of `sin θ` over the cell's band of latitudes.
fn cell_weights(width: usize, height: usize, texels: &[Vec3]) -> Vec<f32> {
    let n_rows = cell_rows(height);
    let band = std::f64::consts::PI / n_rows as f64;
    let mut weights = Vec::with_capacity(width * n_rows);
    for y in 0..n_rows {
        let (a, b) = (y as f64 * band, (y + 1) as f64 * band);
        let mean_sin = ((a.cos() - b.cos()) / band) as f32;
        let (y0, y1) = (y, (y + 1).min(height - 1));
        for x in 0..width {
            let x1 = (x + 1) % width;
            let lum = [(x, y0), (x1, y0), (x, y1), (x1, y1)]
                .iter()
                .map(|&(i, j)| luminance(texels[j * width + i]))
                .fold(0.0f32, f32::max);
            weights.push(lum * mean_sin);
        }
    }
    weights
}

/// `∫ hat_y(θ) sin θ dθ` for each row `y`, where `hat_y` is row `y`'s weight in the
/// interpolation along `θ` (a tent of half-width `π/(height − 1)` around row `y`'s
/// latitude; the whole of `[0, π]` for a one-row map). They sum to 2.
fn row_weights(height: usize) -> Vec<f64> {
    use std::f64::consts::PI as PI64;
    if height < 2 {
        return vec![2.0];
    }
    let d = PI64 / (height - 1) as f64;
    // Over [a, a + d]: ∫ (θ − a)/d sin θ dθ (rising) and ∫ (a + d − θ)/d sin θ dθ (falling).
    let chord = |a: f64| ((a + d).sin() - a.sin()) / d;
    let rising = |a: f64| chord(a) - (a + d).cos();
    let falling = |a: f64| a.cos() - chord(a);
    (0..height)
        .map(|y| {
            let theta = y as f64 * d;
            let below = if y + 1 < height { falling(theta) } else { 0.0 };
            let above = if y > 0 { rising(theta - d) } else { 0.0 };
            below + above
        })
        .collect()
}
