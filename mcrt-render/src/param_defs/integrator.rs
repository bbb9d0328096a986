//! The parameters of the integrators `path`, `direct`, `bdpt`, `mlt`, `ptracer` and `guided`, and the check of
//! an [`IntegratorDesc`] against them (for a description built in code; the loader checks
//! each value as it reads it).

use super::{in_half_open, BoolParam, FloatParam, IntParam, ParamDef, PluginParams};
use crate::description::{IntegratorDesc, SampleCount};
use crate::invalid::Invalid;
use mcrt::integrator::Mlt;

/// Largest `emitter_samples` and `bsdf_samples` of the direct integrator: 2¹⁶ each, so one
/// pixel sample stays short enough to cancel within a second.
pub const MAX_SHADING_SAMPLES: u32 = 1 << 16;

/// Longest `max_depth` of `mlt` (its image keeps one buffer per path length).
pub const MAX_MLT_DEPTH: i32 = 64;

/// `max_depth` of `path` and `bdpt`.
pub(crate) const MAX_DEPTH: IntParam = IntParam {
    name: "max_depth",
    default: -1,
    min: -1,
    max: i32::MAX as i64,
    doc: "longest path in segments; −1 unlimited, 1 emitters seen directly, 2 direct lighting",
};

/// `rr_depth` of `path` and `bdpt`.
pub(crate) const RR_DEPTH: IntParam = IntParam {
    name: "rr_depth",
    default: 5,
    min: 1,
    max: u32::MAX as i64,
    doc: "depth from which Russian roulette plays (`bdpt`: on the camera subpath; light \
          subpaths play it from their first bounce)",
};

/// `hide_emitters` of every integrator.
pub(crate) const HIDE_EMITTERS: BoolParam = BoolParam {
    name: "hide_emitters",
    default: false,
    doc: "hide emitters seen directly: `path` and `direct` see through emitters and not the \
          sky; `bdpt`, `mlt` and `ptracer` leave out paths of one segment (emitters look black)",
};

/// `samples_per_pass` of `ptracer` (accepted; it only splits Mitsuba's work into passes).
pub(crate) const SAMPLES_PER_PASS: IntParam = IntParam {
    name: "samples_per_pass",
    default: -1,
    min: -1,
    max: i32::MAX as i64,
    doc: "accepted and ignored: Mitsuba splits its work into passes of this many samples per \
          pixel, which changes the noise only",
};

/// `shading_samples` of `direct`.
pub(crate) const SHADING_SAMPLES: IntParam = IntParam {
    name: "shading_samples",
    default: 1,
    min: 0,
    max: MAX_SHADING_SAMPLES as i64,
    doc: "the default of both `emitter_samples` and `bsdf_samples`",
};

/// `emitter_samples` of `direct` (default: `shading_samples`).
pub(crate) const EMITTER_SAMPLES: IntParam = IntParam {
    name: "emitter_samples",
    default: 1,
    min: 0,
    max: MAX_SHADING_SAMPLES as i64,
    doc: "light samples per shading point (default `shading_samples`); not both 0",
};

/// `bsdf_samples` of `direct` (default: `shading_samples`).
pub(crate) const BSDF_SAMPLES: IntParam = IntParam {
    name: "bsdf_samples",
    default: 1,
    min: 0,
    max: MAX_SHADING_SAMPLES as i64,
    doc: "BSDF samples per shading point (default `shading_samples`)",
};

/// `max_depth` of `mlt`.
pub(crate) const MLT_MAX_DEPTH: IntParam = IntParam {
    name: "max_depth",
    default: Mlt::DEFAULT.max_depth as i64,
    min: 1,
    max: MAX_MLT_DEPTH as i64,
    doc: "longest path in segments (each chain keeps one path length)",
};

/// `bootstrap_samples` of `mlt`.
pub(crate) const BOOTSTRAP_SAMPLES: IntParam = IntParam {
    name: "bootstrap_samples",
    default: Mlt::DEFAULT.bootstrap_samples as i64,
    min: 1,
    max: u32::MAX as i64,
    doc: "paths that estimate the image's brightness and seed the chains; at least `chains`",
};

/// `chains` of `mlt`.
pub(crate) const CHAINS: IntParam = IntParam {
    name: "chains",
    default: Mlt::DEFAULT.chains as i64,
    min: 1,
    max: u32::MAX as i64,
    doc: "independent Markov chains",
};

/// `mutations_per_pixel` of `mlt`.
pub(crate) const MUTATIONS_PER_PIXEL: IntParam = IntParam {
    name: "mutations_per_pixel",
    default: Mlt::DEFAULT.mutations_per_pixel as i64,
    min: 1,
    max: SampleCount::MAX as i64,
    doc: "mutations per pixel over all chains; `--spp` overrides it",
};

/// `large_step_prob` of `mlt`.
pub(crate) const LARGE_STEP_PROB: FloatParam<f32> = FloatParam {
    name: "large_step_prob",
    default: Mlt::DEFAULT.large_step_prob,
    range: "(0, 1]",
    accept: |v| in_half_open(v, 0.0, 1.0, "must lie in (0, 1]"),
    doc: "probability of a large step, an independent new path",
};

/// `sigma` of `mlt`.
pub(crate) const SIGMA: FloatParam<f32> = FloatParam {
    name: "sigma",
    default: Mlt::DEFAULT.sigma,
    range: "> 0",
    accept: |v| in_half_open(v, 0.0, f32::MAX, "must be positive and finite"),
    doc: "standard deviation of a small step's perturbation of each primary sample value",
};

/// `guide_probability` of `guided`.
pub(crate) const GUIDE_PROBABILITY: FloatParam<f32> = FloatParam {
    name: "guide_probability",
    default: IntegratorDesc::GUIDED_DEFAULTS.0,
    range: "[0, 0.999]",
    accept: |v| {
        if (0.0..=0.999).contains(&v) {
            Ok(v)
        } else {
            Err("must lie in [0, 0.999] (BSDF sampling keeps a positive share)".into())
        }
    },
    doc: "probability of sampling the learned guide rather than the BSDF at a non-specular vertex",
};

/// `spatial_threshold` of `guided`.
pub(crate) const SPATIAL_THRESHOLD: FloatParam<f32> = FloatParam {
    name: "spatial_threshold",
    default: IntegratorDesc::GUIDED_DEFAULTS.1,
    range: "> 0",
    accept: |v| in_half_open(v, 0.0, f32::MAX, "must be positive and finite"),
    doc: "`c`: a spatial leaf that took more than `c·√(2^k)` records in training pass `k` is           split",
};

/// `directional_threshold` of `guided`.
pub(crate) const DIRECTIONAL_THRESHOLD: FloatParam<f32> = FloatParam {
    name: "directional_threshold",
    default: IntegratorDesc::GUIDED_DEFAULTS.2,
    range: "(0, 1]",
    accept: |v| in_half_open(v, 0.0, 1.0, "must lie in (0, 1]"),
    doc: "ρ: a directional quadrant holding more than this fraction of its leaf's energy is           subdivided",
};

/// `path`.
pub(crate) const PATH: PluginParams = PluginParams {
    category: "integrator",
    plugin: "path",
    params: &[
        ParamDef::Int(&MAX_DEPTH),
        ParamDef::Int(&RR_DEPTH),
        ParamDef::Bool(&HIDE_EMITTERS),
    ],
};

/// `guided`.
pub(crate) const GUIDED: PluginParams = PluginParams {
    category: "integrator",
    plugin: "guided",
    params: &[
        ParamDef::Int(&MAX_DEPTH),
        ParamDef::Int(&RR_DEPTH),
        ParamDef::Float(&GUIDE_PROBABILITY),
        ParamDef::Float(&SPATIAL_THRESHOLD),
        ParamDef::Float(&DIRECTIONAL_THRESHOLD),
    ],
};

/// `direct`.
pub(crate) const DIRECT: PluginParams = PluginParams {
    category: "integrator",
    plugin: "direct",
    params: &[
        ParamDef::Int(&SHADING_SAMPLES),
        ParamDef::Int(&EMITTER_SAMPLES),
        ParamDef::Int(&BSDF_SAMPLES),
        ParamDef::Bool(&HIDE_EMITTERS),
    ],
};

/// `bdpt`.
pub(crate) const BDPT: PluginParams = PluginParams {
    category: "integrator",
    plugin: "bdpt",
    params: &[
        ParamDef::Int(&MAX_DEPTH),
        ParamDef::Int(&RR_DEPTH),
        ParamDef::Bool(&HIDE_EMITTERS),
    ],
};

/// `ptracer`.
pub(crate) const PTRACER: PluginParams = PluginParams {
    category: "integrator",
    plugin: "ptracer",
    params: &[
        ParamDef::Int(&MAX_DEPTH),
        ParamDef::Int(&RR_DEPTH),
        ParamDef::Bool(&HIDE_EMITTERS),
        ParamDef::Int(&SAMPLES_PER_PASS),
    ],
};

/// `mlt`.
pub(crate) const MLT: PluginParams = PluginParams {
    category: "integrator",
    plugin: "mlt",
    params: &[
        ParamDef::Int(&MLT_MAX_DEPTH),
        ParamDef::Int(&BOOTSTRAP_SAMPLES),
        ParamDef::Int(&CHAINS),
        ParamDef::Int(&MUTATIONS_PER_PIXEL),
        ParamDef::Float(&LARGE_STEP_PROB),
        ParamDef::Float(&SIGMA),
        ParamDef::Bool(&HIDE_EMITTERS),
    ],
};

/// The checks between parameters of `direct`: not both sample counts zero.
pub(crate) fn direct_counts(emitter_samples: u32, bsdf_samples: u32) -> Result<(), Invalid> {
    if emitter_samples == 0 && bsdf_samples == 0 {
        return Err(Invalid::new(
            EMITTER_SAMPLES.name,
            "and bsdf_samples cannot both be zero",
        ));
    }
    Ok(())
}

/// The check between parameters of `mlt`: at least as many bootstrap paths as chains.
pub(crate) fn mlt_counts(bootstrap_samples: u32, chains: u32) -> Result<(), Invalid> {
    if bootstrap_samples < chains {
        return Err(Invalid::new(
            BOOTSTRAP_SAMPLES.name,
            "must be at least the number of chains",
        ));
    }
    Ok(())
}

/// Every value of `i` against its definition, and the checks between them.
pub(crate) fn check(i: &IntegratorDesc) -> Result<(), Invalid> {
    match *i {
        IntegratorDesc::Path {
            max_depth,
            rr_depth,
        }
        | IntegratorDesc::Bdpt {
            max_depth,
            rr_depth,
        }
        | IntegratorDesc::Ptracer {
            max_depth,
            rr_depth,
        } => {
            MAX_DEPTH.check(max_depth as i64)?;
            RR_DEPTH.check(rr_depth as i64)?;
        }
        IntegratorDesc::Guided {
            max_depth,
            rr_depth,
            guide_probability,
            spatial_threshold,
            directional_threshold,
        } => {
            MAX_DEPTH.check(max_depth as i64)?;
            RR_DEPTH.check(rr_depth as i64)?;
            GUIDE_PROBABILITY.check(guide_probability)?;
            SPATIAL_THRESHOLD.check(spatial_threshold)?;
            DIRECTIONAL_THRESHOLD.check(directional_threshold)?;
        }
        IntegratorDesc::Direct {
            emitter_samples,
            bsdf_samples,
        } => {
            EMITTER_SAMPLES.check(emitter_samples as i64)?;
            BSDF_SAMPLES.check(bsdf_samples as i64)?;
            direct_counts(emitter_samples, bsdf_samples)?;
        }
        IntegratorDesc::Mlt {
            max_depth,
            bootstrap_samples,
            chains,
            mutations_per_pixel,
            large_step_prob,
            sigma,
        } => {
            MLT_MAX_DEPTH.check(max_depth as i64)?;
            BOOTSTRAP_SAMPLES.check(bootstrap_samples as i64)?;
            CHAINS.check(chains as i64)?;
            MUTATIONS_PER_PIXEL.check(mutations_per_pixel as i64)?;
            LARGE_STEP_PROB.check(large_step_prob)?;
            SIGMA.check(sigma)?;
            mlt_counts(bootstrap_samples, chains)?;
        }
    }
    Ok(())
}
