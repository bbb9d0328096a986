//! The parameters of the materials `principled`, `blendbsdf`, `mask` and `twosided` (read
//! by `loader/bsdf.rs` and `loader/principled.rs`).

use super::{non_negative, ColourParam, FloatParam, OtherParam, ParamDef, PluginParams};

/// A weight of the principled material: in [0, 1] (the defaults are
/// [`PrincipledParams::default`](crate::description::PrincipledParams)'s, Mitsuba 3.9's).
const fn weight(name: &'static str, default: f32, doc: &'static str) -> FloatParam<f32> {
    FloatParam {
        name,
        default,
        range: "[0, 1]",
        accept: |v| {
            if (0.0..=1.0).contains(&v) {
                Ok(v)
            } else {
                Err("must be in [0, 1]".into())
            }
        },
        doc,
    }
}

/// A sampling rate of the principled material: ≥ 0.
const fn rate(name: &'static str, doc: &'static str) -> FloatParam<f32> {
    FloatParam {
        name,
        default: 1.0,
        range: "≥ 0",
        accept: |v| non_negative(v, "must be finite and >= 0"),
        doc,
    }
}

/// `base_color`.
pub(crate) const BASE_COLOR: ColourParam = ColourParam {
    name: "base_color",
    default: 0.5,
    doc: "the base colour (or a texture)",
};
/// `roughness`.
pub(crate) const ROUGHNESS: FloatParam<f32> = weight("roughness", 0.5, "the roughness");
/// `anisotropic`.
pub(crate) const ANISOTROPIC: FloatParam<f32> = weight(
    "anisotropic",
    0.0,
    "stretches the lobe along the shading tangent `dp/du`",
);
/// `metallic`.
pub(crate) const METALLIC: FloatParam<f32> = weight("metallic", 0.0, "metalness");
/// `spec_trans`.
pub(crate) const SPEC_TRANS: FloatParam<f32> = weight(
    "spec_trans",
    0.0,
    "specular transmission (above 0 the material refracts)",
);
/// `spec_tint`.
pub(crate) const SPEC_TINT: FloatParam<f32> = weight(
    "spec_tint",
    0.0,
    "tints the specular toward the base colour",
);
/// `sheen`.
pub(crate) const SHEEN: FloatParam<f32> = weight("sheen", 0.0, "the sheen lobe's weight");
/// `sheen_tint`.
pub(crate) const SHEEN_TINT: FloatParam<f32> =
    weight("sheen_tint", 0.0, "tints the sheen toward the base colour");
/// `flatness`.
pub(crate) const FLATNESS: FloatParam<f32> =
    weight("flatness", 0.0, "blends the diffuse lobe toward subsurface");
/// `clearcoat`.
pub(crate) const CLEARCOAT: FloatParam<f32> =
    weight("clearcoat", 0.0, "the clearcoat lobe's weight");
/// `clearcoat_gloss`.
pub(crate) const CLEARCOAT_GLOSS: FloatParam<f32> =
    weight("clearcoat_gloss", 0.0, "the clearcoat's glossiness");
/// `diffuse_reflectance_sampling_rate`.
pub(crate) const DIFFUSE_RATE: FloatParam<f32> = rate(
    "diffuse_reflectance_sampling_rate",
    "relative probability of sampling the diffuse lobe",
);
/// `main_specular_sampling_rate`.
pub(crate) const SPECULAR_RATE: FloatParam<f32> = rate(
    "main_specular_sampling_rate",
    "relative probability of sampling the main specular lobe",
);
/// `clearcoat_sampling_rate`.
pub(crate) const CLEARCOAT_RATE: FloatParam<f32> = rate(
    "clearcoat_sampling_rate",
    "relative probability of sampling the clearcoat lobe",
);
/// `eta` (not with `specular`).
pub(crate) const ETA: FloatParam<f32> = FloatParam {
    name: "eta",
    default: 1.5,
    range: "> 0",
    accept: |v| {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err("must be finite and > 0".into())
        }
    },
    doc: "the index of refraction (not with `specular`)",
};
/// `specular` (not with `eta`).
pub(crate) const SPECULAR: FloatParam<f32> = FloatParam {
    name: "specular",
    default: 0.5,
    range: "[0, 12.5)",
    accept: |v| {
        if (0.0..crate::description::MAX_SPECULAR).contains(&v) {
            Ok(v)
        } else {
            Err("must lie in [0, 12.5)".into())
        }
    },
    doc: "the index as a reflectance, `eta = 2/(1 − √(0.08 · specular)) − 1` (not with `eta`)",
};

/// `weight` of `blendbsdf`.
pub(crate) const WEIGHT: OtherParam = OtherParam {
    name: "weight",
    kind: "float or texture",
    doc: "required, in [0, 1]: the second material's share",
};
/// `opacity` of `mask`.
pub(crate) const OPACITY: OtherParam = OtherParam {
    name: "opacity",
    kind: "float or texture",
    doc: "in [0, 1], default 0.5: the nested material's share; the rest passes through",
};

/// `<bsdf type="principled">`.
pub(crate) const PRINCIPLED: PluginParams = PluginParams {
    category: "bsdf",
    plugin: "principled",
    params: &[
        ParamDef::Colour(&BASE_COLOR),
        ParamDef::Float(&ROUGHNESS),
        ParamDef::Float(&ANISOTROPIC),
        ParamDef::Float(&METALLIC),
        ParamDef::Float(&SPEC_TRANS),
        ParamDef::Float(&SPEC_TINT),
        ParamDef::Float(&SHEEN),
        ParamDef::Float(&SHEEN_TINT),
        ParamDef::Float(&FLATNESS),
        ParamDef::Float(&CLEARCOAT),
        ParamDef::Float(&CLEARCOAT_GLOSS),
        ParamDef::Float(&DIFFUSE_RATE),
        ParamDef::Float(&SPECULAR_RATE),
        ParamDef::Float(&CLEARCOAT_RATE),
        ParamDef::Float(&ETA),
        ParamDef::Float(&SPECULAR),
    ],
};

/// `<bsdf type="blendbsdf">` (and its two nested materials).
pub(crate) const BLENDBSDF: PluginParams = PluginParams {
    category: "bsdf",
    plugin: "blendbsdf",
    params: &[ParamDef::Other(&WEIGHT)],
};

/// `<bsdf type="mask">` (and its nested material).
pub(crate) const MASK: PluginParams = PluginParams {
    category: "bsdf",
    plugin: "mask",
    params: &[ParamDef::Other(&OPACITY)],
};

/// `<bsdf type="twosided">`: no parameters, one nested material.
pub(crate) const TWOSIDED: PluginParams = PluginParams {
    category: "bsdf",
    plugin: "twosided",
    params: &[],
};
