//! The estimators on a scene of someone else's: a renderer with its own geometry (one
//! analytic sphere), its own Lambertian BSDF and its own lights implements
//! `integrator::Scene` and `integrator::Bsdf` and uses `PathTracer` and `DirectIntegrator`
//! without the crate's scene module.
//!
//! - White furnace: a convex Lambertian object under uniform radiance 1 (an environment)
//!   returns its albedo, with every strategy.
//! - The glowing sphere of `examples/custom_scene.rs` (this file includes it): an area light
//!   and no environment or point lights, so it relies on the `Scene` trait's defaults and on
//!   `SurfacePoint::new`. Its radiance `Lₑ Σ_{i<d} ρⁱ` is checked for four strategies and
//!   three depths: 12 two-sided z-tests at the family-wise level 0.01, Šidák-corrected, i.e.
//!   `|mean − L| ≤ 3.34 σ̂ + 10⁻⁵ L` (σ̂ the standard error over the paths; the second term is
//!   the `f32` rounding of the radiance, which matters where the estimator has no variance:
//!   at a finite depth every path returns `L` exactly up to rounding).

use crate::custom_scene;

use custom_scene::{GlowingSphere, Lambert as ExampleLambert};
use mcrt::glam::{Vec2, Vec3};
use mcrt::integrator::{
    Bsdf, BsdfFlags, BsdfSample, DirectIntegrator, LightSample, PathTracer, Scene, Strategy,
    SurfacePoint,
};
use mcrt::sampling::sampler::SampleSource;
use mcrt::sampling::Frame;
use std::f32::consts::PI;

struct Lambert(f32);

impl Bsdf for Lambert {
    fn flags(&self) -> BsdfFlags {
        BsdfFlags {
            smooth: true,
            ..BsdfFlags::default()
        }
    }
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Vec3::ZERO;
        }
        Vec3::splat(self.0 * wi.z / PI)
    }
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        wi.z / PI
    }
    fn sample(&self, wo: Vec3, _u1: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let r = u.x.sqrt();
        let (s, c) = (2.0 * PI * u.y).sin_cos();
        let wi = Vec3::new(r * c, r * s, (1.0 - u.x).max(0.0).sqrt());
        (wi.z > 0.0).then(|| BsdfSample {
            wi,
            weight: Vec3::splat(self.0),
            pdf: wi.z / PI,
            delta: false,
            eta: 1.0,
        })
    }
    fn samples_component(&self) -> bool {
        false
    }
}

/// A unit sphere at the origin under uniform radiance 1.
struct Furnace(Lambert);

fn hit_sphere(o: Vec3, d: Vec3) -> Option<SurfacePoint> {
    let b = o.dot(d);
    let c = o.dot(o) - 1.0;
    let disc = b * b - c;
    if disc < 0.0 {
        return None;
    }
    let t = [-b - disc.sqrt(), -b + disc.sqrt()]
        .into_iter()
        .find(|&t| t > 1e-4)?;
    let p = o + d * t;
    let n = p.normalize();
    Some(SurfacePoint {
        t,
        ..SurfacePoint::new(p, n, Frame::from_normal(n))
    })
}

impl Scene for Furnace {
    type Bsdf<'a> = &'a Lambert;
    fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<SurfacePoint> {
        hit_sphere(origin, dir).filter(|h| h.t < t_max)
    }
    fn trace(&self, from: &SurfacePoint, dir: Vec3) -> Option<SurfacePoint> {
        hit_sphere(from.p + from.ng * 1e-4 * dir.dot(from.ng).signum(), dir)
    }
    fn occluded(&self, from: &SurfacePoint, dir: Vec3, dist: f32) -> bool {
        self.trace(from, dir).is_some_and(|h| h.t < dist)
    }
    fn bsdf(&self, _sp: &SurfacePoint) -> &Lambert {
        &self.0
    }
    fn is_emitter(&self, _sp: &SurfacePoint) -> bool {
        false
    }
    fn emitted(&self, _sp: &SurfacePoint, _wo: Vec3) -> Vec3 {
        Vec3::ZERO
    }
    fn has_environment(&self) -> bool {
        true
    }
    fn environment(&self, _dir: Vec3) -> Vec3 {
        Vec3::ONE
    }
    fn sample_light(&self, _from: &SurfacePoint, _u_pick: Vec2, u: Vec2) -> Option<LightSample> {
        let z = 1.0 - 2.0 * u.x;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let (s, c) = (2.0 * PI * u.y).sin_cos();
        Some(LightSample {
            wi: Vec3::new(r * c, r * s, z),
            dist: f32::INFINITY,
            radiance: Vec3::ONE,
            pdf: 1.0 / (4.0 * PI),
            delta: false,
        })
    }
    fn samples_light_choice(&self) -> bool {
        false
    }
    fn light_pdf(&self, _from: &SurfacePoint, _hit: &SurfacePoint) -> f32 {
        0.0
    }
    fn environment_pdf(&self, _from: &SurfacePoint, _dir: Vec3) -> f32 {
        1.0 / (4.0 * PI)
    }
}

/// A 64-bit LCG with the top 24 bits as the value: enough for a test.
struct Lcg(u64);

impl SampleSource for Lcg {
    fn next_1d(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 40) as f32 / 16_777_216.0
    }
}

/// Mean and standard error of `n` estimates along rays toward the sphere.
fn estimate(mut li: impl FnMut(Vec3, Vec3, &mut Lcg) -> Vec3, n: usize) -> (f64, f64) {
    let mut rng = Lcg(99);
    let (mut s, mut s2) = (0.0f64, 0.0f64);
    for _ in 0..n {
        let off = Vec2::new(rng.next_1d(), rng.next_1d()) - Vec2::splat(0.5);
        let o = Vec3::new(0.0, 0.0, 5.0);
        let d = (Vec3::new(off.x, off.y, 0.0) - o).normalize();
        let v = li(o, d, &mut rng).x as f64;
        s += v;
        s2 += v * v;
    }
    let m = s / n as f64;
    (
        m,
        ((s2 / n as f64 - m * m) / (n as f64 - 1.0)).max(0.0).sqrt(),
    )
}

#[test]
fn furnace_with_every_strategy() {
    let scene = Furnace(Lambert(0.6));
    for strategy in [
        Strategy::BsdfOnly,
        Strategy::LightOnly,
        Strategy::MisBalance,
        Strategy::MisPower,
    ] {
        let pt = PathTracer {
            max_depth: -1,
            rr_depth: 5,
            strategy,
            hide_emitters: false,
        };
        let (m, se) = estimate(
            |o, d, r| pt.li(&scene, o, d, f32::INFINITY, r).radiance,
            20_000,
        );
        assert!(m.is_finite() && se.is_finite());
        assert!(
            (m - 0.6).abs() <= 4.0 * se + 1e-6,
            "{strategy:?}: {m} ± {se}"
        );
        let di = DirectIntegrator {
            emitter_samples: 2,
            bsdf_samples: 1,
            strategy,
            hide_emitters: false,
        };
        let (m, se) = estimate(
            |o, d, r| di.li(&scene, o, d, f32::INFINITY, r).radiance,
            20_000,
        );
        assert!(
            (m - 0.6).abs() <= 4.0 * se + 1e-6,
            "direct {strategy:?}: {m} ± {se}"
        );
    }
}

#[test]
fn max_depth_one_sees_only_emitters() {
    let scene = Furnace(Lambert(0.6));
    let pt = PathTracer {
        max_depth: 1,
        ..PathTracer::default()
    };
    let (m, _) = estimate(
        |o, d, r| pt.li(&scene, o, d, f32::INFINITY, r).radiance,
        100,
    );
    assert_eq!(m, 0.0);
    let pt0 = PathTracer {
        max_depth: 0,
        ..PathTracer::default()
    };
    let (m, _) = estimate(
        |o, d, r| pt0.li(&scene, o, d, f32::INFINITY, r).radiance,
        100,
    );
    assert_eq!(m, 0.0);
}

/// Counts the values drawn from an inner source.
struct Counting(Lcg, u64);

impl SampleSource for Counting {
    fn next_1d(&mut self) -> f32 {
        self.1 += 1;
        self.0.next_1d()
    }
}

#[test]
fn direct_integrator_draws_only_what_is_read() {
    // Neither the light choice (one light) nor the component (one lobe) is read: per hit,
    // 2 values per light sample and 2 per BSDF sample; nothing for a ray that misses.
    let scene = Furnace(Lambert(0.6));
    let di = DirectIntegrator {
        emitter_samples: 2,
        bsdf_samples: 3,
        strategy: Strategy::MisPower,
        hide_emitters: false,
    };
    let o = Vec3::new(0.0, 0.0, 5.0);
    let mut rng = Counting(Lcg(5), 0);
    let hit = di.li(&scene, o, -Vec3::Z, f32::INFINITY, &mut rng);
    assert!(hit.radiance.is_finite());
    assert_eq!(rng.1, 2 * 2 + 3 * 2);
    let mut rng = Counting(Lcg(5), 0);
    di.li(&scene, o, Vec3::Z, f32::INFINITY, &mut rng);
    assert_eq!(rng.1, 0);
}

/// The two-sided critical value for 12 tests at the family-wise level 0.01 (Šidák): each at
/// `1 − 0.99^(1/12) = 8.37·10⁻⁴`, `z = Φ⁻¹(1 − 4.19·10⁻⁴) = 3.340`.
const Z_GLOWING_SPHERE: f64 = 3.340;

#[test]
fn glowing_sphere_matches_its_analytic_radiance() {
    let scene = GlowingSphere {
        wall: ExampleLambert { albedo: 0.6 },
        emitted: 1.0,
    };
    let mut checks = 0;
    for max_depth in [2, 4, -1] {
        for strategy in [
            Strategy::BsdfOnly,
            Strategy::LightOnly,
            Strategy::MisBalance,
            Strategy::MisPower,
        ] {
            let pt = PathTracer {
                max_depth,
                rr_depth: 2,
                strategy,
                hide_emitters: false,
            };
            let (mean, se) = custom_scene::estimate(&scene, &pt, 20_000, 11);
            let want = scene.analytic(max_depth);
            assert!(
                mean.is_finite() && se.is_finite(),
                "{strategy:?} {max_depth}"
            );
            assert!(
                (mean - want).abs() <= Z_GLOWING_SPHERE * se + 1e-5 * want,
                "{strategy:?}, max_depth {max_depth}: {mean} ± {se}, want {want}"
            );
            checks += 1;
        }
    }
    assert_eq!(checks, 12, "the Šidák correction counts 12 tests");
}

/// The check is not blind: the glowing sphere with `light_pdf` off by a factor 2 (so the MIS
/// weights of light and BSDF sampling no longer sum to 1) fails it.
#[test]
fn glowing_sphere_check_rejects_a_wrong_light_pdf() {
    struct WrongPdf(GlowingSphere);
    impl Scene for WrongPdf {
        type Bsdf<'a> = &'a ExampleLambert;
        fn intersect(&self, o: Vec3, d: Vec3, t_max: f32) -> Option<SurfacePoint> {
            self.0.intersect(o, d, t_max)
        }
        fn trace(&self, from: &SurfacePoint, dir: Vec3) -> Option<SurfacePoint> {
            self.0.trace(from, dir)
        }
        fn occluded(&self, from: &SurfacePoint, dir: Vec3, dist: f32) -> bool {
            self.0.occluded(from, dir, dist)
        }
        fn bsdf(&self, sp: &SurfacePoint) -> &ExampleLambert {
            self.0.bsdf(sp)
        }
        fn is_emitter(&self, sp: &SurfacePoint) -> bool {
            self.0.is_emitter(sp)
        }
        fn emitted(&self, sp: &SurfacePoint, wo: Vec3) -> Vec3 {
            self.0.emitted(sp, wo)
        }
        fn sample_light(&self, from: &SurfacePoint, pick: Vec2, u: Vec2) -> Option<LightSample> {
            self.0.sample_light(from, pick, u)
        }
        fn light_pdf(&self, from: &SurfacePoint, hit: &SurfacePoint) -> f32 {
            2.0 * self.0.light_pdf(from, hit)
        }
    }
    let sphere = GlowingSphere {
        wall: ExampleLambert { albedo: 0.6 },
        emitted: 1.0,
    };
    let want = sphere.analytic(2);
    let pt = PathTracer {
        max_depth: 2,
        rr_depth: 2,
        strategy: Strategy::MisPower,
        hide_emitters: false,
    };
    let (mean, se) = custom_scene::estimate_in(&WrongPdf(sphere), &pt, 2_000, 11);
    assert!(mean.is_finite() && se.is_finite());
    assert!(
        (mean - want).abs() > Z_GLOWING_SPHERE * se + 1e-5 * want,
        "{mean} ± {se} passed for {want}"
    );
}
