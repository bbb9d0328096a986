//! White furnace: a unit sphere under a constant environment of radiance 1, seen through a
//! narrow camera so that every pixel sees the sphere. A convex object there reflects the
//! environment scaled by its albedo: a Lambertian sphere returns ρ, a perfect mirror 1 and
//! lossless glass 1 (after every internal bounce; radiance scaled by 1/η² inside and back).
//!
//! Tolerance: the image mean must be within 4 standard errors (from the render's own
//! per-pixel variance) and within 1% of the expected value. Fixed seed; 32×32 pixels.

use mcrt::glam::{Mat4, Vec3};
use mcrt::scene::description::*;
use mcrt::scene::render::{RenderOptions, Renderer};
use std::sync::atomic::AtomicBool;

fn furnace(bsdf: BsdfDesc, spp: u32) -> (Vec3, Vec3) {
    let mut sphere = ShapeDesc::new(ShapeKind::Sphere {
        center: Vec3::ZERO,
        radius: 1.0,
    });
    sphere.bsdf = bsdf;
    let desc = SceneDescription {
        integrator: IntegratorDesc::Path {
            max_depth: -1,
            rr_depth: 5,
        },
        sensor: SensorDesc {
            fov: 8.0,
            to_world: Mat4::look_at_rh(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y).inverse()
                * Mat4::from_scale(Vec3::new(-1.0, 1.0, -1.0)),
            film: FilmDesc {
                width: 32,
                height: 32,
                filter: FilterDesc::Box,
            },
            ..SensorDesc::default()
        },
        shapes: vec![sphere],
        emitters: vec![EmitterDesc::Constant {
            radiance: Vec3::ONE,
        }],
        source: None,
    };
    let opts = RenderOptions {
        spp: Some(spp),
        seed: Some(7),
        ..RenderOptions::default()
    };
    let r = Renderer::new(&desc, &opts).expect("scene builds");
    let out = r.render(&|_, _| {}, &AtomicBool::new(false));
    let img = out.image();
    let var = out.film.variance();
    let n = img.len() as f32;
    let mean = img.iter().copied().sum::<Vec3>() / n;
    // Pixels are independent: the variance of the image mean is the mean variance / n.
    let var_mean = var.iter().copied().sum::<Vec3>() / (n * n);
    (
        mean,
        Vec3::new(var_mean.x.sqrt(), var_mean.y.sqrt(), var_mean.z.sqrt()),
    )
}

fn check(name: &str, got: (Vec3, Vec3), want: Vec3) {
    let (m, se) = got;
    for c in 0..3 {
        assert!(m[c].is_finite() && se[c].is_finite(), "{name}: {m} ± {se}");
        let err = (m[c] - want[c]).abs();
        assert!(
            err <= 4.0 * se[c] + 1e-6 && err <= 0.01 * want[c],
            "{name}: channel {c}: {} vs {} (standard error {})",
            m[c],
            want[c],
            se[c]
        );
    }
}

#[test]
fn diffuse_sphere_returns_its_albedo() {
    let rho = Vec3::new(0.2, 0.5, 0.8);
    check(
        "diffuse",
        furnace(BsdfDesc::Diffuse { reflectance: rho }, 64),
        rho,
    );
}

#[test]
fn mirror_sphere_returns_one() {
    let b = BsdfDesc::Conductor {
        fresnel: ConductorFresnel::Perfect,
        specular_reflectance: Vec3::ONE,
    };
    check("mirror", furnace(b, 4), Vec3::ONE);
}

#[test]
fn glass_sphere_returns_one() {
    let b = BsdfDesc::Dielectric {
        int_ior: 1.5,
        ext_ior: 1.0,
        specular_reflectance: Vec3::ONE,
        specular_transmittance: Vec3::ONE,
    };
    check("glass", furnace(b, 64), Vec3::ONE);
}
