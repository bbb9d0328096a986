//! The parameters of the shapes `rectangle`, `cube`, `disk`, `sphere`, `cylinder` and the
//! mesh files `obj`, `ply` and `serialized` (read by `loader/shape.rs`; `shapegroup` and
//! `instance` are in `shape.rs`).

use super::{other, BoolParam, FloatParam, IntParam, OtherParam, ParamDef, PluginParams};

/// `to_world` of every shape.
pub(crate) const TO_WORLD: OtherParam = other(
    "to_world",
    "transform",
    "object space to world space: affine and invertible",
);

/// `flip_normals` of every shape.
pub(crate) const FLIP_NORMALS: BoolParam = BoolParam {
    name: "flip_normals",
    default: false,
    doc: "turn the front side (and the normals) around",
};

/// `center` of `sphere`.
pub(crate) const CENTER: OtherParam = other("center", "point", "the centre (default origin)");

/// `radius` of `sphere`.
pub(crate) const SPHERE_RADIUS: FloatParam<f32> = FloatParam {
    name: "radius",
    default: 1.0,
    range: "> 0",
    accept: |v| {
        if v > 0.0 {
            Ok(v)
        } else {
            Err("must be positive".into())
        }
    },
    doc: "the radius, applied before `to_world`",
};

/// `p0` of `cylinder`.
pub(crate) const P0: OtherParam = other("p0", "point", "start of the axis (default origin)");
/// `p1` of `cylinder`.
pub(crate) const P1: OtherParam = other(
    "p1",
    "point",
    "end of the axis (default (0, 0, 1)); must differ from `p0`",
);

/// `radius` of `cylinder`.
pub(crate) const CYLINDER_RADIUS: FloatParam<f32> = FloatParam {
    name: "radius",
    default: 1.0,
    range: "> 0",
    accept: |v| {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err("must be finite and positive".into())
        }
    },
    doc: "the tube's radius, applied before `to_world`",
};

/// `filename` of the mesh files.
pub(crate) const FILENAME: OtherParam = other(
    "filename",
    "string",
    "required: the mesh file, found on the search path",
);
/// `face_normals` of the mesh files.
pub(crate) const FACE_NORMALS: BoolParam = BoolParam {
    name: "face_normals",
    default: false,
    doc: "flat face normals even where the file has vertex normals",
};
/// `flip_tex_coords` of `obj`.
pub(crate) const FLIP_TEX_COORDS: BoolParam = BoolParam {
    name: "flip_tex_coords",
    default: true,
    doc: "texture coordinates' `v` becomes `1 − v`, as in Mitsuba",
};
/// `shape_index` of `serialized`.
pub(crate) const SHAPE_INDEX: IntParam = IntParam {
    name: "shape_index",
    default: 0,
    min: 0,
    max: u32::MAX as i64,
    doc: "which mesh of the file",
};

/// The parameters every shape has, then `rest`.
macro_rules! shape {
    ($plugin:literal $(, $rest:expr)*) => {
        PluginParams {
            category: "shape",
            plugin: $plugin,
            params: &[ParamDef::Other(&TO_WORLD), ParamDef::Bool(&FLIP_NORMALS) $(, $rest)*],
        }
    };
}

/// `<shape type="rectangle">`.
pub(crate) const RECTANGLE: PluginParams = shape!("rectangle");
/// `<shape type="cube">`.
pub(crate) const CUBE: PluginParams = shape!("cube");
/// `<shape type="disk">`.
pub(crate) const DISK: PluginParams = shape!("disk");
/// `<shape type="sphere">`.
pub(crate) const SPHERE: PluginParams = shape!(
    "sphere",
    ParamDef::Other(&CENTER),
    ParamDef::Float(&SPHERE_RADIUS)
);
/// `<shape type="cylinder">`.
pub(crate) const CYLINDER: PluginParams = shape!(
    "cylinder",
    ParamDef::Other(&P0),
    ParamDef::Other(&P1),
    ParamDef::Float(&CYLINDER_RADIUS)
);
/// `<shape type="obj">`.
pub(crate) const OBJ: PluginParams = shape!(
    "obj",
    ParamDef::Other(&FILENAME),
    ParamDef::Bool(&FACE_NORMALS),
    ParamDef::Bool(&FLIP_TEX_COORDS)
);
/// `<shape type="ply">`.
pub(crate) const PLY: PluginParams = shape!(
    "ply",
    ParamDef::Other(&FILENAME),
    ParamDef::Bool(&FACE_NORMALS)
);
/// `<shape type="serialized">`.
pub(crate) const SERIALIZED: PluginParams = shape!(
    "serialized",
    ParamDef::Other(&FILENAME),
    ParamDef::Int(&SHAPE_INDEX),
    ParamDef::Bool(&FACE_NORMALS)
);
