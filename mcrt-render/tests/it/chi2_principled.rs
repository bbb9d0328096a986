//! The principled BSDF's sampler against its density on the hemisphere, with the suite's
//! chi-square settings (`tests/common`: α = 0.01 family-wise over 400 runs, Šidák-corrected,
//! 10⁶ samples, fixed seed), the check that every sample's weight is `f · cos θ_i / pdf`
//! in each channel, and a white furnace: with `base_color` = 1 the directional albedo
//! `∫ f cos θ_i dω` stays at most 1 where the model conserves energy (see
//! `white_furnace`).
//!
//! With `spec_trans` > 0 the same on the whole sphere, seen from both sides
//! (`transmission_sampling_matches_density`).
//!
//! Cases: Mitsuba's defaults; a rough anisotropic metal; a smooth, strongly anisotropic
//! half-metal with specular tint; a glossy clearcoat over diffuse with sheen and
//! flatness; unequal sampling rates. Each seen from 0°, 45° and 80° at azimuth 40° (so the
//! anisotropic lobes are seen off their axes). The sampler takes a third value (the lobe),
//! a hash of the other two (`common::third_value`).

use crate::common;

use common::{check_bsdf_sampling, hemisphere, sphere, third_value};
use mcrt::glam::Vec3;
use mcrt::integrator::Bsdf;
use mcrt_render::bsdf::{Principled, PrincipledParams};

fn wo_at(deg: f32) -> Vec3 {
    let (t, p) = (deg.to_radians(), 40f32.to_radians());
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

fn cases() -> Vec<(&'static str, PrincipledParams)> {
    let d = PrincipledParams::default();
    vec![
        ("default", d),
        (
            "metal-anisotropic",
            PrincipledParams {
                base_color: Vec3::new(0.9, 0.6, 0.2),
                metallic: 1.0,
                roughness: 0.4,
                anisotropic: 0.8,
                ..d
            },
        ),
        (
            "smooth-half-metal",
            PrincipledParams {
                base_color: Vec3::new(0.2, 0.5, 0.9),
                metallic: 0.5,
                spec_tint: 0.7,
                roughness: 0.15,
                anisotropic: 1.0,
                ..d
            },
        ),
        (
            "clearcoat-sheen-flat",
            PrincipledParams {
                base_color: Vec3::new(0.1, 0.1, 0.5),
                clearcoat: 1.0,
                clearcoat_gloss: 0.8,
                sheen: 1.0,
                sheen_tint: 0.5,
                flatness: 0.5,
                roughness: 0.6,
                ..d
            },
        ),
        (
            "sampling-rates",
            PrincipledParams {
                clearcoat: 0.5,
                metallic: 0.3,
                diffuse_reflectance_sampling_rate: 0.3,
                main_specular_sampling_rate: 2.0,
                clearcoat_sampling_rate: 0.7,
                ..d
            },
        ),
    ]
}

fn check(name: &str, b: &Principled, wo: Vec3) {
    check_bsdf_sampling(name, b, wo, hemisphere(), |u| {
        b.sample(wo, third_value(u), u)
    });
}

#[test]
fn sampling_matches_density() {
    for (name, params) in cases() {
        let b = Principled::new(params).expect("valid parameters");
        for deg in [0.0, 45.0, 80.0] {
            check(&format!("principled-{name}-{deg}"), &b, wo_at(deg));
        }
    }
}

/// With `spec_trans` > 0 the sampler covers the sphere (reflection and refraction, from
/// either side): pure transmission at roughness 0.3, and a mixture with metal, clearcoat,
/// sheen and anisotropy at index 1.33; each from 20° and 70° above and below the surface.
#[test]
fn transmission_sampling_matches_density() {
    let d = PrincipledParams::default();
    let cases = [
        (
            "spec-trans",
            PrincipledParams {
                spec_trans: 1.0,
                roughness: 0.3,
                ..d
            },
        ),
        (
            "spec-trans-mixed",
            PrincipledParams {
                base_color: Vec3::new(0.8, 0.3, 0.1),
                spec_trans: 0.6,
                metallic: 0.2,
                clearcoat: 0.5,
                anisotropic: 0.5,
                eta: 1.33,
                sheen: 0.4,
                ..d
            },
        ),
    ];
    for (name, params) in cases {
        let b = Principled::new(params).expect("valid parameters");
        for deg in [20.0, 70.0, 110.0, 160.0] {
            let wo = wo_at(deg);
            check_bsdf_sampling(&format!("principled-{name}-{deg}"), &b, wo, sphere(), |u| {
                b.sample(wo, third_value(u), u)
            });
        }
    }
}

/// `∫ f cos θ_i dω` at `wo`, by the midpoint rule in (cos θ, φ) (deterministic).
fn albedo(b: &Principled, wo: Vec3) -> Vec3 {
    let (n_t, n_p) = (1024, 512);
    let mut sum = [0.0f64; 3];
    for i in 0..n_t {
        // cos θ = 1 − s², with s uniform, packs the cells toward the pole where lobes peak.
        let s = (i as f32 + 0.5) / n_t as f32;
        let c = 1.0 - s * s;
        let sin = (1.0 - c * c).max(0.0).sqrt();
        let dc = 2.0 * s / n_t as f32;
        for j in 0..n_p {
            let p = (j as f32 + 0.5) / n_p as f32 * std::f32::consts::TAU;
            let wi = Vec3::new(sin * p.cos(), sin * p.sin(), c);
            let f = b.eval(wo, wi) * (dc * std::f32::consts::TAU / n_p as f32);
            for k in 0..3 {
                sum[k] += f64::from(f[k]);
            }
        }
    }
    Vec3::new(sum[0] as f32, sum[1] as f32, sum[2] as f32)
}

/// A white metal (`metallic` = 1, `base_color` = 1, so Schlick's Fresnel is 1) reflects
/// at most what arrives: single-scattering GGX loses the energy of multiple bounces and
/// creates none, for any roughness and anisotropy. (The dielectric mixture does not obey
/// this bound: Burley's diffuse, sheen and specular lobes are added without coupling, so a
/// white default `principled` reflects up to about 1.2 at grazing angles, in Mitsuba 3 as
/// here; `tests/it/furnace.rs` compares that against Mitsuba's furnace value.)
#[test]
fn white_metal_conserves_energy() {
    let d = PrincipledParams::default();
    for (roughness, anisotropic) in [(0.3, 0.0), (0.5, 0.9), (1.0, 0.0), (1.0, 1.0)] {
        let b = Principled::new(PrincipledParams {
            base_color: Vec3::ONE,
            metallic: 1.0,
            roughness,
            anisotropic,
            ..d
        })
        .expect("valid parameters");
        for deg in [0.0, 30.0, 60.0, 80.0, 89.0] {
            let a = albedo(&b, wo_at(deg));
            assert!(
                a.is_finite() && a.max_element() <= 1.0 + 2e-3 && a.min_element() > 0.05,
                "roughness {roughness} anisotropic {anisotropic} at {deg}°: albedo {a}"
            );
        }
    }
}
