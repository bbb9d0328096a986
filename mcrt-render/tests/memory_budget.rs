//! The hostile inputs of issue 26 that asked for more memory than the machine had, each
//! refused by the memory budget (`--max-memory`) with a located error. The large files are
//! made at test time (sparse files through `File::set_len`, headers that claim more than
//! they hold), and the budgets are small, so every case takes milliseconds.

use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("mcrt-memory-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("scratch folder");
    d
}

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// Runs a program; returns (exit code, stderr).
fn run(exe: &str, args: &[&str]) -> (Option<i32>, String) {
    let out = Command::new(exe).args(args).output().expect("run");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn render(args: &[&str]) -> (Option<i32>, String) {
    run(env!("CARGO_BIN_EXE_render"), args)
}

/// A scene of one mesh shape of `kind` reading `file`, at 16 × 16 pixels.
fn mesh_scene(dir: &Path, kind: &str, file: &str) -> PathBuf {
    let xml = format!(
        r#"<scene version="3.0.0">
  <integrator type="path"/>
  <sensor type="perspective"><float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0,0,4" target="0,0,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film>
  </sensor>
  <shape type="{kind}"><string name="filename" value="{file}"/></shape>
  <emitter type="constant"/>
</scene>"#
    );
    let p = dir.join(format!("{kind}.xml"));
    std::fs::write(&p, xml).expect("scene");
    p
}

fn assert_refused(code: Option<i32>, err: &str, located: &str, needs: &str) {
    assert_eq!(code, Some(1), "{err}");
    assert!(err.contains(located), "not located at {located:?}: {err}");
    assert!(err.contains(needs), "no {needs:?}: {err}");
    assert!(
        err.contains("--max-memory"),
        "does not say how to raise it: {err}"
    );
}

#[test]
fn sparse_obj_stops_at_the_first_overlong_line() {
    let d = scratch("obj");
    let mut f = File::create(d.join("sparse.obj")).unwrap();
    f.write_all(b"v 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
    f.set_len(1 << 30).unwrap(); // 1 GiB of holes, never read in full
    let scene = mesh_scene(&d, "obj", "sparse.obj");
    let (code, err) = render(&[scene.to_str().unwrap(), "--max-memory", "1M"]);
    assert_refused(
        code,
        &err,
        "sparse.obj, line 4",
        "the line is longer than 4.00 KiB",
    );
}

#[test]
fn obj_mesh_growing_past_the_budget_is_refused_at_its_line() {
    let d = scratch("objbig");
    let mut text = String::new();
    for i in 0..100_000 {
        text.push_str(&format!("v {i} 0 0\n"));
    }
    std::fs::write(d.join("big.obj"), text).unwrap();
    let scene = mesh_scene(&d, "obj", "big.obj");
    let (code, err) = render(&[scene.to_str().unwrap(), "--max-memory", "1M"]);
    assert_refused(
        code,
        &err,
        "big.obj, line ",
        "the mesh read so far would need",
    );
    // With room, the same file reads to its real complaint.
    let (code, err) = render(&[scene.to_str().unwrap(), "--max-memory", "64M"]);
    assert_eq!(code, Some(1));
    assert!(err.contains("the file has no faces"), "{err}");
}

#[test]
fn ply_header_claiming_more_than_the_budget_is_refused_unread() {
    let d = scratch("ply");
    let mut f = File::create(d.join("sparse.ply")).unwrap();
    f.write_all(
        b"ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\n\
          property float y\nproperty float z\nelement face 0\n\
          property list uchar int vertex_indices\nend_header\n",
    )
    .unwrap();
    // Sparse: as long as the header's count needs (12 GB), no disk used.
    if f.set_len(12_000_000_200).is_err() {
        f.set_len(64 << 20).unwrap();
    }
    let scene = mesh_scene(&d, "ply", "sparse.ply");
    let (code, err) = render(&[scene.to_str().unwrap(), "--max-memory", "1M"]);
    assert_refused(
        code,
        &err,
        "sparse.ply, line 3, in element \"vertex\"",
        "would need",
    );
}

#[test]
fn mlt_depth_from_the_command_line_is_refused() {
    let scene = data("cornell-box.xml");
    let (code, err) = render(&[
        scene.to_str().unwrap(),
        "--integrator",
        "mlt",
        "-D",
        "max_depth=1000000000",
        "-D",
        "res=16",
        "--spp",
        "1",
    ]);
    assert_eq!(code, Some(1), "{err}");
    assert!(
        err.contains("max_depth 1000000000") && err.contains("[1, 64]"),
        "{err}"
    );
}

#[test]
fn mlt_state_and_film_are_checked_against_the_budget() {
    let scene = data("cornell-box.xml");
    let s = scene.to_str().unwrap();
    let (code, err) = render(&[
        s,
        "--integrator",
        "mlt",
        "-D",
        "res=64",
        "--max-memory",
        "1M",
    ]);
    assert_refused(
        code,
        &err,
        "Metropolis light transport at 64 × 64 pixels",
        "would need",
    );
    let (code, err) = render(&[s, "-D", "res=256", "--max-memory", "1M"]);
    assert_refused(code, &err, "the film of 256 × 256 pixels", "would need");
    let (code, err) = render(&[s, "--max-memory", "lots"]);
    assert_eq!(code, Some(2), "{err}");
}

/// Replaces the display window of the EXR file at `p` by (0, 0)–(`max`, `max`).
fn patch_display_window(p: &Path, max: i32) {
    let mut bytes = std::fs::read(p).unwrap();
    let key = b"displayWindow\0box2i\0";
    let at = bytes
        .windows(key.len())
        .position(|w| w == key)
        .expect("a displayWindow attribute")
        + key.len()
        + 4; // the attribute's size
    bytes[at + 8..at + 12].copy_from_slice(&max.to_le_bytes());
    bytes[at + 12..at + 16].copy_from_slice(&max.to_le_bytes());
    std::fs::write(p, bytes).unwrap();
}

#[test]
fn merge_refuses_a_huge_display_window_before_allocating() {
    let d = scratch("merge");
    let part = d.join("part.exr");
    let (code, err) = render(&[
        data("cornell-box.xml").to_str().unwrap(),
        "-D",
        "res=16",
        "--spp",
        "2",
        "--samples",
        "0..2",
        "-o",
        part.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(0), "{err}");
    patch_display_window(&part, 99_999);
    let out = d.join("merged.exr");
    let merge = env!("CARGO_BIN_EXE_merge");
    let (code, err) = run(merge, &[out.to_str().unwrap(), part.to_str().unwrap()]);
    assert_refused(
        code,
        &err,
        "part.exr: merging an image of 100000 × 100000 pixels",
        "would need",
    );
    let (code, err) = run(merge, &["--max-memory", "x", out.to_str().unwrap()]);
    assert_eq!(code, Some(2), "{err}");
}

/// The CRC-32 of PNG chunks.
fn crc32(bytes: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in bytes {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 != 0 {
                0xedb8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
    }
    !c
}

/// Writes a `size × size` 8-bit RGB PNG of one colour; with `header_only`, just its
/// signature, its header and the start of its data (a 60-byte file that claims the whole
/// image).
fn png(path: &Path, size: u32, header_only: bool) {
    if header_only {
        let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
        for (kind, data) in [
            (
                &b"IHDR"[..],
                [
                    &size.to_be_bytes()[..],
                    &size.to_be_bytes(),
                    &[8, 2, 0, 0, 0],
                ]
                .concat(),
            ),
            (b"IDAT", vec![0x78, 0x9c, 0, 0, 0, 0]),
        ] {
            out.extend((data.len() as u32).to_be_bytes());
            let body = [kind, &data].concat();
            out.extend(&body);
            out.extend(crc32(&body).to_be_bytes());
        }
        std::fs::write(path, out).unwrap();
        return;
    }
    let mut enc = png::Encoder::new(File::create(path).unwrap(), size, size);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut w = enc.write_header().unwrap();
    w.write_image_data(&vec![100u8; (size * size * 3) as usize])
        .unwrap();
}

/// A scene of `n` rectangles, each with a bitmap texture `t{i}.png`.
fn texture_scene(dir: &Path, n: usize) -> PathBuf {
    let shapes: String = (0..n)
        .map(|i| {
            format!(
                r#"<shape type="rectangle"><bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="t{i}.png"/></texture></bsdf></shape>"#
            )
        })
        .collect();
    let xml = format!(
        r#"<scene version="3.0.0"><integrator type="path"/>
  <sensor type="perspective"><float name="fov" value="40"/>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film>
  </sensor>{shapes}<emitter type="constant"/></scene>"#
    );
    let p = dir.join("textures.xml");
    std::fs::write(&p, xml).unwrap();
    p
}

#[test]
fn texture_header_claiming_8192_squared_is_refused_before_decoding() {
    let d = scratch("texhead");
    png(&d.join("t0.png"), 8192, true);
    let scene = texture_scene(&d, 1);
    let (code, err) = render(&[scene.to_str().unwrap(), "--max-memory", "64M"]);
    assert_refused(
        code,
        &err,
        "t0.png: decoding this 8192 × 8192 image",
        "would need",
    );
    assert!(err.contains("line 4"), "{err}");
}

#[test]
fn textures_add_up_against_the_budget() {
    let d = scratch("texsum");
    for i in 0..6 {
        png(&d.join(format!("t{i}.png")), 256, false);
    }
    let scene = texture_scene(&d, 6);
    let (code, err) = render(&[scene.to_str().unwrap(), "--max-memory", "1M"]);
    assert_refused(
        code,
        &err,
        "t3.png: decoding this 256 × 256 image beside the 589824 bytes of images before it",
        "would need",
    );
    // Six 256² 8-bit textures are kept at 3 bytes a pixel: 1.2 MB in all.
    let out = d.join("out.exr");
    let (code, err) = render(&[
        scene.to_str().unwrap(),
        "--max-memory",
        "4M",
        "--spp",
        "1",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(0), "{err}");
}

/// Issue 26: meshes are summed, with the acceleration structure their triangles will
/// need, not checked one at a time: six shapes that each fit refuse together (the third
/// passes 4 MiB), at the element of the shape where the sum passes the budget.
#[test]
fn meshes_add_up_against_the_budget() {
    let d = scratch("meshsum");
    // A 32 × 32 grid of quads: 2048 triangles.
    let mut text = String::new();
    for j in 0..=32 {
        for i in 0..=32 {
            text.push_str(&format!(
                "v {} {} 0\n",
                i as f32 / 16.0 - 1.0,
                j as f32 / 16.0 - 1.0
            ));
        }
    }
    for j in 0..32 {
        for i in 0..32 {
            let v = j * 33 + i + 1;
            text.push_str(&format!("f {} {} {} {}\n", v, v + 1, v + 34, v + 33));
        }
    }
    std::fs::write(d.join("grid.obj"), text).unwrap();
    let shapes: String = (0..6)
        .map(|_| "  <shape type=\"obj\"><string name=\"filename\" value=\"grid.obj\"/></shape>\n")
        .collect();
    let xml = format!(
        r#"<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0,0,4" target="0,0,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film>
  </sensor>
  <emitter type="constant"/>
{shapes}</scene>"#
    );
    let scene = d.join("six.xml");
    std::fs::write(&scene, xml).unwrap();
    let (code, err) = render(&[scene.to_str().unwrap(), "--max-memory", "4M"]);
    assert_refused(
        code,
        &err,
        "six.xml, line 9, column 3, in <shape type=\"obj\">",
        "the shapes up to this one (6144 primitives) with their acceleration structure would need",
    );
    // With room, the same scene renders.
    let out = d.join("out.exr");
    let (code, err) = render(&[
        scene.to_str().unwrap(),
        "--max-memory",
        "16M",
        "--spp",
        "1",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(0), "{err}");
}
