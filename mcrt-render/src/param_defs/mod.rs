//! One definition per scene parameter: its Mitsuba name, type, default and valid range,
//! and a line of documentation. The loader reads every parameter of the plugins below
//! through its definition (`Props::get`, which names file and line on an error), the
//! description holds the checked value, and a test holds `docs/scene-format.md`'s
//! parameter tables to these definitions ([`PLUGINS`]).
//!
//! Mitsuba 3 reads a parameter in the plugin's constructor from `Properties` (the error
//! names file and line; unread parameters are reported); pbrt-v4 does the same with
//! `ParameterDictionary` in each `Create()`. Here the definition is a `const`, so the name,
//! the default and the range are written once.
//!
//! Adding a parameter: one definition constant, listed in its plugin's table, and the
//! line that uses it. For the integrators, one list per plugin generates the parameter
//! struct the description holds, the table and the reading ([`generate`]), so a parameter
//! is an entry in that list and its use: two files.

pub(crate) mod bsdf;
pub(crate) mod bsdf_composite;
pub(crate) mod bsdf_maps;
#[cfg(test)]
mod doc_tests;
pub(crate) mod emitter;
pub(crate) mod film;
pub(crate) mod generate;
pub(crate) mod integrator;
pub(crate) mod sampler;
pub(crate) mod sensor;
pub(crate) mod shape;
pub(crate) mod shape_plugins;
pub(crate) mod texture;
pub(crate) mod volume;

/// An integer parameter in `min..=max`.
#[derive(Debug)]
pub(crate) struct IntParam {
    /// The Mitsuba name.
    pub name: &'static str,
    /// The value when the scene does not give one.
    pub default: i64,
    /// Smallest valid value.
    pub min: i64,
    /// Largest valid value.
    pub max: i64,
    /// What it means (the doc table's last column).
    #[cfg_attr(not(test), allow(dead_code))] // read by the docs' test
    pub doc: &'static str,
}

/// A float parameter (an `<integer>` is accepted too), checked by `accept`, which turns it
/// into its checked type `T` or says what is wrong.
#[derive(Debug)]
pub(crate) struct FloatParam<T: 'static> {
    /// The Mitsuba name.
    pub name: &'static str,
    /// The value when the scene does not give one.
    pub default: T,
    /// The valid values, as the docs write them (e.g. `(0, 1]`).
    #[cfg_attr(not(test), allow(dead_code))] // read by the docs' test
    pub range: &'static str,
    /// The check: the value, or the message (after the quoted name) of the error.
    pub accept: fn(f32) -> Result<T, String>,
    /// What it means.
    #[cfg_attr(not(test), allow(dead_code))] // read by the docs' test
    pub doc: &'static str,
}

/// A boolean parameter.
#[derive(Debug)]
pub(crate) struct BoolParam {
    /// The Mitsuba name.
    pub name: &'static str,
    /// The value when the scene does not give one.
    pub default: bool,
    /// What it means.
    #[cfg_attr(not(test), allow(dead_code))] // read by the docs' test
    pub doc: &'static str,
}

/// A string parameter that names one of `choices` (compared without case).
#[derive(Debug)]
pub(crate) struct ChoiceParam {
    /// The Mitsuba name.
    pub name: &'static str,
    /// The value when the scene does not give one (one of `choices`).
    pub default: &'static str,
    /// The accepted values, lower case.
    pub choices: &'static [&'static str],
    /// What it means.
    #[cfg_attr(not(test), allow(dead_code))] // read by the docs' test
    pub doc: &'static str,
}

/// A colour parameter (`<rgb>`, `<spectrum>` or a float; a texture where the material
/// allows one), as a reflectance: its range is checked with the material's other values.
#[derive(Debug)]
pub(crate) struct ColourParam {
    /// The Mitsuba name.
    pub name: &'static str,
    /// The value when the scene does not give one (grey).
    pub default: f32,
    /// What it means.
    #[cfg_attr(not(test), allow(dead_code))] // read by the docs' test
    pub doc: &'static str,
}

/// An index of refraction: a positive float or the name of one of Mitsuba's media.
#[derive(Debug)]
pub(crate) struct IorParam {
    /// The Mitsuba name.
    pub name: &'static str,
    /// The value when the scene does not give one.
    pub default: f32,
    /// What it means.
    #[cfg_attr(not(test), allow(dead_code))] // read by the docs' test
    pub doc: &'static str,
}

/// A parameter read by code of its own (a colour, a named index of refraction, …): its
/// name and type are listed here so that the table of its plugin is complete.
#[derive(Debug)]
pub(crate) struct OtherParam {
    /// The Mitsuba name.
    pub name: &'static str,
    /// Its type as the docs write it.
    #[cfg_attr(not(test), allow(dead_code))] // read by the docs' test
    pub kind: &'static str,
    /// What it means.
    #[cfg_attr(not(test), allow(dead_code))] // read by the docs' test
    pub doc: &'static str,
}

/// An [`OtherParam`] of `name`, of type `kind` (as the docs write it), meaning `doc`.
pub(crate) const fn other(name: &'static str, kind: &'static str, doc: &'static str) -> OtherParam {
    OtherParam { name, kind, doc }
}

/// Any parameter definition, for a plugin's table.
#[derive(Debug, Clone, Copy)]
pub(crate) enum ParamDef {
    /// An integer.
    Int(&'static IntParam),
    /// A float checked to a plain `f32`.
    Float(&'static FloatParam<f32>),
    /// The microfacet roughness.
    Roughness(&'static FloatParam<crate::description::Roughness>),
    /// A boolean.
    Bool(&'static BoolParam),
    /// One of a few strings.
    Choice(&'static ChoiceParam),
    /// A colour.
    Colour(&'static ColourParam),
    /// An index of refraction.
    Ior(&'static IorParam),
    /// Read by code of its own.
    Other(&'static OtherParam),
}

impl ParamDef {
    /// Its type, as the docs' tables write it.
    #[cfg_attr(not(test), allow(dead_code))] // read by the docs' test
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Int(_) => "integer",
            Self::Float(_) | Self::Roughness(_) => "float",
            Self::Bool(_) => "boolean",
            Self::Choice(_) => "string",
            Self::Colour(_) => "rgb",
            Self::Ior(_) => "float or string",
            Self::Other(p) => p.kind,
        }
    }

    /// The valid values as the docs write them, for a float.
    #[cfg_attr(not(test), allow(dead_code))] // read by the docs' test
    pub fn float_range(&self) -> Option<&'static str> {
        match self {
            Self::Float(p) => Some(p.range),
            Self::Roughness(p) => Some(p.range),
            _ => None,
        }
    }

    /// What it means.
    #[cfg_attr(not(test), allow(dead_code))] // read by the docs' test
    pub fn doc(&self) -> &'static str {
        match self {
            Self::Int(p) => p.doc,
            Self::Float(p) => p.doc,
            Self::Roughness(p) => p.doc,
            Self::Bool(p) => p.doc,
            Self::Choice(p) => p.doc,
            Self::Colour(p) => p.doc,
            Self::Ior(p) => p.doc,
            Self::Other(p) => p.doc,
        }
    }

    /// The Mitsuba name.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Int(p) => p.name,
            Self::Float(p) => p.name,
            Self::Roughness(p) => p.name,
            Self::Bool(p) => p.name,
            Self::Choice(p) => p.name,
            Self::Colour(p) => p.name,
            Self::Ior(p) => p.name,
            Self::Other(p) => p.name,
        }
    }
}

/// The parameters of one plugin.
#[derive(Debug)]
pub(crate) struct PluginParams {
    /// The element: `integrator`, `sampler`, `bsdf`, `shape`, `emitter`, `sensor`, `film`,
    /// `rfilter`, `texture`.
    pub category: &'static str,
    /// The `type` attribute.
    pub plugin: &'static str,
    /// Every parameter the loader reads for it.
    pub params: &'static [ParamDef],
}

/// Every plugin whose parameters are defined here.
pub(crate) const PLUGINS: &[PluginParams] = &[
    integrator::PATH,
    integrator::DIRECT,
    integrator::BDPT,
    integrator::MLT,
    integrator::PTRACER,
    integrator::GUIDED,
    integrator::MOMENT,
    sampler::INDEPENDENT,
    sampler::STRATIFIED,
    sampler::LDSAMPLER,
    sampler::MULTIJITTER,
    sampler::ORTHOGONAL,
    bsdf::DIFFUSE,
    bsdf::CONDUCTOR,
    bsdf::DIELECTRIC,
    bsdf::THINDIELECTRIC,
    bsdf::PLASTIC,
    bsdf::ROUGHCONDUCTOR,
    bsdf::ROUGHDIELECTRIC,
    bsdf::ROUGHPLASTIC,
    bsdf_composite::PRINCIPLED,
    bsdf_composite::BLENDBSDF,
    bsdf_composite::MASK,
    bsdf_composite::TWOSIDED,
    shape::INSTANCE,
    shape::SHAPEGROUP,
    shape_plugins::RECTANGLE,
    shape_plugins::CUBE,
    shape_plugins::DISK,
    shape_plugins::SPHERE,
    shape_plugins::CYLINDER,
    shape_plugins::OBJ,
    shape_plugins::PLY,
    shape_plugins::SERIALIZED,
    emitter::AREA,
    emitter::POINT,
    emitter::SPOT,
    emitter::PROJECTOR,
    emitter::DIRECTIONAL,
    emitter::CONSTANT,
    emitter::ENVMAP,
    sensor::PERSPECTIVE,
    sensor::THINLENS,
    sensor::ORTHOGRAPHIC,
    film::HDRFILM,
    film::BOX,
    film::TENT,
    film::GAUSSIAN,
    texture::BITMAP,
    texture::CHECKERBOARD,
    bsdf_maps::NORMALMAP,
    bsdf_maps::BUMPMAP,
    volume::GRIDVOLUME,
    volume::CONSTVOLUME,
    volume::TEXTURE_VOLUME,
];

/// The table of plugin `plugin` of element `category`, if it has one.
pub(crate) fn plugin(category: &str, plugin: &str) -> Option<&'static PluginParams> {
    PLUGINS
        .iter()
        .find(|p| p.category == category && p.plugin == plugin)
}

/// A float check: finite and non-negative (`message` otherwise).
pub(crate) fn non_negative(v: f32, message: &str) -> Result<f32, String> {
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(message.to_string())
    }
}

/// A float check: finite and in (`lo`, `hi`] (`message` otherwise).
pub(crate) fn in_half_open(v: f32, lo: f32, hi: f32, message: &str) -> Result<f32, String> {
    if v > lo && v <= hi {
        Ok(v)
    } else {
        Err(message.to_string())
    }
}

impl IntParam {
    /// `v` if it lies in `min..=max`.
    ///
    /// # Errors
    /// An [`Invalid`](crate::validate::Invalid) naming the parameter otherwise.
    pub fn check(&self, v: i64) -> Result<i64, crate::validate::Invalid> {
        if (self.min..=self.max).contains(&v) {
            Ok(v)
        } else {
            Err(crate::validate::Invalid::new(
                self.name,
                format!("= {v} is outside [{}, {}]", self.min, self.max),
            ))
        }
    }
}

impl<T> FloatParam<T> {
    /// `v` as its checked type.
    ///
    /// # Errors
    /// An [`Invalid`](crate::validate::Invalid) naming the parameter when `check` refuses it.
    pub fn check(&self, v: f32) -> Result<T, crate::validate::Invalid> {
        (self.accept)(v).map_err(|m| crate::validate::Invalid::new(self.name, m))
    }
}
