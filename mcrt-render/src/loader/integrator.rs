//! `<integrator>`: `path`, `direct`, `bdpt`, `mlt`, `ptracer` and `guided`, read through their
//! definitions (`param_defs::integrator`), and `moment` around `path` or `direct`.

use super::context::{Ctx, Res};
use super::props::Props;
use super::tree::Elem;
use super::{no_objects, plugin_type};
use crate::description::{IntegratorDesc, MomentDesc};
use crate::param_defs::integrator::{
    direct_counts, mlt_counts, BOOTSTRAP_SAMPLES, BSDF_SAMPLES, CHAINS, DIRECTIONAL_THRESHOLD,
    EMITTER_SAMPLES, GUIDE_PROBABILITY, HIDE_EMITTERS, LARGE_STEP_PROB, MAX_DEPTH, MLT_MAX_DEPTH,
    MUTATIONS_PER_PIXEL, RR_DEPTH, SAMPLES_PER_PASS, SHADING_SAMPLES, SIGMA, SPATIAL_THRESHOLD,
};
use crate::scene_error::SceneErrorKind;

/// What an `<integrator>` element says.
pub(crate) struct ReadIntegrator {
    pub integrator: IntegratorDesc,
    pub hide_emitters: bool,
    pub moment: Option<MomentDesc>,
}

/// The integrator types that read their own parameters.
const PLAIN: &[&str] = &["path", "direct", "bdpt", "mlt", "ptracer", "guided"];

/// The name Mitsuba 3 gives the first nested object that has no `name` attribute.
const FIRST_UNNAMED: &str = "_arg_0";

/// Reads an `<integrator>` element: a plain integrator, or `moment` around one.
pub(crate) fn read_integrator(ctx: &Ctx, e: &Elem) -> Res<ReadIntegrator> {
    let ty = plugin_type(ctx, e)?;
    match ty {
        "moment" => read_moment(ctx, e),
        // Mitsuba 3's other integrators that wrap one: named, with what we do support.
        "aov" | "stokes" => Err(ctx.err(
            e,
            SceneErrorKind::Unsupported(format!(
                "integrator \"{ty}\" (of the integrators that wrap another, only \"moment\" \
                 is supported)"
            )),
        )),
        _ => read_plain(ctx, e, ty).map(|(integrator, hide_emitters)| ReadIntegrator {
            integrator,
            hide_emitters,
            moment: None,
        }),
    }
}

/// `moment`: exactly one nested `path` or `direct`, whose image it keeps; the mean and second
/// moment channels are added when the film is written. Several nested integrators (Mitsuba
/// 3 runs each on the same camera ray, one after the other on one sampler stream, and keeps
/// the first one's image) are refused at the second: the render loop runs one estimator per
/// sample (docs/scene-format.md, "The `moment` integrator around another").
fn read_moment(ctx: &Ctx, e: &Elem) -> Res<ReadIntegrator> {
    let p = Props::new(ctx, e)?;
    let objects = p.objects.clone();
    let mut nested = objects.iter().copied();
    let (Some(inner), None) = (nested.next(), nested.next()) else {
        let (at, what) = match objects.get(1) {
            Some(second) => (
                *second,
                "; several, which Mitsuba 3 runs one after the other on each camera ray, are \
                 not supported (the render loop runs one estimator per sample)",
            ),
            None => (e, ""),
        };
        return Err(ctx.err(
            at,
            SceneErrorKind::Unsupported(format!(
                "integrator \"moment\" needs exactly one nested <integrator>{what}"
            )),
        ));
    };
    if inner.tag != "integrator" {
        return Err(ctx.err(
            inner,
            SceneErrorKind::Misplaced(format!(
                "<{}> cannot be nested in integrator \"moment\"",
                inner.tag
            )),
        ));
    }
    let inner_ty = plugin_type(ctx, inner)?;
    if !matches!(inner_ty, "path" | "direct") {
        return Err(ctx.err(
            inner,
            SceneErrorKind::Unsupported(format!(
                "integrator \"{inner_ty}\" inside \"moment\" (only \"path\" and \"direct\", \
                 which sample per pixel)"
            )),
        ));
    }
    let (integrator, hide_emitters) = read_plain(ctx, inner, inner_ty)?;
    p.finish()?;
    let name = inner.attr("name").unwrap_or(FIRST_UNNAMED).to_string();
    Ok(ReadIntegrator {
        integrator,
        hide_emitters,
        moment: Some(MomentDesc { name }),
    })
}

/// One of the [`PLAIN`] integrators, and its `hide_emitters`.
fn read_plain(ctx: &Ctx, e: &Elem, ty: &str) -> Res<(IntegratorDesc, bool)> {
    // Before the nested objects are looked at, so that the error names this element.
    if !PLAIN.contains(&ty) {
        return Err(unknown(ctx, e, ty));
    }
    let mut p = Props::new(ctx, e)?;
    no_objects(ctx, &p)?;
    let desc = match ty {
        "path" => {
            let max_depth = p.get_int(&MAX_DEPTH)? as i32;
            let rr_depth = p.get_int(&RR_DEPTH)? as u32;
            IntegratorDesc::Path {
                max_depth,
                rr_depth,
            }
        }
        "direct" => {
            let shading = p.get_int(&SHADING_SAMPLES)?;
            let emitter_samples = p.get_int_or(&EMITTER_SAMPLES, shading)? as u32;
            let bsdf_samples = p.get_int_or(&BSDF_SAMPLES, shading)? as u32;
            direct_counts(emitter_samples, bsdf_samples)
                .map_err(|i| p.invalid(i.param, e, &i.message))?;
            IntegratorDesc::Direct {
                emitter_samples,
                bsdf_samples,
            }
        }
        "bdpt" => {
            let max_depth = p.get_int(&MAX_DEPTH)? as i32;
            let rr_depth = p.get_int(&RR_DEPTH)? as u32;
            IntegratorDesc::Bdpt {
                max_depth,
                rr_depth,
            }
        }
        "mlt" => {
            let max_depth = p.get_int(&MLT_MAX_DEPTH)? as i32;
            let bootstrap_samples = p.get_int(&BOOTSTRAP_SAMPLES)? as u32;
            let chains = p.get_int(&CHAINS)? as u32;
            let mutations_per_pixel = p.get_int(&MUTATIONS_PER_PIXEL)? as u32;
            let large_step_prob = p.get_float(&LARGE_STEP_PROB)?;
            let sigma = p.get_float(&SIGMA)?;
            mlt_counts(bootstrap_samples, chains).map_err(|i| p.invalid(i.param, e, &i.message))?;
            IntegratorDesc::Mlt {
                max_depth,
                bootstrap_samples,
                chains,
                mutations_per_pixel,
                large_step_prob,
                sigma,
            }
        }
        "ptracer" => {
            let max_depth = p.get_int(&MAX_DEPTH)? as i32;
            let rr_depth = p.get_int(&RR_DEPTH)? as u32;
            p.get_int(&SAMPLES_PER_PASS)?;
            IntegratorDesc::Ptracer {
                max_depth,
                rr_depth,
            }
        }
        "guided" => {
            let max_depth = p.get_int(&MAX_DEPTH)? as i32;
            let rr_depth = p.get_int(&RR_DEPTH)? as u32;
            IntegratorDesc::Guided {
                max_depth,
                rr_depth,
                guide_probability: p.get_float(&GUIDE_PROBABILITY)?,
                spatial_threshold: p.get_float(&SPATIAL_THRESHOLD)?,
                directional_threshold: p.get_float(&DIRECTIONAL_THRESHOLD)?,
            }
        }
        other => return Err(unknown(ctx, e, other)),
    };
    // `guided` has no `hide_emitters` (left unread, it is reported as unknown).
    let hide_emitters = if ty == "guided" {
        false
    } else {
        p.get_bool(&HIDE_EMITTERS)?
    };
    p.finish()?;
    Ok((desc, hide_emitters))
}

fn unknown(ctx: &Ctx, e: &Elem, ty: &str) -> super::SceneError {
    ctx.err(
        e,
        SceneErrorKind::UnknownPlugin {
            category: "integrator".into(),
            plugin_type: ty.into(),
        },
    )
}
