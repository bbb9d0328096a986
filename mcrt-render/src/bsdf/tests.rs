use super::*;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

fn lcg(state: &mut u64) -> f32 {
    *state = state
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    ((*state >> 40) as f32) / (1u64 << 24) as f32
}

fn smooth_bsdfs() -> Vec<Sided<AnyBsdf>> {
    let rc = |ggx, alpha, fresnel| {
        AnyBsdf::RoughConductor(
            RoughConductor::new(ggx, alpha, fresnel, Vec3::ONE).expect("valid alpha"),
        )
    };
    let gold = Fresnel::Complex {
        eta: Vec3::new(0.143, 0.374, 1.442),
        k: Vec3::new(3.98, 2.38, 1.6),
    };
    let list = [
        AnyBsdf::Diffuse(Diffuse {
            reflectance: Vec3::new(0.8, 0.5, 0.2),
        }),
        rc(true, 0.1, Fresnel::Perfect),
        rc(true, 0.5, gold),
        rc(false, 0.2, Fresnel::Perfect),
        rc(false, 0.6, gold),
    ];
    let mut v: Vec<_> = list
        .iter()
        .map(|bsdf| Sided {
            bsdf: bsdf.clone(),
            two_sided: false,
        })
        .collect();
    v.push(Sided {
        bsdf: list[1].clone(),
        two_sided: true,
    });
    v
}

fn wo_list() -> Vec<Vec3> {
    [0.05f32, 0.4, 1.0, 1.5]
        .iter()
        .map(|&t| Vec3::new(t.sin(), 0.0, t.cos()))
        .collect()
}

#[test]
fn sample_weight_is_eval_over_pdf() {
    let mut s = 7u64;
    for b in smooth_bsdfs() {
        for wo in wo_list() {
            for _ in 0..2000 {
                let u = Vec2::new(lcg(&mut s), lcg(&mut s));
                let Some(bs) = b.sample(wo, lcg(&mut s), u) else {
                    continue;
                };
                let (f, pdf) = b.eval_pdf(wo, bs.wi);
                assert!(bs.weight.is_finite() && bs.pdf.is_finite() && pdf.is_finite());
                assert!(
                    (pdf - bs.pdf).abs() <= 1e-3 * pdf.max(1.0),
                    "{b:?} {wo} {pdf} {}",
                    bs.pdf
                );
                let want = f / pdf;
                assert!(
                    (bs.weight - want).abs().max_element() <= 1e-3 * want.max_element().max(1.0),
                    "{b:?} {wo}: {} vs {want}",
                    bs.weight
                );
            }
        }
    }
}

#[test]
fn pdf_integrates_to_at_most_one() {
    let (nt, np) = (512usize, 512usize);
    for b in smooth_bsdfs() {
        for wo in wo_list() {
            let mut sum = 0.0f64;
            for i in 0..nt {
                let theta = (i as f32 + 0.5) * PI / nt as f32;
                let (st, ct) = theta.sin_cos();
                for j in 0..np {
                    let phi = (j as f32 + 0.5) * 2.0 * PI / np as f32;
                    let wi = Vec3::new(st * phi.cos(), st * phi.sin(), ct);
                    sum += (b.pdf(wo, wi) * st) as f64;
                }
            }
            let integral = sum * (PI as f64 / nt as f64) * (2.0 * PI as f64 / np as f64);
            assert!(
                integral.is_finite() && integral <= 1.01,
                "{b:?} {wo}: {integral}"
            );
            if wo.z > 0.3 {
                // Rough lobes lose the reflections that fall below the horizon (GGX α = 0.5:
                // 20% at normal incidence; more for Beckmann sampled without visible normals).
                assert!(integral > 0.6, "{b:?} {wo}: {integral}");
            }
        }
    }
}

#[test]
fn one_sided_is_black_from_behind_and_twosided_is_not() {
    let d = Diffuse {
        reflectance: Vec3::splat(0.5),
    };
    let below = Vec3::new(0.0, 0.6, -0.8);
    let one = Sided {
        bsdf: AnyBsdf::Diffuse(d),
        two_sided: false,
    };
    let two = Sided {
        two_sided: true,
        ..one.clone()
    };
    assert_eq!(one.eval(below, below), Vec3::ZERO);
    assert!(one.sample(below, 0.5, Vec2::splat(0.5)).is_none());
    let v = two.eval(below, Vec3::new(0.0, 0.0, -1.0));
    assert!(v.is_finite() && (v.x - 0.5 / PI).abs() < 1e-6);
    let s = two.sample(below, 0.5, Vec2::splat(0.3)).expect("sample");
    assert!(s.wi.z < 0.0);
}

#[test]
fn from_desc_reads_twosided_and_ior() {
    let desc = crate::description::BsdfDesc::TwoSided(Box::new(
        crate::description::BsdfDesc::Dielectric {
            int_ior: crate::description::Ior::new(1.5).unwrap(),
            ext_ior: crate::description::Ior::new(1.0).unwrap(),
            specular_reflectance: crate::description::Colour::WHITE,
            specular_transmittance: crate::description::Colour::WHITE,
        },
    ));
    let s = AnyBsdf::from_desc(&desc).expect("valid");
    assert!(!s.two_sided, "a dielectric is not mirrored");
    match s.bsdf {
        AnyBsdf::Dielectric(d) => assert_eq!(d.eta, 1.5),
        other => panic!("wrong material {other:?}"),
    }
}

/// Only smooth glass chooses a component with `u1`; the estimators skip drawing it for the
/// others, so those must really ignore it.
#[test]
fn only_dielectric_reads_u1() {
    let glass = Sided {
        bsdf: AnyBsdf::Dielectric(Dielectric {
            eta: 1.5,
            specular_reflectance: Vec3::ONE,
            specular_transmittance: Vec3::ONE,
        }),
        two_sided: false,
    };
    assert!(glass.samples_component());
    let mut bsdfs = smooth_bsdfs();
    bsdfs.push(Sided {
        bsdf: AnyBsdf::Conductor(Conductor {
            fresnel: Fresnel::Perfect,
            specular_reflectance: Vec3::ONE,
        }),
        two_sided: true,
    });
    let mut state = 7u64;
    for b in bsdfs {
        assert!(!b.samples_component(), "{b:?}");
        for _ in 0..50 {
            let wo = Vec3::new(lcg(&mut state) - 0.5, lcg(&mut state) - 0.5, 0.3).normalize();
            let u2 = Vec2::new(lcg(&mut state), lcg(&mut state));
            let a = b.sample(wo, 0.01, u2);
            let c = b.sample(wo, 0.99, u2);
            assert_eq!(a, c, "{b:?}: the result depends on u1");
        }
    }
}
