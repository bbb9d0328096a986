//! `<shape type="shapegroup">` and `<shape type="instance">` (Mitsuba 3's instancing).
//!
//! A shape group holds shapes (inline, or `<ref>`s to shapes declared elsewhere) that are not
//! rendered themselves; an instance names one group by `<ref id>` and places it with its
//! `to_world`. As in Mitsuba 3 (`src/render/shapegroup.cpp`, `src/shapes/instance.cpp`): a
//! group may not hold another group, an instance or a shape with an area emitter; an
//! instance holds exactly one group and nothing else (no BSDF, no emitter, no
//! `flip_normals`); a group's own `to_world` is accepted and ignored. A group is read once,
//! at its first instance or where it is declared, whichever comes first in the file, and
//! shared by its instances.

use super::context::{Ctx, Res};
use super::plugin_type;
use super::props::Props;
use super::shape::read_shape;
use super::tree::Elem;
use crate::description::{Checked, ShapeDesc, ShapeGroupDesc, ShapeKind};
use crate::scene_error::SceneErrorKind;
use std::collections::HashMap;
use std::sync::Arc;

/// The groups read so far in one load, by element.
#[derive(Default)]
pub(crate) struct Groups {
    read: HashMap<*const Elem, Arc<Checked<ShapeGroupDesc>>>,
}

impl Groups {
    /// The group declared by `e`, read on first use.
    fn get(&mut self, ctx: &Ctx, e: &Elem) -> Res<Arc<Checked<ShapeGroupDesc>>> {
        let key = e as *const Elem;
        if let Some(g) = self.read.get(&key) {
            return Ok(Arc::clone(g));
        }
        let g = Arc::new(read_group(ctx, e)?);
        self.read.insert(key, Arc::clone(&g));
        Ok(g)
    }
}

/// A `<shape>` directly inside `<scene>`: a shape group gives `None` (it is read, for its
/// errors, and kept for its instances), anything else its description.
pub(crate) fn read_top_shape<'a>(
    ctx: &Ctx<'a>,
    e: &'a Elem,
    groups: &mut Groups,
) -> Res<Option<Checked<ShapeDesc>>> {
    match e.attr("type") {
        Some("shapegroup") => {
            groups.get(ctx, e)?;
            Ok(None)
        }
        Some("instance") => read_instance(ctx, e, groups).map(Some),
        _ => read_shape(ctx, e).map(Some),
    }
}

/// Whether `e` is a `<shape type="shapegroup">`.
fn is_group(e: &Elem) -> bool {
    e.tag == "shape" && e.attr("type") == Some("shapegroup")
}

/// Reads a `<shape type="shapegroup">`.
fn read_group(ctx: &Ctx, e: &Elem) -> Res<Checked<ShapeGroupDesc>> {
    plugin_type(ctx, e)?;
    let mut p = Props::new(ctx, e)?;
    // Accepted and ignored, as by Mitsuba 3.9.1 (`docs/scene-format.md`).
    p.transform("to_world")?;
    let mut shapes = Vec::with_capacity(p.objects.len());
    for &o in &p.objects {
        let target = match o.tag.as_str() {
            "ref" => follow(ctx, o)?,
            _ => o,
        };
        if target.tag != "shape" {
            return Err(ctx.err(
                o,
                SceneErrorKind::Misplaced(format!(
                    "<{}> inside a shapegroup (a group holds shapes only, as in Mitsuba 3)",
                    target.tag
                )),
            ));
        }
        let nested = match target.attr("type") {
            Some("shapegroup") => Some("a shapegroup inside a shapegroup: nested groups"),
            Some("instance") => Some("an instance inside a shapegroup: nested instancing"),
            _ => None,
        };
        if let Some(what) = nested {
            return Err(ctx.err(
                o,
                SceneErrorKind::Unsupported(format!("{what} are not supported (as in Mitsuba 3)")),
            ));
        }
        let shape = read_shape(ctx, target)?;
        if shape.emitter.is_some() {
            let at = target
                .children
                .iter()
                .find(|c| c.tag == "emitter")
                .unwrap_or(target);
            return Err(ctx.err(
                at,
                SceneErrorKind::Unsupported(
                    "an area emitter on a shape inside a shapegroup: instancing of emitters is \
                     not supported (as in Mitsuba 3)"
                        .into(),
                ),
            ));
        }
        shapes.push(shape);
    }
    p.finish()?;
    // The rules were checked above, each at its element; the group's check repeats them.
    Checked::new(ShapeGroupDesc {
        id: e.attr("id").map(str::to_string),
        shapes,
    })
    .map_err(|i| ctx.err(e, SceneErrorKind::InvalidValue(i.to_string())))
}

/// The element a `<ref id>` names.
fn follow<'a>(ctx: &Ctx<'a>, r: &Elem) -> Res<&'a Elem> {
    super::transform::check_attrs(ctx, r, &["id", "name"], &["id"])?;
    let id = r.attr("id").unwrap_or("");
    ctx.ids.get(id).copied().ok_or_else(|| {
        ctx.err(
            r,
            SceneErrorKind::UndefinedReference(format!("no object has id \"{id}\"")),
        )
    })
}

/// Reads a `<shape type="instance">`.
fn read_instance<'a>(ctx: &Ctx<'a>, e: &'a Elem, groups: &mut Groups) -> Res<Checked<ShapeDesc>> {
    plugin_type(ctx, e)?;
    let mut p = Props::new(ctx, e)?;
    let mut group: Option<(Arc<Checked<ShapeGroupDesc>>, &Elem)> = None;
    for &o in &p.objects {
        let target = match o.tag.as_str() {
            "ref" => follow(ctx, o)?,
            _ if is_group(o) => {
                return Err(ctx.err(
                    o,
                    SceneErrorKind::Misplaced(
                        "a shapegroup declared inside an instance: declare it directly inside \
                         <scene> with an id and name it here with <ref id=\"…\"/>"
                            .into(),
                    ),
                ))
            }
            _ => {
                return Err(ctx.err(
                    o,
                    SceneErrorKind::Misplaced(format!(
                        "<{}> inside an instance: an instance holds only a <ref> to a \
                         shapegroup, whose shapes carry their materials (as in Mitsuba 3)",
                        o.tag
                    )),
                ))
            }
        };
        if !is_group(target) {
            let id = o.attr("id").unwrap_or("");
            return Err(ctx.err(
                o,
                SceneErrorKind::UndefinedReference(format!(
                    "id \"{id}\" names {} (line {}), not a <shape type=\"shapegroup\">",
                    target.describe(),
                    target.line
                )),
            ));
        }
        if let Some((_, first)) = &group {
            return Err(ctx.err(
                o,
                SceneErrorKind::Misplaced(format!(
                    "a second shapegroup in the instance (the first is on line {}; one per \
                     instance, as in Mitsuba 3)",
                    first.line
                )),
            ));
        }
        group = Some((groups.get(ctx, target)?, o));
    }
    let Some((group, _)) = group else {
        return Err(ctx.err(
            e,
            SceneErrorKind::MissingAttribute(
                "<ref id=\"…\"/> naming the instance's shapegroup".into(),
            ),
        ));
    };
    let mut shape = ShapeDesc::new(ShapeKind::Instance(group));
    shape.id = e.attr("id").map(str::to_string);
    shape.to_world = p.transform("to_world")?.unwrap_or(shape.to_world);
    let shape = Checked::new(shape).map_err(|i| p.invalid(i.param, e, &i.message))?;
    p.finish()?;
    Ok(shape)
}
