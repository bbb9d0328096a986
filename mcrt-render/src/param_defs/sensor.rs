//! The parameters of the sensors `perspective`, `thinlens` and `orthographic` (read by
//! `loader/sensor.rs`).

use super::{non_negative, other, FloatParam, OtherParam, ParamDef, PluginParams};
use crate::description::ThinLensDesc;

/// `fov`, degrees.
pub(crate) const FOV: FloatParam<f32> = FloatParam {
    name: "fov",
    default: 45.0,
    range: "(0, 180)",
    accept: |v| {
        if v > 0.0 && v < 180.0 {
            Ok(v)
        } else {
            Err("must lie strictly between 0 and 180 degrees".into())
        }
    },
    doc: "field of view in degrees along `fov_axis` (not with `focal_length`)",
};

/// `fov_axis`: `x`, `y`, `diagonal`, `smaller` or `larger`.
pub(crate) const FOV_AXIS: OtherParam = other(
    "fov_axis",
    "string",
    "the axis `fov` spans: `x` (default), `y`, `diagonal`, `smaller` or `larger`",
);

/// `focal_length`: `Nmm` or `N`.
pub(crate) const FOCAL_LENGTH: OtherParam = other(
    "focal_length",
    "string",
    "`Nmm` or `N`, N > 0 millimetres on a 36 × 24 mm frame (default 50 mm when `fov` is \
     not given)",
);

/// `near_clip`.
pub(crate) const NEAR_CLIP: FloatParam<f32> = FloatParam {
    name: "near_clip",
    default: 1e-2,
    range: "> 0",
    accept: |v| {
        if v > 0.0 {
            Ok(v)
        } else {
            Err("must be positive and below far_clip".into())
        }
    },
    doc: "near clip distance",
};

/// `far_clip` (checked against `near_clip` by the loader).
pub(crate) const FAR_CLIP: FloatParam<f32> = FloatParam {
    name: "far_clip",
    default: 1e4,
    range: "> near_clip",
    accept: Ok,
    doc: "far clip distance",
};

/// `to_world` of a sensor.
pub(crate) const TO_WORLD: OtherParam = other(
    "to_world",
    "transform",
    "camera to world: the camera looks down its +z, +y up, +x to the image's left",
);

/// `to_world` of `orthographic`: its scale sets the view's extent.
pub(crate) const ORTHOGRAPHIC_TO_WORLD: OtherParam = other(
    "to_world",
    "transform",
    "camera to world: rays run along its +z from the near plane's rectangle [-1, 1] × \
     [-1/a, 1/a] (a = width / height, +x to the image's left, +y up), so its scale sets the \
     view's extent",
);

/// `focus_distance` of `perspective` and `orthographic`: accepted and ignored, as by
/// Mitsuba 3.
pub(crate) const IGNORED_FOCUS_DISTANCE: OtherParam = other(
    "focus_distance",
    "float",
    "accepted and ignored, as by Mitsuba 3's perspective and orthographic cameras",
);

/// `aperture_radius` of `thinlens` (required: its `default` is never used).
pub(crate) const APERTURE_RADIUS: FloatParam<f32> = FloatParam {
    name: "aperture_radius",
    default: 0.0,
    range: "≥ 0",
    accept: |v| non_negative(v, "must be finite and non-negative"),
    doc: "required: radius of the lens (0 is a pinhole)",
};

/// `focus_distance` of `thinlens`.
pub(crate) const FOCUS_DISTANCE: FloatParam<f32> = FloatParam {
    name: "focus_distance",
    default: ThinLensDesc::FOCUS_DISTANCE,
    range: "> 0",
    accept: |v| {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err("must be finite and positive".into())
        }
    },
    doc: "distance of the plane in focus",
};

/// `<sensor type="perspective">`.
pub(crate) const PERSPECTIVE: PluginParams = PluginParams {
    category: "sensor",
    plugin: "perspective",
    params: &[
        ParamDef::Float(&FOV),
        ParamDef::Other(&FOV_AXIS),
        ParamDef::Other(&FOCAL_LENGTH),
        ParamDef::Float(&NEAR_CLIP),
        ParamDef::Float(&FAR_CLIP),
        ParamDef::Other(&TO_WORLD),
        ParamDef::Other(&IGNORED_FOCUS_DISTANCE),
    ],
};

/// `<sensor type="thinlens">`.
pub(crate) const THINLENS: PluginParams = PluginParams {
    category: "sensor",
    plugin: "thinlens",
    params: &[
        ParamDef::Float(&FOV),
        ParamDef::Other(&FOV_AXIS),
        ParamDef::Other(&FOCAL_LENGTH),
        ParamDef::Float(&NEAR_CLIP),
        ParamDef::Float(&FAR_CLIP),
        ParamDef::Other(&TO_WORLD),
        ParamDef::Float(&APERTURE_RADIUS),
        ParamDef::Float(&FOCUS_DISTANCE),
    ],
};

/// `<sensor type="orthographic">` (Mitsuba 3's `orthographic`).
pub(crate) const ORTHOGRAPHIC: PluginParams = PluginParams {
    category: "sensor",
    plugin: "orthographic",
    params: &[
        ParamDef::Float(&NEAR_CLIP),
        ParamDef::Float(&FAR_CLIP),
        ParamDef::Other(&ORTHOGRAPHIC_TO_WORLD),
        ParamDef::Other(&IGNORED_FOCUS_DISTANCE),
    ],
};
