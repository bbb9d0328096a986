//! Assembles `convergence.md`: tables, links to the plots, and the explanations in
//! [`crate::prose`].

use crate::distribution::{DistEffort, DistRow};
use crate::prose;
use crate::render_study::{efficiency_table, RenderPoint, SAMPLERS};
use crate::table::{markdown, num, ulps};
use crate::warps::WarpRow;

/// Where and how the figures were made.
pub struct Context {
    /// The command line.
    pub command: String,
    /// CPU and core count.
    pub machine: String,
    /// A remark on the conditions (e.g. other jobs sharing the cores).
    pub note: String,
    /// Whether `--quick` was given.
    pub quick: bool,
}

/// The machine: CPU model from `/proc/cpuinfo` and the number of cores Rust sees.
pub fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    format!(
        "{cpu}, {cores} cores available, {} {}",
        std::env::consts::OS,
        std::env::consts::ARCH
    )
}

fn pair(s: crate::measure::ErrorStats) -> String {
    format!("{} / {}", ulps(s.max), ulps(s.p99))
}

/// The warp table.
pub fn warp_table(rows: &[WarpRow]) -> String {
    let body: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.warp.clone(),
                r.param.clone(),
                pair(r.sample),
                format!("{}: {}", r.key.name(), pair(r.key_err)),
                pair(r.pdf),
                pair(r.pdf_at),
                num(r.ns_f32),
                num(r.ns_f64),
                num(r.ns_f64 / r.ns_f32),
            ]
        })
        .collect();
    markdown(
        &[
            "warp",
            "parameter",
            "sample",
            "key coordinate",
            "pdf",
            "pdf(p)",
            "ns f32",
            "ns f64",
            "f64 / f32",
        ],
        &body,
    )
}

/// The distribution table.
pub fn dist_table(rows: &[DistRow], n: usize) -> String {
    let base = rows.first().map_or(f64::NAN, |r| r.rel_var);
    let body: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                format!("{}×{}", r.width, r.height),
                num(r.build_ms),
                num(r.ns_sample),
                num(r.rel_rmse),
                num((r.rel_var / n as f64).sqrt()),
                num(r.rel_var),
                num(base / r.rel_var),
                num(r.samples_for(0.01)),
                num(r.build_ms + r.samples_for(0.01) * r.ns_sample * 1e-6),
            ]
        })
        .collect();
    markdown(
        &[
            "table",
            "build (ms)",
            "ns / sample",
            &format!("relRMSE, N = {n} (measured)"),
            &format!("relRMSE, N = {n} (predicted)"),
            "relative variance / sample",
            "variance gain vs 1×1",
            "samples for 1% relRMSE",
            "build + sampling for 1% (ms)",
        ],
        &body,
    )
}

/// The whole document.
pub fn document(
    ctx: &Context,
    warps: &[WarpRow],
    dist: &[DistRow],
    de: DistEffort,
    truth: f64,
    render: Result<&[RenderPoint], &str>,
) -> String {
    let mut d = String::new();
    d += prose::TITLE;
    d += &format!(
        "Made with `{}`{}.\n\nMachine: {}. {}\n\n",
        ctx.command,
        if ctx.quick {
            " (quick mode: fewer points, smaller tables, fewer spp)"
        } else {
            ""
        },
        ctx.machine,
        ctx.note
    );
    d += prose::WARPS_INTRO;
    d += &warp_table(warps);
    d += "\n![θ error against u₁](convergence/warp-theta-error.png)\n\n";
    d += prose::WARPS_FINDINGS;
    d += &prose::DIST_INTRO
        .replace("{n}", &de.n.to_string())
        .replace("{m}", &de.m.to_string())
        .replace("{bw}", &de.base_width.to_string())
        .replace("{bh}", &(de.base_width / 2).to_string())
        .replace("{truth}", &format!("{truth:.6}"));
    d += &dist_table(dist, de.n);
    d += "\n![error against resolution](convergence/distribution-resolution.png)\n\n";
    d += "![error against time per sample](convergence/distribution-time.png)\n\n";
    d += prose::DIST_FINDINGS;
    d += prose::RENDER_INTRO;
    match render {
        Ok(points) => {
            let missing: Vec<&str> = SAMPLERS
                .iter()
                .copied()
                .filter(|s| !points.iter().any(|p| p.sampler == *s))
                .collect();
            if !missing.is_empty() {
                d += &format!("{}{}.\n\n", prose::SAMPLERS_MISSING, missing.join(", "));
            }
            for scene in ["cornell-box", "veach-mis"] {
                if points.iter().any(|p| p.scene == scene) {
                    d += &format!("### {scene}\n\n![{scene}: relMSE against time](convergence/render-{scene}.png)\n\n");
                    d += &efficiency_table(points, scene);
                    d += "\n";
                }
            }
            d += prose::RENDER_FINDINGS;
        }
        Err(why) => d += &format!("{}{why}\n", prose::RENDER_PENDING),
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::ErrorStats;
    use crate::warps::Key;

    fn ctx() -> Context {
        Context {
            command: "cmd".into(),
            machine: machine(),
            note: "note".into(),
            quick: true,
        }
    }

    fn inputs() -> (Vec<WarpRow>, Vec<DistRow>, DistEffort) {
        let e = ErrorStats { max: 2.0, p99: 1.0 };
        let w = WarpRow {
            warp: "UniformDisk".into(),
            param: String::new(),
            key: Key::Radius,
            sample: e,
            key_err: e,
            pdf: e,
            pdf_at: ErrorStats {
                max: f64::INFINITY,
                p99: 1.0,
            },
            ns_f32: 10.0,
            ns_f64: 20.0,
        };
        let d = DistRow {
            width: 16,
            height: 8,
            build_ms: 0.01,
            ns_sample: 50.0,
            rel_rmse: 0.5,
            rel_var: 16.0,
        };
        let de = DistEffort {
            base_width: 64,
            max_width: 16,
            n: 64,
            m: 10,
            runs: 1,
        };
        (vec![w], vec![d], de)
    }

    #[test]
    fn document_with_pending_render() {
        let (w, d, de) = inputs();
        let doc = document(&ctx(), &w, &d, de, 2.5, Err("no renderer"));
        for part in [
            "## 1.",
            "## 2.",
            "## 3.",
            "| UniformDisk |",
            "| 16×8 |",
            "no renderer",
            "∞ / 1.0",
            "N = 64 samples",
            "M = 10 independent",
        ] {
            assert!(doc.contains(part), "{part} missing");
        }
        assert!(!doc.contains("{n}") && !doc.contains("{truth}"));
    }

    #[test]
    fn document_with_render_points_names_missing_samplers() {
        let (w, d, de) = inputs();
        let p = RenderPoint {
            scene: "veach-mis".into(),
            strategy: "power".into(),
            sampler: "independent".into(),
            spp: 4,
            seconds: 2.0,
            rel_mse: 0.1,
        };
        let doc = document(&ctx(), &w, &d, de, 2.5, Ok(&[p]));
        assert!(doc.contains("### veach-mis") && !doc.contains("### cornell-box"));
        assert!(doc.contains("stratified, sobol"));
        assert!(doc.contains("| power / independent | 0.100 | 2.00 | 5.00 |"));
    }
}
