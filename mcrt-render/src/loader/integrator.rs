//! `<integrator>`: `path`, `direct`, `bdpt`, `mlt`, `ptracer` and `guided`, read through their
//! definitions (`param_defs::integrator`), and `moment` around `path` or `direct`.

use super::context::{Ctx, Res};
use super::props::Props;
use super::tree::Elem;
use super::{no_objects, plugin_type};
use crate::description::{
    BdptParams, DirectParams, GuidedParams, IntegratorDesc, MltParams, MomentDesc, PathParams,
    PtracerParams,
};
use crate::scene_error::SceneErrorKind;

/// What an `<integrator>` element says.
pub(crate) struct ReadIntegrator {
    pub integrator: IntegratorDesc,
    pub moment: Option<MomentDesc>,
}

/// The integrator types that read their own parameters.
const PLAIN: &[&str] = &["path", "direct", "bdpt", "mlt", "ptracer", "guided"];

/// The name Mitsuba 3 gives the first nested object that has no `name` attribute.
const FIRST_UNNAMED: &str = "_arg_0";

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

/// `moment`: exactly one nested `path` or `direct`, whose image it keeps; the mean and second
/// moment channels are added when the film is written. Several nested integrators (Mitsuba
/// 3 runs each on the same camera ray, one after the other on one sampler stream, and keeps
/// the first one's image) are refused at the second: the render loop runs one estimator per
/// sample (docs/scene-format.md, "The `moment` integrator around another").
fn read_moment(ctx: &Ctx, e: &Elem) -> Res<ReadIntegrator> {
    let p = Props::new(ctx, e)?;
    let objects = p.objects.clone();
    let mut nested = objects.iter().copied();
    let (Some(inner), None) = (nested.next(), nested.next()) else {
        let (at, what) = match objects.get(1) {
            Some(second) => (
                *second,
                "; several, which Mitsuba 3 runs one after the other on each camera ray, are \
                 not supported (the render loop runs one estimator per sample)",
            ),
            None => (e, ""),
        };
        return Err(ctx.err(
            at,
            SceneErrorKind::Unsupported(format!(
                "integrator \"moment\" needs exactly one nested <integrator>{what}"
            )),
        ));
    };
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
    let integrator = read_plain(ctx, inner, inner_ty)?;
    p.finish()?;
    let name = inner.attr("name").unwrap_or(FIRST_UNNAMED).to_string();
    Ok(ReadIntegrator {
        integrator,
        moment: Some(MomentDesc { name }),
    })
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
