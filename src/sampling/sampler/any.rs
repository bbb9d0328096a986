//! A sampler chosen at run time.

use glam::Vec2;

#[cfg(feature = "sobol")]
use super::SobolSampler;
use super::{IndependentSampler, Sampler, StratifiedSampler};

/// One of the crate's samplers, chosen at run time (for example from a scene file's
/// `<sampler type="...">` or a `--sampler` option), itself a [`Sampler`].
///
/// Each call dispatches with a `match`; a renderer that wants no dispatch in its inner loop can
/// match once and call generic code with the concrete type instead.
///
/// ```
/// use mcrt::sampling::sampler::{AnySampler, Sampler, StratifiedSampler};
///
/// let mut s: AnySampler = StratifiedSampler::new(10, 0, true).unwrap().into();
/// assert_eq!(s.samples_per_pixel(), 16);
/// s.start_pixel_sample([0, 0], 0);
/// assert!(s.next_1d() < 1.0);
/// ```
#[derive(Debug, Clone)]
pub enum AnySampler {
    /// [`IndependentSampler`].
    Independent(IndependentSampler),
    /// [`StratifiedSampler`].
    Stratified(StratifiedSampler),
    /// `SobolSampler` (feature `sobol`).
    #[cfg(feature = "sobol")]
    Sobol(SobolSampler),
}

/// Forwards a call to the wrapped sampler.
macro_rules! dispatch {
    ($self:ident, $s:ident => $call:expr) => {
        match $self {
            AnySampler::Independent($s) => $call,
            AnySampler::Stratified($s) => $call,
            #[cfg(feature = "sobol")]
            AnySampler::Sobol($s) => $call,
        }
    };
}

impl Sampler for AnySampler {
    #[inline]
    fn start_pixel_sample(&mut self, pixel: [u32; 2], sample_index: u32) {
        dispatch!(self, s => s.start_pixel_sample(pixel, sample_index))
    }

    #[inline]
    fn next_1d(&mut self) -> f32 {
        dispatch!(self, s => s.next_1d())
    }

    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        dispatch!(self, s => s.next_2d())
    }

    fn samples_per_pixel(&self) -> u32 {
        dispatch!(self, s => s.samples_per_pixel())
    }
}

impl From<IndependentSampler> for AnySampler {
    fn from(s: IndependentSampler) -> Self {
        Self::Independent(s)
    }
}

impl From<StratifiedSampler> for AnySampler {
    fn from(s: StratifiedSampler) -> Self {
        Self::Stratified(s)
    }
}

#[cfg(feature = "sobol")]
impl From<SobolSampler> for AnySampler {
    fn from(s: SobolSampler) -> Self {
        Self::Sobol(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn values<S: Sampler>(mut s: S) -> Vec<f32> {
        s.start_pixel_sample([3, 4], 2);
        let u = s.next_2d();
        vec![u.x, u.y, s.next_1d(), s.samples_per_pixel() as f32]
    }

    #[test]
    fn wrapping_changes_nothing() {
        let a = IndependentSampler::new(8, 1).unwrap();
        assert_eq!(values(a.clone()), values(AnySampler::from(a)));
        let b = StratifiedSampler::new(8, 1, true).unwrap();
        assert_eq!(values(b.clone()), values(AnySampler::from(b)));
        #[cfg(feature = "sobol")]
        {
            let c = SobolSampler::new(8, 1).unwrap();
            assert_eq!(values(c.clone()), values(AnySampler::from(c)));
        }
    }
}
