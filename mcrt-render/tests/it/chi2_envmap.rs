//! The environment map's sampled directions against `EnvMap::pdf`, with the suite's
//! chi-square settings (`tests/common`), on maps with sharp bright features: a one-texel sun
//! 10⁵ times the sky, a bright meridian line, and a bright pole row over a dim next row (the
//! case where the pole vertices keep a density of their own). Each map is checked on the
//! whole sphere and on caps about its sharp features, finer there; a two-row map checks the
//! sub-rows the sampling grid adds to coarse maps.

use crate::common;

use common::{chi2, sphere};
use mcrt::glam::{Mat4, Vec3};
use mcrt::stats::Directions;
use mcrt_render::light::EnvMap;
use std::f32::consts::PI;

/// The world direction of map coordinates `(u, v)`.
fn direction(to_world: Mat4, u: f32, v: f32) -> Vec3 {
    let (st, ct) = (PI * v).sin_cos();
    let (sp, cp) = (2.0 * PI * u).sin_cos();
    to_world.transform_vector3(Vec3::new(st * sp, ct, -st * cp))
}

fn check(map: &EnvMap, dirs: Directions, name: &str) {
    let out =
        chi2(dirs, name).run_weighted(|u| map.sample(u).map(|(d, _, _)| (d, 1.0)), |d| map.pdf(d));
    assert!(out.passed(), "{}", out.report());
}

#[test]
fn a_sun_a_line_and_a_bright_pole() {
    let (w, h) = (64, 32);
    let to_world = Mat4::from_rotation_x(0.4) * Mat4::from_rotation_y(1.0);
    let mut t = vec![Vec3::new(0.02, 0.03, 0.05); w * h];
    for y in 0..h / 2 {
        t[y * w + 10] = Vec3::splat(5.0);
    }
    t[..w].fill(Vec3::new(40.0, 30.0, 20.0));
    t[6 * w + 40] = Vec3::splat(5000.0);
    let map = EnvMap::from_texels(w, h, t, to_world).expect("valid map");
    check(&map, sphere(), "envmap-sharp-sphere");
    let sun = direction(to_world, 40.5 / w as f32, 6.0 / (h - 1) as f32);
    let near_sun = Directions::cap(sun, 0.3).resolution(32, 64).refinement(1.0);
    check(&map, near_sun, "envmap-sharp-sun");
    let pole = direction(to_world, 0.0, 0.0);
    let near_pole = Directions::cap(pole, 0.25)
        .resolution(24, 64)
        .refinement(1.0);
    check(&map, near_pole, "envmap-sharp-pole");
}

#[test]
fn a_two_row_map_with_a_bright_texel() {
    let mut t = vec![Vec3::splat(0.1); 6];
    t[4] = Vec3::new(200.0, 100.0, 50.0);
    let map = EnvMap::from_texels(3, 2, t, Mat4::from_rotation_z(0.3)).expect("valid map");
    check(&map, sphere(), "envmap-two-rows");
}
