//! The perspective camera against Mitsuba 3's conventions on the Cornell box sensor
//! (`tests/data/cornell-box.xml`: origin (0, 0, 3.9) looking at the origin, up +y,
//! fov 39.3077° along the smaller axis, 256×256).

use mcrt::glam::{Mat4, Vec2, Vec3, Vec4};
use mcrt_render::camera::Camera;
use mcrt_render::description::{FilmDesc, FovAxis, SensorDesc, ShapeDesc, ShapeKind};
use mcrt_render::geometry::{AccelKind, Geometry};

/// Mitsuba's `lookat`: columns (left, up, dir, origin) with left = up × dir.
fn lookat(origin: Vec3, target: Vec3, up: Vec3) -> Mat4 {
    let dir = (target - origin).normalize();
    let left = up.normalize().cross(dir).normalize();
    let new_up = dir.cross(left);
    Mat4::from_cols(
        left.extend(0.0),
        new_up.extend(0.0),
        dir.extend(0.0),
        origin.extend(1.0),
    )
}

fn cornell_sensor(w: u32, h: u32) -> SensorDesc {
    SensorDesc {
        fov: 39.3077,
        fov_axis: FovAxis::Smaller,
        near_clip: 0.001,
        far_clip: 100.0,
        to_world: lookat(Vec3::new(0.0, 0.0, 3.9), Vec3::ZERO, Vec3::Y),
        film: mcrt_render::description::Checked::new(FilmDesc {
            width: w,
            height: h,
            ..FilmDesc::default()
        })
        .unwrap(),
        ..SensorDesc::default()
    }
}

fn angle(a: Vec3, b: Vec3) -> f32 {
    a.normalize()
        .dot(b.normalize())
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

#[test]
fn centre_and_edges_of_the_cornell_box_view() {
    let cam = Camera::new(&cornell_sensor(256, 256)).unwrap();
    let centre = cam.generate_ray(Vec2::new(128.0, 128.0));
    assert!(centre.dir.is_finite() && centre.origin.is_finite());
    assert!((centre.dir - -Vec3::Z).length() < 1e-6, "{}", centre.dir);
    assert!((centre.origin - Vec3::new(0.0, 0.0, 3.9 - 0.001)).length() < 1e-6);
    let half = 39.3077 / 2.0;
    // Middle of the left edge looks left (world −x), half the fov off the axis.
    let left = cam.generate_ray(Vec2::new(0.0, 128.0)).dir;
    assert!(left.x < 0.0 && left.y.abs() < 1e-6);
    assert!((angle(left, -Vec3::Z) - half).abs() < 1e-3);
    // Middle of the top edge looks up (world +y).
    let top = cam.generate_ray(Vec2::new(128.0, 0.0)).dir;
    assert!(top.y > 0.0 && top.x.abs() < 1e-6);
    assert!((angle(top, -Vec3::Z) - half).abs() < 1e-3);
    // The top-left corner: tan of the angle is √2 · tan(fov/2).
    let corner = cam.generate_ray(Vec2::ZERO).dir;
    let want = (2f32.sqrt() * half.to_radians().tan()).atan().to_degrees();
    assert!(corner.x < 0.0 && corner.y > 0.0);
    assert!((angle(corner, -Vec3::Z) - want).abs() < 1e-3);
    assert!((corner.length() - 1.0).abs() < 1e-6);
    // Bottom-right corner (w, h) mirrors it.
    let br = cam.generate_ray(Vec2::new(256.0, 256.0)).dir;
    assert!((br - corner * Vec3::new(-1.0, -1.0, 1.0)).length() < 1e-6);
}

#[test]
fn image_left_sees_the_red_wall() {
    let red_wall = {
        let mut s = ShapeDesc::new(ShapeKind::Rectangle);
        s.to_world = Mat4::from_cols(
            Vec4::new(0.0, 0.0, -1.0, 0.0),
            Vec4::new(0.0, 1.0, 0.0, 0.0),
            Vec4::new(1.0, 0.0, 0.0, 0.0),
            Vec4::new(-1.0, 0.0, 0.0, 1.0),
        );
        s
    };
    let green_wall = {
        let mut s = red_wall.clone();
        s.to_world = Mat4::from_cols(
            Vec4::new(0.0, 0.0, 1.0, 0.0),
            Vec4::new(0.0, 1.0, 0.0, 0.0),
            Vec4::new(-1.0, 0.0, 0.0, 0.0),
            Vec4::new(1.0, 0.0, 0.0, 1.0),
        );
        s
    };
    let g = Geometry::new(&[red_wall, green_wall], None, AccelKind::Bvh).unwrap();
    let cam = Camera::new(&cornell_sensor(256, 256)).unwrap();
    let (ray, t_max) = cam.generate_ray_with_tmax(Vec2::new(20.5, 128.5));
    assert!(t_max.is_finite() && t_max > 90.0);
    let hit = g
        .intersect(&ray, t_max)
        .expect("image left must see a wall");
    assert_eq!(
        hit.shape, 0,
        "the red wall is at x = -1, on the image's left"
    );
    assert!((hit.p.x + 1.0).abs() < 1e-5);
    let hit = g
        .intersect(&cam.generate_ray(Vec2::new(235.5, 128.5)), t_max)
        .unwrap();
    assert_eq!(hit.shape, 1, "the green wall is on the image's right");
}

#[test]
fn fov_axis_on_a_wide_film() {
    // 512×256 with fov along "smaller" = y: the vertical half-angle is fov/2.
    let cam = Camera::new(&cornell_sensor(512, 256)).unwrap();
    let top = cam.generate_ray(Vec2::new(256.0, 0.0)).dir;
    assert!((angle(top, -Vec3::Z) - 39.3077 / 2.0).abs() < 1e-3);
    let mut s = cornell_sensor(512, 256);
    s.fov_axis = FovAxis::Larger;
    let cam = Camera::new(&s).unwrap();
    let left = cam.generate_ray(Vec2::new(0.0, 128.0)).dir;
    assert!((angle(left, -Vec3::Z) - 39.3077 / 2.0).abs() < 1e-3);
}

#[test]
fn far_clip_bounds_the_ray() {
    let mut s = cornell_sensor(64, 64);
    s.far_clip = 2.0;
    s.near_clip = 0.5;
    let cam = Camera::new(&s).unwrap();
    for &p in &[Vec2::ZERO, Vec2::new(32.0, 32.0), Vec2::new(64.0, 10.0)] {
        let (ray, t_max) = cam.generate_ray_with_tmax(p);
        assert!(t_max.is_finite());
        // Camera-space depth (distance along -z from z = 3.9) of start and end.
        assert!((3.9 - ray.origin.z - 0.5).abs() < 1e-5);
        assert!((3.9 - ray.at(t_max).z - 2.0).abs() < 1e-5);
    }
}
