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
