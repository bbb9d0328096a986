//! Next-event estimation by resampled importance sampling over light-BVH candidates
//! (`render --light-candidates M`): `M` lights and points on them are drawn as the BVH
//! draws one, and one is kept in proportion to its unshadowed contribution at a diffuse
//! receiver, `L_e · |cos θ|` per steradian of the sample's density, with the library's
//! [`Resampler`]; then one shadow ray. The light sample returned carries the resampler's
//! contribution weight `W` in its radiance (`L_e · p · W`) and the candidates' source
//! density `p` (the BVH's choice times the point's density) as its `pdf`, which is what
//! `Lights::pdf_hit` gives a BSDF-sampled hit: the path tracer's MIS weights for the two
//! strategies then use `p` on both sides and sum to one for every path, so the estimator
//! stays unbiased (`docs/renderer.md`, "Choosing among many lights", resampling).

use super::{mean, toward_area_light, BvhChoice, Light, Lights};
use crate::geometry::Geometry;
use glam::Vec2;
use mcrt::integrator::{LightSample, SurfacePoint};
use mcrt::sampling::{Resampler, ONE_MINUS_EPSILON};

/// The most candidates `--light-candidates` takes.
pub const MAX_LIGHT_CANDIDATES: u32 = 64;

/// The R2 sequence's steps (Roberts 2018, "The Unreasonable Effectiveness of Quasirandom
/// Sequences"): candidate `j`'s point on its light uses `u + j·R2` modulo 1, each one
/// uniform on its own.
const R2: Vec2 = Vec2::new(0.754_877_7, 0.569_840_3);

/// `x` modulo 1, below 1.
#[inline]
fn wrap(x: f32) -> f32 {
    (x - x.floor()).min(ONE_MINUS_EPSILON)
}

impl Lights {
    /// Whether resampling can run over the light BVH: every light is an untextured area
    /// light on a rectangle or on a mesh split into triangles by the tree (so a candidate's
    /// point needs only its two values `u`, and `u_pick.y` is free to choose among the
    /// candidates), and nothing lies outside the tree.
    pub(super) fn resampling_applies(&self) -> bool {
        let Some(b) = &self.bvh else {
            return false;
        };
        self.lights.iter().enumerate().all(|(i, l)| match *l {
            Light::Area { shape, .. } => {
                self.area_texture(shape).is_none()
                    && (b.by_triangle(i) || self.rectangles[i].is_some())
            }
            _ => false,
        })
    }

    /// One light sample chosen among `m` candidates of the BVH `b` (see the module docs):
    /// candidate `j` chooses its light with `u_pick.x + j/m` and its point with `u + j·R2`
    /// (both modulo 1: each candidate is distributed as one BVH sample, the `m` of them
    /// stratified over the tree), and `u_pick.y` chooses among them.
    #[inline]
    pub(super) fn sample_resampled(
        &self,
        b: &BvhChoice,
        m: u32,
        geo: &Geometry,
        from: &SurfacePoint,
        u_pick: Vec2,
        u: Vec2,
    ) -> Option<LightSample> {
        let mut r = Resampler::new(u_pick.y);
        let n = from.frame.n;
        for j in 0..m {
            let jf = j as f32;
            let v = wrap(u_pick.x + jf / m as f32);
            let uj = Vec2::new(wrap(u.x + jf * R2.x), wrap(u.y + jf * R2.y));
            let ls = b
                .sample(from.p, n, v)
                .and_then(|c| match self.lights[c.light] {
                    Light::Area { shape, radiance } => {
                        let s = match (c.triangle, &self.rectangles[c.light]) {
                            (Some(k), _) => geo.sample_triangle(shape, k, from.p, uj)?,
                            (None, Some(rect)) => rect.sample(geo.shape_sampling(), from.p, uj)?,
                            (None, None) => return None,
                        };
                        toward_area_light(s, radiance, from.p, c.pick)
                    }
                    _ => None,
                });
            match ls {
                Some(ls) => {
                    let target = mean(ls.radiance) * n.dot(ls.wi).abs();
                    r.add(ls, target, ls.pdf);
                }
                None => r.add_empty(),
            }
        }
        let (mut ls, w) = r.finish()?;
        ls.radiance *= ls.pdf * w;
        Some(ls)
    }
}
