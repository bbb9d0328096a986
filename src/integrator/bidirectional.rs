//! What the bidirectional estimators ([`Bdpt`](super::Bdpt), [`Mlt`](super::Mlt)) need from
//! a scene beyond [`Scene`]: emitters as the start of light subpaths, and the camera as an
//! endpoint that light subpaths connect to.
//!
//! Measures, as in Veach 1997 (thesis, chapters 8 and 10): positions on lights per unit
//! area, emission directions per unit solid angle. Lights at infinity swap the two: their
//! "position" is the direction light arrives from (per steradian) and their "direction" is
//! the ray origin on a disk perpendicular to it, beyond the scene's bounding sphere (per
//! unit area of that disk), as pbrt-v4 does.

use super::{Scene, SurfacePoint};
use glam::{Vec2, Vec3};

/// What kind of emitter a light subpath starts on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EmitterKind {
    /// Emission from a surface point (area light): position per unit area, direction per
    /// steradian, emitted radiance `Scene::emitted`.
    Area,
    /// A point light: a Dirac delta in position (`pdf_pos` is the choice probability
    /// alone); `radiance` holds the intensity (W/sr) along the sampled direction (see
    /// [`BidirectionalScene::point_intensity`] for lights that are not isotropic).
    Point,
    /// A light at infinity (environment): `pdf_pos` is the density of the arrival
    /// direction per steradian, `pdf_dir` that of the ray origin per unit area of the disk.
    Infinite,
    /// A directional light: at infinity like [`EmitterKind::Infinite`], but a Dirac delta
    /// in direction (`pdf_pos` is the choice probability alone); `pdf_dir` is the density
    /// of the ray origin per unit area of the disk, `radiance` holds the irradiance (W/m²).
    Directional,
}

/// One emitted ray, the start of a light subpath.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EmissionSample {
    /// The scene's index of the light (opaque to the estimators; passed back to
    /// [`BidirectionalScene::emission_pdf`]).
    pub light: u32,
    /// The kind of emitter.
    pub kind: EmitterKind,
    /// The ray origin: a point on the light (its `ng` the emitting side's normal), the
    /// point light's position, or a point on the disk of a light at infinity.
    pub point: SurfacePoint,
    /// Unit direction the light travels along.
    pub dir: Vec3,
    /// Radiance along `dir` (intensity for a point light).
    pub radiance: Vec3,
    /// Density of the position per unit area, times the probability of choosing this
    /// light (see [`EmitterKind`] for point lights and lights at infinity).
    pub pdf_pos: f32,
    /// Density of the direction per steradian (per unit disk area at infinity).
    pub pdf_dir: f32,
}

/// A surface or lens point connected to the camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraConnection {
    /// Film position in pixels (`(0, 0)` the top-left corner).
    pub raster: Vec2,
    /// Unit direction from the point toward the camera.
    pub wi: Vec3,
    /// Distance from the point to the camera's centre of projection.
    pub dist: f32,
    /// Importance `W(ω)` per unit solid angle at the camera, normalised so that
    /// `∫ W(ω) L(ω) dω` over the image is the mean of the image's pixels.
    pub importance: f32,
}

/// A scene that the bidirectional estimators can run on: a [`Scene`] with emission
/// sampling and a camera endpoint.
///
/// Every density here must agree with what the matching sampling routine returns: the
/// estimators' multiple-importance weights divide one by another, and a mismatch biases
/// the image silently. [`Bdpt::check_mis_weights`](super::Bdpt::check_mis_weights) tests a
/// scene's densities against its sampling routines through the weights; the renderer's
/// `mcrt-render/tests/it/chi2_bidirectional.rs` and `bdpt_weights.rs` check the built-in scene's.
pub trait BidirectionalScene: Scene {
    /// Samples an emitted ray: `u_pick.x` chooses a light (by power, independent of any
    /// shading point), `u_pick.y` a part of it such as a triangle, `u_pos` a point on it,
    /// `u_dir` a direction. `None` when there is no light or the sample has zero density.
    fn sample_emission(&self, u_pick: Vec2, u_pos: Vec2, u_dir: Vec2) -> Option<EmissionSample>;

    /// Densities `(pdf_pos, pdf_dir)` with which [`Self::sample_emission`] produces light
    /// `light`'s point `point` and the direction `dir` leaving it (for a light at infinity,
    /// `dir` is the direction of travel and `point` is ignored).
    fn emission_pdf(&self, light: u32, point: &SurfacePoint, dir: Vec3) -> (f32, f32);

    /// Intensity (W/sr) that the point-like light `light` (an [`EmitterKind::Point`]
    /// emitter) sends along the unit direction `dir`, for a light whose intensity varies
    /// with direction, such as a spot light. The default, `None`, means isotropic: the
    /// intensity its [`EmissionSample::radiance`] carried, in every direction.
    #[inline]
    fn point_intensity(&self, _light: u32, _dir: Vec3) -> Option<Vec3> {
        None
    }

    /// The light index of the area emitter under `sp`, if any.
    fn emitter_at(&self, sp: &SurfacePoint) -> Option<u32>;

    /// The light index of the environment, if any.
    fn environment_light(&self) -> Option<u32>;

    /// The camera ray through film position `raster` (pixels): origin, unit direction and
    /// the distance along it to the far clip plane.
    fn camera_ray(&self, raster: Vec2) -> (Vec3, Vec3, f32);

    /// The camera's centre of projection.
    fn camera_position(&self) -> Vec3;

    /// Unit direction the camera looks along.
    fn camera_forward(&self) -> Vec3;

    /// Density per steradian of the camera ray direction `dir` for a film position drawn
    /// uniformly over the image; 0 outside the field of view.
    fn camera_pdf(&self, dir: Vec3) -> f32;

    /// Connects the point `p` to the camera: its film position, the direction and
    /// distance to the camera and the importance there. `None` when `p` is outside the
    /// field of view or the clipping range.
    fn connect_camera(&self, p: Vec3) -> Option<CameraConnection>;

    /// Film size in pixels.
    fn film_size(&self) -> (u32, u32);

    /// Whether the camera has a lens of positive aperture: camera rays and connections to
    /// the camera then take a lens sample. The default, `false`, is the pinhole that the
    /// other camera methods describe; a lens camera implements the `*_lens` methods below
    /// as well (the thin lens's densities are derived in `mcrt-render/src/camera/thin_lens.rs`).
    fn camera_has_lens(&self) -> bool {
        false
    }

    /// The camera ray through film position `raster` and the lens point of
    /// `u_lens ∈ [0,1)²`, as [`Self::camera_ray`].
    fn camera_ray_through_lens(&self, raster: Vec2, _u_lens: Vec2) -> (Vec3, Vec3, f32) {
        self.camera_ray(raster)
    }

    /// The point on the lens that the camera ray from `origin` along `dir` left: the
    /// camera subpath's first vertex. The default is [`Self::camera_position`].
    fn camera_lens_point(&self, _origin: Vec3, _dir: Vec3) -> Vec3 {
        self.camera_position()
    }

    /// [`Self::camera_pdf`] for a ray leaving the lens point `lens` along `dir`.
    fn camera_pdf_from_lens(&self, _lens: Vec3, dir: Vec3) -> f32 {
        self.camera_pdf(dir)
    }

    /// [`Self::connect_camera`] through the lens point of `u_lens ∈ [0,1)²` (chosen with
    /// the same density as camera rays choose theirs): that lens point and the connection
    /// from it. The default connects to [`Self::camera_position`].
    fn connect_camera_through_lens(
        &self,
        p: Vec3,
        _u_lens: Vec2,
    ) -> Option<(Vec3, CameraConnection)> {
        self.connect_camera(p).map(|c| (self.camera_position(), c))
    }
}
