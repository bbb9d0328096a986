//! Building [`Lights`] from a scene description: each emitter with its power, the
//! choice of lights and the sampling plan.

use super::bvh_choice::{BvhChoice, BvhEntry, BVH_MIN_LIGHTS};
use super::choice::{LightChoice, LightPlace};
use super::{mean, EnvMap, Light, LightBvhUse, LightError, Lights, Projector, SamplePlan, Spot};
use crate::description::{EmitterDesc, SceneDescription};
use crate::geometry::{Geometry, RectangleSampler, ShapeSampling};
use mcrt::sampling::light_bvh::LightBounds;
use std::f32::consts::PI;

impl Lights {
    /// The lights of a scene; `radius` bounds the scene (for the power of environment
    /// lights).
    pub fn new(desc: &SceneDescription, geo: &Geometry, radius: f32) -> Result<Self, LightError> {
        Self::with_bvh(desc, geo, radius, LightBvhUse::Auto)
    }

    /// [`Lights::new`], choosing the lights of next-event estimation by the light BVH as
    /// `bvh` says.
    pub fn with_bvh(
        desc: &SceneDescription,
        geo: &Geometry,
        radius: f32,
        bvh: LightBvhUse,
    ) -> Result<Self, LightError> {
        let mut lights = Vec::new();
        let mut power = Vec::new();
        let mut shape_light = vec![None; desc.shapes.len()];
        let shape_texture: Vec<Option<crate::texture::Texture>> = if desc
            .shapes
            .iter()
            .any(|s| s.emitter.is_some() && s.emission_texture.is_some())
        {
            desc.shapes
                .iter()
                .map(|s| s.emitter.and(s.emission_texture.clone()))
                .collect()
        } else {
            Vec::new()
        };
        for (i, s) in desc.shapes.iter().enumerate() {
            if let Some(e) = &s.emitter {
                shape_light[i] = Some(lights.len() as u32);
                power.push(PI * geo.shape_area(i as u32) * mean(e.radiance.get()).max(0.0));
                lights.push(Light::Area {
                    shape: i as u32,
                    radiance: e.radiance.get(),
                });
            }
        }
        let mut env = None;
        let mut has_delta = false;
        for (j, e) in desc.emitters.iter().enumerate() {
            let at = |error: LightError| locate(desc, j, error);
            match &**e {
                EmitterDesc::Point {
                    position,
                    intensity,
                } => {
                    has_delta = true;
                    power.push(4.0 * PI * mean(intensity.get()).max(0.0));
                    lights.push(Light::Point {
                        position: *position,
                        intensity: intensity.get(),
                    });
                }
                EmitterDesc::Spot {
                    intensity,
                    cutoff_angle,
                    beam_width,
                    to_world,
                } => {
                    let spot = Spot::new(intensity.get(), *cutoff_angle, *beam_width, *to_world)
                        .map_err(at)?;
                    has_delta = true;
                    power.push(spot.power());
                    lights.push(Light::Spot(Box::new(spot)));
                }
                EmitterDesc::Textured { inner, texture } => {
                    let EmitterDesc::Spot {
                        intensity,
                        cutoff_angle,
                        beam_width,
                        to_world,
                    } = **inner
                    else {
                        return Err(at(LightError::Spot(
                            "only a spot light takes a texture here".into(),
                        )));
                    };
                    let spot = Spot::new(intensity.get(), cutoff_angle, beam_width, to_world)
                        .map_err(at)?
                        .with_texture(texture.clone(), to_world);
                    has_delta = true;
                    power.push(spot.power());
                    lights.push(Light::Spot(Box::new(spot)));
                }
                EmitterDesc::Projector {
                    irradiance,
                    scale,
                    x_fov,
                    to_world,
                } => {
                    let aspect = texture_aspect(irradiance);
                    let p = Projector::new(irradiance.clone(), aspect, *scale, *x_fov, *to_world)
                        .map_err(at)?;
                    has_delta = true;
                    power.push(p.power());
                    lights.push(Light::Projector(Box::new(p)));
                }
                EmitterDesc::Directional {
                    irradiance,
                    direction,
                } => {
                    // The light through the disk of the scene's bounding sphere.
                    has_delta = true;
                    power.push(PI * radius * radius * mean(irradiance.get()).max(0.0));
                    lights.push(Light::Directional {
                        direction: direction.normalize_or_zero(),
                        irradiance: irradiance.get(),
                    });
                }
                EmitterDesc::Constant { radiance } => {
                    if env.is_some() {
                        return Err(at(LightError::SeveralEnvironments));
                    }
                    env = Some(lights.len() as u32);
                    power.push(4.0 * PI * PI * radius * radius * mean(radiance.get()).max(0.0));
                    lights.push(Light::Constant {
                        radiance: radiance.get(),
                    });
                }
                EmitterDesc::EnvMap {
                    filename,
                    scale,
                    to_world,
                } => {
                    if env.is_some() {
                        return Err(at(LightError::SeveralEnvironments));
                    }
                    let map = EnvMap::load(filename, *scale, *to_world).map_err(|reason| {
                        at(LightError::EnvMap {
                            path: filename.clone(),
                            reason,
                        })
                    })?;
                    env = Some(lights.len() as u32);
                    power.push(PI * radius * radius * map.integral());
                    lights.push(Light::EnvMap(Box::new(map)));
                }
            }
        }
        check_power(desc, &lights, &power)?;
        let rectangles: Vec<Option<RectangleSampler>> = lights
            .iter()
            .map(|l| match *l {
                Light::Area { shape, .. } => geo.rectangle_sampler(shape).cloned(),
                _ => None,
            })
            .collect();
        let single = lights.len() == 1;
        let places: Vec<Option<LightPlace>> = lights
            .iter()
            .map(|l| match *l {
                Light::Area { shape, .. } => geo
                    .shape_bounding_sphere(shape)
                    .map(|(center, radius)| LightPlace { center, radius }),
                Light::Point { position, .. } => Some(LightPlace {
                    center: position,
                    radius: 0.0,
                }),
                Light::Spot(ref s) => Some(LightPlace {
                    center: s.position(),
                    radius: 0.0,
                }),
                Light::Projector(ref p) => Some(LightPlace {
                    center: p.position(),
                    radius: 0.0,
                }),
                Light::Constant { .. } | Light::EnvMap(_) | Light::Directional { .. } => None,
            })
            .collect();
        let picker = LightChoice::new(&power, &places);
        let bvh = picker
            .as_ref()
            .filter(|_| bvh != LightBvhUse::Never)
            .and_then(|_| bvh_choice(&lights, &power, geo, &shape_texture, bvh));
        let lone_rectangle = bvh.is_none()
            && single
            && picker.is_some()
            && matches!(rectangles[..], [Some(_)])
            && shape_texture.is_empty();
        let plan = match (picker.is_some(), lone_rectangle, geo.shape_sampling()) {
            (false, _, _) => SamplePlan::Nothing,
            (true, true, ShapeSampling::Area) => SamplePlan::LoneRectangleByArea,
            (true, true, ShapeSampling::SolidAngle) => SamplePlan::LoneRectangleBySolidAngle,
            (true, true, ShapeSampling::Auto) => SamplePlan::LoneRectangleByDistance,
            (true, false, _) => SamplePlan::Choose {
                single: single && bvh.is_none(),
            },
        };
        let on_mesh =
            |l: &Light| matches!(*l, Light::Area { shape, .. } if geo.shape_reads_pick(shape));
        let shape_radiance = shape_light
            .iter()
            .map(|l| match l.map(|i| &lights[i as usize]) {
                Some(Light::Area { radiance, .. }) => Some(*radiance),
                _ => None,
            })
            .collect();
        Ok(Self {
            shape_radiance,
            shape_texture,
            picker,
            plan,
            reads_pick: bvh.is_some() || lights.iter().any(on_mesh),
            bvh,
            rectangles,
            lights,
            shape_light,
            env,
            has_delta,
            candidates: 0,
        })
    }
}

/// The light BVH's choice when more than [`BVH_MIN_LIGHTS`] lights have a position (each
/// emitting triangle of a mesh counted as one, unless its emission is textured: such a mesh
/// stays one light); `None` below, or when a light's bounds are not usable.
fn bvh_choice(
    lights: &[Light],
    power: &[f32],
    geo: &Geometry,
    shape_texture: &[Option<crate::texture::Texture>],
    bvh: LightBvhUse,
) -> Option<BvhChoice> {
    // Count first: the per-triangle bounds are built only when the tree will be.
    let count: usize = lights
        .iter()
        .map(|l| match *l {
            Light::Area { shape, .. } if !textured(shape_texture, shape) => {
                geo.triangle_count(shape).unwrap_or(1)
            }
            Light::Constant { .. } | Light::EnvMap(_) | Light::Directional { .. } => 0,
            _ => 1,
        })
        .sum();
    if count == 0 || (bvh == LightBvhUse::Auto && count <= BVH_MIN_LIGHTS) {
        return None;
    }
    let mut entries = Vec::with_capacity(count);
    let mut bounds = Vec::with_capacity(count);
    let mut unbounded = Vec::new();
    for (i, l) in lights.iter().enumerate() {
        let whole = |b: mcrt::sampling::light_bvh::LightBounds| {
            (
                vec![BvhEntry {
                    light: i as u32,
                    triangle: None,
                }],
                vec![b],
            )
        };
        let (e, b) = match *l {
            Light::Area { shape, radiance } => {
                let per_triangle = (!textured(shape_texture, shape))
                    .then(|| geo.triangle_light_bounds(shape, mean(radiance).max(0.0)))
                    .flatten();
                match per_triangle {
                    Some(b) => (
                        (0..b.len() as u32)
                            .map(|k| BvhEntry {
                                light: i as u32,
                                triangle: Some(k),
                            })
                            .collect(),
                        b,
                    ),
                    None => whole(geo.shape_light_bounds(shape, power[i])?),
                }
            }
            Light::Point { position, .. } => whole(LightBounds::point(position, power[i])),
            Light::Spot(ref s) => whole(s.light_bounds(power[i])),
            Light::Projector(ref p) => whole(LightBounds::point(p.position(), power[i])),
            Light::Constant { .. } | Light::EnvMap(_) | Light::Directional { .. } => {
                unbounded.push(i as u32);
                continue;
            }
        };
        entries.extend(e);
        bounds.extend(b);
    }
    BvhChoice::new(lights.len(), entries, &bounds, unbounded, power)
}

/// Whether the area light on shape `shape` has a textured emission.
fn textured(shape_texture: &[Option<crate::texture::Texture>], shape: u32) -> bool {
    matches!(shape_texture.get(shape as usize), Some(Some(_)))
}

/// The width over height of a texture's image (Mitsuba's `resolution()`; 1 for a
/// checkerboard, which has none).
pub(crate) fn texture_aspect(t: &crate::texture::Texture) -> f32 {
    match t {
        crate::texture::Texture::Bitmap(b) => b.image.width() as f32 / b.image.height() as f32,
        crate::texture::Texture::Checkerboard(_) => 1.0,
    }
}

/// `error`, at the element emitter `j` was written in, if the description knows it.
fn locate(desc: &SceneDescription, j: usize, error: LightError) -> LightError {
    match desc.origins.emitter(j) {
        Some(at) => LightError::Located {
            at: at.clone(),
            error: Box::new(error),
        },
        None => error,
    }
}

/// Refuses a light whose power is not a finite `f32`, or powers whose sum is not (the choice
/// of lights needs both), naming the brightest such light: it could not be chosen, and was
/// dropped without a word (issue 26).
fn check_power(desc: &SceneDescription, lights: &[Light], power: &[f32]) -> Result<(), LightError> {
    let total: f32 = power.iter().sum();
    if total.is_finite() {
        return Ok(());
    }
    // The first light whose power is infinite or NaN, else the brightest.
    let i = power
        .iter()
        .position(|p| !p.is_finite())
        .or_else(|| (0..power.len()).max_by(|&a, &b| power[a].total_cmp(&power[b])))
        .unwrap_or(0);
    let shape_lights = lights
        .iter()
        .filter(|l| matches!(l, Light::Area { .. }))
        .count();
    let (light, origin) = match lights.get(i) {
        Some(Light::Area { shape, .. }) => {
            let id = desc
                .shapes
                .get(*shape as usize)
                .and_then(|s| s.id.as_deref());
            let name = match id {
                Some(id) => format!("the area light on shape \"{id}\""),
                None => format!("the area light on shape {}", shape + 1),
            };
            (name, desc.origins.shape(*shape as usize))
        }
        Some(l) => {
            let kind = match l {
                Light::Point { .. } => "point",
                Light::Spot(_) => "spot",
                Light::Projector(_) => "projector",
                Light::Directional { .. } => "directional",
                Light::Constant { .. } => "constant",
                _ => "envmap",
            };
            let emitter = i - shape_lights;
            let name = format!("the {kind} light (emitter {})", emitter + 1);
            (name, desc.origins.emitter(emitter))
        }
        None => ("a light".into(), None),
    };
    let error = LightError::PowerOverflow {
        light,
        power: format!("{:e}", power.get(i).copied().unwrap_or(f32::INFINITY)),
    };
    Err(match origin {
        Some(at) => LightError::Located {
            at: at.clone(),
            error: Box::new(error),
        },
        None => error,
    })
}
