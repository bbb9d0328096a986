//! # mcrt: Monte Carlo sampling and light transport
//!
//! Sampling code a renderer can trust: every warp ships its pdf and (where it exists) its
//! inverse, every pdf is proven by a chi-square test, and no input produces a NaN.
//!
//! ## Module map
//!
//! | module | what it holds | feature |
//! |---|---|---|
//! | [`sampling::warp`] | maps from the unit square to disks, triangles, hemispheres, spheres, cones, microfacet normals, spherical triangles and rectangles (uniform and cosine-weighted), bilinear patches, phase-function lobes (Henyey–Greenstein, von Mises–Fisher), Box–Muller; 1D densities ([`sampling::warp::Warp1D`]: linear, tent, exponential, normal, logistic, smoothstep) | always |
//! | [`sampling::distribution`] | piecewise-constant 1D and 2D distributions, piecewise-linear (bilinear) 2D, summed-area tables and windowed 2D sampling, the alias table, the inversion method | always |
//! | [`sampling::jacobian`] | change of variables between measures, numerical Jacobians of any warp | always |
//! | [`sampling::mis`] | balance and power heuristics | always |
//! | [`sampling::light_bvh`] | the light BVH: one light among many, chosen by a conservative bound on its contribution at a point | always |
//! | [`sampling::sampler`] | independent, stratified and low-discrepancy (Sobol, Halton, R2) sample generators | always (Sobol needs `sobol`) |
#![cfg_attr(
    feature = "stats",
    doc = "| [`stats`] | the public chi-square goodness-of-fit harness and pdf-integration checks | `stats` |"
)]
#![cfg_attr(
    not(feature = "stats"),
    doc = "| `stats` | the public chi-square goodness-of-fit harness and pdf-integration checks | `stats` |"
)]
//! | [`integrator`] | path tracing, direct lighting, bidirectional path tracing and Metropolis light transport, over small traits ([`integrator::Scene`], [`integrator::Bsdf`]) that any renderer implements | always |
//!
//! ## A first example
//!
//! The irradiance under a uniform sky of radiance 1 is `∫ cos θ dω = π`: cosine-weighted
//! directions about `+z`, turned about a surface normal by a [`sampling::Frame`], estimate
//! it (exactly, since `cos θ / pdf = π` for every sample), with the values of a
//! [`sampling::sampler::Sampler`].
//!
//! ```
//! use mcrt::glam::{Vec2, Vec3};
//! use mcrt::sampling::sampler::{IndependentSampler, SampleSource, Sampler};
//! use mcrt::sampling::warp::{CosineHemisphere, InvertibleWarp, Warp};
//! use mcrt::sampling::Frame;
//!
//! let frame = Frame::from_normal(Vec3::new(0.0, 0.6, 0.8));
//! let mut sampler = IndependentSampler::new(64, 7).unwrap();
//! let mut sum = 0.0;
//! for i in 0..64 {
//!     sampler.start_pixel_sample([0, 0], i);
//!     let (local, pdf) = CosineHemisphere.sample_with_pdf(sampler.next_2d());
//!     let w = frame.to_world(local); // a direction about the normal
//!     sum += w.dot(frame.n) / pdf; // radiance · cos θ / pdf
//! }
//! assert!((sum / 64.0 - std::f32::consts::PI).abs() < 1e-4);
//!
//! // Every warp has its pdf beside it and, where one exists, its inverse.
//! let u = Vec2::new(0.3, 0.8);
//! assert!((CosineHemisphere.invert(CosineHemisphere.sample(u)) - u).length() < 1e-5);
//! ```
//!
//! To run the estimators on geometry, materials and lights of your own, implement
//! [`integrator::Scene`] and [`integrator::Bsdf`]: `examples/custom_scene.rs` does so for a
//! glowing sphere and prints the path tracer's estimate next to the analytic answer
//! (`cargo run --release --example custom_scene`). `examples/chi2_custom_warp.rs` tests a
//! warp of your own with the chi-square harness.
//!
//! ## Conventions
//!
//! - **Sample values** `u` lie in `[0, 1)^d`. Warps take `u`, never an RNG, so they can be
//!   stratified, driven by low-discrepancy sequences and inverted.
//! - **Shading frame**: directions in local frames are z-up; the normal is `(0, 0, 1)` and
//!   `cos θ = z`.
//! - **Measures**: every pdf states its measure in its doc. Directional pdfs are per unit
//!   solid angle (steradian); planar ones per unit area; triangle ones per unit barycentric
//!   area (the reference triangle has area 1/2).
//! - **Precision**: `f32` and [`glam`] types in the public API, `f64` inside statistics and
//!   accumulation.
//! - **Errors**: constructors validate their input and return `Result`; nothing panics on
//!   user data.
#![forbid(unsafe_code)]
#![deny(missing_docs)]
#![deny(rustdoc::broken_intra_doc_links)]

pub use glam;

#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;

pub mod integrator;
pub mod sampling;
#[cfg(feature = "stats")]
pub mod stats;

// What a renderer author reaches for first, at the crate root (as `rand_distr` does). Each
// item's one home is its module (`sampling::warp`, `sampling::distribution`, ...); these are
// re-exports of it, and the docs show them as such.
#[doc(no_inline)]
pub use integrator::{
    Bdpt, BidirectionalScene, Bsdf, BsdfFlags, BsdfSample, DirectIntegrator, Integrator,
    LightSample, Mlt, PathResult, PathTracer, Scene, Strategy, SurfacePoint,
};
#[doc(no_inline)]
pub use sampling::distribution::{
    AliasTable, Inversion1D, PiecewiseConstant1D, PiecewiseConstant2D, PiecewiseLinear2D,
    SummedAreaTable, WindowedPiecewiseConstant2D,
};
#[doc(no_inline)]
pub use sampling::light_bvh::{LightBounds, LightBvh};
#[doc(no_inline)]
pub use sampling::mis::{balance_heuristic, power_heuristic};
#[doc(no_inline)]
pub use sampling::sampler::{
    AnySampler, CmjSampler, HaltonSampler, IndependentSampler, R2Sampler, SampleSource, Sampler,
    StratifiedSampler,
};
#[cfg(feature = "sobol")]
#[doc(no_inline)]
pub use sampling::sampler::{Sobol4dSampler, SobolSampler};
#[doc(no_inline)]
pub use sampling::warp::{
    Beckmann, BeckmannVisible, Bilinear, BilinearPatch, CosineHemisphere, CosineSphericalTriangle,
    Exponential, Ggx, GgxVisible, HenyeyGreenstein, InvertibleWarp, LatLong, Linear, Logistic,
    LowDistortionTriangle, MicrofacetDistribution, Normal, Normal2D, PowerCosineHemisphere,
    Smoothstep, SphericalRectangle, SphericalTriangle, Tent, ThetaOverSinHemisphere,
    TrimmedLogistic, TruncatedExponential, UniformCone, UniformDisk, UniformDiskConcentric,
    UniformHemisphere, UniformSphere, UniformTriangle, VonMisesFisher, Warp, Warp1D,
};
#[doc(no_inline)]
pub use sampling::{Frame, SamplingError};
