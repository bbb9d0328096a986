//! What the render loop stores per shape and how it forms the material of a hit: a stored
//! material is used as it is; a textured one is formed at the hit's texture coordinates.

use crate::bsdf::{AnyBsdf, Sided, SurfaceDerivatives, TexturedBsdf};
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
        let turn = self.needs_tangent().then(|| geometry.tangent_turn(sp));
        let formed = if self.is_textured() {
            let uv = geometry.tex_coords_at(sp.shape, sp.prim, sp.uv);
            if self.needs_derivatives() {
                HitBsdf::Formed(bump_mapped(self, geometry, sp, uv, turn))
            } else {
                HitBsdf::Formed(self.at(uv))
            }
        } else {
            HitBsdf::Stored(&self.base)
        };
        match turn {
            Some(t) => HitBsdf::Turned(Box::new(formed), t),
            None => formed,
        }
    }
}

/// The material of a bump-mapped `m` at `sp` (texture coordinates `uv`): the surface's
/// derivatives in Mitsuba's shading frame (the hit's frame turned by `turn`,
/// `Geometry::tangent_turn`). Out of line, so that the other materials' path stays small.
#[inline(never)]
fn bump_mapped(
    m: &TexturedBsdf,
    geometry: &Geometry,
    sp: &SurfacePoint,
    uv: Vec2,
    turn: Option<Vec2>,
) -> Sided<AnyBsdf> {
    let (dp_du, dp_dv) = geometry.uv_derivatives(sp);
    let local = |w: Vec3| into_turned(turn.unwrap_or(Vec2::X), sp.frame.to_local(w));
    let d = SurfaceDerivatives {
        dp_du: local(dp_du),
        dp_dv: local(dp_dv),
        ng: local(sp.ng),
    };
    m.at_with(uv, &d)
}

/// The material of a hit in a scene with textures: the stored one, or one formed at the hit.
#[derive(Debug, Clone)]
pub(crate) enum HitBsdf<'a> {
    /// An untextured shape's material.
    Stored(&'a Sided<AnyBsdf>),
    /// A textured material at the hit's texture coordinates.
    Formed(Sided<AnyBsdf>),
    /// An anisotropic material in Mitsuba's shading frame, turned about the normal from
    /// the hit's frame by (cos γ, sin γ) (`Geometry::tangent_turn`).
    Turned(Box<HitBsdf<'a>>, Vec2),
}

impl HitBsdf<'_> {
    #[inline(always)]
    fn get(&self) -> &Sided<AnyBsdf> {
        match self {
            Self::Stored(b) => b,
            Self::Formed(b) => b,
            Self::Turned(b, _) => b.get(),
        }
    }

    /// The turn (cos γ, sin γ) into the material's frame; (1, 0) when not turned.
    #[inline(always)]
    fn turn(&self) -> Option<Vec2> {
        match self {
            Self::Turned(_, t) => Some(*t),
            _ => None,
        }
    }
}

/// Local direction `w` of the hit's frame in the frame turned by `t` = (cos γ, sin γ).
#[inline]
fn into_turned(t: Vec2, w: Vec3) -> Vec3 {
    Vec3::new(t.x * w.x + t.y * w.y, -t.y * w.x + t.x * w.y, w.z)
}

/// Local direction `w` of the turned frame back in the hit's frame.
#[inline]
fn from_turned(t: Vec2, w: Vec3) -> Vec3 {
    Vec3::new(t.x * w.x - t.y * w.y, t.y * w.x + t.x * w.y, w.z)
}

impl Bsdf for HitBsdf<'_> {
    #[inline(always)]
    fn flags(&self) -> BsdfFlags {
        self.get().flags()
    }
    #[inline]
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        match self.turn() {
            None => self.get().eval(wo, wi),
            Some(t) => self.get().eval(into_turned(t, wo), into_turned(t, wi)),
        }
    }
    #[inline]
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self.turn() {
            None => self.get().pdf(wo, wi),
            Some(t) => self.get().pdf(into_turned(t, wo), into_turned(t, wi)),
        }
    }
    #[inline]
    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        match self.turn() {
            None => self.get().eval_pdf(wo, wi),
            Some(t) => self.get().eval_pdf(into_turned(t, wo), into_turned(t, wi)),
        }
    }
    #[inline]
    fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        match self.turn() {
            None => self.get().sample(wo, u1, u2),
            Some(t) => {
                let mut s = self.get().sample(into_turned(t, wo), u1, u2)?;
                s.wi = from_turned(t, s.wi);
                Some(s)
            }
        }
    }
    #[inline]
    fn eval_adjoint(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        match self.turn() {
            None => self.get().eval_adjoint(wo, wi),
            Some(t) => self
                .get()
                .eval_adjoint(into_turned(t, wo), into_turned(t, wi)),
        }
    }
    #[inline]
    fn samples_component(&self) -> bool {
        self.get().samples_component()
    }
}
