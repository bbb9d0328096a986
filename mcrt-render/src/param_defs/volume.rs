//! The parameters of the volumes `gridvolume` and `constvolume` and of the volume texture
//! (`<texture type="volume">`), which are read only to check them (`loader/volume.rs`: no
//! shape may use them). Defaults are Mitsuba 3's (`src/volumes/grid.cpp`, `const.cpp`).

use super::{BoolParam, ChoiceParam, OtherParam, ParamDef, PluginParams};

/// `filename` of `gridvolume`.
pub(crate) const FILENAME: OtherParam = OtherParam {
    name: "filename",
    kind: "string",
    doc: "the grid file (Mitsuba's `.vol`, starting with `VOL`); required, and it must exist",
};

/// `filter_type` of `gridvolume` (compared with case, as Mitsuba 3 does).
pub(crate) const FILTER_TYPE: ChoiceParam = ChoiceParam {
    name: "filter_type",
    default: "trilinear",
    choices: &["trilinear", "nearest"],
    doc: "interpolation of the voxels (checked only; written in lower case)",
};

/// `wrap_mode` of `gridvolume` (compared with case, as Mitsuba 3 does).
pub(crate) const WRAP_MODE: ChoiceParam = ChoiceParam {
    name: "wrap_mode",
    default: "clamp",
    choices: &["repeat", "mirror", "clamp"],
    doc: "lookups outside the grid (checked only; written in lower case)",
};

/// `raw` of `gridvolume`.
pub(crate) const RAW: BoolParam = BoolParam {
    name: "raw",
    default: false,
    doc: "no colour conversion of the data (checked only)",
};

/// `accel` of `gridvolume`.
pub(crate) const ACCEL: BoolParam = BoolParam {
    name: "accel",
    default: true,
    doc: "hardware interpolation on the GPU (checked only)",
};

/// `use_grid_bbox` of `gridvolume`.
pub(crate) const USE_GRID_BBOX: BoolParam = BoolParam {
    name: "use_grid_bbox",
    default: false,
    doc: "place the grid in its file's bounding box (checked only)",
};

/// `max_value` of `gridvolume` (no default: the grid's maximum).
pub(crate) const MAX_VALUE: OtherParam = OtherParam {
    name: "max_value",
    kind: "float",
    doc: "the volume's largest value, instead of the grid's (checked only)",
};

/// `to_world` of the volumes.
pub(crate) const TO_WORLD: OtherParam = OtherParam {
    name: "to_world",
    kind: "transform",
    doc: "placement of the volume (checked only)",
};

/// `value` of `constvolume` (default 1).
pub(crate) const VALUE: OtherParam = OtherParam {
    name: "value",
    kind: "rgb",
    doc: "the constant value, default 1 (checked only)",
};

/// `volume` of the volume texture: its nested or referenced `<volume>`.
pub(crate) const VOLUME: OtherParam = OtherParam {
    name: "volume",
    kind: "volume",
    doc: "the one `<volume name=\"volume\">` (nested or a `<ref>`), read as above",
};

/// `gridvolume`.
pub(crate) const GRIDVOLUME: PluginParams = PluginParams {
    category: "volume",
    plugin: "gridvolume",
    params: &[
        ParamDef::Other(&FILENAME),
        ParamDef::Choice(&FILTER_TYPE),
        ParamDef::Choice(&WRAP_MODE),
        ParamDef::Bool(&RAW),
        ParamDef::Bool(&ACCEL),
        ParamDef::Bool(&USE_GRID_BBOX),
        ParamDef::Other(&MAX_VALUE),
        ParamDef::Other(&TO_WORLD),
    ],
};

/// `constvolume`.
pub(crate) const CONSTVOLUME: PluginParams = PluginParams {
    category: "volume",
    plugin: "constvolume",
    params: &[ParamDef::Other(&VALUE), ParamDef::Other(&TO_WORLD)],
};

/// `<texture type="volume">`.
pub(crate) const TEXTURE_VOLUME: PluginParams = PluginParams {
    category: "texture",
    plugin: "volume",
    params: &[ParamDef::Other(&VOLUME)],
};
