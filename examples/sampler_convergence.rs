//! Error against sample count for each sampler, on two integrands over the unit square.
//!
//! `cargo run --release --example sampler_convergence`
//!
//! For each sampler and spp = 4, 16, …, 1024, estimates the integral in 256 pixels (independent
//! estimates, fixed seed) and prints the root-mean-square error and its slope against spp
//! between successive rows. Integrands: a smooth one, `exp(xy) + sin(3x)·y²`, and a
//! discontinuous one, the indicator of the quarter disk `x² + y² < 1` (integral π/4), which is
//! what a pixel edge or a shadow boundary looks like to a sampler.

use mcrt::glam::Vec2;
#[cfg(feature = "sobol")]
use mcrt::sampling::sampler::SobolSampler;
use mcrt::sampling::sampler::{IndependentSampler, Sampler, StratifiedSampler};

const PIXELS: u32 = 256;

fn smooth(u: Vec2) -> f64 {
    let (x, y) = (f64::from(u.x), f64::from(u.y));
    (x * y).exp() + (3.0 * x).sin() * y * y
}

fn smooth_integral() -> f64 {
    let (mut sum, mut factorial) = (0.0, 1.0);
    for n in 0..20 {
        if n > 0 {
            factorial *= f64::from(n);
        }
        sum += 1.0 / (factorial * f64::from(n + 1).powi(2));
    }
    sum + (1.0 - 3f64.cos()) / 9.0
}

fn quarter_disk(u: Vec2) -> f64 {
    if u.length_squared() < 1.0 {
        1.0
    } else {
        0.0
    }
}

/// RMS error over the pixels of the `spp`-sample estimate (the 2D value of dimension 1, after
/// one 2D value a renderer would spend on the pixel position).
fn rms<S: Sampler>(mut s: S, f: fn(Vec2) -> f64, exact: f64) -> f64 {
    let spp = s.samples_per_pixel();
    let mut sq = 0.0;
    for p in 0..PIXELS {
        let mut sum = 0.0;
        for i in 0..spp {
            s.start_pixel_sample([p % 16, p / 16], i);
            s.next_2d();
            sum += f(s.next_2d());
        }
        sq += (sum / f64::from(spp) - exact).powi(2);
    }
    (sq / f64::from(PIXELS)).sqrt()
}

fn table(name: &str, f: fn(Vec2) -> f64, exact: f64) {
    println!("\n{name}: RMS error over {PIXELS} pixels (slope of log error / log spp)\n");
    print!("| spp | independent | stratified |");
    #[cfg(feature = "sobol")]
    print!(" sobol |");
    println!();
    println!(
        "|---|---|---|{}",
        if cfg!(feature = "sobol") { "---|" } else { "" }
    );
    let mut last: Option<(f64, Vec<f64>)> = None;
    for k in 1..=5 {
        let spp = 1u32 << (2 * k);
        let mut errors = vec![
            rms(IndependentSampler::new(spp, 1).unwrap(), f, exact),
            rms(StratifiedSampler::new(spp, 1, true).unwrap(), f, exact),
        ];
        #[cfg(feature = "sobol")]
        errors.push(rms(SobolSampler::new(spp, 1).unwrap(), f, exact));
        print!("| {spp} |");
        for (j, e) in errors.iter().enumerate() {
            match &last {
                Some((n0, e0)) => {
                    let slope = (e / e0[j]).ln() / (f64::from(spp) / n0).ln();
                    print!(" {e:.2e} ({slope:+.2}) |");
                }
                None => print!(" {e:.2e} |"),
            }
        }
        println!();
        last = Some((f64::from(spp), errors));
    }
}

fn main() {
    table(
        "smooth integrand exp(xy) + sin(3x)·y²",
        smooth,
        smooth_integral(),
    );
    table(
        "discontinuous integrand: quarter disk",
        quarter_disk,
        std::f64::consts::FRAC_PI_4,
    );
    println!("\nExpected slopes: independent −0.5; stratified −1.0 (smooth), −0.75 (edge);");
    println!("Owen-scrambled Sobol −1.5 (smooth), −0.75 (edge).");
}
