//! The scene warning type: something the loader accepted, as Mitsuba 3 does, but that a
//! user likely did not mean (a rotation axis that is not unit length). It names the file,
//! the position and the element as a [`SceneError`](crate::scene_error::SceneError) does.

use crate::scene_error::clip;
use std::fmt;
use std::path::{Path, PathBuf};

/// A located warning from the loader, returned by
/// [`load_scene_with_warnings`](crate::loader::load_scene_with_warnings) and
/// [`parse_scene_with_warnings`](crate::loader::parse_scene_with_warnings); the `render`
/// program prints each one.
///
/// `Display` prints `file, line L, column C, in <element …>: warning: message`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SceneWarning {
    /// The file the element is in (`None` for a scene given as a string without a path).
    pub file: Option<PathBuf>,
    /// 1-based line of the element.
    pub line: Option<u32>,
    /// 1-based column of the element.
    pub column: Option<u32>,
    /// The element, written as its start tag with `type`, `name` and `id`.
    pub element: Option<Box<str>>,
    /// What the loader did and why it may not be what was meant.
    pub message: String,
}

impl SceneWarning {
    /// A warning at a position in a file; quoted user text is clipped as in errors.
    pub fn new(
        file: Option<&Path>,
        line: Option<u32>,
        column: Option<u32>,
        element: Option<String>,
        message: String,
    ) -> Self {
        Self {
            file: file.map(Path::to_path_buf),
            line,
            column,
            element: element.map(|e| clip(&e).into_boxed_str()),
            message,
        }
    }
}

impl fmt::Display for SceneWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.file {
            Some(p) => write!(f, "{}", clip(&p.display().to_string()))?,
            None => write!(f, "<scene string>")?,
        }
        if let Some(line) = self.line {
            write!(f, ", line {line}")?;
        }
        if let Some(col) = self.column {
            write!(f, ", column {col}")?;
        }
        if let Some(e) = &self.element {
            write!(f, ", in {e}")?;
        }
        write!(f, ": warning: {}", self.message)
    }
}
