//! `<bsdf type="principled">`: Mitsuba 3's principled BSDF.

use super::context::Res;
use super::props::Props;
use super::tree::Elem;
use crate::description::BsdfDesc;
use crate::description::{PrincipledParams, MAX_SPECULAR};

/// Reads the parameters of a `principled` BSDF (Mitsuba 3.9's names and defaults), with
/// `eta` or `specular` (not both) for the index; the ranges are checked by the caller's
/// [`validate::bsdf`](crate::validate::bsdf).
pub(crate) fn principled(e: &Elem, p: &mut Props) -> Res<BsdfDesc> {
    let d = PrincipledParams::default();
    let mut f = |name: &str, default: f32| -> Res<f32> { Ok(p.float(name)?.unwrap_or(default)) };
    let mut params = PrincipledParams {
        base_color: d.base_color,
        roughness: f("roughness", d.roughness)?,
        anisotropic: f("anisotropic", d.anisotropic)?,
        metallic: f("metallic", d.metallic)?,
        spec_trans: f("spec_trans", d.spec_trans)?,
        eta: d.eta,
        spec_tint: f("spec_tint", d.spec_tint)?,
        sheen: f("sheen", d.sheen)?,
        sheen_tint: f("sheen_tint", d.sheen_tint)?,
        flatness: f("flatness", d.flatness)?,
        clearcoat: f("clearcoat", d.clearcoat)?,
        clearcoat_gloss: f("clearcoat_gloss", d.clearcoat_gloss)?,
        diffuse_reflectance_sampling_rate: f(
            "diffuse_reflectance_sampling_rate",
            d.diffuse_reflectance_sampling_rate,
        )?,
        main_specular_sampling_rate: f(
            "main_specular_sampling_rate",
            d.main_specular_sampling_rate,
        )?,
        clearcoat_sampling_rate: f("clearcoat_sampling_rate", d.clearcoat_sampling_rate)?,
    };
    if let Some(c) = p.rgb("base_color")? {
        params.base_color = c;
    }
    match (p.float("eta")?, p.float("specular")?) {
        (Some(_), Some(_)) => {
            return Err(p.invalid("specular", e, "cannot be given with \"eta\" (give one)"))
        }
        (Some(eta), None) => params.eta = eta,
        (None, Some(s)) => {
            if !(0.0..MAX_SPECULAR).contains(&s) {
                return Err(p.invalid("specular", e, "must lie in [0, 12.5)"));
            }
            params.eta = PrincipledParams::eta_from_specular(s);
        }
        (None, None) => {}
    }
    Ok(BsdfDesc::Principled(params))
}
