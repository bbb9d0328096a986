//! Which light-transport effects a scene calls for, decided from its materials, emitters
//! and `max_depth`.

use crate::bsdf::{AnyBsdf, Sided};
use crate::light::Lights;
use mcrt::integrator::{Bsdf, Integrator};

/// The effects a scene needs; the renderer picks a specialised render loop from them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Effects {
    /// Every material is Lambertian: the loop is compiled for `Diffuse` alone.
    pub diffuse_only: bool,
    /// Some material is a rough conductor.
    pub glossy: bool,
    /// Some material is a smooth mirror or glass (delta BSDF).
    pub specular: bool,
    /// Some material refracts.
    pub refraction: bool,
    /// Some light is a point light.
    pub delta_lights: bool,
    /// There is a light at infinity.
    pub environment: bool,
    /// Some material has a textured parameter: materials are formed per hit.
    pub textures: bool,
    /// Paths continue past the first bounce (`max_depth` is −1 or above 2).
    pub indirect: bool,
}

impl Effects {
    /// Analyses materials, lights and the integrator.
    pub fn of(bsdfs: &[Sided<AnyBsdf>], lights: &Lights, integrator: &Integrator) -> Self {
        let mut e = Effects {
            diffuse_only: bsdfs.iter().all(|b| b.bsdf.as_diffuse().is_some()),
            delta_lights: lights.has_delta(),
            environment: lights.has_environment(),
            indirect: match integrator {
                Integrator::Path(p) => p.max_depth < 0 || p.max_depth > 2,
                Integrator::Direct(_) => false,
                Integrator::Bdpt(b) => b.max_depth < 0 || b.max_depth > 2,
                Integrator::Mlt(m) => m.max_depth > 2,
            },
            ..Effects::default()
        };
        for b in bsdfs {
            let f = b.flags();
            e.glossy |= f.glossy;
            e.specular |= f.delta;
            e.refraction |= f.transmission;
        }
        e
    }

    /// A one-line description such as `diffuse-only, indirect`.
    pub fn describe(&self) -> String {
        let mut v = Vec::new();
        if self.diffuse_only {
            v.push("diffuse-only");
        } else {
            v.push("diffuse");
        }
        for (on, name) in [
            (self.glossy, "glossy"),
            (self.specular, "specular"),
            (self.refraction, "refraction"),
            (self.delta_lights, "delta lights"),
            (self.environment, "environment"),
            (self.textures, "textures"),
        ] {
            if on {
                v.push(name);
            }
        }
        v.push(if self.indirect {
            "indirect"
        } else {
            "direct only"
        });
        v.join(", ")
    }
}
