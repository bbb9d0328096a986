//! Reads the XML text into a small owned element tree, checking the version, applying
//! `<default>` parameters and `-D` defines, substituting `$name` in every attribute
//! value in document order, taking `<path>` folders into the search path, putting the
//! contents of each `<include filename>`d scene in its place, and upgrading files older
//! than 2.0.0, as Mitsuba 3 does.

pub(crate) use super::elem::Elem;
use super::params::{Params, SubstError};
use super::position::Positions;
use super::search_path::SearchPath;
use crate::scene_error::{clip, SceneError, SceneErrorKind};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Deepest element nesting accepted (real scenes use fewer than ten levels).
const MAX_DEPTH: usize = 64;

/// Most attributes on one element (Mitsuba's take at most five; roxmltree's duplicate check
/// is quadratic in their number).
const MAX_ATTRIBUTES: usize = 256;

/// Parses `xml` into the `<scene>` element tree, with the folders that the files it names
/// resolve against.
pub(crate) fn read_tree(
    xml: &str,
    file: Option<&Path>,
    defines: &[(String, String)],
) -> Result<(Elem, SearchPath), SceneError> {
    let opts = roxmltree::ParsingOptions {
        allow_dtd: false,
        nodes_limit: 10_000_000,
    };
    // roxmltree parses nested elements recursively and checks attributes for duplicates
    // pairwise: refuse deep nesting and crowded elements before it sees them.
    if let Some((offset, message)) = prescan(xml) {
        let (line, column) = Positions::new(xml).at(offset);
        return Err(SceneError::new(
            file,
            Some(line),
            Some(column),
            None,
            SceneErrorKind::Xml(message),
        ));
    }
    let doc = roxmltree::Document::parse_with_options(xml, opts).map_err(|e| {
        let pos = e.pos();
        SceneError::new(
            file,
            Some(pos.row),
            Some(pos.col),
            None,
            SceneErrorKind::Xml(e.to_string()),
        )
    })?;
    let mut reader = Reader {
        positions: Positions::new(xml),
        file,
        included: None,
        search: SearchPath::for_scene(file),
        stack: file.map(crate::io::canonical).into_iter().collect(),
        params: Params::new(defines),
    };
    let mut root = reader.convert(doc.root_element(), 0)?;
    let err = |kind| {
        SceneError::new(
            file,
            Some(root.line),
            Some(root.column),
            Some(root.describe()),
            kind,
        )
    };
    if root.tag != "scene" {
        return Err(err(SceneErrorKind::Misplaced(format!(
            "the root element must be <scene>, not <{}>",
            root.tag
        ))));
    }
    let version = match root.attr("version") {
        None => Err(err(SceneErrorKind::Version(
            "missing \"version\" attribute".into(),
        ))),
        Some(v) => parse_version(v).map_err(|m| err(SceneErrorKind::Version(m))),
    }?;
    if version < super::upgrade::UPGRADE_BELOW {
        super::upgrade::upgrade(&mut root, None);
    }
    check_defines(&reader.params, file, defines)?;
    Ok((root, reader.search))
}

/// Refuses a define that is none of the scene's parameters (see [`Params`]).
fn check_defines(
    params: &Params,
    file: Option<&Path>,
    defines: &[(String, String)],
) -> Result<(), SceneError> {
    let Some(name) = params.unused_defines().first().copied() else {
        return Ok(());
    };
    let value = defines
        .iter()
        .find(|(n, _)| n == name)
        .map_or("", |(_, v)| v.as_str());
    let declared = params.default_names();
    let list = if declared.is_empty() {
        "it declares no <default> parameter".to_string()
    } else {
        format!("its <default> parameters: {}", declared.join(", "))
    };
    Err(SceneError::new(
        file,
        None,
        None,
        None,
        SceneErrorKind::UnknownDefine(format!(
            "-D {name}={value}: the scene neither declares nor uses a parameter \"{name}\" \
             ({list})"
        )),
    ))
}

/// The byte offset of the first start tag nested deeper than [`MAX_DEPTH`] or with more
/// than [`MAX_ATTRIBUTES`] attributes, and what is wrong, by a scan that skips comments,
/// CDATA, processing instructions and quoted attribute values.
pub(super) fn prescan(xml: &str) -> Option<(usize, String)> {
    let b = xml.as_bytes();
    let skip_to = |from: usize, end: &str| {
        xml[from..]
            .find(end)
            .map_or(b.len(), |k| from + k + end.len())
    };
    let (mut i, mut depth) = (0usize, 0usize);
    while i < b.len() {
        if b[i] != b'<' {
            i += 1;
            continue;
        }
        let rest = &xml[i..];
        if rest.starts_with("<!--") {
            i = skip_to(i, "-->");
        } else if rest.starts_with("<![CDATA[") {
            i = skip_to(i, "]]>");
        } else if rest.starts_with("<?") {
            i = skip_to(i, "?>");
        } else if rest.starts_with("</") {
            depth = depth.saturating_sub(1);
            i = skip_to(i, ">");
        } else {
            let start = i;
            let (end, self_closing, attributes) = tag_end(b, i + 1);
            if attributes > MAX_ATTRIBUTES {
                return Some((
                    start,
                    format!("an element with more than {MAX_ATTRIBUTES} attributes"),
                ));
            }
            if !self_closing {
                depth += 1;
                if depth > MAX_DEPTH + 1 {
                    return Some((start, format!("elements nested deeper than {MAX_DEPTH}")));
                }
            }
            i = end;
        }
    }
    None
}

/// The index after the `>` closing a start tag that begins at `i`, whether it is
/// self-closing (`/>`), and its number of attributes (`=` outside quotes). Quoted values
/// may contain `>`.
fn tag_end(b: &[u8], mut i: usize) -> (usize, bool, usize) {
    let (mut quote, mut equals) = (None::<u8>, 0usize);
    while i < b.len() {
        match (quote, b[i]) {
            (Some(q), c) if c == q => quote = None,
            (None, b'"' | b'\'') => quote = Some(b[i]),
            (None, b'=') => equals += 1,
            (None, b'>') => return (i + 1, i > 0 && b[i - 1] == b'/', equals),
            _ => {}
        }
        i += 1;
    }
    (b.len(), false, equals)
}

/// A version `major.minor.patch` (periods or spaces between; Mitsuba 3's `util::Version`).
/// Files older than 2.0.0 are upgraded on load (`upgrade.rs`).
pub(super) fn parse_version(v: &str) -> Result<[u32; 3], String> {
    let parts: Vec<&str> = v.split(['.', ' ']).filter(|s| !s.is_empty()).collect();
    let nums: Option<Vec<u32>> = parts.iter().map(|p| p.parse().ok()).collect();
    match nums {
        Some(n) if n.len() == 3 => Ok([n[0], n[1], n[2]]),
        _ => Err(format!(
            "could not parse version \"{v}\" (expected major.minor.patch)"
        )),
    }
}

pub(super) struct Reader<'a> {
    pub(super) positions: Positions<'a>,
    pub(super) file: Option<&'a Path>,
    /// The file being read when it is an included one (shared by its elements).
    pub(super) included: Option<Arc<Path>>,
    /// The folders `<include>` names and `<path>` values resolve against (this file's
    /// list; see [`SearchPath`]).
    pub(super) search: SearchPath,
    /// The files being read, outermost first (for cycles and depth).
    pub(super) stack: Vec<PathBuf>,
    pub(super) params: Params,
}

impl Reader<'_> {
    pub(super) fn convert(
        &mut self,
        node: roxmltree::Node,
        depth: usize,
    ) -> Result<Elem, SceneError> {
        let (line, column) = self.positions.at(node.range().start);
        // Describe with the raw attributes until substitution succeeds.
        let mut elem = Elem {
            tag: node.tag_name().name().to_string(),
            attrs: node
                .attributes()
                .map(|a| (a.name().to_string(), a.value().to_string()))
                .collect(),
            children: Vec::new(),
            line,
            column,
            file: self.included.clone(),
            renamed_from: None,
        };
        for i in 0..elem.attrs.len() {
            let value = self.substitute(&elem.attrs[i].1);
            elem.attrs[i].1 = value.map_err(|m| self.err(&elem, m))?;
        }
        if depth > MAX_DEPTH {
            return Err(self.err(
                &elem,
                SceneErrorKind::Misplaced(format!("elements nested deeper than {MAX_DEPTH}")),
            ));
        }
        for child in node.children() {
            if child.is_text() {
                let text = child.text().unwrap_or("");
                if !text.trim().is_empty() {
                    return Err(self.err(
                        &elem,
                        SceneErrorKind::Misplaced(format!(
                            "unexpected text \"{}\"",
                            text.trim().chars().take(40).collect::<String>()
                        )),
                    ));
                }
            } else if child.is_element() {
                let c = self.convert(child, depth + 1)?;
                if c.tag == "default" {
                    self.add_default(&c)?;
                } else if c.tag == "path" {
                    // Mitsuba 3: `<path>` only directly inside a file's root element.
                    if !node.parent().is_some_and(|p| p.is_root()) {
                        let m = "<path> not directly inside <scene>".to_string();
                        return Err(self.err(&c, SceneErrorKind::Misplaced(m)));
                    }
                    self.add_path(&c)?;
                } else if c.tag == "include" {
                    let inner = self.include(&c, depth)?;
                    elem.children.extend(inner);
                } else {
                    elem.children.push(c);
                }
            }
        }
        Ok(elem)
    }

    /// `<default name value>`: defines `name` unless a define or earlier default did.
    fn add_default(&mut self, e: &Elem) -> Result<(), SceneError> {
        for (n, _) in &e.attrs {
            if n != "name" && n != "value" {
                return Err(self.err(e, SceneErrorKind::UnknownAttribute(n.clone())));
            }
        }
        let name = e
            .attr("name")
            .ok_or_else(|| self.err(e, SceneErrorKind::MissingAttribute("name".into())))?;
        let value = e
            .attr("value")
            .ok_or_else(|| self.err(e, SceneErrorKind::MissingAttribute("value".into())))?;
        if name.is_empty() {
            return Err(self.err(
                e,
                SceneErrorKind::InvalidValue("<default> needs a non-empty name".into()),
            ));
        }
        self.params.declare(name, value);
        Ok(())
    }

    /// `<path value>`: the folder (resolved against the list so far) goes in front of this
    /// file's search path; it must exist.
    fn add_path(&mut self, e: &Elem) -> Result<(), SceneError> {
        if let Some((n, _)) = e.attrs.iter().find(|(n, _)| n != "value") {
            return Err(self.err(e, SceneErrorKind::UnknownAttribute(n.clone())));
        }
        if let Some(k) = e.children.first() {
            let m = format!("<{}> inside <path>", k.tag);
            return Err(self.err(k, SceneErrorKind::Misplaced(m)));
        }
        let value = e
            .attr("value")
            .ok_or_else(|| self.err(e, SceneErrorKind::MissingAttribute("value".into())))?;
        let found = self
            .search
            .resolve(Path::new(value))
            .filter(|_| !value.is_empty());
        let Some(folder) = found.filter(|p| std::fs::metadata(p).is_ok()) else {
            let reason = format!(
                "<path>: folder not found in the folders searched: {}",
                self.search.describe()
            );
            let path = PathBuf::from(value);
            return Err(self.err(e, SceneErrorKind::Io { path, reason }));
        };
        self.search.prepend(folder);
        Ok(())
    }

    /// Mitsuba's rule (see [`Params`]): `$name` becomes the value of the longest known
    /// name; any other `$` is an undefined parameter.
    fn substitute(&mut self, value: &str) -> Result<String, SceneErrorKind> {
        self.params.substitute(value).map_err(|e| match e {
            SubstError::Undefined => SceneErrorKind::UndefinedParameter(format!(
                "\"{}\" refers to a parameter that no <default> or define gives",
                clip(value)
            )),
            SubstError::TooLarge(m) => SceneErrorKind::InvalidValue(m),
        })
    }

    pub(super) fn err(&self, e: &Elem, kind: SceneErrorKind) -> SceneError {
        SceneError::new(
            e.file.as_deref().or(self.file),
            Some(e.line),
            Some(e.column),
            Some(e.describe()),
            kind,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deep_nesting_is_refused_before_parsing() {
        let deep = |n: usize| {
            format!(
                "<scene version=\"3.0.0\">{}{}</scene>",
                "<a>".repeat(n),
                "</a>".repeat(n)
            )
        };
        assert_eq!(prescan(&deep(MAX_DEPTH)), None);
        assert!(prescan(&deep(MAX_DEPTH + 1)).is_some());
        let e = read_tree(&deep(1_000_000), None, &[]).unwrap_err();
        assert!(matches!(e.kind, SceneErrorKind::Xml(_)), "{e}");
        let flat = "<s>\n<!-- <a><a> --><b x=\">\"/><c/></s>";
        assert_eq!(prescan(flat), None);
    }

    #[test]
    fn versions() {
        assert_eq!(parse_version("3.0.0"), Ok([3, 0, 0]));
        assert_eq!(parse_version("2.1.0"), Ok([2, 1, 0]));
        assert_eq!(parse_version("0.6 0"), Ok([0, 6, 0]));
        assert!(parse_version("3.0").is_err());
        assert!(parse_version("x.0.0").is_err());
    }

    #[test]
    fn defines_beat_defaults_and_longest_name_wins() {
        let xml = r#"<scene version="3.0.0"><default name="a" value="1"/>
            <default name="ab" value="2"/><x v="$a $ab"/></scene>"#;
        let (t, _) = read_tree(xml, None, &[("a".into(), "9".into())]).unwrap();
        assert_eq!(t.children[0].attr("v"), Some("9 2"));
    }
}
