//! `<transform>` elements: `lookat`, `matrix`, `translate`, `rotate` and `scale`, composed
//! in Mitsuba's order (each later operation is applied after the earlier ones, i.e.
//! multiplied from the left).

use super::context::{Ctx, Res};
use super::tree::Elem;
use super::values::{parse_float, parse_matrix, parse_triple, parse_vec3_exact};
use crate::scene_error::SceneErrorKind;
use crate::transform::look_at;
use glam::{Mat4, Vec3};

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

/// Largest distance from 1 of an axis length taken as unit (a few f32 roundings of a
/// unit vector written in decimals).
const UNIT_AXIS_TOLERANCE: f32 = 1e-5;

/// `<rotate>` about `axis` by `angle` degrees. A unit axis (within
/// [`UNIT_AXIS_TOLERANCE`]) gives a rotation. Any other axis is used as given, as Mitsuba
/// 3.9.1 does (its `rotate` does not normalise), which is not a pure rotation: the loader
/// warns.
fn rotate(ctx: &Ctx, e: &Elem) -> Res<Mat4> {
    let axis = xyz(ctx, e, &["angle"], 0.0)?;
    let angle = e
        .attr("angle")
        .ok_or_else(|| ctx.err(e, SceneErrorKind::MissingAttribute("angle".into())))?;
    let angle = parse_float(angle).map_err(|m| ctx.err(e, SceneErrorKind::Malformed(m)))?;
    if axis == Vec3::ZERO {
        return Err(ctx.err(
            e,
            SceneErrorKind::InvalidValue("the rotation axis is zero".into()),
        ));
    }
    let length = axis.length();
    if (length - 1.0).abs() <= UNIT_AXIS_TOLERANCE {
        return Ok(Mat4::from_axis_angle(axis.normalize(), angle.to_radians()));
    }
    ctx.warn(
        e,
        format!(
            "the rotation axis ({}, {}, {}) is not unit length (length {length}); as in \
             Mitsuba 3 it is used as given, so the transform is not a pure rotation \
             (normalise the axis for one)",
            axis.x, axis.y, axis.z
        ),
    );
    Ok(axis_angle_unnormalised(axis, angle))
}

/// Rodrigues' rotation matrix `c·I + s·[a]× + (1 − c)·a aᵀ` evaluated with the axis `a` as
/// given (not normalised), in f64, as Mitsuba 3.9.1's `Transform::rotate` (Dr.Jit's
/// `rotate`) computes it.
fn axis_angle_unnormalised(axis: Vec3, degrees: f32) -> Mat4 {
    let a = axis.as_dvec3();
    let (s, c) = f64::from(degrees).to_radians().sin_cos();
    let k = 1.0 - c;
    let m = glam::DMat3::from_cols(
        glam::DVec3::new(
            a.x * a.x * k + c,
            a.x * a.y * k + a.z * s,
            a.x * a.z * k - a.y * s,
        ),
        glam::DVec3::new(
            a.x * a.y * k - a.z * s,
            a.y * a.y * k + c,
            a.y * a.z * k + a.x * s,
        ),
        glam::DVec3::new(
            a.x * a.z * k + a.y * s,
            a.y * a.z * k - a.x * s,
            a.z * a.z * k + c,
        ),
    );
    Mat4::from_mat3(m.as_mat3())
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
