//! Pixel reconstruction filters, sampled by filter importance sampling.

use crate::description::FilterDesc;
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
        /// `−1/(2σ²)`, the exponent's factor.
        a: f32,
        /// `exp(−r²/2σ²)`, the shift that makes the density 0 at the radius.
        bias: f32,
        /// 1 / the integral of the shifted Gaussian over `[−r, r]` (one axis).
        norm: f32,
    },
    /// Mitsuba's `tent`: `max(0, 1 − |x|/r)` per axis on `[−r, r]`, sampled exactly per axis
    /// by [`Tent`](mcrt::sampling::warp::Tent).
    Tent {
        /// Radius in pixels (Mitsuba's default 1).
        radius: f32,
    },
}

impl PixelFilter {
    /// The filter a description asks for.
    pub fn from_desc(desc: &FilterDesc) -> Self {
        match *desc {
            FilterDesc::Box => PixelFilter::Box,
            FilterDesc::Gaussian { stddev } => Self::gaussian(stddev.max(1e-3)),
            FilterDesc::Tent { radius } => PixelFilter::Tent {
                radius: radius.max(1e-3),
            },
        }
    }

    /// The per-axis density at offset `d` from a pixel centre, and the radius beyond which
    /// it is 0; `None` for the box.
    #[inline]
    fn axis(&self) -> Option<(f32, impl Fn(f32) -> f32 + '_)> {
        let radius = match *self {
            PixelFilter::Box => return None,
            PixelFilter::Gaussian { radius, .. } | PixelFilter::Tent { radius } => radius,
        };
        Some((radius, move |d: f32| match *self {
            PixelFilter::Gaussian { a, bias, norm, .. } => {
                ((a * d * d).exp() - bias).max(0.0) * norm
            }
            PixelFilter::Tent { radius } => (1.0 - d.abs() / radius).max(0.0) / radius,
            PixelFilter::Box => 0.0,
        }))
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
            a: a as f32,
            bias: bias as f32,
            norm: (1.0 / total) as f32,
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
            &PixelFilter::Tent { radius } => match mcrt::sampling::warp::Tent::new(radius) {
                Ok(t) => {
                    use mcrt::sampling::warp::Warp1D;
                    Vec2::new(t.sample(u.x), t.sample(u.y))
                }
                Err(_) => Vec2::ZERO,
            },
        }
    }
}

impl PixelFilter {
    /// `Σ_j h(x − x_j)` over the pixel centres `x_j` of a `width` × `height` film: the
    /// density (relative to uniform over the film) with which the render loop's filter
    /// importance sampling places a film sample at `raster`. 1 inside the film for the box
    /// filter (0 outside); for the Gaussian, about 1 inside (a midpoint sum of its density)
    /// and falling to 0 within its radius outside. The bidirectional estimators weigh the
    /// camera's strategies by it.
    pub fn coverage(&self, raster: Vec2, width: u32, height: u32) -> f32 {
        let mut sums = [0.0f32; 2];
        let Some((radius, density)) = self.axis() else {
            let inside = raster.x >= 0.0
                && raster.y >= 0.0
                && raster.x < width as f32
                && raster.y < height as f32;
            return if inside { 1.0 } else { 0.0 };
        };
        for (axis, (c, n)) in [(raster.x, width), (raster.y, height)]
            .into_iter()
            .enumerate()
        {
            if !c.is_finite() {
                return 0.0;
            }
            let lo = (c - radius - 0.5).ceil().max(0.0) as i64;
            let hi = ((c + radius - 0.5).floor() as i64).min(n as i64 - 1);
            sums[axis] = (lo..=hi).map(|i| density(i as f32 + 0.5 - c)).sum();
        }
        sums[0] * sums[1]
    }

    /// Spreads a contribution at film position `raster` over the pixels of a `width` ×
    /// `height` film as the filter weighs it: `add(pixel index, weight)` for every pixel
    /// whose filter covers `raster`, the weight the filter's density at the offset from the
    /// pixel's centre (weights over all pixels sum to 1 away from the film's edges).
    pub fn splat(&self, raster: Vec2, width: u32, height: u32, mut add: impl FnMut(usize, f32)) {
        if !raster.is_finite() {
            return;
        }
        let Some((radius, density)) = self.axis() else {
            let (x, y) = (raster.x.floor(), raster.y.floor());
            if x >= 0.0 && y >= 0.0 && x < width as f32 && y < height as f32 {
                add(y as usize * width as usize + x as usize, 1.0);
            }
            return;
        };
        let lo = |c: f32| (c - radius - 0.5).ceil().max(0.0) as u32;
        let hi = |c: f32, n: u32| ((c + radius - 0.5).floor() as i64).min(n as i64 - 1);
        let (x0, y0) = (lo(raster.x), lo(raster.y));
        let (x1, y1) = (hi(raster.x, width), hi(raster.y, height));
        for y in y0 as i64..=y1 {
            let wy = density(y as f32 + 0.5 - raster.y);
            if wy <= 0.0 {
                continue;
            }
            for x in x0 as i64..=x1 {
                let wx = density(x as f32 + 0.5 - raster.x);
                if wx > 0.0 {
                    add(y as usize * width as usize + x as usize, wx * wy);
                }
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
        // The tent of radius r has variance r²/6.
        let t = PixelFilter::from_desc(&FilterDesc::Tent { radius: 1.0 });
        let xs: Vec<f64> = (0..n)
            .map(|i| t.sample(Vec2::splat((i as f32 + 0.5) / n as f32)).x as f64)
            .collect();
        assert!(xs.iter().all(|x| x.is_finite() && x.abs() <= 1.0));
        let var = xs.iter().map(|x| x * x).sum::<f64>() / n as f64;
        assert!((var - 1.0 / 6.0).abs() < 1e-3, "{var}");
    }

    #[test]
    fn coverage_is_the_sum_of_the_splat_weights() {
        for f in [
            PixelFilter::Box,
            PixelFilter::from_desc(&FilterDesc::Gaussian { stddev: 0.5 }),
            PixelFilter::from_desc(&FilterDesc::Tent { radius: 1.0 }),
            PixelFilter::from_desc(&FilterDesc::Tent { radius: 1.7 }),
        ] {
            for r in [
                Vec2::new(10.3, 7.8),
                Vec2::new(0.2, 0.1),
                Vec2::new(-0.7, 5.0),
            ] {
                let mut total = 0.0f32;
                f.splat(r, 20, 20, |_, w| total += w);
                let c = f.coverage(r, 20, 20);
                assert!(
                    c.is_finite() && (c - total).abs() < 1e-5,
                    "{r}: {c} vs {total}"
                );
            }
        }
        // Outside the film the Gaussian still covers the border pixels; the box does not.
        let g = PixelFilter::from_desc(&FilterDesc::Gaussian { stddev: 0.5 });
        assert!(g.coverage(Vec2::new(-0.7, 5.0), 20, 20) > 0.0);
        assert_eq!(PixelFilter::Box.coverage(Vec2::new(-0.7, 5.0), 20, 20), 0.0);
    }

    #[test]
    fn splat_weights_sum_to_one_inside_the_film() {
        for f in [
            PixelFilter::Box,
            PixelFilter::from_desc(&FilterDesc::Gaussian { stddev: 0.5 }),
            PixelFilter::from_desc(&FilterDesc::Tent { radius: 1.0 }),
        ] {
            let mut total = 0.0f32;
            f.splat(Vec2::new(10.3, 7.8), 20, 20, |i, w| {
                assert!(w.is_finite() && w > 0.0 && i < 400);
                total += w;
            });
            // The Gaussian's per-axis weights are a midpoint sum of its density: close to 1.
            assert!(total.is_finite() && (total - 1.0).abs() < 0.02, "{total}");
            let mut hits = 0;
            f.splat(Vec2::new(-5.0, 3.0), 20, 20, |_, _| hits += 1);
            assert_eq!(hits, 0);
        }
    }
}
