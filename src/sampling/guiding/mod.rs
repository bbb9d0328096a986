//! Path guiding (Müller, Gross & Novák 2017, "Practical Path Guiding for Efficient
//! Light-Transport Simulation", Computer Graphics Forum 36(4)): an [`SdTree`] learns the
//! radiance arriving in each region of space as a directional quadtree ([`DQuadTree`]) over
//! the equal-area square of the sphere ([`square_to_sphere`]), in training passes of doubling
//! sample counts ([`GuidingSchedule`]), and
//! [`GuidedPathTracer`](crate::integrator::GuidedPathTracer) samples directions from it.
//!
//! Densities: a quadtree leaf cell `C` of area `|C|` on the unit square with a share `E_C/E`
//! of the energy has the density `p□ = E_C / (E |C|)` on the square and
//! `p□ / (4π)` per steradian on the sphere (the map has the constant Jacobian `4π`).

mod filter;
mod map;
mod quadtree;
mod records;
mod schedule;
mod spatial;
#[cfg(test)]
mod tests;

pub use filter::GuidingFilter;
pub use map::{sphere_to_square, square_to_sphere, EqualAreaSphere, SQUARE_TO_SPHERE_JACOBIAN};
pub use quadtree::DQuadTree;
pub use records::{GuidingRecord, GuidingRecords};
pub(crate) use records::{PathVertex, SelectionRecord, StoredRecord};
pub use schedule::{GuidingPass, GuidingSchedule};
pub use spatial::SdTree;
