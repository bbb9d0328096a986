//! Distributed rendering (issue 14): a render divided by pixel samples (`--samples`) and by
//! pixels (`--crop`), each part written to and read back from its EXR file, merges into the
//! image of a single render up to the final rounding to f32 (at most 1 ulp per channel);
//! `merge` refuses parts that overlap, leave samples out, were interrupted, or come from
//! another scene, options or seed. `tests/distributed_processes.rs` runs the examples.

use crate::distributed_common;

use distributed_common::{max_ulps, scratch};
use mcrt_render::description::{FilterDesc, IntegratorKind, SamplerKind, SceneDescription};
use mcrt_render::film::{merge_parts, read_part, Crop, Film, MergeError, Part, SampleRange};
use mcrt_render::render::{RenderOptions, Renderer};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

/// Image size and samples per pixel of the test renders.
const RES: u32 = 32;
const SPP: u32 = 8;

/// The Cornell box at `RES`², with a Gaussian pixel filter if `gaussian`.
fn scene(gaussian: bool) -> SceneDescription {
    let mut d = mcrt_render::cornell_box::cornell_box_with(SPP, RES, -1);
    if gaussian {
        d.sensor = d
            .sensor
            .clone()
            .changed(|s| {
                s.film = s
                    .film
                    .changed(|f| f.filter = FilterDesc::Gaussian { stddev: 0.5 })
                    .unwrap()
            })
            .unwrap();
    }
    d
}

fn render(desc: &SceneDescription, opts: &RenderOptions) -> (Film, Renderer) {
    let r = Renderer::new(desc, opts).expect("renderer");
    let out = r.render(&|_, _| {}, &AtomicBool::new(false));
    (out.film, r)
}

/// One part: its sample range and crop (`None`: all).
type Split = (Option<&'static str>, Option<&'static str>);

/// Renders every split of `desc` as a part, written to `dir` and read back.
fn parts(desc: &SceneDescription, opts: &RenderOptions, splits: &[Split], dir: &Path) -> Vec<Part> {
    splits
        .iter()
        .enumerate()
        .map(|(i, (samples, crop))| {
            let o = RenderOptions {
                samples: samples.map(|s| s.parse().expect("range")),
                crop: crop.map(|c| c.parse().expect("crop")),
                ..opts.clone()
            };
            let (film, r) = render(desc, &o);
            let path = dir.join(format!("part{i}.exr"));
            mcrt_render::film::write_part(&path, &film, &r.part_info("box")).expect("written");
            read_part(&path).expect("read back")
        })
        .collect()
}

/// Merges the parts and compares with the single render: every pixel has all its samples
/// and every channel of the image and of its variance is within 1 ulp.
fn check_merge(desc: &SceneDescription, opts: &RenderOptions, splits: &[Split], name: &str) {
    let dir = scratch(name);
    let (whole, _) = render(desc, opts);
    let merged = merge_parts(&parts(desc, opts, splits, &dir)).expect("merged");
    assert_eq!(merged.count_range(), (SPP, SPP), "{name}");
    assert_eq!(merged.has_splats(), whole.has_splats(), "{name}");
    let d = max_ulps(&merged.mean(), &whole.mean());
    assert!(d <= 1, "{name}: image differs by {d} ulps");
    let d = max_ulps(&merged.variance(), &whole.variance());
    assert!(d <= 1, "{name}: variance differs by {d} ulps");
    std::fs::remove_dir_all(&dir).ok();
}

/// Samples, crops, and both at once (uneven pieces that do not follow the 16-pixel tiles).
const SPLITS: &[&[Split]] = &[
    &[(Some("0..3"), None), (Some("3..8"), None)],
    &[
        (None, Some("0,0,13,32")),
        (None, Some("13,0,32,20")),
        (None, Some("13,20,32,32")),
    ],
    &[
        (Some("5..8"), None),
        (Some("0..5"), Some("0,0,32,7")),
        (Some("0..1"), Some("0,7,32,32")),
        (Some("1..5"), Some("0,7,32,32")),
    ],
];

#[test]
fn path_traced_parts_merge_to_the_single_render_with_every_sampler() {
    for sampler in [
        SamplerKind::Independent,
        SamplerKind::Stratified,
        SamplerKind::LowDiscrepancy,
        SamplerKind::Halton,
        SamplerKind::R2,
    ] {
        let opts = RenderOptions {
            sampler: Some(sampler),
            // Stratified keeps 8 (not a square) as 9 strata: give a square.
            spp: Some(if sampler == SamplerKind::Stratified {
                9
            } else {
                SPP
            }),
            ..RenderOptions::default()
        };
        let splits: &[Split] = if sampler == SamplerKind::Stratified {
            &[(Some("0..4"), None), (Some("4..9"), None)]
        } else {
            SPLITS[2]
        };
        let desc = scene(false);
        let dir = scratch(&format!("sampler-{sampler:?}"));
        let (whole, r) = render(&desc, &opts);
        let merged = merge_parts(&parts(&desc, &opts, splits, &dir)).expect("merged");
        assert_eq!(merged.count_range(), (r.spp(), r.spp()));
        let d = max_ulps(&merged.mean(), &whole.mean());
        assert!(d <= 1, "{sampler:?}: {d} ulps");
        std::fs::remove_dir_all(&dir).ok();
    }
}

#[test]
fn parts_merge_to_the_single_render_with_a_gaussian_filter() {
    for (k, splits) in SPLITS.iter().enumerate() {
        check_merge(
            &scene(true),
            &RenderOptions::default(),
            splits,
            &format!("gauss-{k}"),
        );
    }
}

#[test]
fn bidirectional_parts_merge_with_their_splats() {
    // Light tracing splats anywhere, through a Gaussian filter onto several pixels.
    let opts = RenderOptions {
        integrator: Some(IntegratorKind::Bdpt),
        ..RenderOptions::default()
    };
    for (k, splits) in SPLITS.iter().enumerate() {
        check_merge(&scene(true), &opts, splits, &format!("bdpt-{k}"));
    }
}

/// The error of merging `splits` of the box-filtered Cornell box.
fn merge_error(splits: &[Split], name: &str) -> MergeError {
    let dir = scratch(name);
    let p = parts(&scene(false), &RenderOptions::default(), splits, &dir);
    let e = merge_parts(&p).unwrap_err();
    std::fs::remove_dir_all(&dir).ok();
    e
}

#[test]
fn overlapping_parts_are_refused() {
    let e = merge_error(
        &[
            (Some("0..4"), None),
            (Some("3..8"), Some("0,0,16,16")),
            (Some("4..8"), None),
        ],
        "overlap",
    );
    match &e {
        MergeError::Overlap {
            a,
            b,
            samples,
            pixels,
        } => {
            assert!(a.ends_with("part0.exr") && b.ends_with("part1.exr"), "{e}");
            assert_eq!(*samples, SampleRange { start: 3, end: 4 });
            assert_eq!(*pixels, "0,0,16,16".parse::<Crop>().expect("crop"));
        }
        _ => panic!("{e}"),
    }
    assert!(e.to_string().contains("both hold samples 3..4"), "{e}");
}

#[test]
fn missing_samples_and_pixels_are_named() {
    let e = merge_error(&[(Some("0..3"), None), (Some("5..8"), None)], "gap");
    assert_eq!(
        e,
        MergeError::Gap {
            pixel: (0, 0),
            missing: SampleRange { start: 3, end: 5 },
            pixels: (RES * RES) as u64,
        }
    );
    let e = merge_error(&[(None, Some("0,0,32,31"))], "gap-crop");
    assert_eq!(
        e,
        MergeError::Gap {
            pixel: (0, 31),
            missing: SampleRange::all(SPP),
            pixels: RES as u64,
        }
    );
    assert!(
        e.to_string().contains("pixel (0, 31) lacks samples 0..8"),
        "{e}"
    );
    assert_eq!(merge_parts(&[]).unwrap_err(), MergeError::NoParts);
}

#[test]
fn parts_of_other_renders_are_refused() {
    let dir = scratch("mismatch");
    let desc = scene(false);
    let first = parts(
        &desc,
        &RenderOptions::default(),
        &[(Some("0..4"), None)],
        &dir.join("a").tap_mkdir(),
    );
    let other = |opts: RenderOptions, d: &SceneDescription, name: &str| {
        let mut p = first.clone();
        p.extend(parts(
            d,
            &opts,
            &[(Some("4..8"), None)],
            &dir.join(name).tap_mkdir(),
        ));
        merge_parts(&p).unwrap_err()
    };
    let seed = other(
        RenderOptions {
            seed: Some(7),
            ..RenderOptions::default()
        },
        &desc,
        "seed",
    );
    assert!(
        matches!(seed, MergeError::Mismatch { what: "seed", .. }),
        "{seed}"
    );
    let mut moved = desc.clone();
    moved.shapes[0] = moved.shapes[0]
        .clone()
        .changed(|s| s.to_world.w_axis.x += 1e-3)
        .unwrap();
    let scene_differs = other(RenderOptions::default(), &moved, "scene");
    assert!(
        matches!(&scene_differs, MergeError::Mismatch { what, .. } if what.starts_with("scene")),
        "{scene_differs}"
    );
    let strategy = other(
        RenderOptions {
            strategy: Some(mcrt::integrator::Strategy::parse("balance").expect("balance")),
            ..RenderOptions::default()
        },
        &desc,
        "strategy",
    );
    assert!(
        matches!(strategy, MergeError::Mismatch { .. }),
        "{strategy}"
    );
    let spp = other(
        RenderOptions {
            spp: Some(16),
            ..RenderOptions::default()
        },
        &desc,
        "spp",
    );
    assert!(
        matches!(
            spp,
            MergeError::Mismatch {
                what: "samples per pixel",
                ..
            }
        ),
        "{spp}"
    );
    // The thread count does not shape the image: its parts merge.
    let threads = RenderOptions {
        threads: 1,
        ..RenderOptions::default()
    };
    let mut p = first.clone();
    p.extend(parts(
        &desc,
        &threads,
        &[(Some("4..8"), None)],
        &dir.join("t").tap_mkdir(),
    ));
    assert!(merge_parts(&p).is_ok());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_interrupted_part_is_refused() {
    let dir = scratch("interrupted");
    let desc = scene(false);
    let opts = RenderOptions {
        samples: Some(SampleRange { start: 0, end: 4 }),
        ..RenderOptions::default()
    };
    let r = Renderer::new(&desc, &opts).expect("renderer");
    let cancelled = AtomicBool::new(true);
    let film = r.render(&|_, _| {}, &cancelled).film;
    let path = dir.join("cut.exr");
    mcrt_render::film::write_part(&path, &film, &r.part_info("box")).expect("written");
    let mut p = vec![read_part(&path).expect("read")];
    p.extend(parts(
        &desc,
        &RenderOptions::default(),
        &[(Some("4..8"), None)],
        &dir,
    ));
    let e = merge_parts(&p).unwrap_err();
    assert!(
        matches!(
            e,
            MergeError::Incomplete {
                weight: 0,
                expected: 4,
                ..
            }
        ),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_ranges_and_crops_and_mlt_parts_are_refused_before_rendering() {
    let desc = scene(false);
    let bad = |samples: Option<&str>, crop: Option<&str>, integrator| {
        let opts = RenderOptions {
            samples: samples.map(|s| s.parse().expect("range")),
            crop: crop.map(|c| c.parse().expect("crop")),
            integrator,
            ..RenderOptions::default()
        };
        match Renderer::new(&desc, &opts) {
            Ok(_) => panic!("{samples:?} {crop:?} {integrator:?} accepted"),
            Err(e) => e.to_string(),
        }
    };
    assert!(bad(Some("4..9"), None, None).contains("0..8"));
    assert!(bad(Some("4..4"), None, None).contains("non-empty"));
    assert!(bad(None, Some("0,0,33,8"), None).contains("32×32"));
    assert!(bad(None, Some("5,0,5,8"), None).contains("non-empty"));
    for (s, c) in [(Some("0..4"), None), (None, Some("0,0,8,8"))] {
        assert!(bad(s, c, Some(IntegratorKind::Mlt)).contains("mlt cannot be split"));
    }
}

/// `mkdir -p` that returns the path.
trait TapMkdir {
    fn tap_mkdir(self) -> PathBuf;
}

impl TapMkdir for PathBuf {
    fn tap_mkdir(self) -> PathBuf {
        std::fs::create_dir_all(&self).expect("folder");
        self
    }
}
