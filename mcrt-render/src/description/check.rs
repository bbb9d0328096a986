//! A part of a description that has passed its checks once, when it was made, and is
//! trusted after: [`Checked<T>`] is made only by [`Checked::new`], which runs `T`'s
//! [`Check`]. The XML loader makes each one where it reads the element (so its errors name
//! file and line); a description built in code goes through the same constructor. Nothing
//! downstream, [`Renderer::new`](crate::render::Renderer::new) included, checks the part
//! again.
//!
//! The parts so held, and their checks (in [`validate`](crate::validate)): the sensor's
//! film ([`FilmDesc`](super::FilmDesc)) and the sensor ([`SensorDesc`](super::SensorDesc)),
//! the integrator ([`IntegratorDesc`](super::IntegratorDesc)), each shape with its material
//! and area emitter ([`ShapeDesc`](super::ShapeDesc)), each shape group
//! ([`ShapeGroupDesc`](super::ShapeGroupDesc)) and each emitter
//! ([`EmitterDesc`](super::EmitterDesc)).

use crate::invalid::Invalid;
use std::borrow::Borrow;
use std::fmt;
use std::ops::Deref;

/// The checks a value must pass before a description may hold it.
pub trait Check {
    /// `Ok` if the renderer can use `self`.
    ///
    /// # Errors
    /// An [`Invalid`] naming the first parameter that is wrong.
    fn check(&self) -> Result<(), Invalid>;
}

/// A `T` that has passed [`Check::check`]: it cannot hold a value the renderer refuses.
/// Read it through `Deref`; to change it, take it out ([`Checked::into_inner`]) and make a
/// new one.
///
/// ```
/// use mcrt_render::description::{Checked, IntegratorDesc, PathParams};
///
/// let p = |max_depth, rr_depth| {
///     IntegratorDesc::Path(PathParams { max_depth, rr_depth, ..PathParams::DEFAULT })
/// };
/// let path = Checked::new(p(4, 5)).unwrap();
/// assert_eq!(path.max_depth(), Some(4));
/// let e = Checked::new(p(4, 0)).unwrap_err();
/// assert_eq!(e.param, "rr_depth");
/// let deeper = path.changed(|i| *i = p(8, 5));
/// assert_eq!(deeper.unwrap().max_depth(), Some(8));
/// ```
#[derive(Clone, Copy, PartialEq)]
pub struct Checked<T>(T);

impl<T: Check> Checked<T> {
    /// `value` if it passes its [`Check`].
    ///
    /// # Errors
    /// The [`Invalid`] of the check, naming the parameter.
    pub fn new(value: T) -> Result<Self, Invalid> {
        value.check()?;
        Ok(Self(value))
    }

    /// The value changed by `change`, checked again.
    ///
    /// # Errors
    /// The [`Invalid`] of the check of the changed value.
    pub fn changed(self, change: impl FnOnce(&mut T)) -> Result<Self, Invalid> {
        let mut v = self.0;
        change(&mut v);
        Self::new(v)
    }
}

impl<T> Checked<T> {
    /// `value` if it passes `check`, which stands for `T`'s [`Check`]: the caller's
    /// promise, kept inside this crate, that `check` and the checks the parts of `value`
    /// passed when they were made cover it (a shape and the material the loader checked
    /// at its element, `validate::shape_with`).
    pub(crate) fn assembled(
        value: T,
        check: impl FnOnce(&T) -> Result<(), Invalid>,
    ) -> Result<Self, Invalid> {
        check(&value)?;
        Ok(Self(value))
    }

    /// The value, to change it (it must be checked again to go back into a description).
    pub fn into_inner(self) -> T {
        self.0
    }

    /// Makes `change` to the value, one that its check does not look at (the caller's
    /// promise, kept inside this crate: a sensor's sampler, a shape's file name).
    pub(crate) fn change_unchecked<R>(&mut self, change: impl FnOnce(&mut T) -> R) -> R {
        change(&mut self.0)
    }
}

impl<T> Deref for Checked<T> {
    type Target = T;
    fn deref(&self) -> &T {
        &self.0
    }
}

impl<T> Borrow<T> for Checked<T> {
    fn borrow(&self) -> &T {
        &self.0
    }
}

impl<T> AsRef<T> for Checked<T> {
    fn as_ref(&self) -> &T {
        &self.0
    }
}

/// A checked value equals the plain value it holds.
impl<T: PartialEq> PartialEq<T> for Checked<T> {
    fn eq(&self, other: &T) -> bool {
        self.0 == *other
    }
}

/// As the bare value (a render's identity hashes a description's `Debug` text).
impl<T: fmt::Debug> fmt::Debug for Checked<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

/// The defaults, Mitsuba 3's, pass their checks (the tests below show it).
macro_rules! checked_default {
    ($($t:ty),*) => {$(
        impl Default for Checked<$t> {
            fn default() -> Self {
                Self(<$t>::default())
            }
        }
    )*};
}
checked_default!(
    super::IntegratorDesc,
    super::SensorDesc,
    super::FilmDesc,
    super::ShapeGroupDesc
);

#[cfg(test)]
mod tests {
    use super::super::{FilmDesc, IntegratorDesc, SensorDesc, ShapeGroupDesc};
    use super::*;

    #[test]
    fn the_defaults_pass_their_checks() {
        assert_eq!(IntegratorDesc::default().check(), Ok(()));
        assert_eq!(SensorDesc::default().check(), Ok(()));
        assert_eq!(FilmDesc::default().check(), Ok(()));
        assert_eq!(ShapeGroupDesc::default().check(), Ok(()));
    }

    #[test]
    fn a_bad_value_cannot_be_made_and_the_error_names_it() {
        let film = FilmDesc {
            filter: super::super::FilterDesc::Gaussian { stddev: f32::NAN },
            ..FilmDesc::default()
        };
        assert_eq!(Checked::new(film).unwrap_err().param, "stddev");
        let mut sensor = SensorDesc::default();
        sensor.to_world.w_axis.w = 2.0;
        assert_eq!(Checked::new(sensor).unwrap_err().param, "to_world");
    }
}
