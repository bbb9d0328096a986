//! `<shape>`: `rectangle`, `cube`, `disk`, `sphere`, `cylinder` and the mesh files `obj`, `ply` and
//! `serialized`, each with an optional BSDF (or `<ref>`) and an optional `area` emitter.

use super::bsdf::read_bsdf_or_ref;
use super::context::{Ctx, Res};
use super::emitter::read_area;
use super::props::Props;
use super::tree::Elem;
use super::{plugin_type, unknown_plugin};
use crate::description::{BsdfDesc, Checked, Colour, ShapeDesc, ShapeKind};
use crate::param_defs::shape_plugins as defs;
use crate::scene_error::SceneErrorKind;
use crate::validate;
use glam::Vec3;

/// The parameters of a shape read from a mesh file; the file must exist and be readable
/// (its contents are read when the geometry is built).
fn mesh_file<'a>(ctx: &Ctx<'a>, e: &'a Elem, ty: &str, p: &mut Props) -> Res<ShapeKind> {
    let name = p.string(defs::FILENAME.name)?.ok_or_else(|| {
        ctx.err(
            e,
            SceneErrorKind::MissingAttribute("parameter \"filename\"".into()),
        )
    })?;
    let filename = ctx.readable_file(e, &name, None)?;
    let face_normals = p.get_bool(&defs::FACE_NORMALS)?;
    Ok(match ty {
        "obj" => ShapeKind::Obj {
            filename,
            face_normals,
            flip_tex_coords: p.get_bool(&defs::FLIP_TEX_COORDS)?,
        },
        "ply" => ShapeKind::Ply {
            filename,
            face_normals,
        },
        _ => ShapeKind::Serialized {
            filename,
            shape_index: p.get_int(&defs::SHAPE_INDEX)? as u32,
            face_normals,
        },
    })
}

/// Reads a `<shape>` element.
pub(crate) fn read_shape<'a>(ctx: &Ctx<'a>, e: &'a Elem) -> Res<Checked<ShapeDesc>> {
    let ty = plugin_type(ctx, e)?;
    let mut p = Props::new(ctx, e)?;
    let kind = match ty {
        "rectangle" => ShapeKind::Rectangle,
        "cube" => ShapeKind::Cube,
        "disk" => ShapeKind::Disk,
        "sphere" => {
            let center = p.point(defs::CENTER.name)?.unwrap_or(Vec3::ZERO);
            let radius = p.get_float(&defs::SPHERE_RADIUS)?;
            ShapeKind::Sphere { center, radius }
        }
        "cylinder" => {
            // Mitsuba 3's defaults: the unit-radius tube from the origin to (0, 0, 1).
            let p0 = p.point(defs::P0.name)?.unwrap_or(Vec3::ZERO);
            let p1 = p.point(defs::P1.name)?.unwrap_or(Vec3::Z);
            let radius = p.get_float(&defs::CYLINDER_RADIUS)?;
            ShapeKind::Cylinder { p0, p1, radius }
        }
        "obj" | "ply" | "serialized" => mesh_file(ctx, e, ty, &mut p)?,
        "sdfgrid" => {
            let m = "shape \"sdfgrid\" (signed distance fields are not rendered)".to_string();
            return Err(ctx.err(e, SceneErrorKind::Unsupported(m)));
        }
        other => return Err(unknown_plugin(ctx, e, other)),
    };
    let mut shape = ShapeDesc::new(kind);
    shape.id = e.attr("id").map(str::to_string);
    shape.to_world = p.transform(defs::TO_WORLD.name)?.unwrap_or(shape.to_world);
    shape.flip_normals = p.get_bool(&defs::FLIP_NORMALS)?;
    let (mut bsdf, mut emitter, mut emission_texture) = (None, None, None);
    for o in &p.objects {
        // A `<ref>` names a BSDF, or (as Mitsuba 3 allows) an area emitter declared by id.
        let area = (o.tag == "emitter")
            .then_some(*o)
            .or_else(|| referenced_emitter(ctx, o));
        let first = match (area, o.tag.as_str()) {
            (Some(a), _) => {
                let (desc, tex) = read_area(ctx, a)?;
                emission_texture = tex;
                emitter.replace(desc).is_none()
            }
            (None, "bsdf" | "ref") => bsdf.replace(read_bsdf_or_ref(ctx, o)?).is_none(),
            (None, _) => {
                return Err(ctx.err(
                    o,
                    SceneErrorKind::Misplaced(format!("<{}> inside a <shape>", o.tag)),
                ))
            }
        };
        if !first {
            return Err(ctx.err(
                o,
                SceneErrorKind::Misplaced(format!("a second <{}> in the shape", o.tag)),
            ));
        }
    }
    // As in Mitsuba 3: a shape without a BSDF is diffuse 0.5, but an emitting one is black.
    let bsdf = match bsdf {
        Some(b) => b,
        None => validate::bsdf_element(match emitter {
            Some(_) => BsdfDesc::Diffuse {
                reflectance: Colour::BLACK,
            },
            None => BsdfDesc::default(),
        })
        .map_err(|i| p.invalid(i.param, e, &i.message))?,
    };
    shape.emitter = emitter;
    shape.emission_texture = emission_texture;
    // The material was checked where it was read: the shape's own rules only.
    let shape = validate::shape_with(shape, bsdf).map_err(|i| p.invalid(i.param, e, &i.message))?;
    p.finish()?;
    Ok(shape)
}

/// The `<emitter>` a `<ref>` names, if it names one.
fn referenced_emitter<'a>(ctx: &Ctx<'a>, o: &Elem) -> Option<&'a Elem> {
    if o.tag != "ref" {
        return None;
    }
    let target = ctx.ids.get(o.attr("id")?)?;
    (target.tag == "emitter").then_some(*target)
}
