//! `mcrt::PathTracer` on this crate's own scene (`Shell`: a Lambertian ball inside a glowing
//! Lambertian shell, implementing `mcrt::Scene` and `mcrt::Bsdf`), against the analytic
//! radiance of the ball (`Shell::ball_radiance`), for every strategy and three depths.
//!
//! **Tolerance.** Each case averages `N` i.i.d. paths (an `IndependentSampler`, fixed seed)
//! and compares the mean with the answer `L` by a two-sided z-test on the standard error
//! `σ̂ = s / √N` of the paths: 12 cases at the family-wise level 0.01, Šidák-corrected
//! (per case `1 − 0.99^(1/12) = 8.4·10⁻⁴`, `z = 3.34`), so `|mean − L| ≤ 3.34 σ̂ + 10⁻⁵ L`.
//! The second term is the `f32` rounding of the radiance, which is all that remains where the
//! estimator has no variance (at depth 2 with BSDF sampling every path returns `ρᵢ Lₑ`).
//! The seed is fixed, so the test is deterministic; the level says how rarely a correct
//! estimator would fail at another seed.

#![forbid(unsafe_code)]

use mcrt::glam::Vec3;
use mcrt::{
    Frame, IndependentSampler, PathTracer, SampleSource, Sampler, Scene, Strategy, UniformCone,
    Warp,
};
use mcrt_downstream::{Lambert, Shell};

/// The z value of 12 two-sided tests at the family-wise level 0.01 (Šidák):
/// `Φ⁻¹(1 − (1 − 0.99^(1/12)) / 2)`.
const Z: f64 = 3.34;

/// Paths per case.
const PATHS: u32 = 40_000;

fn shell() -> Shell {
    Shell {
        ball_radius: 1.0,
        ball: Lambert { albedo: 0.8 },
        shell_radius: 2.0,
        shell: Lambert { albedo: 0.5 },
        emitted: 1.0,
    }
}

/// Mean and standard error of `PATHS` estimates of the radiance reaching a camera at
/// `(0, 0, 1.5)` from the ball: directions uniform in a cone just inside the ball's outline.
fn estimate(scene: &Shell, pt: &PathTracer, seed: u64) -> (f64, f64) {
    let camera = Vec3::new(0.0, 0.0, 1.5);
    let toward_ball = Frame::from_normal(-Vec3::Z);
    let half_angle = (scene.ball_radius / camera.length()).asin();
    let cone = UniformCone::from_angle(0.99 * half_angle).expect("a valid cone");
    let mut sampler = IndependentSampler::new(PATHS, seed).expect("a valid sampler");
    let (mut sum, mut sum_sq) = (0.0f64, 0.0f64);
    for i in 0..PATHS {
        sampler.start_pixel_sample([0, 0], i);
        let local = cone.sample(sampler.next_2d());
        let dir = toward_ball.to_world(local);
        // Every camera ray meets the ball.
        let first = scene.intersect(camera, dir, f32::INFINITY);
        assert!(
            first.is_some_and(|h| h.shape == mcrt_downstream::scene::BALL),
            "{dir}"
        );
        let l = f64::from(
            pt.li(scene, camera, dir, f32::INFINITY, &mut sampler)
                .radiance
                .x,
        );
        assert!(l.is_finite() && l >= 0.0, "path {i}: {l}");
        sum += l;
        sum_sq += l * l;
    }
    let n = f64::from(PATHS);
    let mean = sum / n;
    let variance = ((sum_sq - n * mean * mean) / (n - 1.0)).max(0.0);
    (mean, (variance / n).sqrt())
}

#[test]
fn path_tracer_matches_the_analytic_shell() {
    let scene = shell();
    // The answers: ρᵢ Lₑ at depth 2; the series at depth 4; the limit, ρᵢ Lₑ / (1 − ρₒ (F ρᵢ
    // + 1 − F)) with F = ¼, approached by the series.
    let rho_i = f64::from(scene.ball.albedo);
    assert!((scene.ball_radiance(2) - rho_i).abs() < 1e-12);
    let limit = rho_i / (1.0 - 0.5 * (0.25 * rho_i + 0.75));
    assert!((scene.ball_radiance(-1) - limit).abs() < 1e-12);
    assert!((scene.ball_radiance(200) - limit).abs() < 1e-9);
    let mut failures = Vec::new();
    for (d, max_depth) in [2, 4, -1].into_iter().enumerate() {
        let expected = scene.ball_radiance(max_depth);
        for (k, strategy) in [
            Strategy::BsdfOnly,
            Strategy::LightOnly,
            Strategy::MisBalance,
            Strategy::MisPower,
        ]
        .into_iter()
        .enumerate()
        {
            let pt = PathTracer {
                max_depth,
                rr_depth: 5,
                strategy,
                hide_emitters: false,
            };
            // One seed per case, so that the 12 z-tests are independent.
            let (mean, se) = estimate(&scene, &pt, 17 + (4 * d + k) as u64);
            let tolerance = Z * se + 1e-5 * expected;
            let line = format!(
                "depth {max_depth:>2} {:>11}: {mean:.5} ± {se:.5} (analytic {expected:.5}, \
                 tolerance {tolerance:.5})",
                strategy.name()
            );
            println!("{line}");
            if !(mean.is_finite() && se.is_finite() && (mean - expected).abs() <= tolerance) {
                failures.push(line);
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
