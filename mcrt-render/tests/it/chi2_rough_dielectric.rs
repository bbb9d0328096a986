//! The rough dielectric's sampler against its density on the whole sphere of directions,
//! with the suite's chi-square settings (`tests/common`: α = 0.01 family-wise over 400
//! runs, 10⁶ samples, fixed seed), plus the check that every sample's weight is
//! `f · |cos θ_i| / pdf` in each channel.
//!
//! GGX (α = 0.5, and 0.1 once) and Beckmann (α = 0.3) at η = 1.5, seen from outside at 0°,
//! 45° and 80° and from inside at 20° and 60° (the latter beyond the critical angle of the
//! smooth interface, 41.8°, where only the tilted facets transmit). Samples lost below the
//! wrong side or to the warp's rejection form the harness's rejected cell. The sampler
//! takes a third value (the choice between reflection and refraction), a hash of the
//! other two (`common::third_value`).

use crate::common;

use common::{check_bsdf_sampling, sphere, third_value};
use mcrt::glam::Vec3;
use mcrt::integrator::Bsdf;
use mcrt_render::bsdf::RoughDielectric;

fn wo_at(deg: f32) -> Vec3 {
    let t = deg.to_radians();
    Vec3::new(t.sin(), 0.0, t.cos())
}

fn check(name: &str, b: &RoughDielectric, wo: Vec3) {
    check_bsdf_sampling(name, b, wo, sphere(), |u| b.sample(wo, third_value(u), u));
}

fn glass(ggx: bool, alpha: f32) -> RoughDielectric {
    RoughDielectric::new(
        ggx,
        alpha,
        1.5,
        Vec3::new(1.0, 0.8, 0.6),
        Vec3::new(0.5, 0.7, 1.0),
    )
    .expect("valid alpha")
}

#[test]
fn rough_dielectric_from_outside() {
    for (ggx, alpha) in [(true, 0.5), (false, 0.3)] {
        for deg in [0.0, 45.0, 80.0] {
            let name = format!("roughdielectric-{ggx}-{alpha}-out-{deg}");
            check(&name, &glass(ggx, alpha), wo_at(deg));
        }
    }
}

#[test]
fn rough_dielectric_from_inside() {
    for (ggx, alpha) in [(true, 0.5), (false, 0.3)] {
        for deg in [20.0, 60.0] {
            let name = format!("roughdielectric-{ggx}-{alpha}-in-{deg}");
            check(&name, &glass(ggx, alpha), -wo_at(deg));
        }
    }
}

#[test]
fn narrow_rough_dielectric() {
    check(
        "roughdielectric-ggx-0.1-out-30",
        &glass(true, 0.1),
        wo_at(30.0),
    );
}
