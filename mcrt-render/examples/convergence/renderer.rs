//! The one file that calls the renderer: [`mcrt_render::render::Renderer`] with the strategy
//! as [`mcrt::integrator::Strategy`] and the sampler as the scene's
//! [`mcrt_render::description::SamplerKind`]; for the integrator study, with the integrator
//! as [`mcrt_render::description::IntegratorKind`].
//!
//! Whether the renderer honours the scene's sampler kind is checked at run time: a 1-spp
//! render with the sampler must differ from one with `independent` at the same seed. A
//! sampler that makes no difference is reported as skipped instead of being plotted under a
//! name it does not deserve.

use crate::image::Rgb;
use crate::render_study::{Backend, SceneSpec};
use mcrt::integrator::Strategy;
use mcrt_render::description::{
    Checked, IntegratorDesc, IntegratorKind, MltParams, SamplerKind, SceneDescription,
};
use mcrt_render::light::LightBvhUse;
use mcrt_render::render::{RenderOptions, Renderer};
use std::cell::RefCell;
use std::collections::HashMap;
use std::sync::atomic::AtomicBool;

/// Renders with the crate's renderer on all cores.
#[derive(Default)]
struct CrateRenderer {
    /// Per sampler name: does the renderer use it?
    honoured: RefCell<HashMap<String, bool>>,
}

/// The renderer behind the rendering study.
pub fn backend() -> Result<Box<dyn Backend>, String> {
    Ok(Box::<CrateRenderer>::default())
}

fn scene(spec: &SceneSpec) -> Result<SceneDescription, String> {
    match &spec.file {
        None => Ok(mcrt_render::cornell_box::cornell_box()),
        Some(path) => mcrt_render::loader::load_scene(path, &[]).map_err(|e| e.to_string()),
    }
}

fn sampler_kind(name: &str) -> Result<SamplerKind, String> {
    match name {
        "independent" => Ok(SamplerKind::Independent),
        "stratified" => Ok(SamplerKind::Stratified),
        "sobol" => Ok(SamplerKind::Sobol),
        other => Err(format!("unknown sampler {other}")),
    }
}

/// One render: the image and the render time in seconds.
fn render(
    spec: &SceneSpec,
    strategy: Strategy,
    sampler: &str,
    spp: u32,
) -> Result<(Rgb, f64), String> {
    let mut desc = scene(spec)?;
    let kind = sampler_kind(sampler)?;
    desc.sensor = (desc.sensor.clone())
        .changed(|s| s.sampler.kind = kind)
        .map_err(|e| e.to_string())?;
    let opts = RenderOptions {
        spp: Some(spp),
        seed: Some(1),
        strategy: Some(strategy),
        ..RenderOptions::default()
    };
    let renderer = Renderer::new(&desc, &opts).map_err(|e| e.to_string())?;
    let out = renderer.render(&|_, _| {}, &AtomicBool::new(false));
    let (width, height) = renderer.size();
    let pixels = out.image().iter().map(|p| [p.x, p.y, p.z]).collect();
    let img = Rgb {
        width: width as usize,
        height: height as usize,
        pixels,
    };
    Ok((img, out.seconds))
}

impl CrateRenderer {
    /// Whether `sampler` changes the image (checked once, at 1 spp).
    fn honours(&self, spec: &SceneSpec, sampler: &str) -> Result<bool, String> {
        if sampler == "independent" {
            return Ok(true);
        }
        if let Some(&known) = self.honoured.borrow().get(sampler) {
            return Ok(known);
        }
        let (a, _) = render(spec, Strategy::MisPower, "independent", 1)?;
        let (b, _) = render(spec, Strategy::MisPower, sampler, 1)?;
        let differs = a.pixels != b.pixels;
        self.honoured
            .borrow_mut()
            .insert(sampler.to_string(), differs);
        Ok(differs)
    }
}

impl Backend for CrateRenderer {
    fn render(
        &self,
        spec: &SceneSpec,
        strategy: &str,
        sampler: &str,
        spp: u32,
    ) -> Result<(Rgb, f64), String> {
        let strategy =
            Strategy::parse(strategy).ok_or_else(|| format!("unknown strategy {strategy}"))?;
        if !self.honours(spec, sampler)? {
            return Err(format!(
                "the renderer ignores the '{sampler}' sampler (same image as independent)"
            ));
        }
        render(spec, strategy, sampler, spp)
    }
}

/// MLT's depth limit where the scene file's is unlimited: paths longer than 12 segments
/// carry about 0.1% of the Cornell box's light, below the error the study measures.
const MLT_MAX_DEPTH: i32 = 12;

/// One render of the integrator study: `kind` is `path`, `path-power` (the path tracer with
/// the light BVH off), `guided`, `bdpt` or `mlt` (MIS with the power heuristic throughout),
/// `sampler` a sampler name (ignored by MLT), `spp` samples or, for MLT, mutations per
/// pixel. Returns the image and the render time in seconds (for MLT including its
/// bootstrap, for the guided tracer its training passes).
pub fn render_integrator(
    spec: &crate::integrator_study::Scene,
    kind: &str,
    sampler: &str,
    spp: u32,
) -> Result<(Rgb, f64), String> {
    let mut desc = mcrt_render::loader::load_scene(&spec.file, &[]).map_err(|e| e.to_string())?;
    let (integrator, light_bvh) = match kind {
        "path-power" => (IntegratorKind::Path, LightBvhUse::Never),
        _ => (
            IntegratorKind::parse(kind).ok_or(format!("unknown integrator {kind}"))?,
            LightBvhUse::Auto,
        ),
    };
    if integrator == IntegratorKind::Mlt {
        let depth = desc.integrator.max_depth().unwrap_or(-1);
        desc.integrator = Checked::new(IntegratorDesc::Mlt(MltParams {
            max_depth: if depth < 0 { MLT_MAX_DEPTH } else { depth },
            mutations_per_pixel: spp,
            hide_emitters: desc.integrator.hide_emitters(),
            ..MltParams::DEFAULT
        }))
        .map_err(|e| e.to_string())?;
    }
    let opts = RenderOptions {
        spp: Some(spp),
        seed: Some(1),
        strategy: Some(Strategy::MisPower),
        integrator: Some(integrator),
        sampler: (kind != "mlt").then(|| sampler_kind(sampler)).transpose()?,
        light_bvh,
        ..RenderOptions::default()
    };
    let renderer = Renderer::new(&desc, &opts).map_err(|e| e.to_string())?;
    let out = renderer.render(&|_, _| {}, &AtomicBool::new(false));
    if out.nonfinite_samples > 0 {
        eprintln!("    ({} non-finite samples)", out.nonfinite_samples);
    }
    let (width, height) = renderer.size();
    let pixels = out.image().iter().map(|p| [p.x, p.y, p.z]).collect();
    let img = Rgb {
        width: width as usize,
        height: height as usize,
        pixels,
    };
    Ok((img, out.seconds))
}
