//! Path vertices of the bidirectional estimators and the densities between them, per unit
//! area (per steradian toward a light at infinity). `docs/renderer.md`, "Bidirectional path
//! tracing", derives the conversions.

use crate::integrator::{BidirectionalScene, Bsdf, EmissionSample, EmitterKind, SurfacePoint};
use crate::sampling::Frame;
use glam::{Vec2, Vec3};

/// Which way a subpath carries its quantity: radiance (camera subpaths) or importance
/// (light subpaths, which see the adjoint BSDF).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Mode {
    Radiance,
    Importance,
}

/// What a vertex is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    /// The camera's centre of projection.
    Camera,
    /// A scattering surface (possibly emitting too: `light` is then set).
    Surface,
    /// The first vertex of a light subpath, or a camera ray that escaped to the environment
    /// (`Infinite`).
    Light(EmitterKind),
}

/// A vertex with the subpath's throughput up to it and the densities of sampling it from
/// either side.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Vertex {
    pub kind: Kind,
    pub sp: SurfacePoint,
    /// Toward a light at infinity: the unit direction from the scene to the light.
    pub w_env: Vec3,
    /// The scene's light index for lights and emitting surfaces, else `u32::MAX`.
    pub light: u32,
    /// A point light's intensity.
    pub intensity: Vec3,
    /// Throughput of the subpath up to and including this vertex's sampling density.
    pub beta: Vec3,
    /// Density of this vertex when sampled from its own subpath's side.
    pub pdf_fwd: f32,
    /// [`Vertex::pdf_fwd`] per unit area, kept when a Dirac delta sampled here re-expressed
    /// `pdf_fwd` per projected solid angle: a connection that ends here (at a BSDF with
    /// both kinds of component, such as plastic) sees this vertex as not delta.
    pub pdf_fwd_area: f32,
    /// Density of this vertex when sampled from the other side.
    pub pdf_rev: f32,
    /// The scattering at this vertex was a Dirac delta (no connection can end here).
    pub delta: bool,
    /// The BSDF here has a non-delta component (connections can end here).
    pub smooth: bool,
    /// Unit direction toward the previous vertex of this vertex's own subpath (zero at an
    /// endpoint), and the squared distance to it (infinite from a light at infinity):
    /// kept so that connections need not recompute them.
    pub w_prev: Vec3,
    pub d2_prev: f32,
}

/// No light index.
pub(crate) const NO_LIGHT: u32 = u32::MAX;

/// A surface point for a point in space with no surface (camera, point light, the disk of a
/// light at infinity): zero normal, so rays leaving it are not offset.
pub(crate) fn bare_point(p: Vec3) -> SurfacePoint {
    SurfacePoint {
        p,
        ng: Vec3::ZERO,
        frame: Frame::from_normal(Vec3::Z),
        t: 0.0,
        shape: u32::MAX,
        prim: 0,
        uv: Vec2::ZERO,
        instance: 0,
    }
}

impl Vertex {
    /// A vertex of `kind` at `sp`, with no light, throughput `beta` and forward density
    /// `pdf_fwd`.
    pub(crate) fn new(kind: Kind, sp: SurfacePoint, beta: Vec3, pdf_fwd: f32) -> Self {
        Self {
            kind,
            sp,
            w_env: Vec3::ZERO,
            light: NO_LIGHT,
            intensity: Vec3::ZERO,
            beta,
            pdf_fwd,
            pdf_fwd_area: pdf_fwd,
            pdf_rev: 0.0,
            delta: false,
            smooth: true,
            w_prev: Vec3::ZERO,
            d2_prev: 0.0,
        }
    }

    /// The light vertex an emitted ray starts from: throughput `1/pdf_pos`, forward density
    /// `pdf_pos`.
    pub(crate) fn from_emission(es: &EmissionSample) -> Self {
        let mut v = Self::new(
            Kind::Light(es.kind),
            es.point,
            Vec3::splat(1.0 / es.pdf_pos),
            es.pdf_pos,
        );
        v.light = es.light;
        match es.kind {
            EmitterKind::Infinite => v.w_env = -es.dir,
            EmitterKind::Directional => {
                v.w_env = -es.dir;
                v.intensity = es.radiance;
            }
            EmitterKind::Point => v.intensity = es.radiance,
            EmitterKind::Area => {}
        }
        v
    }

    /// At infinity: an environment or a directional light (directions toward it do not
    /// depend on the position; densities toward it stay per steradian).
    #[inline]
    pub(crate) fn is_infinite(&self) -> bool {
        matches!(
            self.kind,
            Kind::Light(EmitterKind::Infinite | EmitterKind::Directional)
        )
    }

    /// On a surface with a normal (densities toward it carry its cosine).
    #[inline]
    pub(crate) fn on_surface(&self) -> bool {
        matches!(self.kind, Kind::Surface | Kind::Light(EmitterKind::Area))
    }

    /// A Dirac delta in position or direction (a point, spot or directional light: no
    /// camera path can hit it; the pinhole is handled by the estimators).
    #[inline]
    pub(crate) fn is_delta_light(&self) -> bool {
        matches!(
            self.kind,
            Kind::Light(EmitterKind::Point | EmitterKind::Directional)
        )
    }

    /// This vertex as a connection that ends here sees it: not delta, its forward density
    /// per unit area (Veach 1997, thesis, section 10.3.5; pbrt-v3 clears the flag the same
    /// way in its `MISWeight`).
    #[inline]
    pub(crate) fn as_endpoint(&self) -> Vertex {
        Vertex {
            delta: false,
            pdf_fwd: self.pdf_fwd_area,
            ..*self
        }
    }

    /// Whether a connection may end here.
    #[inline]
    pub(crate) fn connectible(&self) -> bool {
        match self.kind {
            Kind::Surface => self.smooth,
            Kind::Camera | Kind::Light(_) => true,
        }
    }

    /// Whether this vertex emits (a light, or a surface on an area light).
    #[inline]
    pub(crate) fn is_light(&self) -> bool {
        self.light != NO_LIGHT
    }

    /// Unit direction from this vertex to `to`, and the squared distance (infinite toward
    /// or from a light at infinity).
    #[inline]
    pub(crate) fn dir_to(&self, to: &Vertex) -> (Vec3, f32) {
        if to.is_infinite() {
            return (to.w_env, f32::INFINITY);
        }
        if self.is_infinite() {
            return (-self.w_env, f32::INFINITY);
        }
        let d = to.sp.p - self.sp.p;
        let d2 = d.length_squared();
        if d2 > 0.0 {
            (d / d2.sqrt(), d2)
        } else {
            (Vec3::ZERO, 0.0)
        }
    }

    /// A density per steradian at this vertex toward `to`, in the measure the weights use
    /// for `to`: per unit area (unchanged toward a light at infinity), or, when `to`
    /// scattered by a Dirac delta, per unit *projected* solid angle at this vertex
    /// (`pdf / |cos θ|`). Across a chain of specular vertices the generalized geometric
    /// terms of the two directions then cancel in the ratio of two strategies' densities
    /// (Veach 1997, thesis, section 10.3.5), where per-area densities would leave the
    /// geometry of the chain's first segment from each side in it.
    #[inline]
    pub(crate) fn area_density(&self, pdf_sa: f32, to: &Vertex) -> f32 {
        let (w, d2) = self.dir_to(to);
        self.area_density_along(pdf_sa, to, w, d2)
    }

    /// [`Vertex::area_density`] with the unit direction `w` to `to` and the squared
    /// distance `d2` already known.
    #[inline]
    pub(crate) fn area_density_along(&self, pdf_sa: f32, to: &Vertex, w: Vec3, d2: f32) -> f32 {
        if to.is_infinite() {
            return pdf_sa;
        }
        if to.delta {
            let cos = if self.on_surface() {
                self.sp.ng.dot(w).abs()
            } else {
                1.0
            };
            return if cos > 0.0 { pdf_sa / cos } else { 0.0 };
        }
        if !(d2 > 0.0 && d2.is_finite()) {
            return 0.0;
        }
        let cos = if to.on_surface() {
            to.sp.ng.dot(w).abs()
        } else {
            1.0
        };
        pdf_sa * cos / d2
    }

    /// Density per unit area with which this vertex, reached from `prev`, samples `next`;
    /// an emitting surface with no `prev` (the end of a camera subpath) samples by emission.
    /// (The estimators use `pdf_along` with known directions; `Bdpt::check_mis_weights`
    /// recomputes every density of a path from scratch with this.)
    pub(crate) fn pdf<S: BidirectionalScene>(
        &self,
        scene: &S,
        prev: Option<&Vertex>,
        next: &Vertex,
    ) -> f32 {
        let (w, d2) = self.dir_to(next);
        let w_in = prev.map(|p| self.dir_to(p).0);
        self.pdf_along(scene, w_in, next, w, d2)
    }

    /// `Vertex::pdf` with the directions known: `w_in` toward the vertex this one was
    /// reached from (`None` at an endpoint), `w` toward `next`, `d2` the squared distance
    /// to it.
    pub(crate) fn pdf_along<S: BidirectionalScene>(
        &self,
        scene: &S,
        w_in: Option<Vec3>,
        next: &Vertex,
        w: Vec3,
        d2: f32,
    ) -> f32 {
        match (self.kind, w_in) {
            (Kind::Light(_), _) | (Kind::Surface, None) => self.pdf_light_along(scene, next, w, d2),
            (Kind::Camera, _) => {
                let pdf = scene.camera_pdf_from_lens(self.sp.p, w);
                self.area_density_along(pdf, next, w, d2)
            }
            (Kind::Surface, Some(wp)) => {
                let f = &self.sp.frame;
                let pdf = scene.bsdf(&self.sp).pdf(f.to_local(wp), f.to_local(w));
                self.area_density_along(pdf, next, w, d2)
            }
        }
    }

    /// Density per unit area at `next` of the emission direction of this light (or
    /// emitting surface) toward it.
    pub(crate) fn pdf_light<S: BidirectionalScene>(&self, scene: &S, next: &Vertex) -> f32 {
        let (w, d2) = self.dir_to(next);
        self.pdf_light_along(scene, next, w, d2)
    }

    /// `Vertex::pdf_light` with the unit direction `w` to `next` and the squared distance
    /// `d2` known.
    pub(crate) fn pdf_light_along<S: BidirectionalScene>(
        &self,
        scene: &S,
        next: &Vertex,
        w: Vec3,
        d2: f32,
    ) -> f32 {
        if self.is_infinite() {
            let (_, pdf_disk) = scene.emission_pdf(self.light, &self.sp, -self.w_env);
            let cos = if next.on_surface() && !next.delta {
                next.sp.ng.dot(self.w_env).abs()
            } else {
                1.0
            };
            return pdf_disk * cos;
        }
        let (_, pdf_dir) = scene.emission_pdf(self.light, &self.sp, w);
        self.area_density_along(pdf_dir, next, w, d2)
    }

    /// Density with which a light subpath starts at this light (or emitting surface)
    /// point: per unit area with the light's choice (per steradian for a light at
    /// infinity).
    pub(crate) fn pdf_light_origin<S: BidirectionalScene>(&self, scene: &S, next: &Vertex) -> f32 {
        let w = if self.is_infinite() {
            -self.w_env
        } else {
            self.dir_to(next).0
        };
        scene.emission_pdf(self.light, &self.sp, w).0
    }

    /// Radiance this light (or emitting surface) sends toward `to`.
    pub(crate) fn le<S: BidirectionalScene>(&self, scene: &S, to: &Vertex) -> Vec3 {
        if !self.is_light() {
            return Vec3::ZERO;
        }
        match self.kind {
            Kind::Light(EmitterKind::Infinite) => scene.environment(self.w_env),
            Kind::Light(EmitterKind::Directional) => self.intensity,
            Kind::Light(EmitterKind::Point) => scene
                .point_intensity(self.light, self.dir_to(to).0)
                .unwrap_or(self.intensity),
            _ => scene.emitted(&self.sp, self.dir_to(to).0),
        }
    }

    /// The BSDF times the cosine at this surface vertex in the subpath's `mode`, with world
    /// directions: `wo` toward this subpath's previous vertex, `wi` the other way.
    pub(crate) fn f_dirs<S: BidirectionalScene>(
        &self,
        scene: &S,
        wo: Vec3,
        wi: Vec3,
        mode: Mode,
    ) -> Vec3 {
        let fr = &self.sp.frame;
        let bsdf = scene.bsdf(&self.sp);
        match mode {
            Mode::Radiance => bsdf.eval(fr.to_local(wo), fr.to_local(wi)),
            Mode::Importance => {
                bsdf.eval_adjoint(fr.to_local(wo), fr.to_local(wi))
                    * shading_correction(&self.sp, wo, wi)
            }
        }
    }
}

/// The factor that makes importance transport with shading normals the adjoint of radiance
/// transport: `|wo·n_s| |wi·n_g| / (|wo·n_g| |wi·n_s|)` (Veach 1997, thesis, eq. 5.19); 1
/// where the shading and geometric normals agree.
#[inline]
pub(crate) fn shading_correction(sp: &SurfacePoint, wo: Vec3, wi: Vec3) -> f32 {
    let (ns, ng) = (sp.frame.n, sp.ng);
    if ns == ng {
        return 1.0;
    }
    let num = wo.dot(ns).abs() * wi.dot(ng).abs();
    let den = wo.dot(ng).abs() * wi.dot(ns).abs();
    if den > 0.0 {
        num / den
    } else {
        0.0
    }
}
