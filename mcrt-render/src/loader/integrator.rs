//! `<integrator>`: `path`, `direct`, `bdpt`, `mlt`, `ptracer` and `guided`, read through their
//! definitions (`param_defs::integrator`), and `moment` around one or more `path` or `direct`.

use super::context::{Ctx, Res};
use super::props::Props;
use super::tree::Elem;
use super::{no_objects, plugin_type};
use crate::description::{
    BdptParams, Checked, DirectParams, GuidedParams, IntegratorDesc, MltParams, MomentDesc,
    NestedIntegrator, PathParams, PtracerParams,
};
use crate::scene_error::SceneErrorKind;

/// What an `<integrator>` element says.
pub(crate) struct ReadIntegrator {
    pub integrator: IntegratorDesc,
    pub moment: Option<MomentDesc>,
}

/// The integrator types that read their own parameters.
const PLAIN: &[&str] = &["path", "direct", "bdpt", "mlt", "ptracer", "guided"];

/// The prefix of the names Mitsuba 3 gives nested objects without a `name` attribute:
/// `_arg_0`, `_arg_1`, … counting those objects.
const UNNAMED: &str = "_arg_";

/// Reads an `<integrator>` element: a plain integrator, or `moment` around one.
pub(crate) fn read_integrator(ctx: &Ctx, e: &Elem) -> Res<ReadIntegrator> {
    let ty = plugin_type(ctx, e)?;
    match ty {
        "moment" => read_moment(ctx, e),
        // Mitsuba 3's other integrators that wrap one: named, with what we do support.
        "aov" | "stokes" => Err(ctx.err(
            e,
            SceneErrorKind::Unsupported(format!(
                "integrator \"{ty}\" (of the integrators that wrap another, only \"moment\" \
                 is supported)"
            )),
        )),
        _ => read_plain(ctx, e, ty).map(|integrator| ReadIntegrator {
            integrator,
            moment: None,
        }),
    }
}

/// `moment`: one or more nested `path` or `direct` integrators. The first one's image is the
/// render's; each adds its mean and second-moment channels, named after its `name`
/// attribute or `_arg_N` (`N` counting the unnamed ones), as Mitsuba 3 does
/// (docs/scene-format.md, "The `moment` integrator around another").
fn read_moment(ctx: &Ctx, e: &Elem) -> Res<ReadIntegrator> {
    let p = Props::new(ctx, e)?;
    let objects = p.objects.clone();
    let mut nested: Vec<(String, IntegratorDesc, &Elem)> = Vec::new();
    let mut unnamed = 0;
    for inner in objects.iter().copied() {
        let integrator = read_nested(ctx, inner)?;
        let name = match inner.attr("name") {
            Some(n) => n.to_string(),
            None => {
                unnamed += 1;
                format!("{UNNAMED}{}", unnamed - 1)
            }
        };
        if let Some((_, _, first)) = nested.iter().find(|(n, _, _)| *n == name) {
            return Err(ctx.err(
                inner,
                SceneErrorKind::InvalidValue(format!(
                    "a second integrator named \"{name}\" in \"moment\" (the first is on line \
                     {}): its channels would have the same names",
                    first.line
                )),
            ));
        }
        nested.push((name, integrator, inner));
    }
    p.finish()?;
    let mut nested = nested.into_iter();
    let Some((name, integrator, _)) = nested.next() else {
        return Err(ctx.err(
            e,
            SceneErrorKind::Unsupported(
                "integrator \"moment\" needs at least one nested <integrator>".into(),
            ),
        ));
    };
    let more = nested
        .map(|(name, d, inner)| {
            let integrator = Checked::new(d)
                .map_err(|i| ctx.err(inner, SceneErrorKind::InvalidValue(i.to_string())))?;
            Ok(NestedIntegrator { name, integrator })
        })
        .collect::<Res<Vec<_>>>()?;
    Ok(ReadIntegrator {
        integrator,
        moment: Some(MomentDesc { name, more }),
    })
}

/// One integrator nested in `moment`: `path` or `direct`, which sample per pixel.
fn read_nested(ctx: &Ctx, inner: &Elem) -> Res<IntegratorDesc> {
    if inner.tag != "integrator" {
        return Err(ctx.err(
            inner,
            SceneErrorKind::Misplaced(format!(
                "<{}> cannot be nested in integrator \"moment\"",
                inner.tag
            )),
        ));
    }
    let inner_ty = plugin_type(ctx, inner)?;
    if !matches!(inner_ty, "path" | "direct") {
        return Err(ctx.err(
            inner,
            SceneErrorKind::Unsupported(format!(
                "integrator \"{inner_ty}\" inside \"moment\" (only \"path\" and \"direct\", \
                 which sample per pixel)"
            )),
        ));
    }
    read_plain(ctx, inner, inner_ty)
}

/// One of the [`PLAIN`] integrators, each parameter read through its definition.
fn read_plain(ctx: &Ctx, e: &Elem, ty: &str) -> Res<IntegratorDesc> {
    // Before the nested objects are looked at, so that the error names this element.
    if !PLAIN.contains(&ty) {
        return Err(unknown(ctx, e, ty));
    }
    let mut p = Props::new(ctx, e)?;
    no_objects(ctx, &p)?;
    let desc = match ty {
        "path" => IntegratorDesc::Path(PathParams::read(&mut p)?),
        "direct" => IntegratorDesc::Direct(DirectParams::read(&mut p)?),
        "bdpt" => IntegratorDesc::Bdpt(BdptParams::read(&mut p)?),
        "mlt" => IntegratorDesc::Mlt(MltParams::read(&mut p)?),
        "ptracer" => IntegratorDesc::Ptracer(PtracerParams::read(&mut p)?),
        "guided" => IntegratorDesc::Guided(GuidedParams::read(&mut p)?),
        other => return Err(unknown(ctx, e, other)),
    };
    p.finish()?;
    Ok(desc)
}

fn unknown(ctx: &Ctx, e: &Elem, ty: &str) -> super::SceneError {
    ctx.err(
        e,
        SceneErrorKind::UnknownPlugin {
            category: "integrator".into(),
            plugin_type: ty.into(),
        },
    )
}
