//! Compares a render with a reference by block means.
//!
//! ```text
//! cargo run --release -p mcrt-render --example compare -- image.exr reference.exr [image-variance.exr [s]]
//! ```
//!
//! With `s`, the reference's per-pixel variance is taken as `s` times the image's: right when
//! both come from the same estimator, `s` = (image spp) / (reference spp).
//!
//! Prints, for 16×16 and 32×32 blocks brighter than 5% of the image mean, the worst relative
//! block error, the image mean ratio and (with the variance image) the worst |z| against the
//! Šidák-corrected critical value at α = 0.01; and the relMSE of the image.

use mcrt::glam::Vec3;
use mcrt_render::film::{compare_blocks, read_exr};
use std::fmt::Write as _;
use std::io::{ErrorKind, Write as _};
use std::path::Path;
use std::process::ExitCode;

/// The report, printed by `main`.
fn run() -> Result<String, String> {
    let mut out = String::new();
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 2 {
        return Err("usage: compare image.exr reference.exr [variance.exr [s]]".into());
    }
    let (w, h, img) = read_exr(Path::new(&args[0])).map_err(|e| e.to_string())?;
    let (rw, rh, reference) = read_exr(Path::new(&args[1])).map_err(|e| e.to_string())?;
    if (w, h) != (rw, rh) {
        return Err(format!("sizes differ: {w}×{h} vs {rw}×{rh}"));
    }
    let var = match args.get(2) {
        Some(p) => read_exr(Path::new(p)).map_err(|e| e.to_string())?.2,
        None => vec![Vec3::ZERO; img.len()],
    };
    let ref_var: Option<Vec<Vec3>> = match args.get(3) {
        Some(s) => {
            let s: f32 = s.parse().map_err(|_| format!("'{s}' is not a number"))?;
            Some(var.iter().map(|v| *v * s).collect())
        }
        None => None,
    };
    let rel_mse: f64 = img
        .iter()
        .zip(&reference)
        .map(|(a, r)| {
            let d = *a - *r;
            let e = d * d / (*r * *r + Vec3::splat(0.01));
            f64::from(e.x + e.y + e.z) / 3.0
        })
        .sum::<f64>()
        / img.len() as f64;
    let _ = writeln!(
        out,
        "relMSE {rel_mse:.3e}  (mean of (img − ref)² / (ref² + 0.01))"
    );
    for b in [16, 32] {
        let r = compare_blocks(
            &img,
            &var,
            &reference,
            ref_var.as_deref(),
            w,
            h,
            b,
            0.05,
            0.01,
        );
        let _ = writeln!(
            out,
            "{b}×{b}: {} blocks, worst block {:.2}%, mean ratio ({:.4}, {:.4}, {:.4}), worst |z| {:.2} (critical {:.2}), non-finite pixels {}",
            r.blocks,
            100.0 * r.worst_relative,
            r.mean_ratio.x,
            r.mean_ratio.y,
            r.mean_ratio.z,
            r.worst_z,
            r.z_critical,
            r.non_finite
        );
    }
    Ok(out)
}

fn main() -> ExitCode {
    match run() {
        // A reader that stops early (`compare … | head -1`) is not an error.
        Ok(report) => match std::io::stdout().lock().write_all(report.as_bytes()) {
            Err(e) if e.kind() != ErrorKind::BrokenPipe => {
                eprintln!("error: cannot write the report: {e}");
                ExitCode::FAILURE
            }
            _ => ExitCode::SUCCESS,
        },
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
