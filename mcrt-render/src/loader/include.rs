//! `<include filename="…"/>`: the children of another scene file's `<scene>` in place of
//! the element, read with the parameters and search path known so far, as Mitsuba 3 does.

use super::params::Params;
use super::position::Positions;
use super::tree::{parse_version, prescan, Elem, Reader};
use crate::io::canonical;
use crate::scene_error::{SceneError, SceneErrorKind};
use std::path::Path;
use std::sync::Arc;

/// Deepest chain of `<include>`s (a file that includes itself is refused before this).
const MAX_INCLUDE_DEPTH: usize = 16;

impl Reader<'_> {
    /// `<include filename>`: the children of the named file's `<scene>`, read with the
    /// parameters known so far. The name resolves against the including file's search path
    /// (its folder first); the file must be a regular scene file of at most 256 MiB, not
    /// one already being read. A file older than 2.0.0 is upgraded.
    pub(super) fn include(&mut self, e: &Elem, depth: usize) -> Result<Vec<Elem>, SceneError> {
        if let Some((n, _)) = e.attrs.iter().find(|(n, _)| n != "filename") {
            return Err(self.err(e, SceneErrorKind::UnknownAttribute(n.clone())));
        }
        if let Some(k) = e.children.first() {
            let m = format!("<{}> inside <include>", k.tag);
            return Err(self.err(k, SceneErrorKind::Misplaced(m)));
        }
        let name = e
            .attr("filename")
            .ok_or_else(|| self.err(e, SceneErrorKind::MissingAttribute("filename".into())))?;
        let Some(path) = self
            .search
            .resolve(Path::new(name))
            .filter(|_| !name.is_empty())
        else {
            let reason = if name.is_empty() {
                "empty file name".to_string()
            } else {
                format!(
                    "not found in the folders searched: {}",
                    self.search.describe()
                )
            };
            let path = name.into();
            return Err(self.err(e, SceneErrorKind::Io { path, reason }));
        };
        let io = |reason: String| SceneErrorKind::Io {
            path: path.clone(),
            reason,
        };
        let bytes = crate::io::read_capped(&path, crate::io::MAX_SCENE_BYTES)
            .map_err(|x| self.err(e, io(x.to_string())))?;
        let key = canonical(&path);
        if self.stack.contains(&key) {
            let m = format!("\"{name}\" includes itself (directly or through other files)");
            return Err(self.err(e, SceneErrorKind::InvalidValue(m)));
        }
        if self.stack.len() > MAX_INCLUDE_DEPTH {
            let m = format!("includes nested deeper than {MAX_INCLUDE_DEPTH}");
            return Err(self.err(e, SceneErrorKind::InvalidValue(m)));
        }
        let xml = String::from_utf8(bytes).map_err(|_| self.err(e, io("not UTF-8 text".into())))?;
        // Parse the included text with its own positions; defaults and parameters carry on.
        let here: Arc<Path> = Arc::from(path.as_path());
        let text_err =
            |line, column, kind| SceneError::new(Some(&path), Some(line), Some(column), None, kind);
        if let Some((offset, message)) = prescan(&xml) {
            let (line, column) = Positions::new(&xml).at(offset);
            return Err(text_err(line, column, SceneErrorKind::Xml(message)));
        }
        let opts = roxmltree::ParsingOptions {
            allow_dtd: false,
            nodes_limit: 10_000_000,
        };
        let doc = roxmltree::Document::parse_with_options(&xml, opts).map_err(|x| {
            let p = x.pos();
            text_err(p.row, p.col, SceneErrorKind::Xml(x.to_string()))
        })?;
        let mut search = self.search.clone();
        if let Some(folder) = path.parent().filter(|f| !f.as_os_str().is_empty()) {
            search.prepend(folder.to_path_buf());
        }
        let mut sub = Reader {
            positions: Positions::new(&xml),
            file: Some(&path),
            included: Some(Arc::clone(&here)),
            search,
            stack: std::mem::take(&mut self.stack),
            params: std::mem::replace(&mut self.params, Params::new(&[])),
        };
        sub.stack.push(key);
        let root = sub.convert(doc.root_element(), depth);
        sub.stack.pop();
        self.stack = std::mem::take(&mut sub.stack);
        self.params = sub.params;
        let mut root = root?;
        if root.tag != "scene" {
            let m = format!(
                "an included file's root must be <scene>, not <{}>",
                root.tag
            );
            return Err(sub_err(&root, SceneErrorKind::Misplaced(m)));
        }
        // Mitsuba 3 requires the version of an included file as of the main file's.
        let version = match root.attr("version").map(parse_version) {
            None => {
                let m = "missing \"version\" attribute".to_string();
                return Err(sub_err(&root, SceneErrorKind::Version(m)));
            }
            Some(Err(m)) => return Err(sub_err(&root, SceneErrorKind::Version(m))),
            Some(Ok(v)) => v,
        };
        if version < super::upgrade::UPGRADE_BELOW {
            super::upgrade::upgrade(&mut root, Some(&here));
        }
        Ok(root.children)
    }
}

/// An error at an element of an included file (which the element names).
fn sub_err(e: &Elem, kind: SceneErrorKind) -> SceneError {
    SceneError::new(
        e.file.as_deref(),
        Some(e.line),
        Some(e.column),
        Some(e.describe()),
        kind,
    )
}
