//! The parameters of the emitters `area`, `point`, `spot`, `projector`, `directional`,
//! `constant` and `envmap` (read by `loader/emitter.rs`).

use super::{non_negative, other, ChoiceParam, FloatParam, OtherParam, ParamDef, PluginParams};

/// `radiance` of `area`: a colour or a texture.
pub(crate) const AREA_RADIANCE: OtherParam = other(
    "radiance",
    "rgb or texture",
    "emitted radiance, from the front side only",
);
/// `radiance` of `constant`.
pub(crate) const RADIANCE: OtherParam = other("radiance", "rgb", "radiance from every direction");
/// `intensity` of `point` and `spot`.
pub(crate) const INTENSITY: OtherParam = other("intensity", "rgb", "radiant intensity (W/sr)");
/// `irradiance` of `directional`.
pub(crate) const IRRADIANCE: OtherParam = other(
    "irradiance",
    "rgb",
    "irradiance on a surface facing the light (W/m²)",
);
/// `irradiance` of `projector`: a colour or a texture.
pub(crate) const PROJECTOR_IRRADIANCE: OtherParam = other(
    "irradiance",
    "rgb or texture",
    "the projected image (a colour is a one-pixel image)",
);
/// `position` of `point`.
pub(crate) const POSITION: OtherParam = other(
    "position",
    "point",
    "where the light sits (or give `to_world`, not both)",
);
/// `direction` of `directional`.
pub(crate) const DIRECTION: OtherParam = other(
    "direction",
    "vector",
    "the direction the light travels, any non-zero length (or give `to_world`, not both)",
);
/// `to_world` of `point` (its translation).
pub(crate) const POINT_TO_WORLD: OtherParam = other(
    "to_world",
    "transform",
    "places the light at its translation",
);
/// `to_world` of `directional` (its +z).
pub(crate) const DIRECTIONAL_TO_WORLD: OtherParam =
    other("to_world", "transform", "the light travels along its +z");
/// `to_world` of `spot` and `projector`.
pub(crate) const CONE_TO_WORLD: OtherParam = other(
    "to_world",
    "transform",
    "the light at its origin, shining along its +z; a rotation, uniform scale and translation",
);
/// `to_world` of `envmap`.
pub(crate) const ENVMAP_TO_WORLD: OtherParam = other(
    "to_world",
    "transform",
    "turns the map: a rotation (or reflection) with any translation",
);
/// `texture` of `spot`.
pub(crate) const SPOT_TEXTURE: OtherParam = other(
    "texture",
    "texture",
    "multiplies the intensity by the image spread over the cutoff cone",
);
/// `filename` of `envmap`.
pub(crate) const ENVMAP_FILENAME: OtherParam = other(
    "filename",
    "string",
    "required: an OpenEXR or Radiance RGBE file on the search path",
);
/// `focal_length` of `projector`: refused (not supported yet).
pub(crate) const PROJECTOR_FOCAL_LENGTH: OtherParam = other(
    "focal_length",
    "string",
    "refused (`Unsupported`, not yet): give `fov`",
);

/// `cutoff_angle` of `spot`, degrees.
pub(crate) const CUTOFF_ANGLE: FloatParam<f32> = FloatParam {
    name: "cutoff_angle",
    default: crate::description::EmitterDesc::SPOT_CUTOFF_ANGLE,
    range: "(0, 180]",
    accept: |v| super::in_half_open(v, 0.0, 180.0, "must lie in (0, 180] degrees"),
    doc: "half-angle in degrees beyond which nothing is emitted",
};

/// `beam_width` of `spot`, degrees (its default, ¾ of the cutoff, depends on it).
pub(crate) const BEAM_WIDTH: FloatParam<f32> = FloatParam {
    name: "beam_width",
    default: 0.75 * crate::description::EmitterDesc::SPOT_CUTOFF_ANGLE,
    range: "≥ 0",
    accept: |v| non_negative(v, "must be finite and non-negative"),
    doc: "half-angle in degrees up to which the intensity is the peak's (default ¾ of \
          `cutoff_angle`)",
};

/// `scale` of `envmap` and `projector`.
pub(crate) const SCALE: FloatParam<f32> = FloatParam {
    name: "scale",
    default: 1.0,
    range: "≥ 0",
    accept: |v| non_negative(v, "must be finite and non-negative"),
    doc: "scale on the emitted light",
};

/// `fov` of `projector`, degrees (required: its `default` is never used).
pub(crate) const PROJECTOR_FOV: FloatParam<f32> = FloatParam {
    name: "fov",
    default: 45.0,
    range: "(0, 180)",
    accept: |v| {
        if v > 0.0 && v < 180.0 {
            Ok(v)
        } else {
            Err("must lie in (0, 180) degrees".into())
        }
    },
    doc: "required: the field of view in degrees along `fov_axis`",
};

/// `fov_axis` of `projector`.
pub(crate) const PROJECTOR_FOV_AXIS: ChoiceParam = ChoiceParam {
    name: "fov_axis",
    default: "x",
    choices: &["x", "y", "smaller", "larger", "diagonal"],
    doc: "the image axis `fov` spans, relative to the image's aspect ratio",
};

/// `<emitter type="area">`.
pub(crate) const AREA: PluginParams = PluginParams {
    category: "emitter",
    plugin: "area",
    params: &[ParamDef::Other(&AREA_RADIANCE)],
};

/// `<emitter type="point">`.
pub(crate) const POINT: PluginParams = PluginParams {
    category: "emitter",
    plugin: "point",
    params: &[
        ParamDef::Other(&INTENSITY),
        ParamDef::Other(&POSITION),
        ParamDef::Other(&POINT_TO_WORLD),
    ],
};

/// `<emitter type="spot">`.
pub(crate) const SPOT: PluginParams = PluginParams {
    category: "emitter",
    plugin: "spot",
    params: &[
        ParamDef::Other(&INTENSITY),
        ParamDef::Float(&CUTOFF_ANGLE),
        ParamDef::Float(&BEAM_WIDTH),
        ParamDef::Other(&CONE_TO_WORLD),
        ParamDef::Other(&SPOT_TEXTURE),
    ],
};

/// `<emitter type="projector">`.
pub(crate) const PROJECTOR: PluginParams = PluginParams {
    category: "emitter",
    plugin: "projector",
    params: &[
        ParamDef::Other(&PROJECTOR_IRRADIANCE),
        ParamDef::Float(&SCALE),
        ParamDef::Float(&PROJECTOR_FOV),
        ParamDef::Choice(&PROJECTOR_FOV_AXIS),
        ParamDef::Other(&PROJECTOR_FOCAL_LENGTH),
        ParamDef::Other(&CONE_TO_WORLD),
    ],
};

/// `<emitter type="directional">`.
pub(crate) const DIRECTIONAL: PluginParams = PluginParams {
    category: "emitter",
    plugin: "directional",
    params: &[
        ParamDef::Other(&IRRADIANCE),
        ParamDef::Other(&DIRECTION),
        ParamDef::Other(&DIRECTIONAL_TO_WORLD),
    ],
};

/// `<emitter type="constant">`.
pub(crate) const CONSTANT: PluginParams = PluginParams {
    category: "emitter",
    plugin: "constant",
    params: &[ParamDef::Other(&RADIANCE)],
};

/// `<emitter type="envmap">`.
pub(crate) const ENVMAP: PluginParams = PluginParams {
    category: "emitter",
    plugin: "envmap",
    params: &[
        ParamDef::Other(&ENVMAP_FILENAME),
        ParamDef::Float(&SCALE),
        ParamDef::Other(&ENVMAP_TO_WORLD),
    ],
};
