//! The options of a render: what the caller overrides of the scene file.

use super::{AccelKind, ShapeSampling};
use crate::description::{IntegratorKind, SamplerKind};
use crate::film::{Crop, SampleRange};
use crate::light::LightBvhUse;
use mcrt::integrator::Strategy;

/// Overrides of what the scene file says.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderOptions {
    /// Samples per pixel (else the file's `sample_count`).
    pub spp: Option<u32>,
    /// Seed (else the file's sampler seed).
    pub seed: Option<u64>,
    /// Worker threads; 0 uses all cores. At most [`MAX_THREADS`](super::MAX_THREADS): more
    /// are clamped to it (the `render` program refuses them).
    pub threads: usize,
    /// Sampling strategy at every vertex (else MIS with the power heuristic).
    pub strategy: Option<Strategy>,
    /// Acceleration structure.
    pub accel: AccelKind,
    /// How area lights on triangles and rectangles are sampled by the path tracer and the
    /// direct integrator (by default [`ShapeSampling::Auto`]: by solid angle from near, by
    /// area from far); `bdpt` and `mlt` always sample them by
    /// area (their other strategies cover the region near a light where solid-angle sampling
    /// helps, at a fraction of its cost).
    pub light_sampling: ShapeSampling,
    /// When next-event estimation chooses its light by the light BVH (by default above 16
    /// lights with a position, each emitting triangle counted).
    pub light_bvh: LightBvhUse,
    /// Candidates of resampled next-event estimation over the light BVH for the path and
    /// direct integrators (`render --light-candidates M`; `docs/renderer.md`, "Choosing among
    /// many lights"): `M` BVH samples, one kept in proportion to its unshadowed contribution,
    /// where every light is an untextured rectangle or emitting mesh; 1 for one BVH sample.
    /// `None`: one candidate (no resampling).
    pub light_candidates: Option<u32>,
    /// Sample generator (else the file's `sampler` type).
    pub sampler: Option<SamplerKind>,
    /// Integrator type (else the file's); the file's `max_depth` and `rr_depth` carry over
    /// where both have them.
    pub integrator: Option<IntegratorKind>,
    /// Bidirectional path tracing with this strategy `(s, t)` alone at unit weight (for
    /// tests and pictures of one strategy).
    pub bdpt_only: Option<(u32, u32)>,
    /// Pick the render loop specialised to the scene's effects (default). `false` always
    /// runs the general loop (every material type, point lights and environment checked at
    /// run time); for benchmarks and tests of the specialisation.
    pub specialize: bool,
    /// Render only the pixel samples with these indices (`render --samples START..END`),
    /// exactly those a render of every sample draws for them; else all of them. Not with
    /// `mlt`, whose Markov chains are not divided by pixel sample.
    pub samples: Option<SampleRange>,
    /// Render only these pixels (`render --crop x0,y0,x1,y1`); else the whole image. Not
    /// with `mlt`.
    pub crop: Option<Crop>,
}

/// The candidates of resampled next-event estimation when `--light-candidates` is not given.
pub const DEFAULT_LIGHT_CANDIDATES: u32 = 1;

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            spp: None,
            seed: None,
            threads: 0,
            strategy: None,
            accel: AccelKind::Bvh,
            sampler: None,
            light_sampling: ShapeSampling::Auto,
            light_bvh: LightBvhUse::Auto,
            light_candidates: None,
            specialize: true,
            integrator: None,
            bdpt_only: None,
            samples: None,
            crop: None,
        }
    }
}
