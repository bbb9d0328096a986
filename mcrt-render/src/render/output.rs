//! A finished render and its images.

use crate::film::{write_exr, write_exr_with_channels, write_png, Film, ImageError};
use glam::Vec3;
use std::path::Path;

/// A finished (or cancelled) render.
pub struct RenderOutput {
    /// The accumulated samples.
    pub film: Film,
    /// Samples rendered.
    pub samples: u64,
    /// Rays cast.
    pub rays: u64,
    /// Samples whose value came out NaN or infinite; they are added to their pixel as 0
    /// and counted here (a correct render has none).
    pub nonfinite_samples: u64,
    /// Wall-clock render time in seconds.
    pub seconds: f64,
    /// For bidirectional path tracing: what each strategy contributed.
    pub strategies: Option<mcrt::integrator::StrategyStats>,
    /// For the guided path tracer: its training passes and what they cost (their time is
    /// part of [`RenderOutput::seconds`]; [`RenderOutput::samples`] counts the final
    /// pass's samples, the image's).
    pub guiding: Option<super::GuidingReport>,
}

impl RenderOutput {
    /// The image (per-pixel means), row-major from the top-left.
    pub fn image(&self) -> Vec<Vec3> {
        self.film.mean()
    }

    /// Writes the image as linear float RGB EXR, with the `moment` integrator's channels
    /// if the scene has it.
    pub fn write_exr(&self, path: &Path) -> Result<(), ImageError> {
        let image = self.image();
        let extra = self.film.extra_channels(&image, 0.0);
        write_exr_with_channels(path, self.film.width(), self.film.height(), &image, &extra)
    }

    /// Writes the image as sRGB PNG.
    pub fn write_png(&self, path: &Path) -> Result<(), ImageError> {
        write_png(path, self.film.width(), self.film.height(), &self.image())
    }

    /// Writes the per-pixel variance of the estimate as EXR.
    pub fn write_variance_exr(&self, path: &Path) -> Result<(), ImageError> {
        write_exr(
            path,
            self.film.width(),
            self.film.height(),
            &self.film.variance(),
        )
    }
}
