//! The scene error type, the loader's and the mesh readers': every failure names the file,
//! the position and the element.

use std::fmt;
use std::path::{Path, PathBuf};

/// What went wrong while reading a scene (or an OBJ file it refers to).
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum SceneErrorKind {
    /// A file (the scene itself, a mesh or an EXR environment map) is missing or
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
    /// A define (`-D name=value`) that no `<default>` declares and no `$name` uses.
    UnknownDefine(String),
    /// `ref` to an id that does not exist or names the wrong kind of object.
    UndefinedReference(String),
    /// Two objects with the same `id`.
    DuplicateId(String),
    /// The element is not allowed where it appears.
    Misplaced(String),
    /// A malformed line of an OBJ file.
    Obj(String),
    /// A malformed PLY file (header, element data or mesh).
    Ply(String),
    /// A malformed Mitsuba `serialized` mesh file.
    Serialized(String),
    /// A file would need more memory than the budget ([`crate::memory`]); the message (our
    /// own text, not clipped) says how much and how to raise the limit.
    Memory(String),
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
            Self::UnknownDefine(m) => write!(f, "unknown define: {m}"),
            Self::UndefinedReference(m) => write!(f, "bad reference: {m}"),
            Self::DuplicateId(id) => write!(f, "duplicate id \"{id}\""),
            Self::Misplaced(m) => write!(f, "misplaced element: {m}"),
            Self::Obj(m) => write!(f, "malformed OBJ: {m}"),
            Self::Ply(m) => write!(f, "malformed PLY: {m}"),
            Self::Serialized(m) => write!(f, "malformed serialized mesh: {m}"),
            Self::Memory(m) => write!(f, "over the memory budget: {m}"),
        }
    }
}

/// A scene-loading error: the file, the line and column, the element, and what is wrong.
///
/// `Display` prints `file, line L, column C, in <element …>: message`; for errors that
/// concern a whole file (it cannot be read), the position is absent.
///
/// ```
/// use mcrt_render::loader::{parse_scene, SceneErrorKind};
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

/// Most characters of user text an error message quotes in one place.
pub(crate) const QUOTE_CHARS: usize = 120;

/// Most characters of an I/O error's reason: room for the [`MAX_LISTED_FOLDERS`] folders
/// a file was searched in, each quoted and clipped to [`QUOTE_CHARS`].
const IO_REASON_CHARS: usize = (MAX_LISTED_FOLDERS + 1) * (QUOTE_CHARS + 4);

/// Most characters of a message of ours about a value (`InvalidValue`): room for a
/// sentence that ends in the allowed range, with a clipped quote inside it.
const MESSAGE_CHARS: usize = 3 * QUOTE_CHARS + 40;

/// Most folders a "not found" message lists.
pub(crate) const MAX_LISTED_FOLDERS: usize = 16;

/// `s`, cut to [`QUOTE_CHARS`] characters with `…` marking the cut.
pub(crate) fn clip(s: &str) -> String {
    clip_to(s, QUOTE_CHARS)
}

/// `s`, cut to `n` characters with `…` marking the cut.
fn clip_to(s: &str, n: usize) -> String {
    match s.char_indices().nth(n) {
        None => s.to_string(),
        Some((k, _)) => format!("{}…", &s[..k]),
    }
}

/// A path cut like [`clip`] when it is longer than that.
fn clip_path(p: &Path) -> PathBuf {
    match p.to_str() {
        Some(s) if s.chars().count() > QUOTE_CHARS => PathBuf::from(clip(s)),
        _ => p.to_path_buf(),
    }
}

impl SceneErrorKind {
    /// The kind with every quoted string clipped (see [`clip`]).
    fn clipped(self) -> Self {
        let c = |s: String| clip(&s);
        match self {
            // A reason may list the folders searched, each clipped on its own (see
            // `loader::search_path`): a longer bound, still no quote over QUOTE_CHARS.
            Self::Io { path, reason } => Self::Io {
                path: clip_path(&path),
                reason: clip_to(&reason, IO_REASON_CHARS),
            },
            Self::Xml(m) => Self::Xml(c(m)),
            Self::Version(m) => Self::Version(c(m)),
            Self::UnknownElement(m) => Self::UnknownElement(c(m)),
            Self::Unsupported(m) => Self::Unsupported(c(m)),
            Self::UnknownAttribute(m) => Self::UnknownAttribute(c(m)),
            Self::MissingAttribute(m) => Self::MissingAttribute(c(m)),
            Self::UnknownPlugin {
                category,
                plugin_type,
            } => Self::UnknownPlugin {
                category: c(category),
                plugin_type: c(plugin_type),
            },
            Self::UnknownParameter { plugin, name } => Self::UnknownParameter {
                plugin: c(plugin),
                name: c(name),
            },
            Self::DuplicateParameter(m) => Self::DuplicateParameter(c(m)),
            Self::WrongType {
                name,
                expected,
                found,
            } => Self::WrongType {
                name: c(name),
                expected,
                found: c(found),
            },
            Self::Malformed(m) => Self::Malformed(c(m)),
            // Our own sentence (which quotes user text clipped already): a longer bound, so
            // that the allowed range or largest value at its end is not cut off.
            Self::InvalidValue(m) => Self::InvalidValue(clip_to(&m, MESSAGE_CHARS)),
            Self::UndefinedParameter(m) => Self::UndefinedParameter(c(m)),
            Self::UnknownDefine(m) => Self::UnknownDefine(c(m)),
            Self::UndefinedReference(m) => Self::UndefinedReference(c(m)),
            Self::DuplicateId(m) => Self::DuplicateId(c(m)),
            Self::Misplaced(m) => Self::Misplaced(c(m)),
            Self::Obj(m) => Self::Obj(c(m)),
            Self::Ply(m) => Self::Ply(c(m)),
            Self::Serialized(m) => Self::Serialized(c(m)),
            Self::Memory(m) => Self::Memory(m),
        }
    }
}

impl SceneError {
    /// An error at a position in a file. Quoted user text is clipped to a few hundred
    /// bytes, so that no message repeats a huge attribute.
    pub fn new(
        file: Option<&Path>,
        line: Option<u32>,
        column: Option<u32>,
        element: Option<String>,
        kind: SceneErrorKind,
    ) -> Self {
        Self {
            file: file.map(clip_path),
            line,
            column,
            element: element.map(|e| clip(&e).into_boxed_str()),
            kind: kind.clipped(),
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
        let huge = "é".repeat(100_000);
        let e = SceneError::new(
            Some(Path::new(&huge)),
            Some(1),
            None,
            Some(huge.clone()),
            SceneErrorKind::Malformed(huge.clone()),
        );
        assert!(e.to_string().len() < 2000, "{}", e.to_string().len());
    }
}
