//! Why a sensor description cannot make a [`Camera`](super::Camera).

use std::fmt;

/// Why a sensor description cannot make a camera.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum CameraError {
    /// `fov` is not in (0°, 180°).
    InvalidFov(f32),
    /// The film has zero width or height.
    EmptyFilm {
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
    },
    /// The clip distances are not `0 < near_clip < far_clip < ∞`.
    InvalidClip {
        /// `near_clip`.
        near: f32,
        /// `far_clip`.
        far: f32,
    },
    /// `to_world` is not finite, affine and invertible.
    BadTransform,
    /// A thin lens's aperture radius is negative or not finite, or its focus distance is
    /// not finite and positive.
    InvalidLens {
        /// `aperture_radius`.
        aperture_radius: f32,
        /// `focus_distance`.
        focus_distance: f32,
    },
    /// An orthographic sensor was given a thin lens.
    OrthographicLens,
}

impl fmt::Display for CameraError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidFov(v) => write!(f, "sensor fov {v} must lie in (0, 180) degrees"),
            Self::EmptyFilm { width, height } => write!(f, "film size {width}x{height} is empty"),
            Self::InvalidClip { near, far } => {
                write!(
                    f,
                    "clip distances near {near}, far {far}: need 0 < near < far < inf"
                )
            }
            Self::BadTransform => write!(f, "sensor to_world is not finite, affine and invertible"),
            Self::InvalidLens {
                aperture_radius,
                focus_distance,
            } => write!(
                f,
                "thin lens aperture_radius {aperture_radius}, focus_distance {focus_distance}: \
                 need a finite radius >= 0 and a finite distance > 0"
            ),
            Self::OrthographicLens => write!(f, "an orthographic sensor has no lens"),
        }
    }
}

impl std::error::Error for CameraError {}
