//! On a scene without delta components every strategy (BSDF sampling only, light sampling
//! only, MIS with the balance and with the power heuristic) converges to the same image.
//! Each strategy's render is compared with the power-heuristic render by 8×8 block means:
//! a z-test using both renders' own variances, Šidák-corrected over blocks and channels
//! (family-wise α = 10⁻³ per comparison), and no NaN or infinite pixel. Fixed seeds.

use mcrt::integrator::Strategy;
use mcrt::scene::description::{IntegratorDesc, SceneDescription};
use mcrt::scene::film::compare_blocks;
use mcrt::scene::render::{RenderOptions, Renderer};
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
        let r = compare_blocks(&img, &var, &base, Some(&base_var), w, h, 8, 0.05, 1e-3);
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

#[test]
fn cornell_box_strategies_agree() {
    let desc = mcrt::scene::cornell_box::cornell_box_with(64, 64, -1);
    all_agree(&desc, 64);
}

#[test]
fn cornell_box_direct_strategies_agree() {
    let mut desc = mcrt::scene::cornell_box::cornell_box_with(64, 64, -1);
    desc.integrator = IntegratorDesc::Direct {
        emitter_samples: 2,
        bsdf_samples: 1,
    };
    all_agree(&desc, 64);
}
