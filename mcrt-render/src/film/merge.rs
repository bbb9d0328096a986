//! Merging the parts of a render ([`super::Part`]) into the film a single render would have
//! given: the per-pixel sums and sample counts are added in f64, the splat sums likewise, and
//! the splat scale is the single render's. Parts from different renders, parts that hold the
//! same samples of a pixel twice, parts whose sums are not finite, and sets of parts that
//! leave samples out are refused.

use super::part::Part;
use super::window::{Crop, SampleRange};
use super::Film;
use std::fmt;
use std::path::PathBuf;

/// The parts cannot be merged into one render.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum MergeError {
    /// No part was given.
    NoParts,
    /// A part comes from another render than the first part.
    Mismatch {
        /// The first part.
        first: PathBuf,
        /// The part that differs.
        other: PathBuf,
        /// What differs: image size, samples per pixel, seed or scene.
        what: &'static str,
        /// The first part's value.
        expected: String,
        /// The other part's value.
        found: String,
    },
    /// A pixel of a part does not hold the samples the part's header names (an interrupted
    /// render, or an altered file).
    Incomplete {
        /// The part.
        path: PathBuf,
        /// The pixel.
        pixel: (u32, u32),
        /// Samples it holds.
        weight: u32,
        /// Samples the header names.
        expected: u32,
    },
    /// Two parts hold the same samples of some pixels.
    Overlap {
        /// One part.
        a: PathBuf,
        /// The other.
        b: PathBuf,
        /// The samples both hold.
        samples: SampleRange,
        /// The pixels both hold.
        pixels: Crop,
    },
    /// A part's sums hold NaN or infinite values (a damaged or altered file): merged, they
    /// would make as many pixels of the image non-finite without a word.
    NonFinite {
        /// The part.
        path: PathBuf,
        /// The first pixel with such a value.
        pixel: (u32, u32),
        /// How many values (sums, sums of squares and splat sums, per channel) are not
        /// finite.
        values: u64,
    },
    /// Some pixels lack samples.
    Gap {
        /// The first such pixel, row by row.
        pixel: (u32, u32),
        /// The first range of samples it lacks.
        missing: SampleRange,
        /// How many pixels lack some samples.
        pixels: u64,
    },
}

impl fmt::Display for MergeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoParts => f.write_str("no part to merge"),
            Self::Mismatch {
                first,
                other,
                what,
                expected,
                found,
            } => write!(
                f,
                "{} is not a part of the same render as {}: its {what} is {found}, not \
                 {expected}",
                other.display(),
                first.display()
            ),
            Self::Incomplete {
                path,
                pixel: (x, y),
                weight,
                expected,
            } => write!(
                f,
                "{}: pixel ({x}, {y}) holds {weight} samples where the part's header names \
                 {expected} (an interrupted render?)",
                path.display()
            ),
            Self::Overlap {
                a,
                b,
                samples,
                pixels,
            } => write!(
                f,
                "{} and {} both hold samples {samples} of the pixels {pixels} (x0,y0,x1,y1)",
                a.display(),
                b.display()
            ),
            Self::NonFinite {
                path,
                pixel: (x, y),
                values,
            } => write!(
                f,
                "{}: {values} values of its sums are NaN or infinite, the first at pixel ({x}, \
                 {y}) (a damaged part?)",
                path.display()
            ),
            Self::Gap {
                pixel: (x, y),
                missing,
                pixels,
            } => write!(
                f,
                "the parts do not cover the render: pixel ({x}, {y}) lacks samples {missing}, \
                 and {pixels} pixels in all lack some"
            ),
        }
    }
}

impl std::error::Error for MergeError {}

/// Merges parts of one render into the film a single render of the whole would have given,
/// equal up to floating-point rounding: every pixel's sums and sample count are those of the
/// single render, added in f64 in another order. The splat sums are added likewise and
/// scaled as the single render scales them, and so are the sums of the `moment` channels'
/// squared XYZ samples (the second moment, a mean of squares, is their merged sum over the
/// merged sample count: the parts' means weighted by their sample counts).
///
/// # Errors
/// A part from another render (image size, samples per pixel, seed, or scene identity
/// differ from the first part's, or one part has `moment` channels another lacks), a part
/// whose pixels do not hold the samples its header
/// names, a part whose sums hold NaN or infinite values, two parts holding the same samples
/// of a pixel, or a pixel lacking samples.
pub fn merge_parts(parts: &[Part]) -> Result<Film, MergeError> {
    let first = parts.first().ok_or(MergeError::NoParts)?;
    for p in &parts[1..] {
        check_same_render(first, p)?;
    }
    for p in parts {
        check_complete(p)?;
        check_finite(p)?;
    }
    check_no_overlap(parts)?;
    let (w, h) = (first.info.width, first.info.height);
    check_no_gap(parts, w, h)?;
    let mut film = match &first.moment {
        Some(m) => Film::new(w, h).with_moment(&m.name),
        None => Film::new(w, h),
    };
    let mut splats = false;
    for p in parts {
        let win = p.window;
        for (k, a) in p.pixels.iter().enumerate() {
            let (x, y) = (
                win.x0 + k as u32 % win.width(),
                win.y0 + k as u32 / win.width(),
            );
            let index = (y * w + x) as usize;
            if p.info.crop.contains(x, y) {
                // Inside the image: `read_part` checked the window.
                let merged = film.merge(index, a);
                debug_assert!(merged.is_ok());
                if let Some(m) = &p.moment {
                    film.add_moment(index, m.sum_sq_xyz[k]);
                }
            }
            if let Some(s) = &p.splats {
                film.add_splat_sum(index, s[k]);
                splats = true;
            }
        }
    }
    if splats {
        let samples = first.info.spp as u64 * w as u64 * h as u64;
        film.set_splat_scale(super::splat_scale(samples, w as u64 * h as u64));
    }
    Ok(film)
}

fn check_same_render(first: &Part, p: &Part) -> Result<(), MergeError> {
    let (a, b) = (&first.info, &p.info);
    let moment = |p: &Part| {
        p.moment
            .as_ref()
            .map_or("none".to_string(), |m| format!("\"{}\"", m.name))
    };
    let checks: [(&'static str, String, String); 5] = [
        (
            "image size",
            format!("{}×{}", a.width, a.height),
            format!("{}×{}", b.width, b.height),
        ),
        ("samples per pixel", a.spp.to_string(), b.spp.to_string()),
        ("seed", a.seed.to_string(), b.seed.to_string()),
        (
            "scene (a hash of the scene and every option that shapes the image)",
            format!("{} {:016x}", a.scene, a.identity),
            format!("{} {:016x}", b.scene, b.identity),
        ),
        ("moment channels", moment(first), moment(p)),
    ];
    for (what, expected, found) in checks {
        if expected != found {
            return Err(MergeError::Mismatch {
                first: first.path.clone(),
                other: p.path.clone(),
                what,
                expected,
                found,
            });
        }
    }
    Ok(())
}

fn check_complete(p: &Part) -> Result<(), MergeError> {
    let win = p.window;
    for (k, a) in p.pixels.iter().enumerate() {
        let (x, y) = (
            win.x0 + k as u32 % win.width(),
            win.y0 + k as u32 / win.width(),
        );
        let expected = if p.info.crop.contains(x, y) {
            p.info.samples.len()
        } else {
            0
        };
        if a.count != expected {
            return Err(MergeError::Incomplete {
                path: p.path.clone(),
                pixel: (x, y),
                weight: a.count,
                expected,
            });
        }
    }
    Ok(())
}

/// Refuses a part whose sums hold NaN or infinite values, with their count.
fn check_finite(p: &Part) -> Result<(), MergeError> {
    let win = p.window;
    let mut first = None;
    let mut values = 0u64;
    for (k, a) in p.pixels.iter().enumerate() {
        let splat = p
            .splats
            .as_ref()
            .and_then(|s| s.get(k))
            .into_iter()
            .flatten();
        let moment = p
            .moment
            .as_ref()
            .and_then(|m| m.sum_sq_xyz.get(k))
            .into_iter()
            .flatten();
        let bad = a
            .sum
            .iter()
            .chain(&a.sum_sq)
            .chain(splat)
            .chain(moment)
            .filter(|v| !v.is_finite())
            .count() as u64;
        if bad > 0 {
            values += bad;
            first = first.or(Some((
                win.x0 + k as u32 % win.width(),
                win.y0 + k as u32 / win.width(),
            )));
        }
    }
    match first {
        None => Ok(()),
        Some(pixel) => Err(MergeError::NonFinite {
            path: p.path.clone(),
            pixel,
            values,
        }),
    }
}

fn check_no_overlap(parts: &[Part]) -> Result<(), MergeError> {
    for (i, a) in parts.iter().enumerate() {
        for b in &parts[i + 1..] {
            let (sa, sb) = (a.info.samples, b.info.samples);
            if let Some(pixels) = a.info.crop.intersection(&b.info.crop) {
                if sa.overlaps(&sb) {
                    return Err(MergeError::Overlap {
                        a: a.path.clone(),
                        b: b.path.clone(),
                        samples: SampleRange {
                            start: sa.start.max(sb.start),
                            end: sa.end.min(sb.end),
                        },
                        pixels,
                    });
                }
            }
        }
    }
    Ok(())
}

/// With no overlap, a pixel has all its samples if and only if the lengths of the ranges
/// that cover it add up to the samples per pixel.
fn check_no_gap(parts: &[Part], w: u32, h: u32) -> Result<(), MergeError> {
    let spp = parts[0].info.spp;
    let mut count = vec![0u32; w as usize * h as usize];
    for p in parts {
        let c = p.info.crop;
        for y in c.y0..c.y1 {
            for x in c.x0..c.x1 {
                count[(y * w + x) as usize] += p.info.samples.len();
            }
        }
    }
    let short = count.iter().filter(|&&n| n != spp).count() as u64;
    let Some(first) = count.iter().position(|&n| n != spp) else {
        return Ok(());
    };
    let (x, y) = (first as u32 % w, first as u32 / w);
    let mut ranges: Vec<SampleRange> = parts
        .iter()
        .filter(|p| p.info.crop.contains(x, y))
        .map(|p| p.info.samples)
        .collect();
    ranges.sort_by_key(|r| r.start);
    let mut next = 0;
    for r in &ranges {
        if r.start > next {
            break;
        }
        next = next.max(r.end);
    }
    let end = ranges
        .iter()
        .map(|r| r.start)
        .find(|&s| s > next)
        .unwrap_or(spp);
    Err(MergeError::Gap {
        pixel: (x, y),
        missing: SampleRange { start: next, end },
        pixels: short,
    })
}
