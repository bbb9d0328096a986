//! Tabulated and analytic distributions: piecewise-constant 1D and 2D, piecewise-linear 2D
//! (bilinear), summed-area tables and windowed 2D sampling, the alias table, and the
//! inversion method for a density given by its CDF.

mod alias;
mod inversion;
mod piecewise_1d;
mod piecewise_2d;
mod piecewise_linear_2d;
mod summed_area;

pub use alias::*;
pub use inversion::*;
pub use piecewise_1d::*;
pub use piecewise_2d::*;
pub use piecewise_linear_2d::*;
pub use summed_area::*;
