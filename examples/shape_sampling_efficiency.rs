//! Efficiency of the two ways of sampling area lights on the Cornell box: by solid angle
//! (spherical-rectangle and spherical-triangle warps) against uniformly by area.
//!
//! ```text
//! cargo run --release --example shape_sampling_efficiency -- [--spp N] [--threads N]
//!     [--seed S] [--reference tests/data/cornell-box.exr] [--only solid-angle|area]
//! ```
//!
//! Renders the built-in Cornell box (256×256, path tracer, MIS power heuristic) once per
//! [`ShapeSampling`] through the library's geometry, lights, materials, camera and
//! integrator, and prints for each: relMSE = mean((img − ref)² / (ref² + 0.01)) over pixels
//! and channels, the process CPU time of the render (fairer than wall time on a loaded
//! machine), samples per CPU-second, and efficiency = 1 / (relMSE × CPU time).
//!
//! It builds its own small [`Scene`] instead of calling `Renderer` because the renderer does
//! not (yet) expose the shape-sampling choice.

use mcrt::glam::{Vec2, Vec3};
use mcrt::integrator::{Bsdf, Frame, Integrator, LightSample, PathTracer, SampleSource};
use mcrt::integrator::{Scene, Strategy, SurfacePoint};
use mcrt::scene::bsdf::{AnyBsdf, Diffuse, Sided};
use mcrt::scene::camera::Camera;
use mcrt::scene::description::{IntegratorDesc, SceneDescription};
use mcrt::scene::film::{read_exr, PixelFilter};
use mcrt::scene::geometry::{offset_origin, AccelKind, Geometry, Hit, Ray, ShapeSampling};
use mcrt::scene::light::Lights;
use mcrt::scene::render::PixelRng;
use rayon::prelude::*;
use std::path::PathBuf;
use std::process::ExitCode;

/// Relative shortening of shadow rays (as the renderer does).
const SHADOW_EPSILON: f32 = 1e-3;

/// The Cornell box as the estimators see it (Lambertian materials only).
struct View<'a> {
    geo: &'a Geometry,
    lights: &'a Lights,
    bsdfs: Vec<Sided<Diffuse>>,
}

fn surface(h: Hit) -> SurfacePoint {
    SurfacePoint {
        p: h.p,
        ng: h.ng,
        frame: Frame::from_normal(h.ns),
        t: h.t,
        shape: h.shape,
        prim: h.prim,
        uv: h.uv,
    }
}

impl Scene for View<'_> {
    type Bsdf = Sided<Diffuse>;

    fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<SurfacePoint> {
        self.geo.intersect(&Ray { origin, dir }, t_max).map(surface)
    }

    fn trace(&self, from: &SurfacePoint, dir: Vec3) -> Option<SurfacePoint> {
        let origin = offset_origin(from.p, from.ng, dir);
        self.geo
            .intersect(&Ray { origin, dir }, f32::INFINITY)
            .map(surface)
    }

    fn occluded(&self, from: &SurfacePoint, dir: Vec3, dist: f32) -> bool {
        let origin = offset_origin(from.p, from.ng, dir);
        self.geo
            .occluded(&Ray { origin, dir }, dist * (1.0 - SHADOW_EPSILON))
    }

    fn bsdf(&self, sp: &SurfacePoint) -> &Sided<Diffuse> {
        &self.bsdfs[sp.shape as usize]
    }

    fn is_emitter(&self, sp: &SurfacePoint) -> bool {
        self.lights.area_radiance(sp.shape).is_some()
    }

    fn emitted(&self, sp: &SurfacePoint, wo: Vec3) -> Vec3 {
        match self.lights.area_radiance(sp.shape) {
            Some(l) if sp.ng.dot(wo) > 0.0 => l,
            _ => Vec3::ZERO,
        }
    }

    fn has_environment(&self) -> bool {
        false
    }

    fn environment(&self, _dir: Vec3) -> Vec3 {
        Vec3::ZERO
    }

    fn has_delta_lights(&self) -> bool {
        false
    }

    fn sample_light(&self, from: &SurfacePoint, u_pick: Vec2, u: Vec2) -> Option<LightSample> {
        self.lights.sample(self.geo, from, u_pick, u)
    }

    fn light_pdf(&self, from: &SurfacePoint, hit: &SurfacePoint) -> f32 {
        self.lights.pdf_hit(self.geo, from, hit)
    }

    fn environment_pdf(&self, _from: &SurfacePoint, _dir: Vec3) -> f32 {
        0.0
    }
}

struct Args {
    spp: u32,
    threads: usize,
    seed: u64,
    reference: PathBuf,
    only: Option<String>,
}

fn parse_args() -> Result<Args, String> {
    let mut a = Args {
        spp: 16,
        threads: 0,
        seed: 0,
        reference: PathBuf::from("tests/data/cornell-box.exr"),
        only: None,
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{arg} needs a value"));
        let bad = |v: &str| format!("{arg}: '{v}' is not a valid number");
        match arg.as_str() {
            "--spp" => {
                let v = value()?;
                a.spp = v.parse().map_err(|_| bad(&v))?;
            }
            "--threads" => {
                let v = value()?;
                a.threads = v.parse().map_err(|_| bad(&v))?;
            }
            "--seed" => {
                let v = value()?;
                a.seed = v.parse().map_err(|_| bad(&v))?;
            }
            "--reference" => a.reference = value()?.into(),
            "--only" => a.only = Some(value()?),
            _ => {
                return Err(
                    "usage: shape_sampling_efficiency [--spp N] [--threads N] [--seed S] \
                     [--reference ref.exr] [--only solid-angle|area]"
                        .into(),
                )
            }
        }
    }
    Ok(a)
}

/// CPU time (user + system) of this process in seconds, from `/proc/self/stat`.
fn cpu_seconds() -> Result<f64, String> {
    let stat = std::fs::read_to_string("/proc/self/stat").map_err(|e| e.to_string())?;
    // Fields after the parenthesised command name: state is field 3; utime, stime are 14, 15.
    let rest = stat.rsplit_once(')').map(|(_, r)| r).ok_or("bad stat")?;
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| -> Result<f64, String> {
        f.get(i - 3)
            .and_then(|s| s.parse::<f64>().ok())
            .ok_or_else(|| "bad stat".to_string())
    };
    // Linux reports these in USER_HZ, 100 per second on every common configuration.
    Ok((ticks(14)? + ticks(15)?) / 100.0)
}

/// Renders `spp` samples per pixel; returns the image and the CPU seconds it took.
fn render(
    desc: &SceneDescription,
    how: ShapeSampling,
    args: &Args,
) -> Result<(Vec<Vec3>, f64), String> {
    let geo = Geometry::new(&desc.shapes, None, AccelKind::Bvh)
        .map_err(|e| e.to_string())?
        .with_shape_sampling(how);
    let lights = Lights::new(desc, &geo, geo.bounding_sphere().1).map_err(|e| e.to_string())?;
    let bsdfs = desc
        .shapes
        .iter()
        .map(|s| {
            let b = AnyBsdf::from_desc(&s.bsdf).map_err(|e| e.to_string())?;
            let bsdf = b.bsdf.as_diffuse().ok_or("the Cornell box is Lambertian")?;
            Ok(Sided {
                bsdf,
                two_sided: b.two_sided,
            })
        })
        .collect::<Result<Vec<_>, String>>()?;
    let camera = Camera::new(&desc.sensor).map_err(|e| e.to_string())?;
    let filter = PixelFilter::from_desc(&desc.sensor.film.filter);
    let IntegratorDesc::Path {
        max_depth,
        rr_depth,
    } = desc.integrator
    else {
        return Err("expected a path tracer".into());
    };
    let integrator = Integrator::Path(PathTracer {
        max_depth,
        rr_depth,
        strategy: Strategy::MisPower,
    });
    let scene = View {
        geo: &geo,
        lights: &lights,
        bsdfs,
    };
    debug_assert!(scene.bsdfs.iter().all(|b| !b.flags().delta));
    let (w, h) = (camera.width(), camera.height());
    let pixel = |index: u32| -> Vec3 {
        let (x, y) = (index % w, index / w);
        let mut sum = Vec3::ZERO;
        for s in 0..args.spp {
            let mut rng = PixelRng::new(args.seed, u64::from(index), u64::from(s));
            let film = Vec2::new(x as f32 + 0.5, y as f32 + 0.5) + filter.sample(rng.next_2d());
            let (ray, t_max) = camera.generate_ray_with_tmax(film);
            let v = integrator
                .li(&scene, ray.origin, ray.dir, t_max, &mut rng)
                .radiance;
            sum += if v.is_finite() { v } else { Vec3::ZERO };
        }
        sum / args.spp as f32
    };
    let t0 = cpu_seconds()?;
    let img: Vec<Vec3> = (0..w * h).into_par_iter().map(pixel).collect();
    Ok((img, cpu_seconds()? - t0))
}

/// mean((img − ref)² / (ref² + 0.01)) over pixels and channels.
fn rel_mse(img: &[Vec3], reference: &[Vec3]) -> f64 {
    let sum: f64 = img
        .iter()
        .zip(reference)
        .map(|(a, r)| {
            let (a, r) = (a.as_dvec3(), r.as_dvec3());
            let d = a - r;
            (d * d / (r * r + 0.01)).element_sum()
        })
        .sum();
    sum / (3 * img.len()) as f64
}

fn run() -> Result<(), String> {
    let args = parse_args()?;
    if args.threads > 0 {
        rayon::ThreadPoolBuilder::new()
            .num_threads(args.threads)
            .build_global()
            .map_err(|e| e.to_string())?;
    }
    let desc = mcrt::scene::cornell_box::cornell_box();
    let (rw, rh, reference) = read_exr(&args.reference).map_err(|e| e.to_string())?;
    let film = &desc.sensor.film;
    if (rw, rh) != (film.width, film.height) {
        return Err(format!(
            "reference is {rw}×{rh}, the scene renders {}×{}",
            film.width, film.height
        ));
    }
    let samples = f64::from(args.spp) * f64::from(rw * rh);
    println!(
        "Cornell box {rw}×{rh}, {} spp, MIS power heuristic",
        args.spp
    );
    println!(
        "{:<12} {:>10} {:>9} {:>14} {:>12}",
        "sampling", "relMSE", "CPU s", "M samples/CPUs", "efficiency"
    );
    let mut eff = Vec::new();
    for (name, how) in [
        ("solid-angle", ShapeSampling::SolidAngle),
        ("area", ShapeSampling::Area),
    ] {
        if args.only.as_deref().is_some_and(|o| o != name) {
            continue;
        }
        let (img, cpu) = render(&desc, how, &args)?;
        let e = rel_mse(&img, &reference);
        let efficiency = 1.0 / (e * cpu);
        eff.push(efficiency);
        println!(
            "{name:<12} {e:>10.3e} {cpu:>9.2} {:>14.3} {efficiency:>12.2}",
            samples / cpu / 1e6
        );
    }
    println!(
        "efficiency ratio solid-angle / area: {:.2}",
        eff[0] / eff[1]
    );
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("shape_sampling_efficiency: {e}");
            ExitCode::FAILURE
        }
    }
}
