//! On a scene without delta components every strategy (BSDF sampling only, light sampling
//! only, MIS with the balance and with the power heuristic) converges to the same image.
//! Each strategy's render is compared with the power-heuristic render by 8×8 block means:
//! a z-test using both renders' own variances, Šidák-corrected over blocks and channels
//! (each comparison one test of the suite's budget, `tests/it/common/suite.rs`: family-wise
//! α = 2.513·10⁻⁵ per comparison), and no NaN or infinite pixel. Fixed seeds.

use crate::common;

use mcrt::glam::{Mat4, Vec3};
use mcrt::integrator::Strategy;
use mcrt_render::description::{
    BsdfDesc, ConductorFresnel, IntegratorDesc, Microfacet, MicrofacetKind, Roughness,
    SceneDescription,
};
use mcrt_render::film::compare_blocks;
use mcrt_render::render::{RenderOptions, Renderer};
use std::sync::atomic::AtomicBool;

fn render(
    desc: &SceneDescription,
    s: Strategy,
    spp: u32,
    seed: u64,
) -> (Vec<mcrt::glam::Vec3>, Vec<mcrt::glam::Vec3>) {
    let opts = RenderOptions {
        spp: Some(spp),
        seed: Some(seed),
        strategy: Some(s),
        ..RenderOptions::default()
    };
    let out = Renderer::new(desc, &opts)
        .expect("scene builds")
        .render(&|_, _| {}, &AtomicBool::new(false));
    (out.image(), out.film.variance())
}

fn all_agree(desc: &SceneDescription, spp: u32) {
    let (w, h) = (desc.sensor.film.width, desc.sensor.film.height);
    let (base, base_var) = render(desc, Strategy::MisPower, spp, 1);
    for (k, s) in [
        Strategy::BsdfOnly,
        Strategy::LightOnly,
        Strategy::MisBalance,
    ]
    .into_iter()
    .enumerate()
    {
        let (img, var) = render(desc, s, spp, 2 + k as u64);
        let r = compare_blocks(
            &img,
            &var,
            &base,
            Some(&base_var),
            w,
            h,
            8,
            0.05,
            common::per_test_alpha(),
        );
        assert_eq!(r.non_finite, 0, "{s:?}");
        assert!(r.blocks > 10, "{s:?}: only {} blocks", r.blocks);
        assert!(
            r.z_test_passes(),
            "{s:?} differs from MIS power: worst |z| {:.2} > {:.2}, worst block {:.2}%",
            r.worst_z,
            r.z_critical,
            100.0 * r.worst_relative
        );
    }
}

/// The Cornell box at 64×64 with a light three times wider and deeper (so that BSDF
/// sampling alone finds it often enough for its variance estimate to be trusted at 64 spp;
/// with the original light the BSDF-only estimate is heavy-tailed and needs thousands of
/// spp) and a rough GGX conductor on the tall box (so glossy MIS is exercised too).
fn test_box(max_depth: i32) -> SceneDescription {
    let mut desc = mcrt_render::cornell_box::cornell_box_with(64, 64, max_depth);
    for s in &mut desc.shapes {
        if s.emitter.is_some() {
            *s = s
                .clone()
                .changed(|l| l.to_world *= Mat4::from_scale(Vec3::new(3.0, 3.0, 1.0)))
                .expect("the wider light");
        } else if s.id.as_deref() == Some("large-box") {
            *s = s
                .clone()
                .changed(|tall| {
                    tall.bsdf = BsdfDesc::RoughConductor {
                        microfacet: Microfacet::new(
                            MicrofacetKind::Ggx,
                            Roughness::new(0.3).expect("a roughness"),
                        ),
                        fresnel: ConductorFresnel::Perfect,
                        specular_reflectance: mcrt_render::description::Colour::new(Vec3::splat(
                            0.8,
                        ))
                        .unwrap(),
                    }
                })
                .expect("a rough conductor");
        }
    }
    desc
}

#[test]
fn cornell_box_strategies_agree() {
    all_agree(&test_box(-1), 64);
}

#[test]
fn cornell_box_direct_strategies_agree() {
    let mut desc = test_box(-1);
    desc.integrator = mcrt_render::description::Checked::new(IntegratorDesc::Direct(
        mcrt_render::description::DirectParams {
            emitter_samples: 2,
            bsdf_samples: 1,
            ..Default::default()
        },
    ))
    .unwrap();
    all_agree(&desc, 64);
}

#[test]
fn direct_integrator_equals_path_tracer_with_max_depth_2() {
    let path = test_box(2);
    let mut direct = test_box(2);
    direct.integrator = mcrt_render::description::Checked::new(IntegratorDesc::Direct(
        mcrt_render::description::DirectParams {
            emitter_samples: 1,
            bsdf_samples: 1,
            ..Default::default()
        },
    ))
    .unwrap();
    let (w, h) = (path.sensor.film.width, path.sensor.film.height);
    let (a, va) = render(&path, Strategy::MisPower, 64, 11);
    let (b, vb) = render(&direct, Strategy::MisPower, 64, 12);
    let r = compare_blocks(
        &a,
        &va,
        &b,
        Some(&vb),
        w,
        h,
        8,
        0.05,
        common::per_test_alpha(),
    );
    assert_eq!(r.non_finite, 0);
    assert!(
        r.z_test_passes(),
        "direct vs path(max_depth 2): worst |z| {:.2} > {:.2}",
        r.worst_z,
        r.z_critical
    );
}
