//! The rendering half: each scene × strategy × sampler rendered at 1, 4, 16, … spp, timed and
//! compared with the reference image; then a relMSE-against-time plot per scene and an
//! efficiency table. The renderer itself is reached only through [`Backend`].

use crate::image::{read_exr, rel_mse, Rgb};
use crate::plot::{slope_guide, Look, Marker, Plot, Series};
use crate::table::{markdown, num};
use std::path::PathBuf;

/// Path-tracer strategies, in table order: `bsdf`, `light`, `balance`, `power`.
pub const STRATEGIES: [&str; 4] = ["bsdf", "light", "balance", "power"];
/// Samplers, in table order.
pub const SAMPLERS: [&str; 3] = ["independent", "stratified", "sobol"];

/// A scene of the study.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneSpec {
    /// Short name (file stem of the plot).
    pub name: &'static str,
    /// The scene file, or `None` for the built-in Cornell box.
    pub file: Option<PathBuf>,
    /// The reference image.
    pub reference: PathBuf,
}

/// Names of the study's scenes (for `--scenes`).
pub const SCENES: [&str; 2] = ["cornell-box", "veach-mis"];

/// The two scenes of the study, paths relative to the crate root.
pub fn scenes(root: &std::path::Path) -> Vec<SceneSpec> {
    vec![
        SceneSpec {
            name: "cornell-box",
            file: None,
            reference: root.join("tests/data/cornell-box.exr"),
        },
        SceneSpec {
            name: "veach-mis",
            file: Some(root.join("tests/data/veach-mis.xml")),
            reference: root.join("tests/data/veach-mis.exr"),
        },
    ]
}

/// What renders an image.
pub trait Backend {
    /// Renders `scene` with a strategy and sampler (names from [`STRATEGIES`] and
    /// [`SAMPLERS`]) at `spp`; returns the image and the wall-clock render time in seconds.
    /// An `Err` skips that combination (e.g. a sampler the renderer lacks).
    fn render(
        &self,
        scene: &SceneSpec,
        strategy: &str,
        sampler: &str,
        spp: u32,
    ) -> Result<(Rgb, f64), String>;
}

/// One render.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderPoint {
    /// Scene name.
    pub scene: String,
    /// Strategy name.
    pub strategy: String,
    /// Sampler name.
    pub sampler: String,
    /// Samples per pixel.
    pub spp: u32,
    /// Render time, s.
    pub seconds: f64,
    /// relMSE against the reference.
    pub rel_mse: f64,
}

impl RenderPoint {
    /// 1 / (relMSE × time).
    pub fn efficiency(&self) -> f64 {
        1.0 / (self.rel_mse * self.seconds)
    }
}

/// 1, 4, 16, … up to `max_spp`.
pub fn spp_ladder(max_spp: u32) -> Vec<u32> {
    std::iter::successors(Some(1u32), |s| s.checked_mul(4))
        .take_while(|&s| s <= max_spp)
        .collect()
}

/// Renders every combination that `wanted(strategy, sampler)` accepts; returns the points
/// and the messages of skipped ones.
pub fn run(
    backend: &dyn Backend,
    scenes: &[SceneSpec],
    max_spp: u32,
    wanted: &dyn Fn(&str, &str) -> bool,
) -> (Vec<RenderPoint>, Vec<String>) {
    let (mut points, mut skipped) = (Vec::new(), Vec::new());
    for scene in scenes {
        let reference = match read_exr(&scene.reference) {
            Ok(r) => r,
            Err(e) => {
                skipped.push(e);
                continue;
            }
        };
        for strategy in STRATEGIES {
            for sampler in SAMPLERS.into_iter().filter(|sa| wanted(strategy, sa)) {
                for spp in spp_ladder(max_spp) {
                    let result =
                        backend
                            .render(scene, strategy, sampler, spp)
                            .and_then(|(img, s)| {
                                Ok(RenderPoint {
                                    scene: scene.name.into(),
                                    strategy: strategy.into(),
                                    sampler: sampler.into(),
                                    spp,
                                    seconds: s,
                                    rel_mse: rel_mse(&img, &reference)?,
                                })
                            });
                    match result {
                        Ok(p) => {
                            eprintln!(
                                "  {} {strategy}/{sampler} {spp} spp: {:.2} s, relMSE {:.3e}",
                                p.scene, p.seconds, p.rel_mse
                            );
                            points.push(p);
                        }
                        Err(e) => {
                            skipped.push(format!("{} {strategy}/{sampler}: {e}", scene.name));
                            break;
                        }
                    }
                }
            }
        }
    }
    (points, skipped)
}

/// The (strategy, sampler) lines present for `scene`, in table order.
fn lines(points: &[RenderPoint], scene: &str) -> Vec<(String, String, Vec<RenderPoint>)> {
    let mut out = Vec::new();
    for st in STRATEGIES {
        for sa in SAMPLERS {
            let pts: Vec<RenderPoint> = points
                .iter()
                .filter(|p| p.scene == scene && p.strategy == st && p.sampler == sa)
                .cloned()
                .collect();
            if !pts.is_empty() {
                out.push((st.to_string(), sa.to_string(), pts));
            }
        }
    }
    out
}

/// Colour by strategy, marker by sampler.
fn look(strategy: &str, sampler: &str) -> Look {
    let marker = match sampler {
        "stratified" => Marker::Triangle,
        "sobol" => Marker::Square,
        _ => Marker::Circle,
    };
    Look {
        colour: STRATEGIES.iter().position(|s| *s == strategy),
        marker,
    }
}

/// relMSE against time for one scene, with a relMSE ∝ 1/time guide (error ∝ 1/√N).
pub fn plot(points: &[RenderPoint], scene: &str) -> Option<Plot> {
    let mut series: Vec<Series> = lines(points, scene)
        .into_iter()
        .map(|(st, sa, pts)| Series {
            label: format!("{st} / {sa}"),
            points: pts.iter().map(|p| (p.seconds, p.rel_mse)).collect(),
            guide: false,
            look: look(&st, &sa),
        })
        .collect();
    let anchor = series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(|p| p.0 > 0.0 && p.1.is_finite());
    let (t0, e0) = anchor
        .clone()
        .fold((f64::INFINITY, 0.0), |a, p| if p.0 < a.0 { p } else { a });
    let t1 = anchor.map(|p| p.0).fold(0.0, f64::max);
    if series.is_empty() || t1 <= t0 {
        return None;
    }
    series.push(slope_guide(
        "relMSE ∝ 1/time (error ∝ 1/√N)",
        (t0, e0),
        t1,
        -1.0,
    ));
    Some(Plot {
        title: format!("{scene}: relMSE against render time"),
        x_label: "render time (s)".into(),
        y_label: "relMSE".into(),
        series,
        headroom: 30.0,
    })
}

/// Efficiency table for one scene: per line, relMSE and time at the largest spp, the
/// efficiency 1/(relMSE × time) at each spp, and the spp and time a relMSE of 10⁻³ would
/// take if relMSE keeps falling as 1/N from the largest spp.
pub fn efficiency_table(points: &[RenderPoint], scene: &str) -> String {
    let ls = lines(points, scene);
    let ladder: Vec<u32> = {
        let mut v: Vec<u32> = ls.iter().flat_map(|l| l.2.iter().map(|p| p.spp)).collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let mut headers = vec![
        "strategy / sampler".to_string(),
        "relMSE (max spp)".into(),
        "time (s)".into(),
    ];
    headers.extend(ladder.iter().map(|s| format!("eff. {s} spp")));
    headers.extend(["spp for 1e-3".into(), "time for 1e-3 (s)".into()]);
    let rows: Vec<Vec<String>> = ls
        .iter()
        .map(|(st, sa, pts)| {
            let last = pts.iter().max_by_key(|p| p.spp).expect("non-empty line");
            let mut r = vec![format!("{st} / {sa}"), num(last.rel_mse), num(last.seconds)];
            for s in &ladder {
                r.push(
                    pts.iter()
                        .find(|p| p.spp == *s)
                        .map_or("–".into(), |p| num(p.efficiency())),
                );
            }
            let spp_needed = last.rel_mse * f64::from(last.spp) / 1e-3;
            r.push(num(spp_needed));
            r.push(num(last.seconds / f64::from(last.spp) * spp_needed));
            r
        })
        .collect();
    let h: Vec<&str> = headers.iter().map(String::as_str).collect();
    markdown(&h, &rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fake renderer: the reference plus noise of variance ∝ 1/spp, time ∝ spp; fails
    /// for the Sobol sampler.
    struct Fake;

    impl Backend for Fake {
        fn render(
            &self,
            scene: &SceneSpec,
            strategy: &str,
            sampler: &str,
            spp: u32,
        ) -> Result<(Rgb, f64), String> {
            if sampler == "sobol" {
                return Err("no Sobol sampler".into());
            }
            let mut img = read_exr(&scene.reference)?;
            let amp = if strategy == "bsdf" { 0.4 } else { 0.1 } / f64::from(spp).sqrt();
            for (i, p) in img.pixels.iter_mut().enumerate() {
                let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
                p[0] += (sign * amp) as f32;
            }
            Ok((img, 1e-3 * f64::from(spp)))
        }
    }

    fn root() -> PathBuf {
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
    }

    #[test]
    fn ladder() {
        assert_eq!(spp_ladder(1024), vec![1, 4, 16, 64, 256, 1024]);
        assert_eq!(spp_ladder(20), vec![1, 4, 16]);
        let names: Vec<&str> = scenes(std::path::Path::new("."))
            .iter()
            .map(|s| s.name)
            .collect();
        assert_eq!(names, SCENES);
    }

    #[test]
    fn study_with_a_fake_renderer() {
        let cornell = scenes(&root()).into_iter().take(1).collect::<Vec<_>>();
        let (points, skipped) = run(&Fake, &cornell, 16, &|_, _| true);
        let (only, _) = run(&Fake, &cornell, 1, &|st, sa| st == "power" && sa != "sobol");
        assert_eq!(only.len(), 2);
        assert_eq!(points.len(), 4 * 2 * 3);
        assert_eq!(skipped.len(), 4);
        for w in points
            .windows(2)
            .filter(|w| w[0].sampler == w[1].sampler && w[1].spp == 4 * w[0].spp)
        {
            let ratio = w[0].rel_mse / w[1].rel_mse;
            assert!(ratio.is_finite() && (ratio - 4.0).abs() < 1e-3, "{ratio}");
        }
        let table = efficiency_table(&points, "cornell-box");
        assert_eq!(table.lines().count(), 2 + 8);
        assert!(table.contains("eff. 16 spp") && table.contains("bsdf / stratified"));
        let p = plot(&points, "cornell-box").expect("a plot");
        assert_eq!(p.series.len(), 9);
        assert!(p.series[8].guide);
        assert!(plot(&points, "veach-mis").is_none());
    }
}
