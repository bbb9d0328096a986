//! Unidirectional path tracing with next-event estimation, multiple importance sampling and
//! Russian roulette.

use super::{is_positive, occluded, Bsdf, SampleSource, Scene, Strategy, SurfacePoint};
use glam::{Vec2, Vec3};

/// A path tracer with Mitsuba 3's `path` semantics.
///
/// At every vertex: next-event estimation (a light chosen by the scene, usually by power,
/// then a direction toward it) and BSDF sampling, combined by [`Strategy`]; emitters found by
/// BSDF sampling are weighted against light sampling; delta BSDFs and delta lights get no
/// MIS. Russian roulette from `rr_depth` on continues with probability
/// `q = min(max(throughput) · η², 0.95)`.
///
/// Veach 1997, "Robust Monte Carlo Methods for Light Transport Simulation", PhD thesis,
/// Stanford (chapter 9, multiple importance sampling).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathTracer {
    /// Longest path in segments: −1 unlimited, 0 nothing, 1 emitters seen directly, 2 direct
    /// lighting, and so on (Mitsuba's meaning).
    pub max_depth: i32,
    /// Depth (number of bounces sampled) from which Russian roulette applies.
    pub rr_depth: u32,
    /// Sampling strategy at every vertex.
    pub strategy: Strategy,
    /// Hide emitters seen directly (Mitsuba 3's `hide_emitters`): the camera ray passes
    /// through emitter surfaces, and where it then leaves the scene the sample is zero (the
    /// environment is not seen). Light the emitters cast is unchanged.
    pub hide_emitters: bool,
}

impl Default for PathTracer {
    fn default() -> Self {
        Self {
            max_depth: -1,
            rr_depth: 5,
            strategy: Strategy::MisPower,
            hide_emitters: false,
        }
    }
}

/// Radiance along one camera ray, with the number of rays cast to find it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PathResult {
    /// The radiance estimate, linear RGB.
    pub radiance: Vec3,
    /// Rays cast (intersection and shadow rays).
    pub rays: u32,
}

/// How the previous vertex sampled the current ray: what an emitter hit needs for its MIS
/// weight.
#[derive(Clone, Copy)]
pub(crate) struct PrevVertex {
    pub(crate) sp: SurfacePoint,
    /// The density with which the ray was sampled (a mixture's, for the guided tracer).
    pub(crate) pdf: f32,
    pub(crate) delta: bool,
}

/// `max_depth` as an unsigned bound (−1 and other negatives become unlimited).
#[inline]
pub(crate) fn depth_limit(max_depth: i32) -> u32 {
    u32::try_from(max_depth).unwrap_or(u32::MAX)
}

/// Weight under `strategy` of an emitter reached by the ray sampled at `prev` (`None`: the
/// camera), `light_pdf` giving the light-sampling density from the previous vertex.
#[inline]
pub(crate) fn hit_weight(
    strategy: Strategy,
    prev: &Option<PrevVertex>,
    light_pdf: impl FnOnce(&SurfacePoint) -> f32,
) -> f32 {
    match prev {
        None => 1.0,
        Some(v) if v.delta => 1.0,
        Some(v) => match strategy {
            Strategy::BsdfOnly => 1.0,
            Strategy::LightOnly => 0.0,
            s => s.bsdf_weight(1.0, v.pdf, 1.0, light_pdf(&v.sp)),
        },
    }
}

/// The contribution of one light sample at a vertex (before the path throughput), weighted
/// under `strategy` against the density with which the vertex samples directions:
/// `sampling_pdf` of the BSDF's density toward the light (the identity for the path tracer,
/// the guiding mixture for the guided one; world direction `ls.wi`).
#[inline]
#[allow(clippy::too_many_arguments)]
pub(crate) fn nee<S: Scene>(
    strategy: Strategy,
    scene: &S,
    bsdf: &S::Bsdf<'_>,
    sp: &SurfacePoint,
    wo: Vec3,
    ls: &super::LightSample,
    rays: &mut u32,
    sampling_pdf: impl FnOnce(f32) -> f32,
) -> Vec3 {
    if !ls.delta && !strategy.samples_lights() {
        return Vec3::ZERO;
    }
    if !is_positive(ls.pdf) {
        return Vec3::ZERO;
    }
    let wi = sp.frame.to_local(ls.wi);
    let (f, pdf_b) = bsdf.eval_pdf(wo, wi);
    if f == Vec3::ZERO {
        return Vec3::ZERO;
    }
    *rays += 1;
    if occluded(scene, sp, ls.wi, ls.dist) {
        return Vec3::ZERO;
    }
    let w = if ls.delta {
        1.0
    } else {
        strategy.light_weight(1.0, ls.pdf, 1.0, sampling_pdf(pdf_b))
    };
    f * ls.radiance * (w / ls.pdf)
}

impl PathTracer {
    /// Estimates the radiance arriving at the camera along the unit direction `dir` from
    /// `origin` (hits beyond `t_max` are ignored).
    pub fn li<S: Scene, R: SampleSource>(
        &self,
        scene: &S,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        samples: &mut R,
    ) -> PathResult {
        let max_depth = depth_limit(self.max_depth);
        let mut out = PathResult::default();
        if max_depth == 0 {
            return out;
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
                    out.radiance += throughput * le * w;
                }
                break;
            };
            let wo_world = -ray_dir;
            if scene.is_emitter(&sp) {
                let le = scene.emitted(&sp, wo_world);
                if le != Vec3::ZERO {
                    let w = hit_weight(self.strategy, &prev, |from| scene.light_pdf(from, &sp));
                    out.radiance += throughput * le * w;
                }
            }
            if depth + 1 >= max_depth {
                break;
            }
            let bsdf = &scene.bsdf(&sp);
            let wo = sp.frame.to_local(wo_world);
            let flags = bsdf.flags();
            // Only the values the scene and the BSDF read are drawn. The light sample comes
            // first: at the camera vertex it is dimension 1, which `Sobol4dSampler` stratifies
            // jointly with the position in the pixel (dimension 0); the scene chooses the light
            // with it too, so `u_pick` is drawn only for choices such as a mesh triangle.
            let u_light = samples.next_2d();
            let u_pick = if scene.samples_light_choice() {
                samples.next_2d()
            } else {
                Vec2::splat(0.5)
            };
            if flags.smooth && (self.strategy.samples_lights() || scene.has_delta_lights()) {
                if let Some(ls) = scene.sample_light(&sp, u_pick, u_light) {
                    out.radiance += throughput
                        * nee(
                            self.strategy,
                            scene,
                            bsdf,
                            &sp,
                            wo,
                            &ls,
                            &mut out.rays,
                            |p| p,
                        );
                }
            }
            let Some(bs) = super::sample_bsdf(bsdf, wo, samples) else {
                break;
            };
            throughput *= bs.weight;
            eta *= bs.eta;
            depth += 1;
            let t_max_c = throughput.max_element();
            if !is_positive(t_max_c) {
                break;
            }
            if depth >= self.rr_depth {
                let q = (t_max_c * eta * eta).min(0.95);
                if samples.next_1d() >= q {
                    break;
                }
                throughput /= q;
            }
            ray_dir = sp.frame.to_world(bs.wi);
            hit = scene.trace(&sp, ray_dir);
            out.rays += 1;
            prev = Some(PrevVertex {
                sp,
                pdf: bs.pdf,
                delta: bs.delta,
            });
        }
        out
    }
}
