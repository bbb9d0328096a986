//! Why the lights of a scene could not be set up.

use std::fmt;
use std::path::PathBuf;

/// Why [`Lights::new`](super::Lights::new) refused a scene's emitters.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum LightError {
    /// More than one `constant` or `envmap` emitter: the environment is one light.
    SeveralEnvironments,
    /// An environment map could not be read or used.
    EnvMap {
        /// The image file.
        path: PathBuf,
        /// What is wrong with it.
        reason: String,
    },
    /// A spot light's parameters are out of range (the message says which).
    Spot(String),
}

impl fmt::Display for LightError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LightError::SeveralEnvironments => {
                f.write_str("light setup: more than one environment emitter")
            }
            LightError::EnvMap { path, reason } => {
                write!(f, "light setup: {}: {reason}", path.display())
            }
            LightError::Spot(what) => write!(f, "light setup: spot light: {what}"),
        }
    }
}

impl std::error::Error for LightError {}
