//! Direct lighting: emitters seen from the camera plus light arriving at the first hit, by a
//! fixed number of light and BSDF samples (Mitsuba 3's `direct`).

use super::{is_positive, occluded, Bsdf, PathResult, SampleSource, Scene, Strategy};
use glam::{Vec2, Vec3};

/// Direct-lighting estimator with `emitter_samples` light samples and `bsdf_samples` BSDF
/// samples at the first hit, combined by [`Strategy`] with the sample counts in the
/// heuristic (Veach 1997, thesis, section 9.2: the multi-sample model). Like
/// [`PathTracer`](super::PathTracer), it draws the light choice only when
/// [`Scene::samples_light_choice`] and the BSDF component only when
/// [`Bsdf::samples_component`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DirectIntegrator {
    /// Light samples per shading point.
    pub emitter_samples: u32,
    /// BSDF samples per shading point.
    pub bsdf_samples: u32,
    /// Sampling strategy.
    pub strategy: Strategy,
    /// Hide emitters seen directly (Mitsuba 3's `hide_emitters`), as
    /// [`PathTracer::hide_emitters`](super::PathTracer::hide_emitters) does.
    pub hide_emitters: bool,
}

impl Default for DirectIntegrator {
    fn default() -> Self {
        Self {
            emitter_samples: 1,
            bsdf_samples: 1,
            strategy: Strategy::MisPower,
            hide_emitters: false,
        }
    }
}

impl DirectIntegrator {
    /// The light and BSDF sample counts the strategy actually uses.
    fn counts(&self) -> (u32, u32) {
        match self.strategy {
            Strategy::BsdfOnly => (0, self.bsdf_samples.max(1)),
            Strategy::LightOnly => (self.emitter_samples.max(1), 0),
            _ => (self.emitter_samples, self.bsdf_samples),
        }
    }

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
        let mut out = PathResult::default();
        let hit = super::camera_hit(scene, origin, dir, t_max, self.hide_emitters, &mut out.rays);
        let Some(sp) = hit else {
            if scene.has_environment() && !self.hide_emitters {
                out.radiance = scene.environment(dir);
            }
            return out;
        };
        if scene.is_emitter(&sp) {
            out.radiance += scene.emitted(&sp, -dir);
        }
        let bsdf = &scene.bsdf(&sp);
        let wo = sp.frame.to_local(-dir);
        let (n_l, n_b) = self.counts();
        let (nl, nb) = (n_l as f32, n_b as f32);
        let smooth = bsdf.flags().smooth;
        // The delta-light part, when light sampling of smooth lights is off.
        let n_delta = if n_l == 0 && scene.has_delta_lights() {
            1
        } else {
            n_l
        };
        // Only the values the scene and the BSDF read are drawn (as in `PathTracer`).
        let draw_pick = scene.samples_light_choice();
        let draw_component = bsdf.samples_component();
        for _ in 0..n_delta {
            let u = samples.next_2d();
            let u_pick = if draw_pick {
                samples.next_2d()
            } else {
                Vec2::splat(0.5)
            };
            if !smooth {
                continue;
            }
            let Some(ls) = scene.sample_light(&sp, u_pick, u) else {
                continue;
            };
            if !is_positive(ls.pdf) || (n_l == 0 && !ls.delta) {
                continue;
            }
            let (f, pdf_b) = bsdf.eval_pdf(wo, sp.frame.to_local(ls.wi));
            if f == Vec3::ZERO {
                continue;
            }
            out.rays += 1;
            if occluded(scene, &sp, ls.wi, ls.dist) {
                continue;
            }
            let w = if ls.delta {
                1.0
            } else {
                self.strategy.light_weight(nl, ls.pdf, nb, pdf_b)
            };
            out.radiance += f * ls.radiance * (w / (ls.pdf * n_delta as f32));
        }
        for _ in 0..n_b {
            let u1 = if draw_component {
                samples.next_1d()
            } else {
                0.5
            };
            let u2 = samples.next_2d();
            let Some(bs) = bsdf.sample(wo, u1, u2) else {
                continue;
            };
            let wi = sp.frame.to_world(bs.wi);
            let hit = scene.trace(&sp, wi);
            out.rays += 1;
            let (le, pdf_l) = match hit {
                Some(h) if scene.is_emitter(&h) => (
                    scene.emitted(&h, -wi),
                    if bs.delta {
                        0.0
                    } else {
                        scene.light_pdf(&sp, &h)
                    },
                ),
                Some(_) => continue,
                None if scene.has_environment() => (
                    scene.environment(wi),
                    if bs.delta {
                        0.0
                    } else {
                        scene.environment_pdf(&sp, wi)
                    },
                ),
                None => continue,
            };
            let w = if bs.delta {
                1.0
            } else {
                self.strategy.bsdf_weight(nb, bs.pdf, nl, pdf_l)
            };
            out.radiance += bs.weight * le * (w / nb);
        }
        out
    }
}
