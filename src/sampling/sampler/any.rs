//! A sampler chosen at run time.

use glam::Vec2;

use super::{stream_dimension, SampleSource};
use super::{CmjSampler, HaltonSampler, IndependentSampler, R2Sampler, Sampler, StratifiedSampler};
#[cfg(feature = "sobol")]
use super::{Sobol4dSampler, SobolSampler};
use crate::sampling::SamplingError;

/// One of the crate's samplers, chosen at run time (for example from a scene file's
/// `<sampler type="...">` or a `--sampler` option), itself a [`Sampler`].
///
/// Each call dispatches with a `match`; a renderer that wants no dispatch in its inner loop can
/// match once and call generic code with the concrete type instead.
///
/// ```
/// use mcrt::sampling::sampler::{AnySampler, SampleSource, Sampler, StratifiedSampler};
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
    /// `Sobol4dSampler` (feature `sobol`).
    #[cfg(feature = "sobol")]
    Sobol4d(Sobol4dSampler),
    /// [`HaltonSampler`].
    Halton(HaltonSampler),
    /// [`R2Sampler`].
    R2(R2Sampler),
    /// [`CmjSampler`].
    Cmj(CmjSampler),
}

impl AnySampler {
    /// The names [`AnySampler::by_name`] accepts.
    pub const NAMES: [&'static str; 10] = [
        "independent",
        "stratified",
        "ldsampler",
        "sobol",
        "sobol4d",
        "halton",
        "r2",
        "multijitter",
        "cmj",
        "orthogonal",
    ];

    /// The sampler a name selects, for `spp` samples per pixel and a `seed`, with Mitsuba 3's
    /// sample-count rounding for its plugin names (case-insensitive):
    ///
    /// - `independent`: [`IndependentSampler`], `spp` as given;
    /// - `stratified`: jittered [`StratifiedSampler`], `spp` rounded up to a perfect square;
    /// - `ldsampler`: `Sobol4dSampler`, `spp` rounded up to a power of 4 (as Mitsuba's
    ///   `ldsampler`: 1 → 4, 5 → 16, 17 → 64);
    /// - `sobol`: `SobolSampler`, `spp` as given;
    /// - `sobol4d`: `Sobol4dSampler`, `spp` as given (ours only);
    /// - `halton`: [`HaltonSampler`], `spp` as given (our name: Mitsuba 3 has no such plugin);
    /// - `r2`: [`R2Sampler`], `spp` as given (likewise ours only);
    /// - `multijitter` or `cmj`: jittered [`CmjSampler`], `spp` rounded up to
    ///   `⌊√spp⌋ · ⌈spp / ⌊√spp⌋⌉` (as Mitsuba's `multijitter`: 5 → 6, 17 → 20);
    /// - `orthogonal`: jittered [`CmjSampler`] with `spp` rounded up to the square of a prime
    ///   (as Mitsuba's `orthogonal` of strength 2: 1 → 4, 5 → 9, 64 → 121, 256 → 289). Mitsuba's
    ///   sampler is an orthogonal array (Jarosz et al. 2019); ours of the same kind in each
    ///   2D dimension (one point per cell of a `p × p` grid and per `1/p²` column and row).
    ///
    /// `None` for any other name (and for `ldsampler`/`sobol` when the `sobol` feature is off);
    /// `Some(Err(_))` when the sample count is invalid.
    pub fn by_name(name: &str, spp: u32, seed: u64) -> Option<Result<Self, SamplingError>> {
        let name = name.to_ascii_lowercase();
        match name.as_str() {
            "independent" => Some(IndependentSampler::new(spp, seed).map(Self::from)),
            "stratified" => Some(StratifiedSampler::new(spp, seed, true).map(Self::from)),
            #[cfg(feature = "sobol")]
            "ldsampler" => Some(
                next_power_of_four(spp)
                    .ok_or(SamplingError::InvalidParameter {
                        name: "spp",
                        value: f64::from(spp),
                        expected: "at most 4^15",
                    })
                    .and_then(|n| Sobol4dSampler::new(n, seed))
                    .map(Self::from),
            ),
            #[cfg(feature = "sobol")]
            "sobol" => Some(SobolSampler::new(spp, seed).map(Self::from)),
            #[cfg(feature = "sobol")]
            "sobol4d" => Some(Sobol4dSampler::new(spp, seed).map(Self::from)),
            "halton" => Some(HaltonSampler::new(spp, seed).map(Self::from)),
            "r2" => Some(R2Sampler::new(spp, seed).map(Self::from)),
            "multijitter" | "cmj" => Some(CmjSampler::new(spp, seed, true).map(Self::from)),
            "orthogonal" => Some(
                next_prime_square(spp)
                    .ok_or(SamplingError::InvalidParameter {
                        name: "spp",
                        value: f64::from(spp),
                        expected: "at most 65521²",
                    })
                    .and_then(|n| CmjSampler::new(n, seed, true))
                    .map(Self::from),
            ),
            _ => None,
        }
    }
}

/// The smallest square of a prime at least `n` (so at least 4, as Mitsuba 3.9.1's
/// `orthogonal` rounds its `sample_count`), if it fits in `u32`.
pub(crate) fn next_prime_square(n: u32) -> Option<u32> {
    let is_prime = |p: u32| {
        p >= 2
            && (2..)
                .take_while(|d| d * d <= p)
                .all(|d| !p.is_multiple_of(d))
    };
    let mut p = 2u32;
    loop {
        let square = p.checked_mul(p)?;
        if square >= n && is_prime(p) {
            return Some(square);
        }
        p += 1;
    }
}

/// The smallest power of 4 at least `n`, and at least 4 (Mitsuba 3.9.1's `ldsampler` turns
/// 1 into 4 as well), if it fits in `u32`.
#[cfg(feature = "sobol")]
fn next_power_of_four(n: u32) -> Option<u32> {
    let mut p = 4u32;
    while p < n {
        p = p.checked_mul(4)?;
    }
    Some(p)
}

/// Forwards a call to the wrapped sampler.
macro_rules! dispatch {
    ($self:ident, $s:ident => $call:expr) => {
        match $self {
            AnySampler::Independent($s) => $call,
            AnySampler::Stratified($s) => $call,
            #[cfg(feature = "sobol")]
            AnySampler::Sobol($s) => $call,
            #[cfg(feature = "sobol")]
            AnySampler::Sobol4d($s) => $call,
            AnySampler::Halton($s) => $call,
            AnySampler::R2($s) => $call,
            AnySampler::Cmj($s) => $call,
        }
    };
}

impl Sampler for AnySampler {
    #[inline]
    fn start_pixel_sample(&mut self, pixel: [u32; 2], sample_index: u32) {
        dispatch!(self, s => s.start_pixel_sample(pixel, sample_index))
    }

    #[inline]
    fn skip_to_dimension(&mut self, dim: u32) {
        dispatch!(self, s => s.skip_to_dimension(dim))
    }

    fn samples_per_pixel(&self) -> u32 {
        dispatch!(self, s => s.samples_per_pixel())
    }
}

impl SampleSource for AnySampler {
    #[inline]
    fn next_1d(&mut self) -> f32 {
        dispatch!(self, s => s.next_1d())
    }

    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        dispatch!(self, s => s.next_2d())
    }

    #[inline]
    fn start_stream(&mut self, stream: u32) {
        self.skip_to_dimension(stream_dimension(stream));
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

#[cfg(feature = "sobol")]
impl From<Sobol4dSampler> for AnySampler {
    fn from(s: Sobol4dSampler) -> Self {
        Self::Sobol4d(s)
    }
}

impl From<HaltonSampler> for AnySampler {
    fn from(s: HaltonSampler) -> Self {
        Self::Halton(s)
    }
}

impl From<R2Sampler> for AnySampler {
    fn from(s: R2Sampler) -> Self {
        Self::R2(s)
    }
}

impl From<CmjSampler> for AnySampler {
    fn from(s: CmjSampler) -> Self {
        Self::Cmj(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn values<S: Sampler>(mut s: S) -> Vec<f32> {
        s.start_pixel_sample([3, 4], 2);
        let u = s.next_2d();
        let v = s.next_1d();
        s.skip_to_dimension(1024);
        let w = s.next_2d();
        vec![u.x, u.y, v, w.x, w.y, s.samples_per_pixel() as f32]
    }

    #[test]
    fn names_select_samplers() {
        let s = AnySampler::by_name("Stratified", 5, 0).unwrap().unwrap();
        assert!(matches!(s, AnySampler::Stratified(_)));
        assert_eq!(s.samples_per_pixel(), 9);
        let s = AnySampler::by_name("independent", 5, 0).unwrap().unwrap();
        assert!(matches!(s, AnySampler::Independent(_)));
        #[cfg(feature = "sobol")]
        for (name, spp, expected) in [
            ("ldsampler", 5, 16),
            ("ldsampler", 16, 16),
            ("ldsampler", 17, 64),
            ("ldsampler", 1, 4),
            ("ldsampler", 3, 4),
            ("sobol", 5, 5),
        ] {
            let s = AnySampler::by_name(name, spp, 0).unwrap().unwrap();
            if name == "sobol" {
                assert!(matches!(s, AnySampler::Sobol(_)));
            } else {
                assert!(matches!(s, AnySampler::Sobol4d(_)));
            }
            assert_eq!(s.samples_per_pixel(), expected, "{name} {spp}");
        }
        #[cfg(feature = "sobol")]
        assert!(AnySampler::by_name("ldsampler", u32::MAX, 0)
            .unwrap()
            .is_err());
        let s = AnySampler::by_name("Halton", 5, 0).unwrap().unwrap();
        assert!(matches!(s, AnySampler::Halton(_)));
        assert_eq!(s.samples_per_pixel(), 5);
        let s = AnySampler::by_name("r2", 5, 0).unwrap().unwrap();
        assert!(matches!(s, AnySampler::R2(_)));
        assert_eq!(s.samples_per_pixel(), 5);
        for name in ["multijitter", "CMJ"] {
            let s = AnySampler::by_name(name, 5, 0).unwrap().unwrap();
            assert!(matches!(s, AnySampler::Cmj(_)));
            assert_eq!(s.samples_per_pixel(), 6, "{name}");
        }
        // Mitsuba 3.9.1's `orthogonal` counts (read back from `sample_count()`).
        for (spp, expected) in [
            (1, 4),
            (2, 4),
            (5, 9),
            (10, 25),
            (16, 25),
            (17, 25),
            (64, 121),
            (100, 121),
            (256, 289),
            (1000, 1369),
        ] {
            let s = AnySampler::by_name("orthogonal", spp, 0).unwrap().unwrap();
            assert!(matches!(s, AnySampler::Cmj(_)));
            assert_eq!(s.samples_per_pixel(), expected, "orthogonal {spp}");
        }
        assert_eq!(next_prime_square(65521 * 65521), Some(65521 * 65521));
        assert_eq!(next_prime_square(65521 * 65521 + 1), None);
        assert!(AnySampler::by_name("orthogonal", u32::MAX, 0)
            .unwrap()
            .is_err());
        assert!(AnySampler::by_name("pmj02", 5, 0).is_none());
        assert!(AnySampler::by_name("independent", 0, 0).unwrap().is_err());
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
            let c = Sobol4dSampler::new(8, 1).unwrap();
            assert_eq!(values(c.clone()), values(AnySampler::from(c)));
            let s = AnySampler::by_name("sobol4d", 5, 0).unwrap().unwrap();
            assert!(matches!(s, AnySampler::Sobol4d(_)));
            assert_eq!(s.samples_per_pixel(), 5);
        }
        let d = HaltonSampler::new(8, 1).unwrap();
        assert_eq!(values(d.clone()), values(AnySampler::from(d)));
        let e = R2Sampler::new(8, 1).unwrap();
        assert_eq!(values(e.clone()), values(AnySampler::from(e)));
        let f = CmjSampler::new(8, 1, true).unwrap();
        assert_eq!(values(f.clone()), values(AnySampler::from(f)));
    }
}
