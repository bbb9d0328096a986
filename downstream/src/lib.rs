//! # mcrt-downstream: mcrt as a user's crate sees it
//!
//! A crate of the workspace that is not published (`publish = false`) and depends on `mcrt`
//! the way a renderer author's crate does: by version, with default features, through the
//! public API only, and through the crate-root re-exports where they exist
//! (`mcrt::CosineHemisphere`, `mcrt::PathTracer`, `mcrt::Scene`, ...). This library defines
//! what such a crate would: a warp of its own ([`Tent2D`]), a Lambertian BSDF ([`Lambert`])
//! and a scene ([`Shell`]) implementing `mcrt::Bsdf` and `mcrt::Scene`, and an environment
//! map ([`Sky`]) sampled through `mcrt::PiecewiseConstant2D` and `mcrt::LatLong`. Its tests
//! (`downstream/tests/`) check them against analytic answers and mcrt's chi-square harness,
//! and check the library's list of normal dependencies.
//!
//! **Why it exists.** A breaking change to mcrt's public API (a renamed or moved item, a
//! changed signature, a new required trait method) fails this crate's build, so
//! `cargo test --release` at the workspace root, and CI, fail until this crate, its tests and
//! `CHANGELOG.md` are updated together. Fix the break here as a user would, and record it in
//! the changelog.
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod scene;
pub mod sky;
pub mod warp;

pub use scene::{Lambert, Shell};
pub use sky::Sky;
pub use warp::Tent2D;
