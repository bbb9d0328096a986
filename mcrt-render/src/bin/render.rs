//! Renders a scene file (a subset of Mitsuba 3's XML) or, with no argument, the Cornell box.
//!
//! ```text
//! cargo run --release --bin render -- [scene.xml] [--spp N] [-D name=value]...
//!     [-o out.exr|out.png] [--threads N] [--seed S] [--variance]
//!     [--strategy bsdf|light|balance|power]
//!     [--sampler independent|stratified|sobol|sobol4d|halton|r2|cmj]
//!     [--accel bvh|bvh8|grid|kdtree] [--light-sampling auto|solid-angle|area]
//!     [--light-bvh auto|on|off]
//!     [--integrator path|direct|bdpt|mlt|ptracer|guided] [--bdpt-strategy s,t]
//!     [--samples START..END] [--crop x0,y0,x1,y1]
//! ```
//!
//! `--help` lists every option with its default. Writes a linear float EXR and an sRGB PNG
//! beside it, by default `renders/SCENE.exr` and `renders/SCENE.png` in the current folder
//! (the extension of `-o` chooses which name is which; `<name>-variance.exr` with
//! `--variance`). The output folder is checked before rendering, and files are replaced
//! atomically. Ctrl-C (or SIGTERM) stops early, writes the image so far as
//! `NAME.partial.exr` / `NAME.partial.png` (pixels without a sample are NaN in the EXR)
//! and exits with status 130, in every phase: while the scene loads or the acceleration
//! structure is built it exits at once (nothing written); during the render (Metropolis's
//! bootstrap included) it writes the image so far; while the image is written it finishes
//! writing it.
//!
//! With `--samples` or `--crop` the output is a *part* of the render, an EXR that the `merge`
//! example adds to the other parts (see `docs/distributed.md`).

use clap::{Arg, ArgAction, Command};
use indicatif::{ProgressBar, ProgressStyle};
use mcrt::integrator::Strategy;
use mcrt_render::description::{IntegratorKind, SampleCount, SamplerKind, SceneDescription};
use mcrt_render::film::{OutputPlan, WindowError, EXIT_INTERRUPTED};
use mcrt_render::render::{AccelKind, RenderOptions, Renderer, ShapeSampling, MAX_THREADS};
use std::ffi::OsString;
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

/// One command-line option: adding an option is adding one entry to [`OPTIONS`].
struct Opt {
    /// `--long` name.
    long: &'static str,
    /// `-s` short name, if any.
    short: Option<char>,
    /// The value's placeholder in `--help`; `None` for a switch.
    value: Option<&'static str>,
    /// What it does, and its default.
    help: &'static str,
    /// Applies one occurrence (a switch gets `""`).
    apply: fn(&mut Args, &str) -> Result<(), String>,
}

const OPTIONS: &[Opt] = &[
    Opt {
        long: "spp",
        short: None,
        value: Some("N"),
        help: "samples per pixel [default: the scene's sample_count]",
        apply: |a, v| {
            let n = SampleCount::named("--spp", num("--spp", v)?).map_err(|e| e.to_string())?;
            a.opts.spp = Some(n.get());
            Ok(())
        },
    },
    Opt {
        long: "define",
        short: Some('D'),
        value: Some("NAME=VALUE"),
        help: "set a scene parameter, overriding its <default> (repeatable) [default: none]",
        apply: |a, v| {
            let (k, x) = v
                .split_once('=')
                .ok_or_else(|| format!("-D {v}: expected name=value"))?;
            a.defines.push((k.to_string(), x.to_string()));
            Ok(())
        },
    },
    Opt {
        long: "output",
        short: Some('o'),
        value: Some("FILE"),
        help: "output image, NAME.exr or NAME.png; the other format is written beside it \
               [default: renders/SCENE.exr, the folder made if missing; a part: \
               renders/SCENE.samples-START-END.crop-X0-Y0-X1-Y1.exr]",
        apply: |a, v| {
            a.out = Some(v.into());
            Ok(())
        },
    },
    Opt {
        long: "threads",
        short: None,
        value: Some("N"),
        help: "worker threads, 0 for all cores, at most 1024 [default: 0]",
        apply: |a, v| {
            let n: usize = num("--threads", v)?;
            if n > MAX_THREADS {
                return Err(format!(
                    "--threads {v}: at most {MAX_THREADS} worker threads"
                ));
            }
            a.opts.threads = n;
            Ok(())
        },
    },
    Opt {
        long: "seed",
        short: None,
        value: Some("S"),
        help: "sampler seed [default: the scene's sampler seed]",
        apply: |a, v| {
            a.opts.seed = Some(num("--seed", v)?);
            Ok(())
        },
    },
    Opt {
        long: "variance",
        short: None,
        value: None,
        help: "also write the per-pixel variance of the estimate as NAME-variance.exr \
               [default: off]",
        apply: |a, _| {
            a.variance = true;
            Ok(())
        },
    },
    Opt {
        long: "strategy",
        short: None,
        value: Some("bsdf|light|balance|power"),
        help: "sampling strategy at every vertex [default: power (MIS, power heuristic)]",
        apply: |a, v| {
            let s = Strategy::parse(v)
                .ok_or_else(|| format!("--strategy {v}: expected bsdf, light, balance or power"))?;
            a.opts.strategy = Some(s);
            Ok(())
        },
    },
    Opt {
        long: "sampler",
        short: None,
        value: Some("independent|stratified|sobol|sobol4d|halton|r2|cmj"),
        help: "sample generator [default: the scene's sampler type]",
        apply: |a, v| {
            a.opts.sampler = Some(match v {
                "independent" => SamplerKind::Independent,
                "stratified" => SamplerKind::Stratified,
                "sobol" => SamplerKind::Sobol,
                "sobol4d" | "ldsampler" => SamplerKind::LowDiscrepancy,
                "halton" => SamplerKind::Halton,
                "r2" => SamplerKind::R2,
                "cmj" | "multijitter" => SamplerKind::MultiJitter,
                _ => {
                    return Err(format!(
                        "--sampler {v}: expected independent, stratified, sobol, sobol4d, \
                         halton, r2 or cmj"
                    ))
                }
            });
            Ok(())
        },
    },
    Opt {
        long: "accel",
        short: None,
        value: Some("bvh|bvh8|grid|kdtree"),
        help: "acceleration structure: bvh (4-wide), bvh8 (8-wide, AVX2 where the processor \
               has it), grid or kdtree [default: bvh]",
        apply: |a, v| {
            a.opts.accel = match v {
                "bvh" => AccelKind::Bvh,
                "bvh8" => AccelKind::Bvh8,
                "grid" => AccelKind::Grid,
                "kdtree" => AccelKind::KdTree,
                _ => return Err(format!("--accel {v}: expected bvh, bvh8, grid or kdtree")),
            };
            Ok(())
        },
    },
    Opt {
        long: "light-bvh",
        short: None,
        value: Some("auto|on|off"),
        help: "whether next-event estimation chooses its light by a light BVH: auto above 16 \
               lights with a position (each emitting triangle counted), on whenever a light \
               has one, off never (by power over distance up to 16, by power beyond) \
               [default: auto]",
        apply: |a, v| {
            a.opts.light_bvh = mcrt_render::light::LightBvhUse::parse(v)
                .ok_or_else(|| format!("--light-bvh {v}: expected auto, on or off"))?;
            Ok(())
        },
    },
    Opt {
        long: "light-candidates",
        short: None,
        value: Some("M"),
        help: "path and direct: next-event estimation draws M light-BVH candidates and keeps \
               one in proportion to its unshadowed contribution (resampled importance \
               sampling), where the BVH chooses and every light is an untextured rectangle \
               or emitting mesh; 1 for one BVH sample, at most 64 [default: 1]",
        apply: |a, v| {
            a.opts.light_candidates = Some(
                v.parse()
                    .ok()
                    .filter(|m| (1..=mcrt_render::light::MAX_LIGHT_CANDIDATES).contains(m))
                    .ok_or_else(|| format!("--light-candidates {v}: expected 1 to 64"))?,
            );
            Ok(())
        },
    },
    Opt {
        long: "light-sampling",
        short: None,
        value: Some("auto|solid-angle|area"),
        help: "how area lights on triangles and rectangles are sampled: auto is by solid angle \
               from near, by area from far [default: auto]",
        apply: |a, v| {
            a.opts.light_sampling = match v {
                "auto" => ShapeSampling::Auto,
                "solid-angle" => ShapeSampling::SolidAngle,
                "area" => ShapeSampling::Area,
                _ => {
                    return Err(format!(
                        "--light-sampling {v}: expected auto, solid-angle or area"
                    ))
                }
            };
            Ok(())
        },
    },
    Opt {
        long: "integrator",
        short: None,
        value: Some("path|direct|bdpt|mlt|ptracer|guided"),
        help: "estimator, overriding the scene's <integrator> (its max_depth and rr_depth carry \
               over; mlt counts --spp as mutations per pixel) [default: the scene's]",
        apply: |a, v| {
            a.opts.integrator = Some(IntegratorKind::parse(v).ok_or_else(|| {
                format!("--integrator {v}: expected path, direct, bdpt, mlt, ptracer or guided")
            })?);
            Ok(())
        },
    },
    Opt {
        long: "max-memory",
        short: None,
        value: Some("SIZE"),
        help: "memory budget for loading and rendering, e.g. 4G or 512M: a mesh, texture, \
               film or MLT state that would need more is refused before it is allocated \
               (docs/renderer.md, Memory budget) [default: 8G]",
        apply: |_a, v| {
            let bytes =
                mcrt_render::memory::parse_size(v).map_err(|e| format!("--max-memory {e}"))?;
            mcrt_render::memory::set_max_memory(bytes);
            Ok(())
        },
    },
    Opt {
        long: "bdpt-strategy",
        short: None,
        value: Some("S,T"),
        help: "bdpt: render only the strategy with S light and T camera vertices, unweighted \
               (a picture of one strategy) [default: all, weighted by MIS]",
        apply: |a, v| {
            let bad = || format!("--bdpt-strategy {v}: expected two integers s,t");
            let (s, t) = v.split_once(',').ok_or_else(bad)?;
            a.opts.bdpt_only = Some((
                s.trim().parse().map_err(|_| bad())?,
                t.trim().parse().map_err(|_| bad())?,
            ));
            Ok(())
        },
    },
];

/// The options that divide a render (`docs/distributed.md`).
const SPLIT_OPTIONS: &[Opt] = &[
    Opt {
        long: "samples",
        short: None,
        value: Some("START..END"),
        help: "render only the pixel samples with indices in [START, END) of the --spp budget, \
               exactly those a whole render draws for them, as a part for the merge example \
               (not with mlt) [default: all]",
        apply: |a, v| {
            a.opts.samples = Some(v.parse().map_err(|e: WindowError| format!("--{e}"))?);
            Ok(())
        },
    },
    Opt {
        long: "crop",
        short: None,
        value: Some("X0,Y0,X1,Y1"),
        help: "render only the pixels [X0, X1) × [Y0, Y1), from the top left, as a part for \
               the merge example (not with mlt) [default: the whole image]",
        apply: |a, v| {
            a.opts.crop = Some(v.parse().map_err(|e: WindowError| format!("--{e}"))?);
            Ok(())
        },
    },
];

/// Every option.
fn all_options() -> impl Iterator<Item = &'static Opt> {
    OPTIONS.iter().chain(SPLIT_OPTIONS)
}

fn num<T: std::str::FromStr>(flag: &str, v: &str) -> Result<T, String> {
    v.parse()
        .map_err(|_| format!("{flag}: '{v}' is not a valid number"))
}

/// The parser for [`OPTIONS`].
fn command() -> Command {
    let scene = Arg::new("scene")
        .value_name("SCENE.xml")
        .value_parser(clap::value_parser!(PathBuf))
        .help("Mitsuba 3 XML scene [default: the built-in Cornell box]");
    all_options().fold(
        Command::new("render")
            .about("Renders a Mitsuba 3 XML scene with mcrt's path tracer.")
            .after_help(
                "Images go to the folder renders/ of the current folder unless -o names a \
                 file. Ctrl-C or SIGTERM stops early: the image so far is written as \
                 NAME.partial.exr / NAME.partial.png (nothing if the render has not begun) \
                 and the exit status is 130. \
                 --samples and --crop write a part of the render; \
                 `cargo run --release --bin merge -- OUT.exr PARTS.exr...` adds the parts \
                 into the image one render would give (docs/distributed.md).",
            )
            .arg(scene),
        |cmd, o| {
            let mut arg = Arg::new(o.long).long(o.long).help(o.help);
            if let Some(s) = o.short {
                arg = arg.short(s);
            }
            arg = match o.value {
                // Taken as `OsString`: a file name need not be UTF-8 (`parse_args`).
                Some(v) => arg
                    .value_name(v)
                    .action(ArgAction::Append)
                    .value_parser(clap::value_parser!(OsString)),
                None => arg.action(ArgAction::SetTrue),
            };
            cmd.arg(arg)
        },
    )
}

/// Parses the command line; `Err` carries clap's message (for `--help`, the help text).
fn parse_args() -> Result<Args, clap::Error> {
    let m = command().try_get_matches()?;
    let mut a = Args {
        scene: m.get_one::<PathBuf>("scene").cloned(),
        ..Args::default()
    };
    let usage = |e: String| command().error(clap::error::ErrorKind::ValueValidation, e);
    for o in all_options() {
        match o.value {
            None if m.get_flag(o.long) => (o.apply)(&mut a, "").map_err(usage)?,
            None => {}
            Some(_) => {
                for v in m.get_many::<OsString>(o.long).into_iter().flatten() {
                    if o.long == "output" {
                        // A file name, not necessarily UTF-8.
                        a.out = Some(PathBuf::from(v));
                        continue;
                    }
                    let v = v.to_str().ok_or_else(|| {
                        usage(format!("--{} {}: not UTF-8", o.long, v.to_string_lossy()))
                    })?;
                    (o.apply)(&mut a, v).map_err(usage)?;
                }
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
                    "the built-in Cornell box: unknown define: -D {k}={v}: the scene neither \
                     declares nor uses a parameter \"{k}\" (its <default> parameters: spp, \
                     res, max_depth)"
                ))
            }
        }
    }
    Ok(mcrt_render::cornell_box::cornell_box_with(
        spp, res, max_depth,
    ))
}

/// Loads the scene file and prints the loader's warnings (file, line, element) to stderr.
fn load(path: &std::path::Path, defines: &[(String, String)]) -> Result<SceneDescription, String> {
    let (desc, warnings) =
        mcrt_render::loader::load_scene_with_warnings(path, defines).map_err(|e| e.to_string())?;
    for w in &warnings {
        eprintln!("{w}");
    }
    Ok(desc)
}

/// Renders and writes; returns whether the render was interrupted.
fn run(args: Args) -> Result<bool, String> {
    let name = match &args.scene {
        None => "cornell-box".to_string(),
        Some(p) => p
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into()),
    };
    let split = args.opts.samples.is_some() || args.opts.crop.is_some();
    if split && args.variance {
        return Err(
            "--variance with --samples or --crop: a part keeps the sums of squares, \
                    and `merge --variance` writes the variance of the merged image"
                .into(),
        );
    }
    if split && !ends_in_exr(args.out.as_deref()) {
        return Err("a part (--samples, --crop) is an EXR file: -o must end in .exr".into());
    }
    // Decide and check the output before any work, so that a bad name fails at once.
    let stem = if split {
        format!("{name}{}", part_suffix(&args.opts))
    } else {
        name.clone()
    };
    let plan = OutputPlan::new(
        args.out.as_deref(),
        &stem,
        args.scene.as_deref(),
        args.variance,
    )
    .map_err(|e| e.to_string())?;
    plan.check_writable().map_err(|e| e.to_string())?;
    let (cancel, rendering) = interrupt_handler()?;
    let desc = match &args.scene {
        None => builtin(&args.defines)?,
        Some(p) => load(p, &args.defines)?,
    };
    let renderer = Renderer::new(&desc, &args.opts).map_err(|e| e.to_string())?;
    let (w, h) = renderer.size();
    println!(
        "{name}: {w}×{h}, integrator {}, {} {} ({}), strategy {}, effects: {}",
        renderer.integrator_name(),
        renderer.spp(),
        if renderer.integrator().name() == "mlt" {
            "mutations per pixel"
        } else {
            "spp"
        },
        match renderer.sampler() {
            mcrt::sampling::sampler::AnySampler::Independent(_) => "independent",
            mcrt::sampling::sampler::AnySampler::Stratified(_) => "stratified",
            mcrt::sampling::sampler::AnySampler::Halton(_) => "halton",
            mcrt::sampling::sampler::AnySampler::R2(_) => "r2",
            mcrt::sampling::sampler::AnySampler::Cmj(_) => "cmj",
            mcrt::sampling::sampler::AnySampler::Sobol4d(_) => "sobol4d",
            _ => "sobol",
        },
        renderer.integrator().strategy().name(),
        renderer.effects().describe()
    );
    if let Some(n) = renderer.light_bvh_lights() {
        println!("next-event estimation chooses among {n} lights by a light BVH");
    }
    if split {
        println!(
            "part: samples {} of {}, pixels {} (x0,y0,x1,y1) of {w}×{h}",
            renderer.samples(),
            renderer.spp(),
            renderer.crop()
        );
    }
    let total = renderer.work();
    let bar = ProgressBar::new(total);
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {percent:>3}% {elapsed_precise} eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    rendering.store(true, Ordering::SeqCst);
    let result = renderer.render(&|done, _| bar.set_position(done), &cancel);
    bar.finish_and_clear();
    let interrupted = cancel.load(Ordering::Relaxed);
    let secs = result.seconds.max(1e-9);
    println!(
        "time {:.3} s, {:.3} M samples/s, {:.3} M rays/s ({} samples, {} rays, {} non-finite)",
        result.seconds,
        result.samples as f64 / secs / 1e6,
        result.rays as f64 / secs / 1e6,
        result.samples,
        result.rays,
        result.nonfinite_samples
    );
    if let Some(g) = &result.guiding {
        println!(
            "guided: {} training passes ({} spp, {:.3} s of the time above), final pass {} spp, \
             image of {} spp (the final and last training passes), guide of {} spatial leaves",
            g.passes, g.training_spp, g.training_seconds, g.final_spp, g.image_spp, g.leaves
        );
        if let Some(gain) = g.unguided_final {
            println!(
                "guided: the final pass was path traced without the guide (it promised a gain \
                 of {gain:.2}, below the integrator's min_gain)"
            );
        }
    }
    if let Some(st) = &result.strategies {
        let lens: Vec<String> = st
            .length_shares()
            .iter()
            .filter(|x| x.1 >= 0.001)
            .map(|(l, f)| format!("{l}: {:.1}%", 100.0 * f))
            .collect();
        println!(
            "bdpt, share of the image by path length in segments (above 0.1%): {}",
            lens.join(", ")
        );
        let strat: Vec<String> = st
            .shares()
            .iter()
            .filter(|x| x.2 >= 0.001)
            .map(|(s, t, f)| format!("({s},{t}) {:.1}%", 100.0 * f))
            .collect();
        println!("bdpt, by strategy (s,t) (above 0.1%): {}", strat.join(", "));
    }
    if !interrupted {
        hold_before_writing(&cancel);
    }
    let written = if split {
        let info = renderer.part_info(&name);
        vec![plan
            .write_part(&result.film, &info, interrupted)
            .map_err(|e| e.to_string())?]
    } else {
        plan.write(&result.film, interrupted)
            .map_err(|e| e.to_string())?
    };
    let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
    println!("wrote {}", names.join(", "));
    if !interrupted && cancel.load(Ordering::Relaxed) {
        // A signal while the finished image was written: it is whole, the status is 130.
        println!("interrupted while writing: the image is complete");
        return Ok(true);
    }
    if interrupted {
        let (lo, hi) = result.film.count_range();
        println!(
            "interrupted: pixels have {lo}..{hi} of {} samples each (NaN in the EXR where none)",
            renderer.samples().len()
        );
    }
    Ok(interrupted)
}

/// The test hook for a signal while the finished image is written
/// (`tests/hostile_output.rs`): with the environment variable `MCRT_TEST_HOLD_BEFORE_WRITE`
/// set, prints `writing` and waits until a signal sets `cancel` (at most 60 s) before the
/// image is written, so that the test's signal arrives in that phase for certain.
fn hold_before_writing(cancel: &AtomicBool) {
    if std::env::var_os("MCRT_TEST_HOLD_BEFORE_WRITE").is_none() {
        return;
    }
    println!("writing");
    use std::io::Write as _;
    std::io::stdout().flush().ok();
    let start = std::time::Instant::now();
    while !cancel.load(Ordering::SeqCst) && start.elapsed().as_secs() < 60 {
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
}

/// Installs the SIGINT/SIGTERM/SIGHUP handler, before the scene is loaded: it returns the
/// cancel flag, which the handler sets, and the flag that says the render has begun. Before
/// that (loading, building the acceleration structure) there is no image to keep, and the
/// handler ends the process at once with status 130; from then on the render stops early,
/// the image so far is written and the status is 130.
fn interrupt_handler() -> Result<(Arc<AtomicBool>, Arc<AtomicBool>), String> {
    let cancel = Arc::new(AtomicBool::new(false));
    let rendering = Arc::new(AtomicBool::new(false));
    let (c, r) = (cancel.clone(), rendering.clone());
    // With ctrlc's `termination` feature this handles SIGINT, SIGTERM and SIGHUP; the
    // handler runs on its own thread, not in the signal's context.
    ctrlc::set_handler(move || {
        c.store(true, Ordering::SeqCst);
        if !r.load(Ordering::SeqCst) {
            eprintln!("interrupted before rendering: nothing written");
            std::process::exit(i32::from(EXIT_INTERRUPTED));
        }
    })
    .map_err(|e| format!("cannot install the Ctrl-C handler: {e}"))?;
    Ok((cancel, rendering))
}

/// Whether `-o` is absent or names an EXR file.
fn ends_in_exr(out: Option<&std::path::Path>) -> bool {
    out.is_none_or(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr")))
}

/// The default name's suffix for a part: `.samples-START-END` and `.crop-X0-Y0-X1-Y1`.
fn part_suffix(opts: &RenderOptions) -> String {
    let mut s = String::new();
    if let Some(r) = opts.samples {
        s += &format!(".samples-{}-{}", r.start, r.end);
    }
    if let Some(c) = opts.crop {
        s += &format!(".crop-{}-{}-{}-{}", c.x0, c.y0, c.x1, c.y1);
    }
    s
}

fn main() -> ExitCode {
    let args = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            // `--help` prints to stdout and succeeds; usage errors go to stderr.
            e.print().ok();
            return if e.use_stderr() {
                ExitCode::from(2)
            } else {
                ExitCode::SUCCESS
            };
        }
    };
    match run(args) {
        Ok(false) => ExitCode::SUCCESS,
        Ok(true) => ExitCode::from(EXIT_INTERRUPTED),
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
