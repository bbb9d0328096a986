//! The parameters of the film `hdrfilm` and the reconstruction filters `box`, `tent` and
//! `gaussian` (read by `loader/sensor.rs`).

use super::{BoolParam, FloatParam, IntParam, OtherParam, ParamDef, PluginParams};
use crate::validate::MAX_FILM_PIXELS;

/// Largest film side, in pixels (the area is bounded by [`MAX_FILM_PIXELS`]).
pub(crate) const MAX_RESOLUTION: i64 = MAX_FILM_PIXELS as i64;

const fn side(name: &'static str, default: i64, min: i64, doc: &'static str) -> IntParam {
    IntParam {
        name,
        default,
        min,
        max: MAX_RESOLUTION,
        doc,
    }
}

/// `width`.
pub(crate) const WIDTH: IntParam = side("width", 768, 1, "width in pixels");
/// `height`.
pub(crate) const HEIGHT: IntParam = side("height", 576, 1, "height in pixels");
/// `crop_offset_x`.
pub(crate) const CROP_OFFSET_X: IntParam =
    side("crop_offset_x", 0, 0, "left edge of the rendered window");
/// `crop_offset_y`.
pub(crate) const CROP_OFFSET_Y: IntParam =
    side("crop_offset_y", 0, 0, "top edge of the rendered window");
/// `crop_width` (default: to the film's right edge).
pub(crate) const CROP_WIDTH: IntParam = side(
    "crop_width",
    1,
    1,
    "width of the rendered window (default: to the film's right edge)",
);
/// `crop_height` (default: to the film's bottom edge).
pub(crate) const CROP_HEIGHT: IntParam = side(
    "crop_height",
    1,
    1,
    "height of the rendered window (default: to the film's bottom edge)",
);

const fn ignored(name: &'static str, kind: &'static str) -> OtherParam {
    OtherParam {
        name,
        kind,
        doc: "accepted and ignored (output options)",
    }
}

/// The output-format options, accepted and ignored (the renderer writes float RGB EXR).
pub(crate) const FILE_FORMAT: OtherParam = ignored("file_format", "string");
/// See [`FILE_FORMAT`].
pub(crate) const PIXEL_FORMAT: OtherParam = ignored("pixel_format", "string");
/// See [`FILE_FORMAT`].
pub(crate) const COMPONENT_FORMAT: OtherParam = ignored("component_format", "string");
/// `sample_border`, accepted and ignored.
pub(crate) const SAMPLE_BORDER: BoolParam = BoolParam {
    name: "sample_border",
    default: false,
    doc: "accepted and ignored (output options)",
};
/// `compensate`, accepted and ignored.
pub(crate) const COMPENSATE: BoolParam = BoolParam {
    name: "compensate",
    default: false,
    doc: "accepted and ignored (output options)",
};
/// Mitsuba 0.6's `banner`: Mitsuba 3's film marks it read, of any type.
pub(crate) const BANNER: OtherParam = ignored("banner", "any");

/// A filter width in pixels: in (0, 16].
fn pixels(v: f32) -> Result<f32, String> {
    super::in_half_open(v, 0.0, 16.0, "must lie in (0, 16] pixels")
}

/// `radius` of `tent`.
pub(crate) const TENT_RADIUS: FloatParam<f32> = FloatParam {
    name: "radius",
    default: 1.0,
    range: "(0, 16]",
    accept: pixels,
    doc: "radius in pixels: `max(0, 1 − |x|/r)` per axis",
};

/// `stddev` of `gaussian`.
pub(crate) const STDDEV: FloatParam<f32> = FloatParam {
    name: "stddev",
    default: 0.5,
    range: "(0, 16]",
    accept: pixels,
    doc: "standard deviation in pixels (truncated at 4σ)",
};

/// `<film type="hdrfilm">`.
pub(crate) const HDRFILM: PluginParams = PluginParams {
    category: "film",
    plugin: "hdrfilm",
    params: &[
        ParamDef::Int(&WIDTH),
        ParamDef::Int(&HEIGHT),
        ParamDef::Int(&CROP_OFFSET_X),
        ParamDef::Int(&CROP_OFFSET_Y),
        ParamDef::Int(&CROP_WIDTH),
        ParamDef::Int(&CROP_HEIGHT),
        ParamDef::Other(&FILE_FORMAT),
        ParamDef::Other(&PIXEL_FORMAT),
        ParamDef::Other(&COMPONENT_FORMAT),
        ParamDef::Bool(&SAMPLE_BORDER),
        ParamDef::Bool(&COMPENSATE),
        ParamDef::Other(&BANNER),
    ],
};

/// `<rfilter type="box">`: no parameters.
pub(crate) const BOX: PluginParams = PluginParams {
    category: "rfilter",
    plugin: "box",
    params: &[],
};

/// `<rfilter type="tent">`.
pub(crate) const TENT: PluginParams = PluginParams {
    category: "rfilter",
    plugin: "tent",
    params: &[ParamDef::Float(&TENT_RADIUS)],
};

/// `<rfilter type="gaussian">`.
pub(crate) const GAUSSIAN: PluginParams = PluginParams {
    category: "rfilter",
    plugin: "gaussian",
    params: &[ParamDef::Float(&STDDEV)],
};
