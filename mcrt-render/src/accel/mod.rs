//! Acceleration structures over primitives given by their bounding boxes: a SAH BVH (built
//! binary, then collapsed to 4-wide or to 8-wide nodes), a uniform grid, an SAH kd-tree and
//! brute force, selected by [`AccelKind`] and built as an [`Accel`].
//!
//! They know nothing of the primitives themselves: a query calls back with the index of a
//! primitive (its position in the bounds given to [`Accel::build`]) and the caller
//! intersects it. (The scene's [`Geometry`](crate::geometry::Geometry) stores its
//! triangles inside the BVH's leaves instead, for 4-wide tests; `docs/geometry.md`.)
//!
//! ```
//! use mcrt::glam::Vec3;
//! use mcrt_render::accel::{Aabb, Accel, AccelKind};
//!
//! // Two unit boxes along x; a ray down the x axis from the left hits box 0 first.
//! let boxes = [
//!     Aabb { min: Vec3::new(0.0, -0.5, -0.5), max: Vec3::new(1.0, 0.5, 0.5) },
//!     Aabb { min: Vec3::new(2.0, -0.5, -0.5), max: Vec3::new(3.0, 0.5, 0.5) },
//! ];
//! for kind in [AccelKind::Bvh, AccelKind::Bvh8, AccelKind::Grid, AccelKind::KdTree, AccelKind::BruteForce] {
//!     let accel = Accel::build(kind, &boxes);
//!     // "Intersect" a box at its lower x face.
//!     let t = accel.closest(Vec3::new(-1.0, 0.0, 0.0), Vec3::X, f32::INFINITY, |i, t_max| {
//!         let t = boxes[i as usize].min.x + 1.0;
//!         (t < t_max).then_some(t)
//!     });
//!     assert_eq!(t, Some(1.0));
//! }
//! ```

mod aabb;
mod bvh;
mod bvh4;
mod bvh8;
mod bvh_build;
#[cfg(test)]
mod bvh_build_tests;
mod bvh_node;
mod grid;
mod kdtree;
mod lanes8;
mod leaf_queries;
mod stack;
mod traverse;
mod traverse8;
mod wide_bvh;

pub use aabb::Aabb;

/// Heap bytes held by a vector (its capacity).
pub(crate) fn vec_bytes<T>(v: &Vec<T>) -> usize {
    v.capacity() * std::mem::size_of::<T>()
}
pub(crate) use bvh4::Bvh4;
pub(crate) use bvh8::Bvh8;
use grid::Grid;
use kdtree::KdTree;
#[cfg(test)]
pub(crate) use lanes8::Simd8;
pub(crate) use lanes8::{Lanes8, WithLanes8};
pub(crate) use leaf_queries::LeafQueries;

use glam::Vec3;

/// Which acceleration structure to build.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AccelKind {
    /// A bounding volume hierarchy built with the binned surface area heuristic and
    /// collapsed to 4-wide nodes (the default).
    #[default]
    Bvh,
    /// The same BVH collapsed to 8-wide nodes, whose boxes are tested at once with AVX2
    /// where the processor has it (chosen at run time), else as two 4-wide halves
    /// (`docs/geometry.md`, "The 8-wide BVH").
    Bvh8,
    /// A uniform grid traversed with a 3D DDA.
    Grid,
    /// A kd-tree built with the surface area heuristic in O(N log N) (Wald & Havran 2006; `docs/geometry.md`).
    KdTree,
    /// No structure: every primitive is tested (for reference and tests).
    BruteForce,
}

/// A built acceleration structure.
#[derive(Debug, Clone)]
pub struct Accel {
    structure: Structure,
    /// `order[i]`: the input index of the primitive at position `i` of the structure's
    /// leaves (identity but for the BVH, whose leaves cover ranges of it).
    order: Vec<u32>,
}

#[derive(Debug, Clone)]
enum Structure {
    Bvh(Bvh4),
    Bvh8(Bvh8),
    Grid(Grid),
    KdTree(KdTree),
    BruteForce(u32),
}

impl Accel {
    /// Builds the structure of the given kind over primitives with the given bounds.
    pub fn build(kind: AccelKind, bounds: &[Aabb]) -> Self {
        let identity = || (0..bounds.len() as u32).collect();
        match kind {
            AccelKind::Bvh => {
                let bvh = Bvh4::build(bounds);
                let order = bvh.order().to_vec();
                Self {
                    structure: Structure::Bvh(bvh),
                    order,
                }
            }
            AccelKind::Bvh8 => {
                let bvh = Bvh8::build(bounds);
                let order = bvh.order().to_vec();
                Self {
                    structure: Structure::Bvh8(bvh),
                    order,
                }
            }
            AccelKind::Grid => Self {
                structure: Structure::Grid(Grid::build(bounds)),
                order: identity(),
            },
            AccelKind::KdTree => Self {
                structure: Structure::KdTree(KdTree::build(bounds)),
                order: identity(),
            },
            AccelKind::BruteForce => Self {
                structure: Structure::BruteForce(bounds.len() as u32),
                order: identity(),
            },
        }
    }

    /// Heap bytes held by the structure (its nodes, cells and primitive lists): O(n) for
    /// the BVH and the grid and O(n log n) at most for the kd-tree, whatever the primitives
    /// (`docs/geometry.md`, "Bounds on degenerate input").
    pub fn heap_bytes(&self) -> usize {
        vec_bytes(&self.order)
            + match &self.structure {
                Structure::Bvh(b) => b.heap_bytes(),
                Structure::Bvh8(b) => b.heap_bytes(),
                Structure::Grid(g) => g.heap_bytes(),
                Structure::KdTree(k) => k.heap_bytes(),
                Structure::BruteForce(_) => 0,
            }
    }

    /// Which kind this is.
    pub fn kind(&self) -> AccelKind {
        match self.structure {
            Structure::Bvh(_) => AccelKind::Bvh,
            Structure::Bvh8(_) => AccelKind::Bvh8,
            Structure::Grid(_) => AccelKind::Grid,
            Structure::KdTree(_) => AccelKind::KdTree,
            Structure::BruteForce(_) => AccelKind::BruteForce,
        }
    }

    /// The nearest hit: `test(i, t_max)` intersects primitive `i` (an index into the bounds
    /// given to [`Accel::build`]) and returns its distance if below `t_max`; the bound then
    /// shrinks. Returns the nearest distance.
    #[inline]
    pub fn closest(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        mut test: impl FnMut(u32, f32) -> Option<f32>,
    ) -> Option<f32> {
        match &self.structure {
            Structure::Bvh(b) => {
                let order = &self.order;
                b.closest(origin, dir, t_max, |i, t| test(order[i as usize], t))
            }
            Structure::Bvh8(b) => {
                let order = &self.order;
                b.closest(origin, dir, t_max, |i, t| test(order[i as usize], t))
            }
            Structure::Grid(g) => g.closest(origin, dir, t_max, test),
            Structure::KdTree(k) => k.closest(origin, dir, t_max, test),
            Structure::BruteForce(n) => {
                let mut best = None;
                let mut bound = t_max;
                for i in 0..*n {
                    if let Some(t) = test(i, bound) {
                        bound = t;
                        best = Some(t);
                    }
                }
                best
            }
        }
    }

    /// True as soon as `test(i, t_max)` holds for some primitive `i`.
    #[inline]
    pub fn any(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        mut test: impl FnMut(u32, f32) -> bool,
    ) -> bool {
        match &self.structure {
            Structure::Bvh(b) => {
                let order = &self.order;
                b.any(origin, dir, t_max, |i, t| test(order[i as usize], t))
            }
            Structure::Bvh8(b) => {
                let order = &self.order;
                b.any(origin, dir, t_max, |i, t| test(order[i as usize], t))
            }
            Structure::Grid(g) => g.any(origin, dir, t_max, test),
            Structure::KdTree(k) => k.any(origin, dir, t_max, test),
            Structure::BruteForce(n) => (0..*n).any(|i| test(i, t_max)),
        }
    }
}
