//! `<emitter>`: `area` (inside a shape), `point`, `spot`, `directional`, `constant` and
//! `envmap`.

use super::context::{Ctx, Res};
use super::props::Props;
use super::spectrum::SpectrumUse;
use super::tree::Elem;
use super::{no_objects, plugin_type, unknown_plugin};
use crate::description::{AreaEmitterDesc, EmitterDesc};
use crate::scene_error::SceneErrorKind;
use crate::validate;
use glam::{Mat4, Vec3};

/// The first bytes of every OpenEXR file.
const EXR_MAGIC: [u8; 4] = [0x76, 0x2f, 0x31, 0x01];

/// Whether the file at `path` starts as a Radiance RGBE image.
fn starts_rgbe(path: &std::path::Path) -> bool {
    let mut head = [0u8; 2];
    crate::io::open_regular(path)
        .and_then(|mut f| std::io::Read::read_exact(&mut f, &mut head))
        .is_ok_and(|_| crate::io::is_rgbe(&head))
}

/// Reads an `<emitter>` nested in a shape: it must be `area`.
pub(crate) fn read_area(ctx: &Ctx, e: &Elem) -> Res<AreaEmitterDesc> {
    let ty = plugin_type(ctx, e)?;
    if ty != "area" {
        let msg = if matches!(ty, "point" | "spot" | "directional" | "constant" | "envmap") {
            format!("a \"{ty}\" emitter inside a <shape> (only \"area\" belongs there)")
        } else {
            return Err(unknown_plugin(ctx, e, ty));
        };
        return Err(ctx.err(e, SceneErrorKind::Misplaced(msg)));
    }
    let mut p = Props::new(ctx, e)?;
    no_objects(ctx, &p)?;
    let radiance = non_negative(e, &mut p, "radiance")?;
    // The power of a unit area (the shape's area multiplies it: `Lights::new` checks that).
    validate::emission_power("radiance", radiance, std::f64::consts::PI)
        .map_err(|i| p.invalid(i.param, e, &i.message))?;
    p.finish()?;
    Ok(AreaEmitterDesc { radiance })
}

/// Reads a top-level `<emitter>`: `point`, `spot`, `directional`, `constant` or `envmap`.
pub(crate) fn read_emitter(ctx: &Ctx, e: &Elem) -> Res<EmitterDesc> {
    let ty = plugin_type(ctx, e)?;
    let mut p = Props::new(ctx, e)?;
    no_objects(ctx, &p)?;
    let desc = match ty {
        "point" => {
            let intensity = non_negative(e, &mut p, "intensity")?;
            let position = match (p.point("position")?, p.transform("to_world")?) {
                (Some(_), Some(_)) => {
                    return Err(p.invalid("position", e, "and to_world cannot both be given"))
                }
                (Some(pos), None) => pos,
                (None, Some(m)) => m.transform_point3(Vec3::ZERO),
                (None, None) => Vec3::ZERO,
            };
            EmitterDesc::Point {
                position,
                intensity,
            }
        }
        "spot" => {
            let intensity = non_negative(e, &mut p, "intensity")?;
            let cutoff_angle = p
                .float("cutoff_angle")?
                .unwrap_or(EmitterDesc::SPOT_CUTOFF_ANGLE);
            // Mitsuba 3's default beam width: three quarters of the cutoff angle.
            let beam_width = p.float("beam_width")?.unwrap_or(0.75 * cutoff_angle);
            EmitterDesc::Spot {
                intensity,
                cutoff_angle,
                beam_width,
                to_world: p.transform("to_world")?.unwrap_or(Mat4::IDENTITY),
            }
        }
        "directional" => {
            let irradiance = non_negative(e, &mut p, "irradiance")?;
            // The light travels along +z of its to_world (Mitsuba 3's `directional`).
            let direction = match (p.point("direction")?, p.transform("to_world")?) {
                (Some(_), Some(_)) => {
                    return Err(p.invalid("direction", e, "and to_world cannot both be given"))
                }
                (Some(d), None) => d,
                (None, Some(m)) => m.transform_vector3(Vec3::Z),
                (None, None) => Vec3::Z,
            };
            let Some(direction) = direction.try_normalize() else {
                return Err(p.invalid("direction", e, "must be a finite, non-zero vector"));
            };
            EmitterDesc::Directional {
                irradiance,
                direction,
            }
        }
        "constant" => EmitterDesc::Constant {
            radiance: non_negative(e, &mut p, "radiance")?,
        },
        "envmap" => {
            let name = p.string("filename")?.ok_or_else(|| {
                ctx.err(
                    e,
                    SceneErrorKind::MissingAttribute("parameter \"filename\"".into()),
                )
            })?;
            // OpenEXR or Radiance RGBE (`.hdr`): the OpenEXR magic is asked for unless the
            // file starts as an RGBE one.
            let rgbe = ctx.readable_file(e, &name, None).is_ok_and(|f| starts_rgbe(&f));
            let filename = ctx.readable_file(e, &name, (!rgbe).then_some(&EXR_MAGIC[..]))?;
            let scale = p.float("scale")?.unwrap_or(1.0);
            EmitterDesc::EnvMap {
                filename,
                scale,
                to_world: p.transform("to_world")?.unwrap_or(Mat4::IDENTITY),
            }
        }
        "area" => {
            return Err(ctx.err(
                e,
                SceneErrorKind::Misplaced("an \"area\" emitter must be inside a <shape>".into()),
            ))
        }
        other => return Err(unknown_plugin(ctx, e, other)),
    };
    validate::emitter(&desc).map_err(|i| p.invalid(i.param, e, &i.message))?;
    p.finish()?;
    Ok(desc)
}

/// An emitted colour with default 1 whose channels must be finite and non-negative (a
/// `<spectrum>` is converted as emission, without the D65 weighting of reflectances).
fn non_negative(e: &Elem, p: &mut Props, name: &'static str) -> Res<Vec3> {
    let v = p.colour(name, SpectrumUse::Emission)?.unwrap_or(Vec3::ONE);
    validate::colour(name, v).map_err(|i| p.invalid(name, e, &i.message))?;
    Ok(v)
}
