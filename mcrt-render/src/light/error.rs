//! Why the lights of a scene could not be set up.

use crate::description::Origin;
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
    /// A projector's parameters are out of range (the message says which).
    Projector(String),
    /// A light's power (its emission times its area or solid angle, or the scene's disk for
    /// lights at infinity), or the lights' total power, is not a finite `f32`: the light
    /// could not be chosen, and would have been dropped.
    PowerOverflow {
        /// The light, e.g. `the point light (emitter 1)`.
        light: String,
        /// Its power, in f64.
        power: String,
    },
    /// One of the other errors, at the element of the scene file the light came from.
    Located {
        /// Where the light was written.
        at: Origin,
        /// What is wrong with it.
        error: Box<LightError>,
    },
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
            LightError::Projector(what) => write!(f, "light setup: projector: {what}"),
            LightError::PowerOverflow { light, power } => write!(
                f,
                "light setup: {light}: its power, {power}, or the lights' total power, exceeds \
                 the largest f32, {:e}: lower its emission (or the scene's size)",
                f32::MAX
            ),
            LightError::Located { at, error } => write!(f, "{at}: {error}"),
        }
    }
}

impl std::error::Error for LightError {}
