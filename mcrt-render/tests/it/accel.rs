//! The BVH, the uniform grid and the kd-tree against brute force, on random rays over random
//! triangle soups, spheres and disks, the Cornell box, a closed tessellated sphere, and
//! degenerate cases (axis-parallel rays, rays starting on surfaces, zero-area triangles; for
//! all structures, and in `kdtree_degenerate_scenes` one primitive, primitives with one
//! common box, flat primitives in a few planes, coordinates from 10⁻³ to 10⁶).
//!
//! For every ray: the same nearest `t` (relative 1e-4), the same shape and primitive (unless
//! two primitives tie at the same `t`, e.g. on a shared edge), and the same occlusion answer
//! for a random `t_max`. The BVH tests triangle pairs forming parallelograms as one quad,
//! which reaches a relative 2⁻¹⁴ of its edges past its border (so that rays cannot leak
//! between faces): there, and only there (a barycentric weight of the hit within 10⁻⁴ of
//! 0), the BVH may hit where brute force misses or finds something farther. And for rays
//! starting exactly on a surface, whether that surface is hit again at `t ≈ 0` (below
//! 10⁻⁵) depends on rounding, which differs between the quad and the triangle test.
//!
//! Throughput and build time are measured in `benches/accel.rs` (`cargo bench --features bench --bench accel`).

use mcrt::glam::{Mat4, Vec3};
use mcrt::integrator::SurfacePoint;
use mcrt_render::description::{ShapeDesc, ShapeKind};
use mcrt_render::geometry::{AccelKind, Geometry, Ray};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

#[path = "common/scenes.rs"]
mod scenes;
use scenes::{cornell_box, mesh, point, random_rays, soup, tessellated_sphere, unit_vec};

fn rng(seed: u64) -> Pcg64 {
    Pcg64::seed_from_u64(seed)
}

fn sphere(c: Vec3, r: f32) -> ShapeDesc {
    ShapeDesc::new(ShapeKind::Sphere {
        center: c,
        radius: r,
    })
}

struct Stats {
    rays: usize,
    hits: usize,
    ties: usize,
    /// BVH hits in a quad's slack band (see [`slack_hit`]).
    slack: usize,
}

/// A triangle hit within 10⁻⁴ (in barycentric weight) of the triangle's border: where a
/// BVH quad's slack may reach.
fn on_border(shapes: &[ShapeDesc], h: &SurfacePoint) -> bool {
    let triangles = !matches!(
        shapes[h.shape as usize].kind,
        ShapeKind::Sphere { .. } | ShapeKind::Disk
    );
    let w = [1.0 - h.uv.x - h.uv.y, h.uv.x, h.uv.y];
    triangles && w.iter().any(|&w| w.is_finite() && w < 1e-4)
}

/// `a` (the BVH's answer) may hit in a quad's slack band where brute force (`b`) misses or
/// hits something farther; either may hit the surface the ray starts on where the other
/// does not.
fn slack_hit(shapes: &[ShapeDesc], a: &Option<SurfacePoint>, b: &Option<SurfacePoint>) -> bool {
    fn first<'h>(
        x: &'h Option<SurfacePoint>,
        y: &Option<SurfacePoint>,
    ) -> Option<&'h SurfacePoint> {
        match (x, y) {
            (Some(x), None) => Some(x),
            (Some(x), Some(y)) if x.t < y.t => Some(x),
            _ => None,
        }
    }
    let self_hit = |x: Option<&SurfacePoint>| x.is_some_and(|h| h.t < 1e-5);
    first(a, b).is_some_and(|h| on_border(shapes, h))
        || self_hit(first(a, b))
        || self_hit(first(b, a))
}

fn same_hit(
    a: &Option<SurfacePoint>,
    b: &Option<SurfacePoint>,
    what: &str,
    ray: &Ray,
    stats: &mut Stats,
) {
    match (a, b) {
        (None, None) => {}
        (Some(a), Some(b)) => {
            assert!(
                a.t.is_finite() && b.t.is_finite(),
                "{what}: non-finite t {ray:?}"
            );
            let tol = 1e-4 * b.t.abs().max(1e-6);
            assert!(
                (a.t - b.t).abs() <= tol,
                "{what}: t {} vs {} for {ray:?}",
                a.t,
                b.t
            );
            if (a.shape, a.prim) != (b.shape, b.prim) {
                assert!(
                    (a.t - b.t).abs() <= 1e-6 * b.t.abs().max(1e-6),
                    "{what}: different primitive at different t: {a:?} vs {b:?} for {ray:?}"
                );
                stats.ties += 1;
            }
            stats.hits += 1;
        }
        _ => panic!("{what}: hit vs no hit: {a:?} vs {b:?} for {ray:?}"),
    }
}

/// Checks BVH, grid and kd-tree against brute force on the given rays, and the 8-wide BVH
/// against the 4-wide one (the same hit but for ties, the same occlusion).
fn compare(shapes: &[ShapeDesc], rays: &[Ray], seed: u64) -> Stats {
    let brute = Geometry::new(shapes, None, AccelKind::BruteForce).unwrap();
    let bvh = Geometry::new(shapes, None, AccelKind::Bvh).unwrap();
    let bvh8 = Geometry::new(shapes, None, AccelKind::Bvh8).unwrap();
    let grid = Geometry::new(shapes, None, AccelKind::Grid).unwrap();
    let kd = Geometry::new(shapes, None, AccelKind::KdTree).unwrap();
    let mut r = rng(seed);
    let mut stats = Stats {
        rays: 0,
        hits: 0,
        ties: 0,
        slack: 0,
    };
    for ray in rays {
        let want = brute.intersect(ray, f32::INFINITY);
        let got = bvh.intersect(ray, f32::INFINITY);
        match (&got, &bvh8.intersect(ray, f32::INFINITY)) {
            (Some(a), Some(b)) if a != b => {
                assert!(a.t.is_finite() && b.t.is_finite());
                // Which of two primitives at (nearly) the same distance is met first.
                assert!((a.t - b.t).abs() <= 1e-6 * a.t, "bvh8: {b:?} vs {a:?}");
                stats.ties += 1;
            }
            (a, b) => assert_eq!(a, b, "bvh8 vs bvh for {ray:?}"),
        }
        if slack_hit(shapes, &got, &want) {
            stats.slack += 1;
        } else {
            same_hit(&got, &want, "bvh", ray, &mut stats);
        }
        same_hit(
            &grid.intersect(ray, f32::INFINITY),
            &want,
            "grid",
            ray,
            &mut stats,
        );
        same_hit(
            &kd.intersect(ray, f32::INFINITY),
            &want,
            "kdtree",
            ray,
            &mut stats,
        );
        let t_max = r.random_range(0.0f32..4.0);
        let occ = brute.occluded(ray, t_max);
        let bvh_occ = bvh.occluded(ray, t_max);
        assert_eq!(
            bvh8.occluded(ray, t_max),
            bvh_occ,
            "bvh8 occlusion {ray:?} t_max {t_max}"
        );
        let slack = || {
            slack_hit(
                shapes,
                &bvh.intersect(ray, t_max),
                &brute.intersect(ray, t_max),
            )
        };
        assert!(
            bvh_occ == occ || slack(),
            "bvh occlusion {ray:?} t_max {t_max}"
        );
        assert_eq!(
            grid.occluded(ray, t_max),
            occ,
            "grid occlusion {ray:?} t_max {t_max}"
        );
        assert_eq!(
            kd.occluded(ray, t_max),
            occ,
            "kdtree occlusion {ray:?} t_max {t_max}"
        );
        // Occlusion agrees with the nearest hit (away from the exact hit distance).
        if let Some(h) = &want {
            if (h.t - t_max).abs() > 1e-4 * h.t {
                assert_eq!(occ, h.t < t_max, "occluded vs intersect {ray:?}");
            }
        }
        stats.rays += 1;
    }
    stats.hits /= 3;
    // Rare on random rays; rays running inside the Cornell box's face planes meet the other
    // faces exactly at their borders, so up to a tenth there.
    assert!(
        stats.slack <= stats.rays / 10,
        "{} slack hits of {}",
        stats.slack,
        stats.rays
    );
    stats
}

fn axis_rays(r: &mut Pcg64, n: usize, h: f32) -> Vec<Ray> {
    (0..n)
        .map(|k| {
            let axis = Vec3::AXES[k % 3] * if k % 2 == 0 { 1.0 } else { -1.0 };
            Ray {
                origin: point(r, h),
                dir: axis,
            }
        })
        .collect()
}

/// Rays starting exactly on the surface of a hit (no offset), in random directions.
fn surface_rays(g: &Geometry, r: &mut Pcg64, n: usize) -> Vec<Ray> {
    let mut out = Vec::new();
    while out.len() < n {
        let probe = Ray {
            origin: point(r, 1.5),
            dir: unit_vec(r),
        };
        if let Some(h) = g.intersect(&probe, f32::INFINITY) {
            out.push(Ray {
                origin: h.p,
                dir: unit_vec(r),
            });
        }
    }
    out
}

#[test]
fn triangle_soup_random_axis_and_surface_rays() {
    let mut r = rng(1);
    let shapes = vec![soup(&mut r, 3000)];
    let g = Geometry::new(&shapes, None, AccelKind::BruteForce).unwrap();
    let mut rays = random_rays(&mut r, 3000, 2.0);
    rays.extend(axis_rays(&mut r, 1500, 1.2));
    rays.extend(surface_rays(&g, &mut r, 1000));
    let s = compare(&shapes, &rays, 2);
    assert!(
        s.hits > s.rays / 4,
        "too few hits to mean anything: {}",
        s.hits
    );
    assert!(s.ties < s.rays / 100);
}

#[test]
fn spheres_disks_and_triangles_mixed() {
    let mut r = rng(3);
    let mut shapes: Vec<ShapeDesc> = (0..60)
        .map(|_| sphere(point(&mut r, 1.0), r.random_range(0.02f32..0.3)))
        .collect();
    for _ in 0..40 {
        let mut d = ShapeDesc::new(ShapeKind::Disk);
        d.to_world = Mat4::from_scale_rotation_translation(
            Vec3::new(0.2, 0.1, 1.0),
            mcrt::glam::Quat::from_axis_angle(unit_vec(&mut r), 1.0),
            point(&mut r, 1.0),
        );
        shapes.push(d);
    }
    shapes.push(soup(&mut r, 200));
    let g = Geometry::new(&shapes, None, AccelKind::BruteForce).unwrap();
    let mut rays = random_rays(&mut r, 3000, 2.0);
    rays.extend(axis_rays(&mut r, 1500, 1.2));
    rays.extend(surface_rays(&g, &mut r, 1000));
    let s = compare(&shapes, &rays, 4);
    assert!(s.hits > s.rays / 4, "too few hits: {}", s.hits);
}

#[test]
fn cornell_box_rays_from_inside_always_hit() {
    let shapes = cornell_box();
    let mut r = rng(5);
    let mut rays = random_rays(&mut r, 4000, 0.99);
    rays.extend(axis_rays(&mut r, 2000, 0.99));
    // Rays through the exact corners and edges of the box.
    for &c in &[
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(-1.0, -1.0, -1.0),
        Vec3::new(1.0, -1.0, 0.0),
    ] {
        rays.push(Ray {
            origin: Vec3::ZERO,
            dir: c,
        });
    }
    // Rays running inside the planes of the walls and box faces (a zero direction
    // component, the origin exactly on the plane): they meet edges of other faces.
    for k in 0..600 {
        let a = k % 3;
        let mut o = point(&mut r, 0.99);
        o[a] = [-1.0, 1.0, -0.4, 0.0][k % 4];
        let mut d = unit_vec(&mut r);
        d[a] = 0.0;
        rays.push(Ray { origin: o, dir: d });
    }
    let g = Geometry::new(&shapes, None, AccelKind::Bvh).unwrap();
    rays.extend(surface_rays(&g, &mut r, 1000));
    let s = compare(&shapes, &rays, 6);
    // The box is open at z = +1 only; every ray from inside heading to z < 0... hits.
    let closed_dirs = rays
        .iter()
        .filter(|ray| ray.origin.abs().max_element() < 0.99 && ray.dir.z < 0.0)
        .filter(|ray| g.intersect(ray, f32::INFINITY).is_none())
        .count();
    assert_eq!(closed_dirs, 0);
    assert!(s.hits > s.rays / 2);
}

#[test]
fn closed_tessellated_sphere_is_watertight() {
    let shapes = vec![tessellated_sphere(24, 48)];
    let positions = match &shapes[0].kind {
        ShapeKind::Mesh { positions, .. } => positions.clone(),
        _ => unreachable!(),
    };
    let mut r = rng(7);
    // Rays from inside aimed exactly at vertices and edge midpoints, and random ones.
    let mut rays = Vec::new();
    for w in positions.windows(2) {
        let o = point(&mut r, 0.3);
        rays.push(Ray {
            origin: o,
            dir: w[0] - o,
        });
        rays.push(Ray {
            origin: o,
            dir: 0.5 * (w[0] + w[1]) - o,
        });
    }
    rays.extend(random_rays(&mut r, 2000, 0.5));
    for kind in [
        AccelKind::Bvh,
        AccelKind::Bvh8,
        AccelKind::Grid,
        AccelKind::KdTree,
        AccelKind::BruteForce,
    ] {
        let g = Geometry::new(&shapes, None, kind).unwrap();
        for ray in &rays {
            assert!(
                g.intersect(ray, f32::INFINITY).is_some(),
                "{kind:?} leaked {ray:?}"
            );
        }
    }
    compare(&shapes, &rays, 8);
}

#[test]
fn planar_scene_and_empty_scene() {
    // All geometry in one plane: the grid and BVH have zero thickness along z.
    let mut r = rng(9);
    let pos: Vec<Vec3> = (0..300)
        .map(|_| point(&mut r, 1.0) * Vec3::new(1.0, 1.0, 0.0))
        .collect();
    let idx = (0..100u32).map(|k| [3 * k, 3 * k + 1, 3 * k + 2]).collect();
    let shapes = vec![mesh(pos, idx)];
    let mut rays = random_rays(&mut r, 2000, 1.5);
    rays.extend(axis_rays(&mut r, 600, 1.0));
    compare(&shapes, &rays, 10);
    for kind in [
        AccelKind::Bvh,
        AccelKind::Bvh8,
        AccelKind::Grid,
        AccelKind::KdTree,
        AccelKind::BruteForce,
    ] {
        let g = Geometry::new(&[] as &[ShapeDesc], None, kind).unwrap();
        let ray = Ray {
            origin: Vec3::ZERO,
            dir: Vec3::Z,
        };
        assert!(g.intersect(&ray, f32::INFINITY).is_none() && !g.occluded(&ray, 1.0));
    }
}

/// Rays from near the origin aimed at `target` give or take `spread` in each coordinate.
fn aimed_rays(r: &mut Pcg64, n: usize, target: Vec3, spread: f32) -> Vec<Ray> {
    (0..n)
        .map(|_| {
            let origin = point(r, 1.0);
            Ray {
                origin,
                dir: target + point(r, spread) - origin,
            }
        })
        .collect()
}

/// The kd-tree (with BVH and grid) against brute force where a kd-tree build is easily
/// fooled: one primitive; sixty triangles with the same box (the unit cube) and ten exact
/// duplicates among them, so no plane separates anything and hits tie; axis-aligned squares
/// and triangles in five parallel planes (boxes flat along z, many sharing a plane); small
/// triangles near the origin beside large ones 10⁶ away (huge coordinate range). No panic,
/// and the same answers as brute force.
#[test]
fn kdtree_degenerate_scenes() {
    let mut r = rng(15);
    let tri = |a: Vec3, b: Vec3, c: Vec3| mesh(vec![a, b, c], vec![[0, 1, 2]]);
    // One primitive.
    let one = vec![tri(
        Vec3::new(-0.5, -0.5, 0.2),
        Vec3::new(0.6, -0.4, -0.1),
        Vec3::new(0.0, 0.7, 0.0),
    )];
    let mut rays = random_rays(&mut r, 1500, 1.5);
    rays.extend(aimed_rays(&mut r, 500, Vec3::ZERO, 0.5));
    compare(&one, &rays, 16);
    compare(&[sphere(Vec3::new(0.2, 0.0, 0.0), 0.5)], &rays, 17);
    // Sixty triangles whose boxes are all [0, 1]³ (a vertex on x = 0 and y = 1, one on
    // x = 1 and z = 1, one on y = 0 and z = 0), ten of them repeated exactly.
    let mut pos = Vec::new();
    for k in 0..60 {
        let v = if k % 6 == 5 {
            [pos[pos.len() - 3], pos[pos.len() - 2], pos[pos.len() - 1]]
        } else {
            let u = |r: &mut Pcg64| r.random_range(0.0f32..1.0);
            [
                Vec3::new(0.0, 1.0, u(&mut r)),
                Vec3::new(1.0, u(&mut r), 1.0),
                Vec3::new(u(&mut r), 0.0, 0.0),
            ]
        };
        pos.extend(v);
    }
    let idx = (0..60u32).map(|k| [3 * k, 3 * k + 1, 3 * k + 2]).collect();
    let same_box = vec![mesh(pos, idx)];
    let mut rays = random_rays(&mut r, 2000, 1.5);
    rays.extend(aimed_rays(&mut r, 1000, Vec3::splat(0.5), 0.5));
    rays.extend(axis_rays(&mut r, 600, 1.2));
    compare(&same_box, &rays, 18);
    // Flat along z: squares filling [-1, 1]² at z = -0.5 … 0.5, and 200 small triangles,
    // each in one of those planes.
    let mut flat = Vec::new();
    for k in 0..5 {
        let z = -0.5 + 0.25 * k as f32;
        let mut sq = ShapeDesc::new(ShapeKind::Rectangle);
        sq.to_world = Mat4::from_translation(Vec3::new(0.0, 0.0, z))
            * Mat4::from_scale(Vec3::new(0.3 + 0.15 * k as f32, 1.0, 1.0));
        flat.push(sq);
    }
    for _ in 0..200 {
        let z = -0.5 + 0.25 * r.random_range(0..5) as f32;
        let c = point(&mut r, 1.0) * Vec3::new(1.0, 1.0, 0.0) + Vec3::new(0.0, 0.0, z);
        let v = |r: &mut Pcg64| c + point(r, 0.1) * Vec3::new(1.0, 1.0, 0.0);
        flat.push(tri(v(&mut r), v(&mut r), v(&mut r)));
    }
    let mut rays = random_rays(&mut r, 2000, 1.2);
    rays.extend(axis_rays(&mut r, 600, 1.0));
    // Rays running inside the planes of the squares.
    for k in 0..300 {
        let mut o = point(&mut r, 1.0);
        o.z = -0.5 + 0.25 * (k % 5) as f32;
        let mut d = unit_vec(&mut r);
        d.z = 0.0;
        rays.push(Ray { origin: o, dir: d });
    }
    compare(&flat, &rays, 19);
    // Small triangles (edges ~10⁻³) near the origin and large ones (edges ~10⁵) at
    // distance 10⁶ along ±x and +y.
    let mut wide: Vec<ShapeDesc> = (0..300)
        .map(|_| {
            let c = point(&mut r, 0.5);
            tri(
                c + point(&mut r, 1e-3),
                c + point(&mut r, 1e-3),
                c + point(&mut r, 1e-3),
            )
        })
        .collect();
    let far = [1e6 * Vec3::X, -1e6 * Vec3::X, 1e6 * Vec3::Y];
    for c in far {
        for _ in 0..20 {
            let c = c + point(&mut r, 1e5);
            wide.push(tri(
                c + point(&mut r, 1e5),
                c + point(&mut r, 1e5),
                c + point(&mut r, 1e5),
            ));
        }
    }
    let mut rays = random_rays(&mut r, 1000, 0.6);
    for c in far {
        rays.extend(aimed_rays(&mut r, 500, c, 1e5));
    }
    // Rays leaving the small triangles from points on them (the triangles' centroids).
    for shape in &wide[..300] {
        if let ShapeKind::Mesh { positions, .. } = &shape.kind {
            let c = (positions[0] + positions[1] + positions[2]) / 3.0;
            rays.push(Ray {
                origin: c,
                dir: unit_vec(&mut r),
            });
        }
    }
    let s = compare(&wide, &rays, 20);
    assert!(s.hits > s.rays / 10, "too few hits: {}", s.hits);
}

#[test]
fn hit_data_on_cornell_box() {
    let g = Geometry::new(&cornell_box(), None, AccelKind::Bvh).unwrap();
    // Looking up from the centre: the light (shape 0) faces down (-y).
    let up = Ray {
        origin: Vec3::ZERO,
        dir: Vec3::Y,
    };
    let h = g.intersect(&up, f32::INFINITY).unwrap();
    assert!(h.t.is_finite() && (h.t - 0.99).abs() < 1e-5);
    assert_eq!(h.shape, 0);
    assert!((h.ng - -Vec3::Y).length() < 1e-5, "light normal {}", h.ng);
    // The red wall (shape 5) at x = -1 faces +x, the floor (1) faces +y.
    let left = Ray {
        origin: Vec3::new(0.0, 0.5, 0.5),
        dir: -Vec3::X,
    };
    let h = g.intersect(&left, f32::INFINITY).unwrap();
    assert_eq!(h.shape, 5);
    assert!((h.ng - Vec3::X).length() < 1e-5 && (h.p.x + 1.0).abs() < 1e-6);
    let down = Ray {
        origin: Vec3::new(0.9, 0.0, 0.9),
        dir: -Vec3::Y,
    };
    let h = g.intersect(&down, f32::INFINITY).unwrap();
    assert_eq!(h.shape, 1);
    assert!((h.ng - Vec3::Y).length() < 1e-5);
    // The small box's top face points up.
    let onto_box = Ray {
        origin: Vec3::new(0.335, 0.5, 0.38),
        dir: -Vec3::Y,
    };
    let h = g.intersect(&onto_box, f32::INFINITY).unwrap();
    assert_eq!(h.shape, 6);
    assert!((h.ng - Vec3::Y).length() < 1e-5 && (h.p.y + 0.4).abs() < 1e-5);
    assert_eq!(h.frame.n, h.ng);
}

#[test]
fn obj_meshes_load_relative_to_the_base_dir() {
    let dir = std::env::temp_dir().join(format!("mcrt-geometry-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // A unit quad at z = 0 facing +z, with vertex normals tilted towards +x.
    let text = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvn 0.6 0 0.8\nf 1//1 2//1 3//1 4//1\n";
    std::fs::write(dir.join("quad.obj"), text).unwrap();
    let obj = |face_normals| {
        let mut s = ShapeDesc::new(ShapeKind::Obj {
            filename: "quad.obj".into(),
            face_normals,
            flip_tex_coords: true,
        });
        s.to_world = Mat4::from_translation(Vec3::new(0.0, 0.0, -1.0));
        s
    };
    let ray = Ray {
        origin: Vec3::new(0.2, 0.3, 1.0),
        dir: -Vec3::Z,
    };
    let g = Geometry::new(&[obj(false)], Some(&dir), AccelKind::Bvh).unwrap();
    let h = g.intersect(&ray, f32::INFINITY).unwrap();
    assert!(h.t.is_finite() && (h.t - 2.0).abs() < 1e-6);
    assert!((h.ng - Vec3::Z).length() < 1e-6);
    assert!(
        (h.frame.n - Vec3::new(0.6, 0.0, 0.8)).length() < 1e-5,
        "ns {}",
        h.frame.n
    );
    let g = Geometry::new(&[obj(true)], Some(&dir), AccelKind::Grid).unwrap();
    let h = g.intersect(&ray, f32::INFINITY).unwrap();
    assert_eq!(h.frame.n, h.ng);
    // A missing file is an error that names it.
    let mut missing = obj(false);
    missing.kind = ShapeKind::Obj {
        filename: "nope.obj".into(),
        face_normals: false,
        flip_tex_coords: true,
    };
    let err = Geometry::new(&[missing], Some(&dir), AccelKind::Bvh).unwrap_err();
    assert!(err.to_string().contains("nope.obj"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn invalid_shapes_are_errors() {
    let mut s = sphere(Vec3::ZERO, 1.0);
    s.to_world = Mat4::from_scale(Vec3::new(1.0, 2.0, 1.0));
    assert!(Geometry::new(&[s], None, AccelKind::Bvh).is_err());
    assert!(Geometry::new(&[sphere(Vec3::ZERO, -1.0)], None, AccelKind::Bvh).is_err());
    let bad_index = mesh(vec![Vec3::ZERO; 3], vec![[0, 1, 3]]);
    assert!(Geometry::new(&[bad_index], None, AccelKind::Bvh).is_err());
    let mut singular = ShapeDesc::new(ShapeKind::Rectangle);
    singular.to_world = Mat4::from_scale(Vec3::new(1.0, 0.0, 1.0));
    assert!(Geometry::new(&[singular], None, AccelKind::Bvh).is_err());
    let nan = mesh(vec![Vec3::NAN; 3], vec![[0, 1, 2]]);
    assert!(Geometry::new(&[nan], None, AccelKind::Bvh).is_err());
}

#[test]
fn geometry_and_camera_are_shareable_across_threads() {
    fn shareable<T: Send + Sync>() {}
    shareable::<Geometry>();
    shareable::<mcrt_render::camera::Camera>();
    // Queries from several threads at once agree with one thread (per-thread stacks).
    let g = Geometry::new(&cornell_box(), None, AccelKind::Bvh).unwrap();
    let mut r = rng(12);
    let rays = random_rays(&mut r, 2000, 0.9);
    let serial: Vec<Option<f32>> = rays
        .iter()
        .map(|ray| g.intersect(ray, f32::INFINITY).map(|h| h.t))
        .collect();
    std::thread::scope(|s| {
        for _ in 0..3 {
            s.spawn(|| {
                for (ray, want) in rays.iter().zip(&serial) {
                    assert_eq!(g.intersect(ray, f32::INFINITY).map(|h| h.t), *want);
                }
            });
        }
    });
}

/// Rays spawned from hits with `spawn_ray` (the offset policy) never hit their own flat
/// primitive again, on either side, whatever the direction (grazing included).
#[test]
fn spawned_rays_do_not_self_intersect() {
    use mcrt_render::geometry::spawn_ray;
    let mut shapes = cornell_box();
    shapes.push(tessellated_sphere(16, 32));
    // Move the tessellated sphere away from the origin so coordinates use ulp offsets.
    shapes.last_mut().unwrap().to_world = Mat4::from_translation(Vec3::new(40.0, -25.0, 60.0));
    let g = Geometry::new(&shapes, None, AccelKind::Bvh).unwrap();
    let mut r = rng(13);
    let mut starts = Vec::new();
    while starts.len() < 3000 {
        let origin = if starts.len() % 2 == 0 {
            point(&mut r, 0.9)
        } else {
            Vec3::new(40.0, -25.0, 60.0) + point(&mut r, 0.3)
        };
        let probe = Ray {
            origin,
            dir: unit_vec(&mut r),
        };
        if let Some(h) = g.intersect(&probe, f32::INFINITY) {
            starts.push(h);
        }
    }
    let mut rehits = 0;
    for h in &starts {
        for _ in 0..4 {
            let mut d = unit_vec(&mut r);
            if r.random::<f32>() < 0.3 {
                // Nearly grazing.
                d = (d - h.ng * d.dot(h.ng) * 0.9999).normalize();
            }
            let ray = spawn_ray(h.p, h.ng, d);
            if let Some(n) = g.intersect(&ray, f32::INFINITY) {
                if (n.shape, n.prim) == (h.shape, h.prim) {
                    rehits += 1;
                }
            }
        }
    }
    assert_eq!(rehits, 0);
}

/// Shadow rays from `spawn_ray_to` between two surface points: not occluded when the first
/// thing the open segment meets is the target itself, occluded when something lies well
/// before it.
#[test]
fn shadow_rays_between_surface_points() {
    use mcrt_render::geometry::{spawn_ray, spawn_ray_to};
    let g = Geometry::new(&cornell_box(), None, AccelKind::Bvh).unwrap();
    let mut r = rng(14);
    let mut hits = Vec::new();
    while hits.len() < 600 {
        let probe = Ray {
            origin: point(&mut r, 0.9),
            dir: unit_vec(&mut r),
        };
        if let Some(h) = g.intersect(&probe, f32::INFINITY) {
            hits.push(h);
        }
    }
    let (mut free, mut blocked) = (0, 0);
    for pair in hits.chunks(2) {
        let (a, b) = (&pair[0], &pair[1]);
        if a.shape == b.shape {
            continue; // coplanar (walls) or same box: the segment may run along a face
        }
        let (ray, t_max) = spawn_ray_to(a.p, a.ng, b.p, b.ng);
        // `t = 1` is b (the direction is b − a).
        let first = g.intersect(&spawn_ray(a.p, a.ng, b.p - a.p), f32::INFINITY);
        match first {
            Some(f) if (f.p - b.p).length() < 1e-4 => {
                assert!(!g.occluded(&ray, t_max), "{a:?} -> {b:?}");
                free += 1;
            }
            Some(f) if f.t < 0.99 => {
                assert!(g.occluded(&ray, t_max), "{a:?} -> {b:?} through {f:?}");
                blocked += 1;
            }
            _ => {}
        }
    }
    assert!(free > 50 && blocked > 10, "free {free}, blocked {blocked}");
}
