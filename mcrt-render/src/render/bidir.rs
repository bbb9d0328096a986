//! The render loop of bidirectional path tracing: tiles in parallel as for the path tracer,
//! plus the light-tracing contributions that land anywhere on the film. Each tile returns
//! its splats; they are added in tile order after every batch of tiles, so the image does
//! not depend on the thread count.

use super::tiles::{pass_size, tiles, LoopParams, LoopStats};
use crate::film::{Film, PixelAccum};
use glam::{Vec2, Vec3};
use mcrt::integrator::{Bdpt, BdptBuffers, BidirectionalScene, Splat, StrategyStats};
use mcrt::sampling::sampler::{AnySampler, Sampler};
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// Tiles whose splats are held at once before they are added to the film.
const BATCH: usize = 64;

/// Most samples per pixel in one pass (bounds the splats a batch holds).
const MAX_PASS: u32 = 16;

/// The sample stream of a thin lens's sample (after the estimator's three: camera
/// subpath, light subpath, connections).
const LENS_STREAM: u32 = 3;

/// What one tile hands back.
struct TileOut {
    pixels: Vec<(usize, PixelAccum)>,
    splats: Vec<Splat>,
    rays: u64,
    nonfinite: u64,
    stats: StrategyStats,
}

fn render_tile<S: BidirectionalScene>(
    scene: &S,
    p: &LoopParams<'_>,
    bdpt: &Bdpt,
    tile: (u32, u32, u32, u32),
    samples: (u32, u32),
) -> TileOut {
    match p.sampler {
        AnySampler::Independent(s) => render_tile_with(scene, p, bdpt, s.clone(), tile, samples),
        AnySampler::Stratified(s) => render_tile_with(scene, p, bdpt, s.clone(), tile, samples),
        AnySampler::Sobol(s) => render_tile_with(scene, p, bdpt, s.clone(), tile, samples),
        AnySampler::Halton(s) => render_tile_with(scene, p, bdpt, s.clone(), tile, samples),
        AnySampler::R2(s) => render_tile_with(scene, p, bdpt, s.clone(), tile, samples),
        AnySampler::Cmj(s) => render_tile_with(scene, p, bdpt, s.clone(), tile, samples),
        AnySampler::Sobol4d(s) => render_tile_with(scene, p, bdpt, s.clone(), tile, samples),
    }
}

fn render_tile_with<S: BidirectionalScene, R: Sampler>(
    scene: &S,
    p: &LoopParams<'_>,
    bdpt: &Bdpt,
    mut sampler: R,
    (x0, y0, x1, y1): (u32, u32, u32, u32),
    (s0, s1): (u32, u32),
) -> TileOut {
    let mut out = TileOut {
        pixels: Vec::with_capacity(((x1 - x0) * (y1 - y0)) as usize),
        splats: Vec::new(),
        rays: 0,
        nonfinite: 0,
        stats: StrategyStats::default(),
    };
    let mut buf = BdptBuffers::default();
    for y in y0..y1 {
        for x in x0..x1 {
            let index = (y * p.width + x) as usize;
            let mut acc = PixelAccum::default();
            for s in s0..s1 {
                if p.cancel.load(Ordering::Relaxed) {
                    out.pixels.push((index, acc));
                    return out;
                }
                sampler.start_pixel_sample([x, y], s);
                let off = p.filter.sample(sampler.next_2d());
                let film = Vec2::new(x as f32 + 0.5, y as f32 + 0.5) + off;
                // A thin lens's sample comes from a stream of its own (the estimator starts
                // the camera subpath's stream itself); a pinhole draws none.
                let (ray, t_max) = if p.camera.has_lens() {
                    sampler.start_stream(LENS_STREAM);
                    p.camera.generate_ray_through_lens(film, sampler.next_2d())
                } else {
                    p.camera.generate_ray_with_tmax(film)
                };
                let r = bdpt.sample(
                    scene,
                    ray.origin,
                    ray.dir,
                    t_max.min(p.t_max),
                    &mut sampler,
                    &mut buf,
                    &mut out.splats,
                    Some(&mut out.stats),
                );
                out.rays += r.rays as u64;
                let v = r.radiance;
                if v.is_finite() {
                    acc.add(v);
                } else {
                    acc.add(Vec3::ZERO);
                    out.nonfinite += 1;
                }
            }
            out.pixels.push((index, acc));
        }
    }
    out
}

/// Renders the sample range in the window with bidirectional samples (fewer if cancelled);
/// light tracing splats over the whole film.
pub(crate) fn render_loop_bdpt<S: BidirectionalScene + Sync>(
    scene: &S,
    p: &LoopParams<'_>,
    bdpt: &Bdpt,
) -> (Film, LoopStats) {
    let mut film = Film::new(p.width, p.height);
    let mut stats = LoopStats {
        strategies: Some(StrategyStats::default()),
        ..LoopStats::default()
    };
    let all = tiles(p.window);
    let total = p.samples.len() as u64 * p.window.area();
    let done = AtomicU64::new(0);
    let step = pass_size(p.samples.len()).min(MAX_PASS);
    let mut s0 = p.samples.start;
    while s0 < p.samples.end && !p.cancel.load(Ordering::Relaxed) {
        let s1 = (s0 + step).min(p.samples.end);
        for batch in all.chunks(BATCH) {
            let results: Vec<Option<TileOut>> = batch
                .par_iter()
                .map(|&t| {
                    if p.cancel.load(Ordering::Relaxed) {
                        return None;
                    }
                    let r = render_tile(scene, p, bdpt, t, (s0, s1));
                    let n = ((t.2 - t.0) * (t.3 - t.1) * (s1 - s0)) as u64;
                    let d = done.fetch_add(n, Ordering::Relaxed) + n;
                    (p.progress)(d, total);
                    Some(r)
                })
                .collect();
            for r in results.into_iter().flatten() {
                stats.rays += r.rays;
                stats.nonfinite += r.nonfinite;
                for (i, a) in &r.pixels {
                    stats.samples += a.count as u64;
                    let merged = film.merge(*i, a);
                    debug_assert!(merged.is_ok());
                }
                for sp in &r.splats {
                    if !sp.value.is_finite() {
                        stats.nonfinite += 1;
                    } else {
                        p.filter.splat(sp.raster, p.width, p.height, |i, w| {
                            film.add_splat(i, sp.value * w)
                        });
                    }
                }
                if let Some(st) = stats.strategies.as_mut() {
                    st.merge(&r.stats);
                }
            }
        }
        s0 = s1;
    }
    // Light tracing made one light subpath per pixel sample: a pixel's splats divided by
    // the samples per pixel taken (the same for every pixel of the window unless cancelled).
    film.set_splat_scale(crate::film::splat_scale(stats.samples, p.window.area()));
    (film, stats)
}
