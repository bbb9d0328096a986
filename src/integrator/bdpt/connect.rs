//! One connection strategy `(s, t)`: the first `s` vertices of the light subpath joined to
//! the first `t` of the camera subpath, with its unweighted contribution and its multiple
//! importance weight against every other strategy that can make the same path.
//!
//! The weight uses the ratio recurrence of Veach 1997 (thesis, section 10.2.1): with `p_i`
//! the density of the whole path under the strategy with `i` light vertices,
//! `p_{i+1}/p_i = p_fwd(x_i)/p_rev(x_i)`, so all ratios follow in one pass over the path.

use super::vertex::{bare_point, Kind, Mode, Vertex};
use crate::integrator::{is_positive, occluded, BidirectionalScene, EmitterKind};
use crate::sampling::sampler::SampleSource;
use glam::{Vec2, Vec3};

/// The MIS heuristic's exponent: 1 balance, 2 power.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Heuristic {
    Balance,
    Power,
    /// Every strategy counts in full (for testing one strategy alone).
    Unit,
}

/// A connection's contribution (before its weight), its weight, and for `t = 1` the film
/// position it lands on.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Connection {
    pub value: Vec3,
    pub weight: f32,
    pub raster: Option<Vec2>,
}

/// Connects `light[..s]` with `camera[..t]`; `None` when the strategy cannot make a path
/// here (or the contribution is zero). `s = 1` samples a fresh light point from `samples`,
/// `t = 1` connects to the camera. Shadow rays are added to `rays`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn connect<S: BidirectionalScene, R: SampleSource>(
    scene: &S,
    light: &[Vertex],
    camera: &[Vertex],
    s: usize,
    t: usize,
    heuristic: Heuristic,
    samples: &mut R,
    rays: &mut u32,
) -> Option<Connection> {
    if t == 0 || t > camera.len() || s > light.len() {
        return None;
    }
    // A camera ray that escaped can only be an emitter hit (s = 0).
    if s > 0 && camera[t - 1].is_infinite() {
        return None;
    }
    let mut sampled: Option<Vertex> = None;
    let mut raster = None;
    let value = if s == 0 {
        let pt = &camera[t - 1];
        if t < 2 || !pt.is_light() {
            return None;
        }
        pt.le(scene, &camera[t - 2]) * pt.beta
    } else if t == 1 {
        let qs = &light[s - 1];
        if !qs.connectible() {
            return None;
        }
        // A lens point for the connection, drawn as camera rays draw theirs (its density
        // cancels against theirs in every weight); a pinhole draws no sample.
        let (lens, c) = if scene.camera_has_lens() {
            scene.connect_camera_through_lens(qs.sp.p, samples.next_2d())?
        } else {
            (scene.camera_position(), scene.connect_camera(qs.sp.p)?)
        };
        let mut cam = bare_point(lens);
        cam.ng = scene.camera_forward();
        let cam_v = Vertex::new(Kind::Camera, cam, Vec3::ONE, 1.0);
        let f = if s == 1 {
            // The light seen directly: its emission toward the camera, with the cosine.
            let cos = if qs.on_surface() {
                qs.sp.ng.dot(c.wi).abs()
            } else {
                1.0
            };
            qs.le(scene, &cam_v) * cos
        } else {
            qs.f_dirs(scene, qs.w_prev, c.wi, Mode::Importance)
        };
        let v = qs.beta * f * (c.importance / (c.dist * c.dist));
        if v == Vec3::ZERO || !v.is_finite() {
            return None;
        }
        *rays += 1;
        if occluded(scene, &qs.sp, c.wi, c.dist) {
            return None;
        }
        raster = Some(c.raster);
        sampled = Some(cam_v);
        v
    } else if s == 1 {
        let pt = &camera[t - 1];
        if !pt.connectible() {
            return None;
        }
        let u_pick = samples.next_2d();
        let u = samples.next_2d();
        let (v, lv) = if scene.has_delta_lights() {
            light_by_emission(scene, pt, u_pick, u, rays)?
        } else {
            light_by_nee(scene, pt, u_pick, u, rays)?
        };
        sampled = Some(lv);
        v
    } else {
        let (qs, pt) = (&light[s - 1], &camera[t - 1]);
        if !qs.connectible() || !pt.connectible() {
            return None;
        }
        let (w, d2) = pt.dir_to(qs);
        if !is_positive(d2) {
            return None;
        }
        let fq = qs.f_dirs(scene, qs.w_prev, -w, Mode::Importance);
        let fp = pt.f_dirs(scene, pt.w_prev, w, Mode::Radiance);
        let v = qs.beta * fq * fp * pt.beta / d2;
        if v == Vec3::ZERO || !v.is_finite() {
            return None;
        }
        *rays += 1;
        if occluded(scene, &pt.sp, w, d2.sqrt()) {
            return None;
        }
        v
    };
    if value == Vec3::ZERO || !value.is_finite() {
        return None;
    }
    let weight = match heuristic {
        Heuristic::Unit => 1.0,
        h => mis_weight(scene, light, camera, sampled.as_ref(), s, t, h),
    };
    Some(Connection {
        value,
        weight,
        raster,
    })
}

/// Strategy `s = 1` by the scene's emission sampling (a light by power, a point by area):
/// the same density as a light subpath's first vertex. Used in scenes with delta lights
/// (point, spot, directional), which next-event estimation does not identify. Returns the contribution and the light
/// vertex.
fn light_by_emission<S: BidirectionalScene>(
    scene: &S,
    pt: &Vertex,
    u_pick: Vec2,
    u_pos: Vec2,
    rays: &mut u32,
) -> Option<(Vec3, Vertex)> {
    let es = scene.sample_emission(u_pick, u_pos, Vec2::splat(0.5))?;
    if !is_positive(es.pdf_pos) {
        return None;
    }
    let lv = Vertex::from_emission(&es);
    let (w, d2) = pt.dir_to(&lv);
    let le = lv.le(scene, pt);
    let cos_l = if lv.on_surface() {
        lv.sp.ng.dot(w).abs()
    } else {
        1.0
    };
    let g = if d2.is_finite() { cos_l / d2 } else { 1.0 };
    let f = pt.f_dirs(scene, pt.w_prev, w, Mode::Radiance);
    let v = pt.beta * f * le * (g / es.pdf_pos);
    if v == Vec3::ZERO || !v.is_finite() {
        return None;
    }
    *rays += 1;
    let dist = if d2.is_finite() {
        d2.sqrt()
    } else {
        f32::INFINITY
    };
    if occluded(scene, &pt.sp, w, dist) {
        return None;
    }
    Some((v, lv))
}

/// Strategy `s = 1` by the scene's next-event estimation ([`crate::integrator::Scene::sample_light`]: by
/// solid angle where it can, the light chosen per shading point): the contribution divides
/// by that sample's own density, while the light vertex carries the emission densities, so
/// the weights of all strategies are computed from one set of densities and stay a
/// partition of unity (as pbrt-v4 weighs its `s = 1` samples). The closest hit toward the
/// sample is both the shadow ray and what identifies the light point.
fn light_by_nee<S: BidirectionalScene>(
    scene: &S,
    pt: &Vertex,
    u_pick: Vec2,
    u: Vec2,
    rays: &mut u32,
) -> Option<(Vec3, Vertex)> {
    let ls = scene.sample_light(&pt.sp, u_pick, u)?;
    if ls.delta || !is_positive(ls.pdf) {
        return None;
    }
    let f = pt.f_dirs(scene, pt.w_prev, ls.wi, Mode::Radiance);
    let v = pt.beta * f * ls.radiance / ls.pdf;
    if v == Vec3::ZERO || !v.is_finite() {
        return None;
    }
    *rays += 1;
    let lv = if ls.dist.is_finite() {
        let hit = scene.trace(&pt.sp, ls.wi)?;
        let at = pt.sp.p + ls.wi * ls.dist;
        if (hit.p - at).length_squared() > (1e-3 * ls.dist) * (1e-3 * ls.dist) {
            return None; // something lies in between
        }
        let light = scene.emitter_at(&hit)?;
        let mut lv = Vertex::new(Kind::Light(EmitterKind::Area), hit, Vec3::ONE, 0.0);
        lv.light = light;
        lv.pdf_fwd = scene.emission_pdf(light, &hit, -ls.wi).0;
        lv
    } else {
        if occluded(scene, &pt.sp, ls.wi, f32::INFINITY) {
            return None;
        }
        let light = scene.environment_light()?;
        let mut lv = Vertex::new(
            Kind::Light(EmitterKind::Infinite),
            bare_point(Vec3::ZERO),
            Vec3::ONE,
            0.0,
        );
        lv.light = light;
        lv.w_env = ls.wi;
        lv.pdf_fwd = scene.emission_pdf(light, &lv.sp, -ls.wi).0;
        lv
    };
    Some((v, lv))
}

/// The density per unit area (per steradian toward a light at infinity) with which the
/// scene's next-event estimation at `x1` chooses the light point `x0`.
fn nee_density<S: BidirectionalScene>(scene: &S, x0: &Vertex, x1: &Vertex) -> f32 {
    if x1.kind != Kind::Surface {
        return 0.0;
    }
    if x0.is_infinite() {
        return scene.environment_pdf(&x1.sp, x0.w_env);
    }
    let (w, d2) = x1.dir_to(x0);
    let pdf_sa = scene.light_pdf(&x1.sp, &x0.sp);
    if d2 > 0.0 && d2.is_finite() {
        pdf_sa * x0.sp.ng.dot(w).abs() / d2
    } else {
        0.0
    }
}

/// `x^β`, with 0 mapped to 1 (a zero density is a delta or impossible strategy; its ratio
/// then carries no information).
#[inline]
fn remap(x: f32, h: Heuristic) -> f32 {
    if x == 0.0 {
        return 1.0;
    }
    match h {
        Heuristic::Power => x * x,
        _ => x,
    }
}

/// The MIS weight of strategy `(s, t)` for the path it made; `sampled` is the endpoint
/// that strategy sampled afresh (`s = 1`: the light vertex; `t = 1`: the camera vertex).
pub(crate) fn mis_weight<S: BidirectionalScene>(
    scene: &S,
    light: &[Vertex],
    camera: &[Vertex],
    sampled: Option<&Vertex>,
    s: usize,
    t: usize,
    h: Heuristic,
) -> f32 {
    // Paths of one segment: (0, 2) is the only strategy run (see `Bdpt`).
    if s + t == 2 {
        return 1.0;
    }
    // The endpoints as this strategy sees them (by reference: vertices are large).
    let qs: Option<&Vertex> = match s {
        0 => None,
        1 => sampled.or(light.first()),
        _ => Some(&light[s - 1]),
    };
    let pt: &Vertex = if t == 1 {
        sampled.unwrap_or(&camera[0])
    } else {
        &camera[t - 1]
    };
    // An endpoint whose own walk went on by a Dirac delta (a mixed BSDF) is, for this
    // strategy, a connection: not delta, its density per area.
    let (qs_end, pt_end);
    let qs = match qs {
        Some(q) if q.delta => {
            qs_end = q.as_endpoint();
            Some(&qs_end)
        }
        q => q,
    };
    let pt = if pt.delta {
        pt_end = pt.as_endpoint();
        &pt_end
    } else {
        pt
    };
    let pt_prev = (t > 1).then(|| &camera[t - 2]);
    let qs_prev = (s > 1).then(|| &light[s - 2]);
    // Reverse densities of the four vertices next to the connection; `w` runs from `pt` to
    // `qs`, and each subpath vertex knows the direction to its predecessor.
    let (w, d2) = match qs {
        Some(q) => pt.dir_to(q),
        None => (Vec3::ZERO, 0.0),
    };
    let pt_rev = match qs {
        Some(q) => q.pdf_along(scene, qs_prev.map(|_| q.w_prev), pt, -w, d2),
        None => pt.pdf_light_origin(scene, pt_prev.unwrap_or(pt)),
    };
    let pt_prev_rev = pt_prev.map(|pm| match qs {
        Some(_) => pt.pdf_along(scene, Some(w), pm, pt.w_prev, pt.d2_prev),
        None => pt.pdf_light_along(scene, pm, pt.w_prev, pt.d2_prev),
    });
    let qs_rev = qs.map(|q| pt.pdf_along(scene, pt_prev.map(|_| pt.w_prev), q, w, d2));
    let qs_prev_rev = match (qs, qs_prev) {
        (Some(q), Some(qm)) => Some(q.pdf_along(scene, Some(-w), qm, q.w_prev, q.d2_prev)),
        _ => None,
    };
    // With next-event estimation for s = 1 (scenes without point lights), that strategy's
    // density of the light point is NEE's, not emission's: its ratio to every other
    // strategy carries κ = p_nee(x_0 | x_1) / p_emit(x_0) (x_0 the light end, x_1 its
    // neighbour), per unit area.
    let kappa = if scene.has_delta_lights() {
        1.0
    } else {
        let (x0, x1, p_emit) = match s {
            0 => (Some(pt), pt_prev, pt_rev),
            1 => (qs, Some(pt), qs.map_or(0.0, |q| q.pdf_fwd)),
            _ => (Some(&light[0]), Some(&light[1]), light[0].pdf_fwd),
        };
        match (x0, x1) {
            (Some(x0), Some(x1)) if p_emit > 0.0 => nee_density(scene, x0, x1) / p_emit,
            _ => 1.0,
        }
    };
    let kappa_h = if kappa.is_finite() && kappa >= 0.0 {
        if kappa > 0.0 {
            remap(kappa, h)
        } else {
            0.0
        }
    } else {
        1.0
    };
    // Camera side: strategies with fewer camera vertices.
    let cam_rev = |i: usize| {
        if i == t - 1 {
            pt_rev
        } else if i + 2 == t {
            pt_prev_rev.unwrap_or(0.0)
        } else {
            camera[i].pdf_rev
        }
    };
    let cam_delta = |i: usize| if i == t - 1 { false } else { camera[i].delta };
    let mut sum = 0.0f32;
    let mut r = 1.0f32;
    for i in (1..t).rev() {
        let fwd = if i == t - 1 {
            pt.pdf_fwd
        } else {
            camera[i].pdf_fwd
        };
        r *= remap(cam_rev(i), h) / remap(fwd, h);
        if !cam_delta(i) && !cam_delta(i - 1) {
            // The first step from s = 0 is the strategy s = 1.
            sum += if s == 0 && i == t - 1 { r * kappa_h } else { r };
        }
    }
    // Light side: strategies with fewer light vertices.
    if let Some(q) = qs {
        let light_v = |i: usize| if i == s - 1 { q } else { &light[i] };
        let light_rev = |i: usize| {
            if i == s - 1 {
                qs_rev.unwrap_or(0.0)
            } else if i + 2 == s {
                qs_prev_rev.unwrap_or(0.0)
            } else {
                light[i].pdf_rev
            }
        };
        let light_delta = |i: usize| if i == s - 1 { false } else { light[i].delta };
        let mut r = 1.0f32;
        for i in (0..s).rev() {
            r *= remap(light_rev(i), h) / remap(light_v(i).pdf_fwd, h);
            let before_delta = if i > 0 {
                light_delta(i - 1)
            } else {
                light_v(0).is_delta_light()
            };
            if !light_delta(i) && !before_delta {
                sum += if i == 1 { r * kappa_h } else { r };
            }
        }
    }
    // Seen from s = 1 itself, every other strategy's ratio carries 1/κ.
    if s == 1 && kappa_h > 0.0 {
        sum /= kappa_h;
    }
    let w = 1.0 / (1.0 + sum);
    if w.is_finite() {
        w
    } else {
        0.0
    }
}
