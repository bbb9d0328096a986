//! The error of a value the renderer cannot use, shared by the checked types of the
//! description (`description::Roughness`, `SampleCount`) and the checks of `validate`.

use std::fmt;

/// A value the renderer cannot use: the parameter and what is wrong with it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Invalid {
    /// The parameter's name as in the scene format (`reflectance`, `int_ior`, …).
    pub param: &'static str,
    /// What is wrong, e.g. `must be finite and non-negative`.
    pub message: String,
}

impl fmt::Display for Invalid {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "\"{}\" {}", self.param, self.message)
    }
}

impl std::error::Error for Invalid {}

impl Invalid {
    /// Parameter `param` is wrong: `message`.
    pub fn new(param: &'static str, message: impl Into<String>) -> Self {
        Self {
            param,
            message: message.into(),
        }
    }
}
