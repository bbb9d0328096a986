//! Matrices that place things in a scene, shared by the loader's `<lookat>` and the
//! built-in Cornell box: Mitsuba 3's [`look_at`].

use glam::{Mat4, Vec3, Vec4};

/// Mitsuba 3's look-at camera-to-world matrix: its columns are (left, up′, dir, origin)
/// with dir = normalize(target − origin), left = normalize(up × dir), up′ = dir × left.
/// A zero `up` is replaced by a vector perpendicular to dir, as Mitsuba does. Returns
/// `None` when origin = target or `up` is parallel to the view direction.
///
/// ```
/// use mcrt_render::transform::look_at;
/// use mcrt::glam::Vec3;
/// let m = look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y).unwrap();
/// // The camera looks down its +z axis, and its +x axis points to the image's left.
/// assert!((m.transform_vector3(Vec3::Z) - Vec3::NEG_Z).length() < 1e-6);
/// assert!((m.transform_vector3(Vec3::X) - Vec3::NEG_X).length() < 1e-6);
/// ```
pub fn look_at(origin: Vec3, target: Vec3, up: Vec3) -> Option<Mat4> {
    let dir = (target - origin).try_normalize()?;
    let up = if up.length_squared() == 0.0 {
        perpendicular(dir)
    } else {
        up
    };
    let left = up.cross(dir).try_normalize()?;
    let new_up = dir.cross(left);
    let m = Mat4::from_cols(
        left.extend(0.0),
        new_up.extend(0.0),
        dir.extend(0.0),
        Vec4::new(origin.x, origin.y, origin.z, 1.0),
    );
    m.is_finite().then_some(m)
}

/// The first tangent of the branchless orthonormal basis around the unit vector `n`, as
/// Mitsuba's `coordinate_system` builds it. Duff et al. 2017, "Building an Orthonormal
/// Basis, Revisited", JCGT 6(1).
fn perpendicular(n: Vec3) -> Vec3 {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn perpendicular_is_unit_and_orthogonal() {
        for n in [Vec3::Z, -Vec3::Z, Vec3::new(0.6, 0.0, 0.8), Vec3::X] {
            let t = perpendicular(n);
            assert!(t.is_finite());
            assert!((t.length() - 1.0).abs() < 1e-6);
            assert!(t.dot(n).abs() < 1e-6);
        }
    }
}
