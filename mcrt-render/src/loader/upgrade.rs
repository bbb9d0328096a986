//! The in-memory upgrade of scene files older than version 2.0.0 (Mitsuba 0.5 and 0.6), by
//! the rules of Mitsuba 3's own reader (3.9.1's `upgrade_from_v1` in `src/core/parser.cpp`,
//! and, where it did more, the earlier `upgrade_tree` in `src/core/xml.cpp`):
//!
//! - every `name` attribute goes from camelCase to snake_case (`toWorld` → `to_world`,
//!   `intIOR` → `int_ior`): an underscore before each upper-case letter that follows a
//!   lower-case one, and that letter and the upper-case ones right after it in lower case;
//! - `diffuse_reflectance` of a `diffuse` BSDF becomes `reflectance`;
//! - `uoffset`, `voffset`, `uscale`, `vscale` (`<float>` or `<integer>`) become one
//!   `<transform name="to_uv">`: translate by the offsets, then scale (S · T, as Mitsuba);
//! - `<lookAt>` becomes `<lookat>` and an `id` starting with `_` becomes `ID…__UPGR`
//!   (`xml.cpp`'s rules; 3.9.1 refuses `<lookAt>` and keeps such ids).
//!
//! Only the elements of the old file change (an included file keeps its own version). The
//! elements keep their file, line and column, so later errors point into the file as it is
//! written; a renamed element's message shows the name the file gave.

use super::elem::Elem;
use std::path::Path;
use std::sync::Arc;

/// Files of a version below this are upgraded.
pub(super) const UPGRADE_BELOW: [u32; 3] = [2, 0, 0];

/// The texture-coordinate parameters that become `to_uv`.
const UV_PARAMS: [&str; 4] = ["uoffset", "voffset", "uscale", "vscale"];

/// Upgrades the elements of `root` that come from `file` (`None`: the scene file itself).
pub(super) fn upgrade(root: &mut Elem, file: Option<&Arc<Path>>) {
    visit(root, file);
}

fn same_file(e: &Elem, file: Option<&Arc<Path>>) -> bool {
    match (&e.file, file) {
        (None, None) => true,
        (Some(a), Some(b)) => Arc::ptr_eq(a, b),
        _ => false,
    }
}

fn visit(e: &mut Elem, file: Option<&Arc<Path>>) {
    let mine = same_file(e, file);
    if mine {
        rename_self(e);
    }
    for c in &mut e.children {
        visit(c, file);
    }
    if mine {
        if e.tag == "bsdf" && e.attr("type") == Some("diffuse") {
            rename_child(e, "diffuse_reflectance", "reflectance");
        }
        uv_to_transform(e);
    }
}

/// The element's own tag, `name` and `id`.
fn rename_self(e: &mut Elem) {
    if e.tag == "lookAt" {
        e.tag = "lookat".into();
    }
    for (key, value) in &mut e.attrs {
        if key == "name" {
            let new = snake_case(value);
            if new != *value {
                e.renamed_from = Some(value.as_str().into());
                *value = new;
            }
        } else if key == "id" && value.starts_with('_') {
            *value = format!("ID{value}__UPGR");
        }
    }
}

/// Renames child parameter `from` to `to`.
fn rename_child(e: &mut Elem, from: &str, to: &str) {
    for c in &mut e.children {
        if let Some((_, v)) = c.attrs.iter_mut().find(|(k, v)| k == "name" && v == from) {
            c.renamed_from.get_or_insert_with(|| from.into());
            *v = to.to_string();
        }
    }
}

/// Mitsuba's camelCase → snake_case (ASCII letters only).
pub(super) fn snake_case(name: &str) -> String {
    let chars: Vec<char> = name.chars().collect();
    let mut out = String::with_capacity(name.len() + 4);
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if i > 0 && chars[i - 1].is_ascii_lowercase() && c.is_ascii_uppercase() {
            out.push('_');
            out.push(c.to_ascii_lowercase());
            while i + 1 < chars.len() && chars[i + 1].is_ascii_uppercase() {
                i += 1;
                out.push(chars[i].to_ascii_lowercase());
            }
        } else {
            out.push(c);
        }
        i += 1;
    }
    out
}

/// `uoffset`, `voffset`, `uscale`, `vscale` children → `<transform name="to_uv">` with a
/// `translate` then a `scale`, placed where the first of them was written.
fn uv_to_transform(e: &mut Elem) {
    let is_uv = |c: &Elem| {
        matches!(c.tag.as_str(), "float" | "integer")
            && c.attr("name").is_some_and(|n| UV_PARAMS.contains(&n))
    };
    let Some(first) = e.children.iter().position(is_uv) else {
        return;
    };
    let at = e.children[first].clone();
    let mut values: [Option<String>; 4] = Default::default();
    e.children.retain(|c| {
        if !is_uv(c) {
            return true;
        }
        let k = UV_PARAMS
            .iter()
            .position(|n| Some(*n) == c.attr("name"))
            .unwrap_or(0);
        values[k] = Some(c.attr("value").unwrap_or("").to_string());
        false
    });
    let [uo, vo, us, vs] = values;
    let op = |tag: &str, x: Option<String>, y: Option<String>, default: &str| Elem {
        tag: tag.into(),
        attrs: vec![
            ("x".into(), x.unwrap_or_else(|| default.into())),
            ("y".into(), y.unwrap_or_else(|| default.into())),
        ],
        children: Vec::new(),
        renamed_from: None,
        ..at.clone()
    };
    let transform = Elem {
        tag: "transform".into(),
        attrs: vec![("name".into(), "to_uv".into())],
        children: vec![op("translate", uo, vo, "0"), op("scale", us, vs, "1")],
        renamed_from: Some("uoffset/voffset/uscale/vscale".into()),
        ..at
    };
    e.children.insert(first, transform);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn snake_case_as_mitsuba() {
        for (a, b) in [
            ("toWorld", "to_world"),
            ("intIOR", "int_ior"),
            ("sampleCount", "sample_count"),
            ("maxDepth", "max_depth"),
            ("fooBARBaz", "foo_barbaz"),
            ("already_snake", "already_snake"),
            ("Upper", "Upper"),
            ("a1B", "a1B"),
            ("", ""),
        ] {
            assert_eq!(snake_case(a), b, "{a}");
        }
    }
}
