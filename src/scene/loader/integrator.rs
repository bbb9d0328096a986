//! `<integrator>`: `path` and `direct`.

use super::context::{Ctx, Res};
use super::error::SceneErrorKind;
use super::props::Props;
use super::tree::Elem;
use super::{no_objects, plugin_type};
use crate::scene::description::IntegratorDesc;

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
            let max = crate::scene::validate::MAX_SHADING_SAMPLES as i64;
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
