//! Values that are checked once, when they are made, and trusted after: a [`Roughness`]
//! and a [`SampleCount`] cannot hold a value the renderer refuses, so nothing downstream
//! (the checks of the parts that hold them, the materials, the per-sample code) checks them
//! again.
//! The loader makes them from its parameter definitions (`params`); a scene built in code
//! goes through the same constructors.

use crate::invalid::Invalid;
use std::fmt;
use std::ops::Deref;

/// A microfacet roughness α in [[`Roughness::MIN`], [`Roughness::MAX`]].
///
/// ```
/// use mcrt_render::description::Roughness;
///
/// assert_eq!(Roughness::new(0.3).unwrap(), 0.3);
/// assert!(Roughness::new(0.0).is_err());
/// assert_eq!(Roughness::raised(0.0).unwrap(), Roughness::MIN); // Mitsuba 3's clamp
/// assert!(Roughness::raised(-1.0).is_err() && Roughness::new(f32::NAN).is_err());
/// ```
#[derive(Clone, Copy, PartialEq, PartialOrd)]
pub struct Roughness(f32);

impl Roughness {
    /// Smallest roughness the renderer takes (Mitsuba 3 raises smaller values to it).
    pub const MIN: f32 = 1e-4;
    /// Largest roughness the renderer takes.
    pub const MAX: f32 = 10.0;
    /// Mitsuba 3's default `alpha`, 0.1.
    pub const DEFAULT: Roughness = Roughness(0.1);

    /// `alpha` if it lies in [[`Roughness::MIN`], [`Roughness::MAX`]].
    ///
    /// # Errors
    /// An [`Invalid`] naming `alpha` otherwise (NaN included).
    pub fn new(alpha: f32) -> Result<Self, Invalid> {
        if (Self::MIN..=Self::MAX).contains(&alpha) {
            Ok(Self(alpha))
        } else {
            Err(Invalid::new(
                "alpha",
                format!("must lie in [{}, {}]", Self::MIN, Self::MAX),
            ))
        }
    }

    /// A scene file's `alpha` as Mitsuba 3 reads it: values in [0, [`Roughness::MIN`]) are
    /// raised to [`Roughness::MIN`].
    ///
    /// # Errors
    /// An [`Invalid`] naming `alpha` when it lies outside [0, [`Roughness::MAX`]].
    pub fn raised(alpha: f32) -> Result<Self, Invalid> {
        if (0.0..=Self::MAX).contains(&alpha) {
            Ok(Self(alpha.max(Self::MIN)))
        } else {
            Err(Invalid::new(
                "alpha",
                format!("must lie in [0, {}]", Self::MAX),
            ))
        }
    }

    /// The value.
    pub fn get(self) -> f32 {
        self.0
    }
}

impl Default for Roughness {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl Deref for Roughness {
    type Target = f32;
    fn deref(&self) -> &f32 {
        &self.0
    }
}

impl PartialEq<f32> for Roughness {
    fn eq(&self, other: &f32) -> bool {
        self.0 == *other
    }
}

/// As the bare number (a render's identity hashes a description's `Debug` text).
impl fmt::Debug for Roughness {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(&self.0, f)
    }
}

impl fmt::Display for Roughness {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

/// Samples per pixel (or MLT mutations per pixel) in 1..=[`SampleCount::MAX`].
///
/// ```
/// use mcrt_render::description::SampleCount;
///
/// assert_eq!(SampleCount::new(16).unwrap(), 16);
/// assert!(SampleCount::new(0).is_err());
/// assert!(SampleCount::new(SampleCount::MAX + 1).is_err());
/// ```
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct SampleCount(u32);

impl SampleCount {
    /// Largest count: 2²⁴.
    pub const MAX: u32 = 1 << 24;
    /// Mitsuba 3's default `sample_count`, 4.
    pub const DEFAULT: SampleCount = SampleCount(4);

    /// `n` if it lies in 1..=[`SampleCount::MAX`].
    ///
    /// # Errors
    /// An [`Invalid`] naming `sample_count` otherwise ([`SampleCount::named`] names
    /// another parameter).
    pub fn new(n: u32) -> Result<Self, Invalid> {
        Self::named("sample_count", n)
    }

    /// As [`SampleCount::new`], the error naming `param` (`--spp`, `mutations_per_pixel`).
    ///
    /// # Errors
    /// An [`Invalid`] naming `param` when `n` lies outside 1..=[`SampleCount::MAX`].
    pub fn named(param: &'static str, n: u32) -> Result<Self, Invalid> {
        if (1..=Self::MAX).contains(&n) {
            Ok(Self(n))
        } else {
            Err(Invalid::new(
                param,
                format!("= {n} is outside [1, {}]", Self::MAX),
            ))
        }
    }

    /// The count.
    pub fn get(self) -> u32 {
        self.0
    }

    /// The count, in a `const` context.
    pub const fn get_const(self) -> u32 {
        self.0
    }
}

impl Default for SampleCount {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl Deref for SampleCount {
    type Target = u32;
    fn deref(&self) -> &u32 {
        &self.0
    }
}

impl PartialEq<u32> for SampleCount {
    fn eq(&self, other: &u32) -> bool {
        self.0 == *other
    }
}

/// As the bare number (a render's identity hashes a description's `Debug` text).
impl fmt::Debug for SampleCount {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(&self.0, f)
    }
}

impl fmt::Display for SampleCount {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}
