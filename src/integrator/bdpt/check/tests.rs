//! The weight check on a small scene of its own: the inside of a unit sphere, Lambertian,
//! lit by the cap `z ≥ ½` of its own surface and seen by a pinhole camera at its centre. It
//! passes with the right densities and fails when the BSDF's `pdf` or the scene's
//! `emission_pdf` is off by a factor from what the sampling routines return, when a density
//! is NaN, and when no path is checked.

use super::{MisWeightCheck, MisWeightOutcome};
use crate::integrator::test_scene::{cosine, InsideSphere, FILM, TAN_HALF};
use crate::integrator::{
    Bdpt, BidirectionalScene, CameraConnection, EmissionSample, EmitterKind, Strategy, SurfacePoint,
};
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

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
