//! Dividing a render for distributed rendering: the sample range and the crop a
//! [`Renderer`] renders, and the identity that the parts of a render carry so that `merge`
//! can refuse parts of different renders, a hash of everything that shapes the image except
//! the sample range and the crop.

use super::{RenderError, RenderOptions, Renderer};
use crate::description::{EmitterDesc, SceneDescription, ShapeKind};
use crate::film::{Crop, PartInfo, SampleRange};
use mcrt::integrator::Integrator;
use std::path::{Path, PathBuf};

/// The sample range and crop of `opts` (all samples of `spp`, the whole `width` × `height`
/// image by default), checked; refused for `mlt`.
pub(super) fn window(
    opts: &RenderOptions,
    integrator: &Integrator,
    spp: u32,
    width: u32,
    height: u32,
) -> Result<(SampleRange, Crop), RenderError> {
    if matches!(integrator, Integrator::Mlt(_)) && (opts.samples.is_some() || opts.crop.is_some()) {
        return Err(RenderError::Split(
            "mlt cannot be split by --samples or --crop: its Markov chains roam the whole \
             image and share one mutation budget, so parts would not add up to one render"
                .into(),
        ));
    }
    let samples = opts.samples.unwrap_or(SampleRange::all(spp));
    samples
        .check(spp)
        .map_err(|e| RenderError::Split(e.to_string()))?;
    let crop = opts.crop.unwrap_or(Crop::full(width, height));
    crop.check(width, height)
        .map_err(|e| RenderError::Split(e.to_string()))?;
    Ok((samples, crop))
}

impl Renderer {
    /// The pixel samples rendered (all of them unless [`RenderOptions::samples`] says).
    pub fn samples(&self) -> SampleRange {
        self.samples
    }

    /// The pixels rendered (the whole image unless [`RenderOptions::crop`] says).
    pub fn crop(&self) -> Crop {
        self.crop
    }

    /// Pixel samples [`Renderer::render`] will take: the sample range's length times the
    /// crop's area.
    pub fn work(&self) -> u64 {
        self.samples.len() as u64 * self.crop.area()
    }

    /// A hash of everything that shapes the image except the sample range and the crop: the
    /// scene (with the content of the mesh and map files it names, but not its own path), the
    /// samples per pixel, seed, sampler, integrator, strategy, acceleration structure, light
    /// sampling and loop specialisation, and mcrt's version. Two renders with the same
    /// identity draw the same sample for the same pixel and index.
    pub fn identity(&self) -> u64 {
        self.identity
    }

    /// The header of a part holding this render's samples and pixels (see
    /// [`write_part`](crate::film::write_part)); `scene` names the scene in messages.
    pub fn part_info(&self, scene: &str) -> PartInfo {
        PartInfo {
            scene: scene.to_string(),
            identity: self.identity,
            seed: self.seed,
            spp: self.spp,
            width: self.width,
            height: self.height,
            samples: self.samples,
            crop: self.crop,
        }
    }
}

/// 64-bit FNV-1a: the same value on every platform and Rust version (std's hashers promise
/// neither). Fowler, Noll, Vo 1991, "FNV hash", as specified by Eastlake et al.,
/// IETF draft-eastlake-fnv.
struct Fnv1a(u64);

impl Fnv1a {
    fn new() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }

    fn bytes(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= b as u64;
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    /// A length-prefixed field, so that fields cannot run into each other.
    fn field(&mut self, bytes: &[u8]) {
        self.bytes(&(bytes.len() as u64).to_le_bytes());
        self.bytes(bytes);
    }

    /// The content of a file the scene refers to, which then stands for its name (the same
    /// mesh in another folder is the same scene).
    fn file(&mut self, base: Option<&Path>, name: &mut PathBuf) -> Result<(), String> {
        let path = match base {
            Some(b) if name.is_relative() => b.join(&*name),
            _ => name.clone(),
        };
        // Streamed: the file is hashed a chunk at a time, never held whole.
        let fail = |e: std::io::Error| format!("identity of {}: {e}", path.display());
        let mut f = std::fs::File::open(&path).map_err(fail)?;
        let len = f.metadata().map_err(fail)?.len();
        self.bytes(&len.to_le_bytes());
        let mut buf = vec![0u8; 1 << 16];
        let mut read = 0u64;
        loop {
            let n = std::io::Read::read(&mut f, &mut buf).map_err(fail)?;
            if n == 0 {
                break;
            }
            read += n as u64;
            self.bytes(&buf[..n]);
        }
        if read != len {
            return Err(fail(std::io::Error::other("the file changed while read")));
        }
        *name = PathBuf::new();
        Ok(())
    }
}

/// The hash of `desc` (with the samples per pixel, seed, sampler and integrator the render
/// resolved, and the content of the files it names in place of their names; not its own
/// path) and of `resolved`, the other options that shape the image.
pub(crate) fn render_identity(
    desc: &SceneDescription,
    base: Option<&Path>,
    resolved: &str,
) -> Result<u64, String> {
    let mut h = Fnv1a::new();
    h.field(concat!("mcrt ", env!("CARGO_PKG_VERSION")).as_bytes());
    let mut d = desc.clone();
    d.source = None;
    // A file's name is no part of a shape's or an emitter's check.
    for s in &mut d.shapes {
        s.change_unchecked(|s| match &mut s.kind {
            ShapeKind::Obj { filename, .. }
            | ShapeKind::Ply { filename, .. }
            | ShapeKind::Serialized { filename, .. } => h.file(base, filename),
            _ => Ok(()),
        })?;
    }
    for e in &mut d.emitters {
        e.change_unchecked(|e| match e {
            EmitterDesc::EnvMap { filename, .. } => h.file(base, filename),
            _ => Ok(()),
        })?;
    }
    // Each shape group once, in full (an instance's `Debug` names its group only), in the
    // order of `shape_groups`, which is the numbering of the shapes.
    for g in desc.shape_groups() {
        let mut shapes: Vec<_> = g.shapes.iter().map(|s| (**s).clone()).collect();
        for s in &mut shapes {
            match &mut s.kind {
                ShapeKind::Obj { filename, .. }
                | ShapeKind::Ply { filename, .. }
                | ShapeKind::Serialized { filename, .. } => h.file(base, filename)?,
                _ => {}
            }
        }
        h.field(format!("{shapes:?}").as_bytes());
    }
    h.field(format!("{d:?}").as_bytes());
    h.field(resolved.as_bytes());
    Ok(h.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a_reference_values() {
        // The published test vectors of 64-bit FNV-1a.
        let hash = |s: &str| {
            let mut h = Fnv1a::new();
            h.bytes(s.as_bytes());
            h.0
        };
        assert_eq!(hash(""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(hash("a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(hash("foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn the_scene_file_path_does_not_count_but_its_content_does() {
        let mut a = crate::cornell_box::cornell_box();
        let id = |d: &SceneDescription| render_identity(d, None, "opts").expect("identity");
        let base = id(&a);
        a.source = Some("/somewhere/else.xml".into());
        assert_eq!(id(&a), base);
        assert_ne!(render_identity(&a, None, "other opts").expect("id"), base);
        let film = a.sensor.film.changed(|f| f.width += 1).unwrap();
        a.sensor = a.sensor.changed(|s| s.film = film).unwrap();
        assert_ne!(id(&a), base);
    }
}
