//! The bidirectional estimators' multiple-importance weights on the built-in scene: for
//! random paths of random scenes (diffuse, glass, mirror; smooth plastic, rough glass and a
//! mask, whose vertices may scatter by a Dirac part or by a density; area, point and
//! environment lights; a pinhole and a thin lens), the weights of every strategy that can
//! make a path sum to 1, and the weight the estimator computes from its own subpaths equals
//! the one recomputed from scratch.
//!
//! Through the public diagnostic `mcrt::integrator::Bdpt::check_mis_weights` (via
//! `Renderer::check_mis_weights`, which hands it the renderer's scene): 400 camera and light
//! subpaths of at most 7 vertices each per scene, seed 17, the power heuristic;
//! `|Σ w − 1| < 2·10⁻³` for every path, `|w_estimator − w| ≤ 10⁻³ + 10⁻² w` for every path
//! whose segments are all longer than 2.5% of the box (0.05), and more than 1000 paths
//! compared in all.

use mcrt::glam::Vec3;
use mcrt::integrator::{Bdpt, MisWeightCheck, Strategy};
use mcrt_render::description::{
    BsdfDesc, ConductorFresnel, EmitterDesc, Microfacet, MicrofacetKind, Roughness,
    SceneDescription, ShapeDesc, ShapeKind, ThinLensDesc,
};
use mcrt_render::render::{RenderOptions, Renderer};

fn scenes() -> Vec<(&'static str, SceneDescription)> {
    let cornell = mcrt_render::cornell_box::cornell_box_with(4, 32, -1);
    let caustic = mcrt_render::loader::load_scene(
        &std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data/cornell-box-caustic.xml"),
        &[("res".into(), "32".into())],
    )
    .expect("caustic scene loads");
    let mut mixed = cornell.clone();
    let mut mirror = ShapeDesc::new(ShapeKind::Sphere {
        center: Vec3::new(-0.4, -0.6, 0.2),
        radius: 0.25,
    });
    mirror.bsdf = BsdfDesc::Conductor {
        fresnel: ConductorFresnel::Perfect,
        specular_reflectance: mcrt_render::description::Colour::WHITE,
    };
    mixed
        .shapes
        .push(mcrt_render::description::Checked::new(mirror).unwrap());
    mixed.emitters.push(
        mcrt_render::description::Checked::new(EmitterDesc::Point {
            position: Vec3::new(0.3, 0.5, 0.4),
            intensity: mcrt_render::description::Colour::new(Vec3::splat(0.5)).unwrap(),
        })
        .unwrap(),
    );
    // An open box would let rays escape; a dim environment is still sampled and hit by the
    // camera paths that leave through the open front.
    mixed.emitters.push(
        mcrt_render::description::Checked::new(EmitterDesc::Constant {
            radiance: mcrt_render::description::Colour::new(Vec3::splat(0.2)).unwrap(),
        })
        .unwrap(),
    );
    let mut materials = cornell.clone();
    let sphere = |x: f32, bsdf: BsdfDesc| {
        let mut s = ShapeDesc::new(ShapeKind::Sphere {
            center: Vec3::new(x, -0.7, 0.1),
            radius: 0.25,
        });
        s.bsdf = bsdf;
        s
    };
    materials.shapes.push(
        mcrt_render::description::Checked::new(sphere(
            -0.5,
            BsdfDesc::Plastic {
                int_ior: mcrt_render::description::Ior::new(1.49).unwrap(),
                ext_ior: mcrt_render::description::Ior::new(1.0).unwrap(),
                diffuse_reflectance: mcrt_render::description::Colour::new(Vec3::new(
                    0.8, 0.4, 0.1,
                ))
                .unwrap(),
                specular_reflectance: mcrt_render::description::Colour::WHITE,
                nonlinear: false,
            },
        ))
        .unwrap(),
    );
    materials.shapes.push(
        mcrt_render::description::Checked::new(sphere(
            0.0,
            BsdfDesc::RoughDielectric {
                microfacet: Microfacet::new(
                    MicrofacetKind::Ggx,
                    Roughness::new(0.3).expect("a roughness"),
                ),
                int_ior: mcrt_render::description::Ior::new(1.5).unwrap(),
                ext_ior: mcrt_render::description::Ior::new(1.0).unwrap(),
                specular_reflectance: mcrt_render::description::Colour::WHITE,
                specular_transmittance: mcrt_render::description::Colour::WHITE,
            },
        ))
        .unwrap(),
    );
    materials.shapes.push(
        mcrt_render::description::Checked::new(sphere(
            0.5,
            BsdfDesc::Mask {
                opacity: 0.5,
                inner: Box::new(BsdfDesc::TwoSided(Box::new(BsdfDesc::Diffuse {
                    reflectance: mcrt_render::description::Colour::new(Vec3::splat(0.6)).unwrap(),
                }))),
            },
        ))
        .unwrap(),
    );
    // A thin lens: the camera vertex is a point on the aperture, not the pinhole.
    let mut lens = mixed.clone();
    lens.sensor = lens
        .sensor
        .clone()
        .changed(|s| {
            s.lens = Some(ThinLensDesc {
                aperture_radius: 0.2,
                focus_distance: 2.5,
            })
        })
        .unwrap();
    vec![
        ("cornell", cornell),
        ("caustic", caustic),
        ("lens", lens),
        ("mixed", mixed),
        ("materials", materials),
    ]
}

#[test]
fn weights_of_all_strategies_sum_to_one() {
    let check = MisWeightCheck {
        paths: 400,
        seed: 17,
        max_vertices: 7,
        sum_tolerance: 2e-3,
        weight_tolerance: 1e-3,
        weight_relative_tolerance: 1e-2,
        min_segment: 0.05,
    };
    let bdpt = Bdpt {
        strategy: Strategy::MisPower,
        ..Bdpt::default()
    };
    let mut checked = 0;
    for (name, desc) in scenes() {
        let r = Renderer::new(&desc, &RenderOptions::default()).expect("scene builds");
        let outcome = r.check_mis_weights(&bdpt, &check);
        assert!(outcome.passed(), "{name}: {}", outcome.report());
        checked += outcome.compared;
    }
    assert!(checked > 1000, "only {checked} paths checked");
}
