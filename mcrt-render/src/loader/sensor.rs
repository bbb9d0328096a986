//! `<sensor type="perspective">`, `"thinlens"` or `"orthographic"` with its `<sampler>`, `<film type="hdrfilm">` and
//! `<rfilter>`.

use super::context::{Ctx, Res};
use super::props::Props;
use super::tree::Elem;
use super::{no_objects, plugin_type, unknown_plugin};
use crate::description::{
    Checked, CropWindow, FilmDesc, FilterDesc, FovAxis, Projection, SampleCount, SamplerDesc,
    SamplerKind, SensorDesc, ThinLensDesc,
};
use crate::param_defs::{film as film_defs, sampler, sensor as defs};
use crate::scene_error::SceneErrorKind;

/// Reads a `<sensor>` element.
pub(crate) fn read_sensor(ctx: &Ctx, e: &Elem) -> Res<Checked<SensorDesc>> {
    let ty = plugin_type(ctx, e)?;
    if !matches!(ty, "perspective" | "thinlens" | "orthographic") {
        return Err(unknown_plugin(ctx, e, ty));
    }
    let mut p = Props::new(ctx, e)?;
    let mut s = SensorDesc::default();
    let (diagonal, focal) = if ty == "orthographic" {
        s.projection = Projection::Orthographic;
        // Mitsuba 3's projective cameras all read `focus_distance`; this one never uses it.
        p.float(defs::IGNORED_FOCUS_DISTANCE.name)?;
        (None, None)
    } else {
        read_perspective(ctx, e, &mut p, &mut s, ty)?
    };
    s.near_clip = p.get_float(&defs::NEAR_CLIP)?;
    s.far_clip = p.get_float(&defs::FAR_CLIP)?;
    if !(s.near_clip > 0.0 && s.far_clip > s.near_clip) {
        return Err(p.invalid("near_clip", e, "must be positive and below far_clip"));
    }
    s.to_world = p.transform(defs::TO_WORLD.name)?.unwrap_or(s.to_world);
    let (mut film, mut sampler) = (None, None);
    for o in &p.objects {
        let slot_is_free = match o.tag.as_str() {
            "film" => film.replace(read_film(ctx, o)?).is_none(),
            "sampler" => sampler.replace(read_sampler(ctx, o)?).is_none(),
            _ => {
                return Err(ctx.err(
                    o,
                    SceneErrorKind::Misplaced(format!("<{}> inside a <sensor>", o.tag)),
                ))
            }
        };
        if !slot_is_free {
            return Err(ctx.err(
                o,
                SceneErrorKind::Misplaced(format!("a second <{}> in the sensor", o.tag)),
            ));
        }
    }
    s.film = film.unwrap_or_default();
    if let Some(d) = diagonal {
        s.fov = horizontal_fov(d, s.film.width as f32 / s.film.height as f32);
        s.fov_axis = FovAxis::X;
        // A focal length of 10⁻⁴⁰ mm (or a diagonal fov next to 180) leaves none.
        if !(s.fov > 0.0 && s.fov < 180.0) {
            let (param, what) = match focal.as_deref() {
                Some(t) => ("focal_length", format!("\"{t}\" is too short or too long")),
                None => ("fov", "(diagonal) is too wide".to_string()),
            };
            let msg = format!(
                "{what}: the horizontal field of view on this film must lie strictly between 0 \
                 and 180 degrees"
            );
            return Err(p.invalid(param, e, &msg));
        }
    }
    s.sampler = sampler.unwrap_or_default();
    // Its `to_world` was checked at its <transform>; the sensor's check repeats that.
    let s = Checked::new(s).map_err(|i| p.invalid(i.param, e, &i.message))?;
    p.finish()?;
    Ok(s)
}

/// The field of view (and the lens of a `thinlens`) of a perspective sensor: sets `s.fov`,
/// `s.fov_axis` and `s.lens`, and returns the diagonal field of view in radians that the
/// film's aspect turns into a horizontal one, with the `focal_length` text it came from.
fn read_perspective(
    ctx: &Ctx,
    e: &Elem,
    p: &mut Props,
    s: &mut SensorDesc,
    ty: &str,
) -> Res<(Option<f32>, Option<String>)> {
    if ty == "thinlens" {
        s.lens = Some(read_lens(ctx, e, p)?);
    } else {
        // Mitsuba 3's perspective reads `focus_distance` (a float, as every projective
        // camera does) and never uses it: accepted and ignored.
        p.float(defs::IGNORED_FOCUS_DISTANCE.name)?;
    }
    // Mitsuba 3 reads `fov` (with `fov_axis`) or `focal_length` (default 50 mm on a 36 × 24
    // mm frame: a diagonal field of view), and refuses both. A diagonal fov becomes the
    // horizontal one once the film's aspect is known.
    let mut diagonal = None;
    let focal = p.string(defs::FOCAL_LENGTH.name)?;
    if let Some(fov) = p.float(defs::FOV.name)? {
        if focal.is_some() {
            return Err(p.invalid("fov", e, "and focal_length cannot both be given"));
        }
        let fov = defs::FOV
            .check(fov)
            .map_err(|i| p.invalid(i.param, e, &i.message))?;
        s.fov = fov;
        if let Some(axis) = p.string(defs::FOV_AXIS.name)? {
            s.fov_axis = match axis.to_ascii_lowercase().as_str() {
                "x" => FovAxis::X,
                "y" => FovAxis::Y,
                "smaller" => FovAxis::Smaller,
                "larger" => FovAxis::Larger,
                "diagonal" => {
                    diagonal = Some(fov.to_radians());
                    FovAxis::X
                }
                _ => {
                    return Err(p.invalid(
                        "fov_axis",
                        e,
                        &format!("\"{axis}\" is not supported (x, y, diagonal, smaller or larger)"),
                    ))
                }
            };
        }
    } else {
        let mm = match focal.as_deref() {
            None => 50.0,
            Some(text) => match parse_focal_length(text) {
                Some(mm) => mm,
                None => {
                    return Err(p.invalid(
                        "focal_length",
                        e,
                        &format!("\"{text}\" is not a positive length in mm (such as \"35mm\")"),
                    ))
                }
            },
        };
        diagonal = Some(diagonal_fov(mm));
    }
    Ok((diagonal, focal))
}

/// Mitsuba 3's `focal_length`: `N` or `Nmm`, N > 0 millimetres.
fn parse_focal_length(text: &str) -> Option<f32> {
    let t = text.trim();
    let mm: f32 = t.strip_suffix("mm").unwrap_or(t).trim().parse().ok()?;
    (mm.is_finite() && mm > 0.0).then_some(mm)
}

/// The diagonal field of view in radians of a lens of focal length `mm` on a 36 × 24 mm
/// frame (Mitsuba 3's rule for `focal_length`).
fn diagonal_fov(mm: f32) -> f32 {
    2.0 * (36f32.hypot(24.0) / (2.0 * mm)).atan()
}

/// The horizontal field of view in degrees of a diagonal one of `diag` radians on a film
/// of aspect `a = w/h`: `tan(x/2) = tan(d/2) · a/√(1 + a²)` (as Mitsuba 3 converts it).
fn horizontal_fov(diag: f32, a: f32) -> f32 {
    2.0 * ((0.5 * diag).tan() * a / (1.0 + a * a).sqrt())
        .atan()
        .to_degrees()
}

/// The lens parameters of a `thinlens` sensor: `aperture_radius` (required, as in
/// Mitsuba 3) and `focus_distance`.
fn read_lens(ctx: &Ctx, e: &Elem, p: &mut Props) -> Res<ThinLensDesc> {
    let aperture_radius = p.get_float_opt(&defs::APERTURE_RADIUS)?.ok_or_else(|| {
        ctx.err(
            e,
            SceneErrorKind::MissingAttribute("parameter \"aperture_radius\"".into()),
        )
    })?;
    let focus_distance = p.get_float(&defs::FOCUS_DISTANCE)?;
    Ok(ThinLensDesc {
        aperture_radius,
        focus_distance,
    })
}

/// Reads a `<sampler>` element.
fn read_sampler(ctx: &Ctx, e: &Elem) -> Res<SamplerDesc> {
    let kind = match plugin_type(ctx, e)? {
        "independent" => SamplerKind::Independent,
        "stratified" => SamplerKind::Stratified,
        "ldsampler" => SamplerKind::LowDiscrepancy,
        "multijitter" => SamplerKind::MultiJitter,
        "orthogonal" => SamplerKind::Orthogonal,
        other => return Err(unknown_plugin(ctx, e, other)),
    };
    let mut p = Props::new(ctx, e)?;
    no_objects(ctx, &p)?;
    let sample_count = p.get_int(&sampler::SAMPLE_COUNT)? as u32;
    let sample_count =
        SampleCount::new(sample_count).map_err(|i| p.invalid(i.param, e, &i.message))?;
    let seed = p.get_int(&sampler::SEED)? as u64;
    let s = SamplerDesc {
        kind,
        sample_count,
        seed,
    };
    let jittered = matches!(
        kind,
        SamplerKind::Stratified | SamplerKind::MultiJitter | SamplerKind::Orthogonal
    );
    if jittered && !p.get_bool(&sampler::JITTER)? {
        return Err(ctx.err(e, SceneErrorKind::Unsupported("jitter = false".into())));
    }
    // An orthogonal array of strength t stratifies every t-dimensional projection; ours
    // stratifies each 2D dimension, which matches strength 2 (Mitsuba's default) only.
    if kind == SamplerKind::Orthogonal {
        if let Some((t, at)) = p.int(sampler::STRENGTH.name)? {
            if sampler::STRENGTH.check(t).is_err() {
                let what = format!("orthogonal sampler of strength {t} (only 2 is rendered)");
                return Err(ctx.err(at, SceneErrorKind::Unsupported(what)));
            }
        }
    }
    p.finish()?;
    Ok(s)
}

/// Reads a `<film>` element.
fn read_film(ctx: &Ctx, e: &Elem) -> Res<Checked<FilmDesc>> {
    let ty = plugin_type(ctx, e)?;
    if ty != "hdrfilm" {
        return Err(unknown_plugin(ctx, e, ty));
    }
    let mut p = Props::new(ctx, e)?;
    let mut f = FilmDesc {
        width: p.get_int(&film_defs::WIDTH)? as u32,
        height: p.get_int(&film_defs::HEIGHT)? as u32,
        ..FilmDesc::default()
    };
    // Output-format options: accepted and ignored (the renderer writes float RGB EXR).
    for d in [
        &film_defs::FILE_FORMAT,
        &film_defs::PIXEL_FORMAT,
        &film_defs::COMPONENT_FORMAT,
    ] {
        p.string(d.name)?;
    }
    for d in [&film_defs::SAMPLE_BORDER, &film_defs::COMPENSATE] {
        p.get_bool(d)?;
    }
    // Mitsuba 0.6's `banner` (a boolean): Mitsuba 3's film marks it read, of any type.
    p.raw(film_defs::BANNER.name);
    // Mitsuba's crop window: offsets default to 0, sizes to the rest of the film.
    let (ox, oy) = (
        p.get_int_opt(&film_defs::CROP_OFFSET_X)?,
        p.get_int_opt(&film_defs::CROP_OFFSET_Y)?,
    );
    let (cw, ch) = (
        p.get_int_opt(&film_defs::CROP_WIDTH)?,
        p.get_int_opt(&film_defs::CROP_HEIGHT)?,
    );
    if ox.is_some() || oy.is_some() || cw.is_some() || ch.is_some() {
        let (ox, oy) = (ox.unwrap_or(0) as u32, oy.unwrap_or(0) as u32);
        f.crop = Some(CropWindow {
            offset_x: ox,
            offset_y: oy,
            width: cw.map_or(f.width.saturating_sub(ox), |v| v as u32),
            height: ch.map_or(f.height.saturating_sub(oy), |v| v as u32),
        });
    }
    let mut filter = None;
    for o in &p.objects {
        if o.tag != "rfilter" {
            return Err(ctx.err(
                o,
                SceneErrorKind::Misplaced(format!("<{}> inside a <film>", o.tag)),
            ));
        }
        if filter.replace(read_filter(ctx, o)?).is_some() {
            return Err(ctx.err(o, SceneErrorKind::Misplaced("a second <rfilter>".into())));
        }
    }
    f.filter = filter.unwrap_or_default();
    let f = Checked::new(f).map_err(|i| p.invalid(i.param, e, &i.message))?;
    p.finish()?;
    Ok(f)
}

/// Reads an `<rfilter>` element.
fn read_filter(ctx: &Ctx, e: &Elem) -> Res<FilterDesc> {
    let ty = plugin_type(ctx, e)?;
    let mut p = Props::new(ctx, e)?;
    no_objects(ctx, &p)?;
    let f = match ty {
        "box" => FilterDesc::Box,
        "tent" => FilterDesc::Tent {
            radius: p.get_float(&film_defs::TENT_RADIUS)?,
        },
        "gaussian" => FilterDesc::Gaussian {
            stddev: p.get_float(&film_defs::STDDEV)?,
        },
        other => return Err(unknown_plugin(ctx, e, other)),
    };
    p.finish()?;
    Ok(f)
}
