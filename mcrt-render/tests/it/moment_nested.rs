//! Mitsuba 3's `moment` with several nested integrators (issue 25): the channels are named
//! and ordered as Mitsuba 3.9.1 names them, the image is the first nested integrator's, and
//! each nested integrator's channels are exactly (bit for bit) those it writes alone, as
//! each renders every pixel sample from the sample's start. A render in parts is refused.
//! No statistical test.

use mcrt_render::description::SceneDescription;
use mcrt_render::loader::parse_scene;
use mcrt_render::render::{RenderOptions, RenderOutput, Renderer};
use std::sync::atomic::AtomicBool;

/// A small scene: a floor and a sphere under a rectangle light and a sky, lit directly and
/// by one bounce, with `integrators` inside `moment`.
fn scene(integrators: &str) -> SceneDescription {
    let xml = format!(
        r#"<scene version="3.0.0">
    <integrator type="moment">{integrators}</integrator>
    <sensor type="perspective">
        <float name="fov" value="50"/>
        <transform name="to_world"><lookat origin="0, 2, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="16"/>
            <rfilter type="box"/></film>
        <sampler type="independent"><integer name="sample_count" value="8"/></sampler>
    </sensor>
    <emitter type="constant"><rgb name="radiance" value="0.2, 0.3, 0.4"/></emitter>
    <shape type="rectangle">
        <transform name="to_world"><scale value="4"/><rotate x="1" angle="-90"/><translate y="-1"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.5, 0.4"/></bsdf>
    </shape>
    <shape type="sphere"><float name="radius" value="0.8"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.6, 0.8"/></bsdf></shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="0.5"/><rotate x="1" angle="90"/><translate y="2.5"/></transform>
        <emitter type="area"><rgb name="radiance" value="8, 8, 7"/></emitter>
    </shape>
</scene>"#
    );
    parse_scene(&xml, None, &[]).expect("scene loads")
}

const PATH: &str = r#"<integrator type="path"><integer name="max_depth" value="3"/></integrator>"#;
const DIRECT: &str = r#"<integrator type="direct" name="b"/>"#;

fn render(desc: &SceneDescription) -> RenderOutput {
    let opts = RenderOptions {
        seed: Some(11),
        ..RenderOptions::default()
    };
    Renderer::new(desc, &opts)
        .expect("renderer")
        .render(&|_, _| {}, &AtomicBool::new(false))
}

/// The channels of a render, by name.
fn channels(out: &RenderOutput) -> Vec<(String, Vec<f32>)> {
    out.film.extra_channels(&out.image(), 0.0)
}

/// The channels `NAME.*` and `m2_NAME.*` of `ch`, in order.
fn of(ch: &[(String, Vec<f32>)], name: &str) -> Vec<Vec<f32>> {
    ["", "m2_"]
        .iter()
        .flat_map(|prefix| {
            ["X", "Y", "Z"].map(|axis| {
                let want = format!("{prefix}{name}.{axis}");
                ch.iter()
                    .find(|(n, _)| *n == want)
                    .unwrap_or_else(|| panic!("no channel {want}"))
                    .1
                    .clone()
            })
        })
        .collect()
}

#[test]
fn several_nested_integrators_write_mitsubas_channels_each_as_it_renders_alone() {
    let both = render(&scene(&format!("{PATH}{DIRECT}")));
    let ch = channels(&both);
    let names: Vec<&str> = ch.iter().map(|(n, _)| n.as_str()).collect();
    // Mitsuba 3.9.1's film of `moment` around an unnamed `path` and a `direct` named `b`
    // (`mi.Bitmap` of its EXR; `docs/scene-format.md`).
    let mitsuba = [
        "_arg_0.X",
        "_arg_0.Y",
        "_arg_0.Z",
        "b.X",
        "b.Y",
        "b.Z",
        "m2__arg_0.X",
        "m2__arg_0.Y",
        "m2__arg_0.Z",
        "m2_b.X",
        "m2_b.Y",
        "m2_b.Z",
    ];
    assert_eq!(names, mitsuba);
    assert_eq!(both.nonfinite_samples, 0);

    // The image and the first integrator's channels: `moment` around `path` alone.
    let path_alone = render(&scene(PATH));
    assert_eq!(both.image(), path_alone.image());
    assert_eq!(of(&ch, "_arg_0"), of(&channels(&path_alone), "_arg_0"));
    // The second's: `moment` around `direct` alone, then its only (first) integrator.
    let direct_alone = render(&scene(r#"<integrator type="direct"/>"#));
    let direct = of(&channels(&direct_alone), "_arg_0");
    assert_eq!(of(&ch, "b"), direct);
    // Not trivially: the two integrators' channels differ (path adds a bounce).
    assert_ne!(of(&ch, "_arg_0")[1], direct[1]);
    assert!(direct[1].iter().all(|v| v.is_finite() && *v >= 0.0));
}

#[test]
fn a_render_in_parts_is_refused_with_several_nested_integrators() {
    let desc = scene(&format!("{PATH}{DIRECT}"));
    let opts = RenderOptions {
        samples: Some("0..4".parse().expect("range")),
        ..RenderOptions::default()
    };
    let msg = match Renderer::new(&desc, &opts) {
        Ok(_) => panic!("a part of a two-integrator moment render was made"),
        Err(e) => e.to_string(),
    };
    assert!(msg.contains("several nested integrators"), "{msg}");
    // One nested integrator still renders in parts (`tests/it/distributed_moment.rs`).
    Renderer::new(&scene(PATH), &opts).expect("one nested integrator renders a part");
}
