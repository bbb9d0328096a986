//! One element of the scene's XML tree, after parameter substitution: what the reader
//! (`tree.rs`, `include.rs`) builds, the upgrade of old files (`upgrade.rs`) rewrites and
//! every plugin reader reads.

use crate::scene_error::clip;
use std::path::Path;
use std::sync::Arc;

/// One XML element after parameter substitution.
#[derive(Debug, Clone)]
pub(crate) struct Elem {
    /// The tag name.
    pub tag: String,
    /// Attributes in file order, values substituted.
    pub attrs: Vec<(String, String)>,
    /// Child elements (comments and `<default>` removed).
    pub children: Vec<Elem>,
    /// 1-based line of the start tag.
    pub line: u32,
    /// 1-based column of the start tag.
    pub column: u32,
    /// The included file the element comes from (`None`: the scene file itself).
    pub file: Option<Arc<Path>>,
    /// The `name` the file gave, when the upgrade of an old file renamed it.
    pub renamed_from: Option<Box<str>>,
}

impl Elem {
    /// The value of an attribute.
    pub fn attr(&self, name: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_str())
    }

    /// The start tag with its identifying attributes, for messages.
    pub fn describe(&self) -> String {
        let mut s = format!("<{}", clip(&self.tag));
        for key in ["type", "name", "id"] {
            if let Some(v) = self.attr(key) {
                s.push_str(&format!(" {key}=\"{}\"", clip(v)));
            }
        }
        s.push('>');
        if let Some(old) = &self.renamed_from {
            s.push_str(&format!(" (name=\"{}\" in the file)", clip(old)));
        }
        s
    }
}
