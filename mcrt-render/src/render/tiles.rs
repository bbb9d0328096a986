//! The parallel render loop: passes over the sample range, tiles of the crop in parallel
//! (rayon), per-pixel accumulation merged in a fixed order so the result does not depend on
//! the thread count. A pixel sample is seeded by its pixel and its index alone, so a render
//! of a sample range or a crop draws exactly the samples a whole render draws for them.
//! The cancel flag is read before and after every pixel sample (a sample that was running
//! when it was set is discarded), and the path tracer's paths end at their next bounce
//! once it is set, so cancelling takes effect within one ray.

use crate::camera::Camera;
use crate::film::{xyz_squared, Crop, Film, PixelAccum, PixelFilter, SampleRange};
use glam::Vec2;
use mcrt::integrator::{Integrator, Scene};
use mcrt::sampling::sampler::{AnySampler, Sampler};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

/// Tile edge in pixels.
const TILE: u32 = 16;

/// What the loop needs besides the scene.
pub(crate) struct LoopParams<'a> {
    pub camera: &'a Camera,
    pub integrator: &'a Integrator,
    pub filter: &'a PixelFilter,
    pub width: u32,
    pub height: u32,
    /// Samples per pixel of the whole render (the sampler's layout).
    pub spp: u32,
    /// The sample indices to render.
    pub samples: SampleRange,
    /// The pixels to render.
    pub window: Crop,
    pub sampler: &'a AnySampler,
    /// The render's seed (Metropolis chains derive theirs from it).
    pub seed: u64,
    pub t_max: f32,
    pub progress: &'a (dyn Fn(u64, u64) + Sync),
    pub cancel: &'a AtomicBool,
    /// The `moment` integrator's nested name, if the film keeps its sums.
    pub moment: Option<&'a str>,
    /// The further integrators nested in `moment`, with their names: each renders every
    /// pixel sample again from its start, as it would alone.
    pub moment_more: &'a [(String, Integrator)],
}

/// One tile's per-pixel accumulators, each pixel's sum of squared XYZ samples for the
/// `moment` channels (empty unless the film keeps them), its ray count, its count of
/// non-finite samples, and per pixel the accumulators of the further nested integrators of
/// `moment` (empty without them).
type TileResult = (
    Vec<(usize, PixelAccum)>,
    Vec<[f64; 3]>,
    u64,
    u64,
    Vec<MoreAccum>,
);

/// A pixel's samples of the further integrators nested in `moment`: per integrator, its
/// accumulator and its sum of squared XYZ samples.
type MoreAccum = Vec<(PixelAccum, [f64; 3])>;

/// Counters of the work done.
#[derive(Debug, Clone, Default)]
pub(crate) struct LoopStats {
    pub samples: u64,
    pub rays: u64,
    /// What each bidirectional strategy contributed (BDPT only).
    pub strategies: Option<mcrt::integrator::StrategyStats>,
    /// Samples whose value was NaN or infinite (added as zero).
    pub nonfinite: u64,
    /// What training cost (the guided path tracer only).
    pub guiding: Option<super::GuidingReport>,
}

/// The tiles of window `c`, row by row.
pub(crate) fn tiles(c: Crop) -> Vec<(u32, u32, u32, u32)> {
    let mut v = Vec::new();
    for y0 in (c.y0..c.y1).step_by(TILE as usize) {
        for x0 in (c.x0..c.x1).step_by(TILE as usize) {
            v.push((x0, y0, (x0 + TILE).min(c.x1), (y0 + TILE).min(c.y1)));
        }
    }
    v
}

/// Samples per pass: about 16 passes, at most 64 spp each, so progress and cancellation are
/// responsive.
pub(crate) fn pass_size(spp: u32) -> u32 {
    spp.div_ceil(16).clamp(1, 64)
}

/// Renders one tile for sample indices `s0..s1` with the sampler's concrete type, so that
/// its calls inline into the path loop (no per-call dispatch on [`AnySampler`]).
fn render_tile<S: Scene>(
    scene: &S,
    p: &LoopParams<'_>,
    tile: (u32, u32, u32, u32),
    samples: (u32, u32),
) -> TileResult {
    match p.sampler {
        AnySampler::Independent(s) => render_tile_with(scene, p, s.clone(), tile, samples),
        AnySampler::Stratified(s) => render_tile_with(scene, p, s.clone(), tile, samples),
        AnySampler::Sobol(s) => render_tile_with(scene, p, s.clone(), tile, samples),
        AnySampler::Halton(s) => render_tile_with(scene, p, s.clone(), tile, samples),
        AnySampler::R2(s) => render_tile_with(scene, p, s.clone(), tile, samples),
        AnySampler::Cmj(s) => render_tile_with(scene, p, s.clone(), tile, samples),
        AnySampler::Sobol4d(s) => render_tile_with(scene, p, s.clone(), tile, samples),
    }
}

/// [`render_tile`] for one sampler type.
fn render_tile_with<S: Scene, R: Sampler>(
    scene: &S,
    p: &LoopParams<'_>,
    mut rng: R,
    (x0, y0, x1, y1): (u32, u32, u32, u32),
    (s0, s1): (u32, u32),
) -> TileResult {
    let mut out = Vec::with_capacity(((x1 - x0) * (y1 - y0)) as usize);
    let mut moments = Vec::new();
    let mut mores = Vec::new();
    let (mut rays, mut nonfinite) = (0u64, 0u64);
    for y in y0..y1 {
        for x in x0..x1 {
            let index = (y * p.width + x) as usize;
            let mut acc = PixelAccum::default();
            let mut moment = [0.0f64; 3];
            let mut more: MoreAccum = vec![Default::default(); p.moment_more.len()];
            for s in s0..s1 {
                if p.cancel.load(Ordering::Relaxed) {
                    out.push((index, acc));
                    if p.moment.is_some() {
                        moments.push(moment);
                    }
                    if !more.is_empty() {
                        mores.push(more);
                    }
                    return (out, moments, rays, nonfinite, mores);
                }
                let r = pixel_sample(scene, p, p.integrator, &mut rng, [x, y], s);
                if p.cancel.load(Ordering::Relaxed) {
                    // The path may have been cut short by the cancel (`SceneView::stop`).
                    out.push((index, acc));
                    if p.moment.is_some() {
                        moments.push(moment);
                    }
                    if !more.is_empty() {
                        mores.push(more);
                    }
                    return (out, moments, rays, nonfinite, mores);
                }
                rays += r.rays as u64;
                let v = r.radiance;
                if v.is_finite() {
                    acc.add(v);
                    if p.moment.is_some() {
                        for (m, x) in moment.iter_mut().zip(xyz_squared(v)) {
                            *m += x;
                        }
                    }
                } else {
                    nonfinite += 1;
                    acc.add(glam::Vec3::ZERO);
                }
                // The further nested integrators, each from the pixel sample's start.
                for ((_, integrator), (acc, m2)) in p.moment_more.iter().zip(more.iter_mut()) {
                    let r = pixel_sample(scene, p, integrator, &mut rng, [x, y], s);
                    rays += r.rays as u64;
                    let v = r.radiance;
                    if v.is_finite() {
                        acc.add(v);
                        for (m, x) in m2.iter_mut().zip(xyz_squared(v)) {
                            *m += x;
                        }
                    } else {
                        nonfinite += 1;
                        acc.add(glam::Vec3::ZERO);
                    }
                }
            }
            out.push((index, acc));
            if p.moment.is_some() {
                moments.push(moment);
            }
            if !more.is_empty() {
                mores.push(more);
            }
        }
    }
    (out, moments, rays, nonfinite, mores)
}

/// Pixel sample `s` of pixel `[x, y]` by `integrator`: the sampler started at that sample,
/// a film position by the pixel filter, the camera ray, the estimate.
#[inline]
fn pixel_sample<S: Scene, R: Sampler>(
    scene: &S,
    p: &LoopParams<'_>,
    integrator: &Integrator,
    rng: &mut R,
    [x, y]: [u32; 2],
    s: u32,
) -> mcrt::integrator::PathResult {
    rng.start_pixel_sample([x, y], s);
    let off = p.filter.sample(rng.next_2d());
    let film = Vec2::new(x as f32 + 0.5, y as f32 + 0.5) + off;
    // A thin lens draws its lens sample after the film position (as Mitsuba 3's
    // integrators do); a pinhole draws none.
    let (ray, t_max) = if p.camera.has_lens() {
        p.camera.generate_ray_through_lens(film, rng.next_2d())
    } else {
        p.camera.generate_ray_with_tmax(film)
    };
    integrator.li(scene, ray.origin, ray.dir, t_max.min(p.t_max), rng)
}

/// Renders the sample range in the window (fewer samples if cancelled) into a film.
pub(crate) fn render_loop<S: Scene + Sync>(scene: &S, p: &LoopParams<'_>) -> (Film, LoopStats) {
    let mut film = Film::new(p.width, p.height);
    if let Some(name) = p.moment {
        film = film.with_moment(name);
        let names: Vec<&str> = p.moment_more.iter().map(|(n, _)| n.as_str()).collect();
        film = film.with_moment_more(&names);
    }
    let mut stats = LoopStats::default();
    let tiles = tiles(p.window);
    let total = p.samples.len() as u64 * p.window.area();
    let done = AtomicU64::new(0);
    let step = pass_size(p.samples.len());
    let mut s0 = p.samples.start;
    while s0 < p.samples.end && !p.cancel.load(Ordering::Relaxed) {
        let s1 = (s0 + step).min(p.samples.end);
        let results: Vec<Option<TileResult>> = tiles
            .par_iter()
            .map(|&t| {
                if p.cancel.load(Ordering::Relaxed) {
                    return None;
                }
                let r = render_tile(scene, p, t, (s0, s1));
                let n = ((t.2 - t.0) * (t.3 - t.1) * (s1 - s0)) as u64;
                let d = done.fetch_add(n, Ordering::Relaxed) + n;
                (p.progress)(d, total);
                Some(r)
            })
            .collect();
        for (px, moments, rays, nonfinite, mores) in results.into_iter().flatten() {
            stats.rays += rays;
            stats.nonfinite += nonfinite;
            for (k, (i, a)) in px.iter().enumerate() {
                stats.samples += a.count as u64;
                // Indices come from `tiles`, which lie inside the film.
                let merged = film.merge(*i, a);
                debug_assert!(merged.is_ok());
                if let Some(m) = moments.get(k) {
                    film.add_moment(*i, *m);
                }
                if let Some(more) = mores.get(k) {
                    film.add_moment_more(*i, more);
                }
            }
        }
        s0 = s1;
    }
    (film, stats)
}
