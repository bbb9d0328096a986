//! Acceleration structures over primitives given by their bounding boxes: a SAH BVH (built
//! binary, [`Bvh`], then collapsed to 4-wide nodes, [`Bvh4`], which is what
//! [`AccelKind::Bvh`] uses), a uniform grid ([`Grid`]), an SAH kd-tree ([`KdTree`]) and
//! brute force, selected by [`AccelKind`].
//!
//! They know nothing of the primitives themselves: a query calls back with primitive
//! indices and the caller intersects them. The primitives must be stored in the order
//! [`Accel::order`] reports (the BVH's leaves cover contiguous ranges of that order).
//!
//! ```
//! use mcrt::glam::Vec3;
//! use mcrt::scene::accel::{Aabb, Accel, AccelKind};
//!
//! // Two unit boxes along x; a ray down the x axis from the left hits box 0 first.
//! let boxes = [
//!     Aabb { min: Vec3::new(0.0, -0.5, -0.5), max: Vec3::new(1.0, 0.5, 0.5) },
//!     Aabb { min: Vec3::new(2.0, -0.5, -0.5), max: Vec3::new(3.0, 0.5, 0.5) },
//! ];
//! for kind in [AccelKind::Bvh, AccelKind::Grid, AccelKind::KdTree, AccelKind::BruteForce] {
//!     let accel = Accel::build(kind, &boxes);
//!     let stored = accel.order().to_vec();
//!     // "Intersect" a box at its lower x face.
//!     let t = accel.closest(Vec3::new(-1.0, 0.0, 0.0), Vec3::X, f32::INFINITY, |i, t_max| {
//!         let t = boxes[stored[i as usize] as usize].min.x + 1.0;
//!         (t < t_max).then_some(t)
//!     });
//!     assert_eq!(t, Some(1.0));
//! }
//! ```

mod aabb;
mod bvh;
mod bvh4;
mod grid;
mod kdtree;
mod traverse;

pub use aabb::{Aabb, RayBoxTest};
pub use bvh::{Bvh, BINS, MAX_LEAF};
pub use bvh4::Bvh4;
pub use grid::{Grid, DENSITY, MAX_RES};
pub use kdtree::{KdTree, KdTreeStats, EMPTY_BONUS, INTERSECTION_COST, MAX_DEPTH, TRAVERSAL_COST};

use glam::Vec3;

/// Which acceleration structure to build.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AccelKind {
    /// A bounding volume hierarchy built with the binned surface area heuristic and
    /// collapsed to 4-wide nodes ([`Bvh4`]; the default).
    #[default]
    Bvh,
    /// A uniform grid traversed with a 3D DDA.
    Grid,
    /// A kd-tree built with the surface area heuristic in O(N log N) ([`KdTree`]).
    KdTree,
    /// No structure: every primitive is tested (for reference and tests).
    BruteForce,
}

/// A built acceleration structure.
#[derive(Debug, Clone)]
pub struct Accel {
    imp: Imp,
    order: Vec<u32>,
}

#[derive(Debug, Clone)]
enum Imp {
    Bvh(Bvh4),
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
                    imp: Imp::Bvh(bvh),
                    order,
                }
            }
            AccelKind::Grid => Self {
                imp: Imp::Grid(Grid::build(bounds)),
                order: identity(),
            },
            AccelKind::KdTree => Self {
                imp: Imp::KdTree(KdTree::build(bounds)),
                order: identity(),
            },
            AccelKind::BruteForce => Self {
                imp: Imp::BruteForce(bounds.len() as u32),
                order: identity(),
            },
        }
    }

    /// Which kind this is.
    pub fn kind(&self) -> AccelKind {
        match self.imp {
            Imp::Bvh(_) => AccelKind::Bvh,
            Imp::Grid(_) => AccelKind::Grid,
            Imp::KdTree(_) => AccelKind::KdTree,
            Imp::BruteForce(_) => AccelKind::BruteForce,
        }
    }

    /// The 4-wide BVH when this is [`AccelKind::Bvh`], for leaf-level queries
    /// ([`Bvh4::closest_leaf`], [`Bvh4::any_leaf`]).
    pub fn bvh4(&self) -> Option<&Bvh4> {
        match &self.imp {
            Imp::Bvh(b) => Some(b),
            _ => None,
        }
    }

    /// `order()[i]` is the input index of the primitive to store at position `i`; query
    /// callbacks receive positions in that stored order.
    pub fn order(&self) -> &[u32] {
        &self.order
    }

    /// The nearest hit: `test(i, t_max)` intersects stored primitive `i` and returns its
    /// distance if below `t_max`; the bound then shrinks. Returns the nearest distance.
    #[inline]
    pub fn closest(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        mut test: impl FnMut(u32, f32) -> Option<f32>,
    ) -> Option<f32> {
        match &self.imp {
            Imp::Bvh(b) => b.closest(origin, dir, t_max, test),
            Imp::Grid(g) => g.closest(origin, dir, t_max, test),
            Imp::KdTree(k) => k.closest(origin, dir, t_max, test),
            Imp::BruteForce(n) => {
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

    /// True as soon as `test(i, t_max)` holds for some stored primitive `i`.
    #[inline]
    pub fn any(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        mut test: impl FnMut(u32, f32) -> bool,
    ) -> bool {
        match &self.imp {
            Imp::Bvh(b) => b.any(origin, dir, t_max, test),
            Imp::Grid(g) => g.any(origin, dir, t_max, test),
            Imp::KdTree(k) => k.any(origin, dir, t_max, test),
            Imp::BruteForce(n) => (0..*n).any(|i| test(i, t_max)),
        }
    }
}
