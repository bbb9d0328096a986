//! Path tracing guided by an SD-tree: one-sample MIS between BSDF sampling and the learned
//! distribution of incident radiance.

use super::path::{depth_limit, hit_weight, nee, PrevVertex};
use super::{is_positive, Bsdf, PathResult, PathTracer, SampleSource, Scene, Strategy};
use crate::sampling::guiding::{
    sphere_to_square, DQuadTree, GuidingRecord, GuidingRecords, PathVertex, SdTree,
    SelectionRecord, StoredRecord, SQUARE_TO_SPHERE_JACOBIAN,
};
use crate::sampling::{Frame, ONE_MINUS_EPSILON};
use glam::{Vec2, Vec3};

/// The largest selection probability of the guide, so that BSDF sampling (the only way to
/// a Dirac lobe) keeps a positive probability.
const MAX_GUIDE_PROBABILITY: f32 = 0.999;

/// A path tracer guided by an [`SdTree`] (Müller, Gross & Novák 2017, "Practical Path
/// Guiding for Efficient Light-Transport Simulation", CGF 36(4)).
///
/// As [`PathTracer`] (next-event estimation combined with the sampled directions by
/// [`Strategy`], Russian roulette from `rr_depth`), except that at a vertex whose BSDF has a
/// non-delta part the direction comes from the guide, the tree's distribution at the vertex,
/// with probability `α` (the leaf's learned [`DQuadTree::selection_probability`] if the tree
/// learns one, [`SdTree::learn_selection`], else `guide_probability`), and from the BSDF
/// otherwise. A non-delta
/// direction then has the one-sample mixture density `α·p_guide + (1 − α)·p_bsdf`, which
/// both the path weight and the MIS weights against light sampling use; a Dirac lobe (only
/// the BSDF samples it) has probability `(1 − α)` times the BSDF's; a BSDF without a
/// non-delta part is never guided. The mixture density is positive wherever the BSDF's is,
/// so the estimator is unbiased whatever the tree: training changes only the variance.
///
/// A direction sampled from the guide has an unknown relative index of refraction; Russian
/// roulette counts it as 1 (any continuation probability is unbiased).
///
/// ```
/// use mcrt::glam::Vec3;
/// use mcrt::integrator::GuidedPathTracer;
/// use mcrt::sampling::guiding::SdTree;
///
/// let gpt = GuidedPathTracer::default();
/// assert_eq!(gpt.guide_probability, 0.5);
/// let guide = SdTree::new(Vec3::splat(-1.0), Vec3::ONE); // untrained: the uniform sphere
/// # let _ = guide;
/// // gpt.li(&scene, &guide, origin, dir, f32::INFINITY, &mut sampler, Some(&mut records))
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GuidedPathTracer {
    /// Longest path in segments, as [`PathTracer::max_depth`].
    pub max_depth: i32,
    /// Depth from which Russian roulette applies, as [`PathTracer::rr_depth`].
    pub rr_depth: u32,
    /// Sampling strategy of next-event estimation against the sampled directions.
    pub strategy: Strategy,
    /// The probability α of sampling the guide rather than the BSDF (the paper's 0.5) where
    /// the guide has not learned one; clamped into `[0, 0.999]`, NaN meaning 0.
    pub guide_probability: f32,
    /// Hide emitters seen directly, as [`PathTracer::hide_emitters`] does (Mitsuba 3's
    /// `hide_emitters`): the camera ray passes through emitter surfaces and sees black where
    /// it then leaves the scene.
    pub hide_emitters: bool,
}

impl Default for GuidedPathTracer {
    fn default() -> Self {
        Self::from_path_tracer(&PathTracer::default())
    }
}

/// One direction sampled by [`GuidedPathTracer::sample_direction`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GuidedSample {
    /// The direction, world space.
    pub wi: Vec3,
    /// `f·|cos θ_i| / pdf` per RGB channel (0 where the BSDF is 0, such as a guided
    /// direction below a reflecting surface).
    pub weight: Vec3,
    /// The mixture density `α·p_guide + (1 − α)·p_bsdf` per steradian; for a Dirac lobe,
    /// `(1 − α)` times the BSDF's choice probability.
    pub pdf: f32,
    /// A Dirac lobe of the BSDF was sampled.
    pub delta: bool,
    /// The relative index of refraction crossed (1 for a direction from the guide).
    pub eta: f32,
}

/// The one-sample mixture density.
#[inline(always)]
fn mixture(alpha: f32, p_guide: f32, p_bsdf: f32) -> f32 {
    alpha * p_guide + (1.0 - alpha) * p_bsdf
}

impl GuidedPathTracer {
    /// The guided counterpart of `pt` (same depth, Russian roulette and strategy), α = 0.5.
    pub fn from_path_tracer(pt: &PathTracer) -> Self {
        Self {
            max_depth: pt.max_depth,
            rr_depth: pt.rr_depth,
            strategy: pt.strategy,
            guide_probability: 0.5,
            hide_emitters: pt.hide_emitters,
        }
    }

    /// The selection probability of the guide actually used.
    #[inline]
    pub fn alpha(&self) -> f32 {
        if self.guide_probability > 0.0 {
            self.guide_probability.min(MAX_GUIDE_PROBABILITY)
        } else {
            0.0
        }
    }

    /// The selection probability of the guide at a vertex whose BSDF has `flags`, guided by
    /// `guide`: 0 unless the BSDF has a non-delta part; the guide's learned probability
    /// ([`DQuadTree::selection_probability`]) if it has one, else [`Self::alpha`].
    #[inline]
    fn alpha_for(&self, flags: super::BsdfFlags, guide: &DQuadTree) -> f32 {
        if flags.smooth {
            guide
                .selection_probability()
                .map_or_else(|| self.alpha(), |a| a.min(MAX_GUIDE_PROBABILITY))
        } else {
            0.0
        }
    }

    /// Samples the direction that continues a path at a vertex with BSDF `bsdf`, shading
    /// frame `frame` and local outgoing direction `wo`, from the guide `guide` (the tree's
    /// distribution at the vertex) with probability α, else from the BSDF: one 2D value
    /// from `samples` makes the choice with its first coordinate and, rescaled to the
    /// chosen part, samples the guide or the BSDF (a BSDF with components draws its
    /// component choice after it). `None` when the
    /// BSDF gives no sample or the density is not positive and finite.
    pub fn sample_direction<B: Bsdf, R: SampleSource>(
        &self,
        bsdf: &B,
        frame: &Frame,
        wo: Vec3,
        guide: &DQuadTree,
        samples: &mut R,
    ) -> Option<GuidedSample> {
        let alpha = self.alpha_for(bsdf.flags(), guide);
        self.sample_with_densities(alpha, bsdf, frame, wo, guide, samples, false)
            .map(|(s, _, _)| s)
    }

    /// [`GuidedPathTracer::sample_direction`] with the selection probability `alpha`, and
    /// for a non-delta direction the guide's and the BSDF's densities of it (the guide's
    /// also where `alpha` is 0 if `guide_density`, else 0 there), which the learning of the
    /// selection probability records; and the direction's point of the square
    /// ([`sphere_to_square`](crate::sampling::guiding::sphere_to_square)) where its guide
    /// density was read (zero where it was not), which recording it reuses.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn sample_with_densities<B: Bsdf, R: SampleSource>(
        &self,
        alpha: f32,
        bsdf: &B,
        frame: &Frame,
        wo: Vec3,
        guide: &DQuadTree,
        samples: &mut R,
        guide_density: bool,
    ) -> Option<(GuidedSample, [f32; 2], Vec2)> {
        // One 2D value both chooses (its first coordinate against α) and, rescaled to the
        // chosen part, samples: a dimension fewer per vertex than a separate choice (the
        // rescaled value is uniform on the chosen part, independent of the choice).
        let u = samples.next_2d();
        if u.x < alpha {
            let v = Vec2::new((u.x / alpha).min(ONE_MINUS_EPSILON), u.y);
            let (wi, p_guide, square) = guide.sample_on_square(v);
            let (f, p_bsdf) = bsdf.eval_pdf(wo, frame.to_local(wi));
            let pdf = mixture(alpha, p_guide, p_bsdf);
            let s = GuidedSample {
                wi,
                weight: f / pdf,
                pdf,
                delta: false,
                eta: 1.0,
            };
            return (is_positive(pdf) && pdf.is_finite()).then_some((s, [p_guide, p_bsdf], square));
        }
        let v = Vec2::new(((u.x - alpha) / (1.0 - alpha)).min(ONE_MINUS_EPSILON), u.y);
        let bs = bsdf.sample(wo, super::component_value(bsdf, samples), v)?;
        let wi = frame.to_world(bs.wi);
        let mut densities = [0.0, bs.pdf];
        let mut square = Vec2::ZERO;
        let (weight, pdf) = if bs.delta {
            (bs.weight / (1.0 - alpha), bs.pdf * (1.0 - alpha))
        } else {
            if alpha > 0.0 || guide_density {
                square = sphere_to_square(wi);
                densities[0] = guide.pdf_square(square) / SQUARE_TO_SPHERE_JACOBIAN;
            }
            let pdf = mixture(alpha, densities[0], bs.pdf);
            (bs.weight * (bs.pdf / pdf), pdf)
        };
        let s = GuidedSample {
            wi,
            weight,
            pdf,
            delta: bs.delta,
            eta: bs.eta,
        };
        (is_positive(pdf) && pdf.is_finite()).then_some((s, densities, square))
    }

    /// The density with which [`GuidedPathTracer::sample_direction`] returns the world
    /// direction `wi` (its non-delta part): `α·guide.pdf(wi) + (1 − α)·bsdf.pdf(wo, wi)`.
    pub fn pdf<B: Bsdf>(
        &self,
        bsdf: &B,
        frame: &Frame,
        wo: Vec3,
        guide: &DQuadTree,
        wi: Vec3,
    ) -> f32 {
        let alpha = self.alpha_for(bsdf.flags(), guide);
        let p_guide = if alpha > 0.0 { guide.pdf(wi) } else { 0.0 };
        mixture(alpha, p_guide, bsdf.pdf(wo, frame.to_local(wi)))
    }

    /// Estimates the radiance arriving at the camera along the unit direction `dir` from
    /// `origin` (hits beyond `t_max` are ignored), guided by `guide`. With `records`, appends
    /// one [`GuidingRecord`] per non-delta vertex that continued the path: the radiance the
    /// rest of the path brought along the sampled direction (the mean of its RGB channels),
    /// with the density it was sampled with, for the tree of the next training pass.
    #[allow(clippy::too_many_arguments)]
    pub fn li<S: Scene, R: SampleSource>(
        &self,
        scene: &S,
        guide: &SdTree,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        samples: &mut R,
        mut records: Option<&mut GuidingRecords>,
    ) -> PathResult {
        let max_depth = depth_limit(self.max_depth);
        let mut out = PathResult::default();
        if max_depth == 0 {
            return out;
        }
        if let Some(r) = records.as_deref_mut() {
            r.scratch.clear();
        }
        let mut throughput = Vec3::ONE;
        let mut eta = 1.0f32;
        let mut ray_dir = dir;
        let mut prev: Option<PrevVertex> = None;
        let mut hit =
            super::camera_hit(scene, origin, dir, t_max, self.hide_emitters, &mut out.rays);
        if self.hide_emitters && hit.is_none() {
            return out;
        }
        let mut depth = 0u32;
        loop {
            let Some(sp) = hit else {
                if scene.has_environment() {
                    let le = scene.environment(ray_dir);
                    let w = hit_weight(self.strategy, &prev, |from| {
                        scene.environment_pdf(from, ray_dir)
                    });
                    add(&mut out.radiance, &mut records, throughput * le * w);
                }
                break;
            };
            let wo_world = -ray_dir;
            if scene.is_emitter(&sp) {
                let le = scene.emitted(&sp, wo_world);
                if le != Vec3::ZERO {
                    let w = hit_weight(self.strategy, &prev, |from| scene.light_pdf(from, &sp));
                    add(&mut out.radiance, &mut records, throughput * le * w);
                }
            }
            if depth + 1 >= max_depth {
                break;
            }
            let bsdf = &scene.bsdf(&sp);
            let wo = sp.frame.to_local(wo_world);
            let flags = bsdf.flags();
            let dist = guide.distribution(sp.p);
            let alpha = self.alpha_for(flags, dist);
            let u_light = samples.next_2d();
            let u_pick = if scene.samples_light_choice() {
                samples.next_2d()
            } else {
                Vec2::splat(0.5)
            };
            if flags.smooth && (self.strategy.samples_lights() || scene.has_delta_lights()) {
                if let Some(ls) = scene.sample_light(&sp, u_pick, u_light) {
                    let pg = if alpha > 0.0 { dist.pdf(ls.wi) } else { 0.0 };
                    let mix = |pb: f32| mixture(alpha, pg, pb);
                    let c = nee(self.strategy, scene, bsdf, &sp, wo, &ls, &mut out.rays, mix);
                    add(&mut out.radiance, &mut records, throughput * c);
                }
            }
            let recording = records.is_some();
            let Some((step, [p_guide, p_bsdf], square)) =
                self.sample_with_densities(alpha, bsdf, &sp.frame, wo, dist, samples, recording)
            else {
                break;
            };
            // What the direction's radiance is multiplied by on its way to the pixel, before
            // the division by its density: the selection records weigh each vertex by it.
            let path_f_cos = throughput * step.weight * step.pdf;
            throughput *= step.weight;
            eta *= step.eta;
            depth += 1;
            let t_max_c = throughput.max_element();
            if !(is_positive(t_max_c) && t_max_c.is_finite()) {
                break;
            }
            if depth >= self.rr_depth {
                let q = (t_max_c * eta * eta).min(0.95);
                if samples.next_1d() >= q {
                    break;
                }
                throughput /= q;
            }
            if let (Some(r), false) = (records.as_deref_mut(), step.delta) {
                r.scratch.push(PathVertex {
                    p: sp.p,
                    dir: step.wi,
                    pdf: step.pdf,
                    square,
                    path_f_cos,
                    p_guide,
                    p_bsdf,
                    inv_throughput: Vec3::select(
                        throughput.cmpgt(Vec3::ZERO),
                        throughput.recip(),
                        Vec3::ZERO,
                    ),
                    radiance: Vec3::ZERO,
                });
            }
            ray_dir = step.wi;
            hit = scene.trace(&sp, ray_dir);
            out.rays += 1;
            prev = Some(PrevVertex {
                sp,
                pdf: step.pdf,
                delta: step.delta,
            });
        }
        if let Some(r) = records {
            let n = r.scratch.len();
            for i in 0..n {
                let v = r.scratch[i];
                r.push_stored(StoredRecord {
                    record: GuidingRecord {
                        p: v.p,
                        dir: v.dir,
                        radiance: v.radiance.element_sum() / 3.0,
                        pdf: v.pdf,
                    },
                    square: v.square,
                    selection: Some(SelectionRecord {
                        integrand: (v.path_f_cos * v.radiance).element_sum() / 3.0,
                        p_guide: v.p_guide,
                        p_bsdf: v.p_bsdf,
                    }),
                });
            }
            r.scratch.clear();
        }
        out
    }
}

/// Adds the contribution `c` to the path's radiance and, divided by each vertex's
/// throughput, to the radiance arriving at every recorded vertex before it.
#[inline]
fn add(radiance: &mut Vec3, records: &mut Option<&mut GuidingRecords>, c: Vec3) {
    *radiance += c;
    if let Some(r) = records.as_deref_mut() {
        for v in &mut r.scratch {
            v.radiance += c * v.inv_throughput;
        }
    }
}

#[cfg(test)]
mod tests;
