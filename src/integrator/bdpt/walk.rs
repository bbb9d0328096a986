//! Camera and light subpaths: a random walk by BSDF sampling from an endpoint, recording
//! each vertex's forward density and, once the next direction is known, the previous
//! vertex's reverse density (Veach 1997, thesis, section 10.2).

use super::vertex::{bare_point, shading_correction, Kind, Mode, Vertex};
use crate::integrator::{is_positive, BidirectionalScene, Bsdf, EmitterKind};
use crate::sampling::sampler::SampleSource;
use glam::Vec3;

/// Limits of a random walk.
#[derive(Debug, Clone, Copy)]
pub(crate) struct WalkLimits {
    /// Most vertices the subpath may hold (endpoint included).
    pub max_vertices: usize,
    /// Bounces after which Russian roulette applies.
    pub rr_depth: u32,
}

/// The camera subpath for the ray from `origin` (on the near plane) along the unit `dir`,
/// which ends at `t_max`; `path` is cleared first. Rays cast are added to `rays`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn camera_subpath<S: BidirectionalScene, R: SampleSource>(
    scene: &S,
    origin: Vec3,
    dir: Vec3,
    t_max: f32,
    lim: WalkLimits,
    samples: &mut R,
    path: &mut Vec<Vertex>,
    rays: &mut u32,
) {
    path.clear();
    if lim.max_vertices == 0 {
        return;
    }
    let lens = scene.camera_lens_point(origin, dir);
    let mut cam = bare_point(lens);
    cam.ng = scene.camera_forward();
    path.push(Vertex::new(Kind::Camera, cam, Vec3::ONE, 1.0));
    let pdf = scene.camera_pdf_from_lens(lens, dir);
    if !is_positive(pdf) {
        return;
    }
    let first = scene.intersect(origin, dir, t_max);
    *rays += 1;
    walk(
        scene,
        first,
        dir,
        Vec3::ONE,
        pdf,
        Mode::Radiance,
        lim,
        samples,
        path,
        rays,
    );
}

/// A light subpath: an emitted ray chosen by the scene, then a walk; `path` is cleared first.
pub(crate) fn light_subpath<S: BidirectionalScene, R: SampleSource>(
    scene: &S,
    lim: WalkLimits,
    samples: &mut R,
    path: &mut Vec<Vertex>,
    rays: &mut u32,
) {
    path.clear();
    if lim.max_vertices == 0 {
        return;
    }
    let u_pick = samples.next_2d();
    let u_pos = samples.next_2d();
    let u_dir = samples.next_2d();
    let Some(es) = scene.sample_emission(u_pick, u_pos, u_dir) else {
        return;
    };
    if !(is_positive(es.pdf_pos) && is_positive(es.pdf_dir) && es.radiance.is_finite()) {
        return;
    }
    path.push(Vertex::from_emission(&es));
    let cos = if es.kind == EmitterKind::Area {
        es.point.ng.dot(es.dir).abs()
    } else {
        1.0
    };
    let beta = es.radiance * (cos / (es.pdf_pos * es.pdf_dir));
    let first = scene.trace(&es.point, es.dir);
    *rays += 1;
    walk(
        scene,
        first,
        es.dir,
        beta,
        es.pdf_dir,
        Mode::Importance,
        lim,
        samples,
        path,
        rays,
    );
}

/// Continues a subpath whose last vertex sent a ray along `dir` (density `pdf` per
/// steradian, per unit disk area from a light at infinity) that found `hit`.
#[allow(clippy::too_many_arguments)]
fn walk<S: BidirectionalScene, R: SampleSource>(
    scene: &S,
    mut hit: Option<crate::integrator::SurfacePoint>,
    mut dir: Vec3,
    mut beta: Vec3,
    mut pdf: f32,
    mode: Mode,
    lim: WalkLimits,
    samples: &mut R,
    path: &mut Vec<Vertex>,
    rays: &mut u32,
) {
    // Russian roulette compares the throughput with the first bounce's (light subpaths
    // carry the emitted power in it) and counts η² as the path tracer does.
    let scale = 1.0 / beta.max_element().max(f32::MIN_POSITIVE);
    let mut eta = 1.0f32;
    let mut bounces = 0u32;
    while path.len() < lim.max_vertices {
        let prev = *path.last().expect("a walk starts from an endpoint");
        let Some(sp) = hit else {
            if mode == Mode::Radiance {
                if let Some(light) = scene.environment_light() {
                    let mut v = Vertex::new(
                        Kind::Light(EmitterKind::Infinite),
                        super::vertex::bare_point(Vec3::ZERO),
                        beta,
                        pdf,
                    );
                    v.w_env = dir;
                    v.w_prev = -dir;
                    v.d2_prev = f32::INFINITY;
                    v.light = light;
                    path.push(v);
                }
            }
            return;
        };
        let flags = scene.bsdf(&sp).flags();
        let pdf_in = pdf;
        let mut v = Vertex::new(Kind::Surface, sp, beta, 0.0);
        v.smooth = flags.smooth;
        v.w_prev = -dir;
        v.d2_prev = if prev.is_infinite() {
            f32::INFINITY
        } else {
            (sp.p - prev.sp.p).length_squared()
        };
        v.pdf_fwd = if prev.is_infinite() {
            pdf * sp.ng.dot(dir).abs()
        } else {
            prev.area_density(pdf, &v)
        };
        if mode == Mode::Radiance {
            if let Some(l) = scene.emitter_at(&sp) {
                v.light = l;
            }
        }
        path.push(v);
        if path.len() >= lim.max_vertices {
            return;
        }
        let bsdf = &scene.bsdf(&sp);
        let wo_world = -dir;
        let wo = sp.frame.to_local(wo_world);
        let Some(bs) = crate::integrator::sample_bsdf(bsdf, wo, samples) else {
            return;
        };
        let wi_world = sp.frame.to_world(bs.wi);
        let mut weight = bs.weight;
        if mode == Mode::Importance {
            weight *= bs.eta * bs.eta * shading_correction(&sp, wo_world, wi_world);
        } else {
            eta *= bs.eta;
        }
        beta *= weight;
        let (pdf_fwd, pdf_rev) = if bs.delta {
            (0.0, 0.0)
        } else {
            (bs.pdf, bsdf.pdf(bs.wi, wo))
        };
        let n = path.len();
        if bs.delta {
            // This vertex's own density is then per projected solid angle at the previous
            // one (see `Vertex::area_density`).
            path[n - 1].delta = true;
            path[n - 1].pdf_fwd_area = path[n - 1].pdf_fwd;
            path[n - 1].pdf_fwd = if prev.is_infinite() {
                pdf_in
            } else {
                prev.area_density(pdf_in, &path[n - 1])
            };
        }
        let rev = path[n - 1].area_density(pdf_rev, &path[n - 2]);
        path[n - 2].pdf_rev = rev;
        pdf = pdf_fwd;
        bounces += 1;
        let b = (beta * scale).max_element();
        if !is_positive(b) || !beta.is_finite() {
            return;
        }
        if bounces >= lim.rr_depth {
            let q = (b * eta * eta).min(0.95);
            if samples.next_1d() >= q {
                return;
            }
            beta /= q;
        }
        dir = wi_world;
        hit = scene.trace(&sp, dir);
        *rays += 1;
    }
}
