//! The parameters of the rough materials `roughconductor`, `roughdielectric` and
//! `roughplastic`.

use super::{BoolParam, ChoiceParam, FloatParam, OtherParam, ParamDef, PluginParams};
use crate::description::Roughness;

/// `distribution`: the microfacet normal distribution.
pub(crate) const DISTRIBUTION: ChoiceParam = ChoiceParam {
    name: "distribution",
    default: "beckmann",
    choices: &["beckmann", "ggx"],
    doc: "the microfacet normal distribution",
};

/// `alpha`, checked into a [`Roughness`] (values in [0, 10⁻⁴) raised to 10⁻⁴, as Mitsuba 3
/// does).
pub(crate) const ALPHA: FloatParam<Roughness> = FloatParam {
    name: "alpha",
    default: Roughness::DEFAULT,
    range: "[0, 10]",
    accept: |v| Roughness::raised(v).map_err(|i| i.message),
    doc: "the roughness; below 10⁻⁴ (0 included) it is raised to 10⁻⁴",
};

/// `alpha_u` of `roughconductor` and `roughdielectric`: the roughness along the shading
/// tangent (Mitsuba's `dp/du`), read with [`ALPHA`]'s range; with [`ALPHA_V`] instead of
/// `alpha`.
pub(crate) const ALPHA_U: OtherParam = OtherParam {
    name: "alpha_u",
    kind: "float",
    doc: "instead of `alpha`, with `alpha_v`: the roughness along the shading tangent `dp/du` \
          (anisotropic when they differ)",
};

/// `alpha_v`: see [`ALPHA_U`].
pub(crate) const ALPHA_V: OtherParam = OtherParam {
    name: "alpha_v",
    kind: "float",
    doc: "the roughness along the bitangent; see `alpha_u`",
};

/// `alpha_u` of `roughplastic`, which is isotropic in Mitsuba 3: only with an equal
/// `alpha_v`.
pub(crate) const ALPHA_U_ISOTROPIC: OtherParam = OtherParam {
    name: "alpha_u",
    kind: "float",
    doc: "instead of `alpha`, with an equal `alpha_v` (Mitsuba 3's `roughplastic` is \
          isotropic: anisotropy is an error)",
};

/// `alpha_v` of `roughplastic`: see [`ALPHA_U_ISOTROPIC`].
pub(crate) const ALPHA_V_ISOTROPIC: OtherParam = OtherParam {
    name: "alpha_v",
    kind: "float",
    doc: "see `alpha_u`",
};

/// `sample_visible`: sample the visible normals (Mitsuba's default) or all of them.
pub(crate) const SAMPLE_VISIBLE: BoolParam = BoolParam {
    name: "sample_visible",
    default: true,
    doc: "draw only the normals visible from the incident direction (less noise); \
          `false` draws from the whole distribution. The expected value is the same",
};

const fn other(name: &'static str, kind: &'static str, doc: &'static str) -> OtherParam {
    OtherParam { name, kind, doc }
}

const MATERIAL: OtherParam = other("material", "string", "a named conductor, or `none`");
const ETA: OtherParam = other("eta", "rgb", "real part of the complex index of refraction");
const K: OtherParam = other(
    "k",
    "rgb",
    "imaginary part of the complex index of refraction",
);
const SPECULAR_REFLECTANCE: OtherParam =
    other("specular_reflectance", "rgb", "scale on reflection");
const SPECULAR_TRANSMITTANCE: OtherParam =
    other("specular_transmittance", "rgb", "scale on transmission");
const DIFFUSE_REFLECTANCE: OtherParam = other("diffuse_reflectance", "rgb", "albedo of the base");
const INT_IOR: OtherParam = other("int_ior", "float or string", "interior index of refraction");
const EXT_IOR: OtherParam = other("ext_ior", "float or string", "exterior index of refraction");

/// `nonlinear` of `roughplastic`.
pub(crate) const NONLINEAR: BoolParam = BoolParam {
    name: "nonlinear",
    default: false,
    doc: "internal scattering tints the base's colour",
};

/// `roughconductor`.
pub(crate) const ROUGHCONDUCTOR: PluginParams = PluginParams {
    category: "bsdf",
    plugin: "roughconductor",
    params: &[
        ParamDef::Choice(&DISTRIBUTION),
        ParamDef::Roughness(&ALPHA),
        ParamDef::Other(&ALPHA_U),
        ParamDef::Other(&ALPHA_V),
        ParamDef::Bool(&SAMPLE_VISIBLE),
        ParamDef::Other(&MATERIAL),
        ParamDef::Other(&ETA),
        ParamDef::Other(&K),
        ParamDef::Other(&SPECULAR_REFLECTANCE),
    ],
};

/// `roughdielectric`.
pub(crate) const ROUGHDIELECTRIC: PluginParams = PluginParams {
    category: "bsdf",
    plugin: "roughdielectric",
    params: &[
        ParamDef::Choice(&DISTRIBUTION),
        ParamDef::Roughness(&ALPHA),
        ParamDef::Other(&ALPHA_U),
        ParamDef::Other(&ALPHA_V),
        ParamDef::Bool(&SAMPLE_VISIBLE),
        ParamDef::Other(&INT_IOR),
        ParamDef::Other(&EXT_IOR),
        ParamDef::Other(&SPECULAR_REFLECTANCE),
        ParamDef::Other(&SPECULAR_TRANSMITTANCE),
    ],
};

/// `roughplastic`.
pub(crate) const ROUGHPLASTIC: PluginParams = PluginParams {
    category: "bsdf",
    plugin: "roughplastic",
    params: &[
        ParamDef::Choice(&DISTRIBUTION),
        ParamDef::Roughness(&ALPHA),
        ParamDef::Other(&ALPHA_U_ISOTROPIC),
        ParamDef::Other(&ALPHA_V_ISOTROPIC),
        ParamDef::Bool(&SAMPLE_VISIBLE),
        ParamDef::Other(&INT_IOR),
        ParamDef::Other(&EXT_IOR),
        ParamDef::Other(&DIFFUSE_REFLECTANCE),
        ParamDef::Other(&SPECULAR_REFLECTANCE),
        ParamDef::Bool(&NONLINEAR),
    ],
};
