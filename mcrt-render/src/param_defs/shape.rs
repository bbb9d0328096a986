//! The parameters of the shapes `instance` and `shapegroup` (the other shapes are read by
//! code of their own, `loader/shape.rs`).

use super::{OtherParam, ParamDef, PluginParams};

/// `to_world` of an instance: placed on top of each grouped shape's own.
pub(crate) const INSTANCE_TO_WORLD: OtherParam = OtherParam {
    name: "to_world",
    kind: "transform",
    doc: "the group's space to world space, applied after each grouped shape's own `to_world`",
};

/// `to_world` of a shape group: accepted and ignored, as by Mitsuba 3.9.1.
pub(crate) const GROUP_TO_WORLD: OtherParam = OtherParam {
    name: "to_world",
    kind: "transform",
    doc: "accepted and ignored, as by Mitsuba 3 (place the group with its instances' `to_world`)",
};

/// `<shape type="instance">`.
pub(crate) const INSTANCE: PluginParams = PluginParams {
    category: "shape",
    plugin: "instance",
    params: &[ParamDef::Other(&INSTANCE_TO_WORLD)],
};

/// `<shape type="shapegroup">`.
pub(crate) const SHAPEGROUP: PluginParams = PluginParams {
    category: "shape",
    plugin: "shapegroup",
    params: &[ParamDef::Other(&GROUP_TO_WORLD)],
};
