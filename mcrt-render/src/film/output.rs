//! Where a render's images go, decided and checked before rendering, and written so that
//! nothing is lost: by default into the folder [`DEFAULT_FOLDER`] of the current folder
//! (made if missing; the repository's `.gitignore` lists it), the extension of the requested
//! name chooses the format and the other format goes beside it, a name equal to the scene
//! file is refused, the folder must be writable before any work starts, every file is
//! written atomically (see [`write_exr`]), and an interrupted render writes
//! `NAME.partial.exr` / `NAME.partial.png` instead of replacing a complete image.

use super::part::{write_part, PartInfo};
use super::write::{write_exr, write_exr_with_channels, write_png};
use super::Film;
use crate::io::ImageError;
use glam::Vec3;
use std::fmt;
use std::path::{Path, PathBuf};

/// The folder, relative to the current one, that renders go to when no output is named.
pub const DEFAULT_FOLDER: &str = "renders";

/// The exit status of a render stopped by SIGINT or SIGTERM (128 + SIGINT, as shells do).
pub const EXIT_INTERRUPTED: u8 = 130;

/// The output files of one render.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutputPlan {
    /// The linear float EXR.
    pub exr: PathBuf,
    /// The 8-bit sRGB PNG.
    pub png: PathBuf,
    /// The per-pixel variance EXR (`NAME-variance.exr`), if asked for.
    pub variance: Option<PathBuf>,
}

/// The requested output cannot be used.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutputError(pub String);

impl fmt::Display for OutputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for OutputError {}

impl OutputPlan {
    /// The files for `requested` (`-o`; else `default_stem.exr` in [`DEFAULT_FOLDER`]).
    /// `NAME.exr` or `NAME.png` (any case) gives both `NAME.exr` and `NAME.png`; any other
    /// extension is refused, as is a name that is the scene file.
    ///
    /// ```
    /// use mcrt_render::film::OutputPlan;
    /// use std::path::Path;
    /// let p = OutputPlan::new(None, "scene", None, false).unwrap();
    /// assert_eq!(p.exr, Path::new("renders/scene.exr"));
    /// let p = OutputPlan::new(Some(Path::new("out/x.png")), "scene", None, false).unwrap();
    /// assert_eq!(p.exr, Path::new("out/x.exr"));
    /// assert_eq!(p.png, Path::new("out/x.png"));
    /// assert_eq!(p.partial().exr, Path::new("out/x.partial.exr"));
    /// assert!(OutputPlan::new(Some(Path::new("x.jpg")), "scene", None, false).is_err());
    /// ```
    pub fn new(
        requested: Option<&Path>,
        default_stem: &str,
        scene: Option<&Path>,
        variance: bool,
    ) -> Result<Self, OutputError> {
        let out = requested
            .map(Path::to_path_buf)
            .unwrap_or_else(|| Path::new(DEFAULT_FOLDER).join(format!("{default_stem}.exr")));
        let ext = out
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let (exr, png) = match ext.as_deref() {
            Some("exr") => (out.clone(), out.with_extension("png")),
            Some("png") => (out.with_extension("exr"), out.clone()),
            _ => {
                return Err(OutputError(format!(
                    "output \"{}\": the name must end in .exr or .png (the other format is \
                     written beside it)",
                    out.display()
                )))
            }
        };
        let variance = variance.then(|| {
            let stem = exr
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            exr.with_file_name(format!("{stem}-variance.exr"))
        });
        let plan = Self { exr, png, variance };
        if let Some(scene) = scene {
            for p in plan.files() {
                if same_file(p, scene) {
                    return Err(OutputError(format!(
                        "output \"{}\" is the scene file",
                        p.display()
                    )));
                }
            }
        }
        Ok(plan)
    }

    /// Every file of the plan.
    pub fn files(&self) -> impl Iterator<Item = &PathBuf> {
        [&self.exr, &self.png]
            .into_iter()
            .chain(self.variance.iter())
    }

    /// The names an interrupted render writes: `NAME.partial.exr`, `NAME.partial.png`,
    /// `NAME-variance.partial.exr`.
    pub fn partial(&self) -> Self {
        let part = |p: &PathBuf| {
            let stem = p
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            let ext = p
                .extension()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            p.with_file_name(format!("{stem}.partial.{ext}"))
        };
        Self {
            exr: part(&self.exr),
            png: part(&self.png),
            variance: self.variance.as_ref().map(part),
        }
    }

    /// Checks, before rendering, that every file can be written: its folder exists (the
    /// [`DEFAULT_FOLDER`] is made if missing) and accepts a new file, and the name is not a
    /// folder.
    pub fn check_writable(&self) -> Result<(), OutputError> {
        for p in self.files() {
            if p.is_dir() {
                return Err(OutputError(format!(
                    "output \"{}\" is a folder",
                    p.display()
                )));
            }
            let dir = folder_of(p);
            if dir == Path::new(DEFAULT_FOLDER) && !dir.exists() {
                std::fs::create_dir(&dir).map_err(|e| {
                    OutputError(format!("cannot make the folder \"{}\": {e}", dir.display()))
                })?;
            }
            let probe = dir.join(format!(".mcrt-probe-{}", std::process::id()));
            let made = std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&probe);
            match made {
                Ok(_) => {
                    std::fs::remove_file(&probe).ok();
                }
                Err(e) => {
                    return Err(OutputError(format!(
                        "cannot write \"{}\": folder \"{}\": {e}",
                        p.display(),
                        dir.display()
                    )))
                }
            }
        }
        Ok(())
    }

    /// Writes the film: the complete images under the plan's names, or, if `interrupted`,
    /// under the [`partial`](Self::partial) names with every pixel that has no sample set
    /// to NaN in the EXR (black in the PNG). Returns the files written.
    pub fn write(&self, film: &Film, interrupted: bool) -> Result<Vec<PathBuf>, ImageError> {
        let plan = if interrupted {
            self.partial()
        } else {
            self.clone()
        };
        let unsampled = if interrupted { Vec3::NAN } else { Vec3::ZERO };
        let (w, h) = (film.width(), film.height());
        let image = film.mean_or(unsampled);
        let extra = film.extra_channels(&image, unsampled.x);
        write_exr_with_channels(&plan.exr, w, h, &image, &extra)?;
        write_png(&plan.png, w, h, &image)?;
        if let Some(v) = &plan.variance {
            write_exr(v, w, h, &film.variance())?;
        }
        Ok(plan.files().cloned().collect())
    }
}

impl OutputPlan {
    /// Writes `film`'s share `info` of a render as a part (see [`write_part`]) under the
    /// plan's EXR name, or its [`partial`](Self::partial) name if `interrupted` (the `merge`
    /// example refuses such a part, whose pixels lack samples). Returns the file written.
    pub fn write_part(
        &self,
        film: &Film,
        info: &PartInfo,
        interrupted: bool,
    ) -> Result<PathBuf, ImageError> {
        let path = if interrupted {
            self.partial().exr
        } else {
            self.exr.clone()
        };
        write_part(&path, film, info)?;
        Ok(path)
    }

    /// Refuses a plan that would overwrite one of `inputs` (for `merge`: one of its parts).
    pub fn check_not_inputs(&self, inputs: &[PathBuf]) -> Result<(), OutputError> {
        for p in self.files() {
            if let Some(i) = inputs.iter().find(|i| same_file(p, i)) {
                return Err(OutputError(format!(
                    "output \"{}\" is the input \"{}\"",
                    p.display(),
                    i.display()
                )));
            }
        }
        Ok(())
    }
}

/// The folder a file goes in (`.` for a bare name).
pub(crate) fn folder_of(p: &Path) -> PathBuf {
    match p.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Whether two names are one file (by canonical path when both exist, else by name).
fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => a == b,
    }
}
