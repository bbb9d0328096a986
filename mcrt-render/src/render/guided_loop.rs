//! The render loop of the guided path tracer: training passes of doubling sample counts
//! ([`GuidingSchedule`]), each guided by the SD-tree the previous pass trained and recording
//! into a fresh tree with the refined structure, then the final pass; the image combines the
//! final pass with the last training passes ([`combine`]) (Müller, Gross & Novák 2017,
//! "Practical Path Guiding for Efficient Light-Transport Simulation", CGF 36(4)).
//!
//! Determinism: every pass draws the pixel samples of its own indices ([`pass_indices`]:
//! training pass `k` the aligned block `[2^k, 2^(k+1))`, the final pass index 0 and the rest
//! of the sampler's layout), tiles record into their own [`GuidingRecords`], and the buffers
//! are merged into the training tree in tile order, chunk by chunk: the trees, and so the
//! image, are the same at any thread count.

use super::guided_combine::combine;
use super::tiles::{pass_size, tiles, LoopParams, LoopStats};
use crate::camera::Camera;
use crate::film::{Film, PixelAccum};
use glam::{Vec2, Vec3};
use mcrt::integrator::{GuidedPathTracer, PathTracer, Scene};
use mcrt::sampling::guiding::{GuidingPass, GuidingRecords, GuidingSchedule, SdTree};
use mcrt::sampling::sampler::{AnySampler, Sampler};
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::Instant;

/// Tiles rendered between two merges of their records (bounds the records held at once).
const CHUNK: usize = 64;

/// Training passes whose images join the final pass's ([`combine`]): the last ones of at
/// least two samples per pixel, whose variance can be estimated. Earlier passes hold few
/// samples (at most an eighth of the budget together) and would cost a film each.
pub(crate) const KEPT_TRAINING_IMAGES: usize = 3;

/// The guided path tracer with its training settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct GuidedSetup {
    /// The estimator.
    pub tracer: GuidedPathTracer,
    /// `c` of the spatial threshold `c·√(2^k)`.
    pub spatial_threshold: f32,
    /// ρ, the directional subdivision threshold.
    pub directional_threshold: f32,
    /// The least [`SdTree::selection_gain`] for which training goes on after
    /// [`DECIDING_PASS`] (0: always).
    pub min_gain: f32,
}

/// The training pass (counted from 0) after which, and after every later one, the guide's
/// promised gain is checked against [`GuidedSetup::min_gain`]: the third, of 4 samples per
/// pixel, when 7 of the budget's samples per pixel have trained the guide.
pub(crate) const DECIDING_PASS: u32 = 2;

/// What training cost, for the render's report.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GuidingReport {
    /// Training passes rendered.
    pub passes: u32,
    /// Samples per pixel spent on training.
    pub training_spp: u32,
    /// Samples per pixel of the final pass.
    pub final_spp: u32,
    /// Samples per pixel in the image: the final pass's and those of the last training
    /// passes, whose images are weighted by their inverse variance.
    pub image_spp: u32,
    /// Wall-clock seconds of the training passes (part of the render's time).
    pub training_seconds: f64,
    /// Spatial leaves of the tree that guided the final pass (where training stopped, the
    /// last training pass).
    pub leaves: usize,
    /// Where training stopped because the guide promised less than `min_gain`: the
    /// promised gain ([`SdTree::selection_gain`]). The final pass was then path traced
    /// without the guide (BSDF sampling alone).
    pub unguided_final: Option<f64>,
}

/// The pixels for which `spatial_threshold` is meant: Müller et al.'s `c = 12000` is tuned for
/// images of about a megapixel.
const THRESHOLD_PIXELS: f64 = (1u64 << 20) as f64;

/// The factor on `spatial_threshold` for an image of `pixels`: `√(pixels / 2²⁰)`, at most 1.
/// A small image gives few records per pass, and the paper's threshold would leave the
/// tree a few coarse regions (16 leaves on the 128² indirect room against 260 here); the
/// records per pass scale with the pixels, the threshold with their square root, as the
/// paper's `√(2^k)` does with the samples per pixel. Measured on the indirect room (128²)
/// and the Cornell box (256²) at 64 spp: docs/renderer.md.
pub(crate) fn threshold_scale(pixels: u64) -> f64 {
    (pixels as f64 / THRESHOLD_PIXELS).sqrt().min(1.0)
}

/// Memory the guided loop holds beyond the render's film, for a film of `pixels`: the kept
/// training images, the final pass's, and [`combine`]'s means and variances.
pub(crate) fn extra_bytes(pixels: u64) -> u64 {
    let films = Film::bytes_for(pixels, 1).saturating_mul(KEPT_TRAINING_IMAGES as u64 + 1);
    films.saturating_add(pixels.saturating_mul(24 * (KEPT_TRAINING_IMAGES as u64 + 1)))
}

/// One tile's accumulators (the final pass) or records (a training pass), and its rays.
struct TileOut {
    pixels: Vec<(usize, PixelAccum)>,
    records: GuidingRecords,
    rays: u64,
    nonfinite: u64,
}

/// Renders the whole schedule: the film combining the final pass with the last training
/// passes ([`KEPT_TRAINING_IMAGES`], by [`combine`]), the counters (rays of every pass,
/// samples in the image) and what training cost. While the guide has taken no records (the
/// first pass) it is the uniform sphere and is not sampled (α = 0): BSDF sampling alone.
pub(crate) fn render_guided<S: Scene + Sync>(
    scene: &S,
    p: &LoopParams<'_>,
    g: &GuidedSetup,
    bounds: (Vec3, Vec3),
) -> (Film, LoopStats) {
    let start = Instant::now();
    let mut schedule = GuidingSchedule::new(p.samples.len());
    schedule.spatial_c = f64::from(g.spatial_threshold) * threshold_scale(p.window.area());
    schedule.rho = f64::from(g.directional_threshold);
    let mut guide = SdTree::new(bounds.0, bounds.1);
    // Each leaf learns its selection probability, unless the scene never guides (α = 0).
    guide.learn_selection(g.tracer.guide_probability > 0.0);
    let mut training = guide.clone();
    let mut images: Vec<Film> = Vec::new();
    let mut stats = LoopStats::default();
    let mut report = GuidingReport {
        passes: 0,
        training_spp: 0,
        final_spp: 0,
        image_spp: 0,
        training_seconds: 0.0,
        leaves: guide.leaf_count(),
        unguided_final: None,
    };
    let done = AtomicU64::new(0);
    let mut trained_spp = 0u32;
    for mut pass in schedule.passes() {
        if p.cancel.load(Ordering::Relaxed) {
            break;
        }
        if report.unguided_final.is_some() {
            // The rest of the budget, unguided: the final pass after the passes so far.
            pass.is_final = true;
            pass.spp = p.samples.len().saturating_sub(trained_spp);
            guide = SdTree::new(bounds.0, bounds.1);
        }
        let ranges = pass_indices(&pass, p.samples.start, p.samples.end);
        let mut setup = *g;
        if guide.sample_count() == 0 {
            setup.tracer.guide_probability = 0.0;
        }
        let keep = pass.is_final || pass.spp >= 2;
        let mut film = keep.then(|| Film::new(p.width, p.height));
        if pass.is_final {
            report.training_seconds = start.elapsed().as_secs_f64();
            report.final_spp = pass.spp;
            if report.unguided_final.is_none() {
                report.leaves = guide.leaf_count();
            }
        }
        let record = !pass.is_final;
        run_pass(scene, p, &setup, &guide, &ranges, record, &done, |out| {
            stats.rays += out.rays;
            training.merge(&out.records);
            if let Some(film) = film.as_mut() {
                stats.nonfinite += out.nonfinite;
                for (i, a) in &out.pixels {
                    let merged = film.merge(*i, a);
                    debug_assert!(merged.is_ok());
                }
            }
        });
        if let Some(film) = film {
            if !pass.is_final && images.len() == KEPT_TRAINING_IMAGES {
                images.remove(0);
            }
            images.push(film);
        }
        if pass.is_final {
            break;
        }
        report.passes += 1;
        report.training_spp += pass.spp;
        trained_spp += pass.spp;
        if pass.index >= DECIDING_PASS {
            if let Some(gain) = training.selection_gain() {
                if gain < f64::from(g.min_gain) {
                    report.unguided_final = Some(gain);
                    report.leaves = guide.leaf_count();
                    continue;
                }
            }
        }
        let next = schedule.next_tree(&training, &pass);
        guide = std::mem::replace(&mut training, next);
    }
    let film = combine(&images);
    for i in 0..(film.width() as usize * film.height() as usize) {
        stats.samples += u64::from(film.count(i));
    }
    report.image_spp = film.count_range().1;
    stats.guiding = Some(report);
    (film, stats)
}

/// The sample indices of `pass` in a budget of indices `start..end`, as ranges: training
/// pass `k` (of `2^k` samples) draws `start + [2^k, 2^(k+1))`, the final pass `start + 0`
/// and `start + [2^K, end − start)` after `K` training passes. Every index of the budget is
/// drawn once, and every training pass, and the final pass but its first sample, is an
/// aligned power-of-two block of the sampler's sequence, which is a well stratified net for
/// the Sobol samplers (the indices after the previous passes' were not aligned).
pub(crate) fn pass_indices(pass: &GuidingPass, start: u32, end: u32) -> Vec<(u32, u32)> {
    if !pass.is_final {
        let a = start.saturating_add(pass.spp);
        return vec![(a, a.saturating_add(pass.spp).min(end))];
    }
    // The training passes before the final one drew 2^K − 1 = end − start − spp indices.
    let trained = (end - start).saturating_sub(pass.spp);
    if trained == 0 {
        vec![(start, end)]
    } else {
        vec![(start, start + 1), (start + trained + 1, end)]
    }
}

/// Renders the sample indices `ranges` of every pixel guided by `guide`, recording if
/// `record` (`take` is given the tiles' results in tile order).
///
/// The work goes in batches of [`CHUNK`] tiles (per range, in sub-passes of
/// [`pass_size`] samples, as the path tracer's loop); `take` runs on the results of batch
/// `k` while the tiles of batch `k + 1` render (`rayon::join`), so that merging the
/// records into the training tree, which is sequential to stay deterministic, overlaps the
/// rendering. At most two batches' results are held at once.
#[allow(clippy::too_many_arguments)]
fn run_pass<S: Scene + Sync>(
    scene: &S,
    p: &LoopParams<'_>,
    g: &GuidedSetup,
    guide: &SdTree,
    ranges: &[(u32, u32)],
    record: bool,
    done: &AtomicU64,
    mut take: impl FnMut(&TileOut) + Send,
) {
    let all = tiles(p.window);
    let total = p.samples.len() as u64 * p.window.area();
    let mut batches = Vec::new();
    for &(s0, s1) in ranges {
        let step = pass_size(s1 - s0);
        let mut a = s0;
        while a < s1 {
            let b = (a + step).min(s1);
            batches.extend(all.chunks(CHUNK).map(|chunk| (chunk, (a, b))));
            a = b;
        }
    }
    let mut pending: Vec<TileOut> = Vec::new();
    // Record buffers of merged tiles, cleared, for the next tiles (no allocation per tile;
    // which buffer a tile gets does not change its records).
    let pool: Mutex<Vec<GuidingRecords>> = Mutex::new(Vec::new());
    let give_back = |mut out: TileOut| {
        out.records.clear();
        if let Ok(mut pool) = pool.lock() {
            pool.push(out.records);
        }
    };
    for (chunk, (a, b)) in batches {
        if p.cancel.load(Ordering::Relaxed) {
            break;
        }
        let render = || {
            chunk
                .par_iter()
                .map(|&t| {
                    if p.cancel.load(Ordering::Relaxed) {
                        return None;
                    }
                    let buffer = pool.lock().ok().and_then(|mut pool| pool.pop());
                    let buffer = buffer.unwrap_or_default();
                    let r = render_tile(scene, p, g, guide, t, (a, b), record, buffer);
                    let n = ((t.2 - t.0) * (t.3 - t.1) * (b - a)) as u64;
                    let d = done.fetch_add(n, Ordering::Relaxed) + n;
                    (p.progress)(d, total);
                    Some(r)
                })
                .collect::<Vec<Option<TileOut>>>()
        };
        let earlier = std::mem::take(&mut pending);
        let merge = || {
            for out in earlier {
                take(&out);
                give_back(out);
            }
        };
        let (results, ()) = rayon::join(render, merge);
        pending = results.into_iter().flatten().collect();
    }
    pending.iter().for_each(take);
}

/// One tile with the sampler's concrete type, recording into `records` (emptied) if `record`.
#[allow(clippy::too_many_arguments)]
fn render_tile<S: Scene>(
    scene: &S,
    p: &LoopParams<'_>,
    g: &GuidedSetup,
    guide: &SdTree,
    tile: (u32, u32, u32, u32),
    samples: (u32, u32),
    record: bool,
    records: GuidingRecords,
) -> TileOut {
    let t = Tile {
        scene,
        camera: p.camera,
        filter: p.filter,
        width: p.width,
        t_max: p.t_max,
        tracer: &g.tracer,
        guide,
        cancel: p.cancel,
    };
    match p.sampler {
        AnySampler::Independent(s) => t.run(s.clone(), tile, samples, record, records),
        AnySampler::Stratified(s) => t.run(s.clone(), tile, samples, record, records),
        AnySampler::Sobol(s) => t.run(s.clone(), tile, samples, record, records),
        AnySampler::Halton(s) => t.run(s.clone(), tile, samples, record, records),
        AnySampler::R2(s) => t.run(s.clone(), tile, samples, record, records),
        AnySampler::Cmj(s) => t.run(s.clone(), tile, samples, record, records),
        AnySampler::Sobol4d(s) => t.run(s.clone(), tile, samples, record, records),
    }
}

/// What rendering a tile reads.
struct Tile<'a, S> {
    scene: &'a S,
    camera: &'a Camera,
    filter: &'a crate::film::PixelFilter,
    width: u32,
    t_max: f32,
    tracer: &'a GuidedPathTracer,
    guide: &'a SdTree,
    cancel: &'a std::sync::atomic::AtomicBool,
}

impl<S: Scene> Tile<'_, S> {
    /// The pixel samples `s0..s1` of every pixel of the tile, as the path tracer's loop
    /// draws them (film position, lens, then the path), recording into the tile's buffer if
    /// `record`. A sample running when the render is cancelled is discarded.
    fn run<R: Sampler>(
        &self,
        mut rng: R,
        (x0, y0, x1, y1): (u32, u32, u32, u32),
        (s0, s1): (u32, u32),
        record: bool,
        records: GuidingRecords,
    ) -> TileOut {
        // A pass that neither records nor has a trained guide (the final pass after training
        // stopped, or a budget of one sample) is plain path tracing: the path tracer's own
        // loop, without the guided tracer's lookups of an empty guide.
        let g = self.tracer;
        let plain = (!record && self.guide.sample_count() == 0).then_some(PathTracer {
            max_depth: g.max_depth,
            rr_depth: g.rr_depth,
            strategy: g.strategy,
            hide_emitters: g.hide_emitters,
        });
        let mut out = TileOut {
            pixels: Vec::with_capacity(((x1 - x0) * (y1 - y0)) as usize),
            records,
            rays: 0,
            nonfinite: 0,
        };
        for y in y0..y1 {
            for x in x0..x1 {
                let mut acc = PixelAccum::default();
                for s in s0..s1 {
                    if self.cancel.load(Ordering::Relaxed) {
                        break;
                    }
                    rng.start_pixel_sample([x, y], s);
                    let off = self.filter.sample(rng.next_2d());
                    let film = Vec2::new(x as f32 + 0.5, y as f32 + 0.5) + off;
                    let (ray, t_max) = if self.camera.has_lens() {
                        self.camera.generate_ray_through_lens(film, rng.next_2d())
                    } else {
                        self.camera.generate_ray_with_tmax(film)
                    };
                    let records = record.then_some(&mut out.records);
                    let t_max = t_max.min(self.t_max);
                    let r = match &plain {
                        Some(pt) => pt.li(self.scene, ray.origin, ray.dir, t_max, &mut rng),
                        None => g.li(
                            self.scene, self.guide, ray.origin, ray.dir, t_max, &mut rng, records,
                        ),
                    };
                    if self.cancel.load(Ordering::Relaxed) {
                        break;
                    }
                    out.rays += r.rays as u64;
                    if r.radiance.is_finite() {
                        acc.add(r.radiance);
                    } else {
                        out.nonfinite += 1;
                        acc.add(Vec3::ZERO);
                    }
                }
                out.pixels.push(((y * self.width + x) as usize, acc));
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every index of a budget is drawn by exactly one pass, and each training pass (and the
    /// final pass after its first index) is an aligned power-of-two block.
    #[test]
    fn pass_indices_cover_the_budget_once_in_aligned_blocks() {
        for (start, total) in [(0u32, 1u32), (0, 2), (0, 16), (0, 64), (0, 100), (5, 256)] {
            let end = start + total;
            let mut drawn = vec![0u32; total as usize];
            for pass in GuidingSchedule::new(total).passes() {
                let ranges = pass_indices(&pass, start, end);
                let n: u32 = ranges.iter().map(|(a, b)| b - a).sum();
                assert_eq!(n, pass.spp, "budget {total}, pass {pass:?}");
                for &(a, b) in &ranges {
                    (a..b).for_each(|i| drawn[(i - start) as usize] += 1);
                }
                let (a, _) = *ranges.last().unwrap();
                if !pass.is_final {
                    assert!(
                        pass.spp.is_power_of_two() && (a - start) == pass.spp,
                        "{ranges:?}"
                    );
                } else if ranges.len() == 2 {
                    assert!((a - start).is_power_of_two(), "{ranges:?}");
                }
            }
            assert!(drawn.iter().all(|&c| c == 1), "budget {total}: {drawn:?}");
        }
    }
}
