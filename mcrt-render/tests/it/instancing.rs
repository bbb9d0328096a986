//! Shape groups and instances (issue 25): the loader reads `shapegroup` and `instance` as
//! Mitsuba 3 does and refuses what it refuses, with file and line; an instanced shape is hit
//! where its flattened copy is, with the same shading; memory stays flat in the number of
//! instances.

use crate::common;

use common::located::check_located;
use mcrt::glam::{DVec3, Mat4, Quat, Vec2, Vec3};
use mcrt_render::description::{Checked, ShapeDesc, ShapeGroupDesc, ShapeKind};
use mcrt_render::geometry::{AccelKind, Geometry, Ray};
use mcrt_render::loader::{load_scene, parse_scene, SceneError, SceneErrorKind};
use std::path::{Path, PathBuf};
use std::sync::Arc;

const FILE: &str = "tests/data/instancing-test.xml";

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join("data")
        .join(name)
}

/// Parses `body` inside a scene element whose start tag is on line 1.
fn err(body: &str) -> SceneError {
    let xml = format!("<scene version=\"3.0.0\">\n{body}\n</scene>");
    match parse_scene(&xml, Some(Path::new(FILE)), &[]) {
        Ok(d) => panic!("expected an error, got {d:?}"),
        Err(e) => e,
    }
}

const GROUP: &str = "<shape type=\"shapegroup\" id=\"g\"><shape type=\"sphere\"/></shape>";

#[test]
fn the_published_style_scene_shares_one_group_among_its_instances() {
    let d = load_scene(&data("published/instancing/instancing.xml"), &[]).expect("loads");
    // Six rectangles (walls and light) and four instances; the group is not a shape.
    assert_eq!(d.shapes.len(), 10);
    let groups = d.shape_groups();
    assert_eq!(groups.len(), 1);
    assert_eq!(groups[0].id.as_deref(), Some("thing"));
    assert_eq!(groups[0].shapes.len(), 4);
    let instances: Vec<&ShapeDesc> = d
        .shapes
        .iter()
        .filter(|s| matches!(s.kind, ShapeKind::Instance(_)))
        .map(|s| &**s)
        .collect();
    assert_eq!(instances.len(), 4);
    for s in &instances {
        let ShapeKind::Instance(g) = &s.kind else {
            unreachable!()
        };
        assert!(Arc::ptr_eq(g, groups[0]), "one group, shared");
    }
    // The first instance comes before the group's declaration; its to_world is its own.
    assert_eq!(instances[0].id.as_deref(), Some("left"));
    let p = instances[0].to_world.transform_point3(Vec3::ZERO);
    assert!((p - Vec3::new(-0.42, -0.72, 0.15)).length() < 1e-6, "{p}");
    // Hits number the group's shapes after the scene's own.
    assert_eq!(d.all_shapes().len(), 14);
    // The group's to_world (translate x = 7) is ignored: everything is inside the box.
    let geo = Geometry::new(&d.shapes, None, AccelKind::Bvh).expect("builds");
    let b = geo.bounds();
    assert!(b.min.cmpge(Vec3::splat(-1.01)).all() && b.max.cmple(Vec3::splat(1.01)).all());
    assert_eq!(geo.instance_count(), 4);
    assert_eq!(geo.shape_count(), 14);
}

#[test]
fn a_group_may_follow_its_instance_and_hold_references_to_shapes() {
    let xml = "<scene version=\"3.0.0\">\
        <shape type=\"instance\"><ref id=\"g\"/></shape>\
        <shape type=\"sphere\" id=\"s\"><float name=\"radius\" value=\"0.5\"/></shape>\
        <shape type=\"shapegroup\" id=\"g\"><ref id=\"s\"/><shape type=\"cube\"/></shape>\
        <shape type=\"shapegroup\" id=\"unused\"><shape type=\"disk\"/></shape>\
        </scene>";
    let d = parse_scene(xml, None, &[]).expect("loads");
    // The instance and the sphere; the referenced sphere is also in the group (as in
    // Mitsuba 3), and the unused group is dropped.
    assert_eq!(d.shapes.len(), 2);
    let groups = d.shape_groups();
    assert_eq!(groups.len(), 1);
    assert_eq!(groups[0].shapes.len(), 2);
    assert!(matches!(
        groups[0].shapes[0].kind,
        ShapeKind::Sphere { radius, .. } if radius == 0.5
    ));
}

#[test]
fn an_instance_needs_exactly_one_known_group() {
    let e = err("<shape type=\"instance\">\n<ref id=\"nope\"/>\n</shape>");
    assert!(
        matches!(e.kind, SceneErrorKind::UndefinedReference(_)),
        "{e}"
    );
    check_located(
        &e,
        FILE,
        3,
        "<ref id=\"nope\">",
        "no object has id \"nope\"",
    );

    let e = err("\n<shape type=\"instance\"/>");
    assert!(matches!(e.kind, SceneErrorKind::MissingAttribute(_)), "{e}");
    check_located(&e, FILE, 3, "<shape type=\"instance\">", "shapegroup");

    let e =
        err("<bsdf type=\"diffuse\" id=\"b\"/>\n<shape type=\"instance\"><ref id=\"b\"/></shape>");
    assert!(
        matches!(e.kind, SceneErrorKind::UndefinedReference(_)),
        "{e}"
    );
    check_located(
        &e,
        FILE,
        3,
        "<ref id=\"b\">",
        "not a <shape type=\"shapegroup\">",
    );

    let e = err(&format!(
        "{GROUP}\n<shape type=\"instance\"><ref id=\"g\"/>\n<ref id=\"g\"/></shape>"
    ));
    assert!(matches!(e.kind, SceneErrorKind::Misplaced(_)), "{e}");
    check_located(&e, FILE, 4, "<ref id=\"g\">", "a second shapegroup");

    let e = err(&format!(
        "{GROUP}\n<shape type=\"instance\"><ref id=\"g\"/>\n<bsdf type=\"diffuse\"/></shape>"
    ));
    assert!(matches!(e.kind, SceneErrorKind::Misplaced(_)), "{e}");
    check_located(&e, FILE, 4, "<bsdf type=\"diffuse\">", "inside an instance");

    let e = err(&format!(
        "{GROUP}\n<shape type=\"instance\"><ref id=\"g\"/>\n\
         <boolean name=\"flip_normals\" value=\"true\"/></shape>"
    ));
    assert!(
        matches!(e.kind, SceneErrorKind::UnknownParameter { .. }),
        "{e}"
    );
    check_located(&e, FILE, 4, "flip_normals", "unknown parameter");

    let e = err("<shape type=\"instance\">\n<shape type=\"shapegroup\"><shape type=\"cube\"/></shape></shape>");
    assert!(matches!(e.kind, SceneErrorKind::Misplaced(_)), "{e}");
    check_located(
        &e,
        FILE,
        3,
        "<shape type=\"shapegroup\">",
        "declare it directly inside <scene>",
    );
}

#[test]
fn groups_refuse_emitters_nesting_and_other_objects() {
    let e = err(
        "<shape type=\"shapegroup\" id=\"g\">\n<shape type=\"sphere\">\n\
         <emitter type=\"area\"/></shape></shape>",
    );
    assert!(matches!(e.kind, SceneErrorKind::Unsupported(_)), "{e}");
    check_located(
        &e,
        FILE,
        4,
        "<emitter type=\"area\">",
        "instancing of emitters",
    );

    let e = err(&format!(
        "{GROUP}\n<shape type=\"shapegroup\" id=\"h\">\n<shape type=\"instance\"><ref id=\"g\"/></shape></shape>"
    ));
    assert!(matches!(e.kind, SceneErrorKind::Unsupported(_)), "{e}");
    check_located(
        &e,
        FILE,
        4,
        "<shape type=\"instance\">",
        "nested instancing",
    );

    let e =
        err("<shape type=\"shapegroup\" id=\"g\">\n<shape type=\"shapegroup\" id=\"h\"/></shape>");
    assert!(matches!(e.kind, SceneErrorKind::Unsupported(_)), "{e}");
    check_located(
        &e,
        FILE,
        3,
        "<shape type=\"shapegroup\" id=\"h\">",
        "nested groups",
    );

    let e = err("<shape type=\"shapegroup\" id=\"g\">\n<bsdf type=\"diffuse\"/></shape>");
    assert!(matches!(e.kind, SceneErrorKind::Misplaced(_)), "{e}");
    check_located(&e, FILE, 3, "<bsdf type=\"diffuse\">", "holds shapes only");

    // An unused group is still read, so its errors surface.
    let e = err(
        "<shape type=\"shapegroup\" id=\"g\">\n<shape type=\"sphere\">\n\
                 <float name=\"radius\" value=\"-1\"/></shape></shape>",
    );
    assert!(matches!(e.kind, SceneErrorKind::InvalidValue(_)), "{e}");
    assert_eq!(e.line, Some(4), "{e}");

    let e = err("<shape type=\"shapegroup\" id=\"g\">\n<float name=\"x\" value=\"1\"/></shape>");
    assert!(
        matches!(e.kind, SceneErrorKind::UnknownParameter { .. }),
        "{e}"
    );
    check_located(&e, FILE, 3, "<float name=\"x\">", "unknown parameter");
}

// ---- Geometry ----------------------------------------------------------------------------

/// A smooth blob: a UV sphere of `n` × 2n quads with its radius modulated, and its normals.
fn blob(n: u32) -> ShapeKind {
    let (mut positions, mut normals, mut indices) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..=n {
        let th = std::f32::consts::PI * i as f32 / n as f32;
        for j in 0..=2 * n {
            let ph = std::f32::consts::PI * j as f32 / n as f32;
            let d = Vec3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos());
            let r = 1.0 + 0.2 * (3.0 * ph).sin() * th.sin();
            positions.push(d * r);
            normals.push(d);
        }
    }
    let w = 2 * n + 1;
    for i in 0..n {
        for j in 0..2 * n {
            let (a, b) = (i * w + j, (i + 1) * w + j);
            indices.push([a, b, b + 1]);
            indices.push([a, b + 1, a + 1]);
        }
    }
    ShapeKind::Mesh {
        positions,
        normals,
        indices,
    }
}

fn transforms() -> Vec<Mat4> {
    vec![
        Mat4::from_scale_rotation_translation(
            Vec3::new(0.7, 1.6, 0.4),
            Quat::from_euler(mcrt::glam::EulerRot::XYZ, 0.3, -0.8, 0.2),
            Vec3::new(-2.0, 0.5, 0.3),
        ),
        Mat4::from_scale_rotation_translation(
            Vec3::new(1.2, 0.5, 0.9),
            Quat::from_rotation_y(1.1),
            Vec3::new(2.0, -0.4, -0.6),
        ),
        // Mirrored.
        Mat4::from_scale_rotation_translation(
            Vec3::new(-0.8, 0.8, 1.3),
            Quat::from_rotation_z(0.5),
            Vec3::new(0.0, 2.2, 0.5),
        ),
    ]
}

fn group_shapes() -> Vec<ShapeDesc> {
    let mut mesh = ShapeDesc::new(blob(24));
    mesh.to_world = Mat4::from_translation(Vec3::new(0.1, 0.0, -0.2));
    let mut sphere = ShapeDesc::new(ShapeKind::Sphere {
        center: Vec3::new(0.0, 0.0, 1.6),
        radius: 0.4,
    });
    sphere.to_world = Mat4::from_rotation_x(0.4);
    vec![mesh, sphere]
}

fn instanced(group: &Arc<Checked<ShapeGroupDesc>>) -> Vec<ShapeDesc> {
    transforms()
        .into_iter()
        .map(|m| {
            let mut s = ShapeDesc::new(ShapeKind::Instance(Arc::clone(group)));
            s.to_world = m;
            s
        })
        .collect()
}

/// Rays from a sphere of radius 6 towards points near the origin (deterministic).
fn rays(n: u32) -> impl Iterator<Item = Ray> {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
    };
    (0..n).map(move |_| {
        let o = Vec3::new(next(), next(), next()).normalize_or(Vec3::Z) * 6.0;
        let target = Vec3::new(next() * 2.5, next() * 2.5, next() * 1.5);
        Ray {
            origin: o,
            dir: (target - o).normalize(),
        }
    })
}

/// The mesh instanced three times (one mirrored) is hit where its flattened copies are
/// (the mesh with `to_world` = instance ∘ shape): the same triangle and barycentrics, the
/// point and `t` to 10⁻⁴ and the texture coordinates. Normals are the group's carried by
/// `M⁻ᵀ` and renormalised, as in Mitsuba 3's `instance.cpp`: the geometric normal is the
/// flattened copy's times the sign of `det M` (a mirrored instance keeps the group's front
/// side, where the flattened copy's winding turns it), and the shading normal is the group's
/// interpolated normal carried by `M⁻ᵀ` (the flattened copy interpolates normals already
/// carried, which differs under non-uniform scale by up to about 10⁻² here). Away from triangle
/// edges, where the two searches may pick different neighbours.
#[test]
fn an_instanced_mesh_is_hit_where_its_flattened_copy_is() {
    let mesh = group_shapes().remove(0);
    let ShapeKind::Mesh {
        normals, indices, ..
    } = &mesh.kind
    else {
        unreachable!()
    };
    let group = Arc::new(
        Checked::new(ShapeGroupDesc {
            id: Some("g".into()),
            shapes: vec![mesh.clone()]
                .into_iter()
                .map(|x| Checked::new(x).unwrap())
                .collect(),
        })
        .unwrap(),
    );
    let inst = instanced(&group);
    let flat: Vec<ShapeDesc> = inst
        .iter()
        .map(|i| {
            let mut s = mesh.clone();
            s.to_world = i.to_world * mesh.to_world;
            s
        })
        .collect();
    for accel in [
        AccelKind::Bvh,
        AccelKind::Bvh8,
        AccelKind::Grid,
        AccelKind::KdTree,
    ] {
        let gi = Geometry::new(&inst, None, accel).expect("instanced");
        let gf = Geometry::new(&flat, None, accel).expect("flattened");
        assert_eq!(gi.primitive_count() * 3, gf.primitive_count());
        let (mut compared, mut hits) = (0, 0);
        for ray in rays(20_000) {
            let (a, b) = (
                gi.intersect(&ray, f32::INFINITY),
                gf.intersect(&ray, f32::INFINITY),
            );
            assert_eq!(
                gi.occluded(&ray, f32::INFINITY),
                gf.occluded(&ray, f32::INFINITY),
                "{ray:?}"
            );
            let (a, b) = match (a, b) {
                (None, None) => continue,
                (Some(a), Some(b)) => (a, b),
                (a, b) => {
                    // Grazing an outline: allowed only at a triangle's edge.
                    let h = a.or(b).unwrap();
                    let w = (1.0 - h.uv.x - h.uv.y).min(h.uv.x).min(h.uv.y);
                    assert!(w < 1e-3, "{accel:?}: {a:?} vs {b:?} for {ray:?}");
                    continue;
                }
            };
            hits += 1;
            let edge = |uv: Vec2| (1.0 - uv.x - uv.y).min(uv.x).min(uv.y) < 1e-3;
            if edge(a.uv) || edge(b.uv) || a.prim != b.prim {
                continue;
            }
            // Group shape 0 comes after the three instances; flattened copy k is shape k.
            assert_eq!(a.shape, 3);
            assert!(a.t.is_finite() && a.p.is_finite());
            assert!((a.t - b.t).abs() <= 1e-4 * b.t, "{a:?} {b:?}");
            assert!(
                a.p.distance(b.p) <= 1e-4 * (1.0 + b.p.length()),
                "{a:?} {b:?}"
            );
            assert!((a.uv - b.uv).abs().max_element() < 1e-3, "{a:?} {b:?}");
            let m = inst[b.shape as usize].to_world;
            let det = m.determinant().signum();
            assert!((a.ng - det * b.ng).length() < 1e-4, "{a:?} {b:?}");
            let [n0, n1, n2] = indices[a.prim as usize].map(|v| normals[v as usize]);
            let local = (n0 * (1.0 - a.uv.x - a.uv.y) + n1 * a.uv.x + n2 * a.uv.y).normalize();
            let want = m.inverse().transpose().transform_vector3(local).normalize();
            assert!((a.frame.n - want).length() < 1e-4, "{a:?}: {want}");
            assert!((a.frame.n - b.frame.n).length() < 0.05, "{a:?} {b:?}");
            assert_eq!(gi.tex_coords(&a), a.uv);
            compared += 1;
        }
        assert!(
            hits > 2000 && compared > hits * 9 / 10,
            "{accel:?}: {compared} of {hits}"
        );
    }
}

/// A sphere in a group under a non-uniform instance scale is an ellipsoid: hits and normals
/// (`M⁻ᵀ` of the sphere's) agree with the ellipsoid solved in closed form.
#[test]
fn an_instanced_sphere_is_an_ellipsoid_with_inverse_transpose_normals() {
    let sphere = group_shapes().remove(1);
    let group = Arc::new(
        Checked::new(ShapeGroupDesc {
            id: None,
            shapes: vec![sphere.clone()]
                .into_iter()
                .map(|x| Checked::new(x).unwrap())
                .collect(),
        })
        .unwrap(),
    );
    let inst = instanced(&group);
    let geo = Geometry::new(&inst, None, AccelKind::Bvh).expect("builds");
    let mut hits = 0;
    for ray in rays(5000) {
        // The nearest root over the instances, in each one's unit-sphere space.
        // In f64.
        let mut best: Option<(f32, Vec3)> = None;
        for i in &inst {
            let m = (i.to_world * sphere.to_world).as_dmat4();
            let inv = m.inverse();
            let o = inv.transform_point3(ray.origin.as_dvec3()) - DVec3::new(0.0, 0.0, 1.6);
            let d = inv.transform_vector3(ray.dir.as_dvec3());
            let (a, b, c) = (d.dot(d), 2.0 * o.dot(d), o.dot(o) - 0.16);
            let disc = b * b - 4.0 * a * c;
            if disc < 0.0 {
                continue;
            }
            let t = (-b - disc.sqrt()) / (2.0 * a);
            if t > 0.0 && best.is_none_or(|(bt, _)| t < f64::from(bt)) {
                let n_obj = o + t * d;
                let n = inv.transpose().transform_vector3(n_obj).normalize();
                best = Some((t as f32, n.as_vec3()));
            }
        }
        let got = geo.intersect(&ray, f32::INFINITY);
        match (got, best) {
            // Near the outline, f32 rounding of `t` moves the normal much.
            (Some(h), Some((_, n))) if h.ng.dot(ray.dir).abs() < 0.1 => {
                assert!((h.ng - n).length() < 0.05, "{h:?} vs {n}");
            }
            (Some(h), Some((t, n))) => {
                assert!(
                    h.t.is_finite() && (h.t - t).abs() < 1e-3 * t,
                    "{h:?} vs {t}"
                );
                assert!((h.ng - n).length() < 1e-3, "{h:?} vs {n}");
                assert!((h.p - ray.at(t)).length() < 1e-3, "{h:?}");
                hits += 1;
            }
            (None, None) => {}
            // A graze.
            (h, b) => assert!(
                h.is_some_and(|h| h.ng.dot(ray.dir).abs() < 0.02)
                    || b.is_some_and(|(_, n)| n.dot(ray.dir).abs() < 0.02),
                "{h:?} vs {b:?}"
            ),
        }
    }
    assert!(hits > 100, "{hits}");
}

/// A group holds its primitives once: 10² and 10⁴ instances of a mesh of 2·48² triangles
/// store the same primitives, and the structure grows by a few hundred bytes per instance.
#[test]
fn memory_stays_flat_in_the_number_of_instances() {
    let group = Arc::new(
        Checked::new(ShapeGroupDesc {
            id: None,
            shapes: vec![ShapeDesc::new(blob(48))]
                .into_iter()
                .map(|x| Checked::new(x).unwrap())
                .collect(),
        })
        .unwrap(),
    );
    let build = |n: u32| {
        let side = (n as f32).sqrt().ceil() as u32;
        let shapes: Vec<ShapeDesc> = (0..n)
            .map(|k| {
                let mut s = ShapeDesc::new(ShapeKind::Instance(Arc::clone(&group)));
                s.to_world = Mat4::from_translation(Vec3::new(
                    3.0 * (k % side) as f32,
                    3.0 * (k / side) as f32,
                    0.0,
                )) * Mat4::from_scale(Vec3::new(1.0, 0.5 + (k % 7) as f32 * 0.1, 1.0));
                s
            })
            .collect();
        Geometry::new(&shapes, None, AccelKind::Bvh).expect("builds")
    };
    let (small, large) = (build(100), build(10_000));
    assert_eq!(small.primitive_count(), 2 * 48 * 96);
    assert_eq!(large.primitive_count(), small.primitive_count());
    assert_eq!(large.primitive_heap_bytes(), small.primitive_heap_bytes());
    assert_eq!(large.instance_count(), 10_000);
    let per_instance = (large.accel_heap_bytes() - small.accel_heap_bytes()) as f64 / 9_900.0;
    assert!(
        per_instance.is_finite() && per_instance < 400.0,
        "{per_instance} bytes"
    );
    // And rays still find the far instances.
    let ray = Ray {
        origin: Vec3::new(3.0 * 99.0, 3.0 * 99.0, 10.0),
        dir: -Vec3::Z,
    };
    let h = large
        .intersect(&ray, f32::INFINITY)
        .expect("hits the last row");
    assert!((h.t - 9.0).abs() < 0.3, "{h:?}");
}

/// What a shape group cannot hold, refused by its checked constructor (a description built
/// in code meets the loader's rules): an instance (nested instancing) or an emitter.
#[test]
fn nested_instancing_and_emitters_in_groups_cannot_be_made() {
    let inner = Arc::new(
        Checked::new(ShapeGroupDesc {
            id: None,
            shapes: vec![Checked::new(ShapeDesc::new(ShapeKind::Cube)).unwrap()],
        })
        .unwrap(),
    );
    let nested = Checked::new(ShapeDesc::new(ShapeKind::Instance(inner))).unwrap();
    let outer = Checked::new(ShapeGroupDesc {
        id: None,
        shapes: vec![nested],
    });
    let e = outer.unwrap_err();
    assert!(
        e.param == "type" && e.message.contains("nested instancing"),
        "{e}"
    );

    let mut lit = ShapeDesc::new(ShapeKind::Cube);
    lit.emitter = Some(mcrt_render::description::AreaEmitterDesc {
        radiance: mcrt_render::description::Colour::WHITE,
    });
    let group = Checked::new(ShapeGroupDesc {
        id: Some("g".into()),
        shapes: vec![Checked::new(lit).unwrap()],
    });
    let e = group.unwrap_err();
    assert!(e.param == "emitter" && e.message.contains("emit"), "{e}");
}
