//! Mitsuba 3's `normalmap` and `bumpmap` at a hit: the nested material evaluated in a
//! shading frame turned to a perturbed normal, with Mitsuba 3.9.1's normal flip and
//! shadowing term. Every direction here is in the hit's shading frame as Mitsuba builds it
//! (`s` along the tangent `dp/du`, `n` the shading normal); the derivation of the frame and
//! of the bump-mapped normal is in `docs/bsdf-models.md`, "Normal and bump maps".

use super::{AnyBsdf, Sided};
use glam::{Vec2, Vec3};
use mcrt::integrator::{Bsdf, BsdfFlags, BsdfSample};
use mcrt::sampling::Frame;

/// A material seen in a perturbed shading frame. [`Perturbed::normal`] is set per hit
/// (`TexturedBsdf`); `(0, 0, 1)` leaves the frame exactly as it is.
#[derive(Debug, Clone, PartialEq)]
pub struct Perturbed {
    /// The perturbed normal in the hit's shading frame, not necessarily unit length.
    pub normal: Vec3,
    /// Mirror a normal that faces away from the viewing direction (Mitsuba's
    /// `flip_invalid_normals`).
    pub flip_invalid_normals: bool,
    /// Scale the value by the shadowing term [`shadowing`] (Mitsuba's
    /// `use_shadowing_function`).
    pub use_shadowing_function: bool,
    /// The nested material.
    pub inner: Box<Sided<AnyBsdf>>,
}

/// The perturbed frame, in the hit's shading frame, that a viewer in direction `wo` sees
/// for the perturbed normal `normal`, as Mitsuba 3.9.1 builds it: with `flip`, a normal
/// with `wo.z · (wo · n) ≤ 0` is mirrored about the shading normal (`(−x, −y, z)`); the
/// normal is normalised (`(0, 0, 1)` if it cannot be); `s` is the shading frame's `s` axis
/// `(1, 0, 0)` made orthogonal to it (`(0, 1, 0)` if they are parallel); `t = n × s`.
///
/// ```
/// use mcrt::glam::Vec3;
/// use mcrt_render::bsdf::perturbed_frame;
///
/// let f = perturbed_frame(Vec3::Z, Vec3::new(0.6, 0.0, 0.8), true);
/// assert_eq!((f.s, f.t, f.n), (Vec3::X, Vec3::Y, Vec3::Z)); // exactly unperturbed
/// let g = perturbed_frame(Vec3::new(0.3, 0.0, 1.0), Vec3::new(0.6, 0.0, 0.8), true);
/// assert!(g.n.x > 0.0 && g.s.z < 0.0 && (g.s.cross(g.t) - g.n).length() < 1e-6);
/// ```
pub fn perturbed_frame(normal: Vec3, wo: Vec3, flip: bool) -> Frame {
    let mut n = normal;
    if flip && wo.z * wo.dot(n) <= 0.0 {
        n = Vec3::new(-n.x, -n.y, n.z);
    }
    let n = n.try_normalize().unwrap_or(Vec3::Z);
    let s = (Vec3::X - n * n.x).try_normalize().unwrap_or(Vec3::Y);
    Frame {
        s,
        t: n.cross(s),
        n,
    }
}

/// `tan²θ` of `w` in the shading frame (Mitsuba's `Frame::tan_theta_2`).
#[inline]
fn tan2(w: Vec3) -> f32 {
    (1.0 - w.z * w.z).max(0.0) / (w.z * w.z)
}

/// The shadowing term of a perturbed unit normal `n` toward `w` (both in the shading frame,
/// `w.z ≠ 0`): `2 / (1 + √(1 + α² tan²θ_w))` with `α² = min(tan²θ_n / 8, 1)`; exactly 1 for
/// an unperturbed normal.
///
/// Estevez, Kulla, Kohl 2019, "A Microfacet-Based Shadowing Function to Solve the Bump
/// Terminator Problem", Ray Tracing Gems, ch. 12.
#[inline]
pub fn shadowing(n: Vec3, w: Vec3) -> f32 {
    let alpha2 = (0.125 * tan2(n)).min(1.0);
    2.0 / (1.0 + (1.0 + alpha2 * tan2(w)).sqrt())
}

impl Perturbed {
    /// The frame a viewer in direction `wo` sees ([`perturbed_frame`]).
    #[inline]
    pub fn frame(&self, wo: Vec3) -> Frame {
        perturbed_frame(self.normal, wo, self.flip_invalid_normals)
    }

    /// The factor on the value toward `wi`: 0 when `wi` and its perturbed version lie on
    /// different sides (Mitsuba's `cos θ · cos θ' > 0` test), else the shadowing term if on.
    #[inline]
    fn factor(&self, f: &Frame, wi: Vec3, pwi: Vec3) -> f32 {
        if wi.z * pwi.z > 0.0 {
            if self.use_shadowing_function {
                shadowing(f.n, wi)
            } else {
                1.0
            }
        } else {
            0.0
        }
    }
}

// No `#[inline]` on the methods that recurse into the nested material (as `Blend`, `Mask`):
// `AnyBsdf`'s dispatch stays small enough to inline into the render loops.
impl Bsdf for Perturbed {
    fn flags(&self) -> BsdfFlags {
        self.inner.flags()
    }
    eval_and_pdf_from_eval_pdf!();
    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        let f = self.frame(wo);
        let pwi = f.to_local(wi);
        let k = self.factor(&f, wi, pwi);
        if k == 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let (v, pdf) = self.inner.eval_pdf(f.to_local(wo), pwi);
        (v * k, pdf)
    }
    fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        let f = self.frame(wo);
        let mut s = self.inner.sample(f.to_local(wo), u1, u2)?;
        let wi = f.to_world(s.wi);
        let k = self.factor(&f, wi, s.wi);
        if k == 0.0 {
            return None;
        }
        s.wi = wi;
        s.weight *= k;
        Some(s)
    }
    /// As Mitsuba's adjoint transport evaluates it: the frame seen from `wo` (the light
    /// side), the nested material's adjoint in it, the factor toward `wi`.
    fn eval_adjoint(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        let f = self.frame(wo);
        let pwi = f.to_local(wi);
        let k = self.factor(&f, wi, pwi);
        if k == 0.0 {
            return Vec3::ZERO;
        }
        self.inner.eval_adjoint(f.to_local(wo), pwi) * k
    }
    fn samples_component(&self) -> bool {
        self.inner.samples_component()
    }
}

/// The surface's derivatives at a hit, in its shading frame (Mitsuba's, `s` along `dp/du`):
/// what a bump map tilts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceDerivatives {
    /// `dp/du`, the position's derivative by the texture's u.
    pub dp_du: Vec3,
    /// `dp/dv`.
    pub dp_dv: Vec3,
    /// The unit geometric normal of the front side.
    pub ng: Vec3,
}

impl SurfaceDerivatives {
    /// A flat surface parameterised by its shading frame: `dp/du = s`, `dp/dv = t`,
    /// `ng = n`.
    pub const FLAT: Self = Self {
        dp_du: Vec3::X,
        dp_dv: Vec3::Y,
        ng: Vec3::Z,
    };
}

/// The bump-mapped normal (in the shading frame, not normalised) of a height field whose
/// scaled gradient along (u, v) is `grad`, as Mitsuba 3.9.1's `bumpmap` forms it: the
/// derivatives with their normal components replaced by the gradient, `dp/du' = dp/du +
/// n (∂h/∂u − n · dp/du)` and the same for v (the change of the normal along u and v is
/// neglected), crossed, and turned to the geometric normal's side.
///
/// ```
/// use mcrt::glam::{Vec2, Vec3};
/// use mcrt_render::bsdf::{bump_normal, SurfaceDerivatives};
///
/// let flat = SurfaceDerivatives::FLAT;
/// assert_eq!(bump_normal(Vec2::ZERO, &flat), Vec3::Z);
/// // A height rising along u by 0.5 per unit tilts the normal back along −u by atan 0.5.
/// assert_eq!(bump_normal(Vec2::new(0.5, 0.0), &flat), Vec3::new(-0.5, 0.0, 1.0));
/// ```
pub fn bump_normal(grad: Vec2, d: &SurfaceDerivatives) -> Vec3 {
    let du = Vec3::new(d.dp_du.x, d.dp_du.y, grad.x);
    let dv = Vec3::new(d.dp_dv.x, d.dp_dv.y, grad.y);
    let n = du.cross(dv);
    if d.ng.dot(n) < 0.0 {
        -n
    } else {
        n
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdf::Diffuse;

    fn diffuse() -> Box<Sided<AnyBsdf>> {
        Box::new(Sided {
            bsdf: AnyBsdf::Diffuse(Diffuse {
                reflectance: Vec3::splat(0.5),
            }),
            two_sided: false,
        })
    }

    fn perturbed(normal: Vec3) -> Perturbed {
        Perturbed {
            normal,
            flip_invalid_normals: true,
            use_shadowing_function: true,
            inner: diffuse(),
        }
    }

    /// The normal map's flat colour (0.5, 0.5, 1) gives n = (0, 0, 1): the frame, and so
    /// every value, is exactly the unperturbed one.
    #[test]
    fn flat_normal_map_leaves_the_material_exactly() {
        let n = Vec3::new(0.5, 0.5, 1.0) * 2.0 - 1.0;
        assert_eq!(n, Vec3::Z);
        let p = perturbed(n);
        let wo = Vec3::new(0.36, -0.48, 0.8);
        let f = p.frame(wo);
        assert_eq!((f.s, f.t, f.n), (Vec3::X, Vec3::Y, Vec3::Z));
        for wi in [
            Vec3::new(0.6, 0.0, 0.8),
            Vec3::new(-0.28, 0.96, 0.0),
            Vec3::new(0.0, 0.6, -0.8),
        ] {
            assert_eq!(p.eval_pdf(wo, wi), p.inner.eval_pdf(wo, wi), "{wi}");
        }
        for k in 0..16 {
            let u = Vec2::new((k as f32 + 0.5) / 16.0, 0.3);
            assert_eq!(p.sample(wo, 0.5, u), p.inner.sample(wo, 0.5, u));
        }
    }

    /// Mitsuba 3.9.1's `normalmap` over a white `diffuse` (`bsdf.eval` in `scalar_rgb` with
    /// a constant raw bitmap of colour `c`, n = 2c − 1; the script in
    /// tests/data/REFERENCES.md, "Normal and bump maps"): a tilted normal, and one seen
    /// from its back, which is mirrored (with the flip), zero (without), and without the
    /// shadowing term.
    #[test]
    fn values_match_mitsuba() {
        let white = |c: Vec3, flip, shadow| Perturbed {
            normal: c * 2.0 - 1.0,
            flip_invalid_normals: flip,
            use_shadowing_function: shadow,
            inner: Box::new(Sided {
                bsdf: AnyBsdf::Diffuse(Diffuse {
                    reflectance: Vec3::ONE,
                }),
                two_sided: false,
            }),
        };
        let cases = [
            (
                Vec3::new(0.65, 0.4, 0.95),
                true,
                true,
                Vec3::new(0.48, 0.6, 0.64),
                Vec3::new(-0.36, 0.0, 0.932_952),
                0.240_032_3,
            ),
            (
                Vec3::new(0.95, 0.5, 0.6),
                true,
                true,
                Vec3::new(-0.8, 0.0, 0.6),
                Vec3::new(-0.6, 0.0, 0.8),
                0.214_825_7,
            ),
            (
                Vec3::new(0.95, 0.5, 0.6),
                false,
                true,
                Vec3::new(-0.8, 0.0, 0.6),
                Vec3::new(-0.6, 0.0, 0.8),
                0.0,
            ),
            (
                Vec3::new(0.95, 0.5, 0.6),
                true,
                false,
                Vec3::new(-0.8, 0.0, 0.6),
                Vec3::new(-0.6, 0.0, 0.8),
                0.241_678_9,
            ),
        ];
        for (c, flip, shadow, wo, wi, want) in cases {
            let got = white(c, flip, shadow).eval(wo, wi).x;
            assert!(
                got.is_finite() && (got - want).abs() < 2e-6,
                "{c} {flip} {shadow}: {got} vs {want}"
            );
        }
    }

    /// Directions on opposite sides of the true and the perturbed surface give nothing.
    #[test]
    fn opposite_sides_give_zero_and_no_sample() {
        let p = Perturbed {
            flip_invalid_normals: false,
            ..perturbed(Vec3::new(1.0, 0.0, 1.0))
        };
        let wo = Vec3::new(0.6, 0.0, 0.8);
        // Above the true surface, below the perturbed one.
        let wi = Vec3::new(-0.8, 0.0, 0.1).normalize();
        assert!(p.frame(wo).to_local(wi).z < 0.0);
        assert_eq!(p.eval_pdf(wo, wi), (Vec3::ZERO, 0.0));
        let mut kept = 0;
        for k in 0..64 {
            let u = Vec2::new((k % 8) as f32 / 8.0 + 0.06, (k / 8) as f32 / 8.0 + 0.06);
            if let Some(s) = p.sample(wo, 0.5, u) {
                assert!(s.wi.z > 0.0 && p.frame(wo).to_local(s.wi).z > 0.0);
                assert!(s.weight.is_finite() && s.pdf > 0.0);
                kept += 1;
            }
        }
        // The perturbed hemisphere reaches below the true surface: some samples drop.
        assert!(kept > 0 && kept < 64, "{kept}");
    }

    #[test]
    fn shadowing_is_one_when_flat_and_falls_toward_grazing() {
        let w = Vec3::new(0.6, 0.0, 0.8);
        assert_eq!(shadowing(Vec3::Z, w), 1.0);
        let n = Vec3::new(0.4, 0.0, 1.0).normalize();
        let near = shadowing(n, w);
        let grazing = shadowing(n, Vec3::new(0.999, 0.0, 0.0447));
        assert!(near.is_finite() && grazing.is_finite());
        assert!(near < 1.0 && grazing < near && grazing > 0.0);
    }

    /// The bump normal of a tilted, scaled parameterisation: it is the normal of the
    /// surface p + h n, whose derivatives the gradient sets.
    #[test]
    fn bump_normal_is_the_displaced_surfaces_normal() {
        let d = SurfaceDerivatives {
            dp_du: Vec3::new(2.0, 0.5, 0.1),
            dp_dv: Vec3::new(-0.3, 1.5, -0.2),
            ng: Vec3::new(0.05, 0.0, 1.0).normalize(),
        };
        let g = Vec2::new(0.7, -0.4);
        let n = bump_normal(g, &d);
        // Orthogonal to both displaced derivatives, on the geometric normal's side.
        let du = Vec3::new(2.0, 0.5, 0.7);
        let dv = Vec3::new(-0.3, 1.5, -0.4);
        assert!(n.is_finite() && n.dot(du).abs() < 1e-5 && n.dot(dv).abs() < 1e-5);
        assert!(n.dot(d.ng) > 0.0);
    }
}
