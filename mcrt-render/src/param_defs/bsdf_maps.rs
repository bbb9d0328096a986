//! The parameters of the shading-frame adapters `normalmap` and `bumpmap` (Mitsuba 3.9.1's
//! names and defaults). Each also takes exactly one nested BSDF; `bumpmap` exactly one
//! texture of any name.

use super::{BoolParam, FloatParam, OtherParam, ParamDef, PluginParams};

/// `normalmap`'s texture of tangent-space normals.
pub(crate) const NORMALMAP_TEXTURE: OtherParam = OtherParam {
    name: "normalmap",
    kind: "texture",
    doc: "a bitmap of tangent-space normals stored as `(n + 1)/2` (read as the bitmap says: \
          give it `raw` for a normal map saved linearly)",
};

/// `scale` of `bumpmap`.
pub(crate) const BUMP_SCALE: FloatParam<f32> = FloatParam {
    name: "scale",
    default: 1.0,
    range: "finite",
    accept: |v| {
        if v.is_finite() {
            Ok(v)
        } else {
            Err("must be finite".into())
        }
    },
    doc: "multiplier on the height field's gradient",
};

/// `flip_invalid_normals`.
pub(crate) const FLIP_INVALID_NORMALS: BoolParam = BoolParam {
    name: "flip_invalid_normals",
    default: true,
    doc: "mirror a perturbed normal that faces away from the viewer about the shading normal",
};

/// `use_shadowing_function`.
pub(crate) const USE_SHADOWING_FUNCTION: BoolParam = BoolParam {
    name: "use_shadowing_function",
    default: true,
    doc: "scale the value by Estevez et al.'s shadowing term, which softens the terminator",
};

/// `normalmap`.
pub(crate) const NORMALMAP: PluginParams = PluginParams {
    category: "bsdf",
    plugin: "normalmap",
    params: &[
        ParamDef::Other(&NORMALMAP_TEXTURE),
        ParamDef::Bool(&FLIP_INVALID_NORMALS),
        ParamDef::Bool(&USE_SHADOWING_FUNCTION),
    ],
};

/// `bumpmap`.
pub(crate) const BUMPMAP: PluginParams = PluginParams {
    category: "bsdf",
    plugin: "bumpmap",
    params: &[
        ParamDef::Float(&BUMP_SCALE),
        ParamDef::Bool(&FLIP_INVALID_NORMALS),
        ParamDef::Bool(&USE_SHADOWING_FUNCTION),
    ],
};
