//! From one list of parameter definitions, a plugin's checked parameter struct (what the
//! description holds), its definitions table (what `docs/scene-format.md`'s tables are
//! tested against), its reading from the scene file and its check for a description built
//! in code ([`plugin_params!`]).
//!
//! Adding a parameter to such a plugin is one entry in its list (and, for a new
//! parameter, its definition constant beside it), plus the line that uses the value.

use super::{BoolParam, FloatParam, IntParam};
use crate::invalid::Invalid;

/// Where a plugin's parameters are read from: the loader's `Props` (which names file and
/// line on an error) implements it.
pub(crate) trait ParamSource {
    /// The error of a bad value.
    type Error;
    /// Integer parameter `d`, checked, or its default.
    fn int(&mut self, d: &IntParam) -> Result<i64, Self::Error>;
    /// Integer parameter `d`, checked, or `default` (the value of another parameter).
    fn int_or(&mut self, d: &IntParam, default: i64) -> Result<i64, Self::Error>;
    /// Float parameter `d`, checked, or its default.
    fn float(&mut self, d: &FloatParam<f32>) -> Result<f32, Self::Error>;
    /// Boolean parameter `d`, or its default.
    fn boolean(&mut self, d: &BoolParam) -> Result<bool, Self::Error>;
    /// The error of a check between parameters, located at the parameter it names.
    fn invalid(&self, i: Invalid) -> Self::Error;
}

/// A parameter's value by its definition's type, for what works on any plugin's
/// parameters by name (`--integrator` carrying the values both types have).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum ParamValue {
    /// An integer.
    Int(i64),
    /// A float.
    Float(f32),
    /// A boolean.
    Bool(bool),
}

/// Generates, from a list of `field: type = Kind(DEFINITION)` entries (`Kind` one of
/// `Int`, `Float`, `Bool`; `Int(DEF, or other_field)` defaults to an earlier field's
/// value):
/// - the `pub struct` with one documented field per entry, `DEFAULT` (every definition's
///   default) and `Default`;
/// - `read`, each value through its definition from a [`ParamSource`], then the check
///   between parameters (`check FN`, given `&Self`), located by the source;
/// - `check`, the same checks for values built in code;
/// - `values` and `set`, the values by Mitsuba name;
/// - the definitions table `TABLE` of the plugin `(category, plugin)`.
macro_rules! plugin_params {
    (
        $(#[$meta:meta])*
        pub struct $name:ident;
        table $table:ident = ($category:literal, $plugin:literal);
        $(check $cross:path;)?
        {
            $(
                $(#[$fmeta:meta])*
                $field:ident : $ty:ty = $kind:ident ( $def:path $(, or $alt:ident)? )
            ),* $(,)?
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub struct $name {
            $( $(#[$fmeta])* pub $field: $ty, )*
        }

        impl $name {
            /// Every parameter at its default (the value when the scene file omits it).
            pub const DEFAULT: Self = Self {
                $( $field: $crate::param_defs::generate::default_of!($kind, $def, $ty), )*
            };

            /// Reads every parameter through its definition, then the checks between them.
            #[allow(dead_code)] // not every plugin's table is read this way yet
            pub(crate) fn read<S: $crate::param_defs::generate::ParamSource>(
                s: &mut S,
            ) -> Result<Self, S::Error> {
                $(
                    let $field: $ty =
                        $crate::param_defs::generate::read_one!(s, $kind, $def, $ty $(, $alt)?);
                )*
                let out = Self { $( $field, )* };
                $( $cross(&out).map_err(|i| s.invalid(i))?; )?
                Ok(out)
            }

            /// Every value against its definition, and the checks between them.
            #[allow(dead_code)] // not every plugin's table is checked this way yet
            pub(crate) fn check(&self) -> Result<(), $crate::invalid::Invalid> {
                $( $crate::param_defs::generate::check_one!($kind, $def, self.$field); )*
                $( $cross(self)?; )?
                Ok(())
            }

            /// Every value, by its Mitsuba name.
            #[allow(dead_code)] // not every plugin's values are looked up by name
            pub(crate) fn values(
                &self,
            ) -> Vec<(&'static str, $crate::param_defs::generate::ParamValue)> {
                vec![$(
                    ($def.name, $crate::param_defs::generate::value_of!($kind, self.$field)),
                )*]
            }

            /// Sets the parameter of Mitsuba name `name` to `v`, if it has one of that
            /// type (the value unchecked: [`Self::check`] checks it).
            #[allow(dead_code)] // not every plugin's values are set by name
            pub(crate) fn set(&mut self, name: &str, v: $crate::param_defs::generate::ParamValue) {
                $(
                    if name == $def.name {
                        $crate::param_defs::generate::set_one!($kind, self.$field, $ty, v);
                    }
                )*
            }
        }

        impl Default for $name {
            fn default() -> Self {
                Self::DEFAULT
            }
        }

        #[doc = concat!("The definitions table of `", $category, " type=\"", $plugin, "\"`.")]
        pub(crate) const $table: $crate::param_defs::PluginParams =
            $crate::param_defs::PluginParams {
                category: $category,
                plugin: $plugin,
                params: &[ $( $crate::param_defs::ParamDef::$kind(&$def), )* ],
            };
    };
}
pub(crate) use plugin_params;

/// The default of definition `$def` as the field's type.
macro_rules! default_of {
    (Int, $def:path, $ty:ty) => {
        $def.default as $ty
    };
    (Float, $def:path, $ty:ty) => {
        $def.default
    };
    (Bool, $def:path, $ty:ty) => {
        $def.default
    };
}
pub(crate) use default_of;

/// Reads the value of definition `$def` from source `$s` as the field's type (the
/// definition's range makes the integer cast exact).
macro_rules! read_one {
    ($s:ident, Int, $def:path, $ty:ty) => {
        $s.int(&$def)? as $ty
    };
    ($s:ident, Int, $def:path, $ty:ty, $alt:ident) => {
        $s.int_or(&$def, $alt as i64)? as $ty
    };
    ($s:ident, Float, $def:path, $ty:ty) => {
        $s.float(&$def)?
    };
    ($s:ident, Bool, $def:path, $ty:ty) => {
        $s.boolean(&$def)?
    };
}
pub(crate) use read_one;

/// Checks value `$v` against definition `$def`.
macro_rules! check_one {
    (Int, $def:path, $v:expr) => {
        $def.check($v as i64)?
    };
    (Float, $def:path, $v:expr) => {
        $def.check($v)?
    };
    (Bool, $def:path, $v:expr) => {{
        let _: bool = $v;
    }};
}
pub(crate) use check_one;

/// Value `$v` as a [`ParamValue`].
macro_rules! value_of {
    (Int, $v:expr) => {
        $crate::param_defs::generate::ParamValue::Int($v as i64)
    };
    (Float, $v:expr) => {
        $crate::param_defs::generate::ParamValue::Float($v)
    };
    (Bool, $v:expr) => {
        $crate::param_defs::generate::ParamValue::Bool($v)
    };
}
pub(crate) use value_of;

/// Sets field `$f` to `$v` if it is a value of the field's kind.
macro_rules! set_one {
    (Int, $f:expr, $ty:ty, $v:expr) => {
        if let $crate::param_defs::generate::ParamValue::Int(x) = $v {
            $f = x as $ty;
        }
    };
    (Float, $f:expr, $ty:ty, $v:expr) => {
        if let $crate::param_defs::generate::ParamValue::Float(x) = $v {
            $f = x;
        }
    };
    (Bool, $f:expr, $ty:ty, $v:expr) => {
        if let $crate::param_defs::generate::ParamValue::Bool(x) = $v {
            $f = x;
        }
    };
}
pub(crate) use set_one;
