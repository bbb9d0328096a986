//! A diagnostic of a [`BidirectionalScene`]'s densities as the bidirectional estimator's
//! multiple-importance weights see them: [`Bdpt::check_mis_weights`].
//!
//! For random full paths, made by connecting random camera and light subpaths of the
//! scene, the weights of every strategy that can make the path, each recomputed from
//! scratch from the path's vertices, must sum to 1; and the weight the estimator computed
//! from its own subpaths (forward densities from the sampling routines, reverse densities
//! from the `pdf` methods) must equal the one recomputed from the `pdf` methods alone. A
//! sampling routine whose returned density disagrees with the matching `pdf` method
//! (`Bsdf::sample` with `Bsdf::pdf`, `sample_emission` with `emission_pdf`, camera rays
//! with `camera_pdf_from_lens`) makes the two differ.

use super::connect::{connect, mis_weight, Heuristic};
use super::vertex::{Kind, Vertex};
use super::walk::{camera_subpath, light_subpath, WalkLimits};
use super::Bdpt;
use crate::integrator::{BidirectionalScene, EmitterKind, Strategy};
use crate::sampling::sampler::SampleSource;
use glam::Vec2;
use rand_core::{RngCore, SeedableRng};
use rand_pcg::Pcg32;
use std::collections::BTreeMap;
use std::fmt;

/// Failure messages an outcome keeps (the count covers all of them).
const KEPT_FAILURES: usize = 10;

/// Settings of [`Bdpt::check_mis_weights`]. The defaults are those of the renderer's own
/// check (`mcrt-render/tests/it/bdpt_weights.rs`), for scenes of about unit size.
///
/// ```
/// use mcrt::integrator::MisWeightCheck;
///
/// let check = MisWeightCheck { paths: 100, seed: 3, ..MisWeightCheck::default() };
/// assert_eq!(check.max_vertices, 7);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MisWeightCheck {
    /// Camera subpaths drawn, each with one light subpath; every pair is joined by every
    /// strategy that can join them.
    pub paths: usize,
    /// Seed of the random numbers (the check is deterministic).
    pub seed: u64,
    /// Most vertices of each subpath (endpoint included). The walks play no Russian
    /// roulette: they end here, when a BSDF sample fails or a ray escapes.
    pub max_vertices: usize,
    /// Largest `|Σ weights − 1|` accepted.
    pub sum_tolerance: f32,
    /// Largest `|estimator's weight − recomputed weight|` accepted, in absolute terms,
    /// plus [`MisWeightCheck::weight_relative_tolerance`] times the recomputed weight.
    pub weight_tolerance: f32,
    /// The part of the weight tolerance relative to the recomputed weight.
    pub weight_relative_tolerance: f32,
    /// Paths with a segment shorter than this (in scene units) are left out of the
    /// comparison with the estimator's weight, though not out of the sum: the estimator's
    /// densities use the directions it sampled, the recomputed ones the directions between
    /// the vertices, and where two vertices nearly touch (a corner) the scene's ray offset
    /// makes the two differ.
    pub min_segment: f32,
}

impl Default for MisWeightCheck {
    fn default() -> Self {
        Self {
            paths: 400,
            seed: 17,
            max_vertices: 7,
            sum_tolerance: 2e-3,
            weight_tolerance: 1e-3,
            weight_relative_tolerance: 1e-2,
            min_segment: 0.05,
        }
    }
}

/// What [`Bdpt::check_mis_weights`] found for one strategy `(s, t)`: `s` light-subpath and
/// `t` camera-subpath vertices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MisWeightStrategy {
    /// Light-subpath vertices of the strategy.
    pub s: usize,
    /// Camera-subpath vertices of the strategy.
    pub t: usize,
    /// Paths this strategy made whose weights over all strategies were summed.
    pub summed: usize,
    /// Those whose estimator weight was also compared with the recomputed one.
    pub compared: usize,
    /// Worst `|Σ weights − 1|` over the summed paths; NaN or infinite if any sum was.
    pub worst_sum_error: f32,
    /// Worst `|estimator's weight − recomputed weight|` over the compared paths; NaN or
    /// infinite if any weight was, infinite if the recomputation found no weight for the
    /// strategy.
    pub worst_weight_error: f32,
    /// Paths of this strategy that failed either test.
    pub failures: usize,
}

/// The outcome of [`Bdpt::check_mis_weights`]: counts, the worst errors of each strategy
/// and the first failures. It passes when at least one path was compared and no path
/// failed.
#[derive(Debug, Clone, PartialEq)]
pub struct MisWeightOutcome {
    /// The settings the check ran with.
    pub settings: MisWeightCheck,
    /// Connections whose weights over all strategies were summed.
    pub summed: usize,
    /// Connections whose estimator weight was also compared with the recomputed one.
    pub compared: usize,
    /// Connections that failed either test.
    pub failures: usize,
    /// Each strategy that made a path, by `s + t` then `s`.
    pub strategies: Vec<MisWeightStrategy>,
    /// The first failures, described (at most ten).
    pub failure_messages: Vec<String>,
}

impl MisWeightOutcome {
    /// Whether the scene passed: some path was compared and every sum and weight was
    /// finite and within the tolerances.
    pub fn passed(&self) -> bool {
        self.failures == 0 && self.compared > 0
    }

    /// Worst `|Σ weights − 1|` over all strategies (NaN if any sum was).
    pub fn worst_sum_error(&self) -> f32 {
        self.strategies
            .iter()
            .fold(0.0, |w, s| worse(w, s.worst_sum_error))
    }

    /// Worst `|estimator's weight − recomputed weight|` over all strategies (NaN if any
    /// weight was).
    pub fn worst_weight_error(&self) -> f32 {
        self.strategies
            .iter()
            .fold(0.0, |w, s| worse(w, s.worst_weight_error))
    }

    /// A readable account: the verdict, a table of the strategies and the first failures.
    pub fn report(&self) -> String {
        let c = &self.settings;
        let mut out = format!(
            "MIS weight check {}: {} paths (seed {}, up to {} vertices per subpath), {} \
             connections summed, {} compared, {} failed\n\
             tolerances: |sum - 1| < {:e}; |w_estimator - w| <= {:e} + {:e} w\n",
            if self.passed() { "passed" } else { "FAILED" },
            c.paths,
            c.seed,
            c.max_vertices,
            self.summed,
            self.compared,
            self.failures,
            c.sum_tolerance,
            c.weight_tolerance,
            c.weight_relative_tolerance,
        );
        if self.compared == 0 {
            out.push_str("no connection was compared: the check proves nothing\n");
        }
        out.push_str("    s    t   summed compared  worst|sum-1|   worst|dw|  failures\n");
        for s in &self.strategies {
            out.push_str(&format!(
                "{:>5} {:>4} {:>8} {:>8} {:>13.3e} {:>11.3e} {:>9}\n",
                s.s, s.t, s.summed, s.compared, s.worst_sum_error, s.worst_weight_error, s.failures
            ));
        }
        for m in &self.failure_messages {
            out.push_str(m);
            out.push('\n');
        }
        if self.failures > self.failure_messages.len() {
            out.push_str(&format!(
                "... and {} more failures\n",
                self.failures - self.failure_messages.len()
            ));
        }
        out
    }

    /// Panics with [`MisWeightOutcome::report`] unless the check passed.
    #[track_caller]
    pub fn assert_passed(&self) -> &Self {
        assert!(self.passed(), "{}", self.report());
        self
    }
}

impl fmt::Display for MisWeightOutcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.report())
    }
}

/// The larger error, NaN winning over everything.
fn worse(a: f32, b: f32) -> f32 {
    if a.is_nan() || b.is_nan() {
        f32::NAN
    } else {
        a.max(b)
    }
}

/// Uniform values in `[0, 1)` from a PCG32 stream.
struct Rng(Pcg32);

impl SampleSource for Rng {
    fn next_1d(&mut self) -> f32 {
        (self.0.next_u32() >> 8) as f32 / 16_777_216.0
    }
}

impl Bdpt {
    /// Checks the multiple-importance weights of this estimator on `scene`, a diagnostic
    /// of the scene's densities (its [`BidirectionalScene`] and [`Bsdf`](crate::integrator::Bsdf)
    /// methods): the densities the weights divide by must agree with what the sampling
    /// routines return, or the weights no longer sum to 1 and the image is silently biased.
    ///
    /// For `check.paths` camera rays through random film positions (and lens points), it
    /// walks a camera subpath and a light subpath, joins them by every strategy `(s, t)`
    /// with `t ≥ 2` and `s ≠ 1` (the strategies whose endpoints both lie on the
    /// subpaths; `s = 1` and `t = 1` sample a fresh endpoint) that makes a path, and for
    /// each such path
    ///
    /// - recomputes from scratch, from the path's vertices alone, the weight of every
    ///   strategy that can make it (`s = 1` and `t = 1` included) and checks that they
    ///   sum to 1 within `check.sum_tolerance`;
    /// - checks that the weight the estimator computed from its own subpaths equals the
    ///   recomputed weight of its strategy within `check.weight_tolerance +
    ///   check.weight_relative_tolerance · w` (unless a segment is shorter than
    ///   `check.min_segment`).
    ///
    /// Every value is tested with `is_finite` before any tolerance: a NaN fails. The
    /// weights are the balance heuristic's for [`Strategy::MisBalance`] and the power
    /// heuristic's otherwise (the unit weights of one strategy alone need no check);
    /// `max_depth` and `rr_depth` do not enter (the walks end at `check.max_vertices`).
    ///
    /// ```
    /// use mcrt::integrator::{Bdpt, BidirectionalScene, MisWeightCheck};
    ///
    /// /// A renderer's test of its own scene's densities.
    /// fn check_scene<S: BidirectionalScene>(scene: &S) {
    ///     let check = MisWeightCheck { paths: 400, seed: 1, ..MisWeightCheck::default() };
    ///     let outcome = Bdpt::default().check_mis_weights(scene, &check);
    ///     outcome.assert_passed();
    ///     println!("{outcome}");
    /// }
    /// ```
    pub fn check_mis_weights<S: BidirectionalScene>(
        &self,
        scene: &S,
        check: &MisWeightCheck,
    ) -> MisWeightOutcome {
        let h = match self.strategy {
            Strategy::MisBalance => Heuristic::Balance,
            _ => Heuristic::Power,
        };
        let lim = WalkLimits {
            max_vertices: check.max_vertices,
            rr_depth: u32::MAX,
        };
        let (width, height) = scene.film_size();
        let film = Vec2::new(width as f32, height as f32);
        let mut rng = Rng(Pcg32::seed_from_u64(check.seed));
        let (mut cam, mut light) = (Vec::new(), Vec::new());
        let mut rays = 0u32;
        let mut per: BTreeMap<(usize, usize), MisWeightStrategy> = BTreeMap::new();
        let mut out = MisWeightOutcome {
            settings: *check,
            summed: 0,
            compared: 0,
            failures: 0,
            strategies: Vec::new(),
            failure_messages: Vec::new(),
        };
        let min_d2 = check.min_segment * check.min_segment;
        for _ in 0..check.paths {
            let raster = rng.next_2d() * film;
            let (origin, dir, t_max) = scene.camera_ray_through_lens(raster, rng.next_2d());
            camera_subpath(
                scene, origin, dir, t_max, lim, &mut rng, &mut cam, &mut rays,
            );
            light_subpath(scene, lim, &mut rng, &mut light, &mut rays);
            for t in 2..=cam.len() {
                for s in (0..=light.len()).filter(|&s| s != 1 && s + t >= 3) {
                    let Some(c) = connect(scene, &light, &cam, s, t, h, &mut rng, &mut rays) else {
                        continue;
                    };
                    let st = per.entry((s, t)).or_insert(MisWeightStrategy {
                        s,
                        t,
                        summed: 0,
                        compared: 0,
                        worst_sum_error: 0.0,
                        worst_weight_error: 0.0,
                        failures: 0,
                    });
                    let p = full_path(&light, &cam, s, t);
                    let weights: Vec<(usize, f32)> = (0..p.len())
                        .filter_map(|k| resplit(scene, &p, k, h).map(|w| (k, w)))
                        .collect();
                    let sum: f32 = weights.iter().map(|x| x.1).sum();
                    let sum_error = (sum - 1.0).abs();
                    out.summed += 1;
                    st.summed += 1;
                    st.worst_sum_error = worse(st.worst_sum_error, sum_error);
                    let mut failure = None;
                    if !(sum.is_finite() && sum_error < check.sum_tolerance) {
                        failure = Some(format!(
                            "(s, t) = ({s}, {t}): weights {weights:?} sum to {sum}"
                        ));
                    }
                    let short = p.windows(2).any(|w| {
                        let (_, d2) = w[0].dir_to(&w[1]);
                        d2.is_finite() && d2 < min_d2
                    });
                    if !short {
                        let own = weights.iter().find(|x| x.0 == s).map(|x| x.1);
                        let error = own.map_or(f32::INFINITY, |w| (w - c.weight).abs());
                        out.compared += 1;
                        st.compared += 1;
                        st.worst_weight_error = worse(st.worst_weight_error, error);
                        let ok = c.weight.is_finite()
                            && own.is_some_and(|w| {
                                w.is_finite()
                                    && (w - c.weight).abs()
                                        <= check.weight_tolerance
                                            + check.weight_relative_tolerance * w
                            });
                        if !ok && failure.is_none() {
                            failure = Some(format!(
                                "(s, t) = ({s}, {t}): estimator's weight {} against recomputed \
                                 {own:?} (all strategies: {weights:?})",
                                c.weight
                            ));
                        }
                    }
                    if let Some(f) = failure {
                        out.failures += 1;
                        st.failures += 1;
                        if out.failure_messages.len() < KEPT_FAILURES {
                            out.failure_messages.push(f);
                        }
                    }
                }
            }
        }
        out.strategies = per.into_values().collect();
        out.strategies.sort_by_key(|x| (x.s + x.t, x.s));
        out
    }
}

/// The full path `light[..s] + camera[..t]` reversed, light end first. The connection's
/// endpoints scatter along the connection, not by the Dirac part their own walk may have
/// gone on by: in this path they are not delta.
fn full_path(light: &[Vertex], camera: &[Vertex], s: usize, t: usize) -> Vec<Vertex> {
    let mut p: Vec<Vertex> = light[..s].to_vec();
    p.extend(camera[..t].iter().rev());
    if s > 0 {
        p[s - 1] = p[s - 1].as_endpoint();
    }
    p[s] = p[s].as_endpoint();
    p
}

/// Strategy `s` of the full path `p` with every density recomputed from scratch: the
/// light subpath `p[..s]` and the camera subpath `p[s..]` reversed; `None` when that
/// strategy cannot make the path.
fn resplit<S: BidirectionalScene>(scene: &S, p: &[Vertex], s: usize, h: Heuristic) -> Option<f32> {
    let n = p.len();
    let t = n - s;
    if t == 0 || (s, t) == (1, 1) {
        return None;
    }
    if s == 0 && (!p[0].is_light() || p[0].is_delta_light()) {
        return None;
    }
    if s > 0 && t > 0 {
        let (a, b) = (&p[s - 1], &p[s]);
        let ok = |v: &Vertex| v.connectible() && !v.delta;
        if !(ok(a) || (s == 1)) || !ok(b) {
            return None;
        }
    }
    let mut q: Vec<Vertex> = p.to_vec();
    // As a light endpoint, an emitting surface is an area light.
    if q[0].kind == Kind::Surface {
        q[0].kind = Kind::Light(EmitterKind::Area);
    }
    // Densities from the light side (pdf_fwd of light vertices); a direction a vertex
    // scattered into by a Dirac part has no density (the estimators store 0, whatever
    // density the BSDF's other parts give that direction).
    let from_light: Vec<f32> = (0..n)
        .map(|i| match i {
            0 => q[0].pdf_light_origin(scene, &q[1]),
            1 => q[0].pdf_light(scene, &q[1]),
            _ if q[i - 1].delta => 0.0,
            _ => q[i - 1].pdf(scene, Some(&q[i - 2]), &q[i]),
        })
        .collect();
    // Densities from the camera side.
    let from_camera: Vec<f32> = (0..n)
        .map(|i| {
            if i == n - 1 {
                1.0
            } else if i == n - 2 {
                q[n - 1].pdf(scene, None, &q[n - 2])
            } else if q[i + 1].delta {
                0.0
            } else {
                q[i + 1].pdf(scene, Some(&q[i + 2]), &q[i])
            }
        })
        .collect();
    // Each vertex's direction to its predecessor in its new subpath.
    let toward = |i: usize, j: usize| q[i].dir_to(&q[j]);
    let mut light: Vec<Vertex> = q[..s].to_vec();
    for (i, v) in light.iter_mut().enumerate() {
        v.pdf_fwd = from_light[i];
        v.pdf_rev = from_camera[i];
        if i > 0 {
            (v.w_prev, v.d2_prev) = toward(i, i - 1);
        }
    }
    let mut camera: Vec<Vertex> = q[s..].iter().rev().copied().collect();
    for (j, v) in camera.iter_mut().enumerate() {
        let i = n - 1 - j;
        v.pdf_fwd = from_camera[i];
        v.pdf_rev = from_light[i];
        if i + 1 < n {
            (v.w_prev, v.d2_prev) = toward(i, i + 1);
        }
        if i == s && s == 0 {
            // The emitter the camera path ends on is a surface vertex of that subpath.
            v.kind = p[0].kind;
        }
    }
    let sampled = match (s, t) {
        (1, _) => Some(light[0]),
        (_, 1) => Some(camera[0]),
        _ => None,
    };
    Some(mis_weight(
        scene,
        &light,
        &camera,
        sampled.as_ref(),
        s,
        t,
        h,
    ))
}

#[cfg(test)]
mod tests;
