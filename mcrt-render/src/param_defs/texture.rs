//! The parameters of the textures `bitmap` and `checkerboard` (read by
//! `loader/texture.rs`).

use super::{other, BoolParam, ColourParam, OtherParam, ParamDef, PluginParams};

/// `to_uv` of every texture.
pub(crate) const TO_UV: OtherParam = other(
    "to_uv",
    "transform",
    "maps texture coordinates by its 2D affine part (default identity)",
);
/// `filename` of `bitmap`.
pub(crate) const FILENAME: OtherParam = other(
    "filename",
    "string",
    "required: a PNG, JPEG, OpenEXR or Radiance RGBE file on the search path",
);
/// `raw` of `bitmap`.
pub(crate) const RAW: BoolParam = BoolParam {
    name: "raw",
    default: false,
    doc: "use 8- and 16-bit values as stored (no sRGB decoding)",
};
/// `filter_type` of `bitmap`.
pub(crate) const FILTER_TYPE: OtherParam =
    other("filter_type", "string", "`bilinear` (default) or `nearest`");
/// `wrap_mode` of `bitmap`.
pub(crate) const WRAP_MODE: OtherParam = other(
    "wrap_mode",
    "string",
    "`repeat` (default), `mirror` or `clamp`",
);
/// `color0` of `checkerboard`.
pub(crate) const COLOR0: ColourParam = ColourParam {
    name: "color0",
    default: 0.4,
    doc: "where `frac(u) < ½` and `frac(v) < ½` agree (a constant)",
};
/// `color1` of `checkerboard`.
pub(crate) const COLOR1: ColourParam = ColourParam {
    name: "color1",
    default: 0.2,
    doc: "elsewhere (a constant)",
};

/// `<texture type="bitmap">`.
pub(crate) const BITMAP: PluginParams = PluginParams {
    category: "texture",
    plugin: "bitmap",
    params: &[
        ParamDef::Other(&FILENAME),
        ParamDef::Bool(&RAW),
        ParamDef::Other(&FILTER_TYPE),
        ParamDef::Other(&WRAP_MODE),
        ParamDef::Other(&TO_UV),
    ],
};

/// `<texture type="checkerboard">`.
pub(crate) const CHECKERBOARD: PluginParams = PluginParams {
    category: "texture",
    plugin: "checkerboard",
    params: &[
        ParamDef::Colour(&COLOR0),
        ParamDef::Colour(&COLOR1),
        ParamDef::Other(&TO_UV),
    ],
};
