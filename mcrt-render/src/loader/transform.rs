//! `<transform>` elements: `lookat`, `matrix`, `translate`, `rotate` and `scale`, composed
//! in Mitsuba's order (each later operation is applied after the earlier ones, i.e.
//! multiplied from the left).

use super::context::{Ctx, Res};
use super::error::SceneErrorKind;
use super::tree::Elem;
use super::values::{parse_float, parse_matrix, parse_triple, parse_vec3_exact};
use glam::{Mat4, Vec3, Vec4};

/// The matrix of a `<transform>` element.
pub(crate) fn read_transform(ctx: &Ctx, e: &Elem) -> Res<Mat4> {
    check_attrs(ctx, e, &["name"], &["name"])?;
    let mut m = Mat4::IDENTITY;
    for op in &e.children {
        let step = match op.tag.as_str() {
            "lookat" => lookat(ctx, op)?,
            "matrix" => {
                check_attrs(ctx, op, &["value"], &["value"])?;
                let v = op.attr("value").unwrap_or("");
                parse_matrix(v).map_err(|m| ctx.err(op, SceneErrorKind::Malformed(m)))?
            }
            "translate" => Mat4::from_translation(xyz(ctx, op, &[], 0.0)?),
            "scale" => Mat4::from_scale(xyz(ctx, op, &[], 1.0)?),
            "rotate" => rotate(ctx, op)?,
            other => {
                return Err(ctx.err(
                    op,
                    SceneErrorKind::Misplaced(format!(
                        "<{other}> inside <transform> (expected lookat, matrix, translate, \
                         rotate or scale)"
                    )),
                ))
            }
        };
        m = step * m;
    }
    crate::validate::transform("transform", &m).map_err(|i| {
        ctx.err(
            e,
            SceneErrorKind::InvalidValue(format!("the transform {}", i.message)),
        )
    })?;
    Ok(m)
}

/// Checks that every attribute is in `allowed` and every one of `required` is present.
pub(crate) fn check_attrs(ctx: &Ctx, e: &Elem, allowed: &[&str], required: &[&str]) -> Res<()> {
    for (n, _) in &e.attrs {
        if !allowed.contains(&n.as_str()) {
            return Err(ctx.err(e, SceneErrorKind::UnknownAttribute(n.clone())));
        }
    }
    for r in required {
        if e.attr(r).is_none() {
            return Err(ctx.err(e, SceneErrorKind::MissingAttribute(r.to_string())));
        }
    }
    Ok(())
}

/// The vector of a `translate`, `scale`, `rotate`, `point` or `vector` element: either
/// `value` (one number, splat, or three) or any of `x`, `y`, `z` (missing ones are
/// `default`). `extra` lists the element's other allowed attributes.
pub(crate) fn xyz(ctx: &Ctx, e: &Elem, extra: &[&str], default: f32) -> Res<Vec3> {
    let mut allowed = vec!["value", "x", "y", "z"];
    allowed.extend_from_slice(extra);
    check_attrs(ctx, e, &allowed, &[])?;
    let comps = [e.attr("x"), e.attr("y"), e.attr("z")];
    let malformed = |m: String| ctx.err(e, SceneErrorKind::Malformed(m));
    if let Some(v) = e.attr("value") {
        if comps.iter().any(Option::is_some) {
            return Err(ctx.err(
                e,
                SceneErrorKind::Misplaced("can't mix \"value\" with \"x\"/\"y\"/\"z\"".into()),
            ));
        }
        return parse_triple(v, "value").map_err(malformed);
    }
    if comps.iter().all(Option::is_none) {
        return Err(ctx.err(e, SceneErrorKind::MissingAttribute("x".into())));
    }
    let mut out = [default; 3];
    for (o, c) in out.iter_mut().zip(comps) {
        if let Some(c) = c {
            *o = parse_float(c).map_err(malformed)?;
        }
    }
    Ok(Vec3::from(out))
}

fn rotate(ctx: &Ctx, e: &Elem) -> Res<Mat4> {
    let axis = xyz(ctx, e, &["angle"], 0.0)?;
    let angle = e
        .attr("angle")
        .ok_or_else(|| ctx.err(e, SceneErrorKind::MissingAttribute("angle".into())))?;
    let angle = parse_float(angle).map_err(|m| ctx.err(e, SceneErrorKind::Malformed(m)))?;
    let axis = axis.try_normalize().ok_or_else(|| {
        ctx.err(
            e,
            SceneErrorKind::InvalidValue("the rotation axis is zero".into()),
        )
    })?;
    Ok(Mat4::from_axis_angle(axis, angle.to_radians()))
}

fn lookat(ctx: &Ctx, e: &Elem) -> Res<Mat4> {
    check_attrs(ctx, e, &["origin", "target", "up"], &["origin", "target"])?;
    let get = |name: &str| {
        parse_vec3_exact(e.attr(name).unwrap_or(""), name)
            .map_err(|m| ctx.err(e, SceneErrorKind::Malformed(m)))
    };
    let origin = get("origin")?;
    let target = get("target")?;
    let up = match e.attr("up") {
        Some(_) => get("up")?,
        None => Vec3::ZERO,
    };
    look_at(origin, target, up).ok_or_else(|| {
        ctx.err(
            e,
            SceneErrorKind::InvalidValue(
                "invalid lookat (origin = target, or up parallel to the view direction)".into(),
            ),
        )
    })
}

/// Mitsuba 3's look-at camera-to-world matrix: its columns are (left, up′, dir, origin)
/// with dir = normalize(target − origin), left = normalize(up × dir), up′ = dir × left.
/// A zero `up` is replaced by a vector perpendicular to dir, as Mitsuba does. Returns
/// `None` when origin = target or `up` is parallel to the view direction.
///
/// ```
/// use mcrt_render::loader::look_at;
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
