//! `<integrator>`: `path`, `direct`, `bdpt` and `mlt`, read through their definitions
//! (`param_defs::integrator`).

use super::context::{Ctx, Res};
use super::props::Props;
use super::tree::Elem;
use super::{no_objects, plugin_type};
use crate::description::IntegratorDesc;
use crate::param_defs::integrator::{
    direct_counts, mlt_counts, BOOTSTRAP_SAMPLES, BSDF_SAMPLES, CHAINS, EMITTER_SAMPLES,
    HIDE_EMITTERS, LARGE_STEP_PROB, MAX_DEPTH, MLT_MAX_DEPTH, MUTATIONS_PER_PIXEL, RR_DEPTH,
    SHADING_SAMPLES, SIGMA,
};
use crate::scene_error::SceneErrorKind;

/// Reads an `<integrator>` element.
pub(crate) fn read_integrator(ctx: &Ctx, e: &Elem) -> Res<IntegratorDesc> {
    let ty = plugin_type(ctx, e)?;
    let mut p = Props::new(ctx, e)?;
    no_objects(ctx, &p)?;
    let desc = match ty {
        "path" => {
            let max_depth = p.get_int(&MAX_DEPTH)? as i32;
            let rr_depth = p.get_int(&RR_DEPTH)? as u32;
            hide_emitters(ctx, e, &mut p)?;
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
            hide_emitters(ctx, e, &mut p)?;
            IntegratorDesc::Direct {
                emitter_samples,
                bsdf_samples,
            }
        }
        "bdpt" => {
            let max_depth = p.get_int(&MAX_DEPTH)? as i32;
            let rr_depth = p.get_int(&RR_DEPTH)? as u32;
            hide_emitters(ctx, e, &mut p)?;
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
            hide_emitters(ctx, e, &mut p)?;
            IntegratorDesc::Mlt {
                max_depth,
                bootstrap_samples,
                chains,
                mutations_per_pixel,
                large_step_prob,
                sigma,
            }
        }
        other => {
            return Err(ctx.err(
                e,
                SceneErrorKind::UnknownPlugin {
                    category: "integrator".into(),
                    plugin_type: other.into(),
                },
            ))
        }
    };
    p.finish()?;
    Ok(desc)
}

/// `hide_emitters = false` is accepted; `true` is not supported.
fn hide_emitters(ctx: &Ctx, e: &Elem, p: &mut Props) -> Res<()> {
    if p.get_bool(&HIDE_EMITTERS)? {
        return Err(ctx.err(
            e,
            SceneErrorKind::Unsupported("hide_emitters = true".into()),
        ));
    }
    Ok(())
}
