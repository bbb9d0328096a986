//! Why a scene's shapes could not be turned into geometry.

use std::fmt;

/// An error building [`super::Geometry`] from shape descriptions. Each names the shape by
/// its index in the list given (and its `id`, if it has one).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum GeometryError {
    /// A transform is not finite, not affine, or singular.
    BadTransform {
        /// Index of the shape.
        shape: usize,
        /// What is wrong, in words.
        what: &'static str,
    },
    /// A sphere's `to_world` scales non-uniformly or shears (Mitsuba allows only rotation,
    /// uniform scale and translation for spheres).
    NonUniformSphereScale {
        /// Index of the shape.
        shape: usize,
    },
    /// A parameter or a mesh is invalid (negative radius, index out of range, NaN vertex, ...).
    InvalidShape {
        /// Index of the shape.
        shape: usize,
        /// What is wrong, in words.
        what: String,
    },
    /// An OBJ file could not be read.
    Obj {
        /// Index of the shape.
        shape: usize,
        /// The reader's message (naming the file).
        message: String,
    },
    /// A PLY or `serialized` mesh file could not be read.
    MeshFile {
        /// Index of the shape.
        shape: usize,
        /// The reader's message (naming the file and the place in it).
        message: String,
    },
    /// The shapes up to this one, with the acceleration structure over them, would need
    /// more memory than the budget ([`crate::memory`]).
    Memory {
        /// Index of the shape at which the sum passed the budget.
        shape: usize,
        /// What would have been needed, and how to raise the limit.
        message: String,
    },
}

impl GeometryError {
    /// The index of the shape the error is about.
    pub fn shape(&self) -> usize {
        match self {
            Self::BadTransform { shape, .. }
            | Self::NonUniformSphereScale { shape }
            | Self::InvalidShape { shape, .. }
            | Self::Obj { shape, .. }
            | Self::MeshFile { shape, .. }
            | Self::Memory { shape, .. } => *shape,
        }
    }
}

impl fmt::Display for GeometryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::BadTransform { shape, what } => {
                write!(f, "shape {shape}: unusable to_world transform: {what}")
            }
            Self::NonUniformSphereScale { shape } => write!(
                f,
                "shape {shape}: a sphere's to_world may only rotate, scale uniformly and translate"
            ),
            Self::InvalidShape { shape, what } => write!(f, "shape {shape}: {what}"),
            Self::Obj { shape, message }
            | Self::MeshFile { shape, message }
            | Self::Memory { shape, message } => {
                write!(f, "shape {shape}: {message}")
            }
        }
    }
}

impl std::error::Error for GeometryError {}
