//! `<integrator>`: `path`, `direct`, `bdpt` and `mlt`.

use super::context::{Ctx, Res};
use super::props::Props;
use super::tree::Elem;
use super::{no_objects, plugin_type};
use crate::description::IntegratorDesc;
use crate::scene_error::SceneErrorKind;

/// Reads an `<integrator>` element.
pub(crate) fn read_integrator(ctx: &Ctx, e: &Elem) -> Res<IntegratorDesc> {
    let ty = plugin_type(ctx, e)?;
    let mut p = Props::new(ctx, e)?;
    no_objects(ctx, &p)?;
    let desc = match ty {
        "path" => {
            let max_depth = p.int_in("max_depth", -1, i32::MAX as i64)?.unwrap_or(-1) as i32;
            let rr_depth = p.int_in("rr_depth", 1, u32::MAX as i64)?.unwrap_or(5) as u32;
            hide_emitters(ctx, e, &mut p)?;
            IntegratorDesc::Path {
                max_depth,
                rr_depth,
            }
        }
        "direct" => {
            let max = crate::validate::MAX_SHADING_SAMPLES as i64;
            let shading = p.int_in("shading_samples", 0, max)?.unwrap_or(1);
            let emitter = p.int_in("emitter_samples", 0, max)?.unwrap_or(shading);
            let bsdf = p.int_in("bsdf_samples", 0, max)?.unwrap_or(shading);
            if emitter == 0 && bsdf == 0 {
                return Err(p.invalid(
                    "emitter_samples",
                    e,
                    "and bsdf_samples cannot both be zero",
                ));
            }
            hide_emitters(ctx, e, &mut p)?;
            IntegratorDesc::Direct {
                emitter_samples: emitter as u32,
                bsdf_samples: bsdf as u32,
            }
        }
        "bdpt" => {
            let max_depth = p.int_in("max_depth", -1, i32::MAX as i64)?.unwrap_or(-1) as i32;
            let rr_depth = p.int_in("rr_depth", 1, u32::MAX as i64)?.unwrap_or(5) as u32;
            hide_emitters(ctx, e, &mut p)?;
            IntegratorDesc::Bdpt {
                max_depth,
                rr_depth,
            }
        }
        "mlt" => {
            let IntegratorDesc::Mlt {
                max_depth: d_depth,
                bootstrap_samples: d_boot,
                chains: d_chains,
                mutations_per_pixel: d_mpp,
                large_step_prob: d_large,
                sigma: d_sigma,
            } = IntegratorDesc::MLT_DEFAULTS
            else {
                unreachable!("MLT_DEFAULTS is an Mlt")
            };
            let max = u32::MAX as i64;
            let max_depth = p
                .int_in("max_depth", 1, crate::validate::MAX_MLT_DEPTH as i64)?
                .unwrap_or(d_depth as i64) as i32;
            let bootstrap_samples = p
                .int_in("bootstrap_samples", 1, max)?
                .unwrap_or(d_boot as i64) as u32;
            let chains = p.int_in("chains", 1, max)?.unwrap_or(d_chains as i64) as u32;
            let mutations_per_pixel = p
                .int_in("mutations_per_pixel", 1, max)?
                .unwrap_or(d_mpp as i64) as u32;
            let large_step_prob = p.float("large_step_prob")?.unwrap_or(d_large);
            if !(large_step_prob > 0.0 && large_step_prob <= 1.0) {
                return Err(p.invalid("large_step_prob", e, "must lie in (0, 1]"));
            }
            let sigma = p.float("sigma")?.unwrap_or(d_sigma);
            if !(sigma > 0.0 && sigma.is_finite()) {
                return Err(p.invalid("sigma", e, "must be positive and finite"));
            }
            if bootstrap_samples < chains {
                return Err(p.invalid(
                    "bootstrap_samples",
                    e,
                    "must be at least the number of chains",
                ));
            }
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
    if p.bool("hide_emitters")? == Some(true) {
        return Err(ctx.err(
            e,
            SceneErrorKind::Unsupported("hide_emitters = true".into()),
        ));
    }
    Ok(())
}
