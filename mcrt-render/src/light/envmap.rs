//! An environment map: radiance from a latitude–longitude EXR image at infinity (Mitsuba 3's
//! `envmap`), interpolated bilinearly as Mitsuba 3 does, and sampled from a
//! [`PiecewiseLinear2D`] through the same interpolation vertices, so the density follows the
//! bilinear luminance (times a per-row `sin θ`) rather than a piecewise-constant bound on it.

use crate::io::read_exr_at_most;
use crate::texture::MAX_TEXTURE_PIXELS;
use glam::{Mat3, Mat4, Vec2, Vec3};
use mcrt::integrator::is_positive;
use mcrt::sampling::distribution::PiecewiseLinear2D;
use mcrt::sampling::warp::{LatLong, Warp};
use std::path::Path;

#[cfg(test)]
mod tests;

/// A latitude–longitude environment map. In its own frame, the map coordinates `(u, v)`
/// belong to the direction `(sin θ sin φ, cos θ, −sin θ cos φ)` with `φ = 2πu`, `θ = πv`
/// (Mitsuba 3's convention: `+y` up, `u = 0` toward `−z`; [`LatLong`]).
///
/// **Lookup** (as Mitsuba 3's `envmap`): radiance is interpolated bilinearly. Column `x`
/// sits at `u = (x + ½)/width` (its centre), and interpolation wraps around in `u`; row `y`
/// sits at `v = y/(height − 1)`, so the first row is the north pole (`θ = 0`), the last the
/// south pole, and no clamping is needed in `v` (a one-row map is constant in `v`).
///
/// **Sampling** uses a [`PiecewiseLinear2D`] on the interpolation vertices (`width + 1`
/// columns, shifted by half a texel in `u`, the last repeating the first; the rows, split
/// into sub-rows when there are fewer than 9, with the luminance interpolated between them as
/// the lookup does). A vertex's value is its luminance `L` times its row's `s̄`, the mean of
/// `sin θ` under the row's interpolation tent (half-width `δ`, the grid's row spacing in
/// `θ`). The density per steradian is `p(ω) = p(u, v) / (2π² max(sin θ, ε))`,
/// `ε = f32::EPSILON` (it differs from `p(u, v) / (2π² sin θ)` only at the poles, which have
/// no solid angle), with `p(u, v)` the bilinear interpolation of `L s̄`:
///
/// - away from the poles `s̄ = sin θ · 2(1 − cos δ)/δ²`, one constant for every row, so
///   `p(ω)` is proportional to the radiance's luminance at every vertex; inside a cell,
///   `L s̄` interpolates to `L(u, v) s̄(v) + t(1 − t)(L₀ − L₁)(s̄₀ − s̄₁)` (`t` the fraction
///   between rows, `s̄(v)` the linear interpolation of `s̄`, within `O(δ²)` of the constant
///   times `sin θ`), so the mismatch with the lookup is a product of two differences across
///   one cell;
/// - at a pole the vertex holds `s̄ · max(L − L', L/64)`, `L'` the luminance one grid row
///   away (`s̄ = (1 − sin δ/δ)·2/δ ≈ δ/3`). Where the map does not brighten toward the pole
///   that is `s̄ L/64`, and `p(ω)` follows `L` down to near the pole; where it does, the
///   excess keeps `L/p` in the pole cells within about 3 times its value elsewhere (a bright
///   pole row over a black next row included). Either way the density is positive wherever
///   the interpolated radiance is, the poles themselves included, at the price of a density
///   that grows as `1/sin θ` very near a pole (finite by the `ε` above).
///
/// Reference: Pharr, Jakob & Humphreys, 2023, *Physically Based Rendering* (4th ed.),
/// section 12.5, "Infinite Area Lights" (importance-sampled image lights); the bilinear
/// sampling as Mitsuba 3's `envmap` (W. Jakob et al., `src/emitters/envmap.cpp`).
///
/// ```
/// use mcrt::glam::{Mat4, Vec2, Vec3};
/// use mcrt_render::light::EnvMap;
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
    dist: PiecewiseLinear2D,
    to_world: Mat3,
    to_local: Mat3,
}

/// The pixels of a Radiance RGBE file, within the memory budget.
fn read_rgbe_file(path: &Path) -> Result<(u32, u32, Vec<Vec3>), String> {
    let cap = 1 << 30;
    let len = crate::io::open_regular(path)
        .and_then(|f| f.metadata())
        .map_err(|e| e.to_string())?
        .len();
    crate::memory::check("reading this image file", len.min(cap))?;
    let bytes = crate::io::read_capped(path, cap).map_err(|e| e.to_string())?;
    let file = bytes.len() as u64;
    crate::io::read_rgbe(&bytes, MAX_TEXTURE_PIXELS, |w, h, per| {
        // The pixels, the file, and the map's own copy and sampling table made from them.
        let need = crate::memory::bytes(u64::from(w) * u64::from(h), 3 * per).saturating_add(file);
        crate::memory::check(&format!("decoding this {w} × {h} environment map"), need)
    })
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

/// Interpolation along one axis: `(lower index, upper index, weight of the upper)`.
type Lerp = (usize, usize, f32);

impl EnvMap {
    /// Reads the map from an OpenEXR or a Radiance RGBE (`.hdr`) file, told apart by their
    /// first bytes, with a scale on its radiance and a map-to-world rotation. An RGBE
    /// file's size is checked against the memory budget ([`crate::memory`]) before its
    /// pixels are decoded.
    pub fn load(path: &Path, scale: f32, to_world: Mat4) -> Result<Self, String> {
        let (w, h, px) = if crate::io::open_regular(path)
            .and_then(|mut f| {
                let mut head = [0u8; 2];
                std::io::Read::read_exact(&mut f, &mut head).map(|_| head)
            })
            .is_ok_and(|head| crate::io::is_rgbe(&head))
        {
            read_rgbe_file(path)?
        } else {
            read_exr_at_most(path, MAX_TEXTURE_PIXELS).map_err(|e| e.to_string())?
        };
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
        let (values, columns, rows) = vertex_values(width, height, &texels);
        let dist = PiecewiseLinear2D::new(&values, columns, rows)
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

    /// Map coordinates `(u, v) ∈ [0,1)²` of a world direction and its `sin θ`
    /// ([`LatLong`]).
    fn uv(&self, dir_world: Vec3) -> (Vec2, f32) {
        LatLong::uv_sin_theta((self.to_local * dir_world).normalize_or_zero())
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
        let (cell_uv, pdf_uv) = self.dist.sample_with_pdf(u);
        let uv = Vec2::new(wrap_unit(cell_uv.x + self.half_texel()), cell_uv.y);
        if !is_positive(pdf_uv) {
            return None;
        }
        let (local, st) = LatLong::direction_sin_theta(uv);
        let dir = (self.to_world * local).normalize();
        Some((dir, self.lookup(uv), LatLong::solid_angle_pdf(pdf_uv, st)))
    }

    /// Density per steradian with which [`EnvMap::sample`] returns `dir`.
    pub fn pdf(&self, dir: Vec3) -> f32 {
        let (uv, st) = self.uv(dir);
        let cell_uv = Vec2::new(wrap_unit(uv.x - self.half_texel()), uv.y);
        LatLong::solid_angle_pdf(self.dist.pdf(cell_uv), st)
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

/// The fewest vertex rows of the sampling grid: coarser maps split each interval between
/// rows, so that the per-row `s̄` follows `sin θ` closely enough.
const MIN_GRID_ROWS: usize = 9;

/// The least share of its luminance a pole vertex keeps, so that the density stays positive
/// at the pole itself (a sample with `u.y = 0` lands there), at a variance cost that fades
/// with the map's height: by quadrature in θ, the relative standard deviation of `L/p` for a
/// uniform map grows from 4·10⁻⁴ to 1·10⁻³ at 33 rows, from 10⁻⁶ to 6·10⁻⁵ at 513.
const POLE_FLOOR: f32 = 1.0 / 64.0;

/// The sampling grid, row-major: `(values, columns, rows)`. Column `i` is texel column
/// `i mod width` (the last repeats the first, for the wrap in `u`); grid row `r` lies at
/// `v = r/(rows − 1)`, where the luminance is interpolated linearly between texel rows as the
/// lookup does (a one-row map is two equal rows). A vertex's value is that luminance times
/// the row's `s̄ = ∫ hat_r sin θ dθ / ∫ hat_r dθ`, but at a pole only the luminance in
/// excess of the next row's, and at least [`POLE_FLOOR`] of it (see [`EnvMap`]). A black map
/// gets luminance 1 everywhere, which samples by (nearly) solid angle.
fn vertex_values(width: usize, height: usize, texels: &[Vec3]) -> (Vec<f32>, usize, usize) {
    let columns = width + 1;
    let intervals = height.max(2) - 1;
    let split = (MIN_GRID_ROWS - 1).div_ceil(intervals).max(1);
    let rows = intervals * split + 1;
    let lum: Vec<f32> = texels.iter().map(|&t| luminance(t)).collect();
    let black = lum.iter().all(|&l| l <= 0.0);
    let at = |r: usize, i: usize| {
        let (y0, y1, t) = rows_of(height, (r / split, r % split), split);
        let x = i % width;
        if black {
            1.0
        } else {
            lum[y0 * width + x] * (1.0 - t) + lum[y1 * width + x] * t
        }
    };
    let tent = std::f64::consts::PI / (rows - 1) as f64;
    let mut values = Vec::with_capacity(columns * rows);
    for (r, weight) in row_weights(rows).into_iter().enumerate() {
        let pole_neighbour = match r {
            0 => Some(1),
            _ if r + 1 == rows => Some(r - 1),
            _ => None,
        };
        let tent_area = if pole_neighbour.is_some() {
            tent / 2.0
        } else {
            tent
        };
        let mean_sin = (weight / tent_area) as f32;
        for i in 0..columns {
            let l = match pole_neighbour {
                Some(n) => (at(r, i) - at(n, i)).max(at(r, i) * POLE_FLOOR),
                None => at(r, i),
            };
            values.push(l * mean_sin);
        }
    }
    (values, columns, rows)
}

/// The texel rows around sub-row `k` of interval `j` (of `split` sub-rows): `(lower, upper,
/// weight of the upper)`.
fn rows_of(height: usize, (j, k): (usize, usize), split: usize) -> Lerp {
    if height < 2 {
        return (0, 0, 0.0);
    }
    if j + 1 >= height {
        return (height - 1, height - 1, 0.0);
    }
    (j, j + 1, k as f32 / split as f32)
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
