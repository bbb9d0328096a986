//! The error type of every fallible constructor in [`crate::sampling`].

use std::fmt;

/// Why a warp, distribution or sampler could not be built from the given input.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum SamplingError {
    /// A scalar parameter lies outside its valid range (or is NaN or infinite).
    InvalidParameter {
        /// The parameter's name, as in the constructor's signature.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The valid range, in words (e.g. `"finite and > 0"`).
        expected: &'static str,
    },
    /// A direction parameter is not usable (not unit length, below the horizon, NaN).
    InvalidDirection {
        /// The parameter's name.
        name: &'static str,
        /// What was expected of it, in words.
        expected: &'static str,
    },
    /// A table has no entries.
    EmptyTable,
    /// A table entry is negative, NaN or infinite.
    InvalidEntry {
        /// Index of the first offending entry (row-major for 2D tables).
        index: usize,
        /// Its value.
        value: f64,
    },
    /// Every entry of a table is zero, so there is nothing to sample.
    ZeroTable,
    /// A table's length does not match the dimensions given.
    ShapeMismatch {
        /// The number of entries the dimensions call for.
        expected: usize,
        /// The number of entries given.
        got: usize,
    },
    /// A geometric configuration is degenerate (zero area, zero solid angle, ...).
    Degenerate {
        /// What is degenerate, in words.
        what: &'static str,
    },
}

impl fmt::Display for SamplingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidParameter {
                name,
                value,
                expected,
            } => write!(
                f,
                "invalid parameter `{name}` = {value}: expected {expected}"
            ),
            Self::InvalidDirection { name, expected } => {
                write!(f, "invalid direction `{name}`: expected {expected}")
            }
            Self::EmptyTable => write!(f, "the table is empty"),
            Self::InvalidEntry { index, value } => write!(
                f,
                "table entry {index} is {value}: entries must be finite and >= 0"
            ),
            Self::ZeroTable => write!(f, "every table entry is zero: nothing to sample"),
            Self::ShapeMismatch { expected, got } => write!(
                f,
                "the table has {got} entries but its dimensions call for {expected}"
            ),
            Self::Degenerate { what } => write!(f, "degenerate input: {what}"),
        }
    }
}

impl std::error::Error for SamplingError {}

/// Checks that `value` is finite and satisfies `ok`, else returns
/// [`SamplingError::InvalidParameter`].
pub(crate) fn check_param(
    name: &'static str,
    value: f32,
    expected: &'static str,
    ok: impl FnOnce(f32) -> bool,
) -> Result<f32, SamplingError> {
    if value.is_finite() && ok(value) {
        Ok(value)
    } else {
        Err(SamplingError::InvalidParameter {
            name,
            value: f64::from(value),
            expected,
        })
    }
}
