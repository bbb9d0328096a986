//! TEMPORARY stand-in for `scene::geometry` and `scene::camera` (branch geometry), with the
//! same names and signatures, brute force. Deleted when the real modules land.
#![allow(dead_code, clippy::neg_cmp_op_on_partial_ord)]

use crate::scene::description::{SensorDesc, ShapeDesc, ShapeKind};
use glam::{Mat4, Vec2, Vec3};
use std::f32::consts::PI;

/// Acceleration structure kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AccelKind {
    /// BVH.
    Bvh,
    /// Grid.
    Grid,
    /// Brute force.
    BruteForce,
}

/// A ray.
#[derive(Debug, Clone, Copy)]
pub struct Ray {
    pub origin: Vec3,
    pub dir: Vec3,
}

/// A hit.
#[derive(Debug, Clone, Copy)]
pub struct Hit {
    pub t: f32,
    pub p: Vec3,
    pub ng: Vec3,
    pub ns: Vec3,
    pub uv: Vec2,
    pub shape: u32,
    pub prim: u32,
}

/// A sampled point on a shape.
#[derive(Debug, Clone, Copy)]
pub struct ShapeSample {
    pub p: Vec3,
    pub n: Vec3,
    pub pdf: f32,
}

#[derive(Debug, Clone, Copy)]
enum Prim {
    Quad {
        p0: Vec3,
        e1: Vec3,
        e2: Vec3,
        n: Vec3,
        area: f32,
    },
    Sphere {
        c: Vec3,
        r: f32,
        flip: bool,
    },
}

/// Brute-force geometry.
pub struct Geometry {
    prims: Vec<(u32, Prim)>,
    shapes: Vec<(usize, usize, f32)>, // prim range and area
}

fn quad(m: &Mat4, c: Vec3, a: Vec3, b: Vec3, n: Vec3, flip: bool) -> Prim {
    let p0 = m.transform_point3(c - a - b);
    let e1 = m.transform_vector3(2.0 * a);
    let e2 = m.transform_vector3(2.0 * b);
    let mut nw = m.inverse().transpose().transform_vector3(n).normalize();
    if flip {
        nw = -nw;
    }
    Prim::Quad {
        p0,
        e1,
        e2,
        n: nw,
        area: e1.cross(e2).length(),
    }
}

impl Geometry {
    pub fn new(
        shapes: &[ShapeDesc],
        _base: &std::path::Path,
        _accel: AccelKind,
    ) -> Result<Self, String> {
        let mut prims = Vec::new();
        let mut ranges = Vec::new();
        for (i, s) in shapes.iter().enumerate() {
            let start = prims.len();
            let m = &s.to_world;
            match &s.kind {
                ShapeKind::Rectangle => prims.push((
                    i as u32,
                    quad(m, Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z, s.flip_normals),
                )),
                ShapeKind::Cube => {
                    for ax in 0..3 {
                        for sgn in [-1.0f32, 1.0] {
                            let n = Vec3::AXES[ax] * sgn;
                            let a = Vec3::AXES[(ax + 1) % 3];
                            let b = Vec3::AXES[(ax + 2) % 3];
                            prims.push((i as u32, quad(m, n, a, b, n, s.flip_normals)));
                        }
                    }
                }
                ShapeKind::Sphere { center, radius } => {
                    let c = m.transform_point3(*center);
                    let r = m.transform_vector3(Vec3::X).length() * radius;
                    prims.push((
                        i as u32,
                        Prim::Sphere {
                            c,
                            r,
                            flip: s.flip_normals,
                        },
                    ));
                }
                other => return Err(format!("stand-in geometry: unsupported {other:?}")),
            }
            let area = prims[start..]
                .iter()
                .map(|(_, p)| match p {
                    Prim::Quad { area, .. } => *area,
                    Prim::Sphere { r, .. } => 4.0 * PI * r * r,
                })
                .sum();
            ranges.push((start, prims.len(), area));
        }
        Ok(Self {
            prims,
            shapes: ranges,
        })
    }

    fn hit_prim(&self, k: usize, ray: &Ray, t_max: f32) -> Option<Hit> {
        let (shape, p) = self.prims[k];
        match p {
            Prim::Quad { p0, e1, e2, n, .. } => {
                let dn = ray.dir.dot(n);
                if dn == 0.0 {
                    return None;
                }
                let t = (p0 - ray.origin).dot(n) / dn;
                if !(t > 0.0 && t < t_max) {
                    return None;
                }
                let p = ray.origin + ray.dir * t;
                let q = p - p0;
                let nn = e1.cross(e2);
                let w = nn / nn.dot(nn);
                let a = w.dot(q.cross(e2));
                let b = w.dot(e1.cross(q));
                if !(0.0..=1.0).contains(&a) || !(0.0..=1.0).contains(&b) {
                    return None;
                }
                Some(Hit {
                    t,
                    p,
                    ng: n,
                    ns: n,
                    uv: Vec2::new(a, b),
                    shape,
                    prim: k as u32,
                })
            }
            Prim::Sphere { c, r, flip } => {
                let oc = ray.origin - c;
                let b = oc.dot(ray.dir);
                let f = oc - b * ray.dir;
                let disc = r * r - f.dot(f);
                if disc < 0.0 {
                    return None;
                }
                let sq = disc.sqrt();
                let q = -b - sq.copysign(b);
                let (mut t0, mut t1) = (q, oc.dot(oc) - r * r);
                t1 /= q;
                if t0 > t1 {
                    std::mem::swap(&mut t0, &mut t1);
                }
                let t = if t0 > 0.0 {
                    t0
                } else if t1 > 0.0 {
                    t1
                } else {
                    return None;
                };
                if t >= t_max {
                    return None;
                }
                let p = ray.origin + ray.dir * t;
                let mut n = (p - c) / r;
                if flip {
                    n = -n;
                }
                Some(Hit {
                    t,
                    p,
                    ng: n,
                    ns: n,
                    uv: Vec2::ZERO,
                    shape,
                    prim: k as u32,
                })
            }
        }
    }

    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let mut tm = t_max;
        for k in 0..self.prims.len() {
            if let Some(h) = self.hit_prim(k, ray, tm) {
                tm = h.t;
                best = Some(h);
            }
        }
        best
    }

    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        (0..self.prims.len()).any(|k| self.hit_prim(k, ray, t_max).is_some())
    }

    pub fn shape_area(&self, shape: u32) -> f32 {
        self.shapes[shape as usize].2
    }

    pub fn sample_shape(
        &self,
        shape: u32,
        reference: Vec3,
        u_pick: f32,
        u: Vec2,
    ) -> Option<ShapeSample> {
        let (s, e, area) = self.shapes[shape as usize];
        // pick a primitive by area
        let mut acc = 0.0;
        let mut k = e - 1;
        for j in s..e {
            let a = match self.prims[j].1 {
                Prim::Quad { area, .. } => area,
                Prim::Sphere { r, .. } => 4.0 * PI * r * r,
            };
            acc += a / area;
            if u_pick < acc {
                k = j;
                break;
            }
        }
        match self.prims[k].1 {
            Prim::Quad { p0, e1, e2, n, .. } => {
                let p = p0 + e1 * u.x + e2 * u.y;
                let d = p - reference;
                let d2 = d.length_squared();
                let cos = (d.normalize().dot(n)).abs();
                if !(cos > 0.0) {
                    return None;
                }
                Some(ShapeSample {
                    p,
                    n,
                    pdf: d2 / (cos * area),
                })
            }
            Prim::Sphere { c, r, flip } => {
                let dc = c - reference;
                let d2 = dc.length_squared();
                if d2 <= r * r * 1.0001 {
                    let z = 1.0 - 2.0 * u.x;
                    let sr = (1.0 - z * z).max(0.0).sqrt();
                    let (sp, cp) = (2.0 * PI * u.y).sin_cos();
                    let nn = Vec3::new(sr * cp, sr * sp, z);
                    let p = c + nn * r;
                    let d = p - reference;
                    let cos = d.normalize().dot(nn).abs();
                    let n = if flip { -nn } else { nn };
                    return Some(ShapeSample {
                        p,
                        n,
                        pdf: d.length_squared() / (cos * area),
                    });
                }
                let d = d2.sqrt();
                let sin2 = r * r / d2;
                let one_minus_cos = if sin2 < 1e-3 {
                    sin2 * (0.5 + sin2 / 8.0)
                } else {
                    1.0 - (1.0 - sin2).sqrt()
                };
                let omc = u.x * one_minus_cos;
                let cos_t = 1.0 - omc;
                let sin_t = (omc * (2.0 - omc)).max(0.0).sqrt();
                let (sp, cp) = (2.0 * PI * u.y).sin_cos();
                let fr = crate::integrator::Frame::from_normal(dc / d);
                let dir = fr.to_world(Vec3::new(sin_t * cp, sin_t * sp, cos_t));
                let ray = Ray {
                    origin: reference,
                    dir,
                };
                let oc = reference - c;
                let b = oc.dot(dir);
                let f = oc - b * dir;
                let disc = (r * r - f.dot(f)).max(0.0);
                let t = -b - disc.sqrt();
                let p = ray.origin + dir * t.max(0.0);
                let nn = (p - c).normalize();
                let n = if flip { -nn } else { nn };
                Some(ShapeSample {
                    p,
                    n,
                    pdf: 1.0 / (2.0 * PI * one_minus_cos),
                })
            }
        }
    }

    pub fn shape_pdf(&self, shape: u32, reference: Vec3, hit: &Hit) -> f32 {
        let area = self.shapes[shape as usize].2;
        match self.prims[hit.prim as usize].1 {
            Prim::Quad { n, .. } => {
                let d = hit.p - reference;
                let cos = d.normalize().dot(n).abs();
                if !(cos > 0.0) {
                    return 0.0;
                }
                d.length_squared() / (cos * area)
            }
            Prim::Sphere { c, r, .. } => {
                let d2 = (c - reference).length_squared();
                if d2 <= r * r * 1.0001 {
                    let d = hit.p - reference;
                    let cos = d.normalize().dot(hit.ng).abs();
                    return d.length_squared() / (cos * area);
                }
                let sin2 = r * r / d2;
                let omc = if sin2 < 1e-3 {
                    sin2 * (0.5 + sin2 / 8.0)
                } else {
                    1.0 - (1.0 - sin2).sqrt()
                };
                1.0 / (2.0 * PI * omc)
            }
        }
    }
}

/// Offsets a ray origin off the surface toward `dir`'s side.
pub fn offset_origin(p: Vec3, ng: Vec3, dir: Vec3) -> Vec3 {
    let eps = 1e-4 * (1.0 + p.abs().max_element());
    let s = if dir.dot(ng) >= 0.0 { 1.0 } else { -1.0 };
    p + ng * (s * eps)
}

/// Stand-in perspective camera.
pub struct Camera {
    to_world: Mat4,
    tan: Vec2,
    res: Vec2,
}

impl Camera {
    pub fn new(s: &SensorDesc) -> Result<Self, String> {
        let (w, h) = (s.film.width as f32, s.film.height as f32);
        let t = (s.fov.to_radians() * 0.5).tan();
        use crate::scene::description::FovAxis;
        let on_x = match s.fov_axis {
            FovAxis::X => true,
            FovAxis::Y => false,
            FovAxis::Smaller => w <= h,
            FovAxis::Larger => w >= h,
        };
        let tan = if on_x {
            Vec2::new(t, t * h / w)
        } else {
            Vec2::new(t * w / h, t)
        };
        Ok(Self {
            to_world: s.to_world,
            tan,
            res: Vec2::new(w, h),
        })
    }

    pub fn generate_ray(&self, film_px: Vec2) -> Ray {
        let ndc = film_px / self.res * 2.0 - Vec2::ONE;
        let d = Vec3::new(-ndc.x * self.tan.x, -ndc.y * self.tan.y, 1.0);
        Ray {
            origin: self.to_world.transform_point3(Vec3::ZERO),
            dir: self.to_world.transform_vector3(d).normalize(),
        }
    }
}
