//! One level of the geometry: the scene's own primitives, or those of one shape group in
//! the group's space, stored in the slot order of their ray-query backend.

use super::data::{PrimId, PrimsView, ShapeData};
use super::query::{RayQuery, Stored};
use super::Prim;
use crate::accel::{vec_bytes, Aabb, AccelKind};
use glam::Vec3;
use rayon::prelude::*;

/// Primitives with their acceleration structure.
#[derive(Debug, Clone)]
pub(super) struct Level {
    /// Primitives in the ray-query backend's slot order.
    pub(super) prims: Vec<Prim>,
    /// Per stored primitive, what a hit on it reads (one lookup per hit).
    pub(super) slots: Vec<SlotData>,
    pub(super) query: RayQuery,
    /// The bounding box of every primitive.
    pub(super) bounds: Aabb,
}

impl Level {
    /// Builds the backend of kind `accel` over `view`'s primitives.
    pub(super) fn build(accel: AccelKind, view: PrimsView) -> Self {
        let q = RayQuery::build(accel, &view);
        // Gathers over every primitive, in parallel (`collect` keeps the order).
        Self {
            prims: q
                .slots
                .par_iter()
                .map(|&i| view.prims[i as usize])
                .collect(),
            slots: q
                .slots
                .par_iter()
                .map(|&i| {
                    let id = view.ids[i as usize];
                    SlotData {
                        id,
                        ng: face_normal(view.shapes, &id),
                    }
                })
                .collect(),
            query: q.query,
            bounds: q.bounds,
        }
    }

    /// The stored primitives, for the queries; `shapes` is every shape's data.
    #[inline(always)]
    pub(super) fn stored<'a>(&'a self, shapes: &'a [ShapeData]) -> Stored<'a> {
        Stored {
            prims: &self.prims,
            shapes,
        }
    }

    /// Heap bytes of the acceleration structure alone.
    pub(super) fn accel_bytes(&self) -> usize {
        self.query.heap_bytes()
    }

    /// Heap bytes of the stored primitives and their per-slot data.
    pub(super) fn prim_bytes(&self) -> usize {
        vec_bytes(&self.prims) + vec_bytes(&self.slots)
    }
}

/// What a hit on a stored primitive reads besides the primitive itself.
#[derive(Debug, Clone, Copy)]
pub(super) struct SlotData {
    /// The primitive's shape and index in it.
    pub(super) id: PrimId,
    /// A triangle's unit front normal ([`SurfacePoint::ng`](
    /// mcrt::integrator::SurfacePoint::ng)), else zero.
    pub(super) ng: Vec3,
}

/// The unit front normal of a triangle (zero for other primitives), as hits report it.
fn face_normal(shapes: &[ShapeData], id: &PrimId) -> Vec3 {
    match &shapes[id.shape as usize] {
        ShapeData::Mesh(m) => {
            let [a, b, c] = m.indices[id.prim as usize].map(|v| m.positions[v as usize]);
            let sign = if m.flip { -1.0 } else { 1.0 };
            sign * (b - a).cross(c - a).normalize_or(Vec3::Z)
        }
        _ => Vec3::ZERO,
    }
}
