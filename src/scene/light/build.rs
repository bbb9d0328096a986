//! Building [`Lights`] from a scene description: each emitter with its power, the
//! rectangle fast paths and the choice of lights.

use super::choice::{LightChoice, LightPlace};
use super::rect::AreaRect;
use super::{mean, EnvMap, Light, LightError, Lights};
use crate::sampling::warp::RectangleFrame;
use crate::scene::description::{EmitterDesc, SceneDescription};
use crate::scene::render::geo::Geometry;
use std::f32::consts::PI;

impl Lights {
    /// The lights of a scene; `radius` bounds the scene (for the power of environment
    /// lights).
    pub fn new(desc: &SceneDescription, geo: &Geometry, radius: f32) -> Result<Self, LightError> {
        let mut lights = Vec::new();
        let mut power = Vec::new();
        let mut shape_light = vec![None; desc.shapes.len()];
        for (i, s) in desc.shapes.iter().enumerate() {
            if let Some(e) = &s.emitter {
                shape_light[i] = Some(lights.len() as u32);
                power.push(PI * geo.shape_area(i as u32) * mean(e.radiance).max(0.0));
                lights.push(Light::Area {
                    shape: i as u32,
                    radiance: e.radiance,
                });
            }
        }
        let mut env = None;
        let mut has_delta = false;
        for e in &desc.emitters {
            match e {
                EmitterDesc::Point {
                    position,
                    intensity,
                } => {
                    has_delta = true;
                    power.push(4.0 * PI * mean(*intensity).max(0.0));
                    lights.push(Light::Point {
                        position: *position,
                        intensity: *intensity,
                    });
                }
                EmitterDesc::Constant { radiance } => {
                    if env.is_some() {
                        return Err(LightError("more than one environment emitter".into()));
                    }
                    env = Some(lights.len() as u32);
                    power.push(4.0 * PI * PI * radius * radius * mean(*radiance).max(0.0));
                    lights.push(Light::Constant {
                        radiance: *radiance,
                    });
                }
                EmitterDesc::EnvMap {
                    filename,
                    scale,
                    to_world,
                } => {
                    if env.is_some() {
                        return Err(LightError("more than one environment emitter".into()));
                    }
                    let map = EnvMap::load(filename, *scale, *to_world)
                        .map_err(|e| LightError(format!("{}: {e}", filename.display())))?;
                    env = Some(lights.len() as u32);
                    power.push(PI * radius * radius * map.integral());
                    lights.push(Light::EnvMap(Box::new(map)));
                }
            }
        }
        let rects: Vec<Option<AreaRect>> = lights
            .iter()
            .map(|l| match *l {
                Light::Area { shape, .. } => geo
                    .parallelogram(shape)
                    .and_then(|(par, n, area)| AreaRect::new(par, n, area)),
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
                Light::Constant { .. } | Light::EnvMap(_) => None,
            })
            .collect();
        let picker = LightChoice::new(&power, &places);
        let only_rect = match (single, picker.is_some(), rects.first(), lights.first()) {
            (true, true, Some(Some(r)), Some(&Light::Area { radiance, .. })) => {
                Some((*r, radiance))
            }
            _ => None,
        };
        let only_rect_frame = match (&only_rect, lights.first()) {
            (Some(_), Some(&Light::Area { shape, .. })) => geo
                .parallelogram(shape)
                .and_then(|([corner, ex, ey], _, _)| RectangleFrame::new(corner, ex, ey).ok())
                .map(Box::new),
            _ => None,
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
            picker,
            only_rect,
            only_rect_frame,
            reads_pick: lights.iter().any(on_mesh),
            single,
            rects,
            lights,
            shape_light,
            env,
            has_delta,
        })
    }
}
