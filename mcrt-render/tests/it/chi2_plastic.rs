//! The coated materials' samplers against their densities on the hemisphere, with the
//! suite's chi-square settings (`tests/common`: α = 0.01 family-wise over 400 runs, 10⁶
//! samples, fixed seed), plus the check that every sample's weight is `f · cos θ_i / pdf`
//! in each channel.
//!
//! Smooth plastic: its Dirac reflection has no density, so those samples count as
//! rejected; the rejected cell's expected mass `1 − ∫ pdf` is then the probability of
//! choosing the reflection, which the test thus checks too. Rough plastic: GGX α = 0.3
//! (nonlinear) and Beckmann α = 0.1 (Mitsuba's default), the weight being the whole
//! mixture's `f cos θ_i / pdf`. Each seen from 0°, 45° and 80°. The samplers take a third
//! value (the component), a hash of the other two (`common::third_value`).

use crate::common;

use common::{check_bsdf_sampling, hemisphere, third_value};
use mcrt::glam::Vec3;
use mcrt::integrator::{Bsdf, BsdfSample};
use mcrt_render::bsdf::{Plastic, RoughPlastic};

fn wo_at(deg: f32) -> Vec3 {
    let t = deg.to_radians();
    Vec3::new(t.sin(), 0.0, t.cos())
}

/// The sample if it has a density (not a Dirac component).
fn smooth_part(s: Option<BsdfSample>) -> Option<BsdfSample> {
    s.filter(|s| !s.delta)
}

fn check<B: Bsdf + Sync>(name: &str, b: &B, wo: Vec3) {
    check_bsdf_sampling(name, b, wo, hemisphere(), |u| {
        smooth_part(b.sample(wo, third_value(u), u))
    });
}

#[test]
fn smooth_plastic() {
    let b = Plastic::new(Vec3::new(0.8, 0.4, 0.1), Vec3::ONE, 1.5, false);
    for deg in [0.0, 45.0, 80.0] {
        check(&format!("plastic-{deg}"), &b, wo_at(deg));
    }
}

#[test]
fn rough_plastic() {
    let cases = [
        (true, 0.3, Vec3::new(0.2, 0.5, 0.8), true),
        (false, 0.1, Vec3::splat(0.5), false),
    ];
    for (ggx, alpha, rho, nonlinear) in cases {
        let b = RoughPlastic::new(ggx, alpha, rho, Vec3::ONE, 1.49, nonlinear).expect("valid");
        for deg in [0.0, 45.0, 80.0] {
            check(&format!("roughplastic-{ggx}-{alpha}-{deg}"), &b, wo_at(deg));
        }
    }
}
