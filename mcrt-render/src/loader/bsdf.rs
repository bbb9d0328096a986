//! `<bsdf>`: `diffuse`, `conductor`, `roughconductor`, `dielectric`, `roughdielectric`,
//! `thindielectric`, `plastic`, `roughplastic`, `principled` and `twosided`, and `<ref>` to a BSDF
//! declared elsewhere (`normalmap` and `bumpmap` are read in `bsdf_maps`).

use super::context::{Ctx, Res};
use super::props::{Props, Value};
use super::texture;
use super::tree::Elem;
use super::{no_objects, plugin_type, unknown_plugin};
use crate::bsdf::named_conductor;
use crate::description::{
    BsdfDesc, Colour, ConductorFresnel, Ior, Microfacet, MicrofacetKind, Roughness, TextureParam,
};
use crate::param_defs::bsdf::{
    ALPHA, ALPHA_U, ALPHA_V, COATING_IOR, DIFFUSE_REFLECTANCE, DISTRIBUTION, ETA, EXT_IOR, INT_IOR,
    K, MATERIAL, NONLINEAR, REFLECTANCE, SAMPLE_VISIBLE, SPECULAR_REFLECTANCE,
    SPECULAR_TRANSMITTANCE,
};
use crate::param_defs::bsdf_composite::{OPACITY, WEIGHT};
use crate::param_defs::IorParam;
use crate::scene_error::SceneErrorKind;
use crate::validate::{self, CheckedBsdf};
use glam::Vec3;

/// A `<bsdf>` element, or a `<ref>` whose id names one.
pub(crate) fn read_bsdf_or_ref<'a>(ctx: &Ctx<'a>, e: &'a Elem) -> Res<CheckedBsdf> {
    read_bsdf(ctx, resolve(ctx, e)?)
}

/// Follows a `<ref>` to the BSDF it names (a `<bsdf>` is returned as is).
fn resolve<'a>(ctx: &Ctx<'a>, e: &'a Elem) -> Res<&'a Elem> {
    if e.tag != "ref" {
        return Ok(e);
    }
    super::transform::check_attrs(ctx, e, &["id", "name"], &["id"])?;
    let id = e.attr("id").unwrap_or("");
    match ctx.ids.get(id) {
        Some(target) if target.tag == "bsdf" => Ok(target),
        Some(target) => Err(ctx.err(
            e,
            SceneErrorKind::UndefinedReference(format!(
                "id \"{id}\" names a <{}> (line {}), not a <bsdf>",
                target.tag, target.line
            )),
        )),
        None => Err(ctx.err(
            e,
            SceneErrorKind::UndefinedReference(format!("no object has id \"{id}\"")),
        )),
    }
}

/// Deepest nesting of BSDFs inside `blendbsdf`, `mask`, `twosided`, `normalmap` and
/// `bumpmap` (through `ref`s too,
/// so a cycle of references is an error, not endless recursion).
const MAX_NESTING: u32 = 16;

/// Reads a `<bsdf>` element, each material in it checked once, at its element
/// ([`validate::bsdf_element`]).
pub(crate) fn read_bsdf(ctx: &Ctx, e: &Elem) -> Res<CheckedBsdf> {
    read_nested(ctx, e, 0)
}

/// Reads a `<bsdf>` element nested `depth` levels deep in other BSDFs.
fn read_nested(ctx: &Ctx, e: &Elem, depth: u32) -> Res<CheckedBsdf> {
    if depth > MAX_NESTING {
        return Err(ctx.err(
            e,
            SceneErrorKind::InvalidValue(format!(
                "BSDFs nest more than {MAX_NESTING} deep (a cycle of references?)"
            )),
        ));
    }
    let ty = plugin_type(ctx, e)?;
    let mut p = Props::new(ctx, e)?;
    if matches!(ty, "normalmap" | "bumpmap") {
        return super::bsdf_maps::read(ctx, e, ty, p, depth);
    }
    let textures = texture::take_textures(ctx, ty, &mut p)?;
    // A textured weight or opacity stands in as the texture's mean luminance.
    let scalar = |q: TextureParam| {
        textures
            .iter()
            .find(|t| t.0 == q)
            .map(|t| t.1.mean().clamp(0.0, 1.0))
    };
    match ty {
        "twosided" => {
            if let Some((_, _, o)) = textures.first() {
                return Err(texture::not_here(ctx, o));
            }
            return twosided(ctx, e, p, depth);
        }
        "blendbsdf" => {
            let weight = match (p.float(WEIGHT.name)?, scalar(TextureParam::Weight)) {
                (Some(w), _) | (None, Some(w)) => w,
                (None, None) => {
                    return Err(ctx.err(
                        e,
                        SceneErrorKind::InvalidValue("blendbsdf needs a \"weight\"".into()),
                    ))
                }
            };
            let [first, second] = nested::<2>(ctx, e, p, depth)?;
            let desc = BsdfDesc::Blend {
                weight,
                first: Box::new(first.into_inner()),
                second: Box::new(second.into_inner()),
            };
            return checked(ctx, e, texture::attach(ctx, e, ty, desc, textures)?);
        }
        "mask" => {
            let opacity = p.float(OPACITY.name)?;
            let opacity = opacity.or(scalar(TextureParam::Opacity)).unwrap_or(0.5);
            let [inner] = nested::<1>(ctx, e, p, depth)?;
            let desc = BsdfDesc::Mask {
                opacity,
                inner: Box::new(inner.into_inner()),
            };
            return checked(ctx, e, texture::attach(ctx, e, ty, desc, textures)?);
        }
        _ => {}
    }
    no_objects(ctx, &p)?;
    let desc = match ty {
        "diffuse" => BsdfDesc::Diffuse {
            reflectance: p.get_rgb(&REFLECTANCE)?,
        },
        "conductor" => BsdfDesc::Conductor {
            fresnel: fresnel(e, &mut p)?,
            specular_reflectance: p.get_rgb(&SPECULAR_REFLECTANCE)?,
        },
        "roughconductor" => BsdfDesc::RoughConductor {
            microfacet: microfacet(ctx, e, &mut p, Anisotropy::Allowed, &textures)?,
            fresnel: fresnel(e, &mut p)?,
            specular_reflectance: p.get_rgb(&SPECULAR_REFLECTANCE)?,
        },
        "dielectric" => BsdfDesc::Dielectric {
            int_ior: ior(e, &mut p, &INT_IOR)?,
            ext_ior: ior(e, &mut p, &EXT_IOR)?,
            specular_reflectance: p.get_rgb(&SPECULAR_REFLECTANCE)?,
            specular_transmittance: p.get_rgb(&SPECULAR_TRANSMITTANCE)?,
        },
        "roughdielectric" => BsdfDesc::RoughDielectric {
            microfacet: microfacet(ctx, e, &mut p, Anisotropy::Allowed, &textures)?,
            int_ior: ior(e, &mut p, &INT_IOR)?,
            ext_ior: ior(e, &mut p, &EXT_IOR)?,
            specular_reflectance: p.get_rgb(&SPECULAR_REFLECTANCE)?,
            specular_transmittance: p.get_rgb(&SPECULAR_TRANSMITTANCE)?,
        },
        "thindielectric" => BsdfDesc::ThinDielectric {
            int_ior: ior(e, &mut p, &INT_IOR)?,
            ext_ior: ior(e, &mut p, &EXT_IOR)?,
            specular_reflectance: p.get_rgb(&SPECULAR_REFLECTANCE)?,
            specular_transmittance: p.get_rgb(&SPECULAR_TRANSMITTANCE)?,
        },
        "plastic" => BsdfDesc::Plastic {
            int_ior: ior(e, &mut p, &COATING_IOR)?,
            ext_ior: ior(e, &mut p, &EXT_IOR)?,
            diffuse_reflectance: p.get_rgb(&DIFFUSE_REFLECTANCE)?,
            specular_reflectance: p.get_rgb(&SPECULAR_REFLECTANCE)?,
            nonlinear: p.get_bool(&NONLINEAR)?,
        },
        "roughplastic" => BsdfDesc::RoughPlastic {
            microfacet: microfacet(ctx, e, &mut p, Anisotropy::Refused, &textures)?,
            int_ior: ior(e, &mut p, &COATING_IOR)?,
            ext_ior: ior(e, &mut p, &EXT_IOR)?,
            diffuse_reflectance: p.get_rgb(&DIFFUSE_REFLECTANCE)?,
            specular_reflectance: p.get_rgb(&SPECULAR_REFLECTANCE)?,
            nonlinear: p.get_bool(&NONLINEAR)?,
        },
        "principled" => super::principled::principled(e, &mut p)?,
        other => return Err(unknown_plugin(ctx, e, other)),
    };
    let desc = texture::attach(ctx, e, ty, desc, textures)?;
    let desc = validate::bsdf_element(desc).map_err(|i| p.invalid(i.param, e, &i.message))?;
    p.finish()?;
    Ok(desc)
}

/// A blend, mask or twosided checked by [`validate::bsdf_element`], the error at the
/// element.
fn checked(ctx: &Ctx, e: &Elem, desc: BsdfDesc) -> Res<CheckedBsdf> {
    validate::bsdf_element(desc)
        .map_err(|i| ctx.err(e, SceneErrorKind::InvalidValue(i.to_string())))
}

/// Exactly `N` nested `<bsdf>` or `<ref>` elements of a plugin with parameters `p` (whose
/// other parameters must all have been read), read in file order.
pub(super) fn nested<'a, const N: usize>(
    ctx: &Ctx<'a>,
    e: &'a Elem,
    p: Props<'_, 'a>,
    depth: u32,
) -> Res<[CheckedBsdf; N]> {
    let objects: Vec<&Elem> = p.objects.clone();
    p.finish()?;
    let ty = e.attr("type").unwrap_or("");
    if objects.len() != N {
        return Err(ctx.err(
            e,
            SceneErrorKind::Unsupported(format!(
                "{ty} needs exactly {} nested BSDF{}, found {}",
                ["no", "one", "two"].get(N).copied().unwrap_or("more"),
                if N == 1 { "" } else { "s" },
                objects.len()
            )),
        ));
    }
    let mut out = Vec::with_capacity(N);
    for inner in objects {
        if inner.tag != "bsdf" && inner.tag != "ref" {
            return Err(ctx.err(
                inner,
                SceneErrorKind::Misplaced(format!("<{}> inside a {ty} BSDF", inner.tag)),
            ));
        }
        out.push(read_nested(ctx, resolve(ctx, inner)?, depth + 1)?);
    }
    out.try_into().map_err(|_| {
        ctx.err(
            e,
            SceneErrorKind::Unsupported(format!("{ty} needs exactly {N} nested BSDFs")),
        )
    })
}

/// `twosided`: exactly one nested BSDF, which must not itself be two-sided nor let light
/// through (Mitsuba 3 refuses both).
fn twosided<'a>(ctx: &Ctx<'a>, e: &'a Elem, p: Props<'_, 'a>, depth: u32) -> Res<CheckedBsdf> {
    if let Some(inner) = p.objects.iter().find(|o| o.tag == "bsdf" || o.tag == "ref") {
        let target = resolve(ctx, inner)?;
        if target.attr("type") == Some("twosided") {
            return Err(ctx.err(
                inner,
                SceneErrorKind::InvalidValue("a twosided BSDF cannot nest another".into()),
            ));
        }
    }
    let [inner] = nested::<1>(ctx, e, p, depth)?;
    if inner.transmits() {
        return Err(ctx.err(
            e,
            SceneErrorKind::InvalidValue(
                "twosided cannot nest a material that lets light through (dielectric, \
                 roughdielectric, thindielectric, mask, or a blend with one), as in Mitsuba 3"
                    .into(),
            ),
        ));
    }
    checked(ctx, e, BsdfDesc::TwoSided(Box::new(inner.into_inner())))
}

/// `distribution` (beckmann, the default, or ggx), the roughness of [`roughness`] (or of
/// [`textured_roughness`] when `textures` drive it), and `sample_visible`, which only
/// changes the noise, never the expected value.
fn microfacet(
    ctx: &Ctx,
    e: &Elem,
    p: &mut Props,
    anisotropy: Anisotropy,
    textures: &[(TextureParam, crate::texture::Texture, &Elem)],
) -> Res<Microfacet> {
    let distribution = match p.get_choice(&DISTRIBUTION)? {
        "ggx" => MicrofacetKind::Ggx,
        _ => MicrofacetKind::Beckmann,
    };
    let (alpha_u, alpha_v) = match textured_roughness(ctx, e, p, anisotropy, textures)? {
        Some(alphas) => alphas,
        None => roughness(e, p, anisotropy)?,
    };
    Ok(Microfacet {
        sample_visible: p.get_bool(&SAMPLE_VISIBLE)?,
        ..Microfacet::anisotropic(distribution, alpha_u, alpha_v)
    })
}

/// Whether a material takes `alpha_u` ≠ `alpha_v` (Mitsuba 3's `roughplastic` refuses it).
#[derive(Clone, Copy, PartialEq)]
enum Anisotropy {
    Allowed,
    Refused,
}

/// The roughness (αᵤ, αᵥ): `alpha` ([`ALPHA`]: values in [0, 10⁻⁴) are raised to 10⁻⁴, as
/// Mitsuba 3 does; negative values and values above 10 are refused) for both, or `alpha_u`
/// and `alpha_v`, each checked the same way; unequal only where `anisotropy` allows.
fn roughness(e: &Elem, p: &mut Props, anisotropy: Anisotropy) -> Res<(Roughness, Roughness)> {
    if !p.has(ALPHA_U.name) && !p.has(ALPHA_V.name) {
        let alpha = p.get_float(&ALPHA)?;
        return Ok((alpha, alpha));
    }
    let alpha = p.float(ALPHA.name)?;
    let (au, av) = (p.float(ALPHA_U.name)?, p.float(ALPHA_V.name)?);
    let (u, v) = match (alpha, au, av) {
        (None, Some(u), Some(v)) if u == v || anisotropy == Anisotropy::Allowed => (u, v),
        (None, Some(_), Some(_)) => {
            return Err(p.invalid(
                ALPHA_U.name,
                e,
                "differs from alpha_v (Mitsuba 3's roughplastic has no anisotropy)",
            ))
        }
        _ => return Err(p.invalid("alpha", e, "give either alpha or both alpha_u and alpha_v")),
    };
    let check = |name: &str, a: f32| ALPHA.check(a).map_err(|i| p.invalid(name, e, &i.message));
    Ok((check(ALPHA_U.name, u)?, check(ALPHA_V.name, v)?))
}

/// The roughness when a texture gives `alpha`, `alpha_u` or `alpha_v` (`None` when none
/// does): Mitsuba 3's `roughconductor` and `roughdielectric` take a texture for `alpha`
/// (both αᵤ and αᵥ) or for either of `alpha_u` and `alpha_v` (the other a texture or a
/// number); its `roughplastic` takes numbers only. A textured value stands as
/// [`Roughness::DEFAULT`] until `texture::attach` puts the texture's mean in.
fn textured_roughness(
    ctx: &Ctx,
    e: &Elem,
    p: &mut Props,
    anisotropy: Anisotropy,
    textures: &[(TextureParam, crate::texture::Texture, &Elem)],
) -> Res<Option<(Roughness, Roughness)>> {
    let textured = |q: TextureParam| textures.iter().find(|t| t.0 == q).map(|t| t.2);
    let Some(first) = textures.iter().find(|t| t.0.is_roughness()) else {
        return Ok(None);
    };
    if anisotropy == Anisotropy::Refused {
        return Err(ctx.err(
            first.2,
            SceneErrorKind::Unsupported(format!(
                "a texture for \"{}\" of roughplastic (Mitsuba 3.9.1's roughplastic takes a \
                 number only; roughconductor and roughdielectric take a texture)",
                first.0.name()
            )),
        ));
    }
    let either = "give either alpha or both alpha_u and alpha_v";
    if textured(TextureParam::Alpha).is_some() {
        let stray = [ALPHA_U.name, ALPHA_V.name]
            .into_iter()
            .find(|n| p.has(n) || textures.iter().any(|t| t.0.name() == *n));
        return match stray {
            Some(n) => Err(p.invalid(n, e, either)),
            None => Ok(Some((Roughness::DEFAULT, Roughness::DEFAULT))),
        };
    }
    if p.has(ALPHA.name) {
        return Err(p.invalid(ALPHA.name, e, either));
    }
    let mut one = |q: TextureParam, name: &str| -> Res<Roughness> {
        if textured(q).is_some() {
            return Ok(Roughness::DEFAULT);
        }
        let Some(a) = p.float(name)? else {
            return Err(p.invalid(name, e, either));
        };
        ALPHA.check(a).map_err(|i| p.invalid(name, e, &i.message))
    };
    let u = one(TextureParam::AlphaU, ALPHA_U.name)?;
    let v = one(TextureParam::AlphaV, ALPHA_V.name)?;
    Ok(Some((u, v)))
}

/// Mitsuba's conductor rule: `material = "none"` (the default) without `eta` or `k` is a
/// perfect mirror; `eta`/`k` (defaults 0 and 1) give a complex IOR; a named `material`
/// (Au, Cu, Al, …) gives the RGB values Mitsuba's RGB variants use, and cannot be combined
/// with `eta` or `k`.
fn fresnel(e: &Elem, p: &mut Props) -> Res<ConductorFresnel> {
    let material = p.string(MATERIAL.name)?.unwrap_or_else(|| "none".into());
    let unbounded = super::spectrum::SpectrumUse::Unbounded;
    let (eta, k) = (p.colour(ETA.name, unbounded)?, p.colour(K.name, unbounded)?);
    if material != "none" {
        if eta.is_some() || k.is_some() {
            let which = if eta.is_some() { "eta" } else { "k" };
            return Err(p.invalid(
                which,
                e,
                &format!("cannot be given with material \"{material}\" (give one or the other)"),
            ));
        }
        let Some((eta, k)) = named_conductor(&material) else {
            return Err(p.invalid(
                "material",
                e,
                &format!(
                    "\"{material}\" is not a known conductor (names are case-sensitive, \
                     e.g. Au, Ag, Al, Cu, Cr; docs/scene-format.md lists them)"
                ),
            ));
        };
        return conductor(e, p, eta, k);
    }
    if eta.is_none() && k.is_none() {
        return Ok(ConductorFresnel::Perfect);
    }
    conductor(e, p, eta.unwrap_or(Vec3::ZERO), k.unwrap_or(Vec3::ONE))
}

/// A complex index of refraction, each part checked into a [`Colour`].
fn conductor(e: &Elem, p: &Props, eta: Vec3, k: Vec3) -> Res<ConductorFresnel> {
    let check = |name: &'static str, v: Vec3| {
        Colour::named(name, v).map_err(|i| p.invalid(name, e, &i.message))
    };
    Ok(ConductorFresnel::Complex {
        eta: check(ETA.name, eta)?,
        k: check(K.name, k)?,
    })
}

/// An index of refraction given as a number or as one of Mitsuba's named media.
fn ior(e: &Elem, p: &mut Props, d: &IorParam) -> Res<Ior> {
    let name = d.name;
    let value = match p.raw(name) {
        None => d.default,
        Some((Value::Str(s), _)) => named_ior(&s)
            .ok_or_else(|| p.invalid(name, e, &format!("\"{s}\" is not a known medium")))?,
        Some((Value::Float(v), _)) => v,
        Some((Value::Int(v), _)) => v as f32,
        Some((_, el)) => return Err(p.wrong(el, name, "a <float> or a <string>")),
    };
    Ior::new(value).map_err(|i| p.invalid(name, e, &i.message))
}

/// Mitsuba's table of named indices of refraction.
fn named_ior(name: &str) -> Option<f32> {
    const TABLE: &[(&str, f32)] = &[
        ("vacuum", 1.0),
        ("helium", 1.000036),
        ("hydrogen", 1.000132),
        ("air", 1.000277),
        ("carbon dioxide", 1.00045),
        ("water", 1.333),
        ("acetone", 1.36),
        ("ethanol", 1.361),
        ("carbon tetrachloride", 1.461),
        ("glycerol", 1.4729),
        ("benzene", 1.501),
        ("silicone oil", 1.52045),
        ("bromine", 1.661),
        ("water ice", 1.31),
        ("fused quartz", 1.458),
        ("pyrex", 1.47),
        ("acrylic glass", 1.49),
        ("polypropylene", 1.49),
        ("bk7", 1.5046),
        ("sodium chloride", 1.544),
        ("amber", 1.55),
        ("pet", 1.575),
        ("diamond", 2.419),
    ];
    let lower = name.to_ascii_lowercase();
    TABLE.iter().find(|(n, _)| *n == lower).map(|(_, v)| *v)
}
