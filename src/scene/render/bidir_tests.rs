//! The bidirectional estimators' multiple-importance weights on the built-in scene: for
//! random paths of random scenes (diffuse, glass, mirror; smooth plastic, rough glass and a
//! mask, whose vertices may scatter by a Dirac part or by a density; area, point and
//! environment lights), the weights of every strategy that can make a path sum to 1, and
//! the weight the estimator computes from its own subpaths equals the one recomputed from
//! scratch.

use super::{RenderOptions, Renderer};
use crate::integrator::bdpt::{camera_subpath, connect, light_subpath, mis_weight, Heuristic};
use crate::integrator::bdpt::{Kind, Vertex, WalkLimits};
use crate::integrator::{EmitterKind, SampleSource};
use crate::scene::description::{
    BsdfDesc, ConductorFresnel, EmitterDesc, MicrofacetKind, SceneDescription, ShapeDesc, ShapeKind,
};
use glam::{Vec2, Vec3};
use rand_core::{RngCore, SeedableRng};
use rand_pcg::Pcg32;

struct Rng(Pcg32);

impl SampleSource for Rng {
    fn next_1d(&mut self) -> f32 {
        (self.0.next_u32() >> 8) as f32 / 16_777_216.0
    }
}

fn scenes() -> Vec<(&'static str, SceneDescription)> {
    let cornell = crate::scene::cornell_box::cornell_box_with(4, 32, -1);
    let caustic = crate::scene::loader::load_scene(
        &std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data/cornell-box-caustic.xml"),
        &[("res".into(), "32".into())],
    )
    .expect("caustic scene loads");
    let mut mixed = cornell.clone();
    let mut mirror = ShapeDesc::new(ShapeKind::Sphere {
        center: Vec3::new(-0.4, -0.6, 0.2),
        radius: 0.25,
    });
    mirror.bsdf = BsdfDesc::Conductor {
        fresnel: ConductorFresnel::Perfect,
        specular_reflectance: Vec3::ONE,
    };
    mixed.shapes.push(mirror);
    mixed.emitters.push(EmitterDesc::Point {
        position: Vec3::new(0.3, 0.5, 0.4),
        intensity: Vec3::splat(0.5),
    });
    // An open box would let rays escape; a dim environment is still sampled and hit by the
    // camera paths that leave through the open front.
    mixed.emitters.push(EmitterDesc::Constant {
        radiance: Vec3::splat(0.2),
    });
    let mut materials = cornell.clone();
    let sphere = |x: f32, bsdf: BsdfDesc| {
        let mut s = ShapeDesc::new(ShapeKind::Sphere {
            center: Vec3::new(x, -0.7, 0.1),
            radius: 0.25,
        });
        s.bsdf = bsdf;
        s
    };
    materials.shapes.push(sphere(
        -0.5,
        BsdfDesc::Plastic {
            int_ior: 1.49,
            ext_ior: 1.0,
            diffuse_reflectance: Vec3::new(0.8, 0.4, 0.1),
            specular_reflectance: Vec3::ONE,
            nonlinear: false,
        },
    ));
    materials.shapes.push(sphere(
        0.0,
        BsdfDesc::RoughDielectric {
            distribution: MicrofacetKind::Ggx,
            alpha: 0.3,
            int_ior: 1.5,
            ext_ior: 1.0,
            specular_reflectance: Vec3::ONE,
            specular_transmittance: Vec3::ONE,
        },
    ));
    materials.shapes.push(sphere(
        0.5,
        BsdfDesc::Mask {
            opacity: 0.5,
            inner: Box::new(BsdfDesc::TwoSided(Box::new(BsdfDesc::Diffuse {
                reflectance: Vec3::splat(0.6),
            }))),
        },
    ));
    // A thin lens: the camera vertex is a point on the aperture, not the pinhole.
    let mut lens = mixed.clone();
    lens.sensor.lens = Some(crate::scene::description::ThinLensDesc {
        aperture_radius: 0.2,
        focus_distance: 2.5,
    });
    vec![
        ("cornell", cornell),
        ("caustic", caustic),
        ("lens", lens),
        ("mixed", mixed),
        ("materials", materials),
    ]
}

/// The full path `light[..s] + camera[..t]` reversed, light end first. The connection's
/// endpoints scatter along the connection, not by the Dirac part their own walk may have
/// gone on by: in this path they are not delta.
fn full_path(light: &[Vertex], camera: &[Vertex], s: usize, t: usize) -> Vec<Vertex> {
    let mut p: Vec<Vertex> = light[..s].to_vec();
    p.extend(camera[..t].iter().rev());
    if s > 0 {
        p[s - 1] = p[s - 1].as_endpoint();
    }
    p[s] = p[s].as_endpoint();
    p
}

/// Strategy `s'` of the full path `p` with every density recomputed from scratch: the
/// light subpath `p[..s']` and the camera subpath `p[s'..]` reversed; `None` when that
/// strategy cannot make the path.
fn resplit<S: crate::integrator::BidirectionalScene>(
    scene: &S,
    p: &[Vertex],
    s: usize,
) -> Option<f32> {
    let n = p.len();
    let t = n - s;
    if t == 0 || (s, t) == (1, 1) {
        return None;
    }
    if s == 0 && (!p[0].is_light() || p[0].is_delta_light()) {
        return None;
    }
    if s > 0 && t > 0 {
        let (a, b) = (&p[s - 1], &p[s]);
        let ok = |v: &Vertex| v.connectible() && !v.delta;
        if !(ok(a) || (s == 1)) || !ok(b) {
            return None;
        }
    }
    let mut q: Vec<Vertex> = p.to_vec();
    // As a light endpoint, an emitting surface is an area light.
    if q[0].kind == Kind::Surface {
        q[0].kind = Kind::Light(EmitterKind::Area);
    }
    // Densities from the light side (pdf_fwd of light vertices); a direction a vertex
    // scattered into by a Dirac part has no density (the estimators store 0, whatever
    // density the BSDF's other parts give that direction).
    let from_light: Vec<f32> = (0..n)
        .map(|i| match i {
            0 => q[0].pdf_light_origin(scene, &q[1]),
            1 => q[0].pdf_light(scene, &q[1]),
            _ if q[i - 1].delta => 0.0,
            _ => q[i - 1].pdf(scene, Some(&q[i - 2]), &q[i]),
        })
        .collect();
    // Densities from the camera side.
    let from_camera: Vec<f32> = (0..n)
        .map(|i| {
            if i == n - 1 {
                1.0
            } else if i == n - 2 {
                q[n - 1].pdf(scene, None, &q[n - 2])
            } else if q[i + 1].delta {
                0.0
            } else {
                q[i + 1].pdf(scene, Some(&q[i + 2]), &q[i])
            }
        })
        .collect();
    // Each vertex's direction to its predecessor in its new subpath.
    let toward = |i: usize, j: usize| {
        let (w, d2) = q[i].dir_to(&q[j]);
        (w, d2)
    };
    let mut light: Vec<Vertex> = q[..s].to_vec();
    for (i, v) in light.iter_mut().enumerate() {
        v.pdf_fwd = from_light[i];
        v.pdf_rev = from_camera[i];
        if i > 0 {
            (v.w_prev, v.d2_prev) = toward(i, i - 1);
        }
    }
    let mut camera: Vec<Vertex> = q[s..].iter().rev().copied().collect();
    for (j, v) in camera.iter_mut().enumerate() {
        let i = n - 1 - j;
        v.pdf_fwd = from_camera[i];
        v.pdf_rev = from_light[i];
        if i + 1 < n {
            (v.w_prev, v.d2_prev) = toward(i, i + 1);
        }
        if i == s && s == 0 {
            // The emitter the camera path ends on is a surface vertex of that subpath.
            v.kind = p[0].kind;
        }
    }
    let sampled = match (s, t) {
        (1, _) => Some(light[0]),
        (_, 1) => Some(camera[0]),
        _ => None,
    };
    Some(mis_weight(
        scene,
        &light,
        &camera,
        sampled.as_ref(),
        s,
        t,
        Heuristic::Power,
    ))
}

#[test]
fn weights_of_all_strategies_sum_to_one() {
    let mut checked = 0;
    for (name, desc) in scenes() {
        let r = Renderer::new(&desc, &RenderOptions::default()).expect("scene builds");
        let view = r.view::<_, true, true>(r.bsdfs.clone());
        let lim = WalkLimits {
            max_vertices: 7,
            rr_depth: u32::MAX,
        };
        let mut rng = Rng(Pcg32::seed_from_u64(17));
        let (mut cam, mut light) = (Vec::new(), Vec::new());
        let mut rays = 0;
        for _ in 0..400 {
            let raster = rng.next_2d() * Vec2::splat(32.0);
            let (ray, t_max) = r.camera.generate_ray_through_lens(raster, rng.next_2d());
            camera_subpath(
                &view, ray.origin, ray.dir, t_max, lim, &mut rng, &mut cam, &mut rays,
            );
            light_subpath(&view, lim, &mut rng, &mut light, &mut rays);
            for t in 2..=cam.len() {
                for s in (0..=light.len()).filter(|&s| s != 1) {
                    if s + t < 3 {
                        continue;
                    }
                    let Some(c) = connect(
                        &view,
                        &light,
                        &cam,
                        s,
                        t,
                        Heuristic::Power,
                        &mut rng,
                        &mut rays,
                    ) else {
                        continue;
                    };
                    let p = full_path(&light, &cam, s, t);
                    let weights: Vec<(usize, f32)> = (0..p.len())
                        .filter_map(|k| resplit(&view, &p, k).map(|w| (k, w)))
                        .collect();
                    let sum: f32 = weights.iter().map(|x| x.1).sum();
                    assert!(
                        sum.is_finite() && (sum - 1.0).abs() < 2e-3,
                        "{name}: (s, t) = ({s}, {t}): weights {weights:?} sum to {sum}"
                    );
                    let own = weights.iter().find(|x| x.0 == s).map(|x| x.1);
                    // The estimator's densities use the sampled directions, the recomputed
                    // ones the directions between the points; where two vertices nearly
                    // touch (a corner), the ray offset makes the two differ: compare only
                    // paths whose segments are all longer than 2.5% of the box.
                    let short = p.windows(2).any(|w| {
                        let (_, d2) = w[0].dir_to(&w[1]);
                        d2.is_finite() && d2 < 2.5e-3
                    });
                    if short {
                        continue;
                    }
                    assert!(
                        own.is_some_and(|w| (w - c.weight).abs() <= 1e-3 + 1e-2 * w),
                        "{name}: ({s}, {t}): estimator's weight {} against {own:?}",
                        c.weight
                    );
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 1000, "only {checked} paths checked");
}
