//! What the render loop stores per shape and how it forms the material of a hit: a stored
//! material is used as it is; a textured one is formed at the hit's texture coordinates.

use crate::bsdf::{AnyBsdf, Sided, TexturedBsdf};
use crate::geometry::Geometry;
use glam::{Vec2, Vec3};
use mcrt::integrator::{Bsdf, BsdfFlags, BsdfSample, SurfacePoint};

/// A shape's material as the render loop stores it.
pub(crate) trait Material {
    /// The material of one hit.
    type At<'a>: Bsdf
    where
        Self: 'a;

    /// The material at surface point `sp` of `geometry`.
    fn at<'a>(&'a self, geometry: &Geometry, sp: &SurfacePoint) -> Self::At<'a>;
}

impl<B: Bsdf> Material for Sided<B> {
    type At<'a>
        = &'a Self
    where
        Self: 'a;

    #[inline(always)]
    fn at<'a>(&'a self, _: &Geometry, _: &SurfacePoint) -> &'a Self {
        self
    }
}

impl Material for TexturedBsdf {
    type At<'a> = HitBsdf<'a>;

    #[inline]
    fn at<'a>(&'a self, geometry: &Geometry, sp: &SurfacePoint) -> HitBsdf<'a> {
        if self.is_textured() {
            HitBsdf::Formed(self.at(geometry.tex_coords_at(sp.shape, sp.prim, sp.uv)))
        } else {
            HitBsdf::Stored(&self.base)
        }
    }
}

/// The material of a hit in a scene with textures: the stored one, or one formed at the hit.
#[derive(Debug, Clone)]
pub(crate) enum HitBsdf<'a> {
    /// An untextured shape's material.
    Stored(&'a Sided<AnyBsdf>),
    /// A textured material at the hit's texture coordinates.
    Formed(Sided<AnyBsdf>),
}

impl HitBsdf<'_> {
    #[inline(always)]
    fn get(&self) -> &Sided<AnyBsdf> {
        match self {
            Self::Stored(b) => b,
            Self::Formed(b) => b,
        }
    }
}

impl Bsdf for HitBsdf<'_> {
    #[inline]
    fn flags(&self) -> BsdfFlags {
        self.get().flags()
    }
    #[inline]
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.get().eval(wo, wi)
    }
    #[inline]
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.get().pdf(wo, wi)
    }
    #[inline]
    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        self.get().eval_pdf(wo, wi)
    }
    #[inline]
    fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        self.get().sample(wo, u1, u2)
    }
    #[inline]
    fn eval_adjoint(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.get().eval_adjoint(wo, wi)
    }
    #[inline]
    fn samples_component(&self) -> bool {
        self.get().samples_component()
    }
}
