//! The strict reference figures: renders the three reference scenes at high spp and compares
//! them with Mitsuba 3's references in `tests/data/` (a check a person runs; too slow for CI,
//! about 25 minutes at 1024 spp on the shared 2-core machine).
//!
//! ```text
//! cargo run --release -p mcrt-render --example reference_figures -- [--spp 1024] [--block 32]
//! ```
//!
//! Scenes: `cornell-box.xml` vs `cornell-box.exr`, `cornell-box.xml` with `max_depth=2` vs
//! `cornell-box-direct.exr`, and `veach-mis.xml` vs `veach-mis.exr`. Lights are sampled as
//! Mitsuba samples them (rectangles by area, spheres by cone), fixed seed 2024, as in
//! `tests/it/reference_match.rs`, so the reference's per-pixel variance is taken as ours ×
//! (our spp / its spp).
//!
//! Prints a Markdown table: worst block relative error (blocks brighter than 5% of the image
//! mean), image mean / reference, worst |z| against the Šidák-corrected critical value at
//! α = 0.01, render time and samples per second (wall clock). Exits with status 1 if a block
//! is off by more than 3%, an image mean by more than 1%, or a pixel is NaN or infinite
//! (these bounds are meant for 1024 spp; at low spp the block bound usually fails), and with
//! status 2 on a usage or input error.

use mcrt::glam::Vec3;
use mcrt_render::film::{compare_blocks, read_exr};
use mcrt_render::render::{RenderOptions, Renderer, ShapeSampling};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::AtomicBool;

/// Largest relative error of a block mean.
const BLOCK_BOUND: f64 = 0.03;
/// Largest relative error of the image mean (per channel).
const MEAN_BOUND: f32 = 0.01;

/// One comparison: scene file, `-D` defines, reference image and its samples per pixel
/// (tests/data/REFERENCES.md).
struct Case {
    scene: &'static str,
    defines: &'static [(&'static str, &'static str)],
    reference: &'static str,
    reference_spp: u32,
}

const CASES: [Case; 3] = [
    Case {
        scene: "cornell-box.xml",
        defines: &[],
        reference: "cornell-box.exr",
        reference_spp: 16384,
    },
    Case {
        scene: "cornell-box.xml",
        defines: &[("max_depth", "2")],
        reference: "cornell-box-direct.exr",
        reference_spp: 4096,
    },
    Case {
        scene: "veach-mis.xml",
        defines: &[],
        reference: "veach-mis.exr",
        reference_spp: 16384,
    },
];

/// Figures for one case.
struct Figures {
    worst_block: f64,
    mean_ratio: Vec3,
    worst_z: f64,
    z_critical: f64,
    non_finite: usize,
    seconds: f64,
    samples_per_second: f64,
}

impl Figures {
    fn passes(&self) -> bool {
        let mean_dev = (self.mean_ratio - Vec3::ONE).abs().max_element();
        self.non_finite == 0
            && self.worst_block.is_finite()
            && self.worst_block <= BLOCK_BOUND
            && mean_dev.is_finite()
            && mean_dev <= MEAN_BOUND
    }
}

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join("data")
        .join(name)
}

fn run(case: &Case, spp: u32, block: u32) -> Result<Figures, String> {
    let defines: Vec<(String, String)> = case
        .defines
        .iter()
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect();
    let desc = mcrt_render::loader::load_scene(&data(case.scene), &defines)
        .map_err(|e| format!("{}: {e}", case.scene))?;
    let opts = RenderOptions {
        spp: Some(spp),
        seed: Some(2024),
        light_sampling: ShapeSampling::Area,
        ..RenderOptions::default()
    };
    let out = Renderer::new(&desc, &opts)
        .map_err(|e| format!("{}: {e}", case.scene))?
        .render(&|_, _| {}, &AtomicBool::new(false));
    let (w, h) = (out.film.width(), out.film.height());
    let (rw, rh, reference) =
        read_exr(&data(case.reference)).map_err(|e| format!("{}: {e}", case.reference))?;
    if (w, h) != (rw, rh) {
        return Err(format!(
            "{}: {w}×{h} but the reference is {rw}×{rh}",
            case.scene
        ));
    }
    let img = out.image();
    let var = out.film.variance();
    let scale = spp as f32 / case.reference_spp as f32;
    let ref_var: Vec<Vec3> = var.iter().map(|v| *v * scale).collect();
    let r = compare_blocks(
        &img,
        &var,
        &reference,
        Some(&ref_var),
        w,
        h,
        block,
        0.05,
        0.01,
    );
    Ok(Figures {
        worst_block: r.worst_relative,
        mean_ratio: r.mean_ratio,
        worst_z: r.worst_z,
        z_critical: r.z_critical,
        non_finite: r.non_finite,
        seconds: out.seconds,
        samples_per_second: out.samples as f64 / out.seconds.max(1e-9),
    })
}

/// `--spp N` and `--block B` (defaults 1024 and 32).
fn parse_args() -> Result<(u32, u32), String> {
    let (mut spp, mut block) = (1024u32, 32u32);
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let target = match a.as_str() {
            "--spp" => &mut spp,
            "--block" => &mut block,
            _ => return Err(format!("unknown argument '{a}'")),
        };
        let v = args.next().ok_or(format!("{a} needs a value"))?;
        *target = v
            .parse()
            .ok()
            .filter(|&n: &u32| n > 0)
            .ok_or(format!("{a}: '{v}' is not a positive integer"))?;
    }
    Ok((spp, block))
}

fn main() -> ExitCode {
    let (spp, block) = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("{e}\nusage: reference_figures [--spp N] [--block B]");
            return ExitCode::from(2);
        }
    };
    println!("{spp} spp, {block}×{block} blocks, light sampling by area, seed 2024\n");
    println!(
        "| scene | worst {block}×{block} block | image mean / reference | worst \\|z\\| (critical) | time (s) | samples/s (wall) | within bounds |"
    );
    println!("|---|---|---|---|---|---|---|");
    let mut all_pass = true;
    for case in &CASES {
        eprintln!(
            "rendering {} {:?} at {spp} spp ...",
            case.scene, case.defines
        );
        let f = match run(case, spp, block) {
            Ok(f) => f,
            Err(e) => {
                eprintln!("{e}");
                return ExitCode::from(2);
            }
        };
        let name = case
            .defines
            .iter()
            .fold(case.scene.to_string(), |n, (k, v)| {
                format!("{n}, `{k}={v}`")
            });
        let m = f.mean_ratio;
        let pass = f.passes();
        all_pass &= pass;
        println!(
            "| {name} | {:.2}% | {:.4}, {:.4}, {:.4} | {:.2} ({:.2}) | {:.1} | {:.3} M | {} |",
            100.0 * f.worst_block,
            m.x,
            m.y,
            m.z,
            f.worst_z,
            f.z_critical,
            f.seconds,
            f.samples_per_second / 1e6,
            if pass { "yes" } else { "NO" },
        );
        if f.non_finite > 0 {
            println!("\n{name}: {} NaN or infinite pixels", f.non_finite);
        }
    }
    if all_pass {
        println!("\nEvery block within 3% and every image mean within 1%.");
        ExitCode::SUCCESS
    } else {
        println!("\nA block is off by more than 3%, an image mean by more than 1%, or a pixel is not finite.");
        ExitCode::FAILURE
    }
}
