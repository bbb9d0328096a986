//! `<texture>`: `bitmap` and `checkerboard`, declared at top level or inside a BSDF, and
//! the textures a BSDF's parameters name (nested, or `<ref name="…" id="…"/>`).

use super::context::{Ctx, Res};
use super::props::Props;
use super::tree::Elem;
use super::{no_objects, plugin_type, unknown_plugin};
use crate::description::{BsdfDesc, Colour, Roughness};
use crate::param_defs::texture as defs;
use crate::scene_error::SceneErrorKind;
use crate::texture::{
    read_image_beside, uv_transform, Bitmap, Checkerboard, FilterType, Texture, TextureParam,
    WrapMode,
};
use glam::{Affine2, Vec3};
use std::sync::Arc;

/// Reads a `<texture>` element.
pub(crate) fn read_texture(ctx: &Ctx, e: &Elem) -> Res<Texture> {
    let ty = plugin_type(ctx, e)?;
    if ty == "volume" {
        return super::volume::read_volume_texture(ctx, e);
    }
    let mut p = Props::new(ctx, e)?;
    no_objects(ctx, &p)?;
    let to_uv = match p.transform(defs::TO_UV.name)? {
        Some(m) => uv_transform(&m),
        None => Affine2::IDENTITY,
    };
    let texture = match ty {
        "bitmap" => {
            let Some(name) = p.string(defs::FILENAME.name)? else {
                return Err(ctx.err(
                    e,
                    SceneErrorKind::InvalidValue("bitmap needs a \"filename\"".into()),
                ));
            };
            let raw = p.get_bool(&defs::RAW)?;
            let filter = match p.string(defs::FILTER_TYPE.name)? {
                None => FilterType::default(),
                Some(s) => FilterType::parse(&s).ok_or_else(|| {
                    p.invalid(
                        "filter_type",
                        e,
                        &format!("\"{s}\" is not bilinear or nearest"),
                    )
                })?,
            };
            let wrap = match p.string(defs::WRAP_MODE.name)? {
                None => WrapMode::default(),
                Some(s) => WrapMode::parse(&s).ok_or_else(|| {
                    p.invalid(
                        "wrap_mode",
                        e,
                        &format!("\"{s}\" is not repeat, mirror or clamp"),
                    )
                })?,
            };
            let path = ctx.readable_file(e, &name, None)?;
            let image = match ctx.cached_image(&path, raw) {
                Some(image) => image,
                None => {
                    let used = ctx.image_bytes();
                    let image = read_image_beside(&path, raw, used).map_err(|reason| {
                        // The budget's message is ours and says how to raise it: not clipped.
                        let kind = if reason.contains("--max-memory") {
                            SceneErrorKind::Memory(format!("{}: {reason}", path.display()))
                        } else {
                            SceneErrorKind::Io {
                                path: path.clone(),
                                reason,
                            }
                        };
                        ctx.err(e, kind)
                    })?;
                    ctx.cache_image(&path, raw, Arc::new(image))
                }
            };
            Texture::Bitmap(Bitmap {
                image,
                filter,
                wrap,
                to_uv,
            })
        }
        "checkerboard" => Texture::Checkerboard(Checkerboard {
            // Any finite colour, negative ones too (as Mitsuba 3 takes them).
            color0: p
                .rgb(defs::COLOR0.name)?
                .unwrap_or(Vec3::splat(defs::COLOR0.default)),
            color1: p
                .rgb(defs::COLOR1.name)?
                .unwrap_or(Vec3::splat(defs::COLOR1.default)),
            to_uv,
        }),
        other => return Err(unknown_plugin(ctx, e, other)),
    };
    if let Texture::Checkerboard(c) = &texture {
        for (name, v) in [("color0", c.color0), ("color1", c.color1)] {
            if !v.is_finite() {
                return Err(p.invalid(name, e, "must be finite"));
            }
        }
    }
    if !to_uv.is_finite() {
        return Err(p.invalid("to_uv", e, "must be finite"));
    }
    p.finish()?;
    Ok(texture)
}

/// The `<texture>` element `e` is, or that the `<ref>` `e` names; `None` for anything else
/// (a `<bsdf>`, or a `<ref>` to one).
pub(crate) fn texture_elem<'a>(ctx: &Ctx<'a>, e: &'a Elem) -> Option<&'a Elem> {
    match e.tag.as_str() {
        "texture" => Some(e),
        "ref" => ctx
            .ids
            .get(e.attr("id").unwrap_or(""))
            .copied()
            .filter(|t| t.tag == "texture"),
        _ => None,
    }
}

/// Takes the textures out of a BSDF's nested objects: each must carry the `name` of the
/// parameter it drives, one that plugin `ty` has and that is given once.
pub(crate) fn take_textures<'a>(
    ctx: &Ctx<'a>,
    ty: &str,
    p: &mut Props<'_, 'a>,
) -> Res<Vec<(TextureParam, Texture, &'a Elem)>> {
    let mut out: Vec<(TextureParam, Texture, &'a Elem)> = Vec::new();
    let mut rest = Vec::new();
    for &o in &p.objects {
        let id = o.attr("id").unwrap_or("");
        if o.tag == "ref" && !ctx.ids.contains_key(id) {
            return Err(ctx.err(
                o,
                SceneErrorKind::UndefinedReference(format!("no object has id \"{id}\"")),
            ));
        }
        let Some(target) = texture_elem(ctx, o) else {
            rest.push(o);
            continue;
        };
        let Some(name) = o.attr("name") else {
            return Err(ctx.err(
                o,
                SceneErrorKind::MissingAttribute(
                    "name (the parameter a texture inside a BSDF drives)".into(),
                ),
            ));
        };
        let Some(param) = TextureParam::ALL.into_iter().find(|q| q.name() == name) else {
            return Err(ctx.err(
                o,
                SceneErrorKind::Unsupported(format!(
                    "a texture for \"{name}\" of bsdf \"{ty}\" (textures drive reflectance, \
                     diffuse_reflectance, specular_reflectance, specular_transmittance, \
                     principled's base_color, blendbsdf's weight and mask's opacity)"
                )),
            ));
        };
        if p.has(name) || out.iter().any(|(q, _, _)| *q == param) {
            return Err(ctx.err(o, SceneErrorKind::DuplicateParameter(name.into())));
        }
        if o.tag == "ref" {
            super::transform::check_attrs(ctx, o, &["id", "name"], &["id"])?;
        }
        out.push((param, read_texture(ctx, target)?, o));
    }
    p.objects = rest;
    Ok(out)
}

/// The constant that stands for a texture in a material's description: its mean (grey).
pub(crate) fn stand_in(t: &Texture) -> Vec3 {
    Vec3::splat(t.mean())
}

/// The error for a texture in a place that takes none.
pub(crate) fn not_here(ctx: &Ctx, o: &Elem) -> crate::scene_error::SceneError {
    let what = match o.attr("name") {
        Some(n) => format!("a texture for \"{n}\""),
        None => "a texture".into(),
    };
    ctx.err(
        o,
        SceneErrorKind::Unsupported(format!(
            "{what} here (textures drive BSDF colours, blendbsdf's weight and mask's \
             opacity; emitters and textures' own colours take constants)"
        )),
    )
}

/// `desc` with `textures` attached: each must be a parameter of the plugin (`e`, of type
/// `ty`); colour parameters take the texture's mean as their stand-in (blend weights and
/// opacities took theirs when they were read), which must be a valid [`Colour`].
pub(crate) fn attach(
    ctx: &Ctx,
    e: &Elem,
    ty: &str,
    mut desc: BsdfDesc,
    textures: Vec<(TextureParam, Texture, &Elem)>,
) -> Res<BsdfDesc> {
    if textures.is_empty() {
        return Ok(desc);
    }
    for (param, texture, o) in &textures {
        if !desc.has_param(*param) {
            return Err(ctx.err(
                o,
                SceneErrorKind::UnknownParameter {
                    plugin: format!("bsdf \"{ty}\""),
                    name: param.name().into(),
                },
            ));
        }
        match colour_mut(&mut desc, *param) {
            Some(Slot::Checked(slot)) => {
                *slot = Colour::named(param.name(), stand_in(texture))
                    .map_err(|i| ctx.err(e, SceneErrorKind::InvalidValue(i.to_string())))?;
            }
            Some(Slot::Plain(slot)) => *slot = stand_in(texture),
            None if param.is_roughness() => {
                roughness_stand_in(&mut desc, *param, texture.mean());
            }
            None => {}
        }
    }
    Ok(BsdfDesc::Textured {
        inner: Box::new(desc),
        textures: textures.into_iter().map(|(p, t, _)| (p, t)).collect(),
    })
}

/// Puts a roughness texture's mean (limited to [`Roughness`]'s range) in the roughness `p`
/// of a rough conductor or dielectric (`alpha`: both αᵤ and αᵥ).
fn roughness_stand_in(desc: &mut BsdfDesc, p: TextureParam, mean: f32) {
    let (BsdfDesc::RoughConductor { microfacet, .. }
    | BsdfDesc::RoughDielectric { microfacet, .. }) = desc
    else {
        return;
    };
    let a = Roughness::new(mean.clamp(Roughness::MIN, Roughness::MAX)).unwrap_or_default();
    match p {
        TextureParam::AlphaU => microfacet.alpha = a,
        TextureParam::AlphaV => microfacet.alpha_v = a,
        _ => (microfacet.alpha, microfacet.alpha_v) = (a, a),
    }
}

/// Where a colour parameter of a description lives: a checked [`Colour`], or the plain
/// base colour of `principled` (checked with its other parameters).
enum Slot<'a> {
    Checked(&'a mut Colour),
    Plain(&'a mut Vec3),
}

/// The colour parameter `p` of a material description.
fn colour_mut(desc: &mut BsdfDesc, p: TextureParam) -> Option<Slot<'_>> {
    use TextureParam as P;
    Some(Slot::Checked(match (desc, p) {
        (BsdfDesc::Principled(params), P::BaseColor) => {
            return Some(Slot::Plain(&mut params.base_color))
        }
        (BsdfDesc::Diffuse { reflectance }, P::Reflectance) => reflectance,
        (
            BsdfDesc::Conductor {
                specular_reflectance,
                ..
            }
            | BsdfDesc::RoughConductor {
                specular_reflectance,
                ..
            }
            | BsdfDesc::Dielectric {
                specular_reflectance,
                ..
            }
            | BsdfDesc::RoughDielectric {
                specular_reflectance,
                ..
            }
            | BsdfDesc::ThinDielectric {
                specular_reflectance,
                ..
            }
            | BsdfDesc::Plastic {
                specular_reflectance,
                ..
            }
            | BsdfDesc::RoughPlastic {
                specular_reflectance,
                ..
            },
            P::SpecularReflectance,
        ) => specular_reflectance,
        (
            BsdfDesc::Dielectric {
                specular_transmittance,
                ..
            }
            | BsdfDesc::RoughDielectric {
                specular_transmittance,
                ..
            }
            | BsdfDesc::ThinDielectric {
                specular_transmittance,
                ..
            },
            P::SpecularTransmittance,
        ) => specular_transmittance,
        (
            BsdfDesc::Plastic {
                diffuse_reflectance,
                ..
            }
            | BsdfDesc::RoughPlastic {
                diffuse_reflectance,
                ..
            },
            P::DiffuseReflectance,
        ) => diffuse_reflectance,
        _ => return None,
    }))
}
