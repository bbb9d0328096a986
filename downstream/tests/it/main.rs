//! The downstream checks that run in-process, one module per former test file, in one
//! binary. `dependencies.rs` stays a binary of its own: it runs `cargo tree`.

mod chi2;
mod path_tracer;
mod warps;
