//! Why a scene could not be prepared for rendering.

use crate::camera::CameraError;
use crate::description::Origin;
use crate::geometry::GeometryError;
use crate::light::LightError;
use mcrt::sampling::SamplingError;
use std::fmt;

/// Why [`Renderer::new`](super::Renderer::new) refused a scene. Each variant keeps the
/// typed error of the part that failed, as [`source`](std::error::Error::source).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum RenderError {
    /// What the render's options add is refused (the integrator `opts.integrator` makes of
    /// the scene's, the sample count, the total work, the film's memory); the message names
    /// the part.
    Invalid(String),
    /// The shapes could not be built.
    Geometry(GeometryError),
    /// The lights could not be set up.
    Lights(LightError),
    /// The camera could not be built.
    Camera(CameraError),
    /// A shape's material could not be built.
    Material {
        /// Index of the shape.
        shape: usize,
        /// Its `id` in the scene file, if any.
        id: Option<String>,
        /// Why.
        error: SamplingError,
    },
    /// The sampler could not be built.
    Sampler(SamplingError),
    /// The integrator cannot render this scene with these options.
    Unsupported {
        /// The integrator's name.
        integrator: &'static str,
        /// What it needs.
        reason: &'static str,
    },
    /// `--samples` or `--crop` cannot be applied (the message says why).
    Split(String),
    /// One of the other errors, at the element of the scene file it concerns (a shape
    /// whose geometry could not be built).
    Located {
        /// Where the part was written.
        at: Origin,
        /// What is wrong with it.
        error: Box<RenderError>,
    },
    /// The film has no pixels.
    EmptyFilm {
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
    },
}

impl fmt::Display for RenderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RenderError::Invalid(m) | RenderError::Split(m) => f.write_str(m),
            RenderError::Geometry(e) => write!(f, "geometry: {e}"),
            RenderError::Lights(e) => write!(f, "{e}"),
            RenderError::Camera(e) => write!(f, "camera: {e}"),
            RenderError::Material { shape, id, error } => {
                write!(f, "material of shape {shape} ({id:?}): {error}")
            }
            RenderError::Sampler(e) => write!(f, "sampler: {e}"),
            RenderError::Unsupported { integrator, reason } => write!(f, "{integrator}: {reason}"),
            RenderError::Located { at, error } => write!(f, "{at}: {error}"),
            RenderError::EmptyFilm { width, height } => {
                write!(f, "film size {width}×{height} is empty")
            }
        }
    }
}

impl std::error::Error for RenderError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            RenderError::Geometry(e) => Some(e),
            RenderError::Lights(e) => Some(e),
            RenderError::Camera(e) => Some(e),
            RenderError::Material { error, .. } | RenderError::Sampler(error) => Some(error),
            RenderError::Located { error, .. } => Some(error.as_ref()),
            _ => None,
        }
    }
}
