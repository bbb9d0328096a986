//! The parameters of the samplers `independent`, `stratified`, `ldsampler`, `multijitter`
//! and `orthogonal`.

use super::{BoolParam, IntParam, ParamDef, PluginParams};
use crate::description::SampleCount;

/// `sample_count`, checked into a [`SampleCount`].
pub(crate) const SAMPLE_COUNT: IntParam = IntParam {
    name: "sample_count",
    default: SampleCount::DEFAULT.get_const() as i64,
    min: 1,
    max: SampleCount::MAX as i64,
    doc: "samples per pixel; `--spp` overrides it",
};

/// `seed`.
pub(crate) const SEED: IntParam = IntParam {
    name: "seed",
    default: 0,
    min: 0,
    max: i64::MAX,
    doc: "the sampler's seed; `--seed` overrides it",
};

/// `jitter` of the stratified samplers (only `true`, the default, is rendered).
pub(crate) const JITTER: BoolParam = BoolParam {
    name: "jitter",
    default: true,
    doc: "only `true` is supported",
};

/// `strength` of `orthogonal` (only 2, the default, is rendered).
pub(crate) const STRENGTH: IntParam = IntParam {
    name: "strength",
    default: 2,
    min: 2,
    max: 2,
    doc: "only 2 is supported: ours stratifies 2D projections only",
};

const PLAIN: &[ParamDef] = &[ParamDef::Int(&SAMPLE_COUNT), ParamDef::Int(&SEED)];
const JITTERED: &[ParamDef] = &[
    ParamDef::Int(&SAMPLE_COUNT),
    ParamDef::Int(&SEED),
    ParamDef::Bool(&JITTER),
];

/// `independent`.
pub(crate) const INDEPENDENT: PluginParams = PluginParams {
    category: "sampler",
    plugin: "independent",
    params: PLAIN,
};

/// `stratified`.
pub(crate) const STRATIFIED: PluginParams = PluginParams {
    category: "sampler",
    plugin: "stratified",
    params: JITTERED,
};

/// `ldsampler`.
pub(crate) const LDSAMPLER: PluginParams = PluginParams {
    category: "sampler",
    plugin: "ldsampler",
    params: PLAIN,
};

/// `multijitter`.
pub(crate) const MULTIJITTER: PluginParams = PluginParams {
    category: "sampler",
    plugin: "multijitter",
    params: JITTERED,
};

/// `orthogonal`.
pub(crate) const ORTHOGONAL: PluginParams = PluginParams {
    category: "sampler",
    plugin: "orthogonal",
    params: &[
        ParamDef::Int(&SAMPLE_COUNT),
        ParamDef::Int(&SEED),
        ParamDef::Bool(&JITTER),
        ParamDef::Int(&STRENGTH),
    ],
};
