//! Test a warp of your own with `mcrt::stats` in a few lines.
//!
//! Run with `cargo run --release --example chi2_custom_warp`. The warp here samples the unit
//! square with density p(x, y) = 2y (inversion of the CDF y² gives y = √u₂); swap in yours.

use mcrt::glam::Vec2;
use mcrt::sampling::warp::{InvertibleWarp, Warp};
use mcrt::stats::{
    check_warp_inverse, check_warp_jacobian, ChiSquareTest, JacobianCheck, Rectangle,
};

/// The unit square with density 2y per unit area.
struct LinearRamp;

impl Warp for LinearRamp {
    type Point = Vec2;
    fn sample(&self, u: Vec2) -> Vec2 {
        Vec2::new(u.x, u.y.sqrt())
    }
    fn pdf(&self, p: Vec2) -> f32 {
        let inside = (0.0..=1.0).contains(&p.x) && (0.0..=1.0).contains(&p.y);
        if inside {
            2.0 * p.y
        } else {
            0.0
        }
    }
}

impl InvertibleWarp for LinearRamp {
    fn invert(&self, p: Vec2) -> Vec2 {
        Vec2::new(p.x, p.y * p.y)
    }
}

fn main() {
    // Chi-square over a 32 × 32 grid, 10⁶ samples, fixed seed; α = 0.01 for this one test.
    let outcome = ChiSquareTest::new(Rectangle::unit_square(32))
        .name("linear-ramp")
        .run_warp(&LinearRamp);
    println!("{}", outcome.report());

    // Companion checks: pdf(sample(u)) · J(u) = 1 and invert(sample(u)) = u.
    let jacobian = check_warp_jacobian(&LinearRamp, JacobianCheck::default());
    let inverse = check_warp_inverse(&LinearRamp, 64, 1e-5);
    println!("{}\n{}", jacobian.report(), inverse.report());

    if !(outcome.passed() && jacobian.passed() && inverse.passed()) {
        std::process::exit(1);
    }
}
