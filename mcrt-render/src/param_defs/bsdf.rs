//! The parameters of the materials `diffuse`, `conductor`, `dielectric`,
//! `thindielectric`, `plastic` and the rough ones, `roughconductor`, `roughdielectric` and
//! `roughplastic`.

use super::{
    other, BoolParam, ChoiceParam, ColourParam, FloatParam, IorParam, OtherParam, ParamDef,
    PluginParams,
};
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

/// `material` of the conductors: a named conductor, or `none`.
pub(crate) const MATERIAL: OtherParam = other("material", "string", "a named conductor, or `none`");
/// `eta` of the conductors.
pub(crate) const ETA: OtherParam =
    other("eta", "rgb", "real part of the complex index of refraction");
/// `k` of the conductors.
pub(crate) const K: OtherParam = other(
    "k",
    "rgb",
    "imaginary part of the complex index of refraction",
);

const fn colour(name: &'static str, default: f32, doc: &'static str) -> ColourParam {
    ColourParam { name, default, doc }
}

/// `reflectance` of `diffuse`.
pub(crate) const REFLECTANCE: ColourParam = colour("reflectance", 0.5, "the albedo");
/// `specular_reflectance`.
pub(crate) const SPECULAR_REFLECTANCE: ColourParam =
    colour("specular_reflectance", 1.0, "scale on reflection");
/// `specular_transmittance` of the dielectrics.
pub(crate) const SPECULAR_TRANSMITTANCE: ColourParam =
    colour("specular_transmittance", 1.0, "scale on transmission");
/// `diffuse_reflectance` of the plastics.
pub(crate) const DIFFUSE_REFLECTANCE: ColourParam =
    colour("diffuse_reflectance", 0.5, "albedo of the base");

/// `int_ior` of the dielectrics (BK7 glass).
pub(crate) const INT_IOR: IorParam = IorParam {
    name: "int_ior",
    default: 1.5046,
    doc: "interior index of refraction",
};
/// `int_ior` of the plastics (polypropylene).
pub(crate) const COATING_IOR: IorParam = IorParam {
    name: "int_ior",
    default: 1.49,
    doc: "index of refraction of the coating",
};
/// `ext_ior` (air).
pub(crate) const EXT_IOR: IorParam = IorParam {
    name: "ext_ior",
    default: 1.000277,
    doc: "exterior index of refraction",
};

/// `nonlinear` of the plastics.
pub(crate) const NONLINEAR: BoolParam = BoolParam {
    name: "nonlinear",
    default: false,
    doc: "internal scattering tints the base's colour",
};

/// `diffuse`.
pub(crate) const DIFFUSE: PluginParams = PluginParams {
    category: "bsdf",
    plugin: "diffuse",
    params: &[ParamDef::Colour(&REFLECTANCE)],
};

/// `conductor`.
pub(crate) const CONDUCTOR: PluginParams = PluginParams {
    category: "bsdf",
    plugin: "conductor",
    params: &[
        ParamDef::Other(&MATERIAL),
        ParamDef::Other(&ETA),
        ParamDef::Other(&K),
        ParamDef::Colour(&SPECULAR_REFLECTANCE),
    ],
};

/// `dielectric`.
pub(crate) const DIELECTRIC: PluginParams = PluginParams {
    category: "bsdf",
    plugin: "dielectric",
    params: &[
        ParamDef::Ior(&INT_IOR),
        ParamDef::Ior(&EXT_IOR),
        ParamDef::Colour(&SPECULAR_REFLECTANCE),
        ParamDef::Colour(&SPECULAR_TRANSMITTANCE),
    ],
};

/// `thindielectric`: the same parameters as `dielectric` (`int_ior` is the pane's).
pub(crate) const THINDIELECTRIC: PluginParams = PluginParams {
    category: "bsdf",
    plugin: "thindielectric",
    params: DIELECTRIC.params,
};

/// `plastic`.
pub(crate) const PLASTIC: PluginParams = PluginParams {
    category: "bsdf",
    plugin: "plastic",
    params: &[
        ParamDef::Ior(&COATING_IOR),
        ParamDef::Ior(&EXT_IOR),
        ParamDef::Colour(&DIFFUSE_REFLECTANCE),
        ParamDef::Colour(&SPECULAR_REFLECTANCE),
        ParamDef::Bool(&NONLINEAR),
    ],
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
        ParamDef::Colour(&SPECULAR_REFLECTANCE),
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
        ParamDef::Ior(&INT_IOR),
        ParamDef::Ior(&EXT_IOR),
        ParamDef::Colour(&SPECULAR_REFLECTANCE),
        ParamDef::Colour(&SPECULAR_TRANSMITTANCE),
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
        ParamDef::Ior(&COATING_IOR),
        ParamDef::Ior(&EXT_IOR),
        ParamDef::Colour(&DIFFUSE_REFLECTANCE),
        ParamDef::Colour(&SPECULAR_REFLECTANCE),
        ParamDef::Bool(&NONLINEAR),
    ],
};
