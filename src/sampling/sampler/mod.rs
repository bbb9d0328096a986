//! Samplers: the sample values `u ∈ [0,1)^d` a renderer feeds its warps, one pixel sample at
//! a time.
//!
//! A [`Sampler`] is positioned on a pixel sample with [`Sampler::start_pixel_sample`] and then
//! hands out 1D and 2D values in order ([`SampleSource::next_1d`], [`SampleSource::next_2d`]:
//! [`SampleSource`] is `Sampler`'s supertrait, so import both); each call
//! consumes one *dimension* (a 2D call consumes one 2D dimension). The values depend only on
//! (seed, pixel, sample index, dimension), never on the order in which pixels or samples are
//! visited, so a parallel renderer gets the same image whatever its thread count.
//!
//! | type | what it does | values per dimension over the pixel's samples |
//! |---|---|---|
//! | [`IndependentSampler`] | PCG32 seeded by a hash of (seed, pixel, sample index) | independent uniform |
//! | [`StratifiedSampler`] | jittered strata, shuffled independently per dimension | one per stratum: `n × n` strata in 2D, `spp` in 1D |
//! | `SobolSampler` (feature `sobol`) | Owen-scrambled Sobol, one scrambled (0,2)-sequence per dimension | every elementary interval of area `2^-k` holds one of the first `2^k` samples |
//! | `Sobol4dSampler` (feature `sobol`) | Owen-scrambled Sobol padded in 4D sets: dimensions `2k` and `2k + 1` are one 4D point | as `SobolSampler` in each even dimension, a (2,k,2)-net in each odd one (four points per elementary interval of area `2^(2-k)`), and a (3,k,4)-net in each pair jointly |
//! | [`HaltonSampler`] | Halton bases 2 and 3 with random digit permutations per dimension | each cell of a `2^a × 3^b` grid holds one of the first `2^a 3^b` samples |
//! | [`R2Sampler`] | the R2 Kronecker lattice with a random Cranley–Patterson rotation per dimension | no exact strata; any prefix evenly spread (low discrepancy) |
//! | [`CmjSampler`] | Kensler's correlated multi-jittered patterns, shuffled per dimension | one per cell of an `m × n` grid and one per `1/N` column and row in 2D, `N = m n`; one per `1/N` interval in 1D |
//!
//! Stratifying each dimension on its own and shuffling the strata independently per dimension
//! is the "padding" of Kollig & Keller (2002, "Efficient multidimensional sampling", Computer
//! Graphics Forum 21(3)): each 2D projection used by one warp is well stratified, while
//! different dimensions are decorrelated from each other.
//!
//! # Mitsuba 3 scene files
//!
//! The `<sampler type="...">` tag of a Mitsuba 3 scene maps to ours as follows (the scene
//! description's `SamplerKind` carries the choice; [`AnySampler`] holds whichever sampler a
//! renderer builds from it):
//!
//! | Mitsuba 3 tag | `SamplerKind` | ours | sample count |
//! |---|---|---|---|
//! | `independent` | `Independent` | [`IndependentSampler`] | as given |
//! | `stratified` | `Stratified` | [`StratifiedSampler`] (jittered unless `jitter` is false) | rounded up to a perfect square, as Mitsuba does |
//! | `ldsampler` | `LowDiscrepancy` | `Sobol4dSampler` | rounded up to a power of 4 by [`AnySampler::by_name`], as Mitsuba does; `Sobol4dSampler::new` takes any count |
//! | `multijitter` | `MultiJitter` | [`CmjSampler`] (jittered) | rounded up to `⌊√N⌋ · ⌈N / ⌊√N⌋⌉`, as Mitsuba does |
//! | `orthogonal` | `Orthogonal` | [`CmjSampler`] (jittered; `strength` 2 only) | rounded up to the square of a prime, as Mitsuba does (64 → 121) |
//!
//! `SobolSampler` (`SamplerKind::Sobol`, `--sampler sobol`) has no scene-file name. Why
//! `ldsampler` maps to the 4D-padded Sobol sampler and `multijitter`/`orthogonal` to the
//! correlated multi-jittered one: the relMSE per scene and sample count in
//! `docs/sampler-error.md` (the 4D padding lowers the error on glossy scenes at the same cost;
//! the multi-jittered patterns are of Mitsuba's kind).
//!
//! Mitsuba 3 (checked with 3.9.1) rounds the `sample_count` of `stratified` up to the next
//! perfect square (5 → 9, 10 → 16, 17 → 25) and that of `ldsampler` up to the next power of 4,
//! a count that is both a square and a power of two, at least 4 (1 → 4, 5 → 16, 17 → 64), and
//! that of `multijitter` up to `⌊√N⌋ · ⌈N / ⌊√N⌋⌉` (5 → 6, 10 → 12, 17 → 20), each with a
//! warning.
//! [`StratifiedSampler::new`] and [`CmjSampler::new`] round as Mitsuba's `stratified` and
//! `multijitter` do, and
//! [`Sampler::samples_per_pixel`] reports the rounded count, which is the one a renderer must
//! loop over. Mitsuba's `ldsampler` is Kollig & Keller's padded (0,2)-sequence; ours is a padded
//! Owen-scrambled Sobol sequence of the same family, which works for any count (the first `2^k`
//! samples of a pixel are a (0,k,2)-net in every even 2D dimension; other counts are a prefix
//! of the next net), padded in 4D sets rather than 2D ones. [`AnySampler::by_name`] applies Mitsuba's rounding for the name `ldsampler` so a
//! scene file renders with the count Mitsuba would use, and none for the name `sobol`. The
//! sample values themselves differ from Mitsuba's: the samplers are of the same kind, not
//! bit-identical.
//!
//! ```
//! use mcrt::sampling::sampler::{IndependentSampler, SampleSource, Sampler};
//!
//! let mut sampler = IndependentSampler::new(16, 7).unwrap();
//! sampler.start_pixel_sample([10, 20], 3);
//! let a = (sampler.next_2d(), sampler.next_1d());
//! sampler.start_pixel_sample([10, 20], 3);
//! let b = (sampler.next_2d(), sampler.next_1d());
//! assert_eq!(a, b); // deterministic for (seed, pixel, sample index)
//! assert!((0.0..1.0).contains(&a.1));
//! ```

use super::SamplingError;

mod any;
mod cmj;
mod halton;
pub mod hash;
mod independent;
mod padded;
mod r2;
#[cfg(feature = "sobol")]
mod sobol;
mod source;
mod stratified;

pub use any::AnySampler;
pub use cmj::CmjSampler;
pub use halton::HaltonSampler;
pub use independent::IndependentSampler;
pub use r2::R2Sampler;
#[cfg(feature = "sobol")]
pub use sobol::{Sobol4dSampler, SobolSampler};
pub use source::{stream_dimension, SampleSource, STREAM_DIMENSIONS};
pub use stratified::StratifiedSampler;

/// A source of sample values in `[0,1)^d` for the pixel samples of an image.
///
/// Call [`Sampler::start_pixel_sample`] before drawing the values of a pixel sample; it resets
/// the dimension counter, so the `d`-th call after it returns the same value every time for the
/// same (seed, pixel, sample index). The values come from the supertrait [`SampleSource`]:
/// [`SampleSource::next_1d`] (in `[0, 1)`, never 1.0) and [`SampleSource::next_2d`] (in
/// `[0, 1)²`) each consume one dimension. Import both traits to call them on a concrete
/// sampler. Samplers are cheap to clone: a renderer gives each thread its own copy.
pub trait Sampler: SampleSource + Clone + Send + Sync {
    /// Positions the sampler on sample `sample_index` of pixel `pixel` (x, y) and resets the
    /// dimension counter.
    fn start_pixel_sample(&mut self, pixel: [u32; 2], sample_index: u32);

    /// Jumps to dimension `dim` of the current pixel sample (the next call returns the
    /// value of that dimension). Estimators with several sample streams (the bidirectional
    /// ones: camera subpath, light subpath, connections) place each stream at a fixed
    /// dimension, so that a value keeps its dimension whatever the other streams drew. The
    /// default does nothing: right for samplers whose dimensions are alike (independent).
    #[inline]
    fn skip_to_dimension(&mut self, _dim: u32) {}

    /// The number of samples per pixel the sampler was built for (after any rounding, e.g. to a
    /// perfect square for [`StratifiedSampler`]). Sample indices at or beyond it are still
    /// valid, with weaker stratification (each type documents what it does).
    fn samples_per_pixel(&self) -> u32;
}

/// Checks a sample count: at least 1.
fn check_spp(spp: u32) -> Result<u32, SamplingError> {
    if spp >= 1 {
        Ok(spp)
    } else {
        Err(SamplingError::InvalidParameter {
            name: "spp",
            value: f64::from(spp),
            expected: "at least 1",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_spp_is_rejected() {
        assert!(check_spp(0).is_err());
        assert_eq!(check_spp(1), Ok(1));
    }
}
