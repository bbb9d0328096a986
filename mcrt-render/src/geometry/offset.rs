//! Spawning rays from surfaces without hitting the surface again.
//!
//! Policy: intersection routines accept only `t > 0` and apply no epsilon of their own. A
//! ray leaving a surface starts at [`offset_origin`]: the hit point pushed along the
//! geometric normal, to the side the ray leaves by, by a few hundred ulps of each coordinate
//! (a fixed tiny distance near the world origin). A shadow ray towards a point on another
//! surface ends at that point pushed the same way towards the ray ([`spawn_ray_to`]), so
//! `t_max = 1` never reaches the target surface either.

use super::Ray;
use glam::Vec3;

/// Below this magnitude a coordinate is offset by a fixed distance rather than in ulps.
const ORIGIN: f32 = 1.0 / 32.0;
/// The fixed distance (times the normal component) used near the origin.
const FLOAT_SCALE: f32 = 1.0 / 65536.0;
/// Ulps (times the normal component) added to each coordinate elsewhere.
const INT_SCALE: f32 = 256.0;

/// The origin for a ray leaving the surface point `p` (geometric normal `ng`, either
/// orientation) in direction `dir`: `p` moved off the surface to the side `dir` points to.
/// Each coordinate moves by about `256 · |ng_i|` ulps of itself, or by `|ng_i| / 65536`
/// where it is below 1/32 in magnitude (Wächter & Binder 2019, "A Fast and Robust Method
/// for Avoiding Self-Intersection", Ray Tracing Gems, ch. 6).
///
/// ```
/// use mcrt::glam::Vec3;
/// use mcrt_render::geometry::offset_origin;
///
/// let o = offset_origin(Vec3::new(10.0, 0.0, 2.0), Vec3::Z, Vec3::new(0.3, 0.0, 1.0));
/// assert!(o.z > 2.0 && o.z < 2.0 + 1e-3);
/// let o = offset_origin(Vec3::new(10.0, 0.0, 2.0), Vec3::Z, Vec3::new(0.3, 0.0, -1.0));
/// assert!(o.z < 2.0);
/// ```
#[inline]
#[must_use]
pub fn offset_origin(p: Vec3, ng: Vec3, dir: Vec3) -> Vec3 {
    let n = if ng.dot(dir) < 0.0 { -ng } else { ng };
    #[cfg(target_arch = "x86_64")]
    if let Some(o) = lanes::offset(p, n) {
        return o;
    }
    offset_scalar(p, n)
}

/// [`offset_origin`] once the normal `n` points to the ray's side, one coordinate at a time.
#[inline]
fn offset_scalar(p: Vec3, n: Vec3) -> Vec3 {
    let f = |x: f32, nx: f32| {
        if x.abs() < ORIGIN {
            return x + FLOAT_SCALE * nx;
        }
        // Step the bit pattern: for x < 0 increasing the bits moves away from zero, so the
        // step's sign follows x's sign for a move along +nx.
        let step = (INT_SCALE * nx) as i32;
        let step = if x < 0.0 { -step } else { step };
        f32::from_bits((x.to_bits() as i32).wrapping_add(step) as u32)
    };
    Vec3::new(f(p.x, n.x), f(p.y, n.y), f(p.z, n.z))
}

/// [`offset_scalar`] on the three coordinates at once in SSE2 lanes (x86-64's baseline, so
/// pulp's token for it is found at compile time): the same operations lane by lane, so the
/// same bits.
#[cfg(target_arch = "x86_64")]
mod lanes {
    use super::{FLOAT_SCALE, INT_SCALE, ORIGIN};
    use glam::{Vec3, Vec3A};

    /// Below this normal component the lane conversion to integer ulps cannot overflow, so
    /// it agrees with Rust's saturating `as i32`.
    const SAFE_COMPONENT: f32 = 1.0e6;

    /// The offset origin, or `None` without SSE2 or for a normal component that is NaN or
    /// huge (left to the scalar code, whose conversion saturates).
    #[inline(always)]
    pub(super) fn offset(p: Vec3, n: Vec3) -> Option<Vec3> {
        let simd = pulp::x86::V1::try_new()?;
        let (sse, sse2) = (simd.sse, simd.sse2);
        let x = sse._mm_setr_ps(p.x, p.y, p.z, 0.0);
        let nx = sse._mm_setr_ps(n.x, n.y, n.z, 0.0);
        let abs_mask = sse2._mm_castsi128_ps(sse2._mm_set1_epi32(i32::MAX));
        let abs = |v| sse._mm_and_ps(v, abs_mask);
        let fits = sse._mm_cmplt_ps(abs(nx), sse._mm_set1_ps(SAFE_COMPONENT));
        if sse._mm_movemask_ps(fits) & 0b111 != 0b111 {
            return None;
        }
        // Near the origin: a fixed step along the normal.
        let near = sse._mm_add_ps(x, sse._mm_mul_ps(sse._mm_set1_ps(FLOAT_SCALE), nx));
        // Elsewhere: step the bit pattern, by the step negated where x < 0.
        let step = sse2._mm_cvttps_epi32(sse._mm_mul_ps(sse._mm_set1_ps(INT_SCALE), nx));
        let negative = sse2._mm_castps_si128(sse._mm_cmplt_ps(x, sse._mm_setzero_ps()));
        let step = sse2._mm_sub_epi32(sse2._mm_xor_si128(step, negative), negative);
        let far = sse2._mm_castsi128_ps(sse2._mm_add_epi32(sse2._mm_castps_si128(x), step));
        let small = sse._mm_cmplt_ps(abs(x), sse._mm_set1_ps(ORIGIN));
        let o = sse._mm_or_ps(sse._mm_and_ps(small, near), sse._mm_andnot_ps(small, far));
        Some(Vec3::from(Vec3A::from(o)))
    }
}

/// A ray leaving surface point `p` (geometric normal `ng`) in direction `dir` (passed
/// through unchanged, so unit if `dir` is).
#[inline]
#[must_use]
pub fn spawn_ray(p: Vec3, ng: Vec3, dir: Vec3) -> Ray {
    Ray {
        origin: offset_origin(p, ng, dir),
        dir,
    }
}

/// A shadow ray from surface point `p` (normal `ng`) to surface point `q` (normal `nq`;
/// pass `Vec3::ZERO` for a point not on a surface, e.g. a point light), and its `t_max`.
/// The direction is *not* unit: `t = 1` is the offset target, so use the returned
/// `t_max` (= 1) with [`super::Geometry::occluded`].
#[inline]
#[must_use]
pub fn spawn_ray_to(p: Vec3, ng: Vec3, q: Vec3, nq: Vec3) -> (Ray, f32) {
    let origin = offset_origin(p, ng, q - p);
    let target = offset_origin(q, nq, p - q);
    (
        Ray {
            origin,
            dir: target - origin,
        },
        1.0,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The SSE2 lanes give the scalar code's bits, near the origin and far from it, for
    /// either sign of each coordinate and of each normal component.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn lanes_match_the_scalar_offset_bit_for_bit() {
        use rand_core::{RngCore, SeedableRng};
        let mut rng = rand_pcg::Pcg32::seed_from_u64(37);
        let mut unit = || (rng.next_u32() >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0;
        let mut checked = 0;
        for k in 0..20_000 {
            // Magnitudes from 2^-20 to 2^20, zeros and the 1/32 border among them.
            let scale = 2f32.powi(k % 41 - 20);
            let mut p = Vec3::new(unit(), unit(), unit()) * scale;
            if k % 7 == 0 {
                p.y = 0.0;
            }
            if k % 11 == 0 {
                p.x = -ORIGIN;
            }
            let n = Vec3::new(unit(), unit(), unit()).normalize_or(Vec3::Z);
            let o = lanes::offset(p, n).expect("SSE2 and a unit normal");
            let s = offset_scalar(p, n);
            assert!(o.is_finite() && s.is_finite());
            assert_eq!(
                o.to_array().map(f32::to_bits),
                s.to_array().map(f32::to_bits)
            );
            checked += 1;
        }
        assert_eq!(checked, 20_000);
        // A NaN or huge normal component is left to the scalar code.
        assert!(lanes::offset(Vec3::ONE, Vec3::new(f32::NAN, 0.0, 1.0)).is_none());
        assert!(lanes::offset(Vec3::ONE, Vec3::new(0.0, 1e9, 0.0)).is_none());
    }

    #[test]
    fn offsets_move_to_the_ray_side_in_every_octant() {
        for &p in &[
            Vec3::new(100.0, -100.0, 0.001),
            Vec3::new(-3.0, 2.0, -0.01),
            Vec3::new(-1e4, 1e4, 5.0),
        ] {
            for &n in &[Vec3::X, -Vec3::Y, Vec3::new(0.6, 0.0, -0.8)] {
                let o = offset_origin(p, n, n);
                assert!(o.is_finite());
                assert!((o - p).dot(n) > 0.0, "p {p} n {n} o {o}");
                let o = offset_origin(p, n, -n);
                assert!((o - p).dot(n) < 0.0);
                assert!((o - p).length() < 1e-3 * (1.0 + p.abs().max_element()));
            }
        }
    }
}
