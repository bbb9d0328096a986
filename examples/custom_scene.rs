//! A scene of your own under mcrt's estimators: the inside of a glowing sphere, written
//! through the `Scene` and `Bsdf` traits with no part of the crate's `scene` module, traced
//! by `PathTracer` and printed next to its analytic answer.
//!
//! The unit sphere's inner wall is Lambertian with albedo ρ and emits radiance `Lₑ` into the
//! sphere. Every point of the wall sees nothing but the wall, so the radiance is the same
//! everywhere and in every direction: `L = Lₑ + ρ L`, i.e. `L = Lₑ / (1 − ρ)` (with paths of
//! at most `d` segments, `Lₑ (1 + ρ + … + ρ^(d−1))`). A camera at the centre therefore sees
//! `L` in every direction, whichever strategy the path tracer uses.
//!
//! At a finite depth every path returns exactly that answer (up to `f32` rounding): BSDF
//! sampling weighs each bounce by ρ, and sampling the wall by area gives the same, since
//! between two points of a sphere `cos θ cos θ′ / d² = ¼`. Only Russian roulette, at
//! unlimited depth, leaves noise. A wrong density anywhere (a missing cosine, a `light_pdf`
//! that does not match `sample_light`) shows at once.
//!
//! The scene has no environment and no point lights, so it leaves `has_environment`,
//! `environment`, `environment_pdf` and `has_delta_lights` to their defaults.
//!
//! ```sh
//! cargo run --release --example custom_scene
//! ```
//!
//! `tests/it/integrator_custom_scene.rs` runs this file's scene as a statistical test.

use mcrt::glam::{Vec2, Vec3};
use mcrt::integrator::{
    Bsdf, BsdfFlags, BsdfSample, LightSample, PathTracer, Scene, Strategy, SurfacePoint,
};
use mcrt::sampling::jacobian::solid_angle_pdf_from_area;
use mcrt::sampling::sampler::{IndependentSampler, SampleSource, Sampler};
use mcrt::sampling::warp::{CosineHemisphere, UniformSphere, Warp};
use mcrt::sampling::Frame;
use std::f32::consts::PI;

/// A Lambertian BSDF, `f = albedo / π`, in the estimators' z-up local frame.
pub struct Lambert {
    /// The albedo ρ in `[0, 1)`.
    pub albedo: f32,
}

impl Bsdf for Lambert {
    fn flags(&self) -> BsdfFlags {
        BsdfFlags {
            smooth: true,
            ..BsdfFlags::default()
        }
    }

    /// `f · cos θ_i`.
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Vec3::ZERO;
        }
        Vec3::splat(self.albedo / PI * wi.z)
    }

    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 {
            return 0.0;
        }
        CosineHemisphere.pdf(wi)
    }

    /// Cosine-weighted directions: the weight `f cos θ / pdf` is the albedo.
    fn sample(&self, wo: Vec3, _u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let (wi, pdf) = CosineHemisphere.sample_with_pdf(u2);
        (pdf > 0.0).then_some(BsdfSample {
            wi,
            weight: Vec3::splat(self.albedo),
            pdf,
            delta: false,
            eta: 1.0,
        })
    }

    /// One lobe: no component to choose, so the estimators need not draw `u1`.
    fn samples_component(&self) -> bool {
        false
    }
}

/// The inside of the unit sphere at the origin: a Lambertian wall that emits `emitted` into
/// the sphere.
pub struct GlowingSphere {
    /// The wall's material.
    pub wall: Lambert,
    /// The radiance `Lₑ` the wall emits.
    pub emitted: f32,
}

impl GlowingSphere {
    /// The radiance seen from anywhere inside along paths of at most `max_depth` segments
    /// (−1: unlimited): `Lₑ Σ_{i < d} ρⁱ`.
    pub fn analytic(&self, max_depth: i32) -> f64 {
        let (le, rho) = (f64::from(self.emitted), f64::from(self.wall.albedo));
        match u32::try_from(max_depth) {
            Ok(d) => le * (1.0 - rho.powi(d as i32)) / (1.0 - rho),
            Err(_) => le / (1.0 - rho),
        }
    }

    /// The wall point seen from `origin` (inside or on the sphere) along unit `dir`: the far
    /// root of `|origin + t dir| = 1`, so a ray leaving the wall never finds its own origin.
    fn wall_hit(origin: Vec3, dir: Vec3) -> Option<SurfacePoint> {
        let b = origin.dot(dir);
        let c = origin.length_squared() - 1.0;
        let t = -b + (b * b - c).max(0.0).sqrt();
        if !(t > 0.0 && t.is_finite()) {
            return None;
        }
        let p = origin + t * dir;
        // The front side faces the centre: emission and reflection happen on the inside.
        let ng = -p.normalize();
        Some(SurfacePoint {
            t,
            ..SurfacePoint::new(p, ng, Frame::from_normal(ng))
        })
    }

    /// Density per unit solid angle, seen from `from`, of a wall point `q` (front normal
    /// `nq`) sampled uniformly by area (`1/4π`).
    fn area_pdf_as_solid_angle(from: Vec3, q: Vec3, nq: Vec3) -> f32 {
        let d = from - q;
        let dist_sq = d.length_squared();
        let cos_light = nq.dot(d) / dist_sq.sqrt();
        solid_angle_pdf_from_area(1.0 / (4.0 * PI), dist_sq, cos_light)
    }
}

impl Scene for GlowingSphere {
    type Bsdf<'a> = &'a Lambert;

    fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<SurfacePoint> {
        Self::wall_hit(origin, dir).filter(|h| h.t < t_max)
    }

    fn trace(&self, from: &SurfacePoint, dir: Vec3) -> Option<SurfacePoint> {
        Self::wall_hit(from.p, dir)
    }

    /// A plain ray query (`0 < t < dist`): the estimators shorten `dist` themselves, so the
    /// wall point they aim at does not hide itself.
    fn occluded(&self, from: &SurfacePoint, dir: Vec3, dist: f32) -> bool {
        self.trace(from, dir).is_some_and(|h| h.t < dist)
    }

    fn bsdf(&self, _sp: &SurfacePoint) -> &Lambert {
        &self.wall
    }

    fn is_emitter(&self, _sp: &SurfacePoint) -> bool {
        true
    }

    fn emitted(&self, sp: &SurfacePoint, wo: Vec3) -> Vec3 {
        if sp.ng.dot(wo) > 0.0 {
            Vec3::splat(self.emitted)
        } else {
            Vec3::ZERO
        }
    }

    /// A wall point uniformly by area, as a direction and its density per steradian.
    fn sample_light(&self, from: &SurfacePoint, _u_pick: Vec2, u: Vec2) -> Option<LightSample> {
        let q = UniformSphere.sample(u);
        let to_light = q - from.p;
        let dist = to_light.length();
        if dist <= 0.0 || dist.is_nan() {
            return None;
        }
        let wi = to_light / dist;
        let pdf = Self::area_pdf_as_solid_angle(from.p, q, -q);
        let radiance = if (-q).dot(-wi) > 0.0 {
            Vec3::splat(self.emitted)
        } else {
            Vec3::ZERO
        };
        (pdf > 0.0).then_some(LightSample {
            wi,
            dist,
            radiance,
            pdf,
            delta: false,
        })
    }

    /// One light with one part: nothing to choose.
    fn samples_light_choice(&self) -> bool {
        false
    }

    fn light_pdf(&self, from: &SurfacePoint, hit: &SurfacePoint) -> f32 {
        Self::area_pdf_as_solid_angle(from.p, hit.p, hit.ng)
    }
}

/// Mean and standard error of `paths` estimates of the radiance at the centre, along
/// uniformly distributed directions, from an [`IndependentSampler`] seeded with `seed`.
pub fn estimate(scene: &GlowingSphere, pt: &PathTracer, paths: u32, seed: u64) -> (f64, f64) {
    estimate_in(scene, pt, paths, seed)
}

/// [`estimate`] for any scene.
pub fn estimate_in<S: Scene>(scene: &S, pt: &PathTracer, paths: u32, seed: u64) -> (f64, f64) {
    let mut sampler = IndependentSampler::new(paths.max(1), seed).expect("at least one sample");
    let (mut sum, mut sum_sq) = (0.0f64, 0.0f64);
    for i in 0..paths {
        sampler.start_pixel_sample([0, 0], i);
        let dir = UniformSphere.sample(sampler.next_2d());
        let l = f64::from(
            pt.li(scene, Vec3::ZERO, dir, f32::INFINITY, &mut sampler)
                .radiance
                .x,
        );
        sum += l;
        sum_sq += l * l;
    }
    let n = f64::from(paths.max(2));
    let mean = sum / n;
    let variance = ((sum_sq - n * mean * mean) / (n - 1.0)).max(0.0);
    (mean, (variance / n).sqrt())
}

fn main() {
    let scene = GlowingSphere {
        wall: Lambert { albedo: 0.6 },
        emitted: 1.0,
    };
    println!("inside a glowing Lambertian sphere (albedo 0.6, emitted radiance 1)");
    println!("max_depth  strategy  estimate ± std. error   analytic");
    for max_depth in [2, 4, -1] {
        for strategy in [Strategy::BsdfOnly, Strategy::LightOnly, Strategy::MisPower] {
            let pt = PathTracer {
                max_depth,
                rr_depth: 5,
                strategy,
                hide_emitters: false,
            };
            let (mean, se) = estimate(&scene, &pt, 100_000, 7);
            println!(
                "{max_depth:>9}  {:>8}  {mean:.4} ± {se:.4}       {:.4}",
                strategy.name(),
                scene.analytic(max_depth)
            );
        }
    }
}
