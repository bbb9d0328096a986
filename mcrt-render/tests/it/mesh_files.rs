//! The mesh-file shapes (`ply`, `serialized`, `obj` texture coordinates) and their
//! hostile inputs: every damaged file is an error naming the file and the place, never a
//! panic or an allocation beyond what the file holds. The files in `tests/data/meshes/`
//! were written by `scripts/make_mesh_data.py`, which checks that Mitsuba 3 reads each to
//! the same geometry (vertex and triangle counts below are Mitsuba's).

use mcrt::glam::{Vec2, Vec3};
use mcrt_render::description::{ShapeDesc, ShapeKind};
use mcrt_render::geometry::{AccelKind, Geometry, Ray};
use mcrt_render::mesh_file::ply::{parse_ply, read_ply};
use mcrt_render::mesh_file::serialized::{parse_serialized, read_serialized, write_serialized};
use mcrt_render::mesh_file::TriangleMesh;
use rand::{Rng, SeedableRng};
use std::path::{Path, PathBuf};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/meshes")
        .join(name)
}

/// A PLY file of `m` (float positions, normals if any, uchar/int face lists) in `format`.
fn ply_bytes(m: &TriangleMesh, faces: &[Vec<u32>], format: &str) -> Vec<u8> {
    let normals = !m.normals.is_empty();
    let mut head = format!(
        "ply\nformat {format} 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
         property float z\n",
        m.positions.len()
    );
    if normals {
        head += "property float nx\nproperty float ny\nproperty float nz\n";
    }
    head += &format!(
        "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        faces.len()
    );
    let mut out = head.into_bytes();
    let rows: Vec<Vec<f32>> = (0..m.positions.len())
        .map(|i| {
            let mut r = m.positions[i].to_array().to_vec();
            if normals {
                r.extend(m.normals[i].to_array());
            }
            r
        })
        .collect();
    let be = format == "binary_big_endian";
    for r in &rows {
        if format == "ascii" {
            let line: Vec<String> = r.iter().map(|x| format!("{x:?}")).collect();
            out.extend(format!("{}\n", line.join(" ")).bytes());
        } else {
            for x in r {
                out.extend(if be { x.to_be_bytes() } else { x.to_le_bytes() });
            }
        }
    }
    for f in faces {
        if format == "ascii" {
            let line: Vec<String> = f.iter().map(u32::to_string).collect();
            out.extend(format!("{} {}\n", f.len(), line.join(" ")).bytes());
        } else {
            out.push(f.len() as u8);
            for &i in f {
                out.extend(if be { i.to_be_bytes() } else { i.to_le_bytes() });
            }
        }
    }
    out
}

#[test]
fn ply_encodings_read_alike_and_as_mitsuba_does() {
    let sphere = read_ply(&data("icosphere.ply")).expect("icosphere reads");
    assert_eq!((sphere.positions.len(), sphere.indices.len()), (162, 320));
    assert!(sphere.uvs.is_empty());
    for (p, n) in sphere.positions.iter().zip(&sphere.normals) {
        let (lp, ln) = (p.length(), n.length());
        assert!(lp.is_finite() && (lp - 1.0).abs() < 1e-5 && (ln - 1.0).abs() < 1e-5);
    }
    let faces: Vec<Vec<u32>> = sphere.indices.iter().map(|t| t.to_vec()).collect();
    for format in ["ascii", "binary_big_endian", "binary_little_endian"] {
        let m = parse_ply(&ply_bytes(&sphere, &faces, format), None).expect(format);
        assert_eq!(m, sphere, "{format}");
    }
    let be = read_ply(&data("tetra-be.ply")).unwrap();
    let ascii = read_ply(&data("tetra-ascii.ply")).unwrap();
    assert_eq!(be.positions, ascii.positions);
    assert_eq!(be.indices, ascii.indices);
    // The ASCII tetrahedron's texture coordinates are its vertices' x and y.
    let xy: Vec<Vec2> = ascii.positions.iter().map(|p| p.truncate()).collect();
    assert_eq!(ascii.uvs, xy);
}

#[test]
fn ply_polygons_are_fans() {
    let m = TriangleMesh {
        positions: (0..6)
            .map(|i| Vec3::new(i as f32, (i * i) as f32, 0.0))
            .collect(),
        ..TriangleMesh::default()
    };
    let faces = vec![vec![0, 1, 2, 3], vec![1, 2, 3, 4, 5], vec![5, 4, 3]];
    for format in ["ascii", "binary_little_endian"] {
        let got = parse_ply(&ply_bytes(&m, &faces, format), None).unwrap();
        assert_eq!(
            got.indices,
            vec![
                [0, 1, 2],
                [0, 2, 3],
                [1, 2, 3],
                [1, 3, 4],
                [1, 4, 5],
                [5, 4, 3]
            ]
        );
    }
}

#[test]
fn damaged_ply_files_are_located_errors() {
    let sphere = read_ply(&data("icosphere.ply")).unwrap();
    let faces: Vec<Vec<u32>> = sphere.indices.iter().map(|t| t.to_vec()).collect();
    let bin = ply_bytes(&sphere, &faces, "binary_little_endian");
    let name = Path::new("damaged.ply");
    // Every cut is an error naming the file (the whole file reads).
    for n in (0..bin.len()).step_by(7) {
        let e = parse_ply(&bin[..n], Some(name)).unwrap_err();
        assert!(e.to_string().starts_with("damaged.ply"), "{e}");
    }
    // Changed bytes never panic; a mesh that still reads is a valid mesh.
    let mut rng = rand_pcg::Pcg64::seed_from_u64(16);
    for _ in 0..2000 {
        let mut b = bin.clone();
        for _ in 0..rng.random_range(1..4) {
            let k = rng.random_range(0..b.len());
            b[k] = rng.random();
        }
        if let Ok(m) = parse_ply(&b, Some(name)) {
            assert!(m.check().is_ok());
        }
    }
    // Wrong counts, indices and layouts.
    let text = |head: &str, body: &str| format!("ply\nformat ascii 1.0\n{head}end_header\n{body}");
    let xyz = "property float x\nproperty float y\nproperty float z\n";
    let list = "element face 1\nproperty list uchar int vertex_indices\n";
    for (head, body, words) in [
        (
            format!("element vertex 4\n{xyz}{list}"),
            "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
            "line 14, in element \"face\"",
        ),
        (
            format!("element vertex 3\n{xyz}{list}"),
            "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
            "vertex 3 of 3",
        ),
        (
            format!("element vertex 3\n{xyz}{list}"),
            "0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
            "3 corners",
        ),
        (
            format!("element vertex 3\nproperty float x\nproperty float y\n{list}"),
            "",
            "\"z\"",
        ),
        (
            format!("element vertex 3\n{xyz}property float nx\n{list}"),
            "",
            "nx, ny and nz",
        ),
        (
            format!(
                "element vertex 3\n{xyz}element face 1\nproperty list uchar float vertex_indices\n"
            ),
            "",
            "list of integers",
        ),
        (
            format!("element vertex 3\n{xyz}element face 1\nproperty int material\n"),
            "",
            "vertex_indices",
        ),
        (
            format!("element vertex 99999999999\n{xyz}"),
            "",
            "more than the file's",
        ),
        ("element vertex 3\nproperty floot x\n".into(), "", "header"),
    ] {
        let e = parse_ply(text(&head, body).as_bytes(), Some(name)).unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.starts_with("damaged.ply") && msg.contains(words),
            "{words}: {msg}"
        );
    }
}

#[test]
fn serialized_meshes_and_their_dictionary() {
    let torus = read_serialized(&data("shapes.serialized"), 1).expect("mesh 1 reads");
    assert_eq!(torus.name, "torus");
    assert_eq!(
        (torus.mesh.positions.len(), torus.mesh.indices.len()),
        (288, 576)
    );
    assert!(torus.mesh.normals.is_empty() && !torus.face_normals);
    let card = read_serialized(&data("shapes.serialized"), 0).expect("mesh 0 reads");
    assert_eq!((card.name.as_str(), card.mesh.indices.len()), ("card", 2));
    let e = read_serialized(&data("shapes.serialized"), 2).unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.contains("shapes.serialized, in mesh 2") && msg.contains("holds 2"),
        "{msg}"
    );
    // Rewritten by our writer, the file reads back the same.
    let again = write_serialized(&[("card", &card.mesh), ("torus", &torus.mesh)]);
    assert_eq!(parse_serialized(&again, 1, None).unwrap(), torus);
}

#[test]
fn damaged_serialized_files_are_located_errors() {
    let bytes = std::fs::read(data("shapes.serialized")).unwrap();
    let name = Path::new("damaged.serialized");
    // Mesh 1 starts where the dictionary says; mesh 0 reads from any cut past that, and
    // nothing else reads from a cut file.
    let second = u64::from_le_bytes(bytes[bytes.len() - 12..bytes.len() - 4].try_into().unwrap());
    for n in 0..bytes.len() {
        for index in [0, 1] {
            let read = parse_serialized(&bytes[..n], index, Some(name)).is_ok();
            assert_eq!(
                read,
                index == 0 && n as u64 >= second,
                "cut {n}, mesh {index}"
            );
        }
    }
    let mut rng = rand_pcg::Pcg64::seed_from_u64(4);
    for _ in 0..3000 {
        let mut b = bytes.clone();
        let k = rng.random_range(0..b.len());
        b[k] = rng.random();
        for index in [0, 1] {
            if let Err(e) = parse_serialized(&b, index, Some(name)) {
                assert!(e.to_string().starts_with("damaged.serialized"), "{e}");
            }
        }
    }
    // A stream that claims 2^31 vertices in a few bytes is refused before reading on.
    let mut body = 0x1000u32.to_le_bytes().to_vec();
    body.push(0);
    body.extend((1u64 << 31).to_le_bytes());
    body.extend(1u64.to_le_bytes());
    let mut enc = flate2_like_zlib(&body);
    let mut file = vec![0x1c, 0x04, 4, 0];
    file.append(&mut enc);
    let e = parse_serialized(&file, 0, Some(name)).unwrap_err();
    assert!(e.to_string().contains("compressed bytes can hold"), "{e}");
}

/// A zlib stream of `raw`, stored uncompressed (RFC 1950/1951), so this test needs no
/// compressor of its own.
fn flate2_like_zlib(raw: &[u8]) -> Vec<u8> {
    let mut out = vec![0x78, 0x01];
    out.push(1); // final block, stored
    let n = raw.len() as u16;
    out.extend(n.to_le_bytes());
    out.extend((!n).to_le_bytes());
    out.extend(raw);
    let (mut a, mut b) = (1u32, 0u32);
    for &x in raw {
        a = (a + u32::from(x)) % 65521;
        b = (b + a) % 65521;
    }
    out.extend(((b << 16) | a).to_be_bytes());
    out
}

#[test]
fn texture_coordinates_interpolate_at_hits() {
    // The ASCII tetrahedron's (u, v) is its vertices' (x, y); the face z = 0 is hit
    // from below.
    let shape = ShapeDesc::new(ShapeKind::Ply {
        filename: data("tetra-ascii.ply"),
        face_normals: false,
    });
    let geo = Geometry::new(&[shape], None, AccelKind::Bvh).unwrap();
    let ray = Ray {
        origin: Vec3::new(0.2, 0.3, -1.0),
        dir: Vec3::Z,
    };
    let hit = geo
        .intersect(&ray, f32::INFINITY)
        .expect("hits the tetrahedron");
    let uv = geo.tex_coords(&hit);
    assert!(
        uv.is_finite() && (uv - Vec2::new(0.2, 0.3)).abs().max_element() < 1e-5,
        "{uv}"
    );
    // OBJ texture coordinates are flipped (v → 1 − v) unless flip_tex_coords is false.
    let dir = std::env::temp_dir().join(format!("mcrt-uv-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let obj = dir.join("t.obj");
    std::fs::write(
        &obj,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n",
    )
    .unwrap();
    for (flip, want) in [(true, Vec2::new(0.2, 0.7)), (false, Vec2::new(0.2, 0.3))] {
        let shape = ShapeDesc::new(ShapeKind::Obj {
            filename: obj.clone(),
            face_normals: false,
            flip_tex_coords: flip,
        });
        let geo = Geometry::new(&[shape], None, AccelKind::Bvh).unwrap();
        let ray = Ray {
            origin: Vec3::new(0.2, 0.3, 1.0),
            dir: -Vec3::Z,
        };
        let uv = geo.tex_coords(&geo.intersect(&ray, f32::INFINITY).unwrap());
        assert!(
            uv.is_finite() && (uv - want).abs().max_element() < 1e-5,
            "{flip}: {uv}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_damaged_mesh_file_fails_the_render_naming_the_file() {
    let dir = std::env::temp_dir().join(format!("mcrt-badmesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("bad.ply"),
        "ply\nformat ascii 1.0\nelement vertex 1\nend_header\n",
    )
    .unwrap();
    std::fs::write(dir.join("bad.serialized"), [0x1c, 0x04, 4, 0, 1, 2, 3]).unwrap();
    for (ty, file) in [("ply", "bad.ply"), ("serialized", "bad.serialized")] {
        let xml = format!(
            "<scene version=\"3.0.0\"><shape type=\"{ty}\">\
             <string name=\"filename\" value=\"{}\"/></shape></scene>",
            dir.join(file).display()
        );
        let desc = mcrt_render::loader::parse_scene(&xml, None, &[]).unwrap();
        let opts = mcrt_render::render::RenderOptions::default();
        let e = mcrt_render::render::Renderer::new(&desc, &opts)
            .err()
            .expect("the render fails");
        assert!(e.to_string().contains(file), "{e}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A scene given by a path relative to the working directory finds its mesh files once: the
/// loader resolves them against the scene's folder and the renderer does not join it again.
#[test]
fn a_scene_by_relative_path_finds_its_meshes() {
    use mcrt_render::loader::load_scene;
    use mcrt_render::render::{RenderOptions, Renderer};
    // `cargo test` runs in the package root, where tests/data lies.
    let desc = load_scene(Path::new("tests/data/meshes.xml"), &[]).expect("loads");
    let r = Renderer::new(&desc, &RenderOptions::default());
    assert!(r.is_ok(), "{:?}", r.err().map(|e| e.to_string()));
}
