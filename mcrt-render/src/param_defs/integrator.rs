//! The parameters of the integrators `path`, `direct`, `bdpt`, `mlt`, `ptracer` and
//! `guided`: each plugin's list of definitions generates its parameter struct (what
//! [`IntegratorDesc`] holds), its definitions table and its reading ([`plugin_params!`]),
//! and the check of an [`IntegratorDesc`] built in code against them (the loader checks
//! each value as it reads it).

use super::generate::plugin_params;
use super::{in_half_open, non_negative, BoolParam, FloatParam, IntParam};
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
    default: 0.5,
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
    default: 12_000.0,
    range: "> 0",
    accept: |v| in_half_open(v, 0.0, f32::MAX, "must be positive and finite"),
    doc: "`c`: a spatial leaf that took more than `c·√(2^k)` records in training pass `k` is           split",
};

/// `directional_threshold` of `guided`.
pub(crate) const DIRECTIONAL_THRESHOLD: FloatParam<f32> = FloatParam {
    name: "directional_threshold",
    default: 0.01,
    range: "(0, 1]",
    accept: |v| in_half_open(v, 0.0, 1.0, "must lie in (0, 1]"),
    doc: "ρ: a directional quadrant holding more than this fraction of its leaf's energy is subdivided",
};

/// `min_gain` of `guided`.
pub(crate) const MIN_GAIN: FloatParam<f32> = FloatParam {
    name: "min_gain",
    default: 1.6,
    range: "≥ 0",
    accept: |v| non_negative(v, "must be finite and at least 0"),
    doc: "from the third training pass on, the least factor by which the guide must promise to lower the second moment of the directional choices (`SdTree::selection_gain`) for training to go on; below it the rest of the samples are path traced without the guide; 0 always guides",
};

plugin_params! {
    /// The parameters of Mitsuba 3's `path`: unidirectional path tracing with next-event
    /// estimation and MIS.
    pub struct PathParams;
    table PATH = ("integrator", "path");
    {
        /// Longest path in segments: −1 unlimited, 1 emitters seen directly, 2 direct
        /// lighting (default −1).
        max_depth: i32 = Int(MAX_DEPTH),
        /// Depth from which Russian roulette starts (default 5).
        rr_depth: u32 = Int(RR_DEPTH),
        /// Hide emitters seen directly: the camera sees through emitters, and not the sky
        /// (default `false`).
        hide_emitters: bool = Bool(HIDE_EMITTERS),
    }
}

plugin_params! {
    /// The parameters of `guided`: path tracing guided by a learned distribution of
    /// incident radiance.
    pub struct GuidedParams;
    table GUIDED = ("integrator", "guided");
    {
        /// Longest path in segments, as for `path`.
        max_depth: i32 = Int(MAX_DEPTH),
        /// Depth from which Russian roulette starts, as for `path`.
        rr_depth: u32 = Int(RR_DEPTH),
        /// Hide emitters seen directly, as for `path`.
        hide_emitters: bool = Bool(HIDE_EMITTERS),
        /// The probability of sampling the guide rather than the BSDF (default 0.5).
        guide_probability: f32 = Float(GUIDE_PROBABILITY),
        /// `c` of the spatial subdivision threshold `c·√(2^k)` records (default 12000).
        spatial_threshold: f32 = Float(SPATIAL_THRESHOLD),
        /// The energy fraction above which a directional quadrant is subdivided (default
        /// 0.01).
        directional_threshold: f32 = Float(DIRECTIONAL_THRESHOLD),
        /// The least promised gain (`SdTree::selection_gain`) for which training goes on
        /// after the third pass; below it the rest is path traced (default 1.6, about the
        /// guided tracer's cost per sample over the path tracer's; 0 always guides).
        min_gain: f32 = Float(MIN_GAIN),
    }
}

plugin_params! {
    /// The parameters of Mitsuba 3's `direct`: direct lighting with a number of emitter and
    /// BSDF samples.
    pub struct DirectParams;
    table DIRECT = ("integrator", "direct");
    check direct_counts;
    {
        /// The file's default of both sample counts (default 1; read only for them).
        shading_samples: u32 = Int(SHADING_SAMPLES),
        /// Light samples per shading point (default `shading_samples`).
        emitter_samples: u32 = Int(EMITTER_SAMPLES, or shading_samples),
        /// BSDF samples per shading point (default `shading_samples`).
        bsdf_samples: u32 = Int(BSDF_SAMPLES, or shading_samples),
        /// Hide emitters seen directly, as for `path`.
        hide_emitters: bool = Bool(HIDE_EMITTERS),
    }
}

plugin_params! {
    /// The parameters of `bdpt`: bidirectional path tracing (Mitsuba 0.6's and pbrt-v4's).
    pub struct BdptParams;
    table BDPT = ("integrator", "bdpt");
    {
        /// Longest path in segments, as for `path`.
        max_depth: i32 = Int(MAX_DEPTH),
        /// Bounces after which Russian roulette applies on the camera subpath (default 5;
        /// light subpaths play it from their first bounce).
        rr_depth: u32 = Int(RR_DEPTH),
        /// Leave out paths of one segment, so emitters in view look black.
        hide_emitters: bool = Bool(HIDE_EMITTERS),
    }
}

plugin_params! {
    /// The parameters of Mitsuba 3's `ptracer`: particle tracing, i.e. light tracing alone.
    pub struct PtracerParams;
    table PTRACER = ("integrator", "ptracer");
    {
        /// Longest path in segments, as for `path`.
        max_depth: i32 = Int(MAX_DEPTH),
        /// Bounces after which Russian roulette applies (default 5; our light subpaths play
        /// it from their first bounce, which changes the noise only).
        rr_depth: u32 = Int(RR_DEPTH),
        /// Leave out paths of one segment, so emitters in view look black.
        hide_emitters: bool = Bool(HIDE_EMITTERS),
        /// Accepted and ignored (Mitsuba's passes change the noise only; default −1).
        samples_per_pass: i32 = Int(SAMPLES_PER_PASS),
    }
}

plugin_params! {
    /// The parameters of `mlt`: Metropolis light transport in primary sample space over
    /// bidirectional paths (Mitsuba 0.6's `pssmlt` under pbrt-v4's `mlt` names; defaults
    /// the library's [`Mlt::DEFAULT`]).
    pub struct MltParams;
    table MLT = ("integrator", "mlt");
    check mlt_counts;
    {
        /// Longest path in segments, 1..=64 (default 5).
        max_depth: i32 = Int(MLT_MAX_DEPTH),
        /// Paths sampled to estimate the image's brightness and seed the chains (default
        /// 100000).
        bootstrap_samples: u32 = Int(BOOTSTRAP_SAMPLES),
        /// Independent Markov chains (default 1000).
        chains: u32 = Int(CHAINS),
        /// Mutations per pixel over all chains (default 100).
        mutations_per_pixel: u32 = Int(MUTATIONS_PER_PIXEL),
        /// Probability of a large step, an independent new path (default 0.3).
        large_step_prob: f32 = Float(LARGE_STEP_PROB),
        /// Standard deviation of a small step's perturbation of each primary sample value
        /// (default 0.01).
        sigma: f32 = Float(SIGMA),
        /// Leave out paths of one segment, so emitters in view look black.
        hide_emitters: bool = Bool(HIDE_EMITTERS),
    }
}

/// `moment` (Mitsuba 3's): no parameters of its own, one nested `path` or `direct`.
pub(crate) const MOMENT: super::PluginParams = super::PluginParams {
    category: "integrator",
    plugin: "moment",
    params: &[],
};

/// The check between parameters of `direct`: not both sample counts zero.
pub(crate) fn direct_counts(d: &DirectParams) -> Result<(), Invalid> {
    if d.emitter_samples == 0 && d.bsdf_samples == 0 {
        return Err(Invalid::new(
            EMITTER_SAMPLES.name,
            "and bsdf_samples cannot both be zero",
        ));
    }
    Ok(())
}

/// The check between parameters of `mlt`: at least as many bootstrap paths as chains.
pub(crate) fn mlt_counts(m: &MltParams) -> Result<(), Invalid> {
    if m.bootstrap_samples < m.chains {
        return Err(Invalid::new(
            BOOTSTRAP_SAMPLES.name,
            "must be at least the number of chains",
        ));
    }
    Ok(())
}

/// Every value of `i` against its definition, and the checks between them.
pub(crate) fn check(i: &IntegratorDesc) -> Result<(), Invalid> {
    match i {
        IntegratorDesc::Path(p) => p.check(),
        IntegratorDesc::Direct(p) => p.check(),
        IntegratorDesc::Bdpt(p) => p.check(),
        IntegratorDesc::Mlt(p) => p.check(),
        IntegratorDesc::Ptracer(p) => p.check(),
        IntegratorDesc::Guided(p) => p.check(),
    }
}
