//! `<bsdf type="normalmap">` and `<bsdf type="bumpmap">`: one nested BSDF seen in a shading
//! frame that a texture perturbs, with Mitsuba 3.9.1's parameters
//! (`param_defs::bsdf_maps`). `normalmap` reads the texture named `normalmap`; `bumpmap`
//! exactly one texture of any name (Mitsuba takes whichever texture is nested).

use super::context::{Ctx, Res};
use super::props::Props;
use super::texture;
use super::tree::Elem;
use crate::description::{BsdfDesc, NormalSource, Perturbation};
use crate::param_defs::bsdf_maps::{
    BUMP_SCALE, FLIP_INVALID_NORMALS, NORMALMAP_TEXTURE, USE_SHADOWING_FUNCTION,
};
use crate::scene_error::SceneErrorKind;
use crate::validate::{self, CheckedBsdf};

/// Reads a `normalmap` or `bumpmap` element `e` (of type `ty`) with parameters `p`, nested
/// `depth` levels deep in other BSDFs.
pub(super) fn read<'a>(
    ctx: &Ctx<'a>,
    e: &'a Elem,
    ty: &str,
    mut p: Props<'_, 'a>,
    depth: u32,
) -> Res<CheckedBsdf> {
    // The nested textures (as written, and the `<texture>` each is or names); the rest must
    // be the one BSDF.
    let (textures, rest): (Vec<&Elem>, Vec<&Elem>) = p
        .objects
        .iter()
        .copied()
        .partition(|o| texture::texture_elem(ctx, o).is_some());
    p.objects = rest;
    for o in textures.iter().filter(|o| o.tag == "ref") {
        super::transform::check_attrs(ctx, o, &["id", "name"], &["id"])?;
    }
    let flip_invalid_normals = p.get_bool(&FLIP_INVALID_NORMALS)?;
    let use_shadowing_function = p.get_bool(&USE_SHADOWING_FUNCTION)?;
    let (texture_elem, source) = if ty == "normalmap" {
        let name = NORMALMAP_TEXTURE.name;
        if let Some((_, el)) = p.raw(name) {
            return Err(p.wrong(el, name, "a <texture> (a bitmap) or a <ref> to one"));
        }
        if let Some(o) = textures.iter().find(|o| o.attr("name") != Some(name)) {
            return Err(ctx.err(
                o,
                SceneErrorKind::Unsupported(format!(
                    "a texture named \"{}\" in a normalmap (its texture is named \"{name}\")",
                    o.attr("name").unwrap_or("")
                )),
            ));
        }
        let o = exactly_one(ctx, e, ty, &textures, "a texture named \"normalmap\"")?;
        (o, NormalSource::NormalMap(map_texture(ctx, o)?))
    } else {
        let scale = p.get_float(&BUMP_SCALE)?;
        let o = exactly_one(ctx, e, ty, &textures, "one texture (the height field)")?;
        let height = map_texture(ctx, o)?;
        (o, NormalSource::BumpMap { height, scale })
    };
    let [inner] = super::bsdf::nested::<1>(ctx, e, p, depth)?;
    let desc = BsdfDesc::Perturbed {
        perturbation: Perturbation {
            source,
            flip_invalid_normals,
            use_shadowing_function,
        },
        inner: Box::new(inner.into_inner()),
    };
    validate::bsdf_element(desc).map_err(|i| {
        // The texture's own faults at the texture, the rest at the element.
        let at = if matches!(i.param, "normalmap" | "texture") {
            texture_elem
        } else {
            e
        };
        ctx.err(at, SceneErrorKind::InvalidValue(i.to_string()))
    })
}

/// The texture a nested object is or names.
fn map_texture(ctx: &Ctx, o: &Elem) -> Res<crate::texture::Texture> {
    let target = texture::texture_elem(ctx, o).unwrap_or(o);
    texture::read_texture(ctx, target)
}

/// The only element of `textures`: none, or more than one, is an error naming `what`.
fn exactly_one<'a>(
    ctx: &Ctx,
    e: &Elem,
    ty: &str,
    textures: &[&'a Elem],
    what: &str,
) -> Res<&'a Elem> {
    match textures {
        [o] => Ok(o),
        [] => Err(ctx.err(
            e,
            SceneErrorKind::InvalidValue(format!("{ty} needs {what}, found none")),
        )),
        [_, second, ..] => Err(ctx.err(
            second,
            SceneErrorKind::Unsupported(format!(
                "a second texture in a {ty} (it takes {what}, as Mitsuba 3)"
            )),
        )),
    }
}
