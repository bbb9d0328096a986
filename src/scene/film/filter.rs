//! Pixel reconstruction filters, sampled by filter importance sampling.

use crate::scene::description::FilterDesc;
use glam::Vec2;

const TABLE: usize = 1024;

/// A separable pixel filter, as a density over the offset from the pixel centre.
#[derive(Debug, Clone, PartialEq)]
pub enum PixelFilter {
    /// Uniform over the pixel's footprint `[−½, ½)²`.
    Box,
    /// Mitsuba's `gaussian`: `max(0, exp(−x²/2σ²) − exp(−r²/2σ²))` per axis on `[−r, r]`,
    /// `r = 4σ`, sampled per axis by inverting a tabulated CDF (piecewise linear).
    Gaussian {
        /// Truncation radius in pixels.
        radius: f32,
        /// Inverse CDF at `TABLE + 1` equally spaced probabilities, in `[−r, r]`.
        inv_cdf: Vec<f32>,
    },
}

impl PixelFilter {
    /// The filter a description asks for.
    pub fn from_desc(desc: &FilterDesc) -> Self {
        match *desc {
            FilterDesc::Box => PixelFilter::Box,
            FilterDesc::Gaussian { stddev } => Self::gaussian(stddev.max(1e-3)),
        }
    }

    fn gaussian(stddev: f32) -> Self {
        let radius = 4.0 * stddev as f64;
        let a = -1.0 / (2.0 * (stddev as f64).powi(2));
        let bias = (a * radius * radius).exp();
        let f = |x: f64| ((a * x * x).exp() - bias).max(0.0);
        // Fine CDF by the midpoint rule, then inverted at equally spaced probabilities.
        let n = 4096;
        let h = 2.0 * radius / n as f64;
        let mut cdf = vec![0.0f64; n + 1];
        for i in 0..n {
            cdf[i + 1] = cdf[i] + f(-radius + (i as f64 + 0.5) * h) * h;
        }
        let total = cdf[n];
        let mut inv = Vec::with_capacity(TABLE + 1);
        let mut j = 0;
        for k in 0..=TABLE {
            let target = total * k as f64 / TABLE as f64;
            while j < n - 1 && cdf[j + 1] < target {
                j += 1;
            }
            let span = (cdf[j + 1] - cdf[j]).max(1e-300);
            let t = ((target - cdf[j]) / span).clamp(0.0, 1.0);
            inv.push((-radius + (j as f64 + t) * h) as f32);
        }
        PixelFilter::Gaussian {
            radius: radius as f32,
            inv_cdf: inv,
        }
    }

    /// Offset from the pixel centre for `u ∈ [0,1)²`.
    #[inline]
    pub fn sample(&self, u: Vec2) -> Vec2 {
        match self {
            PixelFilter::Box => u - Vec2::splat(0.5),
            PixelFilter::Gaussian { inv_cdf, .. } => {
                let one = |x: f32| {
                    let s = x * TABLE as f32;
                    let i = (s as usize).min(TABLE - 1);
                    let t = s - i as f32;
                    inv_cdf[i] + (inv_cdf[i + 1] - inv_cdf[i]) * t
                };
                Vec2::new(one(u.x), one(u.y))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gaussian_is_symmetric_with_the_right_spread() {
        let f = PixelFilter::from_desc(&FilterDesc::Gaussian { stddev: 0.5 });
        let n = 10000;
        let (mut m, mut v) = (0.0f64, 0.0f64);
        for i in 0..n {
            let x = f.sample(Vec2::splat((i as f32 + 0.5) / n as f32)).x as f64;
            assert!(x.is_finite() && x.abs() <= 2.0 + 1e-5);
            m += x;
            v += x * x;
        }
        m /= n as f64;
        v /= n as f64;
        assert!(m.abs() < 1e-3, "{m}");
        // The truncated-and-shifted Gaussian has σ = 0.4988 (by quadrature); the table's
        // linear interpolation widens it slightly.
        assert!((v.sqrt() - 0.4988).abs() < 0.004, "{}", v.sqrt());
        let b = PixelFilter::Box.sample(Vec2::new(0.0, 0.75));
        assert_eq!(b, Vec2::new(-0.5, 0.25));
    }
}
