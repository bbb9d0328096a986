//! White furnace: a unit sphere under a constant environment of radiance 1, seen through a
//! narrow camera so that every pixel sees the sphere. A convex object there reflects the
//! environment scaled by its albedo: a Lambertian sphere returns ρ, a perfect mirror 1 and
//! lossless glass 1 (after every internal bounce; radiance scaled by 1/η² inside and back).
//!
//! Also analytic checks of the other light types: a uniform environment map (through its
//! importance sampling) and point, spot and directional lights over a diffuse plane.
//!
//! The coated and thin materials: a white plastic sphere (ρ = 1) returns 1, a thin glass
//! sphere 1, rough glass nearly 1 at α = 0.01; rough glass at α = 0.3 and white rough
//! plastic, which lose energy, what Mitsuba 3 returns in the same scene; a blend of white
//! materials and a mask over a white two-sided one return 1; white `principled` spheres
//! (one gains energy, one loses it) what Mitsuba 3 returns.
//!
//! Tolerance: the image mean must be within 4 standard errors (from the render's own
//! per-pixel variance) and within 1% of the expected value. Fixed seed; 32×32 pixels.

use mcrt::glam::{Mat4, Vec3};
use mcrt_render::description::*;
use mcrt_render::render::{RenderOptions, Renderer};
use std::sync::atomic::AtomicBool;

fn furnace(bsdf: BsdfDesc, spp: u32) -> (Vec3, Vec3) {
    furnace_with(
        bsdf,
        spp,
        EmitterDesc::Constant {
            radiance: mcrt_render::description::Colour::WHITE,
        },
    )
}

fn camera(from: Vec3, fov: f32, res: u32) -> SensorDesc {
    SensorDesc {
        fov,
        to_world: Mat4::look_at_rh(from, Vec3::ZERO, Vec3::Y).inverse()
            * Mat4::from_scale(Vec3::new(-1.0, 1.0, -1.0)),
        film: mcrt_render::description::Checked::new(FilmDesc {
            width: res,
            height: res,
            filter: FilterDesc::Box,
            crop: None,
        })
        .unwrap(),
        ..SensorDesc::default()
    }
}

fn render(desc: &SceneDescription, spp: u32) -> (Vec3, Vec3) {
    let opts = RenderOptions {
        spp: Some(spp),
        seed: Some(7),
        ..RenderOptions::default()
    };
    let r = Renderer::new(desc, &opts).expect("scene builds");
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

fn furnace_with(bsdf: BsdfDesc, spp: u32, env: EmitterDesc) -> (Vec3, Vec3) {
    let mut sphere = ShapeDesc::new(ShapeKind::Sphere {
        center: Vec3::ZERO,
        radius: 1.0,
    });
    sphere.bsdf = bsdf;
    let desc = SceneDescription {
        integrator: mcrt_render::description::Checked::new(IntegratorDesc::Path(
            mcrt_render::description::PathParams {
                max_depth: -1,
                rr_depth: 5,
                ..Default::default()
            },
        ))
        .unwrap(),
        sensor: mcrt_render::description::Checked::new(camera(Vec3::new(0.0, 0.0, 5.0), 8.0, 32))
            .unwrap(),
        shapes: vec![sphere]
            .into_iter()
            .map(|x| mcrt_render::description::Checked::new(x).unwrap())
            .collect(),
        emitters: vec![env]
            .into_iter()
            .map(|x| mcrt_render::description::Checked::new(x).unwrap())
            .collect(),
        source: None,
        ..SceneDescription::default()
    };
    render(&desc, spp)
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

/// A furnace mean `(m, se)` against Mitsuba 3's value `want ± want_se` for the same sphere:
/// per channel, finite, within 4 combined standard errors and within 1 %.
fn check_against_mitsuba(name: &str, (m, se): (Vec3, Vec3), want: f32, want_se: f32) {
    for c in 0..3 {
        let err = (m[c] - want).abs();
        let bound = 4.0 * (se[c] * se[c] + want_se * want_se).sqrt();
        assert!(
            m[c].is_finite() && se[c].is_finite() && err <= bound && err <= 0.01 * want,
            "{name}: channel {c}: {m} ± {se}, Mitsuba {want} ± {want_se}"
        );
    }
}

#[test]
fn diffuse_sphere_returns_its_albedo() {
    let rho = Vec3::new(0.2, 0.5, 0.8);
    check(
        "diffuse",
        furnace(
            BsdfDesc::Diffuse {
                reflectance: mcrt_render::description::Colour::new(rho).unwrap(),
            },
            64,
        ),
        rho,
    );
}

#[test]
fn mirror_sphere_returns_one() {
    let b = BsdfDesc::Conductor {
        fresnel: ConductorFresnel::Perfect,
        specular_reflectance: mcrt_render::description::Colour::WHITE,
    };
    check("mirror", furnace(b, 4), Vec3::ONE);
}

#[test]
fn glass_sphere_returns_one() {
    let b = BsdfDesc::Dielectric {
        int_ior: mcrt_render::description::Ior::new(1.5).unwrap(),
        ext_ior: mcrt_render::description::Ior::new(1.0).unwrap(),
        specular_reflectance: mcrt_render::description::Colour::WHITE,
        specular_transmittance: mcrt_render::description::Colour::WHITE,
    };
    check("glass", furnace(b, 64), Vec3::ONE);
}

#[test]
fn diffuse_sphere_under_a_uniform_envmap_returns_its_albedo() {
    // A uniform map exercises the map's importance sampling and MIS with its pdf.
    let dir = std::env::temp_dir().join(format!("mcrt-furnace-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("white.exr");
    mcrt_render::film::write_exr(&path, 16, 8, &[Vec3::ONE; 128]).expect("write map");
    let rho = Vec3::new(0.2, 0.5, 0.8);
    let env = EmitterDesc::EnvMap {
        filename: path,
        scale: 1.0,
        to_world: Mat4::IDENTITY,
    };
    let got = furnace_with(
        BsdfDesc::Diffuse {
            reflectance: mcrt_render::description::Colour::new(rho).unwrap(),
        },
        64,
        env,
    );
    std::fs::remove_dir_all(&dir).ok();
    check("diffuse under envmap", got, rho);
}

/// The albedo of the plane tests' diffuse floor.
const PLANE_RHO: Vec3 = Vec3::new(0.3, 0.5, 0.7);

/// The mean of a 16 × 16 render, 4 spp, of the diffuse floor seen from (0, 0, 5) under one
/// light, checked finite and within 0.1 % of `want` per channel.
fn check_lit_plane(light: EmitterDesc, integrator: IntegratorDesc, want: Vec3) {
    let mut floor = ShapeDesc::new(ShapeKind::Rectangle);
    floor.to_world = Mat4::from_scale(Vec3::splat(10.0));
    floor.bsdf = BsdfDesc::Diffuse {
        reflectance: mcrt_render::description::Colour::new(PLANE_RHO).unwrap(),
    };
    let desc = SceneDescription {
        integrator: mcrt_render::description::Checked::new(integrator).unwrap(),
        sensor: mcrt_render::description::Checked::new(camera(Vec3::new(0.0, 0.0, 5.0), 0.45, 16))
            .unwrap(),
        shapes: vec![floor]
            .into_iter()
            .map(|x| mcrt_render::description::Checked::new(x).unwrap())
            .collect(),
        emitters: vec![light.clone()]
            .into_iter()
            .map(|x| mcrt_render::description::Checked::new(x).unwrap())
            .collect(),
        source: None,
        ..SceneDescription::default()
    };
    let (m, _) = render(&desc, 4);
    for c in 0..3 {
        assert!(
            m[c].is_finite() && (m[c] / want[c] - 1.0).abs() < 1e-3,
            "{integrator:?}, {light:?}: {m} vs {want}"
        );
    }
}

#[test]
fn point_light_over_a_diffuse_plane() {
    // Radiance ρ/π · I cos θ / d² with d = 1 right under the light; the camera sees a disk
    // of radius 0.02 around that point, where cos θ / d² > 0.9994.
    let light = EmitterDesc::Point {
        position: Vec3::new(0.0, 0.0, 1.0),
        intensity: mcrt_render::description::Colour::WHITE,
    };
    let path = IntegratorDesc::Path(mcrt_render::description::PathParams {
        max_depth: 2,
        rr_depth: 5,
        ..Default::default()
    });
    check_lit_plane(light, path, PLANE_RHO / std::f32::consts::PI);
}

/// A directional light at angle θ to a diffuse plane gives irradiance `E cos θ` (the
/// radiance `ρ/π · E cos θ` everywhere, with no falloff); a spot light straight above gives
/// `ρ/π · I f(0) / d²` under it, its full intensity inside the beam. Path and direct.
#[test]
fn directional_and_spot_lights_over_a_diffuse_plane() {
    let theta = 50f32.to_radians();
    let lights = [
        (
            EmitterDesc::Directional {
                irradiance: mcrt_render::description::Colour::new(Vec3::splat(2.0)).unwrap(),
                direction: Vec3::new(theta.sin(), 0.0, -theta.cos()),
            },
            2.0 * theta.cos(),
        ),
        (
            EmitterDesc::Spot {
                intensity: mcrt_render::description::Colour::new(Vec3::splat(3.0)).unwrap(),
                cutoff_angle: 20.0,
                beam_width: 15.0,
                to_world: Mat4::from_translation(Vec3::new(0.0, 0.0, 2.0))
                    * Mat4::from_rotation_x(std::f32::consts::PI),
            },
            3.0 / 4.0,
        ),
    ];
    let integrators = [
        IntegratorDesc::Path(mcrt_render::description::PathParams {
            max_depth: 2,
            rr_depth: 5,
            ..Default::default()
        }),
        IntegratorDesc::Direct(mcrt_render::description::DirectParams {
            emitter_samples: 1,
            bsdf_samples: 1,
            ..Default::default()
        }),
    ];
    for ((light, irradiance), integrator) in lights
        .iter()
        .flat_map(|l| integrators.iter().map(move |i| (l.clone(), *i)))
    {
        let want = PLANE_RHO / std::f32::consts::PI * irradiance;
        check_lit_plane(light, integrator, want);
    }
}

#[test]
fn white_plastic_sphere_returns_one() {
    // ρ = 1 under the coating: what the coating does not reflect enters, and the internal
    // scattering term returns all of it, so the albedo is 1 up to the fits of the
    // coating's diffuse reflectances (0.12% for η = 1.49; docs/bsdf-models.md, "Plastic").
    for nonlinear in [false, true] {
        let b = BsdfDesc::Plastic {
            int_ior: mcrt_render::description::Ior::new(1.49).unwrap(),
            ext_ior: mcrt_render::description::Ior::new(1.000277).unwrap(),
            diffuse_reflectance: mcrt_render::description::Colour::WHITE,
            specular_reflectance: mcrt_render::description::Colour::WHITE,
            nonlinear,
        };
        check("white plastic", furnace(b, 64), Vec3::ONE);
    }
}

#[test]
fn thin_glass_sphere_returns_one() {
    let b = BsdfDesc::ThinDielectric {
        int_ior: mcrt_render::description::Ior::new(1.5).unwrap(),
        ext_ior: mcrt_render::description::Ior::new(1.0).unwrap(),
        specular_reflectance: mcrt_render::description::Colour::WHITE,
        specular_transmittance: mcrt_render::description::Colour::WHITE,
    };
    check("thin glass", furnace(b, 16), Vec3::ONE);
}

fn rough_glass(alpha: f32) -> BsdfDesc {
    BsdfDesc::RoughDielectric {
        microfacet: Microfacet::new(
            MicrofacetKind::Ggx,
            Roughness::new(alpha).expect("a roughness"),
        ),
        int_ior: mcrt_render::description::Ior::new(1.5).unwrap(),
        ext_ior: mcrt_render::description::Ior::new(1.0).unwrap(),
        specular_reflectance: mcrt_render::description::Colour::WHITE,
        specular_transmittance: mcrt_render::description::Colour::WHITE,
    }
}

#[test]
fn nearly_smooth_rough_glass_sphere_returns_one() {
    // At α = 0.01 the microfacet model's single-scattering loss is below 0.1%.
    check(
        "rough glass α = 0.01",
        furnace(rough_glass(0.01), 64),
        Vec3::ONE,
    );
}

/// Furnace values of materials that lose energy, as Mitsuba 3.9.1 renders the same scene
/// (`scripts/mitsuba_furnace.py`, 16384 spp, with its standard error): rough glass, and
/// rough plastic, whose coating model is single-scattering too.
#[test]
fn lossy_spheres_return_what_mitsuba_returns() {
    let rough_plastic = |distribution, alpha| BsdfDesc::RoughPlastic {
        microfacet: Microfacet::new(distribution, Roughness::new(alpha).expect("a roughness")),
        int_ior: mcrt_render::description::Ior::new(1.49).unwrap(),
        ext_ior: mcrt_render::description::Ior::new(1.000277).unwrap(),
        diffuse_reflectance: mcrt_render::description::Colour::WHITE,
        specular_reflectance: mcrt_render::description::Colour::WHITE,
        nonlinear: false,
    };
    let cases = [
        (
            "rough glass, GGX α = 0.3",
            rough_glass(0.3),
            0.85456,
            0.0001,
        ),
        (
            "white rough plastic, Beckmann α = 0.1",
            rough_plastic(MicrofacetKind::Beckmann, 0.1),
            0.96797,
            0.00007,
        ),
        (
            "white rough plastic, GGX α = 0.3",
            rough_plastic(MicrofacetKind::Ggx, 0.3),
            0.69356,
            0.00005,
        ),
    ];
    for (name, b, want, want_se) in cases {
        check_against_mitsuba(name, furnace(b, 64), want, want_se);
    }
}

#[test]
fn blend_and_mask_of_lossless_materials_return_one() {
    let white = BsdfDesc::Diffuse {
        reflectance: mcrt_render::description::Colour::WHITE,
    };
    let blend = BsdfDesc::Blend {
        weight: 0.4,
        first: Box::new(white.clone()),
        second: Box::new(BsdfDesc::Plastic {
            int_ior: mcrt_render::description::Ior::new(1.49).unwrap(),
            ext_ior: mcrt_render::description::Ior::new(1.000277).unwrap(),
            diffuse_reflectance: mcrt_render::description::Colour::WHITE,
            specular_reflectance: mcrt_render::description::Colour::WHITE,
            nonlinear: false,
        }),
    };
    check("blend of white materials", furnace(blend, 64), Vec3::ONE);
    // Two-sided, so that light that passed the front is reflected by the back from inside.
    let mask = BsdfDesc::Mask {
        opacity: 0.3,
        inner: Box::new(BsdfDesc::TwoSided(Box::new(white))),
    };
    check("mask over white", furnace(mask, 64), Vec3::ONE);
}

/// Furnace values of white `principled` spheres as Mitsuba 3.9.1 renders the same scene
/// (`scripts/mitsuba_furnace.py --only principled`, 16384 spp, with its standard error):
/// Mitsuba's defaults with `base_color` = 1, which reflect more than they receive (the
/// Disney diffuse, retro-reflection and specular lobes are summed without coupling), a
/// white rough anisotropic metal, which loses energy (single-scattering GGX), and a white
/// sphere with `spec_trans` 0.8 at roughness 0.3, which refracts light through it.
#[test]
fn principled_spheres_return_what_mitsuba_returns() {
    let white = PrincipledParams {
        base_color: Vec3::ONE,
        ..PrincipledParams::default()
    };
    let metal = PrincipledParams {
        metallic: 1.0,
        roughness: 0.4,
        anisotropic: 0.8,
        ..white
    };
    let glass = PrincipledParams {
        spec_trans: 0.8,
        roughness: 0.3,
        ..white
    };
    let cases = [
        ("white principled", white, 1.04312, 0.00009),
        (
            "white principled with spec_trans 0.8",
            glass,
            0.83771,
            0.00011,
        ),
        (
            "white anisotropic principled metal",
            metal,
            0.92978,
            0.00008,
        ),
    ];
    for (name, p, want, want_se) in cases {
        check_against_mitsuba(name, furnace(BsdfDesc::Principled(p), 64), want, want_se);
    }
}
