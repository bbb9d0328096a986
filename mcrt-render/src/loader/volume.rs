//! `<volume>` (`gridvolume`, `constvolume`) and `<texture type="volume">`: accepted, checked
//! and left out of the scene where they cannot change the image — a `<volume>` declared at
//! the top level, and a volume texture in a material or texture declared at the top level
//! (read there only to check it) — as Mitsuba 3.9.1 loads such a scene and renders it as
//! if they were absent. Where a shape uses a volume texture it is a located error, as is
//! every `<medium>` (this renderer has no 3D textures or participating media).

use super::context::{Ctx, Res};
use super::props::Props;
use super::tree::Elem;
use super::{no_objects, plugin_type, unknown_plugin};
use crate::param_defs::volume::{
    ACCEL, FILENAME, FILTER_TYPE, MAX_VALUE, RAW, TO_WORLD, USE_GRID_BBOX, VALUE, WRAP_MODE,
};
use crate::scene_error::SceneErrorKind;
use crate::texture::{Checkerboard, Texture};

/// Reads and checks a `<volume>` element (Mitsuba 3's `gridvolume` and `constvolume`
/// parameters; a grid's file must exist and start with `VOL`).
pub(crate) fn read_volume(ctx: &Ctx, e: &Elem) -> Res<()> {
    let ty = plugin_type(ctx, e)?;
    let mut p = Props::new(ctx, e)?;
    no_objects(ctx, &p)?;
    match ty {
        "gridvolume" => {
            let Some(name) = p.string(FILENAME.name)? else {
                let what = format!("parameter \"{}\"", FILENAME.name);
                return Err(ctx.err(e, SceneErrorKind::MissingAttribute(what)));
            };
            ctx.readable_file(e, &name, Some((b"VOL", "a Mitsuba volume (.vol)")))?;
            // Compared with case, as Mitsuba 3 does (`Props::get_choice` ignores it).
            for d in [&FILTER_TYPE, &WRAP_MODE] {
                if let Some(v) = p.string(d.name)? {
                    if !d.choices.contains(&v.as_str()) {
                        let m = format!("\"{v}\" is not {}", d.choices.join(" or "));
                        return Err(p.invalid(d.name, e, &m));
                    }
                }
            }
            for d in [&RAW, &ACCEL, &USE_GRID_BBOX] {
                p.get_bool(d)?;
            }
            p.float(MAX_VALUE.name)?;
        }
        "constvolume" => {
            p.rgb(VALUE.name)?;
        }
        other => return Err(unknown_plugin(ctx, e, other)),
    }
    p.transform(TO_WORLD.name)?;
    p.finish()
}

/// A `<texture type="volume">` (Mitsuba 3's adapter from a volume to a surface texture):
/// checked and given a stand-in in a top-level declaration; an error anywhere else.
pub(crate) fn read_volume_texture(ctx: &Ctx, e: &Elem) -> Res<Texture> {
    if !ctx.declaration.get() {
        return Err(ctx.err(
            e,
            SceneErrorKind::Unsupported(
                "texture type \"volume\" (a 3D texture) where a shape uses it (accepted only \
                 in a material or texture that no shape uses)"
                    .into(),
            ),
        ));
    }
    let mut volume = None::<&Elem>;
    for c in &e.children {
        let target = match c.tag.as_str() {
            "volume" => c,
            "ref" => {
                let id = c.attr("id").unwrap_or("");
                match ctx.ids.get(id) {
                    Some(t) if t.tag == "volume" => t,
                    _ => {
                        let m = format!("no <volume> has id \"{id}\"");
                        return Err(ctx.err(c, SceneErrorKind::UndefinedReference(m)));
                    }
                }
            }
            _ => {
                return Err(ctx.err(
                    c,
                    SceneErrorKind::UnknownParameter {
                        plugin: "texture \"volume\"".into(),
                        name: c.attr("name").unwrap_or(&c.tag).into(),
                    },
                ))
            }
        };
        if c.attr("name").is_some_and(|n| n != "volume") || volume.replace(target).is_some() {
            return Err(ctx.err(
                c,
                SceneErrorKind::Misplaced(
                    "a volume texture takes one <volume name=\"volume\">".into(),
                ),
            ));
        }
        read_volume(ctx, target)?;
    }
    // Never rendered: the declaration is read only to check it.
    Ok(Texture::Checkerboard(Checkerboard::default()))
}
