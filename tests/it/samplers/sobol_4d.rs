//! The 4D Sobol sampler: nets in each dimension, a joint (3,k,4)-net in each pair of
//! dimensions `2j, 2j + 1`, and independent scrambles between pairs.

use super::*;

/// The first `count` samples of pixel `pixel`: the 2D values of dimensions `0..dims`.
fn points<S: Sampler>(s: &mut S, pixel: [u32; 2], count: u32, dims: usize) -> Vec<Vec<Vec2>> {
    (0..count)
        .map(|i| {
            s.start_pixel_sample(pixel, i);
            (0..dims).map(|_| s.next_2d()).collect()
        })
        .collect()
}

/// Whether every box of the grid `2^a × 2^b × 2^c × 2^d` over the 4D points
/// (u_j.x, u_j.y, u_{j+1}.x, u_{j+1}.y) holds the same number of points.
fn equal_boxes(pts: &[Vec<Vec2>], j: usize, shape: [u32; 4]) -> bool {
    let n = shape.iter().sum::<u32>();
    let mut boxes = vec![0u32; 1 << n];
    for p in pts {
        let coords = [p[j].x, p[j].y, p[j + 1].x, p[j + 1].y];
        let mut index = 0usize;
        for (v, bits) in coords.into_iter().zip(shape) {
            assert!(in_unit(v), "{v}");
            index = (index << bits) | ((v * (1u32 << bits) as f32) as usize);
        }
        boxes[index] += 1;
    }
    boxes.iter().all(|&b| b == boxes[0])
}

/// All shapes `[a, b, c, d]` with `a + b + c + d = total`.
fn shapes(total: u32) -> Vec<[u32; 4]> {
    let mut out = Vec::new();
    for a in 0..=total {
        for b in 0..=total - a {
            for c in 0..=total - a - b {
                out.push([a, b, c, total - a - b - c]);
            }
        }
    }
    out
}

/// 256 samples: every elementary box of volume 2⁻⁵ (all 56 shapes) over a pair `2j, 2j + 1`
/// holds 8 points, the (3,8,4)-net property of Sobol dimensions 0–3 under Owen scrambling.
#[test]
fn pairs_of_dimensions_form_4d_nets() {
    let mut s = Sobol4dSampler::new(256, 3).unwrap();
    for pixel in [[0, 0], [17, 4], [1000, 999]] {
        let pts = points(&mut s, pixel, 256, 6);
        for j in [0, 2, 4] {
            for shape in shapes(5) {
                assert!(
                    equal_boxes(&pts, j, shape),
                    "pixel {pixel:?} dims {j}, {}: {shape:?}",
                    j + 1
                );
            }
        }
    }
}

/// The 4D check has power: the 2D-padded Sobol sampler's dimensions 0 and 1 are each nets,
/// but not jointly (random pairing leaves most 4D shapes unequal).
#[test]
fn the_4d_check_rejects_2d_padding() {
    let mut s = SobolSampler::new(256, 3).unwrap();
    let pts = points(&mut s, [17, 4], 256, 2);
    let equal = shapes(5)
        .into_iter()
        .filter(|&sh| equal_boxes(&pts, 0, sh))
        .count();
    println!("2D padding: {equal} of 56 shapes equal");
    // Only shapes within one dimension (c = d = 0 or a = b = 0) are guaranteed: 12 of 56.
    assert!(equal <= 14, "{equal} of 56 shapes equal");
}

/// Each 2D dimension on its own: even dimensions (Sobol 0–1) are (0,k,2)-nets, odd ones
/// (Sobol 2–3) (2,k,2)-nets (each elementary interval of area `2^(2-k)` holds 4 points), for
/// k up to 10. No better pair than t = 2 exists among Sobol dimensions 2 to 7.
#[test]
fn each_dimension_is_a_net() {
    let mut s = Sobol4dSampler::new(1024, 77).unwrap();
    let pts = points(&mut s, [5, 6], 1024, 4);
    for k in 2..=10u32 {
        for d in 0..4 {
            let t = 2 * (d % 2) as u32;
            for a in 0..=k - t {
                let (nx, ny) = (1u32 << a, 1u32 << (k - t - a));
                let mut cells = vec![0u32; (nx * ny) as usize];
                for p in &pts[..1 << k] {
                    let u = p[d];
                    cells[((u.y * ny as f32) as u32 * nx + (u.x * nx as f32) as u32) as usize] += 1;
                }
                assert!(
                    cells.iter().all(|&c| c == 1 << t),
                    "k {k} dim {d} grid {nx}x{ny}: {cells:?}"
                );
            }
        }
    }
}

/// Dimensions of different pairs are scrambled independently: (x of dimension 1, x of
/// dimension 2) over 16 samples fill a 4 × 4 grid like independent points (about 11 cells),
/// while within a pair they fill all 16.
#[test]
fn pairs_are_independent_of_each_other() {
    let mut s = Sobol4dSampler::new(16, 21).unwrap();
    let (mut across, mut within, mut grids) = (0u32, 0u32, 0u32);
    for p in 0..64u32 {
        let pts = points(&mut s, [p, 3], 16, 4);
        let filled = |a: usize, b: usize| {
            let mut cells = [false; 16];
            for u in &pts {
                cells[(u[a].x * 4.0) as usize * 4 + (u[b].x * 4.0) as usize] = true;
            }
            cells.iter().filter(|&&c| c).count() as u32
        };
        across += filled(1, 2);
        within += filled(0, 1) + filled(2, 3);
        grids += 1;
    }
    let across = f64::from(across) / f64::from(grids);
    let within = f64::from(within) / f64::from(2 * grids);
    assert!(
        across.is_finite() && (9.0..13.0).contains(&across),
        "{across} cells across"
    );
    assert_eq!(within, 16.0);
}
