//! The convergence study: what accuracy costs in time.
//!
//! ```text
//! cargo run --release --features plots -p mcrt-render --example convergence -- [--quick] [--out docs/]
//!     [--max-spp N] [--no-render] [--strategies bsdf,light,balance,power]
//!     [--samplers independent,stratified,sobol] [--scenes cornell-box,veach-mis] [--note TEXT]
//! cargo run --release --features plots -p mcrt-render --example convergence -- --integrators [--max-spp N]
//!     [--kinds path,path-power,guided,bdpt,mlt]
//!     [--scenes cornell-box,veach-mis,cornell-box-caustic,many-lights,indirect,door]
//!     [--time-limit SECONDS] [--note TEXT]
//! ```
//!
//! Measures the f32 warps against f64 references, the resolution of a 2D distribution
//! against the error of an importance-sampled estimate, and the path tracer's strategies and
//! samplers against the reference images; writes `convergence.md` into the output directory
//! and its PNG plots (and the render results as CSV) into `convergence/` beside it. With
//! `--no-render`, or when the renderer is missing, the rendering section is rebuilt from the
//! CSV of an earlier run if there is one. New renders are merged into that CSV (replacing
//! the same scene, strategy, sampler and spp), so `--strategies`/`--samplers`/`--scenes` can add
//! or redo lines
//! to an earlier study.
//!
//! `--integrators` runs only the integrator study (PT, BDPT, MLT, and issue 28's light BVH and
//! guided tracer on its scenes; ladder to 256 spp unless
//! `--max-spp` says otherwise), merges it into `convergence/integrators.csv`, redraws its
//! plots and replaces section 4 of an existing `convergence.md` (the rest of the page is
//! kept); other runs carry section 4 over unchanged. `--time-limit` skips a render, and the
//! larger ones of its line, when four times the line's previous render time exceeds it;
//! `--max-spp 0` renders nothing and rebuilds section 4 from the CSV.
//!
//! Run time on the project's busy 2-core machine: `--quick` (renders to 4 spp) about 15 s;
//! the sampling half of a full run about 30 s; the rendering half to 256 spp
//! (`--max-spp 256`) about 20 minutes, and to the default 1024 spp several times longer.
//! `--integrators` to 256 spp about 8 minutes, and MLT alone to 1024 (`--kinds mlt
//! --max-spp 1024`) about 3 more.

mod csv;
mod distribution;
mod environment;
mod image;
mod integrator_prose;
mod integrator_study;
mod measure;
mod naive;
mod plot;
mod prose;
mod reference;
mod reference_microfacet;
mod render_study;
mod renderer;
mod report;
mod table;
mod warp_curves;
mod warps;

use distribution::DistEffort;
use std::path::{Path, PathBuf};

/// Command-line options.
struct Options {
    quick: bool,
    out: PathBuf,
    max_spp: Option<u32>,
    render: bool,
    note: String,
    strategies: Option<Vec<String>>,
    samplers: Option<Vec<String>>,
    scenes: Option<Vec<String>>,
    integrators: bool,
    kinds: Option<Vec<String>>,
    time_limit: Option<f64>,
}

/// A comma-separated list, each entry one of `allowed`.
fn list(v: Option<String>, flag: &str, allowed: &[&str]) -> Result<Option<Vec<String>>, String> {
    let v = v.ok_or(format!("{flag} needs a list"))?;
    let items: Vec<String> = v.split(',').map(str::to_string).collect();
    match items.iter().find(|i| !allowed.contains(&i.as_str())) {
        Some(bad) => Err(format!(
            "{flag}: unknown '{bad}' (one of {})",
            allowed.join(", ")
        )),
        None => Ok(Some(items)),
    }
}

const USAGE: &str = "usage: convergence [--quick] [--out DIR] [--max-spp N] [--no-render] \
[--strategies bsdf,light,balance,power] [--samplers independent,stratified,sobol] \
[--scenes cornell-box,veach-mis] [--note TEXT]
       convergence --integrators [--out DIR] [--max-spp N] [--kinds path,bdpt,mlt] \
[--scenes cornell-box,veach-mis,cornell-box-caustic] [--time-limit SECONDS] [--note TEXT]";

fn parse() -> Result<Options, String> {
    let mut o = Options {
        quick: false,
        out: PathBuf::from("docs"),
        max_spp: None,
        render: true,
        note: String::new(),
        strategies: None,
        samplers: None,
        scenes: None,
        integrators: false,
        kinds: None,
        time_limit: None,
    };
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--quick" => o.quick = true,
            "--no-render" => o.render = false,
            "--out" => o.out = it.next().ok_or("--out needs a directory")?.into(),
            "--note" => o.note = it.next().ok_or("--note needs a text")?,
            "--max-spp" => {
                let v = it.next().ok_or("--max-spp needs a number")?;
                o.max_spp = Some(
                    v.parse()
                        .map_err(|_| format!("--max-spp {v}: not a number"))?,
                );
            }
            "--strategies" => o.strategies = list(it.next(), &a, &render_study::STRATEGIES)?,
            "--samplers" => o.samplers = list(it.next(), &a, &render_study::SAMPLERS)?,
            "--scenes" => o.scenes = list(it.next(), &a, &integrator_study::SCENES)?,
            "--integrators" => o.integrators = true,
            "--kinds" => o.kinds = list(it.next(), &a, &integrator_study::KINDS)?,
            "--time-limit" => {
                let v = it.next().ok_or("--time-limit needs seconds")?;
                o.time_limit = Some(
                    v.parse()
                        .map_err(|_| format!("--time-limit {v}: not a number"))?,
                );
            }
            "-h" | "--help" => return Err(USAGE.into()),
            other => return Err(format!("unknown argument {other}\n{USAGE}")),
        }
    }
    let only_integrators = |l: &Vec<String>| {
        l.iter()
            .find(|s| !render_study::SCENES.contains(&s.as_str()))
            .cloned()
    };
    if let Some(s) = o.scenes.as_ref().and_then(only_integrators) {
        if !o.integrators {
            return Err(format!("--scenes {s}: only with --integrators"));
        }
    }
    Ok(o)
}

fn draw(p: Option<plot::Plot>, path: &Path) -> Result<(), String> {
    match p {
        Some(p) => plot::draw(&p, path, (960, 640)),
        None => Ok(()),
    }
}

/// Error against table size, and against time per sample.
fn dist_plots(rows: &[distribution::DistRow], n: usize, dir: &Path) -> Result<(), String> {
    let pts =
        |f: &dyn Fn(&distribution::DistRow) -> (f64, f64)| rows.iter().map(f).collect::<Vec<_>>();
    let series = |label: &str, points| plot::Series {
        label: label.into(),
        points,
        guide: false,
        look: plot::Look::default(),
    };
    let res = plot::Plot {
        title: format!("Importance sampling from a table: relRMSE at N = {n}"),
        x_label: "table cells".into(),
        y_label: "relative RMSE".into(),
        series: vec![
            series(
                "measured",
                pts(&|r| ((r.width * r.height) as f64, r.rel_rmse)),
            ),
            series(
                "predicted",
                pts(&|r| ((r.width * r.height) as f64, (r.rel_var / n as f64).sqrt())),
            ),
        ],
        headroom: 1.5,
    };
    plot::draw(&res, &dir.join("distribution-resolution.png"), (960, 640))?;
    let time = plot::Plot {
        title: format!("relRMSE at N = {n} against time per sample"),
        x_label: "ns per sample (table lookup)".into(),
        y_label: "relative RMSE".into(),
        series: vec![series(
            "tables 1×1 … (left to right: coarse to fine)",
            pts(&|r| (r.ns_sample, r.rel_rmse)),
        )],
        headroom: 1.5,
    };
    plot::draw(&time, &dir.join("distribution-time.png"), (960, 640))
}

/// Runs the rendering study, or recovers an earlier one from its CSV.
fn render_half(o: &Options, dir: &Path) -> Result<Vec<render_study::RenderPoint>, String> {
    let csv_path = dir.join("render.csv");
    let earlier = || -> Result<Vec<_>, String> {
        let text = std::fs::read_to_string(&csv_path)
            .map_err(|e| format!("{}: {e}", csv_path.display()))?;
        csv::read(&text)
    };
    let backend = match (o.render, renderer::backend()) {
        (true, Ok(b)) => b,
        (true, Err(why)) => {
            eprintln!("rendering study skipped: {why}");
            return earlier().map_err(|_| why);
        }
        (false, _) => {
            return earlier().map_err(|e| format!("--no-render and no earlier results ({e})"))
        }
    };
    let max_spp = o.max_spp.unwrap_or(if o.quick { 4 } else { 1024 });
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let wanted = |st: &str, sa: &str| {
        let ok = |list: &Option<Vec<String>>, x: &str| {
            list.as_ref().is_none_or(|l| l.iter().any(|y| y == x))
        };
        ok(&o.strategies, st) && ok(&o.samplers, sa)
    };
    let mut scenes = render_study::scenes(root);
    if let Some(keep) = &o.scenes {
        scenes.retain(|s| keep.iter().any(|k| k == s.name));
    }
    let (points, skipped) = render_study::run(backend.as_ref(), &scenes, max_spp, &wanted);
    for s in &skipped {
        eprintln!("skipped: {s}");
    }
    let all = csv::merge(earlier().unwrap_or_default(), &points);
    std::fs::write(&csv_path, csv::write(&all)).map_err(|e| e.to_string())?;
    Ok(all)
}

/// Runs the integrator study, merges it into its CSV, draws its plots and returns section 4
/// of the page.
fn integrator_half(o: &Options, dir: &Path) -> Result<String, String> {
    let csv_path = dir.join("integrators.csv");
    let earlier = std::fs::read_to_string(&csv_path)
        .ok()
        .map(|t| csv::read_with(csv::INTEGRATOR_HEADER, &t))
        .transpose()?
        .unwrap_or_default();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut scenes = integrator_study::scenes(root);
    if let Some(keep) = &o.scenes {
        scenes.retain(|s| keep.iter().any(|k| k == s.name));
    }
    let wanted = |k: &str, sa: &str| {
        let ok =
            |l: &Option<Vec<String>>, x: &str| l.as_ref().is_none_or(|l| l.iter().any(|y| y == x));
        ok(&o.kinds, k) && (k == "mlt" || ok(&o.samplers, sa))
    };
    let plan = integrator_study::Plan {
        wanted: &wanted,
        max_spp: o.max_spp.unwrap_or(if o.quick { 4 } else { 256 }),
        limit: o.time_limit,
    };
    let (points, skipped) = integrator_study::run(&renderer::render_integrator, &scenes, &plan);
    for s in &skipped {
        eprintln!("skipped: {s}");
    }
    let all = csv::merge(earlier, &points);
    let text = csv::write_with(csv::INTEGRATOR_HEADER, &all);
    std::fs::write(&csv_path, text).map_err(|e| format!("{}: {e}", csv_path.display()))?;
    for scene in integrator_study::SCENES {
        draw(
            integrator_study::plot(&all, scene),
            &dir.join(format!("integrators-{scene}.png")),
        )?;
    }
    let made = format!(
        "Made with `{}` on {}. {}",
        command(),
        report::machine(),
        o.note
    );
    Ok(integrator_study::section(&all, made.trim_end()))
}

/// The command line as typed (arguments with spaces quoted).
fn command() -> String {
    std::iter::once(
        "cargo run --release --features plots -p mcrt-render --example convergence --".to_string(),
    )
    .chain(
        std::env::args()
            .skip(1)
            .map(|a| if a.contains(' ') { format!("'{a}'") } else { a }),
    )
    .collect::<Vec<_>>()
    .join(" ")
}

/// `--integrators`: the integrator study alone, spliced into an existing page.
fn run_integrators(o: &Options) -> Result<(), String> {
    let dir = o.out.join("convergence");
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let section = integrator_half(o, &dir)?;
    let path = o.out.join("convergence.md");
    let doc = std::fs::read_to_string(&path).unwrap_or_default();
    let doc = integrator_study::splice(&doc, &section);
    std::fs::write(&path, doc).map_err(|e| format!("{}: {e}", path.display()))?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

fn run(o: &Options) -> Result<(), String> {
    if o.integrators {
        return run_integrators(o);
    }
    let dir = o.out.join("convergence");
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let effort = if o.quick {
        warps::Effort {
            points: 1 << 12,
            runs: 21,
            reps: 1,
        }
    } else {
        warps::Effort {
            points: 1 << 20,
            runs: 101,
            reps: 1,
        }
    };
    eprintln!("warps: f32 against f64 …");
    let warp_rows = warps::run(effort);
    draw(
        warp_curves::plot(if o.quick { 48 } else { 192 }),
        &dir.join("warp-theta-error.png"),
    )?;
    eprintln!("2D distribution: table resolution …");
    let de = if o.quick {
        DistEffort {
            base_width: 1024,
            max_width: 256,
            n: 64,
            m: 500,
            runs: 5,
        }
    } else {
        DistEffort {
            base_width: 2048,
            max_width: 2048,
            n: 64,
            m: 10_000,
            runs: 25,
        }
    };
    let (dist_rows, truth) = distribution::run(de)?;
    dist_plots(&dist_rows, de.n, &dir)?;
    eprintln!("rendering …");
    let render = render_half(o, &dir);
    if let Ok(points) = &render {
        for scene in ["cornell-box", "veach-mis"] {
            draw(
                render_study::plot(points, scene),
                &dir.join(format!("render-{scene}.png")),
            )?;
        }
    }
    let ctx = report::Context {
        command: command(),
        machine: report::machine(),
        note: o.note.clone(),
        quick: o.quick,
    };
    let render_ref = render.as_deref().map_err(String::as_str);
    let mut doc = report::document(&ctx, &warp_rows, &dist_rows, de, truth, render_ref);
    let path = o.out.join("convergence.md");
    let earlier = std::fs::read_to_string(&path).unwrap_or_default();
    if let Some(section) = integrator_study::section_of(&earlier) {
        doc = integrator_study::splice(&doc, section);
    }
    std::fs::write(&path, doc).map_err(|e| format!("{}: {e}", path.display()))?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

fn main() {
    let code = match parse().and_then(|o| run(&o)) {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("{e}");
            1
        }
    };
    std::process::exit(code);
}
