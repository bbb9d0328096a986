//! The Mitsuba 3 XML scene loader: turns a scene file into a [`SceneDescription`].
//!
//! The supported subset, its defaults and its errors are listed in `docs/scene-format.md`.
//! In short: `<scene version="3.x.y">` with `<default>` parameters and `$name`
//! substitution (defines passed to [`load_scene`] beat defaults), `ref`/`id`, the value
//! tags `integer`, `float`, `boolean`, `string`, `rgb`, `point`, `vector`, `transform`
//! (`lookat`, `matrix`, `translate`, `rotate`, `scale`), and the plugins
//! `path`/`direct`, `perspective`/`thinlens`/`orthographic`, `independent`/`stratified`/`ldsampler`/`multijitter`/`orthogonal`, `hdrfilm` with
//! `box`/`gaussian`/`tent` and `crop_*`, `rectangle`/`cube`/`disk`/`sphere`/`obj`/`ply`/`serialized`,
//! `shapegroup`/`instance`,
//! `diffuse`/`conductor`/`roughconductor`/`dielectric`/`twosided` and the other BSDFs of
//! `docs/scene-format.md`, `area`/`point`/`spot`/`directional`/`constant`/`envmap`, and the
//! textures `bitmap`/`checkerboard` on BSDF colours, blend weights and opacities. Semantics
//! and defaults follow Mitsuba 3.
//!
//! Anything else — an unknown element, attribute, plugin or parameter, a value of the
//! wrong type, a malformed number, an undefined `$name` or `ref`, a missing file — is a
//! [`SceneError`] naming the file, the line and column, and the element. The loader never
//! panics on any input.
//!
//! ```
//! use mcrt_render::loader::parse_scene;
//! use mcrt_render::description::{IntegratorDesc, PathParams};
//! let xml = r#"<scene version="3.0.0">
//!     <default name="depth" value="3"/>
//!     <integrator type="path"><integer name="max_depth" value="$depth"/></integrator>
//! </scene>"#;
//! let d = parse_scene(xml, None, &[("depth".into(), "2".into())]).unwrap();
//! let path = PathParams { max_depth: 2, ..PathParams::DEFAULT };
//! assert_eq!(d.integrator, IntegratorDesc::Path(path));
//! ```

mod bsdf;
mod bsdf_maps;
mod cie_tables;
mod context;
mod elem;
mod emitter;
mod include;
mod instance;
mod integrator;
mod params;
mod position;
mod principled;
mod props;
mod search_path;
mod sensor;
mod shape;
mod spectrum;
mod texture;
mod transform;
mod tree;
mod upgrade;
mod values;
mod volume;

use crate::io::read_capped;
pub use crate::io::{MAX_OBJ_BYTES, MAX_SCENE_BYTES};
pub use crate::scene_error::{SceneError, SceneErrorKind};
pub use crate::scene_warning::SceneWarning;
pub use crate::transform::look_at;

use crate::description::{Checked, EmitterDesc, SceneDescription};
use context::{Ctx, Res};
use props::Props;
use std::path::Path;
use tree::Elem;

/// Reads and parses the scene file at `path`. `defines` are `-D name=value` pairs; they
/// take precedence over the file's `<default>` values. Relative file names inside the
/// scene (meshes, textures, maps) are resolved on the file search path: the scene's
/// `<path>` folders, its folder, the current directory (`docs/scene-format.md`).
///
/// Only a regular file of at most [`MAX_SCENE_BYTES`] is read (a FIFO or a device is
/// refused before it is opened). The loader's warnings are dropped; see
/// [`load_scene_with_warnings`].
pub fn load_scene(
    path: &Path,
    defines: &[(String, String)],
) -> Result<SceneDescription, SceneError> {
    load_scene_with_warnings(path, defines).map(|(d, _)| d)
}

/// [`load_scene`], with the loader's warnings (what Mitsuba 3 accepts but a user likely
/// did not mean, such as a `<rotate>` axis that is not unit length), in file order.
pub fn load_scene_with_warnings(
    path: &Path,
    defines: &[(String, String)],
) -> Result<(SceneDescription, Vec<SceneWarning>), SceneError> {
    let bytes = read_capped(path, MAX_SCENE_BYTES).map_err(|e| SceneError::io(path, &e))?;
    let xml = String::from_utf8(bytes).map_err(|_| {
        let e = std::io::Error::other("not UTF-8 text");
        SceneError::io(path, &e)
    })?;
    parse_scene_with_warnings(&xml, Some(path), defines)
}

/// Parses scene XML held in memory. `source` is the file it came from, used in messages
/// and to resolve relative file names (without it, they are resolved against the current
/// directory). `defines` take precedence over `<default>` values. The loader's warnings
/// are dropped; see [`parse_scene_with_warnings`].
pub fn parse_scene(
    xml: &str,
    source: Option<&Path>,
    defines: &[(String, String)],
) -> Result<SceneDescription, SceneError> {
    parse_scene_with_warnings(xml, source, defines).map(|(d, _)| d)
}

/// [`parse_scene`], with the loader's warnings in file order.
///
/// ```
/// use mcrt_render::loader::parse_scene_with_warnings;
/// let xml = "<scene version=\"3.0.0\">\n<shape type=\"cube\"><transform name=\"to_world\">\n\
///            <rotate x=\"0\" y=\"1\" z=\"1\" angle=\"30\"/></transform></shape></scene>";
/// let (_, warnings) = parse_scene_with_warnings(xml, None, &[]).unwrap();
/// assert_eq!(warnings[0].line, Some(3));
/// assert!(warnings[0].to_string().contains("not unit length"));
/// ```
pub fn parse_scene_with_warnings(
    xml: &str,
    source: Option<&Path>,
    defines: &[(String, String)],
) -> Result<(SceneDescription, Vec<SceneWarning>), SceneError> {
    let (root, search) = tree::read_tree(xml, source, defines)?;
    let ctx = Ctx::new(source, &root, search)?;
    transform::check_attrs(&ctx, &root, &["version"], &["version"])?;
    let mut desc = SceneDescription {
        source: source.map(Path::to_path_buf),
        ..SceneDescription::default()
    };
    let (mut integrator, mut sensor) = (None::<&Elem>, None::<&Elem>);
    let mut environment = None::<&Elem>;
    let mut groups = instance::Groups::default();
    for c in &root.children {
        match c.tag.as_str() {
            "integrator" => {
                once(&ctx, &mut integrator, c)?;
                let read = integrator::read_integrator(&ctx, c)?;
                // Each parameter was checked as it was read (`param_defs::integrator`);
                // the integrator's check repeats that, once.
                desc.integrator = Checked::new(read.integrator)
                    .map_err(|i| ctx.err(c, SceneErrorKind::InvalidValue(i.to_string())))?;
                desc.moment = read.moment;
            }
            "sensor" => {
                once(&ctx, &mut sensor, c)?;
                desc.sensor = sensor::read_sensor(&ctx, c)?;
            }
            "shape" => {
                if let Some(s) = instance::read_top_shape(&ctx, c, &mut groups)? {
                    desc.shapes.push(s);
                    desc.origins.shapes.push(Some(ctx.origin(c)));
                }
            }
            // An area emitter with an id is declared for a shape's `ref` (as in Mitsuba 3).
            "emitter" if c.attr("type") == Some("area") && c.attr("id").is_some() => {
                declaration(&ctx, || emitter::read_area(&ctx, c).map(|_| ()))?;
            }
            "emitter" => {
                let em = emitter::read_emitter(&ctx, c)?;
                if matches!(
                    *em,
                    EmitterDesc::Constant { .. } | EmitterDesc::EnvMap { .. }
                ) {
                    second_environment(&ctx, &mut environment, c)?;
                }
                desc.emitters.push(em);
                desc.origins.emitters.push(Some(ctx.origin(c)));
            }
            // Declared for `ref`; built here too so that its errors surface even if unused
            // (a volume texture is accepted here: it counts only where a shape uses it).
            "bsdf" => {
                declaration(&ctx, || bsdf::read_bsdf(&ctx, c).map(|_| ()))?;
            }
            "texture" => {
                declaration(&ctx, || texture::read_texture(&ctx, c).map(|_| ()))?;
            }
            "volume" => volume::read_volume(&ctx, c)?,
            _ => return Err(top_level_error(&ctx, c)),
        }
    }
    orthographic_integrator(&ctx, &desc, sensor, integrator)?;
    // The total work: located at the sensor, or at the integrator if only it is given.
    let film = &desc.sensor.film;
    let window = film.window();
    let pixels = window.width as u64 * window.height as u64;
    let spp = desc
        .integrator
        .samples_per_pixel(desc.sensor.sampler.sample_count);
    if let Err(i) = crate::validate::work(pixels, spp, &desc.integrator) {
        let at = sensor.or(integrator).unwrap_or(&root);
        return Err(ctx.err(at, SceneErrorKind::InvalidValue(i.to_string())));
    }
    Ok((desc, ctx.take_warnings()))
}

/// An orthographic sensor is a delta in direction: no light path can be connected to it,
/// and Mitsuba 3's `orthographic` has no `sample_direction` (its `ptracer` stops with
/// "not implemented"). The integrators that connect light paths to the camera are refused
/// with it, at the sensor.
fn orthographic_integrator(
    ctx: &Ctx,
    desc: &SceneDescription,
    sensor: Option<&Elem>,
    integrator: Option<&Elem>,
) -> Res<()> {
    use crate::description::{IntegratorKind, Projection};
    let (Some(sensor), Some(integrator)) = (sensor, integrator) else {
        return Ok(());
    };
    let kind = desc.integrator.kind();
    if desc.sensor.projection != Projection::Orthographic
        || !matches!(
            kind,
            IntegratorKind::Bdpt | IntegratorKind::Mlt | IntegratorKind::Ptracer
        )
    {
        return Ok(());
    }
    Err(ctx.err(
        sensor,
        SceneErrorKind::Unsupported(format!(
            "sensor \"orthographic\" with integrator \"{}\" (line {}): it connects light \
             paths to the camera, and an orthographic camera, a delta in direction, cannot be \
             reached by them (Mitsuba 3's orthographic has no sample_direction either); use \
             path, direct or guided",
            kind.name(),
            integrator.line
        )),
    ))
}

/// Runs `read` on a top-level declaration (see [`Ctx::declaration`]).
fn declaration(ctx: &Ctx, read: impl FnOnce() -> Res<()>) -> Res<()> {
    ctx.declaration.set(true);
    let r = read();
    ctx.declaration.set(false);
    r
}

/// Records the only allowed element of a kind (integrator, sensor).
fn once<'a>(ctx: &Ctx, slot: &mut Option<&'a Elem>, e: &'a Elem) -> Res<()> {
    if let Some(prev) = slot.replace(e) {
        return Err(ctx.err(
            e,
            SceneErrorKind::Unsupported(format!(
                "a second <{}> (the first is on line {})",
                e.tag, prev.line
            )),
        ));
    }
    Ok(())
}

/// Records the environment emitter (`constant` or `envmap`): a scene has one at most.
fn second_environment<'a>(ctx: &Ctx, slot: &mut Option<&'a Elem>, e: &'a Elem) -> Res<()> {
    if let Some(prev) = slot.replace(e) {
        return Err(ctx.err(
            e,
            SceneErrorKind::Unsupported(format!(
                "more than one environment emitter (constant or envmap; the first is on line \
                 {})",
                prev.line
            )),
        ));
    }
    Ok(())
}

/// The error for an element that may not appear directly inside `<scene>`.
fn top_level_error(ctx: &Ctx, c: &Elem) -> SceneError {
    let tag = c.tag.as_str();
    match tag {
        "sampler" | "film" | "rfilter" | "ref" => ctx.err(
            c,
            SceneErrorKind::Misplaced(format!("<{tag}> directly inside <scene>")),
        ),
        _ if props::OBJECT_TAGS.contains(&tag) => ctx.err(
            c,
            SceneErrorKind::Misplaced(format!("<{tag}> directly inside <scene>")),
        ),
        // Property tags, unsupported and unknown elements: the property reader names them.
        _ => match props::read_value(ctx, c) {
            Err(e) => e,
            Ok(_) => ctx.err(
                c,
                SceneErrorKind::Misplaced(format!("parameter <{tag}> directly inside <scene>")),
            ),
        },
    }
}

/// The `type` attribute of a plugin element; only `type`, `id` and `name` are allowed.
pub(crate) fn plugin_type<'e>(ctx: &Ctx, e: &'e Elem) -> Res<&'e str> {
    transform::check_attrs(ctx, e, &["type", "id", "name"], &["type"])?;
    for key in ["id", "name"] {
        if let Some(v) = e.attr(key) {
            if v.starts_with('_') {
                return Err(ctx.err(
                    e,
                    SceneErrorKind::InvalidValue(format!(
                        "{key} \"{v}\": leading underscores are reserved"
                    )),
                ));
            }
        }
    }
    Ok(e.attr("type").unwrap_or(""))
}

/// The error for an unsupported plugin type in `e`'s category.
pub(crate) fn unknown_plugin(ctx: &Ctx, e: &Elem, ty: &str) -> SceneError {
    ctx.err(
        e,
        SceneErrorKind::UnknownPlugin {
            category: e.tag.clone(),
            plugin_type: ty.to_string(),
        },
    )
}

/// Errors if the plugin has nested objects.
pub(crate) fn no_objects(ctx: &Ctx, p: &Props) -> Res<()> {
    match p.objects.first() {
        None => Ok(()),
        Some(o) if texture::texture_elem(ctx, o).is_some() => Err(texture::not_here(ctx, o)),
        Some(o) => Err(ctx.err(
            o,
            SceneErrorKind::Misplaced(format!("<{}> cannot be nested here", o.tag)),
        )),
    }
}
