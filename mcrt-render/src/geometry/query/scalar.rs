//! Ray–primitive intersection: watertight triangles, spheres, disks.
//!
//! Every routine accepts a direction of any nonzero length and returns `t` in units of that
//! length, and reports only hits with `0 < t < t_max` (strict at both ends).

use glam::{Affine3A, DVec3, Vec3, Vec3A, Vec3Swizzles};

/// A triangle stored by coordinate: lane `i` of `x`, `y`, `z` holds vertex `i`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TriSoa {
    x: Vec3A,
    y: Vec3A,
    z: Vec3A,
}

impl TriSoa {
    pub(crate) fn new(v: [Vec3; 3]) -> Self {
        Self {
            x: Vec3A::new(v[0].x, v[1].x, v[2].x),
            y: Vec3A::new(v[0].y, v[1].y, v[2].y),
            z: Vec3A::new(v[0].z, v[1].z, v[2].z),
        }
    }

    /// The point with barycentric weights `w` (of vertices 0, 1, 2), summed in the order
    /// `(w0 v0 + w1 v1) + w2 v2` per coordinate.
    #[inline(always)]
    pub(crate) fn point(&self, w: Vec3A) -> Vec3 {
        let sum = |c: Vec3A| c.x + c.y + c.z;
        Vec3::new(sum(self.x * w), sum(self.y * w), sum(self.z * w))
    }

    /// The three vertices.
    pub(crate) fn vertices(&self) -> [Vec3; 3] {
        [0, 1, 2].map(|i| Vec3::new(self.x[i], self.y[i], self.z[i]))
    }
}

/// A ray prepared for the watertight triangle test (Woop, Benthin & Wald 2013,
/// "Watertight Ray/Triangle Intersection", JCGT 2(1)): the permutation and shear that map the
/// ray to the +z axis through the origin, folded into three row vectors.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TriRay {
    origin: Vec3,
    /// Rows of the shear: x' = rx·v, y' = ry·v, z' = rz·v for v relative to the origin. Each
    /// row has at most two nonzero entries, one of them exactly 1, so x' and y' are the
    /// paper's `A[kx] − Sx·A[kz]` rounded exactly the same way (adding ±0 changes nothing).
    rx: Vec3,
    ry: Vec3,
    rz: Vec3,
}

impl TriRay {
    #[inline]
    pub(crate) fn new(origin: Vec3, dir: Vec3) -> Self {
        let kz = dir.abs().max_position();
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        if dir[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        let unit = |k: usize| Vec3::AXES[k];
        let sz = 1.0 / dir[kz];
        Self {
            origin,
            rx: unit(kx) - unit(kz) * (dir[kx] * sz),
            ry: unit(ky) - unit(kz) * (dir[ky] * sz),
            rz: unit(kz) * sz,
        }
    }

    /// The hit `(t, b1, b2)` with the triangle, where `b1`, `b2` are the barycentric
    /// weights of vertices 1 and 2. All three vertices are processed at once in SIMD lanes.
    #[inline(always)]
    pub(crate) fn hit(&self, tri: &TriSoa, t_max: f32) -> Option<(f32, f32, f32)> {
        let x = tri.x - Vec3A::splat(self.origin.x);
        let y = tri.y - Vec3A::splat(self.origin.y);
        let z = tri.z - Vec3A::splat(self.origin.z);
        let row = |r: Vec3| x * r.x + y * r.y + z * r.z;
        let (px, py) = (row(self.rx), row(self.ry));
        // Lanes (U, V, W): the edge functions of edges BC, CA, AB at the origin.
        let mut e = px.zxy() * py.yzx() - py.zxy() * px.yzx();
        if e.cmpeq(Vec3A::ZERO).any() {
            e = edges_f64(px, py);
        }
        if e.min_element() < 0.0 && e.max_element() > 0.0 {
            return None;
        }
        let det = e.x + e.y + e.z;
        if det == 0.0 {
            return None;
        }
        let tt = e.dot(row(self.rz));
        let inside = if det > 0.0 {
            tt > 0.0 && tt < t_max * det
        } else {
            tt < 0.0 && tt > t_max * det
        };
        if !inside {
            return None;
        }
        let inv = 1.0 / det;
        let t = tt * inv;
        (t > 0.0 && t < t_max).then_some((t, e.y * inv, e.z * inv))
    }
}

/// The edge functions in f64: on an edge in f32, the paper decides in higher precision so
/// that shared edges are claimed consistently.
#[cold]
fn edges_f64(px: Vec3A, py: Vec3A) -> Vec3A {
    let (x, y) = (px.as_dvec3(), py.as_dvec3());
    let e = x.zxy() * y.yzx() - y.zxy() * x.yzx();
    e.as_vec3a()
}

/// The nearest root in `(0, t_max)` of |o + t d − c|² = r², computed as in Haines, Günther,
/// Akenine-Möller 2019, "Precision Improvements for Ray/Sphere Intersection", Ray Tracing
/// Gems, ch. 7: the discriminant from the distance of the centre to the ray line, and the
/// smaller root from the larger by Vieta's formula, both in f64 for the few flops it takes.
#[inline(never)]
pub(crate) fn hit_sphere(
    origin: Vec3,
    dir: Vec3,
    center: Vec3,
    radius: f32,
    t_max: f32,
) -> Option<f32> {
    let f = origin.as_dvec3() - center.as_dvec3();
    let d = dir.as_dvec3();
    let r = f64::from(radius);
    let a = d.dot(d);
    let b = f.dot(d);
    let l: DVec3 = f - d * (b / a);
    let disc = a * (r * r - l.dot(l));
    if disc < 0.0 {
        return None;
    }
    let q = -(b + disc.sqrt().copysign(b));
    let c = f.dot(f) - r * r;
    let (mut t0, mut t1) = (c / q, q / a);
    if q == 0.0 {
        // b = 0 and disc = 0: a tangent ray through the closest point; both roots are 0.
        (t0, t1) = (0.0, 0.0);
    }
    let (t0, t1) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
    let t_max = f64::from(t_max);
    [t0, t1]
        .into_iter()
        .map(|t| t as f32)
        .find(|&t| t > 0.0 && f64::from(t) < t_max)
}

/// The hit distance with the unit disk `x² + y² ≤ 1, z = 0` in the object space that
/// `to_object` maps to, and the hit point in object space.
#[inline(never)]
pub(crate) fn hit_disk(
    origin: Vec3,
    dir: Vec3,
    to_object: &Affine3A,
    t_max: f32,
) -> Option<(f32, Vec3)> {
    let o = to_object.transform_point3(origin);
    let d = to_object.transform_vector3(dir);
    if d.z == 0.0 {
        return None;
    }
    let t = -o.z / d.z;
    if !(t > 0.0 && t < t_max) {
        return None;
    }
    let p = Vec3::new(o.x + t * d.x, o.y + t * d.y, 0.0);
    (p.x * p.x + p.y * p.y <= 1.0).then_some((t, p))
}

#[cfg(test)]
mod tests {
    use super::*;

    const V: [Vec3; 3] = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ];

    #[test]
    fn triangle_barycentrics_and_distance() {
        let tri = TriSoa::new(V);
        assert_eq!(tri.vertices(), V);
        let r = TriRay::new(Vec3::new(0.25, 0.5, 2.0), Vec3::new(0.0, 0.0, -2.0));
        let (t, b1, b2) = r.hit(&tri, f32::INFINITY).unwrap();
        assert!(t.is_finite() && b1.is_finite() && b2.is_finite());
        assert!((t - 1.0).abs() < 1e-6);
        assert!((b1 - 0.25).abs() < 1e-6 && (b2 - 0.5).abs() < 1e-6);
        // Same from below (back face) and with t_max too small.
        let r = TriRay::new(Vec3::new(0.25, 0.5, -1.0), Vec3::Z);
        assert!(r.hit(&tri, 2.0).is_some());
        assert!(r.hit(&tri, 1.0).is_none());
        assert!(TriRay::new(Vec3::new(0.8, 0.8, 1.0), -Vec3::Z)
            .hit(&tri, 9.0)
            .is_none());
    }

    #[test]
    fn shared_edge_is_claimed_once_or_more_never_missed() {
        // Two triangles sharing the diagonal of the unit square; rays exactly on it.
        let tri = TriSoa::new(V);
        let other = TriSoa::new([V[1], Vec3::new(1.0, 1.0, 0.0), V[2]]);
        for i in 1..64 {
            let s = i as f32 / 64.0;
            let d = Vec3::new(0.1, -0.2, -1.0);
            let r2 = TriRay::new(Vec3::new(s, 1.0 - s, 0.0) - d, d);
            let hits = usize::from(r2.hit(&tri, 9.0).is_some())
                + usize::from(r2.hit(&other, 9.0).is_some());
            assert!(hits >= 1, "ray {i} fell through the shared edge");
        }
    }

    #[test]
    fn degenerate_triangle_is_never_hit() {
        let flat = TriSoa::new([Vec3::ZERO, Vec3::X, Vec3::X * 2.0]);
        let r = TriRay::new(Vec3::new(0.5, 0.0, 1.0), -Vec3::Z);
        assert!(r.hit(&flat, 9.0).is_none());
    }

    #[test]
    fn sphere_near_and_far_roots() {
        let t = hit_sphere(Vec3::new(0.0, 0.0, -5.0), Vec3::Z, Vec3::ZERO, 1.0, 100.0).unwrap();
        assert!(t.is_finite() && (t - 4.0).abs() < 1e-6);
        let t = hit_sphere(Vec3::ZERO, Vec3::Z * 2.0, Vec3::ZERO, 1.0, 100.0).unwrap();
        assert!(t.is_finite() && (t - 0.5).abs() < 1e-6);
        assert!(hit_sphere(Vec3::new(0.0, 2.0, -5.0), Vec3::Z, Vec3::ZERO, 1.0, 9.0).is_none());
        // Far away, tiny sphere: the precise discriminant still finds it.
        let t = hit_sphere(Vec3::new(0.0, 0.0, -1e4), Vec3::Z, Vec3::ZERO, 1e-2, 1e5).unwrap();
        assert!(t.is_finite() && (t - (1e4 - 1e-2)).abs() < 1e-2);
    }

    #[test]
    fn rays_leaving_a_sphere_do_not_hit_it_again() {
        use crate::geometry::offset_origin;
        let c = Vec3::new(3.0, -2.0, 7.0);
        for k in 0..200 {
            let a = k as f32 * 0.37;
            let n = Vec3::new(
                a.cos() * (a * 0.5).sin(),
                (a * 0.5).cos(),
                a.sin() * (a * 0.5).sin(),
            )
            .normalize();
            let p = c + 0.8 * n;
            // Leaving outwards: nothing ahead.
            let out = n + Vec3::new(0.1, -0.2, 0.05);
            let o = offset_origin(p, n, out);
            assert!(hit_sphere(o, out, c, 0.8, f32::INFINITY).is_none(), "k {k}");
            // Refracted inwards: the far side, not the start point.
            let inward = -n + Vec3::new(0.05, 0.1, -0.1);
            let o = offset_origin(p, n, inward);
            let t = hit_sphere(o, inward, c, 0.8, f32::INFINITY).unwrap();
            assert!(t.is_finite() && t > 0.1, "k {k}: t {t}");
        }
    }

    #[test]
    fn disk_hit_inside_only() {
        let id = Affine3A::IDENTITY;
        let (t, p) = hit_disk(Vec3::new(0.5, 0.0, 1.0), -Vec3::Z, &id, 9.0).unwrap();
        assert!(t.is_finite() && (t - 1.0).abs() < 1e-6 && p.z == 0.0);
        assert!(hit_disk(Vec3::new(0.8, 0.8, 1.0), -Vec3::Z, &id, 9.0).is_none());
        assert!(hit_disk(Vec3::new(0.0, 0.0, 1.0), Vec3::X, &id, 9.0).is_none());
    }
}
