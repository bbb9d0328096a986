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
