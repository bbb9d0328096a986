//! [`SampleSource`]: the values an estimator draws, one after another, for one pixel sample.

use glam::Vec2;

/// A source of uniform sample values in `[0,1)`, drawn one after another: what the
/// estimators of [`crate::integrator`] draw from. Every [`Sampler`](super::Sampler) is one
/// (positioned on its pixel sample first); so is any other generator a user writes (an RNG
/// wrapper, primary sample space for Metropolis sampling).
///
/// `next_1d` and `next_2d` are defined here only, and [`Sampler`](super::Sampler) extends
/// this trait, so a scope that imports both traits calls them without ambiguity:
///
/// ```
/// use mcrt::sampling::sampler::{IndependentSampler, SampleSource, Sampler};
///
/// let mut s = IndependentSampler::new(4, 1).unwrap();
/// s.start_pixel_sample([3, 5], 0);
/// let u = s.next_2d();
/// assert!((0.0..1.0).contains(&u.x) && (0.0..1.0).contains(&s.next_1d()));
/// ```
pub trait SampleSource {
    /// One value in `[0,1)`.
    fn next_1d(&mut self) -> f32;

    /// Two values in `[0,1)²`.
    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        let x = self.next_1d();
        Vec2::new(x, self.next_1d())
    }

    /// Switches to the sample stream `stream` (the bidirectional estimators draw the camera
    /// subpath from stream 0, the light subpath from 1 and connections from 2). Sources
    /// without streams ignore it (the default); the crate's samplers jump to dimension
    /// [`stream_dimension(stream)`](stream_dimension); Metropolis sampling keeps one stream
    /// per role so that a path's primary sample coordinates keep their meaning when its length
    /// changes (Hachisuka et al. 2014).
    #[inline]
    fn start_stream(&mut self, _stream: u32) {}
}

/// Dimensions between the starts of two sample streams of a [`Sampler`](super::Sampler).
pub const STREAM_DIMENSIONS: u32 = 1024;

/// The dimension at which a [`Sampler`](super::Sampler) starts sample stream `stream`:
/// `1 + stream · STREAM_DIMENSIONS` (the first stream starts after the pixel filter's
/// dimension; saturating).
#[inline]
#[must_use]
pub fn stream_dimension(stream: u32) -> u32 {
    1 + stream.saturating_mul(STREAM_DIMENSIONS)
}
