//! Metropolis light transport in primary sample space over the bidirectional path sampler,
//! multiplexed over path lengths and connection strategies.
//!
//! Kelemen, Szirmay-Kalos, Antal, Csonka 2002, "A Simple and Robust Mutation Strategy for
//! the Metropolis Light Transport Algorithm", Computer Graphics Forum 21(3); Hachisuka,
//! Kaplanyan, Dachsbacher 2014, "Multiplexed Metropolis Light Transport", ACM TOG 33(4).
//!
//! A point of primary sample space ([`PrimarySamples`]) maps to one path: the first values
//! choose a film position and one strategy `(s, t)` uniformly among the `k + 1` that make
//! paths of `k` segments, the rest drive the camera subpath, the light subpath and the
//! connection, each from its own stream. The path's contribution times the number of
//! strategies, with the strategy's MIS weight, is the function the chains sample in
//! proportion to its brightness. A bootstrap of independent paths per length estimates the
//! normalisation `b` (the mean brightness over primary sample space) and picks the chains'
//! starting points and lengths; rejected proposals still splat their expected share
//! (Veach 1997, thesis, section 11.5).

mod chain;
mod primary;

pub use chain::MltChain;
pub use primary::PrimarySamples;

use super::bdpt::{camera_subpath, connect, light_subpath, BdptBuffers, Heuristic, WalkLimits};
use super::{BidirectionalScene, SampleSource, Strategy};
use glam::{Vec2, Vec3};

/// Metropolis light transport's parameters (pbrt-v4's names; Mitsuba 0.6's `pssmlt`).
///
/// ```
/// use mcrt::integrator::Mlt;
///
/// let m = Mlt::default();
/// assert_eq!((m.max_depth, m.chains, m.mutations_per_pixel), (5, 1000, 100));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mlt {
    /// Longest path in segments (at least 1; Mitsuba's meaning of `max_depth`).
    pub max_depth: u32,
    /// Independent paths per path length for the normalisation and the chains' seeds.
    pub bootstrap_samples: u32,
    /// Markov chains.
    pub chains: u32,
    /// Mutations per pixel, over all chains.
    pub mutations_per_pixel: u32,
    /// Probability of a large step (a fresh, independent point).
    pub large_step_prob: f32,
    /// Standard deviation of a small step.
    pub sigma: f32,
    /// The MIS heuristic among the strategies of one path (balance or power).
    pub strategy: Strategy,
    /// Hide emitters seen directly: paths of one segment carry nothing, as with
    /// [`Bdpt::hide_emitters`](super::Bdpt::hide_emitters).
    pub hide_emitters: bool,
}

impl Mlt {
    /// The defaults (pbrt-v4's): `max_depth` 5, `bootstrap_samples` 100000, `chains` 1000,
    /// `mutations_per_pixel` 100, `large_step_prob` 0.3, `sigma` 0.01, the power heuristic.
    /// A `const`, so that a scene format can name these numbers as its own defaults.
    pub const DEFAULT: Mlt = Mlt {
        max_depth: 5,
        bootstrap_samples: 100_000,
        chains: 1000,
        mutations_per_pixel: 100,
        large_step_prob: 0.3,
        sigma: 0.01,
        strategy: Strategy::MisPower,
        hide_emitters: false,
    };
}

impl Default for Mlt {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// One path of primary sample space: where it lands on the film and what it carries.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MltPath {
    /// Film position in pixels.
    pub raster: Vec2,
    /// Contribution (already multiplied by the number of strategies).
    pub value: Vec3,
}

/// The brightness a chain samples in proportion to: the channel mean (0 for a
/// non-finite or negative value).
#[inline]
pub fn brightness(v: Vec3) -> f32 {
    let y = (v.x + v.y + v.z) / 3.0;
    if y.is_finite() && y > 0.0 {
        y
    } else {
        0.0
    }
}

impl Mlt {
    fn heuristic(&self) -> Heuristic {
        match self.strategy {
            Strategy::MisBalance => Heuristic::Balance,
            _ => Heuristic::Power,
        }
    }

    /// The path of `segments` segments that the primary sample point `u` maps to (zero
    /// value where the chosen strategy cannot make one). Rays cast are added to `rays`.
    pub fn path<S: BidirectionalScene, R: SampleSource>(
        &self,
        scene: &S,
        segments: u32,
        u: &mut R,
        buf: &mut BdptBuffers,
        rays: &mut u32,
    ) -> MltPath {
        let (w, h) = scene.film_size();
        u.start_stream(0);
        let raster = u.next_2d() * Vec2::new(w as f32, h as f32);
        let mut out = MltPath {
            raster,
            value: Vec3::ZERO,
        };
        // Strategy choice: uniform over the k + 1 strategies of k segments (the camera
        // seeing an emitter directly has only s = 0).
        if self.hide_emitters && segments == 1 {
            return out;
        }
        let k = segments as usize;
        let n = if k == 1 { 1 } else { k + 1 };
        let s = if k == 1 {
            0
        } else {
            ((u.next_1d() * n as f32) as usize).min(n - 1)
        };
        let t = k + 1 - s;
        let (origin, dir, t_max) = if scene.camera_has_lens() {
            scene.camera_ray_through_lens(raster, u.next_2d())
        } else {
            scene.camera_ray(raster)
        };
        let lim = |max_vertices| WalkLimits {
            max_vertices,
            rr_depth: u32::MAX,
        };
        camera_subpath(scene, origin, dir, t_max, lim(t), u, &mut buf.camera, rays);
        if buf.camera.len() != t {
            return out;
        }
        u.start_stream(1);
        light_subpath(scene, lim(s), u, &mut buf.light, rays);
        if buf.light.len() != s {
            return out;
        }
        u.start_stream(2);
        let Some(c) = connect(
            scene,
            &buf.light,
            &buf.camera,
            s,
            t,
            self.heuristic(),
            u,
            rays,
        ) else {
            return out;
        };
        if let Some(r) = c.raster {
            out.raster = r;
        }
        out.value = c.value * (c.weight * n as f32);
        out
    }

    /// Seed of the primary sample point of bootstrap sample `index` for `segments`
    /// segments, from the render's `seed`.
    pub fn bootstrap_seed(&self, seed: u64, index: u32, segments: u32) -> u64 {
        let k = (index as u64) * (self.max_depth as u64 + 1) + segments as u64;
        use crate::sampling::sampler::hash::{combine, mix64};
        combine(mix64(seed), k)
    }
}
