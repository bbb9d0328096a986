//! Converts a linear EXR to an sRGB PNG: `cargo run --bin exr2png -- in.exr out.png`;
//! with a third argument `ref.exr`, writes instead the relative difference |in − ref| / ref
//! of 8×8 block means (white = 10% or more) and prints the worst blocks.
use mcrt::glam::Vec3;
use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let a: Vec<String> = std::env::args().skip(1).collect();
    if a.len() < 2 {
        return Err("usage: exr2png in.exr out.png [ref.exr]".into());
    }
    let (w, h, px) = mcrt_render::film::read_exr(Path::new(&a[0]))?;
    let Some(r) = a.get(2) else {
        mcrt_render::film::write_png(Path::new(&a[1]), w, h, &px)?;
        return Ok(());
    };
    let (_, _, rf) = mcrt_render::film::read_exr(Path::new(r))?;
    let var = match a.get(3) {
        Some(v) => mcrt_render::film::read_exr(Path::new(v))?.2,
        None => vec![Vec3::ZERO; px.len()],
    };
    let b = 8;
    let mut out = vec![Vec3::ZERO; px.len()];
    let mut list = Vec::new();
    for by in 0..h / b {
        for bx in 0..w / b {
            let (mut s, mut t, mut v) = (Vec3::ZERO, Vec3::ZERO, Vec3::ZERO);
            for y in by * b..(by + 1) * b {
                for x in bx * b..(bx + 1) * b {
                    s += px[(y * w + x) as usize];
                    t += rf[(y * w + x) as usize];
                    v += var[(y * w + x) as usize];
                }
            }
            let e = (s - t).x / t.x.max(1e-6);
            let z = (s - t).x / v.x.sqrt().max(1e-12);
            list.push((if a.len() > 3 { z } else { e }, bx * b, by * b, t.x / 64.0));
            for y in by * b..(by + 1) * b {
                for x in bx * b..(bx + 1) * b {
                    out[(y * w + x) as usize] = if e > 0.0 {
                        Vec3::new(e * 10.0, 0.0, 0.0)
                    } else {
                        Vec3::new(0.0, 0.0, -e * 10.0)
                    };
                }
            }
        }
    }
    list.sort_by(|a, b| b.0.abs().total_cmp(&a.0.abs()));
    for l in list.iter().take(12) {
        println!("block at ({}, {}): {:+.3} (ref {:.4})", l.1, l.2, l.0, l.3);
    }
    mcrt_render::film::write_png(Path::new(&a[1]), w, h, &out)?;
    Ok(())
}
