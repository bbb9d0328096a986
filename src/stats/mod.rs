//! A public chi-square goodness-of-fit harness, and companion checks, to prove that a
//! sampler draws from the density it claims.
//!
//! - [`ChiSquareTest`] compares the histogram of samples over a [`Domain`] with the pdf
//!   integrated over each cell: [`Interval`], [`Rectangle`] (disks and triangles fit in
//!   one), [`Directions`] (sphere, hemisphere, spherical cap about any axis, with cells
//!   that resolve narrow lobes) and [`Discrete`] (categories). It takes any
//!   [`Warp`](crate::sampling::warp::Warp), a plain closure and a pdf closure, a BSDF-like
//!   closure returning a point and a weight, or exact cell masses for tabulated densities.
//! - [`check_integral`], [`check_jacobian`], [`check_inverse`] and [`check_weights`]:
//!   the pdf integrates to 1, `pdf(sample(u)) · J(u) = 1`, `invert(sample(u)) = u`, and a
//!   sample weight equals `value / pdf`.
//!
//! Everything is deterministic: a fixed seed, fixed chunks with one RNG stream each, and
//! results independent of the thread count. A failure gives a readable
//! [`Chi2Outcome::report`] and PNG images of the observed and expected histograms.
//!
//! The method follows Mitsuba 3's `chi2` module in outline (pooling below 5 expected
//! samples, Šidák correction); the code is our own.
//!
//! ```
//! use mcrt::glam::Vec2;
//! use mcrt::stats::{ChiSquareTest, Rectangle};
//!
//! // Uniform disk by r = √u₁ against the pdf 1/π on the unit disk.
//! let disk = |u: Vec2| {
//!     let (r, phi) = (u.x.sqrt(), std::f32::consts::TAU * u.y);
//!     Vec2::new(r * phi.cos(), r * phi.sin())
//! };
//! let pdf = |p: Vec2| if p.length_squared() <= 1.0 { std::f32::consts::FRAC_1_PI } else { 0.0 };
//! let test = ChiSquareTest::new(Rectangle::new(Vec2::splat(-1.0), Vec2::splat(1.0), 32, 32))
//!     .samples(200_000)
//!     .seed(1)
//!     .significance(0.01, 1)
//!     .name("doc-disk");
//! test.run(disk, pdf).assert_passed();
//!
//! // The "obvious but wrong" r = u₁ is rejected.
//! let wrong = |u: Vec2| {
//!     let phi = std::f32::consts::TAU * u.y;
//!     Vec2::new(u.x * phi.cos(), u.x * phi.sin())
//! };
//! let outcome = test.output_dir(None).run(wrong, pdf);
//! assert!(!outcome.passed());
//! println!("{}", outcome.report());
//! ```

mod checks;
mod chi2;
mod directions;
mod domain;
mod evaluate;
mod harness;
mod outcome;
mod parallel;
mod quadrature;
mod report;

pub use checks::{
    check_integral, check_inverse, check_jacobian, check_warp_inverse, check_warp_jacobian,
    check_weights, CheckOutcome, JacobianCheck,
};
pub use chi2::{p_value, sidak, CellCount, MIN_EXPECTED};
pub use directions::Directions;
pub use domain::{Discrete, Domain, Interval, PdfRef, Rectangle, StatPoint};
pub use evaluate::{RECHECK_MAX_CELLS, RECHECK_SIGMAS};
pub use harness::ChiSquareTest;
pub use outcome::{Chi2Failure, Chi2Outcome};
