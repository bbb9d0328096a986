//! `docs/scene-format.md`'s parameter tables against the definitions: a table per plugin
//! of [`PLUGINS`], headed ``#### `category type="plugin"` ``, whose rows name exactly the
//! parameters the loader reads.

use super::{ParamDef, PLUGINS};
use std::collections::{BTreeMap, BTreeSet};

const DOC: &str = include_str!("../../../docs/scene-format.md");

/// A table's rows: parameter name → the cells after it (type, default, valid, meaning).
type Rows = BTreeMap<String, Vec<String>>;

/// The tables of the doc: `(category, plugin)` → its rows. A table belongs to the `####`
/// heading above it, if no other table came between.
fn doc_tables(doc: &str) -> Vec<((String, String), Rows)> {
    let mut out: Vec<((String, String), Rows)> = Vec::new();
    // The heading whose table is open, and whether its rows have started.
    let mut current: Option<usize> = None;
    let mut started = false;
    for line in doc.lines() {
        if let Some(head) = line.strip_prefix("#### `") {
            let head = head.trim_end_matches('`');
            let (category, rest) = head.split_once(' ').unwrap_or((head, ""));
            let plugin = rest
                .strip_prefix("type=\"")
                .and_then(|r| r.strip_suffix('"'))
                .unwrap_or("");
            out.push(((category.into(), plugin.into()), Rows::new()));
            current = Some(out.len() - 1);
            started = false;
            continue;
        }
        if line.starts_with('#') {
            current = None;
            continue;
        }
        if !line.starts_with('|') {
            if started {
                current = None;
            }
            continue;
        }
        started = true;
        let (Some(i), Some(cell)) = (current, line.strip_prefix("| `")) else {
            continue;
        };
        let mut cells = cell.split('|').map(|c| c.trim().to_string());
        let name = cells.next().unwrap_or_default();
        let name = name.trim_end_matches('`').to_string();
        let rest: Vec<String> = cells.collect();
        assert!(
            out[i].1.insert(name.clone(), rest).is_none(),
            "{:?}: `{name}` listed twice",
            out[i].0
        );
    }
    out
}

#[test]
fn every_defined_parameter_is_documented_and_every_documented_one_is_defined() {
    let tables = doc_tables(DOC);
    for p in PLUGINS {
        let key = (p.category.to_string(), p.plugin.to_string());
        let Some((_, documented)) = tables.iter().find(|(k, _)| *k == key) else {
            panic!(
                "docs/scene-format.md has no table `#### `{} type=\"{}\"``",
                key.0, key.1
            );
        };
        let defined: BTreeSet<String> = p.params.iter().map(|d| d.name().to_string()).collect();
        let listed: BTreeSet<String> = documented.keys().cloned().collect();
        let undocumented: Vec<_> = defined.difference(&listed).collect();
        let unread: Vec<_> = listed.difference(&defined).collect();
        assert!(
            undocumented.is_empty() && unread.is_empty(),
            "{} \"{}\": read but not in the doc {undocumented:?}; in the doc but not read \
             {unread:?}",
            p.category,
            p.plugin
        );
        for d in p.params {
            let cells = &documented[d.name()];
            assert_eq!(
                cells.first().map(String::as_str),
                Some(d.kind()),
                "{} \"{}\": the type of `{}`",
                p.category,
                p.plugin,
                d.name()
            );
            if let Some(range) = d.float_range() {
                assert_eq!(
                    cells.get(2).map(String::as_str),
                    Some(range),
                    "{}",
                    d.name()
                );
            }
            assert!(!d.doc().is_empty(), "{}", d.name());
        }
    }
    for ((category, plugin), _) in &tables {
        assert!(
            super::plugin(category, plugin).is_some(),
            "docs/scene-format.md has a table for {category} \"{plugin}\", which has no \
             definitions in param_defs"
        );
    }
}

#[test]
fn the_check_finds_a_missing_and_an_extra_parameter() {
    let doc = "#### `integrator type=\"path\"`\nprose\n\n| parameter | x |\n|---|---|\n\
               | `max_depth` | x |\n| `typo` | x |\n\nprose\n\n| `another_table` | x |\n";
    let tables = doc_tables(doc);
    assert_eq!(tables.len(), 1);
    let names: Vec<_> = tables[0].1.keys().map(String::as_str).collect();
    assert_eq!(names, ["max_depth", "typo"]);
    let path = super::plugin("integrator", "path").expect("path has a table");
    assert!(path.params.iter().all(|d| d.name() != "typo"));
    assert!(path.params.iter().any(|d| d.name() == "rr_depth"));
}

/// Each definition's default lies in its own range (a default is never checked otherwise).
#[test]
fn every_default_is_valid() {
    for p in PLUGINS {
        for d in p.params {
            match d {
                ParamDef::Int(i) => assert!(i.check(i.default).is_ok(), "{}", i.name),
                ParamDef::Float(f) => {
                    assert!((f.accept)(f.default).is_ok(), "{}", f.name)
                }
                ParamDef::Roughness(f) => {
                    assert!((f.accept)(f.default.get()).is_ok(), "{}", f.name)
                }
                ParamDef::Choice(c) => assert!(c.choices.contains(&c.default), "{}", c.name),
                ParamDef::Colour(c) => assert!(c.default >= 0.0, "{}", c.name),
                ParamDef::Ior(i) => assert!(i.default > 0.0, "{}", i.name),
                ParamDef::Bool(_) | ParamDef::Other(_) => {}
            }
        }
    }
}
