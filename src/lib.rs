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
//! | [`sampling::sampler`] | independent, stratified and low-discrepancy (Sobol, Halton, R2) sample generators | always (Sobol needs `sobol`) |
//! | `stats` | the public chi-square goodness-of-fit harness and pdf-integration checks | `stats` |
//! | [`integrator`] | path tracing and direct lighting estimators of the light transport equation | always |
//! | `scene` | the reference scene, its Mitsuba 3 XML loader, and the renderer | `render` |
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
#[cfg(feature = "render")]
pub mod scene;
#[cfg(feature = "stats")]
pub mod stats;
