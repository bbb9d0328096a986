//! The loader's error type: every failure names the file, the position and the element.

use std::fmt;
use std::path::{Path, PathBuf};

/// What went wrong while reading a scene (or an OBJ file it refers to).
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum SceneErrorKind {
    /// A file (the scene itself, an OBJ mesh or an EXR environment map) is missing or
    /// cannot be read.
    Io {
        /// The file that could not be read.
        path: PathBuf,
        /// The operating system's reason.
        reason: String,
    },
    /// The text is not well-formed XML.
    Xml(String),
    /// The `version` attribute of `<scene>` is missing, malformed or unsupported.
    Version(String),
    /// An element this loader does not know.
    UnknownElement(String),
    /// An element Mitsuba knows but this loader does not support.
    Unsupported(String),
    /// An attribute that is not allowed on this element.
    UnknownAttribute(String),
    /// A required attribute is absent.
    MissingAttribute(String),
    /// A plugin `type` that is not supported for this category.
    UnknownPlugin {
        /// The category (`bsdf`, `shape`, …).
        category: String,
        /// The requested type.
        plugin_type: String,
    },
    /// A parameter name the plugin does not take.
    UnknownParameter {
        /// The plugin, e.g. `bsdf "diffuse"`.
        plugin: String,
        /// The parameter name.
        name: String,
    },
    /// A parameter given twice.
    DuplicateParameter(String),
    /// A parameter given with the wrong value tag (e.g. `<string>` for a float).
    WrongType {
        /// The parameter name.
        name: String,
        /// What the plugin expects.
        expected: &'static str,
        /// The tag that was found.
        found: String,
    },
    /// A number, boolean, colour, point or matrix that cannot be parsed.
    Malformed(String),
    /// A well-formed value outside the allowed range.
    InvalidValue(String),
    /// `$name` with no `<default>` or define.
    UndefinedParameter(String),
    /// `ref` to an id that does not exist or names the wrong kind of object.
    UndefinedReference(String),
    /// Two objects with the same `id`.
    DuplicateId(String),
    /// The element is not allowed where it appears.
    Misplaced(String),
    /// A malformed line of an OBJ file.
    Obj(String),
}

impl fmt::Display for SceneErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Io { path, reason } => {
                write!(f, "cannot read file \"{}\": {reason}", path.display())
            }
            Self::Xml(m) => write!(f, "malformed XML: {m}"),
            Self::Version(m) => write!(f, "bad scene version: {m}"),
            Self::UnknownElement(t) => write!(f, "unknown element <{t}>"),
            Self::Unsupported(m) => write!(f, "unsupported: {m}"),
            Self::UnknownAttribute(a) => write!(f, "unknown attribute \"{a}\""),
            Self::MissingAttribute(a) => write!(f, "missing attribute \"{a}\""),
            Self::UnknownPlugin {
                category,
                plugin_type,
            } => write!(f, "unknown {category} plugin type \"{plugin_type}\""),
            Self::UnknownParameter { plugin, name } => {
                write!(f, "unknown parameter \"{name}\" for {plugin}")
            }
            Self::DuplicateParameter(n) => write!(f, "parameter \"{n}\" given twice"),
            Self::WrongType {
                name,
                expected,
                found,
            } => write!(
                f,
                "parameter \"{name}\" must be {expected}, found <{found}>"
            ),
            Self::Malformed(m) => write!(f, "malformed value: {m}"),
            Self::InvalidValue(m) => write!(f, "invalid value: {m}"),
            Self::UndefinedParameter(m) => write!(f, "undefined parameter: {m}"),
            Self::UndefinedReference(m) => write!(f, "bad reference: {m}"),
            Self::DuplicateId(id) => write!(f, "duplicate id \"{id}\""),
            Self::Misplaced(m) => write!(f, "misplaced element: {m}"),
            Self::Obj(m) => write!(f, "malformed OBJ: {m}"),
        }
    }
}

/// A scene-loading error: the file, the line and column, the element, and what is wrong.
///
/// `Display` prints `file, line L, column C, in <element …>: message`; for errors that
/// concern a whole file (it cannot be read), the position is absent.
///
/// ```
/// use mcrt::scene::loader::{parse_scene, SceneErrorKind};
/// let xml = "<scene version=\"3.0.0\">\n  <shape type=\"teapot\"/>\n</scene>";
/// let err = parse_scene(xml, Some(std::path::Path::new("a.xml")), &[]).unwrap_err();
/// assert_eq!(err.line, Some(2));
/// assert!(matches!(err.kind, SceneErrorKind::UnknownPlugin { .. }));
/// assert!(err.to_string().contains("a.xml, line 2"));
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SceneError {
    /// The file the error is in (`None` for a scene given as a string without a path).
    pub file: Option<PathBuf>,
    /// 1-based line, if the error has a position.
    pub line: Option<u32>,
    /// 1-based column, if known.
    pub column: Option<u32>,
    /// The element, written as its start tag with `type`, `name` and `id`, if any.
    pub element: Option<Box<str>>,
    /// What is wrong.
    pub kind: SceneErrorKind,
}

impl SceneError {
    /// An error at a position in a file.
    pub fn new(
        file: Option<&Path>,
        line: Option<u32>,
        column: Option<u32>,
        element: Option<String>,
        kind: SceneErrorKind,
    ) -> Self {
        Self {
            file: file.map(Path::to_path_buf),
            line,
            column,
            element: element.map(String::into_boxed_str),
            kind,
        }
    }

    /// A file that cannot be read (no position).
    pub fn io(path: &Path, err: &std::io::Error) -> Self {
        Self::new(
            Some(path),
            None,
            None,
            None,
            SceneErrorKind::Io {
                path: path.to_path_buf(),
                reason: err.to_string(),
            },
        )
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.file {
            Some(p) => write!(f, "{}", p.display())?,
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
        write!(f, ": {}", self.kind)
    }
}

impl std::error::Error for SceneError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn error_stays_small() {
        assert!(std::mem::size_of::<SceneError>() < 128);
    }
}
