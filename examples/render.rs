//! Renders a scene file (a subset of Mitsuba 3's XML) or, with no argument, the Cornell box.
//!
//! ```text
//! cargo run --release --example render -- [scene.xml] [--spp N] [-D name=value]...
//!     [-o out.exr] [--threads N] [--seed S] [--variance]
//!     [--strategy bsdf|light|balance|power] [--sampler independent|stratified|sobol]
//!     [--accel bvh|grid] [--light-sampling solid-angle|area]
//!     [--integrator path|direct|bdpt|mlt] [--bdpt-strategy s,t]
//! ```
//!
//! Writes a linear float EXR and an sRGB PNG beside it (and `<name>-variance.exr` with
//! `--variance`). Ctrl-C stops early and writes the image so far.

use indicatif::{ProgressBar, ProgressStyle};
use mcrt::integrator::Strategy;
use mcrt::scene::description::{IntegratorKind, SamplerKind, SceneDescription};
use mcrt::scene::render::{AccelKind, RenderOptions, Renderer, ShapeSampling};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

#[derive(Default)]
struct Args {
    scene: Option<PathBuf>,
    defines: Vec<(String, String)>,
    out: Option<PathBuf>,
    variance: bool,
    opts: RenderOptions,
}

const USAGE: &str = "usage: render [scene.xml] [--spp N] [-D name=value]... [-o out.exr] \
[--threads N] [--seed S] [--variance] [--strategy bsdf|light|balance|power] \
[--sampler independent|stratified|sobol] [--accel bvh|grid] \
[--light-sampling solid-angle|area] [--integrator path|direct|bdpt|mlt] [--bdpt-strategy s,t]";

fn parse_num<T: std::str::FromStr>(flag: &str, v: Option<String>) -> Result<T, String> {
    let v = v.ok_or_else(|| format!("{flag} needs a value"))?;
    v.parse()
        .map_err(|_| format!("{flag}: '{v}' is not a valid number"))
}

fn parse_args() -> Result<Args, String> {
    let mut a = Args::default();
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "-h" | "--help" => return Err(USAGE.into()),
            "--spp" => a.opts.spp = Some(parse_num("--spp", it.next())?),
            "--threads" => a.opts.threads = parse_num("--threads", it.next())?,
            "--seed" => a.opts.seed = Some(parse_num("--seed", it.next())?),
            "--variance" => a.variance = true,
            "-o" => a.out = Some(it.next().ok_or("-o needs a file name")?.into()),
            "-D" => {
                let d = it.next().ok_or("-D needs name=value")?;
                let (k, v) = d
                    .split_once('=')
                    .ok_or_else(|| format!("-D {d}: expected name=value"))?;
                a.defines.push((k.to_string(), v.to_string()));
            }
            "--strategy" => {
                let s = it.next().ok_or("--strategy needs a value")?;
                a.opts.strategy = Some(Strategy::parse(&s).ok_or_else(|| {
                    format!("--strategy {s}: expected bsdf, light, balance or power")
                })?);
            }
            "--sampler" => {
                let s = it.next().ok_or("--sampler needs a value")?;
                a.opts.sampler = Some(match s.as_str() {
                    "independent" => SamplerKind::Independent,
                    "stratified" => SamplerKind::Stratified,
                    "sobol" | "ldsampler" => SamplerKind::LowDiscrepancy,
                    _ => {
                        return Err(format!(
                            "--sampler {s}: expected independent, stratified or sobol"
                        ))
                    }
                });
            }
            "--light-sampling" => {
                let s = it.next().ok_or("--light-sampling needs a value")?;
                a.opts.light_sampling = match s.as_str() {
                    "solid-angle" => ShapeSampling::SolidAngle,
                    "area" => ShapeSampling::Area,
                    _ => {
                        return Err(format!(
                            "--light-sampling {s}: expected solid-angle or area"
                        ))
                    }
                };
            }
            "--integrator" => {
                let s = it.next().ok_or("--integrator needs a value")?;
                a.opts.integrator = Some(IntegratorKind::parse(&s).ok_or_else(|| {
                    format!("--integrator {s}: expected path, direct, bdpt or mlt")
                })?);
            }
            "--bdpt-strategy" => {
                let v = it.next().ok_or("--bdpt-strategy needs s,t")?;
                let bad = || format!("--bdpt-strategy {v}: expected two integers s,t");
                let (s, t) = v.split_once(',').ok_or_else(bad)?;
                a.opts.bdpt_only = Some((
                    s.trim().parse().map_err(|_| bad())?,
                    t.trim().parse().map_err(|_| bad())?,
                ));
            }
            "--accel" => {
                let s = it.next().ok_or("--accel needs a value")?;
                a.opts.accel = match s.as_str() {
                    "bvh" => AccelKind::Bvh,
                    "grid" => AccelKind::Grid,
                    _ => return Err(format!("--accel {s}: expected bvh or grid")),
                };
            }
            s if s.starts_with('-') => return Err(format!("unknown option {s}\n{USAGE}")),
            s => {
                if a.scene.is_some() {
                    return Err(format!("more than one scene given ({s})\n{USAGE}"));
                }
                a.scene = Some(s.into());
            }
        }
    }
    Ok(a)
}

/// The built-in Cornell box, with the defines that its XML file declares applied.
fn builtin(defines: &[(String, String)]) -> Result<SceneDescription, String> {
    let (mut spp, mut res, mut max_depth) = (64u32, 256u32, -1i32);
    for (k, v) in defines {
        let bad = || format!("-D {k}={v}: not a valid integer");
        match k.as_str() {
            "spp" => spp = v.parse().map_err(|_| bad())?,
            "res" => res = v.parse().map_err(|_| bad())?,
            "max_depth" => max_depth = v.parse().map_err(|_| bad())?,
            _ => {
                return Err(format!(
                    "-D {k}: the Cornell box has no parameter '{k}' (spp, res, max_depth)"
                ))
            }
        }
    }
    Ok(mcrt::scene::cornell_box::cornell_box_with(
        spp, res, max_depth,
    ))
}

fn load(path: &std::path::Path, defines: &[(String, String)]) -> Result<SceneDescription, String> {
    mcrt::scene::loader::load_scene(path, defines).map_err(|e| e.to_string())
}

fn run() -> Result<(), String> {
    let args = parse_args()?;
    let (desc, name) = match &args.scene {
        None => (builtin(&args.defines)?, "cornell-box".to_string()),
        Some(p) => (
            load(p, &args.defines)?,
            p.file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "scene".into()),
        ),
    };
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("{name}.exr")));
    let renderer = Renderer::new(&desc, &args.opts).map_err(|e| e.to_string())?;
    let (w, h) = renderer.size();
    println!(
        "{name}: {w}×{h}, integrator {}, {} {} ({}), strategy {}, effects: {}",
        renderer.integrator().name(),
        renderer.spp(),
        if renderer.integrator().name() == "mlt" {
            "mutations per pixel"
        } else {
            "spp"
        },
        match renderer.sampler() {
            mcrt::sampling::sampler::AnySampler::Independent(_) => "independent",
            mcrt::sampling::sampler::AnySampler::Stratified(_) => "stratified",
            _ => "sobol",
        },
        renderer.integrator().strategy().name(),
        renderer.effects().describe()
    );
    let cancel = Arc::new(AtomicBool::new(false));
    {
        let c = cancel.clone();
        ctrlc::set_handler(move || c.store(true, Ordering::Relaxed))
            .map_err(|e| format!("cannot install the Ctrl-C handler: {e}"))?;
    }
    let total = renderer.spp() as u64 * w as u64 * h as u64;
    let bar = ProgressBar::new(total);
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {percent:>3}% {elapsed_precise} eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let result = renderer.render(&|done, _| bar.set_position(done), &cancel);
    bar.finish_and_clear();
    let (lo, hi) = result.film.count_range();
    if cancel.load(Ordering::Relaxed) {
        println!("interrupted: pixels have {lo}..{hi} samples each");
    }
    let secs = result.seconds.max(1e-9);
    println!(
        "time {:.3} s, {:.3} M samples/s, {:.3} M rays/s ({} samples, {} rays)",
        result.seconds,
        result.samples as f64 / secs / 1e6,
        result.rays as f64 / secs / 1e6,
        result.samples,
        result.rays
    );
    if let Some(st) = &result.strategies {
        let lens: Vec<String> = st
            .length_shares()
            .iter()
            .map(|(l, f)| format!("{l}: {:.1}%", 100.0 * f))
            .collect();
        println!(
            "share of the image by path length (segments): {}",
            lens.join(", ")
        );
        let strat: Vec<String> = st
            .shares()
            .iter()
            .filter(|x| x.2 >= 0.001)
            .map(|(s, t, f)| format!("({s},{t}) {:.1}%", 100.0 * f))
            .collect();
        println!("by strategy (s,t), above 0.1%: {}", strat.join(", "));
    }
    result.write_exr(&out).map_err(|e| e.to_string())?;
    let png = out.with_extension("png");
    result.write_png(&png).map_err(|e| e.to_string())?;
    println!("wrote {} and {}", out.display(), png.display());
    if args.variance {
        let stem = out
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let vpath = out.with_file_name(format!("{stem}-variance.exr"));
        result
            .write_variance_exr(&vpath)
            .map_err(|e| e.to_string())?;
        println!("wrote {}", vpath.display());
    }
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
