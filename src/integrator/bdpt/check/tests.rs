//! The weight check on a small scene of its own: the inside of a unit sphere, Lambertian,
//! lit by the cap `z ≥ ½` of its own surface and seen by a pinhole camera at its centre. It
//! passes with the right densities and fails when the BSDF's `pdf` or the scene's
//! `emission_pdf` is off by a factor from what the sampling routines return, when a density
//! is NaN, and when no path is checked.

use super::{MisWeightCheck, MisWeightOutcome};
use crate::integrator::{
    Bdpt, BidirectionalScene, Bsdf, BsdfFlags, BsdfSample, CameraConnection, EmissionSample,
    EmitterKind, LightSample, Scene, Strategy, SurfacePoint,
};
use crate::sampling::Frame;
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, PI};

/// Half the side of the camera's image plane at distance 1 (`tan` of half the field of view).
const TAN_HALF: f32 = 0.8;
/// Film size in pixels.
const FILM: u32 = 16;

/// Lambertian reflection with albedo ½ whose `pdf` is `scale` times the density its
/// `sample` draws from (cosine-weighted).
struct Lambert {
    scale: f32,
}

impl Bsdf for Lambert {
    fn flags(&self) -> BsdfFlags {
        BsdfFlags {
            smooth: true,
            ..BsdfFlags::default()
        }
    }
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Vec3::ZERO;
        }
        Vec3::splat(0.5 * wi.z * FRAC_1_PI)
    }
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        self.scale * wi.z * FRAC_1_PI
    }
    fn sample(&self, wo: Vec3, _u1: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = cosine(u);
        BsdfSample::from_value(wi, self.eval(wo, wi), wi.z * FRAC_1_PI, 1.0)
    }
    fn samples_component(&self) -> bool {
        false
    }
}

/// A cosine-weighted direction about `z`.
fn cosine(u: Vec2) -> Vec3 {
    let r = u.x.sqrt();
    let (s, c) = (2.0 * PI * u.y).sin_cos();
    Vec3::new(r * c, r * s, (1.0 - u.x).max(0.0).sqrt())
}

/// The inside of the unit sphere; `emission_scale` multiplies the direction density that
/// `emission_pdf` states.
struct InsideSphere {
    bsdf: Lambert,
    emission_scale: f32,
}

impl InsideSphere {
    fn new(bsdf_scale: f32, emission_scale: f32) -> Self {
        Self {
            bsdf: Lambert { scale: bsdf_scale },
            emission_scale,
        }
    }

    /// The surface point at `p` on the sphere, its front side facing the inside.
    fn point(p: Vec3, t: f32) -> SurfacePoint {
        let n = -p;
        SurfacePoint {
            t,
            ..SurfacePoint::new(p, n, Frame::from_normal(n))
        }
    }

    /// The far hit of the ray from `o` (inside or on the sphere) along the unit `dir`.
    fn hit(o: Vec3, dir: Vec3) -> Option<SurfacePoint> {
        let b = o.dot(dir);
        let c = o.length_squared() - 1.0;
        let t = -b + (b * b - c).max(0.0).sqrt();
        (t > 1e-4).then(|| Self::point((o + t * dir).normalize(), t))
    }

    fn on_light(p: Vec3) -> bool {
        p.z >= 0.5
    }

    /// A point uniform on the light (the cap `z ≥ ½`, area π).
    fn light_point(u: Vec2) -> SurfacePoint {
        let z = 0.5 + 0.5 * u.x;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let (s, c) = (2.0 * PI * u.y).sin_cos();
        Self::point(Vec3::new(r * c, r * s, z), 0.0)
    }

    /// The film position and density per steradian of the camera direction `dir`.
    fn camera_density(dir: Vec3) -> Option<(Vec2, f32)> {
        let c = -dir.z;
        if c <= 0.0 {
            return None;
        }
        let (x, y) = (dir.x / c, dir.y / c);
        if x.abs() >= TAN_HALF || y.abs() >= TAN_HALF {
            return None;
        }
        let f = FILM as f32;
        let raster = Vec2::new(
            (x / TAN_HALF + 1.0) * 0.5 * f,
            (1.0 - y / TAN_HALF) * 0.5 * f,
        );
        let area = 4.0 * TAN_HALF * TAN_HALF;
        Some((raster, 1.0 / (area * c * c * c)))
    }
}

impl Scene for InsideSphere {
    type Bsdf<'a> = &'a Lambert;

    fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<SurfacePoint> {
        Self::hit(origin, dir).filter(|h| h.t <= t_max)
    }
    fn trace(&self, from: &SurfacePoint, dir: Vec3) -> Option<SurfacePoint> {
        if from.ng.dot(dir) <= 0.0 {
            return None;
        }
        Self::hit(from.p, dir)
    }
    fn occluded(&self, _from: &SurfacePoint, _dir: Vec3, _dist: f32) -> bool {
        false // the inside of a convex surface sees all of it
    }
    fn bsdf(&self, _sp: &SurfacePoint) -> &Lambert {
        &self.bsdf
    }
    fn is_emitter(&self, sp: &SurfacePoint) -> bool {
        Self::on_light(sp.p)
    }
    fn emitted(&self, sp: &SurfacePoint, wo: Vec3) -> Vec3 {
        if Self::on_light(sp.p) && sp.ng.dot(wo) > 0.0 {
            Vec3::ONE
        } else {
            Vec3::ZERO
        }
    }
    fn sample_light(&self, from: &SurfacePoint, _u_pick: Vec2, u: Vec2) -> Option<LightSample> {
        let l = Self::light_point(u);
        let d = l.p - from.p;
        let dist = d.length();
        let wi = d / dist;
        let pdf = self.light_pdf(from, &l);
        (pdf > 0.0 && pdf.is_finite()).then_some(LightSample {
            wi,
            dist,
            radiance: Vec3::ONE,
            pdf,
            delta: false,
        })
    }
    fn samples_light_choice(&self) -> bool {
        false
    }
    fn light_pdf(&self, from: &SurfacePoint, hit: &SurfacePoint) -> f32 {
        if !Self::on_light(hit.p) {
            return 0.0;
        }
        let d = hit.p - from.p;
        let d2 = d.length_squared();
        let cos = hit.ng.dot(-d).max(0.0) / d2.sqrt();
        if cos > 0.0 {
            FRAC_1_PI * d2 / cos
        } else {
            0.0
        }
    }
}

impl BidirectionalScene for InsideSphere {
    fn sample_emission(&self, _u_pick: Vec2, u_pos: Vec2, u_dir: Vec2) -> Option<EmissionSample> {
        let point = Self::light_point(u_pos);
        let local = cosine(u_dir);
        Some(EmissionSample {
            light: 0,
            kind: EmitterKind::Area,
            point,
            dir: point.frame.to_world(local),
            radiance: Vec3::ONE,
            pdf_pos: FRAC_1_PI,
            pdf_dir: local.z * FRAC_1_PI,
        })
    }
    fn emission_pdf(&self, _light: u32, point: &SurfacePoint, dir: Vec3) -> (f32, f32) {
        if !Self::on_light(point.p) {
            return (0.0, 0.0);
        }
        let cos = point.ng.dot(dir).max(0.0);
        (FRAC_1_PI, self.emission_scale * cos * FRAC_1_PI)
    }
    fn emitter_at(&self, sp: &SurfacePoint) -> Option<u32> {
        Self::on_light(sp.p).then_some(0)
    }
    fn environment_light(&self) -> Option<u32> {
        None
    }
    fn camera_ray(&self, raster: Vec2) -> (Vec3, Vec3, f32) {
        let f = FILM as f32;
        let x = (2.0 * raster.x / f - 1.0) * TAN_HALF;
        let y = (1.0 - 2.0 * raster.y / f) * TAN_HALF;
        (Vec3::ZERO, Vec3::new(x, y, -1.0).normalize(), f32::INFINITY)
    }
    fn camera_position(&self) -> Vec3 {
        Vec3::ZERO
    }
    fn camera_forward(&self) -> Vec3 {
        -Vec3::Z
    }
    fn camera_pdf(&self, dir: Vec3) -> f32 {
        Self::camera_density(dir).map_or(0.0, |(_, pdf)| pdf)
    }
    fn connect_camera(&self, p: Vec3) -> Option<CameraConnection> {
        let dist = p.length();
        let dir = p / dist;
        let (raster, pdf) = Self::camera_density(dir)?;
        Some(CameraConnection {
            raster,
            wi: -dir,
            dist,
            importance: pdf,
        })
    }
    fn film_size(&self) -> (u32, u32) {
        (FILM, FILM)
    }
}

fn run(scene: &InsideSphere, strategy: Strategy) -> MisWeightOutcome {
    let check = MisWeightCheck {
        paths: 300,
        seed: 5,
        max_vertices: 5,
        ..MisWeightCheck::default()
    };
    let bdpt = Bdpt {
        strategy,
        ..Bdpt::default()
    };
    bdpt.check_mis_weights(scene, &check)
}

#[test]
fn right_densities_pass_with_either_heuristic() {
    for strategy in [Strategy::MisPower, Strategy::MisBalance] {
        let out = run(&InsideSphere::new(1.0, 1.0), strategy);
        out.assert_passed();
        assert!(out.compared > 500, "{}", out.report());
        assert!(out.worst_sum_error() < 1e-4, "{}", out.report());
        // Every strategy the check compares took part: s = 0, 2, 3 with t ≥ 2.
        for (s, t) in [(0, 3), (2, 2), (3, 2), (2, 3), (0, 5)] {
            assert!(
                out.strategies
                    .iter()
                    .any(|x| (x.s, x.t) == (s, t) && x.compared > 0),
                "({s}, {t}) not compared:\n{}",
                out.report()
            );
        }
    }
}

#[test]
fn a_bsdf_pdf_off_by_a_quarter_fails() {
    let out = run(&InsideSphere::new(1.25, 1.0), Strategy::MisPower);
    assert!(!out.passed(), "{}", out.report());
    assert!(out.failures > 10, "{}", out.report());
    assert!(out.worst_weight_error() > 0.05, "{}", out.report());
    assert!(out.report().contains("FAILED"));
    assert!(!out.failure_messages.is_empty());
}

#[test]
fn an_emission_pdf_off_by_a_quarter_fails() {
    let out = run(&InsideSphere::new(1.0, 1.25), Strategy::MisPower);
    assert!(!out.passed(), "{}", out.report());
    assert!(out.failures > 10, "{}", out.report());
    assert!(out.worst_weight_error() > 0.05, "{}", out.report());
}

#[test]
fn a_nan_density_fails() {
    let out = run(&InsideSphere::new(f32::NAN, 1.0), Strategy::MisPower);
    assert!(!out.passed(), "{}", out.report());
    assert!(out.failures > 10, "{}", out.report());
}

#[test]
#[should_panic(expected = "FAILED")]
fn assert_passed_panics_with_the_report() {
    run(&InsideSphere::new(1.25, 1.0), Strategy::MisPower).assert_passed();
}

#[test]
fn checking_nothing_fails() {
    let check = MisWeightCheck {
        paths: 0,
        ..MisWeightCheck::default()
    };
    let out = Bdpt::default().check_mis_weights(&InsideSphere::new(1.0, 1.0), &check);
    assert_eq!((out.summed, out.compared, out.failures), (0, 0, 0));
    assert!(!out.passed());
    assert!(out.report().contains("proves nothing"));
}

#[test]
fn the_check_is_deterministic() {
    let scene = InsideSphere::new(1.0, 1.0);
    assert_eq!(
        run(&scene, Strategy::MisPower),
        run(&scene, Strategy::MisPower)
    );
}
