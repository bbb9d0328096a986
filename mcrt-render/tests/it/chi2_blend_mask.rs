//! `blendbsdf` and `mask` samplers against their densities, with the suite's chi-square
//! settings (`tests/common`: α = 0.01 family-wise over 400 runs, 10⁶ samples, fixed seed),
//! plus the check that every sample's weight is `f · |cos θ_i| / pdf` in each channel.
//!
//! A blend of a diffuse and a rough gold material (hemisphere), and of smooth plastic and
//! rough glass (sphere; the plastic's Dirac reflection counts as rejected, so the rejected
//! cell checks its probability); a mask of opacity 0.3 over a two-sided diffuse material
//! (sphere; the light that passes through counts as rejected). Each seen from 30° and 70°.
//! The samplers take a third value (which material, then its own choice), a hash of the
//! other two (`common::third_value`).

use crate::common;

use common::{check_bsdf_sampling, hemisphere, sphere, third_value};
use mcrt::glam::Vec3;
use mcrt::integrator::{Bsdf, BsdfSample};
use mcrt::stats::Directions;
use mcrt_render::bsdf::{
    AnyBsdf, Blend, Diffuse, Fresnel, Mask, Plastic, RoughConductor, RoughDielectric, Sided,
};

fn wo_at(deg: f32) -> Vec3 {
    let t = deg.to_radians();
    Vec3::new(t.sin(), 0.0, t.cos())
}

fn one_sided(b: AnyBsdf) -> Box<Sided<AnyBsdf>> {
    Box::new(Sided {
        bsdf: b,
        two_sided: false,
    })
}

fn smooth_part(s: Option<BsdfSample>) -> Option<BsdfSample> {
    s.filter(|s| !s.delta)
}

fn check<B: Bsdf + Sync>(name: &str, b: &B, wo: Vec3, dirs: Directions) {
    check_bsdf_sampling(name, b, wo, dirs, |u| {
        smooth_part(b.sample(wo, third_value(u), u))
    });
}

#[test]
fn blend_of_diffuse_and_rough_gold() {
    let gold = Fresnel::Complex {
        eta: Vec3::new(0.143, 0.375, 1.442),
        k: Vec3::new(3.983, 2.386, 1.603),
    };
    let b = Blend {
        weight: 0.3,
        first: one_sided(AnyBsdf::Diffuse(Diffuse {
            reflectance: Vec3::new(0.2, 0.5, 0.8),
        })),
        second: one_sided(AnyBsdf::RoughConductor(
            RoughConductor::new(true, 0.3, gold, Vec3::ONE).expect("valid"),
        )),
    };
    for deg in [30.0, 70.0] {
        check(
            &format!("blend-diffuse-gold-{deg}"),
            &b,
            wo_at(deg),
            hemisphere(),
        );
    }
}

#[test]
fn blend_of_plastic_and_rough_glass() {
    let b = Blend {
        weight: 0.6,
        first: one_sided(AnyBsdf::Plastic(Plastic::new(
            Vec3::new(0.8, 0.4, 0.1),
            Vec3::ONE,
            1.49,
            false,
        ))),
        second: one_sided(AnyBsdf::RoughDielectric(
            RoughDielectric::new(true, 0.3, 1.5, Vec3::ONE, Vec3::ONE).expect("valid"),
        )),
    };
    for deg in [30.0, 70.0] {
        check(
            &format!("blend-plastic-glass-{deg}"),
            &b,
            wo_at(deg),
            sphere(),
        );
    }
}

#[test]
fn mask_over_twosided_diffuse() {
    let m = Mask {
        opacity: 0.3,
        inner: Box::new(Sided {
            bsdf: AnyBsdf::Diffuse(Diffuse {
                reflectance: Vec3::new(0.8, 0.5, 0.2),
            }),
            two_sided: true,
        }),
    };
    for wo in [wo_at(30.0), -wo_at(70.0)] {
        check(&format!("mask-{}", wo.z), &m, wo, sphere());
    }
}
