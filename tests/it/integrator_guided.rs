//! The guided path tracer (`GuidedPathTracer` with an `SdTree` trained by the
//! `GuidingSchedule`) on scenes with analytic answers: after training, the final pass's mean
//! must match the answer within `Z` standard errors (two-sided z-tests, 6 of them at the
//! family-wise level 0.01, Šidák: `Z = 3.14`), at fixed seeds.
//!
//! - The glowing sphere of `examples/custom_scene.rs` (a diffuse wall inside a uniformly
//!   emitting sphere): `Lₑ/(1 − ρ)` at unlimited depth, `Lₑ(1 + ρ)` at depth 2.
//! - A white furnace: a convex Lambertian sphere under uniform radiance 1 returns ρ.
//! - A Lambertian floor under a small bright cap of the sky ("sun", half-angle θ_c,
//!   radiance L): `ρ L sin² θ_c`. With BSDF sampling only, guiding must find the cap and
//!   cut the standard error by a large factor.
//!
//! And the training is deterministic at any thread count: tiles rendered on two or three
//! threads and merged in tile order give the same tree (split in space) and image as one
//! thread.

use crate::custom_scene;

use custom_scene::{GlowingSphere, Lambert};
use mcrt::glam::{Vec2, Vec3};
use mcrt::integrator::{GuidedPathTracer, LightSample, Scene, Strategy, SurfacePoint};
use mcrt::sampling::guiding::{GuidingRecords, GuidingSchedule, SdTree};
use mcrt::sampling::sampler::{IndependentSampler, SampleSource, Sampler};
use mcrt::sampling::warp::{UniformSphere, Warp};
use mcrt::sampling::Frame;
use std::f32::consts::PI;

/// Two-sided critical value for 6 z-tests at the family-wise level 0.01 (Šidák):
/// `Φ⁻¹(1 − (1 − 0.99^(1/6))/2) = 3.144`.
const Z: f64 = 3.144;

/// A camera: the ray of pixel `i`.
type Camera = dyn Fn(u32, &mut IndependentSampler) -> (Vec3, Vec3) + Sync;

/// Renders `pixels` pixels of `spp` samples guided by `guide` on the pixels `range`,
/// recording into one buffer; returns the per-sample radiances (red channel).
#[allow(clippy::too_many_arguments)]
fn render_tile<S: Scene>(
    scene: &S,
    gpt: &GuidedPathTracer,
    guide: &SdTree,
    camera: &Camera,
    range: std::ops::Range<u32>,
    spp: u32,
    seed: u64,
    records: Option<&mut GuidingRecords>,
) -> Vec<f64> {
    let mut records = records;
    let mut sampler = IndependentSampler::new(spp, seed).unwrap();
    let mut out = Vec::new();
    for px in range {
        for s in 0..spp {
            sampler.start_pixel_sample([px, 0], s);
            let (o, d) = camera(px, &mut sampler);
            let r = gpt.li(
                scene,
                guide,
                o,
                d,
                f32::INFINITY,
                &mut sampler,
                records.as_deref_mut(),
            );
            out.push(f64::from(r.radiance.x));
        }
    }
    out
}

/// Trains on `pixels` pixels with the schedule of `total_spp` (spatial threshold
/// `spatial_c·√(2^k)`), tiles of `tile` pixels run on
/// `threads` threads and merged in tile order; returns the final pass's mean and standard
/// error, and the last trained tree.
#[allow(clippy::too_many_arguments)]
fn train_and_render<S: Scene + Sync>(
    scene: &S,
    gpt: &GuidedPathTracer,
    bounds: (Vec3, Vec3),
    camera: &Camera,
    pixels: u32,
    total_spp: u32,
    seed: u64,
    threads: usize,
    spatial_c: f64,
) -> (f64, f64, SdTree) {
    let schedule = GuidingSchedule {
        spatial_c,
        ..GuidingSchedule::new(total_spp)
    };
    let mut guide = SdTree::new(bounds.0, bounds.1);
    // The trees learn the selection probability, as the renderer's do (the estimator must
    // stay unbiased, and the same at any thread count, with it), unless the tracer is never
    // to be guided.
    guide.learn_selection(gpt.guide_probability > 0.0);
    let mut training = guide.clone();
    let tile = 16u32;
    let tiles: Vec<u32> = (0..pixels.div_ceil(tile)).collect();
    let mut result = (f64::NAN, f64::NAN);
    for pass in schedule.passes() {
        let pass_seed = seed ^ (u64::from(pass.index) << 32);
        // Each thread renders every `threads`-th tile; buffers are merged in tile order.
        let mut per_tile: Vec<(u32, Vec<f64>, GuidingRecords)> = std::thread::scope(|s| {
            let handles: Vec<_> = (0..threads)
                .map(|t| {
                    let (tiles, guide) = (&tiles, &guide);
                    s.spawn(move || {
                        let mut out = Vec::new();
                        for &k in tiles.iter().skip(t).step_by(threads) {
                            let range = k * tile..((k + 1) * tile).min(pixels);
                            let mut rec = GuidingRecords::new();
                            let seed = pass_seed ^ u64::from(k);
                            let v = render_tile(
                                scene,
                                gpt,
                                guide,
                                camera,
                                range,
                                pass.spp,
                                seed,
                                Some(&mut rec),
                            );
                            out.push((k, v, rec));
                        }
                        out
                    })
                })
                .collect();
            handles
                .into_iter()
                .flat_map(|h| h.join().unwrap())
                .collect()
        });
        per_tile.sort_by_key(|t| t.0);
        for (_, _, rec) in &per_tile {
            training.merge(rec);
        }
        if pass.is_final {
            let v: Vec<f64> = per_tile.into_iter().flat_map(|t| t.1).collect();
            let n = v.len() as f64;
            let mean = v.iter().sum::<f64>() / n;
            let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
            result = (mean, (var / n).sqrt());
        } else {
            let next = schedule.next_tree(&training, &pass);
            guide = std::mem::replace(&mut training, next);
        }
    }
    (result.0, result.1, guide)
}

fn assert_close(name: &str, (m, se): (f64, f64), expected: f64) {
    assert!(m.is_finite() && se.is_finite(), "{name}: {m} ± {se}");
    assert!(
        (m - expected).abs() <= Z * se + 1e-5 * expected,
        "{name}: {m} ± {se}, expected {expected}"
    );
}

fn centre_camera(_px: u32, s: &mut IndependentSampler) -> (Vec3, Vec3) {
    (Vec3::ZERO, UniformSphere.sample(s.next_2d()))
}

/// With `hide_emitters`, a camera ray inside the glowing sphere passes through its emitting
/// wall and leaves the scene: nothing is seen (without it, the wall's glow and more).
#[test]
fn hide_emitters_sees_through_the_glowing_wall() {
    let scene = GlowingSphere {
        wall: Lambert { albedo: 0.6 },
        emitted: 1.0,
    };
    let guide = SdTree::new(Vec3::splat(-1.0), Vec3::ONE);
    let mut s = IndependentSampler::new(1, 5).expect("one sample per pixel");
    for hide_emitters in [false, true] {
        let gpt = GuidedPathTracer {
            hide_emitters,
            ..GuidedPathTracer::default()
        };
        for i in 0..64 {
            s.start_pixel_sample([i, 0], 0);
            let (origin, dir) = centre_camera(i, &mut s);
            let r = gpt.li(&scene, &guide, origin, dir, f32::INFINITY, &mut s, None);
            assert!(r.radiance.is_finite(), "{:?}", r.radiance);
            if hide_emitters {
                assert_eq!(r.radiance, Vec3::ZERO);
            } else {
                assert!(r.radiance.min_element() >= 1.0, "{:?}", r.radiance);
            }
        }
    }
}

#[test]
fn glowing_sphere_is_unbiased() {
    let scene = GlowingSphere {
        wall: Lambert { albedo: 0.6 },
        emitted: 1.0,
    };
    let bounds = (Vec3::splat(-1.0), Vec3::splat(1.0));
    for (max_depth, strategy) in [(-1, Strategy::MisPower), (2, Strategy::BsdfOnly)] {
        let gpt = GuidedPathTracer {
            max_depth,
            rr_depth: 5,
            strategy,
            guide_probability: 0.5,
            hide_emitters: false,
        };
        let (m, se, tree) =
            train_and_render(&scene, &gpt, bounds, &centre_camera, 256, 64, 11, 1, 200.0);
        // A low spatial threshold: the guide is split over the wall.
        assert!(
            tree.sample_count() > 0 && tree.leaf_count() > 1,
            "{}",
            tree.leaf_count()
        );
        assert_close(
            &format!("glowing sphere {max_depth} {strategy:?}"),
            (m, se),
            scene.analytic(max_depth),
        );
    }
}

/// The unit sphere at the origin, Lambertian, under uniform radiance 1 (or, with `sun`, a
/// plane `z = 0` facing up under a cap of the sky about +z).
struct Sky {
    albedo: Lambert,
    /// `Some((cos θ_c, L))`: the sky is a cap of half-angle θ_c and radiance L, the ground a
    /// plane; `None`: uniform radiance 1 and a unit sphere.
    sun: Option<(f32, f32)>,
}

impl Sky {
    fn hit(&self, o: Vec3, d: Vec3) -> Option<SurfacePoint> {
        if self.sun.is_some() {
            let t = -o.z / d.z;
            return (t > 1e-4 && t.is_finite()).then(|| SurfacePoint {
                t,
                ..SurfacePoint::new(o + d * t, Vec3::Z, Frame::from_normal(Vec3::Z))
            });
        }
        let b = o.dot(d);
        let disc = b * b - (o.dot(o) - 1.0);
        if disc < 0.0 {
            return None;
        }
        let t = [-b - disc.sqrt(), -b + disc.sqrt()]
            .into_iter()
            .find(|&t| t > 1e-4)?;
        let n = (o + d * t).normalize();
        Some(SurfacePoint {
            t,
            ..SurfacePoint::new(o + d * t, n, Frame::from_normal(n))
        })
    }

    fn cap_pdf(&self) -> f32 {
        match self.sun {
            Some((c, _)) => 1.0 / (2.0 * PI * (1.0 - c)),
            None => 1.0 / (4.0 * PI),
        }
    }
}

impl Scene for Sky {
    type Bsdf<'a> = &'a Lambert;
    fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<SurfacePoint> {
        self.hit(origin, dir).filter(|h| h.t < t_max)
    }
    fn trace(&self, from: &SurfacePoint, dir: Vec3) -> Option<SurfacePoint> {
        self.hit(from.p + from.ng * 1e-4 * dir.dot(from.ng).signum(), dir)
    }
    fn occluded(&self, from: &SurfacePoint, dir: Vec3, dist: f32) -> bool {
        self.trace(from, dir).is_some_and(|h| h.t < dist)
    }
    fn bsdf(&self, _sp: &SurfacePoint) -> &Lambert {
        &self.albedo
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
    fn environment(&self, dir: Vec3) -> Vec3 {
        match self.sun {
            Some((c, l)) if dir.z >= c => Vec3::splat(l),
            Some(_) => Vec3::ZERO,
            None => Vec3::ONE,
        }
    }
    fn sample_light(&self, _from: &SurfacePoint, _u_pick: Vec2, u: Vec2) -> Option<LightSample> {
        let (c, l) = self.sun.unwrap_or((-1.0, 1.0));
        let z = 1.0 - u.x * (1.0 - c);
        let r = (1.0 - z * z).max(0.0).sqrt();
        let (s, co) = (2.0 * PI * u.y).sin_cos();
        Some(LightSample {
            wi: Vec3::new(r * co, r * s, z),
            dist: f32::INFINITY,
            radiance: Vec3::splat(l),
            pdf: self.cap_pdf(),
            delta: false,
        })
    }
    fn samples_light_choice(&self) -> bool {
        false
    }
    fn light_pdf(&self, _from: &SurfacePoint, _hit: &SurfacePoint) -> f32 {
        0.0
    }
    fn environment_pdf(&self, _from: &SurfacePoint, dir: Vec3) -> f32 {
        match self.sun {
            Some((c, _)) if dir.z < c => 0.0,
            _ => self.cap_pdf(),
        }
    }
}

fn outside_camera(_px: u32, s: &mut IndependentSampler) -> (Vec3, Vec3) {
    let off = s.next_2d() - Vec2::splat(0.5);
    let o = Vec3::new(0.0, 0.0, 5.0);
    (o, (Vec3::new(off.x, off.y, 0.0) - o).normalize())
}

#[test]
fn white_furnace_is_unbiased() {
    let scene = Sky {
        albedo: Lambert { albedo: 0.6 },
        sun: None,
    };
    let gpt = GuidedPathTracer::default();
    let bounds = (Vec3::splat(-1.0), Vec3::splat(1.0));
    let r = train_and_render(
        &scene,
        &gpt,
        bounds,
        &outside_camera,
        256,
        64,
        5,
        1,
        12_000.0,
    );
    assert_close("furnace", (r.0, r.1), 0.6);
}

#[test]
fn sun_is_found_by_guiding() {
    let cos_c = 0.95f32;
    let scene = Sky {
        albedo: Lambert { albedo: 0.5 },
        sun: Some((cos_c, 20.0)),
    };
    let expected = 0.5 * 20.0 * (1.0 - f64::from(cos_c).powi(2));
    let bounds = (Vec3::new(-1.0, -1.0, -0.1), Vec3::new(1.0, 1.0, 0.1));
    for strategy in [Strategy::BsdfOnly, Strategy::MisPower] {
        let gpt = GuidedPathTracer {
            max_depth: 2,
            strategy,
            ..GuidedPathTracer::default()
        };
        let guided = train_and_render(
            &scene,
            &gpt,
            bounds,
            &outside_camera,
            256,
            128,
            3,
            1,
            12_000.0,
        );
        assert_close(
            &format!("sun guided {strategy:?}"),
            (guided.0, guided.1),
            expected,
        );
        if strategy == Strategy::BsdfOnly {
            // The same budget, never guided: the standard error is much larger.
            let unguided = GuidedPathTracer {
                guide_probability: 0.0,
                ..gpt
            };
            let plain = train_and_render(
                &scene,
                &unguided,
                bounds,
                &outside_camera,
                256,
                128,
                3,
                1,
                12_000.0,
            );
            assert_close("sun unguided", (plain.0, plain.1), expected);
            assert!(
                guided.1 < 0.5 * plain.1,
                "guided {} vs unguided {}",
                guided.1,
                plain.1
            );
        }
    }
}

#[test]
fn training_is_deterministic_at_any_thread_count() {
    let scene = GlowingSphere {
        wall: Lambert { albedo: 0.6 },
        emitted: 1.0,
    };
    let gpt = GuidedPathTracer::default();
    let bounds = (Vec3::splat(-1.0), Vec3::splat(1.0));
    let one = train_and_render(&scene, &gpt, bounds, &centre_camera, 100, 16, 9, 1, 100.0);
    let two = train_and_render(&scene, &gpt, bounds, &centre_camera, 100, 16, 9, 2, 100.0);
    let three = train_and_render(&scene, &gpt, bounds, &centre_camera, 100, 16, 9, 3, 100.0);
    assert!(one.2.leaf_count() > 1);
    assert_eq!(one.2, two.2);
    assert_eq!(one.2, three.2);
    assert_eq!(one.0.to_bits(), two.0.to_bits());
    assert_eq!(one.0.to_bits(), three.0.to_bits());
}
