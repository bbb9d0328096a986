//! Checked optical values: a [`Colour`] (finite, non-negative linear RGB) and an index of
//! refraction ([`Ior`], finite and positive). The loader makes them from its parameter
//! definitions, and a scene built in code goes through the same constructors, so nothing
//! downstream (the validation of a description, the materials, the lights) checks them again.

use crate::invalid::Invalid;
use glam::Vec3;
use std::fmt;
use std::ops::Deref;

/// A linear RGB colour whose channels are finite and non-negative: a reflectance, a
/// transmittance, a conductor's η or k, or an emitted quantity.
///
/// ```
/// use glam::Vec3;
/// use mcrt_render::description::Colour;
///
/// assert_eq!(Colour::new(Vec3::new(0.2, 0.5, 4.0)).unwrap(), Vec3::new(0.2, 0.5, 4.0));
/// assert_eq!(Colour::grey(0.5).unwrap().get(), Vec3::splat(0.5));
/// assert!(Colour::new(Vec3::new(0.5, -0.1, 0.5)).is_err());
/// assert!(Colour::grey(f32::NAN).is_err() && Colour::grey(f32::INFINITY).is_err());
/// ```
#[derive(Clone, Copy, PartialEq)]
pub struct Colour(Vec3);

impl Colour {
    /// Black (0, 0, 0).
    pub const BLACK: Colour = Colour(Vec3::ZERO);
    /// White (1, 1, 1).
    pub const WHITE: Colour = Colour(Vec3::ONE);
    /// The message of a refused colour.
    pub const MESSAGE: &'static str = "must be finite and non-negative";

    /// `v` if its channels are finite and non-negative.
    ///
    /// # Errors
    /// An [`Invalid`] naming `colour` otherwise ([`Colour::named`] names the parameter).
    pub fn new(v: Vec3) -> Result<Self, Invalid> {
        Self::named("colour", v)
    }

    /// As [`Colour::new`], the error naming parameter `param`.
    ///
    /// # Errors
    /// An [`Invalid`] naming `param` when a channel is negative, infinite or NaN.
    pub fn named(param: &'static str, v: Vec3) -> Result<Self, Invalid> {
        if v.is_finite() && v.min_element() >= 0.0 {
            Ok(Self(v))
        } else {
            Err(Invalid::new(param, Self::MESSAGE))
        }
    }

    /// `v`, known valid (for constants: a const evaluation of an invalid one fails to
    /// compile).
    pub(crate) const fn known(v: Vec3) -> Self {
        assert!(v.x >= 0.0 && v.y >= 0.0 && v.z >= 0.0 && v.x.is_finite());
        assert!(v.y.is_finite() && v.z.is_finite());
        Self(v)
    }

    /// Grey `g` in every channel.
    ///
    /// # Errors
    /// As [`Colour::new`].
    pub fn grey(g: f32) -> Result<Self, Invalid> {
        Self::new(Vec3::splat(g))
    }

    /// The channels.
    pub fn get(self) -> Vec3 {
        self.0
    }
}

impl Deref for Colour {
    type Target = Vec3;
    fn deref(&self) -> &Vec3 {
        &self.0
    }
}

impl From<Colour> for Vec3 {
    fn from(c: Colour) -> Vec3 {
        c.0
    }
}

impl TryFrom<Vec3> for Colour {
    type Error = Invalid;
    fn try_from(v: Vec3) -> Result<Self, Invalid> {
        Self::new(v)
    }
}

impl PartialEq<Vec3> for Colour {
    fn eq(&self, other: &Vec3) -> bool {
        self.0 == *other
    }
}

/// As the bare `Vec3` (a render's identity hashes a description's `Debug` text).
impl fmt::Debug for Colour {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(&self.0, f)
    }
}

impl fmt::Display for Colour {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

/// An index of refraction: finite and positive.
///
/// ```
/// use mcrt_render::description::Ior;
///
/// assert_eq!(Ior::new(1.5).unwrap(), 1.5);
/// assert!(Ior::new(0.0).is_err() && Ior::new(-1.5).is_err() && Ior::new(f32::NAN).is_err());
/// ```
#[derive(Clone, Copy, PartialEq, PartialOrd)]
pub struct Ior(f32);

impl Ior {
    /// Vacuum, 1.
    pub const VACUUM: Ior = Ior(1.0);
    /// The message of a refused index.
    pub const MESSAGE: &'static str = "must be finite and positive";

    /// `eta` if it is finite and positive.
    ///
    /// # Errors
    /// An [`Invalid`] naming `ior` otherwise.
    pub fn new(eta: f32) -> Result<Self, Invalid> {
        if eta.is_finite() && eta > 0.0 {
            Ok(Self(eta))
        } else {
            Err(Invalid::new("ior", Self::MESSAGE))
        }
    }

    /// The index.
    pub fn get(self) -> f32 {
        self.0
    }
}

impl Deref for Ior {
    type Target = f32;
    fn deref(&self) -> &f32 {
        &self.0
    }
}

impl PartialEq<f32> for Ior {
    fn eq(&self, other: &f32) -> bool {
        self.0 == *other
    }
}

/// As the bare number (a render's identity hashes a description's `Debug` text).
impl fmt::Debug for Ior {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(&self.0, f)
    }
}

impl fmt::Display for Ior {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}
