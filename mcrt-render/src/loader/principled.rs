//! `<bsdf type="principled">`: Mitsuba 3's principled BSDF.

use super::context::Res;
use super::props::Props;
use super::tree::Elem;
use crate::description::BsdfDesc;
use crate::description::PrincipledParams;
use crate::param_defs::bsdf_composite as defs;

/// Reads the parameters of a `principled` BSDF (Mitsuba 3.9's names and defaults, each
/// checked by its definition), with `eta` or `specular` (not both) for the index.
pub(crate) fn principled(e: &Elem, p: &mut Props) -> Res<BsdfDesc> {
    let d = PrincipledParams::default();
    let mut params = PrincipledParams {
        base_color: d.base_color,
        roughness: p.get_float(&defs::ROUGHNESS)?,
        anisotropic: p.get_float(&defs::ANISOTROPIC)?,
        metallic: p.get_float(&defs::METALLIC)?,
        spec_trans: p.get_float(&defs::SPEC_TRANS)?,
        eta: d.eta,
        spec_tint: p.get_float(&defs::SPEC_TINT)?,
        sheen: p.get_float(&defs::SHEEN)?,
        sheen_tint: p.get_float(&defs::SHEEN_TINT)?,
        flatness: p.get_float(&defs::FLATNESS)?,
        clearcoat: p.get_float(&defs::CLEARCOAT)?,
        clearcoat_gloss: p.get_float(&defs::CLEARCOAT_GLOSS)?,
        diffuse_reflectance_sampling_rate: p.get_float(&defs::DIFFUSE_RATE)?,
        main_specular_sampling_rate: p.get_float(&defs::SPECULAR_RATE)?,
        clearcoat_sampling_rate: p.get_float(&defs::CLEARCOAT_RATE)?,
    };
    if let Some(c) = p.rgb(defs::BASE_COLOR.name)? {
        params.base_color = c;
    }
    match (p.float(defs::ETA.name)?, p.float(defs::SPECULAR.name)?) {
        (Some(_), Some(_)) => {
            return Err(p.invalid("specular", e, "cannot be given with \"eta\" (give one)"))
        }
        (Some(eta), None) => {
            params.eta = defs::ETA
                .check(eta)
                .map_err(|i| p.invalid(i.param, e, &i.message))?
        }
        (None, Some(s)) => {
            let s = defs::SPECULAR
                .check(s)
                .map_err(|i| p.invalid(i.param, e, &i.message))?;
            params.eta = PrincipledParams::eta_from_specular(s);
        }
        (None, None) => {}
    }
    Ok(BsdfDesc::Principled(params))
}

#[cfg(test)]
mod tests {
    use crate::param_defs::bsdf_composite as defs;

    /// The definitions' defaults are the description's (Mitsuba 3.9's), so a scene built in
    /// code with `PrincipledParams::default()` means what an XML without them means.
    #[test]
    fn the_definitions_defaults_are_the_descriptions() {
        let d = crate::description::PrincipledParams::default();
        for (def, v) in [
            (&defs::ROUGHNESS, d.roughness),
            (&defs::ANISOTROPIC, d.anisotropic),
            (&defs::METALLIC, d.metallic),
            (&defs::SPEC_TRANS, d.spec_trans),
            (&defs::SPEC_TINT, d.spec_tint),
            (&defs::SHEEN, d.sheen),
            (&defs::SHEEN_TINT, d.sheen_tint),
            (&defs::FLATNESS, d.flatness),
            (&defs::CLEARCOAT, d.clearcoat),
            (&defs::CLEARCOAT_GLOSS, d.clearcoat_gloss),
            (&defs::DIFFUSE_RATE, d.diffuse_reflectance_sampling_rate),
            (&defs::SPECULAR_RATE, d.main_specular_sampling_rate),
            (&defs::CLEARCOAT_RATE, d.clearcoat_sampling_rate),
            (&defs::ETA, d.eta),
        ] {
            assert_eq!(def.default, v, "{}", def.name);
        }
        assert_eq!(d.base_color, glam::Vec3::splat(defs::BASE_COLOR.default));
    }
}
