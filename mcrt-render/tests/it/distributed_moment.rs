//! Mitsuba 3's `moment` channels of a render in parts (issue 25): a render divided by pixel
//! samples (`--samples`) and by pixels (`--crop`), each part written to and read back from
//! its EXR file, merges into the `moment` channels of a single render up to the final
//! rounding to f32 (at most 1 ulp per channel). The parts keep the sums of the squared XYZ
//! samples in f64 (48 bits in the file), which add; the merged second moment is their sum
//! over the merged sample count (the parts' second moments weighted by their sample
//! counts), the merged mean the merged image's. `merge` refuses parts of which one has the
//! channels and another not.

use crate::distributed_common;

use distributed_common::{max_ulps, scratch};
use mcrt::glam::Vec3;
use mcrt_render::film::{merge_parts, read_part, write_part, Film, MergeError, Part};
use mcrt_render::render::{RenderOptions, Renderer};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

/// Samples per pixel of the test renders (the scene is 32×32).
const SPP: u32 = 8;

/// `tests/data/published/integrators/moment.xml`: the Cornell box under `moment(path)`.
fn scene() -> mcrt_render::description::SceneDescription {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/published/integrators/moment.xml");
    mcrt_render::loader::load_scene(&path, &[]).expect("scene loads")
}

fn opts() -> RenderOptions {
    RenderOptions {
        spp: Some(SPP),
        seed: Some(7),
        ..RenderOptions::default()
    }
}

fn render(o: &RenderOptions) -> (Film, Renderer) {
    let r = Renderer::new(&scene(), o).expect("renderer");
    let out = r.render(&|_, _| {}, &AtomicBool::new(false));
    (out.film, r)
}

/// Renders each (samples, crop) split as a part, written to `dir` and read back.
fn parts(splits: &[(Option<&str>, Option<&str>)], dir: &Path) -> Vec<Part> {
    splits
        .iter()
        .enumerate()
        .map(|(i, (samples, crop))| {
            let o = RenderOptions {
                samples: samples.map(|s| s.parse().expect("range")),
                crop: crop.map(|c| c.parse().expect("crop")),
                ..opts()
            };
            let (film, r) = render(&o);
            let path = dir.join(format!("part{i}.exr"));
            write_part(&path, &film, &r.part_info("moment")).expect("written");
            read_part(&path).expect("read back")
        })
        .collect()
}

/// The six `moment` channels of `film`, as triples per pixel: (mean XYZ, second moment XYZ).
fn moment_channels(film: &Film) -> (Vec<String>, Vec<Vec3>, Vec<Vec3>) {
    let ch = film.extra_channels(&film.mean(), 0.0);
    let names = ch.iter().map(|(n, _)| n.clone()).collect();
    let triple = |k: usize| {
        (0..ch[k].1.len())
            .map(|i| Vec3::new(ch[k].1[i], ch[k + 1].1[i], ch[k + 2].1[i]))
            .collect::<Vec<_>>()
    };
    (names, triple(0), triple(3))
}

#[test]
fn moment_channels_of_parts_merge_to_the_single_render() {
    let (whole, _) = render(&opts());
    let (names, mean, m2) = moment_channels(&whole);
    assert_eq!(
        names,
        [
            "nested.X",
            "nested.Y",
            "nested.Z",
            "m2_nested.X",
            "m2_nested.Y",
            "m2_nested.Z"
        ]
    );
    // The second moment is not the squared mean: the test sees a wrong merge.
    assert!(m2
        .iter()
        .zip(&mean)
        .any(|(s, m)| (*s - *m * *m).max_element() > 1e-3));
    let splits: &[&[(Option<&str>, Option<&str>)]] = &[
        &[(Some("0..3"), None), (Some("3..8"), None)],
        &[(None, Some("0,0,13,32")), (None, Some("13,0,32,32"))],
        &[
            (Some("5..8"), None),
            (Some("0..5"), Some("0,0,32,7")),
            (Some("0..1"), Some("0,7,32,32")),
            (Some("1..5"), Some("0,7,32,32")),
        ],
    ];
    for (k, split) in splits.iter().enumerate() {
        let dir = scratch(&format!("moment-{k}"));
        let merged = merge_parts(&parts(split, &dir)).expect("merged");
        assert_eq!(merged.count_range(), (SPP, SPP));
        let (got_names, got_mean, got_m2) = moment_channels(&merged);
        assert_eq!(got_names, names, "split {k}");
        let (dm, d2) = (max_ulps(&got_mean, &mean), max_ulps(&got_m2, &m2));
        println!("split {k}: mean within {dm} ulps, second moment within {d2} ulps");
        assert!(dm <= 1, "split {k}: mean channels differ by {dm} ulps");
        assert!(
            d2 <= 1,
            "split {k}: second-moment channels differ by {d2} ulps"
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}

#[test]
fn parts_with_and_without_moment_channels_are_refused() {
    let dir = scratch("moment-mixed");
    let mut ps = parts(&[(Some("0..3"), None), (Some("3..8"), None)], &dir);
    assert!(ps.iter().all(|p| p.moment.is_some()));
    ps[1].moment = None;
    match merge_parts(&ps) {
        Err(e @ MergeError::Mismatch { .. }) => {
            let msg = e.to_string();
            assert!(
                msg.contains("moment channels") && msg.contains("part1.exr"),
                "{msg}"
            );
        }
        other => panic!("expected a mismatch, got {other:?}"),
    }
    std::fs::remove_dir_all(&dir).ok();
}
