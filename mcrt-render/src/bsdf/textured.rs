//! Materials with textured parameters: the per-hit material is the constant one with each
//! textured parameter replaced by the texture's value at the hit, and each normal or bump
//! map's normal set from its texture there.

use super::perturbed::{bump_normal, SurfaceDerivatives};
use super::{AnyBsdf, Sided};
use crate::description::{BsdfDesc, NormalSource};
use crate::texture::{Texture, TextureParam};
use glam::{Vec2, Vec3};
use mcrt::sampling::SamplingError;

impl AnyBsdf {
    /// Sets parameter `p` to `v` (a scalar parameter takes `v.x`, clamped to [0, 1] as
    /// Mitsuba 3 clamps a textured blend weight or opacity). Returns whether this material
    /// has the parameter.
    pub fn set_param(&mut self, p: TextureParam, v: Vec3) -> bool {
        use TextureParam as P;
        let slot = match (self, p) {
            (AnyBsdf::Diffuse(b), P::Reflectance) => &mut b.reflectance,
            (AnyBsdf::Conductor(b), P::SpecularReflectance) => &mut b.specular_reflectance,
            (AnyBsdf::RoughConductor(b), P::SpecularReflectance) => &mut b.specular_reflectance,
            (AnyBsdf::Dielectric(b), P::SpecularReflectance) => &mut b.specular_reflectance,
            (AnyBsdf::Dielectric(b), P::SpecularTransmittance) => &mut b.specular_transmittance,
            (AnyBsdf::RoughDielectric(b), P::SpecularReflectance) => &mut b.specular_reflectance,
            (AnyBsdf::RoughDielectric(b), P::SpecularTransmittance) => {
                &mut b.specular_transmittance
            }
            (AnyBsdf::ThinDielectric(b), P::SpecularReflectance) => &mut b.specular_reflectance,
            (AnyBsdf::ThinDielectric(b), P::SpecularTransmittance) => &mut b.specular_transmittance,
            (AnyBsdf::Plastic(b), P::DiffuseReflectance) => &mut b.diffuse_reflectance,
            (AnyBsdf::Plastic(b), P::SpecularReflectance) => &mut b.specular_reflectance,
            (AnyBsdf::RoughPlastic(b), P::DiffuseReflectance) => &mut b.diffuse_reflectance,
            (AnyBsdf::RoughPlastic(b), P::SpecularReflectance) => &mut b.specular_reflectance,
            (AnyBsdf::Blend(b), P::Weight) => {
                b.weight = v.x.clamp(0.0, 1.0);
                return true;
            }
            (AnyBsdf::Principled(b), P::BaseColor) => {
                b.set_base_color(v);
                return true;
            }
            (AnyBsdf::Mask(b), P::Opacity) => {
                b.opacity = v.x.clamp(0.0, 1.0);
                return true;
            }
            (AnyBsdf::RoughConductor(b), P::Alpha | P::AlphaU | P::AlphaV) => {
                b.ndf = textured_alpha(&b.ndf, p, v.x);
                return true;
            }
            (AnyBsdf::RoughDielectric(b), P::Alpha | P::AlphaU | P::AlphaV) => {
                b.ndf = textured_alpha(&b.ndf, p, v.x);
                return true;
            }
            _ => return false,
        };
        *slot = v;
        true
    }

    /// The material nested at `path` (0: a blend's first or a mask's, normal map's or bump
    /// map's material, 1: a blend's second), this one for an empty path.
    fn nested_mut(&mut self, path: &[u8]) -> Option<&mut AnyBsdf> {
        let Some((&step, rest)) = path.split_first() else {
            return Some(self);
        };
        let next = match (self, step) {
            (AnyBsdf::Blend(b), 0) => &mut b.first.bsdf,
            (AnyBsdf::Blend(b), 1) => &mut b.second.bsdf,
            (AnyBsdf::Mask(m), 0) => &mut m.inner.bsdf,
            (AnyBsdf::Perturbed(m), 0) => &mut m.inner.bsdf,
            _ => return None,
        };
        next.nested_mut(rest)
    }
}

/// `ndf` with the textured roughness `p` (`alpha`: both, `alpha_u`, `alpha_v`) set to `a`.
fn textured_alpha(ndf: &super::Ndf, p: TextureParam, a: f32) -> super::Ndf {
    let (u, v) = ndf.alphas();
    match p {
        TextureParam::AlphaU => ndf.with_alphas(a, v),
        TextureParam::AlphaV => ndf.with_alphas(u, a),
        _ => ndf.with_alphas(a, a),
    }
}

/// One textured parameter: where its material sits among nested ones, which parameter,
/// and the texture.
#[derive(Debug, Clone, PartialEq)]
struct Slot {
    path: Vec<u8>,
    param: TextureParam,
    texture: Texture,
}

/// How a normal or bump map sets its normal.
#[derive(Debug, Clone, Copy, PartialEq)]
enum MapKind {
    /// A normal map's normal, `2 · rgb − 1`.
    Normal,
    /// A bump map's normal, from the gradient times `scale`.
    Bump { scale: f32 },
}

/// One normal or bump map: where its material sits among nested ones, its kind and its
/// texture.
#[derive(Debug, Clone, PartialEq)]
struct MapSlot {
    path: Vec<u8>,
    kind: MapKind,
    texture: Texture,
}

/// A material whose parameters may be textures. [`TexturedBsdf::at`] forms the material at
/// texture coordinates `uv`: a copy of the constant material with every textured parameter
/// set to its texture's value there (a colour, or the luminance for a blend weight or an
/// opacity). The copy allocates only for `blendbsdf` and `mask`, which own their nested
/// materials, and `principled`, which is boxed.
#[derive(Debug, Clone, PartialEq)]
pub struct TexturedBsdf {
    /// The material with the textures' means in their parameters.
    pub base: Sided<AnyBsdf>,
    slots: Vec<Slot>,
    /// The normal and bump maps (kept apart, so that materials without them loop over
    /// their parameters as before).
    maps: Vec<MapSlot>,
    /// Whether a map is a bump map (which reads the surface's derivatives).
    bump: bool,
    /// Whether the material turns with the shading tangent (anisotropic roughness, normal
    /// and bump maps).
    tangent: bool,
}

impl TexturedBsdf {
    /// The material a description asks for, with its textures.
    ///
    /// # Errors
    /// As [`AnyBsdf::from_desc`].
    pub fn from_desc(desc: &BsdfDesc) -> Result<Self, SamplingError> {
        Ok(Self::with_base(AnyBsdf::from_desc(desc)?, desc))
    }

    /// The textured material of `desc` whose constant material `base` is already built
    /// (`AnyBsdf::from_desc(desc)`).
    pub fn with_base(base: Sided<AnyBsdf>, desc: &BsdfDesc) -> Self {
        let (mut slots, mut maps) = (Vec::new(), Vec::new());
        collect(desc, &mut Vec::new(), &mut slots, &mut maps);
        Self {
            base,
            slots,
            bump: maps.iter().any(|m| matches!(m.kind, MapKind::Bump { .. })),
            maps,
            tangent: desc.needs_tangent(),
        }
    }

    /// Whether the material turns with the shading tangent `dp/du` (anisotropic
    /// roughness): its hits then need Mitsuba's shading frame.
    #[inline]
    pub fn needs_tangent(&self) -> bool {
        self.tangent
    }

    /// Whether any parameter is textured, or the material has a normal or bump map.
    #[inline]
    pub fn is_textured(&self) -> bool {
        !self.slots.is_empty() || !self.maps.is_empty()
    }

    /// Whether a bump map needs the surface's derivatives at each hit
    /// ([`TexturedBsdf::at_with`]).
    #[inline]
    pub fn needs_derivatives(&self) -> bool {
        self.bump
    }

    /// The material at texture coordinates `uv` of a surface whose derivatives are
    /// [`SurfaceDerivatives::FLAT`] (which only bump maps read).
    pub fn at(&self, uv: Vec2) -> Sided<AnyBsdf> {
        let mut out = self.params_at(uv);
        if !self.maps.is_empty() {
            self.set_normals(&mut out, uv, &SurfaceDerivatives::FLAT);
        }
        out
    }

    /// The material at texture coordinates `uv` of a surface with derivatives `d` (in the
    /// hit's shading frame, for bump maps).
    pub fn at_with(&self, uv: Vec2, d: &SurfaceDerivatives) -> Sided<AnyBsdf> {
        let mut out = self.params_at(uv);
        self.set_normals(&mut out, uv, d);
        out
    }

    /// The material with its textured parameters set at `uv` (normals not yet).
    #[inline]
    fn params_at(&self, uv: Vec2) -> Sided<AnyBsdf> {
        let mut out = self.base.clone();
        for s in &self.slots {
            let v = if s.param.is_scalar() {
                Vec3::splat(s.texture.eval_1(uv))
            } else {
                s.texture.eval(uv)
            };
            if let Some(b) = out.bsdf.nested_mut(&s.path) {
                b.set_param(s.param, v);
            }
        }
        out
    }

    /// Sets the normal of each normal or bump map of `out` at `uv` and derivatives `d`.
    fn set_normals(&self, out: &mut Sided<AnyBsdf>, uv: Vec2, d: &SurfaceDerivatives) {
        for m in &self.maps {
            let n = match m.kind {
                MapKind::Normal => m.texture.eval(uv) * 2.0 - 1.0,
                MapKind::Bump { scale } => bump_normal(scale * m.texture.eval_1_grad(uv), d),
            };
            if let Some(AnyBsdf::Perturbed(p)) = out.bsdf.nested_mut(&m.path) {
                p.normal = n;
            }
        }
    }
}

/// Records the textured parameters and the normal and bump maps of `desc` and of the
/// materials nested in it.
fn collect(desc: &BsdfDesc, path: &mut Vec<u8>, out: &mut Vec<Slot>, maps: &mut Vec<MapSlot>) {
    match desc {
        BsdfDesc::Textured { inner, textures } => {
            out.extend(textures.iter().map(|(param, texture)| Slot {
                path: path.clone(),
                param: *param,
                texture: texture.clone(),
            }));
            collect(inner, path, out, maps);
        }
        BsdfDesc::Perturbed {
            perturbation,
            inner,
        } => {
            let kind = match perturbation.source {
                NormalSource::NormalMap(_) => MapKind::Normal,
                NormalSource::BumpMap { scale, .. } => MapKind::Bump { scale },
            };
            maps.push(MapSlot {
                path: path.clone(),
                kind,
                texture: perturbation.texture().clone(),
            });
            path.push(0);
            collect(inner, path, out, maps);
            path.pop();
        }
        BsdfDesc::TwoSided(inner) => collect(inner, path, out, maps),
        BsdfDesc::Blend { first, second, .. } => {
            for (step, d) in [(0, first), (1, second)] {
                path.push(step);
                collect(d, path, out, maps);
                path.pop();
            }
        }
        BsdfDesc::Mask { inner, .. } => {
            path.push(0);
            collect(inner, path, out, maps);
            path.pop();
        }
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::Checkerboard;

    fn checker() -> Texture {
        Texture::Checkerboard(Checkerboard {
            color0: Vec3::new(0.8, 0.1, 0.1),
            color1: Vec3::new(0.1, 0.1, 0.8),
            ..Checkerboard::default()
        })
    }

    #[test]
    fn diffuse_reflectance_follows_the_texture() {
        let desc = BsdfDesc::TwoSided(Box::new(BsdfDesc::Textured {
            inner: Box::new(BsdfDesc::Diffuse {
                reflectance: crate::description::Colour::new(Vec3::splat(0.3)).unwrap(),
            }),
            textures: vec![(TextureParam::Reflectance, checker())],
        }));
        let t = TexturedBsdf::from_desc(&desc).unwrap();
        assert!(t.is_textured() && t.base.two_sided);
        let at = |u, v| t.at(Vec2::new(u, v)).bsdf.as_diffuse().unwrap().reflectance;
        assert_eq!(at(0.25, 0.25), Vec3::new(0.8, 0.1, 0.1));
        assert_eq!(at(0.75, 0.25), Vec3::new(0.1, 0.1, 0.8));
    }

    /// A texture on the second material of a blend and on the blend's weight.
    #[test]
    fn nested_slots_and_scalar_weight() {
        let diffuse = |r| BsdfDesc::Diffuse {
            reflectance: crate::description::Colour::new(Vec3::splat(r)).unwrap(),
        };
        let desc = BsdfDesc::Textured {
            inner: Box::new(BsdfDesc::Blend {
                weight: 0.5,
                first: Box::new(diffuse(0.2)),
                second: Box::new(BsdfDesc::Textured {
                    inner: Box::new(diffuse(0.3)),
                    textures: vec![(TextureParam::Reflectance, checker())],
                }),
            }),
            textures: vec![(TextureParam::Weight, checker())],
        };
        let t = TexturedBsdf::from_desc(&desc).unwrap();
        let AnyBsdf::Blend(b) = t.at(Vec2::new(0.75, 0.25)).bsdf else {
            panic!("not a blend")
        };
        // A checkerboard's single value is the other square's channel mean (Mitsuba 3.9.1).
        let w = (0.8 + 0.1 + 0.1) / 3.0;
        assert!(
            b.weight.is_finite() && (b.weight - w).abs() < 1e-6,
            "{}",
            b.weight
        );
        assert_eq!(
            b.first.bsdf.as_diffuse().unwrap().reflectance,
            Vec3::splat(0.2)
        );
        assert_eq!(
            b.second.bsdf.as_diffuse().unwrap().reflectance,
            Vec3::new(0.1, 0.1, 0.8)
        );
    }

    #[test]
    fn scalar_parameters_are_clamped_and_wrong_ones_refused() {
        let mut m = AnyBsdf::from_desc(&BsdfDesc::Mask {
            opacity: 0.5,
            inner: Box::new(BsdfDesc::default()),
        })
        .unwrap()
        .bsdf;
        assert!(m.set_param(TextureParam::Opacity, Vec3::splat(3.0)));
        assert!(matches!(&m, AnyBsdf::Mask(k) if k.opacity == 1.0));
        assert!(!m.set_param(TextureParam::Reflectance, Vec3::ONE));
        let mut d = AnyBsdf::from_desc(&BsdfDesc::default()).unwrap().bsdf;
        assert!(!d.set_param(TextureParam::Weight, Vec3::ONE));
    }
}
