//! The sample count of a render, resolved once: after every override (`--integrator`,
//! `--spp`, `--sampler`) and the sampler's rounding, and only then held to the work limit.

use super::{RenderError, RenderOptions};
use crate::description::{
    Checked, IntegratorDesc, MltParams, SampleCount, SamplerKind, SceneDescription,
};
use mcrt::sampling::sampler::{
    AnySampler, CmjSampler, HaltonSampler, IndependentSampler, R2Sampler, Sampler, Sobol4dSampler,
    SobolSampler, StratifiedSampler,
};
use mcrt::sampling::SamplingError;

/// What a render takes from the scene and the options together.
pub(super) struct Resolved {
    /// The integrator, after `opts.integrator`.
    pub integrator: Checked<IntegratorDesc>,
    /// The sampler's type, after `opts.sampler`.
    pub kind: SamplerKind,
    /// The seed, after `opts.seed`.
    pub seed: u64,
    /// The sample generator.
    pub sampler: AnySampler,
    /// Samples (or MLT mutations) per pixel: `opts.spp`, else the scene's
    /// ([`IntegratorDesc::samples_per_pixel`]), as the sampler rounds it.
    pub spp: SampleCount,
}

/// Resolves the integrator, the sampler and the sample count of rendering `desc` with
/// `opts`, then checks the total work of that render (pixels of `width` × `height`).
///
/// # Errors
/// `opts.spp` (`--spp`) or `mutations_per_pixel` outside 1..=2²⁴, a sampler that cannot be
/// made, or work past [`MAX_WORK`](crate::validate::MAX_WORK).
pub(super) fn resolve(
    desc: &SceneDescription,
    opts: &RenderOptions,
    pixels: u64,
) -> Result<Resolved, RenderError> {
    // The scene's integrator is a checked one; another kind from `opts` is made (and
    // checked) here, from the scene's depths and that kind's defaults.
    let integrator = match opts.integrator {
        Some(kind) => overridden(desc.integrator.with_kind(kind))?,
        None => desc.integrator,
    };
    let invalid = |e: crate::validate::Invalid| RenderError::Invalid(format!("sampler: {e}"));
    // Only `--spp` and `mutations_per_pixel` can be out of range: the file's
    // `sample_count` is a checked `SampleCount`.
    let (param, n) = match opts.spp {
        Some(n) => ("--spp", n),
        None => (
            "mutations_per_pixel",
            integrator.samples_per_pixel(desc.sensor.sampler.sample_count),
        ),
    };
    let requested = SampleCount::named(param, n).map_err(invalid)?;
    let seed = opts.seed.unwrap_or(desc.sensor.sampler.seed);
    let kind = opts.sampler.unwrap_or(desc.sensor.sampler.kind);
    let sampler = make_sampler(kind, requested.get(), seed).map_err(RenderError::Sampler)?;
    // The sampler may round the count up (a square, the square of a prime).
    let spp = SampleCount::named(param, sampler.samples_per_pixel()).map_err(invalid)?;
    crate::validate::work(pixels, spp.get(), &integrator).map_err(invalid)?;
    Ok(Resolved {
        integrator,
        kind,
        seed,
        sampler,
        spp,
    })
}

/// The integrator that `--integrator` makes of the scene's, checked: MLT's depth with its
/// own message (a scene's unlimited depth becomes MLT's default), then every parameter.
fn overridden(integrator: IntegratorDesc) -> Result<Checked<IntegratorDesc>, RenderError> {
    if let IntegratorDesc::Mlt(MltParams { max_depth, .. }) = integrator {
        let most = crate::validate::MAX_MLT_DEPTH;
        if !(1..=most).contains(&max_depth) {
            return Err(RenderError::Invalid(format!(
                "integrator: max_depth {max_depth} (the scene's, carried over to mlt) must \
                 lie in [1, {most}] for mlt: a chain keeps its length, and every length \
                 has its own bootstrap samples and image; lower it in the scene or with -D"
            )));
        }
    }
    Checked::new(integrator).map_err(|e| RenderError::Invalid(format!("integrator: {e}")))
}

/// The sampler for a scene's `sampler` type (see `sampling::sampler` for the mapping of
/// Mitsuba's tags; stratified counts round up to a square; Halton and R2 are ours only).
fn make_sampler(kind: SamplerKind, spp: u32, seed: u64) -> Result<AnySampler, SamplingError> {
    Ok(match kind {
        SamplerKind::Independent => IndependentSampler::new(spp, seed)?.into(),
        SamplerKind::Stratified => StratifiedSampler::new(spp, seed, true)?.into(),
        SamplerKind::LowDiscrepancy => Sobol4dSampler::new(spp, seed)?.into(),
        SamplerKind::Sobol => SobolSampler::new(spp, seed)?.into(),
        SamplerKind::Halton => HaltonSampler::new(spp, seed)?.into(),
        SamplerKind::R2 => R2Sampler::new(spp, seed)?.into(),
        SamplerKind::MultiJitter => CmjSampler::new(spp, seed, true)?.into(),
        SamplerKind::Orthogonal => match AnySampler::by_name("orthogonal", spp, seed) {
            Some(s) => s?,
            None => unreachable!("`orthogonal` is one of AnySampler::NAMES"),
        },
    })
}

#[cfg(test)]
mod tests {
    use super::resolve;
    use crate::description::{IntegratorDesc, IntegratorKind};
    use crate::render::RenderOptions;

    fn error(opts: &RenderOptions, mlt_mutations: Option<u32>) -> String {
        let mut d = crate::cornell_box::cornell_box_with(1, 8, -1);
        if let Some(m) = mlt_mutations {
            let mut mlt = IntegratorDesc::MLT_DEFAULTS;
            if let IntegratorDesc::Mlt(p) = &mut mlt {
                p.mutations_per_pixel = m;
            }
            // A count the integrator's constructor refuses never reaches `resolve`.
            match crate::description::Checked::new(mlt) {
                Ok(mlt) => d.integrator = mlt,
                Err(e) => return e.to_string(),
            }
        }
        match resolve(&d, opts, 8192 * 4096) {
            Ok(r) => panic!("accepted {} spp", r.spp),
            Err(e) => e.to_string(),
        }
    }

    /// The work limit sees the count the render takes: MLT's mutations (the file's
    /// `sample_count` is 1 here), also when `--integrator mlt` brings them in.
    #[test]
    fn the_work_limit_sees_the_resolved_count() {
        let e = error(&RenderOptions::default(), Some(1 << 24));
        assert!(e.contains("exceeds the limit"), "{e}");
        let d = crate::cornell_box::cornell_box_with(1, 8, -1);
        let opts = RenderOptions {
            spp: Some(1 << 24),
            integrator: Some(IntegratorKind::Mlt),
            ..RenderOptions::default()
        };
        assert!(resolve(&d, &opts, 8192 * 4096).is_err());
        let ok = resolve(&d, &RenderOptions::default(), 8192 * 4096).expect("1 spp fits");
        assert_eq!(ok.spp, 1);
    }

    /// `--spp 0` is named as such; so is an MLT count out of range.
    #[test]
    fn an_out_of_range_count_names_where_it_came_from() {
        let opts = RenderOptions {
            spp: Some(0),
            ..RenderOptions::default()
        };
        let e = error(&opts, None);
        assert!(e.contains("\"--spp\" = 0"), "{e}");
        let e = error(&RenderOptions::default(), Some(0));
        assert!(e.contains("mutations_per_pixel"), "{e}");
    }
}
