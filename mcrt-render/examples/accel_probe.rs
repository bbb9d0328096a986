//! Builds one acceleration structure over one scene of `benches/accel.rs` and runs that
//! benchmark's closest-hit (and, on the Cornell box, occlusion) queries once: a small binary
//! for counting instructions with callgrind, where criterion's timing loops would take far
//! too long. Prints the hit count.
//!
//! ```text
//! cargo build --release -p mcrt-render --example accel_probe
//! valgrind --tool=callgrind --callgrind-out-file=kd.cg \
//!     target/release/examples/accel_probe soup kdtree
//! callgrind_annotate --inclusive=yes kd.cg | grep -E "Accel::build|Geometry::intersect"
//! ```
//!
//! Scenes: `cornell` (16 384 rays), `soup` (100 000 triangles), `sphere` (130 560
//! triangles; 4096 rays each). Structures: `bvh`, `bvh8`, `grid`, `kdtree`, `brute`.

use mcrt_render::description::ShapeDesc;
use mcrt_render::geometry::{AccelKind, Geometry, Ray};
use rand::SeedableRng;
use rand_pcg::Pcg64;
use std::hint::black_box;
use std::process::ExitCode;

#[path = "../tests/it/common/scenes.rs"]
mod scenes;
use scenes::{cornell_box, random_rays, soup, tessellated_sphere};

/// The benchmark's scene and rays (the same seeds and counts).
fn scene(name: &str) -> Option<(Vec<ShapeDesc>, Vec<Ray>)> {
    match name {
        "cornell" => {
            let rays = random_rays(&mut Pcg64::seed_from_u64(11), 16_384, 0.95);
            Some((cornell_box(), rays))
        }
        "soup" | "sphere" => {
            let mut r = Pcg64::seed_from_u64(15);
            let rays = random_rays(&mut r, 4096, 0.5);
            let shapes = if name == "soup" {
                vec![soup(&mut r, 100_000)]
            } else {
                vec![tessellated_sphere(256, 256)]
            };
            Some((shapes, rays))
        }
        _ => None,
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let kind = match args.get(1).map(String::as_str) {
        Some("bvh") => AccelKind::Bvh,
        Some("bvh8") => AccelKind::Bvh8,
        Some("grid") => AccelKind::Grid,
        Some("kdtree") => AccelKind::KdTree,
        Some("brute") => AccelKind::BruteForce,
        _ => {
            eprintln!("usage: accel_probe cornell|soup|sphere bvh|bvh8|grid|kdtree|brute");
            return ExitCode::FAILURE;
        }
    };
    let Some((shapes, rays)) = args.first().and_then(|s| scene(s)) else {
        eprintln!("usage: accel_probe cornell|soup|sphere bvh|bvh8|grid|kdtree|brute");
        return ExitCode::FAILURE;
    };
    let g = match Geometry::new(&shapes, None, kind) {
        Ok(g) => g,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let hits = rays
        .iter()
        .filter(|ray| black_box(&g).intersect(ray, f32::INFINITY).is_some())
        .count();
    let blocked = rays
        .iter()
        .filter(|ray| args[0] == "cornell" && black_box(&g).occluded(ray, 1.0))
        .count();
    println!(
        "{kind:?}: {hits} hits, {blocked} occluded of {} rays",
        rays.len()
    );
    ExitCode::SUCCESS
}
