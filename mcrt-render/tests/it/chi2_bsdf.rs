//! The renderer's BSDF and light samplers against their densities, with the suite's
//! chi-square settings (`tests/common`: α = 0.01 family-wise over 400 runs, 10⁶ samples,
//! fixed seed), plus the check that every sample's weight equals `f · cos θ / pdf`.
//!
//! Materials: diffuse; rough conductors (GGX and Beckmann, visible-normal sampling, α = 0.5,
//! 0.2 on the hemisphere and 0.05 on a cap about the mirror direction) seen from 0°, 45° and
//! 80°; a two-sided material seen from below. Lights: an environment map with a small sun.
//! Delta components (mirror, glass) have no density; their weights are unit-tested in
//! `scene::bsdf`.

use crate::common;

use common::{check_bsdf_sampling, chi2, hemisphere};
use mcrt::glam::{Mat4, Vec3};
use mcrt::integrator::Bsdf;
use mcrt::stats::Directions;
use mcrt_render::bsdf::{AnyBsdf, Diffuse, Fresnel, RoughConductor, Sided};
use mcrt_render::light::EnvMap;

fn wo_at(deg: f32) -> Vec3 {
    let t = deg.to_radians();
    Vec3::new(t.sin(), 0.0, t.cos())
}

fn rough(ggx: bool, alpha: f32) -> Sided<AnyBsdf> {
    let gold = Fresnel::Complex {
        eta: Vec3::new(0.143, 0.374, 1.442),
        k: Vec3::new(3.98, 2.38, 1.6),
    };
    Sided {
        bsdf: AnyBsdf::RoughConductor(
            RoughConductor::new(ggx, alpha, gold, Vec3::ONE).expect("valid alpha"),
        ),
        two_sided: false,
    }
}

/// Chi-square of the sampled directions (channel 0 weight decides rejection) and the weight
/// check on every channel.
fn check(name: &str, b: &Sided<AnyBsdf>, wo: Vec3, dirs: Directions) {
    check_bsdf_sampling(name, b, wo, dirs, |u| b.sample(wo, 0.5, u));
}

#[test]
fn diffuse() {
    let b = Sided {
        bsdf: AnyBsdf::Diffuse(Diffuse {
            reflectance: Vec3::new(0.8, 0.5, 0.2),
        }),
        two_sided: false,
    };
    for deg in [0.0, 45.0, 80.0] {
        check(&format!("diffuse-{deg}"), &b, wo_at(deg), hemisphere());
    }
}

#[test]
fn twosided_diffuse_from_below() {
    let b = Sided {
        bsdf: AnyBsdf::Diffuse(Diffuse {
            reflectance: Vec3::splat(0.7),
        }),
        two_sided: true,
    };
    let wo = -wo_at(30.0);
    let dirs = Directions::cap(-Vec3::Z, std::f32::consts::FRAC_PI_2).resolution(64, 128);
    check("twosided-diffuse-below", &b, wo, dirs);
}

#[test]
fn rough_conductors_wide() {
    for ggx in [true, false] {
        for alpha in [0.5, 0.2] {
            for deg in [0.0, 45.0, 80.0] {
                let name = format!(
                    "rough-{}-{alpha}-{deg}",
                    if ggx { "ggx" } else { "beckmann" }
                );
                check(&name, &rough(ggx, alpha), wo_at(deg), hemisphere());
            }
        }
    }
}

#[test]
fn rough_conductors_narrow() {
    for ggx in [true, false] {
        for deg in [0.0, 45.0] {
            let wo = wo_at(deg);
            let mirror = Vec3::new(-wo.x, -wo.y, wo.z);
            let dirs = Directions::cap(mirror, 0.6)
                .resolution(61, 64)
                .refinement(1.5);
            let name = format!("rough-{}-0.05-{deg}", if ggx { "ggx" } else { "beckmann" });
            check(&name, &rough(ggx, 0.05), wo, dirs);
        }
    }
}

#[test]
fn environment_map_with_a_sun() {
    let (w, h) = (64, 32);
    let mut t = vec![Vec3::new(0.2, 0.3, 0.5); w * h];
    for y in 0..h / 2 {
        t[y * w + 10] = Vec3::splat(2.0);
    }
    t[6 * w + 40] = Vec3::splat(3000.0);
    let map = EnvMap::from_texels(w, h, t, Mat4::from_rotation_x(0.4)).expect("valid map");
    let out = chi2(Directions::sphere().resolution(64, 128), "envmap-sun")
        .run_weighted(|u| map.sample(u).map(|(d, _, _)| (d, 1.0)), |d| map.pdf(d));
    assert!(out.passed(), "{}", out.report());
}
