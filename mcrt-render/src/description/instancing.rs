//! Shape groups and their instances (Mitsuba 3's `shapegroup` and `instance`), and the
//! numbering of shapes that hits report when a scene has instances.
//!
//! A [`ShapeGroupDesc`] is shared by its instances ([`ShapeKind::Instance`] holds an
//! `Arc` to it), so a scene of many instances holds the group's shapes once. Shapes are
//! numbered as [`SurfacePoint::shape`](mcrt::integrator::SurfacePoint::shape) reports
//! them: first the scene's own shapes (`SceneDescription::shapes`, instances included,
//! which are never hit themselves), then the shapes of each distinct group in the order its
//! first instance appears ([`SceneDescription::all_shapes`]).

use super::{Checked, SceneDescription, ShapeDesc, ShapeKind};
use std::borrow::Borrow;
use std::collections::HashSet;
use std::fmt;
use std::sync::Arc;

/// A group of shapes that is not rendered itself but through instances
/// ([`ShapeKind::Instance`]), each with a `to_world` of its own: Mitsuba 3's `shapegroup`.
///
/// As in Mitsuba 3 (`src/render/shapegroup.cpp`), the shapes of a group carry their own
/// materials, may not carry area emitters, and may not be instances themselves (no nested
/// instancing): a group is held as a [`Checked`] one, whose check refuses a group that
/// breaks these rules.
///
/// `Debug` prints the id and the number of shapes only, so that a description with many
/// instances of a large group prints in size proportional to the instances.
#[derive(Clone, PartialEq, Default)]
pub struct ShapeGroupDesc {
    /// The `id` attribute, if any.
    pub id: Option<String>,
    /// The shapes, each with its `to_world` in the group's space.
    pub shapes: Vec<Checked<ShapeDesc>>,
}

impl fmt::Debug for ShapeGroupDesc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "ShapeGroupDesc {{ id: {:?}, {} shapes }}",
            self.id,
            self.shapes.len()
        )
    }
}

/// The distinct groups that the instances among `shapes` refer to (by `Arc` identity), in
/// the order of their first instance.
pub fn groups_of<S: Borrow<ShapeDesc>>(shapes: &[S]) -> Vec<&Arc<Checked<ShapeGroupDesc>>> {
    let mut seen = HashSet::new();
    shapes
        .iter()
        .filter_map(|s| match &s.borrow().kind {
            ShapeKind::Instance(g) => seen.insert(Arc::as_ptr(g)).then_some(g),
            _ => None,
        })
        .collect()
}

impl SceneDescription {
    /// The distinct shape groups the scene's instances refer to, in the order of their
    /// first instance (see the module docs of `description::instancing`).
    pub fn shape_groups(&self) -> Vec<&Arc<Checked<ShapeGroupDesc>>> {
        groups_of(&self.shapes)
    }

    /// Every shape in the numbering hits report ([`SurfacePoint::shape`](
    /// mcrt::integrator::SurfacePoint::shape)): [`SceneDescription::shapes`], then the
    /// shapes of each group of [`SceneDescription::shape_groups`]. Without instances, just
    /// `shapes`.
    pub fn all_shapes(&self) -> Vec<&ShapeDesc> {
        let groups = self.shape_groups();
        self.shapes
            .iter()
            .map(|s| &**s)
            .chain(
                groups
                    .into_iter()
                    .flat_map(|g| g.shapes.iter().map(|s| &**s)),
            )
            .collect()
    }
}
