//! Where the parts of a scene were written: the loader records the file, line and column of
//! each top-level shape and emitter, so that errors found only when the scene is prepared
//! for rendering (a light whose power overflows because of the scene's size) still name
//! the place to fix.

use std::fmt;
use std::path::PathBuf;

/// The element a part of the scene came from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Origin {
    /// The file (`None` for a scene given as a string without a path).
    pub file: Option<PathBuf>,
    /// 1-based line of the element's start tag.
    pub line: u32,
    /// 1-based column of the element's start tag.
    pub column: u32,
    /// The element, written as its start tag with `type`, `name` and `id`, if any.
    pub element: Box<str>,
}

/// Written as a [`SceneError`](crate::scene_error::SceneError) writes its position:
/// `file, line L, column C, in <element …>`.
impl fmt::Display for Origin {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.file {
            Some(p) => write!(f, "{}", p.display())?,
            None => f.write_str("<scene string>")?,
        }
        write!(
            f,
            ", line {}, column {}, in {}",
            self.line, self.column, self.element
        )
    }
}

/// The origins of a description's top-level shapes and emitters, index for index with
/// [`SceneDescription::shapes`](super::SceneDescription::shapes) and
/// [`SceneDescription::emitters`](super::SceneDescription::emitters). A description built
/// in code leaves both empty (an index without an entry has no origin).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Origins {
    /// Per top-level shape: its `<shape>` element.
    pub shapes: Vec<Option<Origin>>,
    /// Per emitter not attached to a shape: its `<emitter>` element.
    pub emitters: Vec<Option<Origin>>,
}

impl Origins {
    /// Where shape `i` was written, if known.
    pub fn shape(&self, i: usize) -> Option<&Origin> {
        self.shapes.get(i).and_then(Option::as_ref)
    }

    /// Where emitter `i` was written, if known.
    pub fn emitter(&self, i: usize) -> Option<&Origin> {
        self.emitters.get(i).and_then(Option::as_ref)
    }
}
