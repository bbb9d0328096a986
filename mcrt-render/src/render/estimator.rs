//! Assembling the estimators' inputs from a [`SceneDescription`]: geometry, lights,
//! materials, camera, the integrator with its settings, and the resolved sample count.

use super::guided_loop::GuidedSetup;
use super::samples::resolve;
use super::{split, Effects, RenderError, RenderOptions, Renderer};
use crate::bsdf::{AnyBsdf, TexturedBsdf};
use crate::camera::Camera;
use crate::description::{
    Checked, IntegratorDesc, IntegratorKind, SceneDescription, ShapeDesc, ShapeGroupDesc, ShapeKind,
};
use crate::film::{Film, PixelFilter};
use crate::geometry::{Geometry, ShapeSampling};
use crate::light::Lights;
use glam::{Vec3, Vec4Swizzles};
use mcrt::integrator::{
    Bdpt, DirectIntegrator, GuidedPathTracer, Integrator, Mlt, PathTracer, Strategy,
};
use std::collections::HashMap;
use std::sync::Arc;

impl Renderer {
    /// The body of [`Renderer::new`], on its thread pool.
    pub(super) fn prepare(
        desc: &SceneDescription,
        opts: &RenderOptions,
    ) -> Result<Self, RenderError> {
        // No pass over `desc` to check it: it holds only `Checked` parts
        // (`description::Checked`), checked when they were made.
        let film = &desc.sensor.film;
        let window = film.window();
        let resolved = resolve(desc, opts, window.width as u64 * window.height as u64)?;
        // The bidirectional estimators' s = 1 strategy samples rectangles and triangles by
        // area: their other strategies cover what solid-angle sampling adds near a light,
        // at a fraction of its cost (spheres keep cone sampling either way).
        let shape_sampling = match resolved.integrator.kind() {
            IntegratorKind::Bdpt | IntegratorKind::Mlt | IntegratorKind::Ptracer => {
                ShapeSampling::Area
            }
            _ => opts.light_sampling,
        };
        // The loader has resolved mesh file names against the scene file's folder already
        // (a description built in code names them relative to the working directory).
        let geo = Geometry::new(&desc.shapes, None, opts.accel)
            .map_err(|e| {
                let at = desc.origins.shape(e.shape()).cloned();
                let error = RenderError::Geometry(e);
                match at {
                    Some(at) => RenderError::Located {
                        at,
                        error: Box::new(error),
                    },
                    None => error,
                }
            })?
            .with_shape_sampling(shape_sampling);
        let mut lights = Lights::with_bvh(desc, &geo, scene_radius(desc), opts.light_bvh)
            .map_err(RenderError::Lights)?;
        if matches!(
            resolved.integrator.kind(),
            IntegratorKind::Path | IntegratorKind::Direct
        ) {
            lights.set_light_candidates(
                opts.light_candidates
                    .unwrap_or(super::options::DEFAULT_LIGHT_CANDIDATES),
            );
        }
        let camera = Camera::new(&desc.sensor).map_err(RenderError::Camera)?;
        // Per shape in the numbering hits report: the scene's, then its groups'.
        let all_shapes = desc.all_shapes();
        let bsdfs = all_shapes
            .iter()
            .enumerate()
            .map(|(i, s)| {
                AnyBsdf::from_desc(&s.bsdf).map_err(|error| RenderError::Material {
                    shape: i,
                    id: s.id.clone(),
                    error,
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let per_hit =
            |s: &crate::description::ShapeDesc| s.bsdf.is_textured() || s.bsdf.needs_tangent();
        let textured = all_shapes.iter().any(|s| per_hit(s)).then(|| {
            bsdfs
                .iter()
                .zip(&all_shapes)
                .map(|(b, s)| TexturedBsdf::with_base(b.clone(), &s.bsdf))
                .collect::<Vec<_>>()
        });
        let strategy = opts.strategy.unwrap_or_default();
        let integrator = integrator(&resolved.integrator, strategy, opts.bdpt_only);
        check_bidirectional(&integrator, &camera, strategy)?;
        let guided = guided_setup(&resolved.integrator, &integrator);
        if guided.is_some() {
            check_guided(opts)?;
        }
        if desc.moment.is_some()
            && (guided.is_some()
                || !matches!(integrator, Integrator::Path(_) | Integrator::Direct(_)))
        {
            return Err(RenderError::Unsupported {
                integrator: if guided.is_some() {
                    "guided"
                } else {
                    integrator.name()
                },
                reason: "the moment integrator wraps only path and direct, which sample per pixel",
            });
        }
        if film.width == 0 || film.height == 0 {
            return Err(RenderError::EmptyFilm {
                width: film.width,
                height: film.height,
            });
        }
        // The rendered window: the whole film, or its crop window (the camera maps it).
        let (width, height) = (camera.width(), camera.height());
        let (w64, h64) = (u64::from(width), u64::from(height));
        crate::memory::check(
            &format!("the film of {width} × {height} pixels"),
            Film::bytes_for(w64, h64),
        )
        .map_err(RenderError::Invalid)?;
        if let Integrator::Mlt(m) = &integrator {
            let need = super::mlt_loop::state_bytes(m, w64, h64);
            crate::memory::check(
                &format!(
                    "Metropolis light transport at {width} × {height} pixels and max_depth {} \
                     (its chains' images, per-length sums and bootstrap)",
                    m.max_depth
                ),
                need.saturating_add(Film::bytes_for(w64, h64)),
            )
            .map_err(RenderError::Invalid)?;
        }
        if guided.is_some() {
            crate::memory::check(
                &format!(
                    "the guided path tracer at {width} × {height} pixels (the images of its \
                     last passes, combined at the end)"
                ),
                super::guided_loop::extra_bytes(w64 * h64)
                    .saturating_add(Film::bytes_for(w64, h64)),
            )
            .map_err(RenderError::Invalid)?;
        }
        let mut effects = Effects::of(&bsdfs, &lights, &integrator);
        if textured.is_some() {
            effects.textures = true;
            effects.diffuse_only = false;
        }
        let spp = resolved.spp.get();
        let (samples, crop) = split::window(opts, &integrator, spp, width, height)?;
        let moment_more = moment_more(desc, strategy, opts)?;
        let mut described = desc.clone();
        described.integrator = resolved.integrator;
        // The sampler is no part of the sensor's check (its count is a checked one).
        described.sensor.change_unchecked(|s| {
            s.sampler = crate::description::SamplerDesc {
                kind: resolved.kind,
                sample_count: resolved.spp,
                seed: resolved.seed,
            }
        });
        let identity = split::render_identity(
            &described,
            None,
            &format!(
                "{integrator:?} {:?} {shape_sampling:?} {}{}{}",
                opts.accel,
                opts.specialize,
                guided.map_or(String::new(), |g| format!(" {g:?}")),
                // Only where it changes the choice, so that identities stay as they were.
                match lights.bvh_lights() {
                    Some(n) => format!(" light BVH over {n}"),
                    None => String::new(),
                }
            ),
        )
        .map_err(RenderError::Invalid)?;
        Ok(Self {
            geometry: geo,
            lights,
            bsdfs,
            textured,
            camera,
            integrator,
            guided,
            filter: PixelFilter::from_desc(&film.filter),
            width,
            height,
            spp,
            sampler: resolved.sampler,
            threads: opts.threads,
            effects,
            specialize: opts.specialize,
            seed: resolved.seed,
            samples,
            crop,
            identity,
            moment: desc.moment.as_ref().map(|m| m.name.clone()),
            moment_more,
        })
    }
}

/// The library's integrator for description `d`, sampling with `strategy` (and, for `bdpt`,
/// only strategy `only` if given). `ptracer` is bidirectional path tracing with the
/// light-tracing strategies alone.
fn integrator(d: &IntegratorDesc, strategy: Strategy, only: Option<(u32, u32)>) -> Integrator {
    match *d {
        IntegratorDesc::Path(p) => Integrator::Path(PathTracer {
            max_depth: p.max_depth,
            rr_depth: p.rr_depth,
            strategy,
            hide_emitters: p.hide_emitters,
        }),
        // The path tracer the guided one guides (`guided_setup` adds the rest).
        IntegratorDesc::Guided(p) => Integrator::Path(PathTracer {
            max_depth: p.max_depth,
            rr_depth: p.rr_depth,
            strategy,
            hide_emitters: p.hide_emitters,
        }),
        IntegratorDesc::Direct(p) => Integrator::Direct(DirectIntegrator {
            emitter_samples: p.emitter_samples,
            bsdf_samples: p.bsdf_samples,
            strategy,
            hide_emitters: p.hide_emitters,
        }),
        IntegratorDesc::Bdpt(p) => Integrator::Bdpt(Bdpt {
            max_depth: p.max_depth,
            rr_depth: p.rr_depth,
            strategy,
            only,
            hide_emitters: p.hide_emitters,
        }),
        IntegratorDesc::Ptracer(p) => Integrator::Bdpt(Bdpt {
            max_depth: p.max_depth,
            rr_depth: p.rr_depth,
            strategy: Strategy::LightOnly,
            only: None,
            hide_emitters: p.hide_emitters,
        }),
        IntegratorDesc::Mlt(p) => Integrator::Mlt(Mlt {
            max_depth: p.max_depth.max(1) as u32,
            bootstrap_samples: p.bootstrap_samples,
            chains: p.chains,
            mutations_per_pixel: p.mutations_per_pixel,
            large_step_prob: p.large_step_prob,
            sigma: p.sigma,
            strategy,
            hide_emitters: p.hide_emitters,
        }),
    }
}

/// The guided path tracer of description `d` (`None` unless it is `guided`), from the path
/// tracer `base` that [`integrator`] made of it.
fn guided_setup(d: &IntegratorDesc, base: &Integrator) -> Option<GuidedSetup> {
    match (*d, base) {
        (IntegratorDesc::Guided(p), Integrator::Path(pt)) => Some(GuidedSetup {
            tracer: GuidedPathTracer {
                guide_probability: p.guide_probability,
                ..GuidedPathTracer::from_path_tracer(pt)
            },
            spatial_threshold: p.spatial_threshold,
            directional_threshold: p.directional_threshold,
            min_gain: p.min_gain,
        }),
        _ => None,
    }
}

/// What `guided` cannot do: render a part of the samples or pixels (its training passes
/// need every pixel, and a part's tree would differ from the whole's).
fn check_guided(opts: &RenderOptions) -> Result<(), RenderError> {
    if opts.samples.is_some() || opts.crop.is_some() {
        return Err(RenderError::Split(
            "guided cannot be split by --samples or --crop: every part would train its own              guide, so parts would not add up to one render"
                .into(),
        ));
    }
    Ok(())
}

/// The further integrators nested in `moment`, with their names. Each renders the same
/// pixel samples as it would alone, so a render in parts could merge them; their sums are
/// not in the part format yet, so a render with them is refused in parts.
fn moment_more(
    desc: &SceneDescription,
    strategy: Strategy,
    opts: &RenderOptions,
) -> Result<Vec<(String, Integrator)>, RenderError> {
    let Some(m) = desc.moment.as_ref().filter(|m| !m.more.is_empty()) else {
        return Ok(Vec::new());
    };
    if opts.samples.is_some() || opts.crop.is_some() {
        return Err(RenderError::Split(
            "a moment integrator with several nested integrators cannot be rendered in parts \
             (--samples, --crop) yet: the part format keeps one nested integrator's sums"
                .into(),
        ));
    }
    Ok(m.more
        .iter()
        .map(|n| (n.name.clone(), integrator(&n.integrator, strategy, None)))
        .collect())
}

/// What `bdpt` (and `ptracer`, which runs as it) and `mlt` need of the camera and the
/// strategy.
fn check_bidirectional(
    integrator: &Integrator,
    camera: &Camera,
    strategy: Strategy,
) -> Result<(), RenderError> {
    if !matches!(integrator, Integrator::Bdpt(_) | Integrator::Mlt(_)) {
        return Ok(());
    }
    if camera.is_orthographic() {
        return Err(RenderError::Unsupported {
            integrator: integrator.name(),
            reason: "an orthographic camera is a delta in direction: light paths cannot be \
                     connected to it (render it with path, direct or guided)",
        });
    }
    if !camera.is_similarity() {
        return Err(RenderError::Unsupported {
            integrator: integrator.name(),
            reason: "the camera's to_world must be a rotation, uniform scale and \
                     translation (its importance is exact only then)",
        });
    }
    if matches!(strategy, Strategy::BsdfOnly | Strategy::LightOnly)
        && matches!(integrator, Integrator::Mlt(_))
    {
        return Err(RenderError::Unsupported {
            integrator: "mlt",
            reason: "it weighs its strategies by MIS: use --strategy balance or power",
        });
    }
    Ok(())
}

/// Radius of a sphere about the origin that holds every shape (approximate for meshes read
/// from files, which count as a unit cube; an instance counts as the box of its group's
/// points, computed once per group).
fn scene_radius(desc: &SceneDescription) -> f32 {
    let mut r = 1.0f32;
    let mut groups: HashMap<*const Checked<ShapeGroupDesc>, Vec<Vec3>> = HashMap::new();
    for s in &desc.shapes {
        let pts = match &s.kind {
            ShapeKind::Instance(g) => groups
                .entry(Arc::as_ptr(g))
                .or_insert_with(|| group_box_corners(g))
                .clone(),
            _ => shape_points(s),
        };
        for p in pts {
            r = r.max((s.to_world * p.extend(1.0)).xyz().length());
        }
    }
    r
}

/// The points of a shape (not an instance) that [`scene_radius`] counts, in object space.
fn shape_points(s: &ShapeDesc) -> Vec<Vec3> {
    match &s.kind {
        ShapeKind::Mesh { positions, .. } => positions.clone(),
        ShapeKind::Sphere { center, radius } => (0..8)
            .map(|i| *center + Vec3::new(bit(i, 0), bit(i, 1), bit(i, 2)) * *radius)
            .collect(),
        _ => (0..8)
            .map(|i| Vec3::new(bit(i, 0), bit(i, 1), bit(i, 2)))
            .collect(),
    }
}

/// The corners of the box holding a group's shapes' points ([`shape_points`]), in the
/// group's space; none for an empty group.
fn group_box_corners(g: &ShapeGroupDesc) -> Vec<Vec3> {
    let mut b = crate::accel::Aabb::EMPTY;
    for s in &g.shapes {
        for p in shape_points(s) {
            b = b.grow((s.to_world * p.extend(1.0)).xyz());
        }
    }
    if b.is_empty() {
        return Vec::new();
    }
    (0..8)
        .map(|i| {
            let pick = |k: u32, lo: f32, hi: f32| if (i >> k) & 1 == 1 { hi } else { lo };
            Vec3::new(
                pick(0, b.min.x, b.max.x),
                pick(1, b.min.y, b.max.y),
                pick(2, b.min.z, b.max.z),
            )
        })
        .collect()
}

fn bit(i: u32, b: u32) -> f32 {
    if (i >> b) & 1 == 1 {
        1.0
    } else {
        -1.0
    }
}

#[cfg(test)]
mod tests {
    use crate::description::IntegratorKind;
    use crate::render::{RenderOptions, Renderer};
    use crate::validate::CHECKS_RUN;

    /// `Renderer::new` does not walk the description to check it: its parts are `Checked`
    /// ones. Only an integrator it makes itself (`--integrator`) is checked, once.
    #[test]
    fn preparing_a_render_checks_no_part_of_the_description() {
        let d = crate::cornell_box::cornell_box_with(1, 8, -1);
        let count = || CHECKS_RUN.with(|c| c.get());
        let before = count();
        Renderer::prepare(&d, &RenderOptions::default()).expect("renders");
        assert_eq!(count(), before);
        let opts = RenderOptions {
            integrator: Some(IntegratorKind::Bdpt),
            ..RenderOptions::default()
        };
        Renderer::prepare(&d, &opts).expect("renders");
        assert_eq!(count(), before + 1);
    }
}
