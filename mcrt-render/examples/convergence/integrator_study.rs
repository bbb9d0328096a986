//! The integrator study (section 4): path tracing, bidirectional path tracing and Metropolis
//! light transport on three scenes, each render timed and compared with the reference;
//! a relMSE-against-time plot, a relMSE table and an efficiency table per scene. The
//! renderer is reached only through the `render` closure given to [`run`].

use crate::image::{read_exr, rel_mse, Rgb};
use crate::plot::{slope_guide, Look, Marker, Plot, Series};
use crate::render_study::RenderPoint;
use crate::table::{markdown, num};
use std::path::{Path, PathBuf};

/// Integrators, in table order (`path` is PT with MIS, `mlt` is PSSMLT over BDPT paths).
pub const KINDS: [&str; 3] = ["path", "bdpt", "mlt"];

/// The study's lines `(integrator, sampler)`; MLT draws its own primary samples (`pss`).
pub const LINES: [(&str, &str); 4] = [
    ("path", "sobol"),
    ("bdpt", "independent"),
    ("bdpt", "sobol"),
    ("mlt", "pss"),
];

/// Names of the study's scenes (for `--scenes`).
pub const SCENES: [&str; 3] = ["cornell-box", "veach-mis", "cornell-box-caustic"];

/// A scene of the study: its name, the scene file and the reference image.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Short name (`tests/data/<name>.xml` and `.exr`).
    pub name: &'static str,
    /// The scene file.
    pub file: PathBuf,
    /// The reference image.
    pub reference: PathBuf,
}

/// The three scenes, paths under the crate root.
pub fn scenes(root: &Path) -> Vec<Scene> {
    SCENES
        .iter()
        .map(|&name| Scene {
            name,
            file: root.join(format!("tests/data/{name}.xml")),
            reference: root.join(format!("tests/data/{name}.exr")),
        })
        .collect()
}

/// Renders a scene with an integrator and sampler (names from [`LINES`]) at `spp` (MLT:
/// mutations per pixel); returns the image and the render time in seconds.
pub type Render<'a> = dyn Fn(&Scene, &str, &str, u32) -> Result<(Rgb, f64), String> + 'a;

/// What to render: which lines, up to which spp, and a time limit per render.
pub struct Plan<'a> {
    /// `wanted(integrator, sampler)`.
    pub wanted: &'a dyn Fn(&str, &str) -> bool,
    /// Largest spp of the ladder 1, 4, 16, ….
    pub max_spp: u32,
    /// Skip a render (and the line's larger ones) when 4× the line's previous render time
    /// exceeds this many seconds.
    pub limit: Option<f64>,
}

/// Renders every wanted line of every scene at 1, 4, 16, … spp; returns the points (the
/// integrator in [`RenderPoint::strategy`]) and messages about what was skipped.
pub fn run(render: &Render, scenes: &[Scene], plan: &Plan) -> (Vec<RenderPoint>, Vec<String>) {
    let (mut points, mut skipped) = (Vec::new(), Vec::new());
    for scene in scenes {
        let reference = match read_exr(&scene.reference) {
            Ok(r) => r,
            Err(e) => {
                skipped.push(e);
                continue;
            }
        };
        for (kind, sampler) in LINES.into_iter().filter(|l| (plan.wanted)(l.0, l.1)) {
            let mut last: Option<f64> = None;
            for spp in crate::render_study::spp_ladder(plan.max_spp) {
                let what = format!("{} {kind}/{sampler} {spp} spp", scene.name);
                if let (Some(t), Some(lim)) = (last, plan.limit) {
                    if 4.0 * t > lim {
                        skipped.push(format!("{what}: would take about {:.0} s", 4.0 * t));
                        break;
                    }
                }
                let result = render(scene, kind, sampler, spp).and_then(|(img, s)| {
                    Ok(RenderPoint {
                        scene: scene.name.into(),
                        strategy: kind.into(),
                        sampler: sampler.into(),
                        spp,
                        seconds: s,
                        rel_mse: rel_mse(&img, &reference)?,
                    })
                });
                match result {
                    Ok(p) => {
                        eprintln!("  {what}: {:.2} s, relMSE {:.3e}", p.seconds, p.rel_mse);
                        last = Some(p.seconds);
                        points.push(p);
                    }
                    Err(e) => {
                        skipped.push(format!("{what}: {e}"));
                        break;
                    }
                }
            }
        }
    }
    (points, skipped)
}

/// The lines present for `scene`, in [`LINES`] order, each sorted by spp.
fn lines(points: &[RenderPoint], scene: &str) -> Vec<(String, Vec<RenderPoint>)> {
    LINES
        .iter()
        .filter_map(|&(k, sa)| {
            let mut pts: Vec<RenderPoint> = points
                .iter()
                .filter(|p| p.scene == scene && p.strategy == k && p.sampler == sa)
                .cloned()
                .collect();
            pts.sort_by_key(|p| p.spp);
            (!pts.is_empty()).then(|| (label(k, sa), pts))
        })
        .collect()
}

/// The name of a line in tables and legends.
fn label(kind: &str, sampler: &str) -> String {
    match kind {
        "path" => format!("PT (MIS power) / {sampler}"),
        "bdpt" => format!("BDPT (MIS power) / {sampler}"),
        "mlt" => "MLT (PSSMLT, BDPT paths)".into(),
        other => format!("{other} / {sampler}"),
    }
}

/// relMSE against time for one scene, one line per integrator/sampler, with a
/// relMSE ∝ 1/time guide through the fastest point.
pub fn plot(points: &[RenderPoint], scene: &str) -> Option<Plot> {
    let mut series: Vec<Series> = lines(points, scene)
        .into_iter()
        .map(|(name, pts)| {
            let (k, sa) = (&pts[0].strategy, &pts[0].sampler);
            Series {
                label: name,
                points: pts.iter().map(|p| (p.seconds, p.rel_mse)).collect(),
                guide: false,
                look: Look {
                    colour: KINDS.iter().position(|x| x == k).map(|i| 2 * i),
                    marker: if sa == "sobol" {
                        Marker::Square
                    } else {
                        Marker::Circle
                    },
                },
            }
        })
        .collect();
    let usable = || {
        series
            .iter()
            .flat_map(|s| s.points.iter().copied())
            .filter(|p| p.0 > 0.0 && p.1.is_finite())
    };
    let first = usable().min_by(|a, b| a.0.total_cmp(&b.0))?;
    let t1 = usable().map(|p| p.0).fold(0.0, f64::max);
    if t1 <= first.0 {
        return None;
    }
    series.push(slope_guide("relMSE ∝ 1/time", first, t1, -1.0));
    Some(Plot {
        title: format!("{scene}: relMSE against render time, by integrator"),
        x_label: "render time (s)".into(),
        y_label: "relMSE".into(),
        series,
        headroom: 30.0,
    })
}

/// Two tables for one scene: relMSE at each spp (with the time at the largest), and the
/// efficiency 1/(relMSE × time) at each spp.
pub fn tables(points: &[RenderPoint], scene: &str) -> String {
    let ls = lines(points, scene);
    let mut ladder: Vec<u32> = ls.iter().flat_map(|l| l.1.iter().map(|p| p.spp)).collect();
    ladder.sort_unstable();
    ladder.dedup();
    let cell = |pts: &[RenderPoint], s: u32, f: &dyn Fn(&RenderPoint) -> f64| {
        pts.iter()
            .find(|p| p.spp == s)
            .map_or("–".into(), |p| num(f(p)))
    };
    let table = |first: &str, f: &dyn Fn(&RenderPoint) -> f64, last_time: bool| {
        let mut h = vec![first.to_string()];
        h.extend(ladder.iter().map(|s| format!("{s} spp")));
        if last_time {
            h.push("time at max (s)".into());
        }
        let rows: Vec<Vec<String>> = ls
            .iter()
            .map(|(name, pts)| {
                let mut r = vec![name.clone()];
                r.extend(ladder.iter().map(|&s| cell(pts, s, f)));
                if last_time {
                    r.push(pts.last().map_or("–".into(), |p| num(p.seconds)));
                }
                r
            })
            .collect();
        let h: Vec<&str> = h.iter().map(String::as_str).collect();
        markdown(&h, &rows)
    };
    format!(
        "relMSE:\n\n{}\nEfficiency 1/(relMSE × time):\n\n{}",
        table("integrator / sampler", &|p| p.rel_mse, true),
        table("integrator / sampler", &|p| p.efficiency(), false)
    )
}

/// Section 4 of `convergence.md` from the study's points; `made` says how and where.
pub fn section(points: &[RenderPoint], made: &str) -> String {
    let mut d = format!("{}{made}\n\n", crate::integrator_prose::INTRO);
    for scene in SCENES {
        if points.iter().any(|p| p.scene == scene) {
            d += &format!(
                "### {scene}\n\n![{scene}: relMSE against time, by integrator]\
                 (convergence/integrators-{scene}.png)\n\n{}\n",
                tables(points, scene)
            );
        }
    }
    d + crate::integrator_prose::FINDINGS
}

/// Section 4 of `doc`, from its heading to the end, if it has one.
pub fn section_of(doc: &str) -> Option<&str> {
    doc.find(crate::integrator_prose::HEADING)
        .map(|i| &doc[i..])
}

/// `doc` with its section 4 (from its heading to the end) replaced by `section`, or with
/// `section` appended.
pub fn splice(doc: &str, section: &str) -> String {
    let head = section_of(doc).map_or(doc, |s| &doc[..doc.len() - s.len()]);
    format!("{}\n\n{section}", head.trim_end())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn root() -> PathBuf {
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
    }

    /// The reference plus noise of variance ∝ 1/spp (4× more for MLT), time ∝ spp; BDPT
    /// with Sobol fails.
    fn fake(scene: &Scene, kind: &str, sampler: &str, spp: u32) -> Result<(Rgb, f64), String> {
        if kind == "bdpt" && sampler == "sobol" {
            return Err("no".into());
        }
        let mut img = read_exr(&scene.reference)?;
        let amp = if kind == "mlt" { 0.2 } else { 0.1 } / f64::from(spp).sqrt();
        for (i, p) in img.pixels.iter_mut().enumerate() {
            p[1] += (if i % 2 == 0 { amp } else { -amp }) as f32;
        }
        Ok((img, 1e-3 * f64::from(spp)))
    }

    #[test]
    fn study_with_a_fake_renderer() {
        let caustic: Vec<Scene> = scenes(&root()).into_iter().skip(2).collect();
        assert_eq!(caustic[0].name, "cornell-box-caustic");
        let plan = Plan {
            wanted: &|_, _| true,
            max_spp: 64,
            limit: Some(0.03),
        };
        let (points, skipped) = run(&fake, &caustic, &plan);
        // 1, 4, 16 spp for three lines; 64 spp (4 × 16 ms > 30 ms) and BDPT/Sobol skipped.
        assert_eq!(points.len(), 9);
        assert_eq!(skipped.len(), 4, "{skipped:?}");
        let t = tables(&points, "cornell-box-caustic");
        assert_eq!(t.matches("| MLT (").count(), 2);
        assert!(t.contains("| 16 spp |") && !t.contains("64 spp"));
        let p = plot(&points, "cornell-box-caustic").expect("a plot");
        assert_eq!(p.series.len(), 4);
        assert!(p.series[3].guide && plot(&points, "veach-mis").is_none());
        let mlt = &points[8];
        assert!(mlt.rel_mse.is_finite() && mlt.strategy == "mlt" && mlt.spp == 16);
    }

    #[test]
    fn splice_replaces_section_four() {
        let h = crate::integrator_prose::HEADING;
        let doc = format!("# T\n\n## 3. x\n\ntext\n\n{h}\n\nold\n");
        let once = splice(&doc, &format!("{h}\n\nnew\n"));
        assert_eq!(once, format!("# T\n\n## 3. x\n\ntext\n\n{h}\n\nnew\n"));
        assert_eq!(splice(&once, &format!("{h}\n\nnew\n")), once);
        assert_eq!(splice("# T\n", "S"), "# T\n\nS");
        assert_eq!(section_of(&once), Some(format!("{h}\n\nnew\n").as_str()));
        assert_eq!(section_of("# T\n"), None);
    }
}
