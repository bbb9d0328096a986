//! A part of a render, for distributed rendering: an OpenEXR file that holds what an exact
//! merge ([`merge_parts`](super::merge_parts)) needs; [`write_part`] describes the format.
//! `render --samples START..END` and `--crop x0,y0,x1,y1` write one; the `merge` example
//! reads them back.

use super::window::{Crop, SampleRange};
use super::write::write_atomically;
use super::{Film, PixelAccum};
use crate::io::{err, ImageError};
use std::path::{Path, PathBuf};

/// The version written as `mcrt.part`.
const FORMAT: &str = "1";

/// Which render a part belongs to, and which share of it it holds.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PartInfo {
    /// The scene's name (the scene file's stem), for messages.
    pub scene: String,
    /// Hash of everything that shapes the image except the sample range and the crop
    /// ([`Renderer::identity`](crate::render::Renderer::identity)).
    pub identity: u64,
    /// The sampler seed.
    pub seed: u64,
    /// Samples per pixel of the whole render.
    pub spp: u32,
    /// Width of the whole image.
    pub width: u32,
    /// Height of the whole image.
    pub height: u32,
    /// The pixel samples this part holds.
    pub samples: SampleRange,
    /// The pixels this part holds.
    pub crop: Crop,
}

/// A part read back from its file.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// The file.
    pub path: PathBuf,
    /// Its header.
    pub info: PartInfo,
    /// The pixels stored (the EXR data window): the crop, or the whole image with splats.
    pub window: Crop,
    /// For every pixel of `window`, row-major: the sums and the sample count.
    pub pixels: Vec<PixelAccum>,
    /// For every pixel of `window`, row-major: the splat sums, if the part has any.
    pub splats: Option<Vec<[f64; 3]>>,
    /// The `moment` integrator's sums, if the render has its channels.
    pub moment: Option<PartMoment>,
}

/// A part's sums for Mitsuba 3's `moment` channels: the second moment is a mean of squares,
/// so parts keep the sums of the squared XYZ samples, which add, and `merge` divides by the
/// merged sample count (the mean channels come from the merged image itself).
#[derive(Debug, Clone, PartialEq)]
pub struct PartMoment {
    /// The nested integrator's name, the prefix of the channel names (`mcrt.moment`).
    pub name: String,
    /// For every pixel of the part's window, row-major: the sum of the squared XYZ samples.
    pub sum_sq_xyz: Vec<[f64; 3]>,
}

/// Channel names of an XYZ triple.
const XYZ: [&str; 3] = ["X", "Y", "Z"];

/// Channel names of an RGB triple.
const RGB: [&str; 3] = ["R", "G", "B"];

/// `x` as its nearest f32 and the rounded remainder.
fn split(x: f64) -> (f32, f32) {
    let hi = x as f32;
    (hi, (x - hi as f64) as f32)
}

/// An attribute's text; characters outside Latin-1 (which EXR text cannot hold) become `?`.
fn text(s: &str) -> exr::prelude::Text {
    let latin1: String = s
        .chars()
        .map(|c| if (c as u32) < 256 { c } else { '?' })
        .collect();
    exr::prelude::Text::new_or_none(latin1).unwrap_or_default()
}

/// Writes `film`'s share `info` of a render as a part, atomically.
///
/// **Header.** The display window is the whole image. The data window is the crop, or the
/// whole image when the film has splats (light tracing lands anywhere on the film). String
/// attributes: `mcrt.part` (format version, `1`), `mcrt.scene` (the scene's name, for
/// messages), `mcrt.identity` (16 hex digits: a hash of everything that shapes the image
/// except the sample range and the crop, see
/// [`Renderer::identity`](crate::render::Renderer::identity)), `mcrt.seed`,
/// `mcrt.spp`, `mcrt.samples` (`START..END`) and `mcrt.crop` (`x0,y0,x1,y1`).
///
/// **Channels**, 32-bit floats unless said otherwise:
/// - `R`, `G`, `B`: the part's own estimate, so that a viewer shows something sensible;
/// - `sum.R` … and `sumsq.R` …: per pixel, the sums of the sample values and of their
///   squares;
/// - `weight` (32-bit unsigned): the sum of the samples' filter weights. Under filter
///   importance sampling (see [`film`](super)) a sample weighs 1 in the pixel it was drawn
///   for and nothing elsewhere, so this is the pixel's sample count;
/// - `splat.R` … (if the film has splats): per pixel, the sum of the contributions splatted
///   onto it, before the splat scale. A Gaussian filter spreads each over several pixels;
/// - `m2sum.X`, `m2sum.Y`, `m2sum.Z` (if the render has Mitsuba 3's `moment` channels, and
///   then the string attribute `mcrt.moment`, the nested integrator's name): per pixel, the
///   sums of the squared CIE XYZ samples.
///
/// The renderer keeps every sum in f64; each is stored as two floats, its nearest f32
/// (`sum.R`) and the rounded remainder (`sum.lo.R`), which carry 48 of its 53 significant
/// bits, so a merged pixel differs from a single render's only by the final rounding to f32.
pub fn write_part(path: &Path, film: &Film, info: &PartInfo) -> Result<(), ImageError> {
    use exr::prelude::traits::WritableImage;
    use exr::prelude::{
        AnyChannel, AnyChannels, AttributeValue, Encoding, FlatSamples, Image, IntegerBounds,
        Layer, LayerAttributes, LineOrder, SmallVec, Vec2,
    };
    let (w, h) = (film.width(), film.height());
    if film.has_moment_more() {
        return Err(err(
            path,
            "a moment integrator with several nested integrators cannot be written as a part \
             yet (the part format keeps one nested integrator's sums)"
                .to_string(),
        ));
    }
    if (w, h) != (info.width, info.height) {
        return Err(err(
            path,
            format!(
                "a {w}×{h} film for a part of a {}×{} image",
                info.width, info.height
            ),
        ));
    }
    let window = if film.has_splats() {
        Crop::full(w, h)
    } else {
        info.crop
    };
    let index: Vec<usize> = (window.y0..window.y1)
        .flat_map(|y| (window.x0..window.x1).map(move |x| (y * w + x) as usize))
        .collect();
    let mean = film.mean();
    let mut channels = Vec::new();
    let f32s = |name: &str, v: Vec<f32>| AnyChannel::new(text(name), FlatSamples::F32(v));
    for (c, n) in RGB.iter().enumerate() {
        channels.push(f32s(n, index.iter().map(|&i| mean[i][c]).collect()));
    }
    let mut sums = |name: &str, get: &dyn Fn(usize) -> [f64; 3], axes: [&str; 3]| {
        for (c, n) in axes.iter().enumerate() {
            let (hi, lo): (Vec<f32>, Vec<f32>) = index.iter().map(|&i| split(get(i)[c])).unzip();
            channels.push(f32s(&format!("{name}.{n}"), hi));
            channels.push(f32s(&format!("{name}.lo.{n}"), lo));
        }
    };
    sums("sum", &|i| film.pixel(i).sum, RGB);
    sums("sumsq", &|i| film.pixel(i).sum_sq, RGB);
    if film.has_splats() {
        sums("splat", &|i| film.splat_sum(i), RGB);
    }
    if let Some(m) = &film.moment {
        sums("m2sum", &|i| m.sum_sq_xyz[i], XYZ);
    }
    let weight = index.iter().map(|&i| film.pixel(i).count).collect();
    channels.push(AnyChannel::new(text("weight"), FlatSamples::U32(weight)));
    let mut attributes = LayerAttributes {
        layer_position: Vec2(window.x0 as i32, window.y0 as i32),
        ..LayerAttributes::default()
    };
    if let Some(m) = &film.moment {
        attributes
            .other
            .insert(text("mcrt.moment"), AttributeValue::Text(text(&m.name)));
    }
    for (k, v) in [
        ("mcrt.part", FORMAT.to_string()),
        ("mcrt.scene", info.scene.clone()),
        ("mcrt.identity", format!("{:016x}", info.identity)),
        ("mcrt.seed", info.seed.to_string()),
        ("mcrt.spp", info.spp.to_string()),
        ("mcrt.samples", info.samples.to_string()),
        ("mcrt.crop", info.crop.to_string()),
    ] {
        attributes
            .other
            .insert(text(k), AttributeValue::Text(text(&v)));
    }
    let encoding = Encoding {
        line_order: LineOrder::Increasing,
        ..Encoding::FAST_LOSSLESS
    };
    let size = (window.width() as usize, window.height() as usize);
    let channels = AnyChannels::sort(SmallVec::from_vec(channels));
    let mut image = Image::from_layer(Layer::new(size, attributes, encoding, channels));
    image.attributes.display_window = IntegerBounds::new((0, 0), (w as usize, h as usize));
    write_atomically(path, |f| {
        image.write().to_unbuffered(&*f).map_err(|e| e.to_string())
    })
}

/// Checks a part's windows against the memory budget from its headers alone, before its
/// pixels are read: merging needs a film of the display window (and a sample count per
/// pixel), reading it its data window's channels and accumulators.
fn check_budget(path: &Path) -> Result<(), ImageError> {
    let meta = exr::meta::MetaData::read_from_file(path, false).map_err(|e| err(path, e))?;
    for h in meta.headers.iter() {
        let d = h.shared_attributes.display_window.size;
        let (w, hh) = (d.0 as u64, d.1 as u64);
        let merge = super::Film::bytes_for(w, hh).saturating_add(crate::memory::bytes(w * hh, 4));
        crate::memory::check(
            &format!("merging an image of {w} × {hh} pixels (the part's display window)"),
            merge,
        )
        .map_err(|m| err(path, m))?;
        let l = h.layer_size;
        let data = crate::memory::bytes(l.0 as u64 * l.1 as u64, 13 * 4 + 2 * 56);
        crate::memory::check(
            &format!("reading a data window of {} × {} pixels", l.0, l.1),
            data,
        )
        .map_err(|m| err(path, m))?;
    }
    Ok(())
}

/// Reads a part written by [`write_part`], checking that its header is complete and
/// consistent (the sample range within the samples per pixel, the crop within the image
/// and within the data window) and that every channel is there. Only a regular file is
/// opened (a FIFO, device or folder is refused first).
pub fn read_part(path: &Path) -> Result<Part, ImageError> {
    use exr::prelude::traits::{read, ReadChannels, ReadLayers};
    use exr::prelude::{AttributeValue, FlatSamples, Vec2};
    // Only a regular file: opening a FIFO would wait for a writer forever (issue 26). It is
    // checked before the header is read for the memory budget.
    let file = crate::io::open_regular(path).map_err(|e| err(path, e))?;
    check_budget(path)?;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::BufReader::new(file))
        .map_err(|e| err(path, e))?;
    let layer = &image.layer_data;
    let get = |k: &str| {
        let key = text(k);
        match layer
            .attributes
            .other
            .get(&key)
            .or_else(|| image.attributes.other.get(&key))
        {
            Some(AttributeValue::Text(t)) => Ok(t.to_string()),
            _ => Err(err(
                path,
                format!(
                    "not a part of a render: no text attribute \"{k}\" (parts are written by \
                     render --samples or --crop)"
                ),
            )),
        }
    };
    let bad = |k: &str, v: &str| err(path, format!("attribute \"{k}\" = \"{v}\" is malformed"));
    let version = get("mcrt.part")?;
    if version != FORMAT {
        return Err(err(
            path,
            format!("part format {version}; this merge reads format {FORMAT}"),
        ));
    }
    let num = |k: &str| -> Result<u64, ImageError> {
        let v = get(k)?;
        v.parse().map_err(|_| bad(k, &v))
    };
    let identity = get("mcrt.identity")?;
    let samples = get("mcrt.samples")?;
    let crop = get("mcrt.crop")?;
    let display = image.attributes.display_window;
    let info = PartInfo {
        scene: get("mcrt.scene")?,
        identity: u64::from_str_radix(&identity, 16)
            .map_err(|_| bad("mcrt.identity", &identity))?,
        seed: num("mcrt.seed")?,
        spp: u32::try_from(num("mcrt.spp")?).map_err(|_| bad("mcrt.spp", "too large"))?,
        width: display.size.0 as u32,
        height: display.size.1 as u32,
        samples: samples.parse().map_err(|_| bad("mcrt.samples", &samples))?,
        crop: crop.parse().map_err(|_| bad("mcrt.crop", &crop))?,
    };
    let pos = layer.attributes.layer_position;
    let window = Crop {
        x0: pos.0.max(0) as u32,
        y0: pos.1.max(0) as u32,
        x1: (pos.0.max(0) as usize + layer.size.0) as u32,
        y1: (pos.1.max(0) as usize + layer.size.1) as u32,
    };
    let consistent = display.position == Vec2(0, 0)
        && pos.0 >= 0
        && pos.1 >= 0
        && window.check(info.width, info.height).is_ok()
        && window.intersection(&info.crop) == Some(info.crop)
        && info.crop.check(info.width, info.height).is_ok()
        && info.samples.check(info.spp).is_ok();
    if !consistent {
        return Err(err(
            path,
            format!(
                "inconsistent part: samples {} of {} spp, crop {} and data window {} of a {}×{} \
                 image",
                info.samples, info.spp, info.crop, window, info.width, info.height
            ),
        ));
    }
    let n = window.area() as usize;
    let channel = |name: &str| {
        layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name.to_string() == name)
            .map(|c| &c.sample_data)
            .ok_or_else(|| err(path, format!("part without channel \"{name}\"")))
    };
    let floats = |name: &str| match channel(name)? {
        FlatSamples::F32(v) if v.len() == n => Ok(v),
        _ => Err(err(
            path,
            format!("channel \"{name}\": expected {n} 32-bit floats"),
        )),
    };
    let sums = |name: &str, axes: [&str; 3]| -> Result<Vec<[f64; 3]>, ImageError> {
        let mut out = vec![[0.0; 3]; n];
        for (c, ch) in axes.iter().enumerate() {
            let hi = floats(&format!("{name}.{ch}"))?;
            let lo = floats(&format!("{name}.lo.{ch}"))?;
            for (o, (h, l)) in out.iter_mut().zip(hi.iter().zip(lo)) {
                o[c] = *h as f64 + *l as f64;
            }
        }
        Ok(out)
    };
    let weight = match channel("weight")? {
        FlatSamples::U32(v) if v.len() == n => v,
        _ => {
            return Err(err(
                path,
                format!("channel \"weight\": expected {n} 32-bit unsigned integers"),
            ))
        }
    };
    let (sum, sum_sq) = (sums("sum", RGB)?, sums("sumsq", RGB)?);
    let pixels = (0..n)
        .map(|i| PixelAccum {
            sum: sum[i],
            sum_sq: sum_sq[i],
            count: weight[i],
        })
        .collect();
    let splats = match channel("splat.R") {
        Ok(_) => Some(sums("splat", RGB)?),
        Err(_) => None,
    };
    let moment = match get("mcrt.moment") {
        Ok(name) => Some(PartMoment {
            name,
            sum_sq_xyz: sums("m2sum", XYZ)?,
        }),
        Err(_) => None,
    };
    Ok(Part {
        path: path.to_path_buf(),
        info,
        window,
        pixels,
        splats,
        moment,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn a_part_round_trips_with_its_sums_to_48_bits() {
        let dir = std::env::temp_dir().join(format!("mcrt-part-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let mut film = Film::new(5, 4);
        let mut a = PixelAccum::default();
        for v in [0.1f32, 1.0 / 3.0, 1e-7, 12345.678] {
            a.add(Vec3::new(v, 2.0 * v, 0.5));
        }
        film.merge(7, &a).expect("inside");
        film.add_splat_sum(19, [1.0 / 3.0, 0.0, 1e-9]);
        let info = PartInfo {
            scene: "box ü→".into(),
            identity: 0xfedc_ba98_7654_3210,
            seed: u64::MAX,
            spp: 8,
            width: 5,
            height: 4,
            samples: SampleRange { start: 4, end: 8 },
            crop: "1,1,3,2".parse().expect("crop"),
        };
        let p = dir.join("part.exr");
        write_part(&p, &film, &info).expect("written");
        let back = read_part(&p).expect("read");
        assert_eq!(back.info.scene, "box ü?");
        assert_eq!(back.info.identity, info.identity);
        assert_eq!(
            (back.info.seed, back.info.samples),
            (info.seed, info.samples)
        );
        // With splats the data window is the whole image.
        assert_eq!(back.window, Crop::full(5, 4));
        let got = back.pixels[7];
        assert_eq!(got.count, 4);
        for c in 0..3 {
            let rel = (got.sum[c] - a.sum[c]).abs() / a.sum[c];
            assert!(rel.is_finite() && rel < 2f64.powi(-47), "{rel}");
        }
        let s = back.splats.expect("splats")[19];
        assert!(s[0].is_finite() && (s[0] - 1.0 / 3.0).abs() < 1e-15);
        // A file that is no part is refused with its name.
        let plain = dir.join("plain.exr");
        super::super::write_exr(&plain, 2, 2, &[Vec3::ONE; 4]).expect("exr");
        let e = read_part(&plain).unwrap_err().to_string();
        assert!(e.contains("plain.exr") && e.contains("mcrt.part"), "{e}");
        std::fs::remove_dir_all(&dir).ok();
    }
}
