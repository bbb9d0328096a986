//! The Cornell box built in code: the same scene as `tests/data/cornell-box.xml` (Mitsuba
//! 3's `cornell_box()` with a box pixel filter), so the renderer needs no file to run.

use crate::description::{
    AreaEmitterDesc, BsdfDesc, Check, Checked, Colour, FilmDesc, FilterDesc, FovAxis,
    IntegratorDesc, PathParams, Projection, SampleCount, SamplerDesc, SamplerKind,
    SceneDescription, SensorDesc, ShapeDesc, ShapeKind,
};
use crate::transform::look_at;
use glam::{Mat4, Vec3};

/// The Cornell box with the file's defaults: 64 samples per pixel, 256 × 256 pixels,
/// unlimited path depth. Equal to loading `tests/data/cornell-box.xml`.
///
/// ```
/// let scene = mcrt_render::cornell_box::cornell_box();
/// assert_eq!(scene.shapes.len(), 8);
/// assert_eq!(scene.sensor.film.width, 256);
/// ```
pub fn cornell_box() -> SceneDescription {
    cornell_box_with(64, 256, -1)
}

/// The Cornell box with `spp` samples per pixel, a `res` × `res` film and path depth
/// `max_depth` (−1 unlimited, 2 direct lighting only): the file loaded with
/// `-D spp=… -D res=… -D max_depth=…`.
///
/// # Panics
/// If `spp` is 0 or above [`SampleCount::MAX`], `res` is 0 or too large a film, or
/// `max_depth` is below −1: every part is made by its checked constructor
/// ([`Checked::new`]), as the loader makes it.
pub fn cornell_box_with(spp: u32, res: u32, max_depth: i32) -> SceneDescription {
    let white = diffuse(0.885809, 0.698859, 0.666422);
    let red = diffuse(0.570068, 0.0430135, 0.0443706);
    let green = diffuse(0.105421, 0.37798, 0.076425);
    let rect = |id: &str, m: [f32; 16], bsdf: &BsdfDesc| shape(id, ShapeKind::Rectangle, m, bsdf);
    let cube = |id: &str, m: [f32; 16]| shape(id, ShapeKind::Cube, m, &white);
    let mut light = rect(
        "light",
        [
            0.23, 0., 0., 0., 0., 0., -0.19, 0.99, 0., 0.19, 0., 0.01, 0., 0., 0., 1.,
        ],
        &white,
    );
    light.emitter = Some(AreaEmitterDesc {
        radiance: Colour::known(Vec3::new(18.387, 13.9873, 6.75357)),
    });
    let shapes = [
        light,
        rect(
            "floor",
            [
                1., 0., 0., 0., 0., 0., 1., -1., 0., -1., 0., 0., 0., 0., 0., 1.,
            ],
            &white,
        ),
        rect(
            "ceiling",
            [
                1., 0., 0., 0., 0., 0., -1., 1., 0., 1., 0., 0., 0., 0., 0., 1.,
            ],
            &white,
        ),
        rect(
            "back",
            [
                1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., -1., 0., 0., 0., 1.,
            ],
            &white,
        ),
        rect(
            "green-wall",
            [
                0., 0., -1., 1., 0., 1., 0., 0., 1., 0., 0., 0., 0., 0., 0., 1.,
            ],
            &green,
        ),
        rect(
            "red-wall",
            [
                0., 0., 1., -1., 0., 1., 0., 0., -1., 0., 0., 0., 0., 0., 0., 1.,
            ],
            &red,
        ),
        cube(
            "small-box",
            [
                0.286891, 0., -0.0877115, 0.335, 0., 0.3, 0., -0.7, 0.0877115, 0., 0.286891, 0.38,
                0., 0., 0., 1.,
            ],
        ),
        cube(
            "large-box",
            [
                0.28491, 0., 0.0939491, -0.33, 0., 0.61, 0., -0.4, -0.0939491, 0., 0.28491, -0.28,
                0., 0., 0., 1.,
            ],
        ),
    ];
    SceneDescription {
        integrator: checked(IntegratorDesc::Path(PathParams {
            max_depth,
            ..PathParams::DEFAULT
        })),
        sensor: checked(sensor(spp, res)),
        shapes: shapes.into_iter().map(checked).collect(),
        emitters: Vec::new(),
        source: None,
        ..SceneDescription::default()
    }
}

/// `value` through its checked constructor; a refusal is a bad argument of
/// [`cornell_box_with`].
fn checked<T: Check>(value: T) -> Checked<T> {
    Checked::new(value).unwrap_or_else(|e| panic!("cornell_box_with: {e}"))
}

fn sensor(spp: u32, res: u32) -> SensorDesc {
    let to_world = look_at(Vec3::new(0.0, 0.0, 3.9), Vec3::ZERO, Vec3::Y).unwrap_or_default();
    SensorDesc {
        projection: Projection::Perspective,
        fov: 39.3077,
        fov_axis: FovAxis::Smaller,
        near_clip: 0.001,
        far_clip: 100.0,
        to_world,
        film: checked(FilmDesc {
            width: res,
            height: res,
            filter: FilterDesc::Box,
            crop: None,
        }),
        sampler: SamplerDesc {
            kind: SamplerKind::Independent,
            sample_count: SampleCount::new(spp).unwrap_or_else(|e| panic!("cornell_box_with: {e}")),
            seed: 0,
        },
        lens: None,
    }
}

fn diffuse(r: f32, g: f32, b: f32) -> BsdfDesc {
    BsdfDesc::Diffuse {
        reflectance: Colour::known(Vec3::new(r, g, b)),
    }
}

/// A shape with a row-major object-to-world matrix.
fn shape(id: &str, kind: ShapeKind, m: [f32; 16], bsdf: &BsdfDesc) -> ShapeDesc {
    let mut s = ShapeDesc::new(kind);
    s.id = Some(id.to_string());
    s.to_world = Mat4::from_cols_array(&m).transpose();
    s.bsdf = bsdf.clone();
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn light_faces_down_and_boxes_stand_on_the_floor() {
        let s = cornell_box();
        let light = &s.shapes[0];
        assert!(light.emitter.is_some());
        let n = light.to_world.transform_vector3(Vec3::Z).normalize();
        assert!(n.is_finite() && (n - Vec3::NEG_Y).length() < 1e-6, "{n}");
        for b in &s.shapes[6..] {
            let bottom = b.to_world.transform_point3(Vec3::new(-1.0, -1.0, -1.0)).y;
            // Mitsuba's large box sinks 0.01 into the floor.
            assert!(
                bottom.is_finite() && (bottom + 1.0).abs() <= 0.0101,
                "{bottom}"
            );
        }
        let floor_normal = s.shapes[1].to_world.transform_vector3(Vec3::Z);
        assert!((floor_normal - Vec3::Y).length() < 1e-6);
    }
}
