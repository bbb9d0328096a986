//! Tests of `ply_binary.rs`: binary payloads decode to what `ply-rs-bw` reads from the same
//! mesh in ASCII, on layouts off the fast paths, and the fast paths fall back and locate
//! errors.

use super::ply::parse_ply;

/// A header with unusual types: a double position, a byte colour, a list in the vertex
/// element (so no fixed stride), texture coordinates, a short-counted ushort index list
/// before a second list, and an extra element.
const HEAD: &str = "element vertex 4\nproperty double x\nproperty float y\n\
    property uchar red\nproperty float z\nproperty list uchar float extra\n\
    property float s\nproperty float t\nelement face 2\nproperty uchar flags\n\
    property list short ushort vertex_indices\nproperty list uchar int other\n\
    element note 1\nproperty list uint char text\nend_header\n";

/// Vertex rows (x, y, red, z, extra list, s, t) and faces (flags, indices, other).
fn rows() -> (Vec<[f64; 6]>, Vec<Vec<u16>>) {
    let v = vec![
        [0.5, -1.25, 0.0, 3.0, 0.25, 0.75],
        [1e10, 2.0, 1.0, -0.0, 1.0, 0.0],
        [-3.5, 0.125, 2.0, 7.0, 0.5, 0.5],
        [0.1, 0.2, 3.0, 0.3, 0.0, 1.0],
    ];
    (v, vec![vec![0, 1, 2], vec![0, 2, 3, 1]])
}

fn ascii() -> Vec<u8> {
    let (v, f) = rows();
    let mut s = format!("ply\nformat ascii 1.0\n{HEAD}");
    for r in &v {
        s += &format!(
            "{:?} {:?} {} {:?} 2 9.5 8.5 {:?} {:?}\n",
            r[0], r[1] as f32, r[2], r[3] as f32, r[4] as f32, r[5] as f32
        );
    }
    for x in &f {
        let idx: Vec<String> = x.iter().map(u16::to_string).collect();
        s += &format!("7 {} {} 1 -4\n", x.len(), idx.join(" "));
    }
    s += "3 104 105 33\n";
    s.into_bytes()
}

fn binary(big: bool) -> Vec<u8> {
    let (v, f) = rows();
    let order = if big { "big" } else { "little" };
    let mut out = format!("ply\nformat binary_{order}_endian 1.0\n{HEAD}").into_bytes();
    macro_rules! put {
        ($x:expr) => {
            out.extend(if big {
                $x.to_be_bytes()
            } else {
                $x.to_le_bytes()
            })
        };
    }
    for r in &v {
        put!(r[0]);
        put!(r[1] as f32);
        out.push(r[2] as u8);
        put!(r[3] as f32);
        out.push(2);
        put!(9.5f32);
        put!(8.5f32);
        put!(r[4] as f32);
        put!(r[5] as f32);
    }
    for x in &f {
        out.push(7);
        put!(x.len() as i16);
        for &i in x {
            put!(i);
        }
        out.push(1);
        put!(-4i32);
    }
    put!(3u32);
    out.extend([104, 105, 33]);
    out
}

#[test]
fn binary_decoding_matches_ply_rs_on_unusual_layouts() {
    let want = parse_ply(&ascii(), None).expect("ascii reads");
    assert_eq!(want.indices, vec![[0, 1, 2], [0, 2, 3], [0, 3, 1]]);
    assert_eq!(want.uvs.len(), 4);
    for big in [false, true] {
        let got = parse_ply(&binary(big), None).expect("binary reads");
        assert_eq!(got.positions, want.positions, "big endian {big}");
        assert_eq!((&got.uvs, &got.indices), (&want.uvs, &want.indices));
        assert!(got.normals.is_empty());
    }
}

#[test]
fn binary_fast_paths_fall_back_and_locate_errors() {
    // Fixed-stride vertices and byte-counted int triangles, with one quad, one negative
    // index and one cut-short file.
    let head = "ply\nformat binary_little_endian 1.0\nelement vertex 3\n\
        property float x\nproperty float y\nproperty float z\nelement face 2\n\
        property list uchar int vertex_indices\nend_header\n";
    let mut ok = head.as_bytes().to_vec();
    for x in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
        ok.extend(x.to_le_bytes());
    }
    let mut faces = ok.clone();
    faces.push(3);
    [0i32, 1, 2]
        .iter()
        .for_each(|i| faces.extend(i.to_le_bytes()));
    faces.push(4);
    [2i32, 1, 0, 1]
        .iter()
        .for_each(|i| faces.extend(i.to_le_bytes()));
    let m = parse_ply(&faces, None).expect("reads");
    assert_eq!(m.indices, vec![[0, 1, 2], [2, 1, 0], [2, 0, 1]]);
    assert_eq!(m.positions[1].x, 1.0);
    let mut negative = ok.clone();
    for t in [[0i32, 1, 2], [0, -1, 2]] {
        negative.push(3);
        t.iter().for_each(|i| negative.extend(i.to_le_bytes()));
    }
    let e = parse_ply(&negative, None).unwrap_err().to_string();
    assert!(
        e.contains("element \"face\" 1 of 2") && e.contains("negative"),
        "{e}"
    );
    let e = parse_ply(&faces[..faces.len() - 3], None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("element \"face\" 1 of 2") && e.contains("ends"),
        "{e}"
    );
}
