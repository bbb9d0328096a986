//! What a scene file says, as data: the output of the XML loader and the input of the
//! renderer. Every default is Mitsuba 3's, so a description built in code with
//! [`Default`] values means what the same XML without those attributes means to Mitsuba.
//!
//! A [`SceneDescription`] holds only checked values: its parts (the integrator, the sensor
//! and its film, each shape with its material and area emitter, each shape group, each
//! emitter) are [`Checked`] ones, made by [`Checked::new`], and the numbers inside them that
//! have a type of their own ([`Roughness`], [`SampleCount`], [`Colour`], [`Ior`]) were
//! checked when those were made. Nothing downstream checks them again.

mod check;
mod checked;
mod colour;
mod instancing;
mod microfacet;
mod origin;
mod perturbation;
mod principled;

use crate::param_defs::generate::ParamValue;
pub use crate::param_defs::integrator::{
    BdptParams, DirectParams, GuidedParams, MltParams, PathParams, PtracerParams,
};
pub use crate::texture::{Texture, TextureParam};
pub use check::{Check, Checked};
pub use checked::{Roughness, SampleCount};
pub use colour::{Colour, Ior};
use glam::{Mat4, Vec3};
pub(crate) use instancing::groups_of;
pub use instancing::ShapeGroupDesc;
pub use microfacet::Microfacet;
pub use origin::{Origin, Origins};
pub use perturbation::{NormalSource, Perturbation};
pub use principled::{PrincipledParams, MAX_SPECULAR};
use std::path::PathBuf;

/// A whole scene: integrator, sensor, shapes with their materials and area emitters, and the
/// emitters that are not attached to shapes.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SceneDescription {
    /// How light transport is estimated.
    pub integrator: Checked<IntegratorDesc>,
    /// The `moment` integrator around the integrator, if any: its outputs are added to the
    /// image.
    pub moment: Option<MomentDesc>,
    /// The camera, its film and its sampler.
    pub sensor: Checked<SensorDesc>,
    /// Every shape, in file order.
    pub shapes: Vec<Checked<ShapeDesc>>,
    /// Emitters not attached to a shape (point, spot, directional, constant environment,
    /// environment map).
    pub emitters: Vec<Checked<EmitterDesc>>,
    /// The file the description was read from, if any (for messages and relative paths).
    pub source: Option<PathBuf>,
    /// Where each top-level shape and emitter was written (filled by the loader; empty for
    /// a description built in code), for errors found when the scene is prepared.
    pub origins: Origins,
}

/// The integrator plugin and its parameters. Each plugin's parameter struct is generated
/// from its list of definitions (`param_defs::integrator`), with `DEFAULT` and `Default`
/// (Mitsuba 3's defaults), so a description built in code names only what it changes:
///
/// ```
/// use mcrt_render::description::{IntegratorDesc, PathParams};
///
/// let i = IntegratorDesc::Path(PathParams { max_depth: 4, ..PathParams::DEFAULT });
/// assert_eq!(i.max_depth(), Some(4));
/// assert!(!i.hide_emitters());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum IntegratorDesc {
    /// Mitsuba's `path`: unidirectional path tracing with next-event estimation and MIS.
    Path(PathParams),
    /// Mitsuba's `direct`: direct lighting with a number of emitter and BSDF samples.
    Direct(DirectParams),
    /// Bidirectional path tracing (Mitsuba 0.6's and pbrt-v4's `bdpt`).
    Bdpt(BdptParams),
    /// Metropolis light transport in primary sample space over bidirectional paths
    /// (Mitsuba 0.6's `pssmlt` parameters under pbrt-v4's `mlt` names).
    Mlt(MltParams),
    /// Mitsuba 3's `ptracer`: particle tracing, i.e. light tracing alone (bidirectional path
    /// tracing's `t = 1` strategies at unit weight), emitters in view included by
    /// connecting points sampled on them to the camera.
    Ptracer(PtracerParams),
    /// Path tracing guided by a learned distribution of incident radiance (Müller, Gross &
    /// Novák 2017, "Practical Path Guiding for Efficient Light-Transport Simulation"; no
    /// Mitsuba 3 plugin, Mitsuba 0.6's `guided_path` of the paper's authors is the model):
    /// the render trains an SD-tree in passes of doubling sample counts and keeps the image
    /// of the final pass.
    Guided(GuidedParams),
}

/// Mitsuba 3's `moment` integrator around sampling integrators (`path` or `direct`): the
/// image is the first nested integrator's, and the EXR gains, per nested integrator in file
/// order, the per-pixel mean of its samples in CIE XYZ as channels `NAME.X`, `NAME.Y`,
/// `NAME.Z`, then for each in the same order the second moment as `m2_NAME.X`, `m2_NAME.Y`,
/// `m2_NAME.Z` (Mitsuba 3.9.1's order and names).
#[derive(Debug, Clone, PartialEq)]
pub struct MomentDesc {
    /// The first nested integrator's name (the description's integrator is that one): its
    /// `name` attribute, else `_arg_0` (Mitsuba's name for the first unnamed nested object).
    pub name: String,
    /// The further nested integrators, in file order (Mitsuba 3 accepts several); each
    /// renders the same pixel samples as if it were alone, and adds its channels.
    pub more: Vec<NestedIntegrator>,
}

/// A further integrator nested in `moment` ([`MomentDesc::more`]).
#[derive(Debug, Clone, PartialEq)]
pub struct NestedIntegrator {
    /// Its `name` attribute, else `_arg_N`, `N` counting the unnamed nested integrators
    /// from 0 (as Mitsuba 3 names them).
    pub name: String,
    /// The integrator (`path` or `direct`).
    pub integrator: Checked<IntegratorDesc>,
}

/// The integrator types, for overriding a scene file's choice (`--integrator`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IntegratorKind {
    /// `path`.
    Path,
    /// `direct`.
    Direct,
    /// `bdpt`.
    Bdpt,
    /// `mlt`.
    Mlt,
    /// `ptracer`.
    Ptracer,
    /// `guided`.
    Guided,
}

impl IntegratorKind {
    /// Parses `path`, `direct`, `bdpt`, `mlt`, `ptracer` or `guided`.
    pub fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "path" => Self::Path,
            "direct" => Self::Direct,
            "bdpt" => Self::Bdpt,
            "mlt" => Self::Mlt,
            "ptracer" => Self::Ptracer,
            "guided" => Self::Guided,
            _ => return None,
        })
    }

    /// The name [`IntegratorKind::parse`] reads.
    pub fn name(self) -> &'static str {
        match self {
            Self::Path => "path",
            Self::Direct => "direct",
            Self::Bdpt => "bdpt",
            Self::Mlt => "mlt",
            Self::Ptracer => "ptracer",
            Self::Guided => "guided",
        }
    }
}

impl IntegratorDesc {
    /// `mlt` with every parameter at its default: the library's
    /// [`Mlt::DEFAULT`](mcrt::integrator::Mlt::DEFAULT) (pbrt-v4's).
    pub const MLT_DEFAULTS: IntegratorDesc = IntegratorDesc::Mlt(MltParams::DEFAULT);

    /// The samples per pixel a render of this integrator takes when nothing overrides the
    /// scene: `mutations_per_pixel` for `mlt`, else the sampler's `sample_count`.
    pub fn samples_per_pixel(&self, sample_count: SampleCount) -> u32 {
        match self {
            Self::Mlt(m) => m.mutations_per_pixel,
            _ => sample_count.get(),
        }
    }

    /// Which integrator this is.
    pub fn kind(&self) -> IntegratorKind {
        match self {
            Self::Path(_) => IntegratorKind::Path,
            Self::Direct(_) => IntegratorKind::Direct,
            Self::Bdpt(_) => IntegratorKind::Bdpt,
            Self::Mlt(_) => IntegratorKind::Mlt,
            Self::Ptracer(_) => IntegratorKind::Ptracer,
            Self::Guided(_) => IntegratorKind::Guided,
        }
    }

    /// The integrator of type `kind` with every parameter at its default.
    pub fn default_of(kind: IntegratorKind) -> IntegratorDesc {
        match kind {
            IntegratorKind::Path => Self::Path(PathParams::DEFAULT),
            IntegratorKind::Direct => Self::Direct(DirectParams::DEFAULT),
            IntegratorKind::Bdpt => Self::Bdpt(BdptParams::DEFAULT),
            IntegratorKind::Mlt => Self::Mlt(MltParams::DEFAULT),
            IntegratorKind::Ptracer => Self::Ptracer(PtracerParams::DEFAULT),
            IntegratorKind::Guided => Self::Guided(GuidedParams::DEFAULT),
        }
    }

    /// Every parameter's value, by its Mitsuba name.
    fn values(&self) -> Vec<(&'static str, ParamValue)> {
        match self {
            Self::Path(p) => p.values(),
            Self::Direct(p) => p.values(),
            Self::Bdpt(p) => p.values(),
            Self::Mlt(p) => p.values(),
            Self::Ptracer(p) => p.values(),
            Self::Guided(p) => p.values(),
        }
    }

    /// Sets the parameter of Mitsuba name `name`, where this integrator has one.
    fn set(&mut self, name: &str, v: ParamValue) {
        match self {
            Self::Path(p) => p.set(name, v),
            Self::Direct(p) => p.set(name, v),
            Self::Bdpt(p) => p.set(name, v),
            Self::Mlt(p) => p.set(name, v),
            Self::Ptracer(p) => p.set(name, v),
            Self::Guided(p) => p.set(name, v),
        }
    }

    /// The value of parameter `name`, where this integrator has one.
    fn value(&self, name: &str) -> Option<ParamValue> {
        self.values()
            .into_iter()
            .find_map(|(n, v)| (n == name).then_some(v))
    }

    /// `max_depth`, where the integrator has one.
    pub fn max_depth(&self) -> Option<i32> {
        match self.value("max_depth") {
            Some(ParamValue::Int(d)) => Some(d as i32),
            _ => None,
        }
    }

    /// `hide_emitters` (Mitsuba 3's meaning), `false` where the integrator has none: `path`
    /// and `direct` see through emitters and not the sky from the camera; `bdpt`, `mlt` and
    /// `ptracer` leave out paths of one segment, so emitters in view look black.
    pub fn hide_emitters(&self) -> bool {
        matches!(self.value("hide_emitters"), Some(ParamValue::Bool(true)))
    }

    /// This description as integrator `kind`, keeping every parameter both types have
    /// (such as `max_depth`, `rr_depth` and `hide_emitters`) and taking the defaults for
    /// the rest (an unlimited depth becomes MLT's default 5, since MLT needs a bound).
    /// Unchanged if it already is of that kind.
    pub fn with_kind(&self, kind: IntegratorKind) -> IntegratorDesc {
        if self.kind() == kind {
            return *self;
        }
        let mut out = Self::default_of(kind);
        for (name, v) in self.values() {
            let unlimited = name == "max_depth" && matches!(v, ParamValue::Int(d) if d < 0);
            if !(kind == IntegratorKind::Mlt && unlimited) {
                out.set(name, v);
            }
        }
        out
    }
}

impl Default for IntegratorDesc {
    fn default() -> Self {
        Self::Path(PathParams::DEFAULT)
    }
}

/// Which image axis `fov` spans.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FovAxis {
    /// The horizontal axis (Mitsuba's default).
    #[default]
    X,
    /// The vertical axis.
    Y,
    /// The shorter of the two.
    Smaller,
    /// The longer of the two.
    Larger,
}

/// The camera's projection: Mitsuba 3's `perspective` (and `thinlens`) or `orthographic`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Projection {
    /// A pinhole (or, with [`SensorDesc::lens`], a thin lens) with the field of view
    /// [`SensorDesc::fov`].
    #[default]
    Perspective,
    /// Mitsuba 3's `orthographic`: rays parallel to the camera's +z, leaving the camera-space
    /// rectangle `[-1, 1] × [-1/a, 1/a]` on the near plane (`a` = width / height), which
    /// `to_world` maps (its scale sets the extent); `fov`, `fov_axis` and `lens` are unused.
    Orthographic,
}

/// A sensor: Mitsuba's `perspective`, `thinlens` or `orthographic`.
#[derive(Debug, Clone, PartialEq)]
pub struct SensorDesc {
    /// The projection.
    pub projection: Projection,
    /// Field of view in degrees, along [`SensorDesc::fov_axis`] (perspective only).
    pub fov: f32,
    /// Which axis `fov` spans.
    pub fov_axis: FovAxis,
    /// Near clip distance (default 0.01).
    pub near_clip: f32,
    /// Far clip distance (default 10⁴).
    pub far_clip: f32,
    /// Camera-to-world transform. The camera looks down +z in its own space, +y up, and
    /// (as in Mitsuba) +x to the left of the image.
    pub to_world: Mat4,
    /// The film.
    pub film: Checked<FilmDesc>,
    /// The sampler.
    pub sampler: SamplerDesc,
    /// The thin lens of a `thinlens` sensor; `None` for a pinhole (`perspective`) and for
    /// `orthographic` (whose check refuses a lens).
    pub lens: Option<ThinLensDesc>,
}

impl Default for SensorDesc {
    fn default() -> Self {
        Self {
            projection: Projection::Perspective,
            fov: 45.0,
            fov_axis: FovAxis::X,
            near_clip: 1e-2,
            far_clip: 1e4,
            to_world: Mat4::IDENTITY,
            film: Checked::default(),
            sampler: SamplerDesc::default(),
            lens: None,
        }
    }
}

/// The film (Mitsuba's `hdrfilm`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilmDesc {
    /// Width in pixels (default 768).
    pub width: u32,
    /// Height in pixels (default 576).
    pub height: u32,
    /// The pixel reconstruction filter.
    pub filter: FilterDesc,
    /// Render only this window of the `width` × `height` image (Mitsuba's `crop_*`); the
    /// output is the window's size. `None`: the whole image.
    pub crop: Option<CropWindow>,
}

impl Default for FilmDesc {
    fn default() -> Self {
        Self {
            width: 768,
            height: 576,
            filter: FilterDesc::default(),
            crop: None,
        }
    }
}

impl FilmDesc {
    /// The window that is rendered: the crop window, or the whole image.
    pub fn window(&self) -> CropWindow {
        self.crop.unwrap_or(CropWindow {
            offset_x: 0,
            offset_y: 0,
            width: self.width,
            height: self.height,
        })
    }
}

/// A window of the film in pixels, `(0, 0)` the top-left corner.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CropWindow {
    /// Left edge (`crop_offset_x`).
    pub offset_x: u32,
    /// Top edge (`crop_offset_y`).
    pub offset_y: u32,
    /// Width (`crop_width`).
    pub width: u32,
    /// Height (`crop_height`).
    pub height: u32,
}

/// A pixel reconstruction filter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FilterDesc {
    /// One pixel wide: each pixel is the plain mean of radiance over its footprint.
    Box,
    /// A Gaussian of the given standard deviation in pixels, truncated at 4σ (Mitsuba's
    /// default filter, σ = 0.5).
    Gaussian {
        /// Standard deviation in pixels.
        stddev: f32,
    },
    /// Mitsuba's `tent`: `max(0, 1 − |x|/r)` per axis.
    Tent {
        /// Radius in pixels (Mitsuba's default 1).
        radius: f32,
    },
}

impl Default for FilterDesc {
    fn default() -> Self {
        Self::Gaussian { stddev: 0.5 }
    }
}

/// Which sample generator a scene asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SamplerKind {
    /// Mitsuba's `independent`.
    #[default]
    Independent,
    /// Mitsuba's `stratified` (jittered).
    Stratified,
    /// Mitsuba's `ldsampler`; ours is Owen-scrambled Sobol padded in 4D sets
    /// ([`Sobol4dSampler`](mcrt::sampling::sampler::Sobol4dSampler), `--sampler sobol4d`),
    /// the lower error per sample of our two Sobol samplers in `docs/sampler-error.md`.
    LowDiscrepancy,
    /// Owen-scrambled Sobol padded per 2D dimension
    /// ([`SobolSampler`](mcrt::sampling::sampler::SobolSampler)); no scene-file name (the
    /// file's `ldsampler` is [`SamplerKind::LowDiscrepancy`]): chosen through the API or
    /// `--sampler sobol`.
    Sobol,
    /// Mitsuba's `multijitter` (jittered): correlated multi-jittered patterns
    /// ([`CmjSampler`](mcrt::sampling::sampler::CmjSampler)).
    MultiJitter,
    /// Mitsuba's `orthogonal` (strength 2, jittered): rendered with the same correlated
    /// multi-jittered patterns, the sample count rounded up to the square of a prime as
    /// Mitsuba's is (64 → 121).
    Orthogonal,
    /// Scrambled Halton ([`HaltonSampler`](mcrt::sampling::sampler::HaltonSampler)); no
    /// Mitsuba 3 plugin, so no scene-file name: chosen through the API or `--sampler halton`.
    Halton,
    /// The R2 lattice ([`R2Sampler`](mcrt::sampling::sampler::R2Sampler)); no Mitsuba 3
    /// plugin, so no scene-file name: chosen through the API or `--sampler r2`.
    R2,
}

/// The sampler plugin.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SamplerDesc {
    /// The generator.
    pub kind: SamplerKind,
    /// Samples per pixel (default 4).
    pub sample_count: SampleCount,
    /// Seed (default 0).
    pub seed: u64,
}

impl Default for SamplerDesc {
    fn default() -> Self {
        Self {
            kind: SamplerKind::Independent,
            sample_count: SampleCount::DEFAULT,
            seed: 0,
        }
    }
}

/// The geometry of a shape, in its object space (before `to_world`).
#[derive(Debug, Clone, PartialEq)]
pub enum ShapeKind {
    /// `rectangle`: [−1,1]² in the z = 0 plane, facing +z.
    Rectangle,
    /// `cube`: [−1,1]³, faces pointing outwards.
    Cube,
    /// `disk`: the unit disk in the z = 0 plane, facing +z.
    Disk,
    /// `sphere`: centre and radius (applied before `to_world`), normals pointing outwards.
    Sphere {
        /// Centre (default origin).
        center: Vec3,
        /// Radius (default 1).
        radius: f32,
    },
    /// `cylinder`: an open tube (no caps) of radius `radius` about the segment from `p0` to
    /// `p1` (applied before `to_world`), normals pointing outwards. `to_world` may rotate,
    /// translate, scale uniformly, and scale along the axis; nothing else.
    Cylinder {
        /// Start of the axis (default origin).
        p0: Vec3,
        /// End of the axis (default (0, 0, 1)).
        p1: Vec3,
        /// Radius (default 1).
        radius: f32,
    },
    /// `obj`: a triangle mesh read from a Wavefront OBJ file.
    Obj {
        /// The file, as found on the scene's search path (its `<path>` folders, its folder,
        /// the current directory).
        filename: PathBuf,
        /// Use flat face normals even where the file has vertex normals.
        face_normals: bool,
        /// Flip texture coordinates' `v` to `1 − v` (Mitsuba's default, true).
        flip_tex_coords: bool,
    },
    /// `ply`: a triangle mesh read from a PLY file (ASCII or binary).
    Ply {
        /// The file, as found on the scene's search path (its `<path>` folders, its folder,
        /// the current directory).
        filename: PathBuf,
        /// Use flat face normals even where the file has vertex normals.
        face_normals: bool,
    },
    /// `serialized`: one mesh of a file in Mitsuba's compressed mesh format.
    Serialized {
        /// The file, as found on the scene's search path (its `<path>` folders, its folder,
        /// the current directory).
        filename: PathBuf,
        /// Which mesh of the file (Mitsuba's default 0, the first).
        shape_index: u32,
        /// Use flat face normals even where the file has vertex normals (the file's own
        /// face-normal flag asks for them too).
        face_normals: bool,
    },
    /// A triangle mesh given in code.
    Mesh {
        /// Vertex positions.
        positions: Vec<Vec3>,
        /// Per-vertex normals (empty for flat shading).
        normals: Vec<Vec3>,
        /// Triangles as vertex indices.
        indices: Vec<[u32; 3]>,
    },
    /// `instance`: the shapes of a shape group (Mitsuba's `shapegroup`), placed by this
    /// shape's `to_world` on top of each one's own. The group is shared, not copied: every
    /// instance of it holds the same [`Arc`](std::sync::Arc), and the geometry builds it
    /// once ([`ShapeGroupDesc`] has the rules).
    Instance(std::sync::Arc<Checked<ShapeGroupDesc>>),
}

/// A shape with its transform, material and optional area emitter.
#[derive(Debug, Clone, PartialEq)]
pub struct ShapeDesc {
    /// The `id` attribute, if any.
    pub id: Option<String>,
    /// The geometry in object space.
    pub kind: ShapeKind,
    /// Object-to-world transform.
    pub to_world: Mat4,
    /// Flip the normals (Mitsuba's `flip_normals`).
    pub flip_normals: bool,
    /// The material. Mitsuba's default when a shape has none is diffuse with reflectance 0.5,
    /// and black (reflectance 0) when the shape is an emitter.
    pub bsdf: BsdfDesc,
    /// The area emitter on the shape's front side, if any.
    pub emitter: Option<AreaEmitterDesc>,
    /// The area emitter's radiance as a texture (`bitmap` or `checkerboard`), looked up at
    /// the texture coordinates of each point ([`Geometry::tex_coords`]); then
    /// `emitter.radiance` holds the texture's mean, for the choice among lights.
    ///
    /// [`Geometry::tex_coords`]: crate::geometry::Geometry::tex_coords
    pub emission_texture: Option<Texture>,
}

impl ShapeDesc {
    /// A shape of the given kind with identity transform, the default material and no
    /// emitter.
    pub fn new(kind: ShapeKind) -> Self {
        Self {
            id: None,
            kind,
            to_world: Mat4::IDENTITY,
            flip_normals: false,
            bsdf: BsdfDesc::default(),
            emitter: None,
            emission_texture: None,
        }
    }
}

/// Microfacet normal distribution of a rough material.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MicrofacetKind {
    /// Beckmann (Mitsuba's default).
    #[default]
    Beckmann,
    /// GGX / Trowbridge–Reitz.
    Ggx,
}

/// The Fresnel term of a conductor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ConductorFresnel {
    /// Mitsuba's `material = "none"` (its default): a 100% reflecting mirror.
    Perfect,
    /// A complex index of refraction per RGB channel (given as `eta` and `k`, or by a
    /// named `material`, see [`named_conductor`](crate::bsdf::named_conductor)).
    Complex {
        /// Real part η.
        eta: Colour,
        /// Imaginary part k.
        k: Colour,
    },
}

/// A material (Mitsuba's BSDF plugins that the loader supports).
#[derive(Debug, Clone, PartialEq)]
pub enum BsdfDesc {
    /// `diffuse`: Lambertian, one-sided.
    Diffuse {
        /// Albedo, linear RGB (default 0.5).
        reflectance: Colour,
    },
    /// `conductor`: a smooth mirror.
    Conductor {
        /// The Fresnel term.
        fresnel: ConductorFresnel,
        /// Scale on the reflectance (default 1).
        specular_reflectance: Colour,
    },
    /// `roughconductor`: a microfacet conductor, sampled with visible normals.
    RoughConductor {
        /// The microfacet surface (distribution, roughness, sampling).
        microfacet: Microfacet,
        /// The Fresnel term.
        fresnel: ConductorFresnel,
        /// Scale on the reflectance (default 1).
        specular_reflectance: Colour,
    },
    /// `dielectric`: smooth glass that reflects and refracts.
    Dielectric {
        /// Interior index of refraction (default 1.5046, BK7).
        int_ior: Ior,
        /// Exterior index of refraction (default 1.000277, air).
        ext_ior: Ior,
        /// Scale on reflection (default 1).
        specular_reflectance: Colour,
        /// Scale on transmission (default 1).
        specular_transmittance: Colour,
    },
    /// `roughdielectric`: microfacet glass that reflects and refracts, sampled with
    /// visible normals.
    RoughDielectric {
        /// The microfacet surface (distribution, roughness, sampling).
        microfacet: Microfacet,
        /// Interior index of refraction (default 1.5046, BK7).
        int_ior: Ior,
        /// Exterior index of refraction (default 1.000277, air).
        ext_ior: Ior,
        /// Scale on reflection (default 1).
        specular_reflectance: Colour,
        /// Scale on transmission (default 1).
        specular_transmittance: Colour,
    },
    /// `thindielectric`: a pane of glass of negligible thickness (reflects, or lets light
    /// through undeflected).
    ThinDielectric {
        /// Index of refraction of the pane (default 1.5046, BK7).
        int_ior: Ior,
        /// Exterior index of refraction (default 1.000277, air).
        ext_ior: Ior,
        /// Scale on reflection (default 1).
        specular_reflectance: Colour,
        /// Scale on transmission (default 1).
        specular_transmittance: Colour,
    },
    /// `plastic`: a diffuse base under a smooth dielectric coating.
    Plastic {
        /// Index of refraction of the coating (default 1.49, polypropylene).
        int_ior: Ior,
        /// Exterior index of refraction (default 1.000277, air).
        ext_ior: Ior,
        /// Albedo of the base (default 0.5).
        diffuse_reflectance: Colour,
        /// Scale on the coating's reflection (default 1).
        specular_reflectance: Colour,
        /// Whether internal scattering tints the base's colour (default false).
        nonlinear: bool,
    },
    /// `roughplastic`: a diffuse base under a rough dielectric coating.
    RoughPlastic {
        /// The microfacet surface (distribution, roughness, sampling).
        microfacet: Microfacet,
        /// Index of refraction of the coating (default 1.49, polypropylene).
        int_ior: Ior,
        /// Exterior index of refraction (default 1.000277, air).
        ext_ior: Ior,
        /// Albedo of the base (default 0.5).
        diffuse_reflectance: Colour,
        /// Scale on the coating's reflection (default 1).
        specular_reflectance: Colour,
        /// Whether internal scattering tints the base's colour (default false).
        nonlinear: bool,
    },
    /// `principled`: the Disney BSDF (specular transmission when `spec_trans` > 0).
    Principled(PrincipledParams),
    /// `blendbsdf`: `(1 − weight) · first + weight · second`.
    Blend {
        /// Weight of the second material, in [0, 1] (required; a constant, not a texture).
        weight: f32,
        /// The first nested material.
        first: Box<BsdfDesc>,
        /// The second nested material.
        second: Box<BsdfDesc>,
    },
    /// `mask`: the nested material with opacity `opacity`; light passes the rest of the
    /// surface unchanged.
    Mask {
        /// Opacity in [0, 1] (default 0.5; a constant, not a texture).
        opacity: f32,
        /// The nested material.
        inner: Box<BsdfDesc>,
    },
    /// `twosided`: the nested BSDF on both sides of the surface.
    TwoSided(Box<BsdfDesc>),
    /// `normalmap` or `bumpmap`: the nested material in a shading frame whose normal a
    /// texture perturbs.
    Perturbed {
        /// The texture and how it perturbs the normal.
        perturbation: Perturbation,
        /// The nested material.
        inner: Box<BsdfDesc>,
    },
    /// A material (`diffuse`, a conductor, dielectric, plastic, `blendbsdf` or `mask`, never
    /// `twosided`) some of whose parameters are textures. `inner` holds, for each textured
    /// parameter, the texture's mean (Mitsuba 3 derives a plastic's sampling weights from
    /// its textures' means); at each hit the renderer replaces it with the texture's value.
    Textured {
        /// The material, with textures' means in their parameters.
        inner: Box<BsdfDesc>,
        /// The textured parameters, each at most once.
        textures: Vec<(TextureParam, Texture)>,
    },
}

impl BsdfDesc {
    /// Whether the material lets light through the surface (Mitsuba 3's `twosided` refuses
    /// such a nested material).
    pub fn transmits(&self) -> bool {
        match self {
            Self::Dielectric { .. }
            | Self::RoughDielectric { .. }
            | Self::ThinDielectric { .. }
            | Self::Mask { .. } => true,
            Self::Principled(p) => p.spec_trans > 0.0,
            Self::Blend { first, second, .. } => first.transmits() || second.transmits(),
            Self::TwoSided(inner)
            | Self::Textured { inner, .. }
            | Self::Perturbed { inner, .. } => inner.transmits(),
            Self::Diffuse { .. }
            | Self::Conductor { .. }
            | Self::RoughConductor { .. }
            | Self::Plastic { .. }
            | Self::RoughPlastic { .. } => false,
        }
    }
}

impl BsdfDesc {
    /// Whether a texture drives any parameter of this material or of those nested in it.
    pub fn is_textured(&self) -> bool {
        match self {
            Self::Textured { .. } | Self::Perturbed { .. } => true,
            Self::TwoSided(inner) | Self::Mask { inner, .. } => inner.is_textured(),
            Self::Blend { first, second, .. } => first.is_textured() || second.is_textured(),
            _ => false,
        }
    }

    /// Whether this material or one nested in it turns with the shading tangent `dp/du`
    /// (anisotropic roughness, αᵤ ≠ αᵥ or a textured `alpha_u` or `alpha_v`; a normal or
    /// bump map, whose frame is built on the tangent), so that its hits need the tangent.
    pub fn needs_tangent(&self) -> bool {
        match self {
            Self::RoughConductor { microfacet, .. }
            | Self::RoughDielectric { microfacet, .. }
            | Self::RoughPlastic { microfacet, .. } => microfacet.is_anisotropic(),
            Self::Principled(p) => p.anisotropic > 0.0,
            Self::Perturbed { .. } => true,
            Self::Textured { inner, textures } => {
                textures
                    .iter()
                    .any(|(p, _)| matches!(p, TextureParam::AlphaU | TextureParam::AlphaV))
                    || inner.needs_tangent()
            }
            Self::TwoSided(inner) | Self::Mask { inner, .. } => inner.needs_tangent(),
            Self::Blend { first, second, .. } => first.needs_tangent() || second.needs_tangent(),
            _ => false,
        }
    }

    /// Whether this material (not looking into nested ones) has the parameter `p`, which
    /// a texture may then drive.
    pub fn has_param(&self, p: TextureParam) -> bool {
        use TextureParam as P;
        matches!(
            (self, p),
            (Self::Diffuse { .. }, P::Reflectance)
                | (
                    Self::Conductor { .. } | Self::RoughConductor { .. },
                    P::SpecularReflectance
                )
                | (Self::Blend { .. }, P::Weight)
                | (Self::Mask { .. }, P::Opacity)
                | (
                    Self::Dielectric { .. }
                        | Self::RoughDielectric { .. }
                        | Self::ThinDielectric { .. },
                    P::SpecularReflectance | P::SpecularTransmittance,
                )
                | (
                    Self::Plastic { .. } | Self::RoughPlastic { .. },
                    P::DiffuseReflectance | P::SpecularReflectance,
                )
                | (Self::Principled(_), P::BaseColor)
                | (
                    Self::RoughConductor { .. } | Self::RoughDielectric { .. },
                    P::Alpha | P::AlphaU | P::AlphaV,
                )
        )
    }
}

impl Default for BsdfDesc {
    fn default() -> Self {
        Self::Diffuse {
            reflectance: Colour::known(Vec3::splat(0.5)),
        }
    }
}

/// An `area` emitter attached to a shape: constant radiance leaving the front side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AreaEmitterDesc {
    /// Emitted radiance, linear RGB.
    pub radiance: Colour,
}

/// An emitter that is not attached to a shape.
#[derive(Debug, Clone, PartialEq)]
pub enum EmitterDesc {
    /// `point`: an isotropic point light.
    Point {
        /// Position in world space.
        position: Vec3,
        /// Radiant intensity, linear RGB (W/sr).
        intensity: Colour,
    },
    /// `constant`: radiance arriving equally from every direction.
    Constant {
        /// Radiance, linear RGB.
        radiance: Colour,
    },
    /// `envmap`: an environment map read from an EXR file (latitude–longitude).
    EnvMap {
        /// The file, as found on the scene's search path (its `<path>` folders, its folder,
        /// the current directory).
        filename: PathBuf,
        /// Scale on the radiance (default 1).
        scale: f32,
        /// Map-to-world transform.
        to_world: Mat4,
    },
    /// `spot`: a point light whose intensity falls off inside a cone about its local +z
    /// axis (Mitsuba 3's `spot`).
    Spot {
        /// Peak radiant intensity, linear RGB (W/sr), along the axis.
        intensity: Colour,
        /// Half-angle in degrees beyond which nothing is emitted (default 20).
        cutoff_angle: f32,
        /// Half-angle in degrees up to which the intensity is the peak's; it falls off
        /// linearly in the angle from there to `cutoff_angle` (default ¾ of the cutoff).
        beam_width: f32,
        /// Light-to-world transform: the light sits at its origin and shines along its +z.
        to_world: Mat4,
    },
    /// `directional`: light arriving from one direction everywhere (Mitsuba 3's
    /// `directional`).
    Directional {
        /// Irradiance on a surface facing the light, linear RGB (W/m²).
        irradiance: Colour,
        /// Unit direction the light travels along, world space (default +z).
        direction: Vec3,
    },
    /// `projector`: a pinhole that projects an image (Mitsuba 3's `projector`), a light
    /// with a position and no area.
    Projector {
        /// The image: `irradiance` on the virtual image plane at distance 1 (before the
        /// direction-dependent factor that makes a constant image light a plane evenly).
        irradiance: Texture,
        /// Scale on the irradiance (default 1).
        scale: f32,
        /// Field of view in degrees across the image's width (`fov` along `fov_axis`
        /// converted as Mitsuba's `perspective` converts it).
        x_fov: f32,
        /// Light-to-world transform: the pinhole at its origin, looking along its +z, its
        /// +x toward the image's left edge (as Mitsuba's cameras).
        to_world: Mat4,
    },
    /// An emitter some of whose parameters are textures: a `spot` with a `texture`, its
    /// image spread over the cutoff cone and multiplying the intensity.
    Textured {
        /// The emitter (a [`EmitterDesc::Spot`]).
        inner: Box<EmitterDesc>,
        /// The spot's `texture`.
        texture: Texture,
    },
}

impl EmitterDesc {
    /// Mitsuba 3's default `cutoff_angle` of a `spot`, in degrees.
    pub const SPOT_CUTOFF_ANGLE: f32 = 20.0;
}

/// A thin lens in front of the perspective camera (Mitsuba 3's `thinlens` sensor): rays
/// leave a disk of radius `aperture_radius` and meet on the plane `focus_distance` in front.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThinLensDesc {
    /// Radius of the aperture disk, in world units (required by Mitsuba; no default).
    pub aperture_radius: f32,
    /// Distance of the plane in focus along the viewing axis (default 10⁴, Mitsuba's).
    pub focus_distance: f32,
}

impl ThinLensDesc {
    /// Mitsuba 3's default `focus_distance`.
    pub const FOCUS_DISTANCE: f32 = 1e4;
}
