//! An environment map of the user's own: a small procedural latitude–longitude image,
//! importance-sampled through `mcrt::PiecewiseConstant2D` and `mcrt::LatLong`.

use mcrt::glam::{Vec2, Vec3};
use mcrt::{InvertibleWarp, LatLong, PiecewiseConstant2D, SamplingError, SummedAreaTable, Warp};

/// A latitude–longitude environment image (`+y` up, mcrt's [`LatLong`] convention), its
/// sampling table (radiance × `sin θ` at each texel's centre) and the table's summed-area
/// table.
#[derive(Clone, Debug)]
pub struct Sky {
    width: usize,
    height: usize,
    radiance: Vec<f32>,
    table: PiecewiseConstant2D,
    sat: SummedAreaTable,
}

impl Sky {
    /// A `width × height` sky: a gradient brightening toward the zenith, a dim ground, and a
    /// sun (radiance 50, angular radius 0.12 rad) 30° above the horizon toward `sun_azimuth`
    /// (`u` of its centre).
    ///
    /// # Errors
    /// As [`PiecewiseConstant2D::new`] (not for a positive size).
    pub fn procedural(
        width: usize,
        height: usize,
        sun_azimuth: f32,
    ) -> Result<Self, SamplingError> {
        let sun = LatLong.sample(Vec2::new(sun_azimuth, 1.0 / 3.0));
        let cos_sun = 0.12f32.cos();
        let mut radiance = Vec::with_capacity(width * height);
        let mut weights = Vec::with_capacity(width * height);
        for j in 0..height {
            for i in 0..width {
                let uv = Vec2::new(
                    (i as f32 + 0.5) / width as f32,
                    (j as f32 + 0.5) / height as f32,
                );
                let dir = LatLong.sample(uv);
                let l = if dir.dot(sun) >= cos_sun {
                    50.0
                } else if dir.y >= 0.0 {
                    0.2 + 0.8 * dir.y
                } else {
                    0.05
                };
                radiance.push(l);
                weights.push(l * LatLong::sin_theta(dir));
            }
        }
        Ok(Self {
            width,
            height,
            table: PiecewiseConstant2D::new(&weights, width, height)?,
            sat: SummedAreaTable::new(&weights, width, height)?,
            radiance,
        })
    }

    /// The image's width and height in texels.
    pub fn size(&self) -> [usize; 2] {
        [self.width, self.height]
    }

    /// The sampling table (density per unit area of the `(u, v)` square).
    pub fn table(&self) -> &PiecewiseConstant2D {
        &self.table
    }

    /// The summed-area table of the sampling weights.
    pub fn summed_area_table(&self) -> &SummedAreaTable {
        &self.sat
    }

    /// The texel `(column, row)` holding `uv ∈ [0, 1)²`.
    pub fn texel(&self, uv: Vec2) -> [usize; 2] {
        let i = ((uv.x * self.width as f32) as usize).min(self.width - 1);
        let j = ((uv.y * self.height as f32) as usize).min(self.height - 1);
        [i, j]
    }

    /// The radiance of texel `(i, j)`.
    pub fn texel_radiance(&self, [i, j]: [usize; 2]) -> f32 {
        self.radiance[j * self.width + i]
    }

    /// The radiance arriving from the unit direction `dir` (the texel it falls in).
    pub fn radiance(&self, dir: Vec3) -> f32 {
        self.texel_radiance(self.texel(LatLong.invert(dir)))
    }

    /// `∫ L dω` over the sphere, exactly: each texel's radiance times its solid angle
    /// `(2π / width)(cos θ₀ − cos θ₁)`.
    pub fn power(&self) -> f64 {
        let dphi = std::f64::consts::TAU / self.width as f64;
        let mut sum = 0.0;
        for j in 0..self.height {
            let theta = |v: usize| std::f64::consts::PI * v as f64 / self.height as f64;
            let omega = dphi * (theta(j).cos() - theta(j + 1).cos());
            for i in 0..self.width {
                sum += f64::from(self.texel_radiance([i, j])) * omega;
            }
        }
        sum
    }

    /// A direction drawn from the table for `u ∈ [0, 1)²`, with its density per steradian.
    pub fn sample(&self, u: Vec2) -> (Vec3, f32) {
        let (uv, pdf_uv) = self.table.sample_with_pdf(u);
        let (dir, sin_theta) = LatLong::direction_sin_theta(uv);
        (dir, LatLong::solid_angle_pdf(pdf_uv, sin_theta))
    }

    /// The density per steradian with which [`Sky::sample`] returns the unit direction `dir`.
    pub fn pdf(&self, dir: Vec3) -> f32 {
        let (uv, sin_theta) = LatLong::uv_sin_theta(dir);
        LatLong::solid_angle_pdf(self.table.pdf(uv), sin_theta)
    }
}
