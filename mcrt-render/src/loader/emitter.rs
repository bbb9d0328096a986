//! `<emitter>`: `area` (inside a shape), `point`, `spot`, `directional`, `constant` and
//! `envmap`.

use super::context::{Ctx, Res};
use super::props::Props;
use super::spectrum::SpectrumUse;
use super::tree::Elem;
use super::{no_objects, plugin_type, texture, unknown_plugin};
use crate::description::{AreaEmitterDesc, Checked, Colour, EmitterDesc};
use crate::param_defs::emitter as defs;
use crate::scene_error::SceneErrorKind;
use crate::texture::Texture;
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

/// Takes the texture named `name` (nested, or `<ref name="…" id="…"/>`) out of `p`'s nested
/// objects; any other nested object is an error, as is the parameter given twice.
fn take_texture<'a>(ctx: &Ctx<'a>, p: &mut Props<'_, 'a>, name: &str) -> Res<Option<Texture>> {
    let mut found = None;
    let mut rest = Vec::new();
    for &o in &p.objects {
        let target = texture::texture_elem(ctx, o);
        match target {
            Some(t) if o.attr("name") == Some(name) => {
                if found.is_some() || p.has(name) {
                    return Err(ctx.err(o, SceneErrorKind::DuplicateParameter(name.into())));
                }
                if o.tag == "ref" {
                    super::transform::check_attrs(ctx, o, &["id", "name"], &["id"])?;
                }
                found = Some(texture::read_texture(ctx, t)?);
            }
            _ => rest.push(o),
        }
    }
    p.objects = rest;
    no_objects(ctx, p)?;
    Ok(found)
}

/// Reads an `<emitter>` nested in a shape: it must be `area`; its `radiance` may be a
/// texture (returned beside it; the description's radiance is then the texture's mean).
pub(crate) fn read_area(ctx: &Ctx, e: &Elem) -> Res<(AreaEmitterDesc, Option<Texture>)> {
    let ty = plugin_type(ctx, e)?;
    if ty != "area" {
        let msg = if matches!(
            ty,
            "point" | "spot" | "directional" | "constant" | "envmap" | "projector"
        ) {
            format!("a \"{ty}\" emitter inside a <shape> (only \"area\" belongs there)")
        } else {
            return Err(unknown_plugin(ctx, e, ty));
        };
        return Err(ctx.err(e, SceneErrorKind::Misplaced(msg)));
    }
    let mut p = Props::new(ctx, e)?;
    let tex = take_texture(ctx, &mut p, defs::AREA_RADIANCE.name)?;
    let radiance = match &tex {
        Some(t) => {
            let name = defs::AREA_RADIANCE.name;
            Colour::named(name, texture::stand_in(t)).map_err(|i| p.invalid(name, e, &i.message))?
        }
        None => non_negative(e, &mut p, defs::AREA_RADIANCE.name)?,
    };
    // The power of a unit area (the shape's area multiplies it: `Lights::new` checks that).
    validate::emission_power("radiance", radiance.get(), std::f64::consts::PI)
        .map_err(|i| p.invalid(i.param, e, &i.message))?;
    p.finish()?;
    Ok((AreaEmitterDesc { radiance }, tex))
}

/// Reads a top-level `<emitter>`: `point`, `spot`, `directional`, `constant` or `envmap`.
pub(crate) fn read_emitter(ctx: &Ctx, e: &Elem) -> Res<Checked<EmitterDesc>> {
    let ty = plugin_type(ctx, e)?;
    let mut p = Props::new(ctx, e)?;
    // The textures a spot (`texture`) and a projector (`irradiance`) take.
    let tex = match ty {
        "spot" => take_texture(ctx, &mut p, defs::SPOT_TEXTURE.name)?,
        "projector" => take_texture(ctx, &mut p, defs::PROJECTOR_IRRADIANCE.name)?,
        _ => {
            no_objects(ctx, &p)?;
            None
        }
    };
    let desc = match ty {
        "point" => {
            let intensity = non_negative(e, &mut p, defs::INTENSITY.name)?;
            let position = match (
                p.point(defs::POSITION.name)?,
                p.transform(defs::POINT_TO_WORLD.name)?,
            ) {
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
            let intensity = non_negative(e, &mut p, defs::INTENSITY.name)?;
            let cutoff_angle = p.get_float(&defs::CUTOFF_ANGLE)?;
            // Mitsuba 3's default beam width: three quarters of the cutoff angle.
            let beam_width = p
                .get_float_opt(&defs::BEAM_WIDTH)?
                .unwrap_or(0.75 * cutoff_angle);
            let spot = EmitterDesc::Spot {
                intensity,
                cutoff_angle,
                beam_width,
                to_world: p
                    .transform(defs::CONE_TO_WORLD.name)?
                    .unwrap_or(Mat4::IDENTITY),
            };
            match tex {
                Some(texture) => EmitterDesc::Textured {
                    inner: Box::new(spot),
                    texture,
                },
                None => spot,
            }
        }
        "projector" => read_projector(ctx, e, &mut p, tex)?,
        "directional" => {
            let irradiance = non_negative(e, &mut p, defs::IRRADIANCE.name)?;
            // The light travels along +z of its to_world (Mitsuba 3's `directional`).
            let direction = match (
                p.point(defs::DIRECTION.name)?,
                p.transform(defs::DIRECTIONAL_TO_WORLD.name)?,
            ) {
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
            radiance: non_negative(e, &mut p, defs::RADIANCE.name)?,
        },
        "envmap" => {
            let name = p.string(defs::ENVMAP_FILENAME.name)?.ok_or_else(|| {
                ctx.err(
                    e,
                    SceneErrorKind::MissingAttribute("parameter \"filename\"".into()),
                )
            })?;
            // OpenEXR or Radiance RGBE (`.hdr`): the OpenEXR magic is asked for unless the
            // file starts as an RGBE one.
            let rgbe = ctx
                .readable_file(e, &name, None)
                .is_ok_and(|f| starts_rgbe(&f));
            let filename =
                ctx.readable_file(e, &name, (!rgbe).then_some((&EXR_MAGIC[..], "an OpenEXR")))?;
            let scale = p.get_float(&defs::SCALE)?;
            EmitterDesc::EnvMap {
                filename,
                scale,
                to_world: p
                    .transform(defs::ENVMAP_TO_WORLD.name)?
                    .unwrap_or(Mat4::IDENTITY),
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
    let desc = Checked::new(desc).map_err(|i| p.invalid(i.param, e, &i.message))?;
    p.finish()?;
    Ok(desc)
}

/// A `projector`: its `irradiance` a texture (`tex`) or a colour (a one-pixel image), `fov`
/// along `fov_axis` (`x`, `y`, `smaller`, `larger` or `diagonal`, converted to the image
/// width's as Mitsuba's cameras convert it).
fn read_projector(ctx: &Ctx, e: &Elem, p: &mut Props, tex: Option<Texture>) -> Res<EmitterDesc> {
    let irradiance = match tex {
        Some(t) => t,
        None => {
            let c = non_negative(e, p, defs::PROJECTOR_IRRADIANCE.name)?;
            let image = crate::texture::Image::new(1, 1, vec![c.get()])
                .ok_or_else(|| p.invalid(defs::PROJECTOR_IRRADIANCE.name, e, "unusable"))?;
            Texture::Bitmap(crate::texture::Bitmap {
                image: std::sync::Arc::new(image),
                filter: crate::texture::FilterType::Nearest,
                wrap: crate::texture::WrapMode::Clamp,
                to_uv: glam::Affine2::IDENTITY,
            })
        }
    };
    let aspect = f64::from(crate::light::texture_aspect(&irradiance));
    if p.has(defs::PROJECTOR_FOCAL_LENGTH.name) {
        return Err(ctx.err(
            e,
            SceneErrorKind::Unsupported(
                "\"focal_length\" on a projector (not supported yet: give \"fov\")".into(),
            ),
        ));
    }
    let Some(fov) = p.get_float_opt(&defs::PROJECTOR_FOV)? else {
        return Err(ctx.err(
            e,
            SceneErrorKind::MissingAttribute("parameter \"fov\" (of the projector)".into()),
        ));
    };
    let axis = p
        .string(defs::PROJECTOR_FOV_AXIS.name)?
        .unwrap_or_else(|| defs::PROJECTOR_FOV_AXIS.default.into());
    let half_tan = (0.5 * f64::from(fov).to_radians()).tan();
    // Mitsuba 3's `parse_fov`: every axis converted to the width's.
    let x_half_tan = match axis.to_ascii_lowercase().as_str() {
        "x" => half_tan,
        "y" => half_tan * aspect,
        "smaller" if aspect > 1.0 => half_tan * aspect,
        "smaller" => half_tan,
        "larger" if aspect > 1.0 => half_tan,
        "larger" => half_tan * aspect,
        "diagonal" => half_tan / (1.0 + 1.0 / (aspect * aspect)).sqrt(),
        other => {
            return Err(p.invalid(
                defs::PROJECTOR_FOV_AXIS.name,
                e,
                &format!("\"{other}\" is not x, y, smaller, larger or diagonal"),
            ))
        }
    };
    Ok(EmitterDesc::Projector {
        irradiance,
        scale: p.get_float(&defs::SCALE)?,
        x_fov: (2.0 * x_half_tan.atan()).to_degrees() as f32,
        to_world: p
            .transform(defs::CONE_TO_WORLD.name)?
            .unwrap_or(Mat4::IDENTITY),
    })
}

/// An emitted colour with default 1, checked into a [`Colour`] (a `<spectrum>` is converted
/// as emission, without the D65 weighting of reflectances).
fn non_negative(e: &Elem, p: &mut Props, name: &'static str) -> Res<Colour> {
    let v = p.colour(name, SpectrumUse::Emission)?.unwrap_or(Vec3::ONE);
    Colour::named(name, v).map_err(|i| p.invalid(name, e, &i.message))
}
