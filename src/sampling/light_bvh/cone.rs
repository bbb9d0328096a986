//! The bounds of a set of lights in `f64` while building: box, cone of normals (its union
//! is made to contain both cones in the arithmetic that computes it), emission spread,
//! power; and the cost of Conty Estevez & Kulla's surface area orientation heuristic.

use std::f64::consts::PI;

use glam::DVec3;

use super::LightBounds;

/// Extra angle (radians) given to a merged cone beyond what contains both cones.
const CONE_PAD: f64 = 1e-9;

/// The bounds of one light or of a set of lights (`phi == 0`: the empty set).
#[derive(Clone, Copy, Debug)]
pub(super) struct Bound {
    pub min: DVec3,
    pub max: DVec3,
    /// Unit axis of the cone of normals.
    pub axis: DVec3,
    /// `cos θ_o` (`−1`: every direction).
    pub cos_o: f64,
    /// `cos θ_e`.
    pub cos_e: f64,
    /// Total power.
    pub phi: f64,
    pub two_sided: bool,
}

impl Bound {
    /// The empty set: the identity of [`Bound::union`].
    pub const EMPTY: Bound = Bound {
        min: DVec3::INFINITY,
        max: DVec3::NEG_INFINITY,
        axis: DVec3::Z,
        cos_o: 1.0,
        cos_e: 1.0,
        phi: 0.0,
        two_sided: false,
    };

    /// The bounds of a validated light (its axis normalised; any axis for a full sphere).
    pub fn from_light(l: &LightBounds) -> Self {
        let cos_o = f64::from(l.cos_theta_o);
        let axis = l.axis.as_dvec3();
        let (axis, cos_o) = if cos_o <= -1.0 {
            (DVec3::Z, -1.0)
        } else {
            (axis / axis.length(), cos_o)
        };
        Self {
            min: l.min.as_dvec3(),
            max: l.max.as_dvec3(),
            axis,
            cos_o,
            cos_e: f64::from(l.cos_theta_e),
            phi: f64::from(l.power),
            two_sided: l.two_sided,
        }
    }

    /// The centre of the box.
    pub fn centroid(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }

    /// Bounds of both sets: the box union, a cone containing both cones, the wider `θ_e`,
    /// the summed power, two-sided if either is.
    pub fn union(&self, o: &Bound) -> Bound {
        if self.phi == 0.0 {
            return *o;
        }
        if o.phi == 0.0 {
            return *self;
        }
        let (axis, cos_o) = cone_union((self.axis, self.cos_o), (o.axis, o.cos_o));
        Bound {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
            axis,
            cos_o,
            cos_e: self.cos_e.min(o.cos_e),
            phi: self.phi + o.phi,
            two_sided: self.two_sided || o.two_sided,
        }
    }

    /// The SAOH cost of these bounds as one child of a split along `dim` of a node whose
    /// box has the diagonal `diag`: `Φ · M_Ω · K_r · A` (pbrt-v4's `EvaluateCost`), with the
    /// box's extents raised to `min_extent` so that point lights have an area.
    pub fn cost(&self, diag: DVec3, dim: usize, min_extent: f64) -> f64 {
        let e = (self.max - self.min).max(DVec3::splat(min_extent));
        let area = 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
        let k_r = diag.max_element() / diag[dim];
        self.phi * orientation_measure(self.cos_o, self.cos_e) * k_r * area
    }
}

/// `M_Ω`: the solid angle of the normals' cone plus, beyond it out to `θ_o + θ_e`, the
/// cosine-weighted measure of the emission (Conty Estevez & Kulla 2018, eq. 1).
pub(super) fn orientation_measure(cos_o: f64, cos_e: f64) -> f64 {
    let theta_o = cos_o.clamp(-1.0, 1.0).acos();
    let theta_e = cos_e.clamp(-1.0, 1.0).acos();
    let theta_w = (theta_o + theta_e).min(PI);
    let sin_o = (1.0 - cos_o * cos_o).max(0.0).sqrt();
    2.0 * PI * (1.0 - cos_o)
        + PI / 2.0
            * (2.0 * theta_w * sin_o - (theta_o - 2.0 * theta_w).cos() - 2.0 * theta_o * sin_o
                + cos_o)
}

/// The angle between unit vectors, accurate at 0 and π.
pub(super) fn angle_between(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// The smallest cone (pbrt-v4's `Union(DirectionCone, DirectionCone)`) containing the cones
/// `(axis, cos θ)` `a` and `b`; the angle is then widened until both cones lie inside it as
/// computed (plus [`CONE_PAD`]), so rounding never makes it too narrow.
pub(super) fn cone_union(a: (DVec3, f64), b: (DVec3, f64)) -> (DVec3, f64) {
    const FULL: (DVec3, f64) = (DVec3::Z, -1.0);
    if a.1 <= -1.0 || b.1 <= -1.0 {
        return FULL;
    }
    let theta_a = a.1.clamp(-1.0, 1.0).acos();
    let theta_b = b.1.clamp(-1.0, 1.0).acos();
    let theta_d = angle_between(a.0, b.0);
    if (theta_d + theta_b).min(PI) <= theta_a {
        return a;
    }
    if (theta_d + theta_a).min(PI) <= theta_b {
        return b;
    }
    let theta_o = 0.5 * (theta_a + theta_d + theta_b);
    if theta_o >= PI {
        return FULL;
    }
    let k = a.0.cross(b.0);
    let len = k.length();
    if len.is_nan() || len <= 0.0 {
        return FULL;
    }
    let k = k / len;
    let theta_r = theta_o - theta_a;
    let w = a.0 * theta_r.cos() + k.cross(a.0) * theta_r.sin();
    let w = w / w.length();
    let theta = theta_o
        .max(angle_between(w, a.0) + theta_a)
        .max(angle_between(w, b.0) + theta_b)
        + CONE_PAD;
    if theta >= PI {
        FULL
    } else {
        (w, theta.cos())
    }
}
