//! Materials: Mitsuba 3's `diffuse`, `conductor`, `roughconductor` (both with the named
//! materials of [`named_conductor`]), `dielectric`, `roughdielectric`, `thindielectric`,
//! `plastic`, `roughplastic`, `principled` and `twosided`, and the adapters `blendbsdf`,
//! `mask`, `normalmap` and `bumpmap` ([`Perturbed`]), as [`Bsdf`] implementations in the
//! local z-up frame.
//!
//! One-sided BSDFs are black from the back (`wo.z ≤ 0`), as in Mitsuba; [`Sided`] adds the
//! `twosided` flip. [`AnyBsdf`] dispatches over all of them; a scene made of diffuse surfaces
//! only is rendered with `Sided<Diffuse>` instead, so no glossy or refraction code is
//! compiled into its render loop.

/// `eval` and `pdf` for a BSDF whose `eval_pdf` computes both at once: each takes its half.
macro_rules! eval_and_pdf_from_eval_pdf {
    () => {
        #[inline]
        fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
            self.eval_pdf(wo, wi).0
        }
        #[inline]
        fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
            self.eval_pdf(wo, wi).1
        }
    };
}

/// `eval` and `pdf` of a purely specular (Dirac) BSDF: no value and no density off its
/// delta directions.
macro_rules! eval_and_pdf_of_a_delta_bsdf {
    () => {
        #[inline]
        fn eval(&self, _wo: Vec3, _wi: Vec3) -> Vec3 {
            Vec3::ZERO
        }
        #[inline]
        fn pdf(&self, _wo: Vec3, _wi: Vec3) -> f32 {
            0.0
        }
    };
}

mod blend;
mod conductor;
mod dielectric;
mod diffuse;
mod fresnel;
mod mask;
mod named_conductors;
mod ndf;
mod perturbed;
mod plastic;
mod principled;
mod principled_lobes;
mod principled_transmission;
mod rough_conductor;
mod rough_dielectric;
mod rough_plastic;
mod textured;
mod thin_dielectric;

pub use crate::description::{PrincipledParams, MAX_SPECULAR};
pub use blend::Blend;
pub use conductor::{Conductor, Fresnel};
pub use dielectric::Dielectric;
pub use diffuse::Diffuse;
pub use fresnel::{fresnel_conductor, fresnel_dielectric, fresnel_diffuse_reflectance};
pub use mask::Mask;
pub use named_conductors::{conductor_names, named_conductor};
pub use ndf::{Ndf, VisibleNdf};
pub use perturbed::{bump_normal, perturbed_frame, shadowing, Perturbed, SurfaceDerivatives};
pub use plastic::Plastic;
pub use principled::Principled;
pub use rough_conductor::RoughConductor;
pub use rough_dielectric::RoughDielectric;
pub use rough_plastic::RoughPlastic;
pub use textured::TexturedBsdf;
pub use thin_dielectric::ThinDielectric;

use super::description::{BsdfDesc, ConductorFresnel};
use glam::{Vec2, Vec3};
use mcrt::integrator::{Bsdf, BsdfFlags, BsdfSample};
use mcrt::sampling::SamplingError;

/// Any of the supported materials.
#[derive(Debug, Clone, PartialEq)]
pub enum AnyBsdf {
    /// Lambertian.
    Diffuse(Diffuse),
    /// Smooth mirror.
    Conductor(Conductor),
    /// Microfacet conductor.
    RoughConductor(RoughConductor),
    /// Smooth glass.
    Dielectric(Dielectric),
    /// Microfacet glass.
    RoughDielectric(RoughDielectric),
    /// A thin pane of glass.
    ThinDielectric(ThinDielectric),
    /// Diffuse base under a smooth coating.
    Plastic(Plastic),
    /// Diffuse base under a rough coating.
    RoughPlastic(RoughPlastic),
    /// Mitsuba's `principled` (the Disney BSDF); boxed, so that its many
    /// parameters do not enlarge every other material.
    Principled(Box<Principled>),
    /// A blend of two materials.
    Blend(Blend),
    /// A material with an opacity.
    Mask(Mask),
    /// A material in a perturbed shading frame (`normalmap`, `bumpmap`).
    Perturbed(Perturbed),
}

macro_rules! dispatch {
    ($self:ident, $b:ident => $e:expr) => {
        match $self {
            AnyBsdf::Diffuse($b) => $e,
            AnyBsdf::Conductor($b) => $e,
            AnyBsdf::RoughConductor($b) => $e,
            AnyBsdf::Dielectric($b) => $e,
            AnyBsdf::RoughDielectric($b) => $e,
            AnyBsdf::ThinDielectric($b) => $e,
            AnyBsdf::Plastic($b) => $e,
            AnyBsdf::RoughPlastic($b) => $e,
            AnyBsdf::Principled($b) => $e,
            AnyBsdf::Blend($b) => $e,
            AnyBsdf::Mask($b) => $e,
            AnyBsdf::Perturbed($b) => $e,
        }
    };
}

impl Bsdf for AnyBsdf {
    #[inline]
    fn flags(&self) -> BsdfFlags {
        dispatch!(self, b => b.flags())
    }
    #[inline]
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        dispatch!(self, b => b.eval(wo, wi))
    }
    #[inline]
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        dispatch!(self, b => b.pdf(wo, wi))
    }
    #[inline]
    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        dispatch!(self, b => b.eval_pdf(wo, wi))
    }
    #[inline]
    fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        dispatch!(self, b => b.sample(wo, u1, u2))
    }
    #[inline]
    fn eval_adjoint(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        dispatch!(self, b => b.eval_adjoint(wo, wi))
    }
    #[inline]
    fn samples_component(&self) -> bool {
        dispatch!(self, b => b.samples_component())
    }
}

/// A BSDF with Mitsuba's `twosided` option: when `two_sided`, a direction below the surface
/// sees the BSDF mirrored to the other side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sided<B> {
    /// The material.
    pub bsdf: B,
    /// Whether the back side shows the same material.
    pub two_sided: bool,
}

#[inline]
fn flip(w: Vec3) -> Vec3 {
    Vec3::new(w.x, w.y, -w.z)
}

impl<B: Bsdf> Bsdf for Sided<B> {
    #[inline]
    fn flags(&self) -> BsdfFlags {
        self.bsdf.flags()
    }
    eval_and_pdf_from_eval_pdf!();
    #[inline]
    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        if self.two_sided && wo.z < 0.0 {
            self.bsdf.eval_pdf(flip(wo), flip(wi))
        } else {
            self.bsdf.eval_pdf(wo, wi)
        }
    }
    #[inline]
    fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if self.two_sided && wo.z < 0.0 {
            let mut s = self.bsdf.sample(flip(wo), u1, u2)?;
            s.wi = flip(s.wi);
            Some(s)
        } else {
            self.bsdf.sample(wo, u1, u2)
        }
    }
    #[inline]
    fn eval_adjoint(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if self.two_sided && wo.z < 0.0 {
            self.bsdf.eval_adjoint(flip(wo), flip(wi))
        } else {
            self.bsdf.eval_adjoint(wo, wi)
        }
    }
    #[inline]
    fn samples_component(&self) -> bool {
        self.bsdf.samples_component()
    }
}

fn fresnel_of(f: &ConductorFresnel) -> Fresnel {
    match *f {
        ConductorFresnel::Perfect => Fresnel::Perfect,
        ConductorFresnel::Complex { eta, k } => Fresnel::Complex {
            eta: eta.get(),
            k: k.get(),
        },
    }
}

impl AnyBsdf {
    /// The material a description asks for, and whether it is two-sided (`twosided`
    /// wrappers nest; any depth means two-sided; a wrapped dielectric stays as it is, since
    /// it already has two sides).
    ///
    /// # Errors
    /// A roughness outside the microfacet warps' range.
    pub fn from_desc(desc: &BsdfDesc) -> Result<Sided<AnyBsdf>, SamplingError> {
        let bsdf = match desc {
            BsdfDesc::TwoSided(inner) => {
                let mut s = Self::from_desc(inner)?;
                // A dielectric already has two sides (its inside is the other medium);
                // mirroring it would turn refraction out of the object into refraction in.
                s.two_sided = !s.bsdf.flags().transmission;
                return Ok(s);
            }
            // The textures' means stand in the parameters; `TexturedBsdf` sets them per hit.
            BsdfDesc::Textured { inner, .. } => return Self::from_desc(inner),
            BsdfDesc::Diffuse { reflectance } => AnyBsdf::Diffuse(Diffuse {
                reflectance: reflectance.get(),
            }),
            BsdfDesc::Conductor {
                fresnel,
                specular_reflectance,
            } => AnyBsdf::Conductor(Conductor {
                fresnel: fresnel_of(fresnel),
                specular_reflectance: specular_reflectance.get(),
            }),
            BsdfDesc::RoughConductor {
                microfacet,
                fresnel,
                specular_reflectance,
            } => AnyBsdf::RoughConductor(RoughConductor::with_ndf(
                Ndf::of(microfacet),
                fresnel_of(fresnel),
                specular_reflectance.get(),
            )),
            BsdfDesc::Dielectric {
                int_ior,
                ext_ior,
                specular_reflectance,
                specular_transmittance,
            } => AnyBsdf::Dielectric(Dielectric {
                eta: int_ior.get() / ext_ior.get(),
                specular_reflectance: specular_reflectance.get(),
                specular_transmittance: specular_transmittance.get(),
            }),
            BsdfDesc::RoughDielectric {
                microfacet,
                int_ior,
                ext_ior,
                specular_reflectance,
                specular_transmittance,
            } => AnyBsdf::RoughDielectric(RoughDielectric::with_ndf(
                Ndf::of(microfacet),
                int_ior.get() / ext_ior.get(),
                specular_reflectance.get(),
                specular_transmittance.get(),
            )),
            BsdfDesc::ThinDielectric {
                int_ior,
                ext_ior,
                specular_reflectance,
                specular_transmittance,
            } => AnyBsdf::ThinDielectric(ThinDielectric {
                eta: int_ior.get() / ext_ior.get(),
                specular_reflectance: specular_reflectance.get(),
                specular_transmittance: specular_transmittance.get(),
            }),
            BsdfDesc::Plastic {
                int_ior,
                ext_ior,
                diffuse_reflectance,
                specular_reflectance,
                nonlinear,
            } => AnyBsdf::Plastic(Plastic::new(
                diffuse_reflectance.get(),
                specular_reflectance.get(),
                int_ior.get() / ext_ior.get(),
                *nonlinear,
            )),
            BsdfDesc::RoughPlastic {
                microfacet,
                int_ior,
                ext_ior,
                diffuse_reflectance,
                specular_reflectance,
                nonlinear,
            } => AnyBsdf::RoughPlastic(RoughPlastic::with_ndf(
                Ndf::of(microfacet),
                diffuse_reflectance.get(),
                specular_reflectance.get(),
                int_ior.get() / ext_ior.get(),
                *nonlinear,
            )),
            BsdfDesc::Principled(params) => {
                AnyBsdf::Principled(Box::new(Principled::new(*params)?))
            }
            BsdfDesc::Blend {
                weight,
                first,
                second,
            } => AnyBsdf::Blend(Blend {
                weight: *weight,
                first: Box::new(Self::from_desc(first)?),
                second: Box::new(Self::from_desc(second)?),
            }),
            BsdfDesc::Mask { opacity, inner } => AnyBsdf::Mask(Mask {
                opacity: *opacity,
                inner: Box::new(Self::from_desc(inner)?),
            }),
            // The unperturbed frame stands in; `TexturedBsdf` sets the normal per hit.
            BsdfDesc::Perturbed {
                perturbation,
                inner,
            } => AnyBsdf::Perturbed(Perturbed {
                normal: Vec3::Z,
                flip_invalid_normals: perturbation.flip_invalid_normals,
                use_shadowing_function: perturbation.use_shadowing_function,
                inner: Box::new(Self::from_desc(inner)?),
            }),
        };
        Ok(Sided {
            bsdf,
            two_sided: false,
        })
    }

    /// The Lambertian albedo if this is a diffuse material.
    pub fn as_diffuse(&self) -> Option<Diffuse> {
        match self {
            AnyBsdf::Diffuse(d) => Some(*d),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests;
