//! The one file that calls the renderer: [`mcrt::scene::render::Renderer`] with the strategy
//! as [`mcrt::integrator::Strategy`] and the sampler as the scene's
//! [`mcrt::scene::description::SamplerKind`].
//!
//! The renderer does not take a sampler choice yet (it draws every pixel sample from its
//! own PCG32 stream), so only `independent` is rendered and the other samplers are reported
//! as skipped: add them to [`HONOURED`] once the renderer uses the scene's sampler kind.

use crate::image::Rgb;
use crate::render_study::{Backend, SceneSpec};
use mcrt::integrator::Strategy;
use mcrt::scene::description::{SamplerKind, SceneDescription};
use mcrt::scene::render::{RenderOptions, Renderer};
use std::sync::atomic::AtomicBool;

/// The samplers the renderer actually uses when asked to.
const HONOURED: &[&str] = &["independent"];

/// Renders with the crate's renderer on all cores.
struct CrateRenderer;

/// The renderer behind the rendering study.
pub fn backend() -> Result<Box<dyn Backend>, String> {
    Ok(Box::new(CrateRenderer))
}

fn scene(spec: &SceneSpec) -> Result<SceneDescription, String> {
    match &spec.file {
        None => Ok(mcrt::scene::cornell_box::cornell_box()),
        Some(path) => mcrt::scene::loader::load_scene(path, &[]).map_err(|e| e.to_string()),
    }
}

fn sampler_kind(name: &str) -> Result<SamplerKind, String> {
    match name {
        "independent" => Ok(SamplerKind::Independent),
        "stratified" => Ok(SamplerKind::Stratified),
        "sobol" => Ok(SamplerKind::LowDiscrepancy),
        other => Err(format!("unknown sampler {other}")),
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
        if !HONOURED.contains(&sampler) {
            return Err(format!(
                "the renderer has no '{sampler}' sampler yet (it always samples independently)"
            ));
        }
        let strategy =
            Strategy::parse(strategy).ok_or_else(|| format!("unknown strategy {strategy}"))?;
        let mut desc = scene(spec)?;
        desc.sensor.sampler.kind = sampler_kind(sampler)?;
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
        Ok((
            Rgb {
                width: width as usize,
                height: height as usize,
                pixels,
            },
            out.seconds,
        ))
    }
}
