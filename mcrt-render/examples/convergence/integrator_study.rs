//! The integrator study (section 4): path tracing, bidirectional path tracing and Metropolis
//! light transport on three scenes, and the learned sampling of issue 28 (the light BVH
//! against the power choice, the guided path tracer against the path tracer) on the scenes
//! made for it; each render timed and compared with the reference; a relMSE-against-time
//! plot, a relMSE table and an efficiency table per scene. The renderer is reached only
//! through the `render` closure given to [`run`].

use crate::image::{read_exr, rel_mse, Rgb};
use crate::plot::{slope_guide, Look, Marker, Plot, Series};
use crate::render_study::RenderPoint;
use crate::table::{markdown, num};
use std::path::{Path, PathBuf};

/// Integrators, in table order (`path` is PT with MIS and the scene's light choice,
/// `path-power` the same with the light BVH off, `guided` the guided path tracer with its
/// training, `mlt` PSSMLT over BDPT paths).
pub const KINDS: [&str; 5] = ["path", "path-power", "guided", "bdpt", "mlt"];

/// The lines `(integrator, sampler)` of the first three scenes; MLT draws its own primary
/// samples (`pss`).
const CLASSIC: &[(&str, &str)] = &[
    ("path", "sobol"),
    ("bdpt", "independent"),
    ("bdpt", "sobol"),
    ("mlt", "pss"),
];

/// The Cornell box's lines: the classic ones and the guided tracer (the cost of guiding
/// where it has nothing to learn).
const CORNELL: &[(&str, &str)] = &[
    ("path", "sobol"),
    ("guided", "sobol"),
    ("bdpt", "independent"),
    ("bdpt", "sobol"),
    ("mlt", "pss"),
];

/// The many-lights room: the light BVH (the default there) against the power choice.
const MANY_LIGHTS: &[(&str, &str)] = &[("path", "sobol"), ("path-power", "sobol")];

/// The indirect room: the guided tracer against the path tracer.
const INDIRECT: &[(&str, &str)] = &[("path", "sobol"), ("guided", "sobol")];

/// The door scene: guiding against BDPT and MLT.
const DOOR: &[(&str, &str)] = &[
    ("path", "sobol"),
    ("guided", "sobol"),
    ("bdpt", "sobol"),
    ("mlt", "pss"),
];

/// Names of the study's scenes (for `--scenes`), in page order.
pub const SCENES: [&str; 6] = [
    "cornell-box",
    "veach-mis",
    "cornell-box-caustic",
    "many-lights",
    "indirect",
    "door",
];

/// The lines of a scene of [`SCENES`], in table order.
pub fn lines_of(scene: &str) -> &'static [(&'static str, &'static str)] {
    match scene {
        "cornell-box" => CORNELL,
        "many-lights" => MANY_LIGHTS,
        "indirect" => INDIRECT,
        "door" => DOOR,
        _ => CLASSIC,
    }
}

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

/// The scenes, paths under the crate root (issue 28's in `tests/data/issue28/`).
pub fn scenes(root: &Path) -> Vec<Scene> {
    SCENES
        .iter()
        .map(|&name| {
            let dir = match name {
                "many-lights" | "indirect" | "door" => root.join("tests/data/issue28"),
                _ => root.join("tests/data"),
            };
            Scene {
                name,
                file: dir.join(format!("{name}.xml")),
                reference: dir.join(format!("{name}.exr")),
            }
        })
        .collect()
}

/// Renders a scene with an integrator and sampler (names from [`lines_of`]) at `spp` (MLT:
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
        let wanted = lines_of(scene.name).iter().copied();
        for (kind, sampler) in wanted.filter(|l| (plan.wanted)(l.0, l.1)) {
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

/// The lines present for `scene`, in [`lines_of`] order, each sorted by spp.
fn lines(points: &[RenderPoint], scene: &str) -> Vec<(String, Vec<RenderPoint>)> {
    lines_of(scene)
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

/// A kind's palette colour: the classic three keep the colours of the earlier plots
/// (0, 2, 4), the learned ones take colours between them.
fn colour(kind: &str) -> Option<usize> {
    Some(match kind {
        "path" => 0,
        "path-power" => 1,
        "bdpt" => 2,
        "guided" => 3,
        "mlt" => 4,
        _ => return None,
    })
}

/// The name of a line in tables and legends.
fn label(kind: &str, sampler: &str) -> String {
    match kind {
        "path" => format!("PT (MIS power) / {sampler}"),
        "path-power" => format!("PT, light chosen by power / {sampler}"),
        "guided" => format!("guided PT (training included) / {sampler}"),
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
                    colour: colour(k),
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
        let caustic: Vec<Scene> = scenes(&root()).into_iter().skip(2).take(1).collect();
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
    fn every_scene_has_its_file_its_reference_and_lines_of_known_kinds() {
        let all = scenes(&root());
        assert_eq!(all.len(), SCENES.len());
        for s in &all {
            assert!(s.file.is_file() && s.reference.is_file(), "{s:?}");
            assert!(!lines_of(s.name).is_empty());
            for (k, _) in lines_of(s.name) {
                assert!(KINDS.contains(k) && colour(k).is_some(), "{k}");
            }
        }
        assert_eq!(lines_of("many-lights"), MANY_LIGHTS);
        assert!(lines_of("cornell-box").contains(&("guided", "sobol")));
        assert!(!lines_of("veach-mis").iter().any(|l| l.0 == "guided"));
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
