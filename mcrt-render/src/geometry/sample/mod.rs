//! Sampling points on shapes (for area lights), with densities per unit solid angle at a
//! reference point, and the matching pdf of a given point.
//!
//! Strategies (see `docs/geometry.md`):
//! - **sphere**, reference outside: a direction uniform in the cone the sphere subtends
//!   ([`UniformCone`](mcrt::sampling::warp::UniformCone)), pdf 1/Ω, and the nearer
//!   intersection of that direction with the sphere. Reference inside (or the cone too
//!   narrow for f32): uniform by area.
//! - **triangle meshes and cubes**: a triangle by its area
//!   ([`AliasTable`](mcrt::sampling::distribution::AliasTable)), then a point on it
//!   (spherical-triangle sampling where the warp allows, else uniform by area).
//! - **rectangles**: the parallelogram as a whole (spherical-rectangle sampling where the
//!   warp allows, else uniform by area).
//! - **disks**: uniform by area (Shirley–Chiu concentric map through `to_world`).
//!
//! Area densities become solid-angle ones as `p_ω = p_A · d² / |cos θ'|` (`d` the distance,
//! `θ'` the angle at the sampled point between its normal and the way back).

mod light_bounds;
mod mesh;
pub(super) mod rectangle;
mod sphere;

pub(crate) use mesh::front_normal;
pub(crate) use rectangle::RectangleSampler;

use super::data::ShapeData;
use super::{Geometry, ShapeSample};
use mcrt::integrator::SurfacePoint;

/// How [`Geometry::sample_shape`] samples triangles and rectangles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ShapeSampling {
    /// Per reference point: by solid angle where the shape is near, uniformly by area where
    /// it is far (the default). "Near" is a distance to the shape's centre below 1.5
    /// times its diagonal (a triangle's longest edge): there the area
    /// density varies over the shape by more than a factor of about 1.2 and the spherical
    /// warp repays its cost; farther away, area sampling gives almost the same variance at
    /// a fraction of the cost. Sampling and density make the same choice at the same point.
    #[default]
    Auto,
    /// By solid angle where the spherical warps allow (lowest variance, several times the
    /// cost of area sampling per sample).
    SolidAngle,
    /// Uniformly by area, converted to solid angle (as Mitsuba 3 samples rectangles and
    /// meshes): several times cheaper per sample, more variance close to large lights.
    /// Spheres keep cone sampling, which is cheap.
    Area,
}

/// The distance, in diagonals of a rectangle (longest edges of a triangle), below which
/// [`ShapeSampling::Auto`] samples the shape by solid angle. At 1.5 diagonals straight
/// above a square the area density varies by a factor of 1.1 over it
/// (`(1 + 1/(2·1.5²·2))^{3/2}`; derivation in `docs/geometry.md`, "Light sampling by
/// distance").
pub(crate) const NEAR_FACTOR: f32 = 1.5;

impl ShapeSampling {
    /// Whether a shape is sampled by solid angle; for `Auto`, `distances` gives the squared
    /// distance from the reference point to the shape's centre and its squared size
    /// (diagonal², or longest edge²), computed only in that case.
    #[inline]
    pub(crate) fn by_solid_angle(self, distances: impl FnOnce() -> (f32, f32)) -> bool {
        match self {
            Self::SolidAngle => true,
            Self::Area => false,
            Self::Auto => {
                let (dist2, size2) = distances();
                dist2 < NEAR_FACTOR * NEAR_FACTOR * size2
            }
        }
    }
}

use crate::accel::Aabb;
use glam::{Vec2, Vec3};
use mcrt::sampling::warp::{UniformDiskConcentric, UniformSphere, Warp};
use std::f32::consts::PI;

/// `p_A · d² / |cos θ'|`: the solid-angle density at `reference` of an area density
/// `pdf_area` at point `p` with normal `n`; `None` where it is infinite or undefined.
#[inline]
pub(crate) fn area_to_solid_angle(pdf_area: f32, reference: Vec3, p: Vec3, n: Vec3) -> Option<f32> {
    let d = reference - p;
    let dist2 = d.length_squared();
    let cos = n.dot(d).abs() / dist2.sqrt();
    let pdf = pdf_area * dist2 / cos;
    (pdf.is_finite() && pdf > 0.0).then_some(pdf)
}

impl Geometry {
    /// This geometry with the given strategy for triangles and rectangles.
    #[must_use]
    pub fn with_shape_sampling(mut self, sampling: ShapeSampling) -> Self {
        self.shape_sampling = sampling;
        self
    }

    /// The strategy in use for triangles and rectangles.
    pub fn shape_sampling(&self) -> ShapeSampling {
        self.shape_sampling
    }

    /// The surface area of shape `shape` (world space); 0 for an index out of range.
    pub fn shape_area(&self, shape: u32) -> f32 {
        match self.own_shape(shape) {
            Some(ShapeData::Mesh(m)) => m.area,
            Some(ShapeData::Sphere { radius, .. }) => 4.0 * PI * radius * radius,
            Some(ShapeData::Disk(d)) => d.area,
            Some(ShapeData::Cylinder(c)) => c.area(),
            Some(ShapeData::Instance) | None => 0.0,
        }
    }

    /// The sampler of shape `shape` if it is a `rectangle` (sampled as a whole): the one
    /// [`Geometry::sample_shape`] uses, for a light to call without the shape lookup.
    pub(crate) fn rectangle_sampler(&self, shape: u32) -> Option<&RectangleSampler> {
        match self.own_shape(shape)? {
            ShapeData::Mesh(m) => m.rectangle.as_ref(),
            _ => None,
        }
    }

    /// A sphere bounding shape `shape` (centre, radius); `None` for an index out of range
    /// or a mesh without vertices.
    pub(crate) fn shape_bounding_sphere(&self, shape: u32) -> Option<(Vec3, f32)> {
        match self.own_shape(shape)? {
            ShapeData::Mesh(m) => {
                let b = Aabb::from_points(&m.positions);
                (!b.is_empty()).then(|| (b.center(), 0.5 * b.extent().length()))
            }
            &ShapeData::Sphere { center, radius, .. } => Some((center, radius)),
            // The disk is the image of the unit disk: c + cos φ·a + sin φ·b, so its points
            // lie within √(|a|² + |b|²) of c (Cauchy–Schwarz).
            ShapeData::Disk(d) => Some((
                d.to_world.translation.into(),
                (d.to_world.matrix3.x_axis.length_squared()
                    + d.to_world.matrix3.y_axis.length_squared())
                .sqrt(),
            )),
            ShapeData::Instance => None,
            ShapeData::Cylinder(c) => Some(c.bounding_sphere()),
        }
    }

    /// Whether [`Geometry::sample_shape`] reads `u_pick` for shape `shape`: only triangle
    /// meshes and cubes do (to choose a triangle); rectangles, spheres and disks ignore it.
    pub(crate) fn shape_reads_pick(&self, shape: u32) -> bool {
        matches!(
            self.own_shape(shape),
            Some(ShapeData::Mesh(m)) if m.rectangle.is_none()
        )
    }

    /// A point on shape `shape` for lighting `reference`: `u_pick` chooses a triangle of a
    /// mesh or cube (ignored otherwise), `u` the point. `pdf` is per unit solid angle at
    /// `reference`, by the strategies in the module docs of `geometry`. `None` when the
    /// shape has no area, the index is out of range, or the density is infinite (a point
    /// edge-on or at `reference`).
    pub fn sample_shape(
        &self,
        shape: u32,
        reference: Vec3,
        u_pick: f32,
        u: Vec2,
    ) -> Option<ShapeSample> {
        match self.own_shape(shape)? {
            ShapeData::Mesh(m) => mesh::sample(m, self.shape_sampling, reference, u_pick, u),
            &ShapeData::Sphere {
                center,
                radius,
                flip,
            } => sphere::sample(center, radius, flip, reference, u),
            ShapeData::Disk(d) => {
                let q = UniformDiskConcentric.sample(u);
                let p = d.to_world.transform_point3(q.extend(0.0));
                let pdf = area_to_solid_angle(1.0 / d.area, reference, p, d.normal)?;
                Some(ShapeSample {
                    p,
                    n: d.normal,
                    pdf,
                })
            }
            ShapeData::Instance => None,
            ShapeData::Cylinder(c) => {
                let s = c.sample_area(u);
                let pdf = area_to_solid_angle(s.pdf, reference, s.p, s.n)?;
                Some(ShapeSample { pdf, ..s })
            }
        }
    }

    /// A point uniformly distributed by area over shape `shape` (`u_pick` chooses a
    /// triangle of a mesh by its area, `u` the point): the emission positions of area
    /// lights. `pdf` is per unit area, `1/area`. `None` for a shape without area or an
    /// index out of range.
    pub fn sample_area(&self, shape: u32, u_pick: f32, u: Vec2) -> Option<ShapeSample> {
        let area = self.shape_area(shape);
        if !(area > 0.0 && area.is_finite()) {
            return None;
        }
        let (p, n) = match self.own_shape(shape)? {
            ShapeData::Mesh(m) => mesh::sample_area(m, u_pick, u)?,
            &ShapeData::Sphere {
                center,
                radius,
                flip,
            } => {
                let n = UniformSphere.sample(u);
                (center + radius * n, if flip { -n } else { n })
            }
            ShapeData::Disk(d) => {
                let q = UniformDiskConcentric.sample(u);
                (d.to_world.transform_point3(q.extend(0.0)), d.normal)
            }
            ShapeData::Instance => return None,
            ShapeData::Cylinder(c) => {
                let s = c.sample_area(u);
                (s.p, s.n)
            }
        };
        p.is_finite().then_some(ShapeSample {
            p,
            n,
            pdf: 1.0 / area,
        })
    }

    /// The density per unit solid angle at `reference` with which
    /// [`Geometry::sample_shape`] produces the point of `hit` (a hit on shape `shape`, as
    /// returned by [`Geometry::intersect`]); 0 if it never does.
    pub fn shape_pdf(&self, shape: u32, reference: Vec3, hit: &SurfacePoint) -> f32 {
        if hit.shape != shape {
            return 0.0;
        }
        self.shape_pdf_at(shape, reference, (hit.p, hit.ng, hit.prim))
    }

    /// [`Geometry::shape_pdf`] at point `p` with front normal `ng` of primitive `prim` of
    /// shape `shape` (what the estimators' surface points carry).
    pub(crate) fn shape_pdf_at(&self, shape: u32, reference: Vec3, at: (Vec3, Vec3, u32)) -> f32 {
        let pdf = match self.own_shape(shape) {
            Some(ShapeData::Mesh(m)) => mesh::pdf(m, self.shape_sampling, reference, at),
            Some(&ShapeData::Sphere { center, radius, .. }) => {
                sphere::pdf(center, radius, reference, at.0)
            }
            Some(ShapeData::Disk(d)) => area_to_solid_angle(1.0 / d.area, reference, at.0, at.1),
            Some(ShapeData::Cylinder(c)) => {
                area_to_solid_angle(1.0 / c.area(), reference, at.0, at.1)
            }
            Some(ShapeData::Instance) | None => None,
        };
        pdf.unwrap_or(0.0)
    }
}

#[cfg(test)]
mod tests {
    use crate::accel::AccelKind;
    use crate::description::{ShapeDesc, ShapeKind};
    use crate::geometry::Geometry;
    use glam::{Mat4, Vec3};

    #[test]
    fn bounding_spheres_hold_their_shapes() {
        let mut rect = ShapeDesc::new(ShapeKind::Rectangle);
        rect.to_world = Mat4::from_translation(Vec3::new(0.0, 0.0, -2.0))
            * Mat4::from_scale(Vec3::new(3.0, 1.0, 1.0));
        let sphere = ShapeDesc::new(ShapeKind::Sphere {
            center: Vec3::new(1.0, 2.0, 3.0),
            radius: 0.5,
        });
        let mut disk = ShapeDesc::new(ShapeKind::Disk);
        disk.to_world =
            Mat4::from_translation(Vec3::X) * Mat4::from_scale(Vec3::new(2.0, 1.0, 1.0));
        let geo = Geometry::new(&[rect, sphere, disk], None, AccelKind::Bvh).unwrap();
        let expect = [
            (Vec3::new(0.0, 0.0, -2.0), 10f32.sqrt()), // corners (±3, ±1)
            (Vec3::new(1.0, 2.0, 3.0), 0.5),
            (Vec3::X, 5f32.sqrt()), // √(2² + 1²) bounds the ellipse's semi-axes 2 and 1
        ];
        for (i, (c, r)) in expect.into_iter().enumerate() {
            let (centre, radius) = geo.shape_bounding_sphere(i as u32).unwrap();
            assert!(centre.is_finite() && radius.is_finite(), "shape {i}");
            assert!((centre - c).length() < 1e-5, "shape {i}: {centre}");
            assert!((radius - r).abs() < 1e-5, "shape {i}: {radius}");
        }
        assert!(geo.shape_bounding_sphere(3).is_none());
    }
}
