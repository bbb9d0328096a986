//! The integrator features of published Mitsuba 3 scenes (issue 25) against Mitsuba 3.9.1's
//! images of the same files (`tests/data/published/integrators/`, 64×64 or 32×32, box
//! filter; `tests/data/REFERENCES.md` says how each was made):
//!
//! - `hide-emitters.xml`: the Cornell box under a sky with `hide_emitters`, by the path
//!   tracer (the camera sees through the light and not the sky): a z-test on 16×16 block
//!   means with the render's own per-pixel variance plus the reference's, as
//!   `tests/it/reference_match.rs` does, at the suite's per-test level (Šidák over the suite's
//!   budget, `tests/it/common/suite.rs`); and the sky's pixels exactly black.
//! - `ptracer.xml`: the Cornell box by the particle tracer, against the path tracer's
//!   reference `cornell-box.exr` averaged over 4×4 pixels (the same image, 64×64): light
//!   tracing splats anywhere, so 16 replicates t-test the 16×16 block means
//!   (`tests/it/common/replicates.rs`, the suite's per-test α per comparison, 1% allowance for bias and the
//!   reference's error).
//! - `moment.xml`: `moment` around `path`. Its mean channels are the image in CIE XYZ,
//!   checked exactly against our own image and, for Mitsuba's matrix and names, Mitsuba's
//!   against its own image; the image is block-tested as `hide-emitters.xml`; the second
//!   moment channels are t-tested on 8×8 blocks by 16 replicates against Mitsuba's (2% allowance: the
//!   reference's second moment has heavy tails).
//!
//! Fixed seeds throughout.

use crate::common;

use common::published::assert_blocks_match;
use common::replicates::{compare, render_replicates};
use mcrt::glam::Vec3;
use mcrt_render::description::SceneDescription;
use mcrt_render::film::read_exr;
use mcrt_render::render::{RenderOptions, RenderOutput, Renderer, ShapeSampling};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

const REPLICATES: u32 = 16;
const SEED: u64 = 1000;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join("data")
        .join(name)
}

fn published(name: &str) -> PathBuf {
    data("published").join("integrators").join(name)
}

fn load(path: &Path) -> SceneDescription {
    mcrt_render::loader::load_scene(path, &[]).expect("scene loads")
}

/// Lights sampled as Mitsuba samples them (rectangles by area), so that the reference's own
/// variance is ours scaled by spp / reference spp.
fn opts(spp: u32, seed: u64) -> RenderOptions {
    RenderOptions {
        spp: Some(spp),
        seed: Some(seed),
        light_sampling: ShapeSampling::Area,
        ..RenderOptions::default()
    }
}

fn render(desc: &SceneDescription, o: &RenderOptions) -> RenderOutput {
    Renderer::new(desc, o)
        .expect("scene builds")
        .render(&|_, _| {}, &AtomicBool::new(false))
}

#[test]
fn hide_emitters_sees_through_the_light_and_not_the_sky() {
    let path = published("hide-emitters.xml");
    let desc = load(&path);
    assert!(desc.integrator.hide_emitters());
    let spp = 64;
    let out = render(&desc, &opts(spp, 2024));
    let (_, _, reference) = read_exr(&path.with_extension("exr")).expect("reference reads");
    // Where Mitsuba sees only the hidden sky, so do we: exactly black.
    let img = out.image();
    let sky: Vec<usize> = (0..reference.len())
        .filter(|&i| reference[i] == Vec3::ZERO)
        .collect();
    assert!(sky.len() > 100, "the view shows the sky");
    assert!(sky.iter().all(|&i| img[i] == Vec3::ZERO));
    assert_blocks_match("hide-emitters.xml", &out, (spp, 16384), &reference, 4);
}

/// `reference` (`w`×`h`) averaged over `k`×`k` pixels.
fn downsample(reference: &[Vec3], w: u32, h: u32, k: u32) -> Vec<Vec3> {
    let (ow, oh) = (w / k, h / k);
    let mut out = vec![Vec3::ZERO; (ow * oh) as usize];
    for y in 0..oh * k {
        for x in 0..ow * k {
            out[((y / k) * ow + x / k) as usize] += reference[(y * w + x) as usize];
        }
    }
    out.iter().map(|v| *v / (k * k) as f32).collect()
}

#[test]
fn ptracer_matches_the_cornell_box() {
    let desc = load(&published("ptracer.xml"));
    let (rw, rh, reference) = read_exr(&data("cornell-box.exr")).expect("reference reads");
    let reference = downsample(&reference, rw, rh, 4);
    let (w, h, images) = render_replicates(&desc, &opts(16, 0), REPLICATES, SEED);
    assert_eq!((w, h), (rw / 4, rh / 4));
    compare(&images, &reference, w, h, 16, 0.01).assert_passed("ptracer.xml");
}

#[test]
fn ptracer_hides_emitters_by_leaving_out_the_paths_of_one_segment() {
    // max_depth 1 is the light seen directly: black when hidden.
    let mut desc = load(&published("ptracer.xml"));
    desc.integrator =
        mcrt_render::description::Checked::new(mcrt_render::description::IntegratorDesc::Ptracer(
            mcrt_render::description::PtracerParams {
                max_depth: 1,
                rr_depth: 5,
                ..Default::default()
            },
        ))
        .unwrap();
    let shown = render(&desc, &opts(4, 1)).image();
    assert!(
        shown.iter().any(|v| v.max_element() > 1.0),
        "the light is seen"
    );
    desc.integrator = desc
        .integrator
        .changed(|i| {
            if let mcrt_render::description::IntegratorDesc::Ptracer(p) = i {
                p.hide_emitters = true;
            }
        })
        .unwrap();
    let hidden = render(&desc, &opts(4, 1)).image();
    assert!(hidden.iter().all(|v| *v == Vec3::ZERO));
}

/// Channels `names` of a multichannel EXR, as one image per three names.
fn read_channels(path: &Path, names: [&str; 3]) -> Vec<Vec3> {
    use exr::prelude::*;
    let image = read_all_flat_layers_from_file(path).expect("EXR reads");
    let layer = &image.layer_data[0];
    let channel = |name: &str| -> Vec<f32> {
        let c = layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name == *name)
            .unwrap_or_else(|| panic!("{}: no channel {name}", path.display()));
        (0..c.sample_data.len())
            .map(|i| c.sample_data.value_by_flat_index(i).to_f32())
            .collect()
    };
    let [x, y, z] = names.map(channel);
    (0..x.len()).map(|i| Vec3::new(x[i], y[i], z[i])).collect()
}

fn names(c: &[String; 3]) -> [&str; 3] {
    [c[0].as_str(), c[1].as_str(), c[2].as_str()]
}

/// Linear sRGB to CIE XYZ with Mitsuba 3's matrix (`srgb_to_xyz`), for checking the
/// channels against the image.
fn xyz(v: Vec3) -> Vec3 {
    Vec3::new(
        0.412453 * v.x + 0.357580 * v.y + 0.180423 * v.z,
        0.212671 * v.x + 0.715160 * v.y + 0.072169 * v.z,
        0.019334 * v.x + 0.119193 * v.y + 0.950227 * v.z,
    )
}

fn assert_close(what: &str, got: &[Vec3], want: &[Vec3], rel: f32) {
    assert_eq!(got.len(), want.len(), "{what}: sizes");
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(g.is_finite(), "{what}: pixel {i} is {g}");
        let tol = rel * w.abs().max_element().max(1e-3);
        assert!(
            (*g - *w).abs().max_element() <= tol,
            "{what}: pixel {i}: {g} against {w}"
        );
    }
}

#[test]
fn moment_writes_the_mean_and_second_moment_as_mitsuba_does() {
    let path = published("moment.xml");
    let desc = load(&path);
    let name = desc.moment.as_ref().expect("moment is read").name.clone();
    assert_eq!(name, "nested");
    let reference = path.with_extension("exr");
    let channels = |prefix: &str| [".X", ".Y", ".Z"].map(|a| format!("{prefix}{name}{a}"));
    let (mean_names, m2_names) = (channels(""), channels("m2_"));
    // Mitsuba's mean channels are its image in XYZ: the matrix and the names are its own.
    let ref_rgb = read_channels(&reference, ["R", "G", "B"]);
    let ref_mean = read_channels(&reference, names(&mean_names));
    let ref_xyz: Vec<Vec3> = ref_rgb.iter().map(|v| xyz(*v)).collect();
    assert_close("Mitsuba's mean channels", &ref_mean, &ref_xyz, 1e-4);

    // Ours, written by the renderer: the same channels, the mean our image in XYZ.
    let spp = 64;
    let out = render(&desc, &opts(spp, 2024));
    let file = std::env::temp_dir().join(format!("mcrt-moment-{}.exr", std::process::id()));
    out.write_exr(&file).expect("EXR writes");
    let img = read_channels(&file, ["R", "G", "B"]);
    let mean = read_channels(&file, names(&mean_names));
    let m2 = read_channels(&file, names(&m2_names));
    std::fs::remove_file(&file).ok();
    let ours_xyz: Vec<Vec3> = img.iter().map(|v| xyz(*v)).collect();
    assert_close("our mean channels", &mean, &ours_xyz, 1e-5);
    // The second moment is at least the squared mean (Jensen), pixel by pixel.
    for (s, m) in m2.iter().zip(&mean) {
        assert!(
            s.is_finite() && s.cmpge(*m * *m * 0.999).all(),
            "{s} < {m}²"
        );
    }
    assert_blocks_match("moment.xml", &out, (spp, 16384), &ref_rgb, 4);

    // The second moment against Mitsuba's, by replicates, where the light is not seen
    // directly: there it is the light's squared radiance, hundreds of times the rest,
    // which would leave no other block above the comparison's brightness threshold.
    let lit: Vec<bool> = ref_rgb.iter().map(|v| v.max_element() > 1.0).collect();
    let unlit = |img: Vec<Vec3>| -> Vec<Vec3> {
        img.iter()
            .zip(&lit)
            .map(|(v, &l)| if l { Vec3::ZERO } else { *v })
            .collect()
    };
    assert!(lit.iter().any(|&l| l) && lit.iter().filter(|&&l| l).count() < lit.len() / 10);
    let ref_m2 = unlit(read_channels(&reference, names(&m2_names)));
    let images: Vec<Vec<Vec3>> = (0..REPLICATES)
        .map(|r| {
            let out = render(&desc, &opts(16, SEED + u64::from(r)));
            let image = out.image();
            let ch = out.film.extra_channels(&image, 0.0);
            let get = |n: &str| &ch.iter().find(|(c, _)| c == n).expect("channel").1;
            let [x, y, z] = names(&m2_names).map(get);
            unlit((0..x.len()).map(|i| Vec3::new(x[i], y[i], z[i])).collect())
        })
        .collect();
    let (w, h) = (out.film.width(), out.film.height());
    compare(&images, &ref_m2, w, h, 8, 0.02).assert_passed("moment.xml second moment");
}
