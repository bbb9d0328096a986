//! Property test: the loader never panics on mutated scene files, and every error names
//! the file and a line.

use mcrt_render::loader::parse_scene;
use proptest::prelude::*;
use proptest::test_runner::{Config as ProptestConfig, RngSeed};
use std::path::Path;

const SCENES: [&str; 6] = [
    "tests/data/cornell-box.xml",
    "tests/data/veach-mis.xml",
    "tests/data/cornell-box-plastic.xml",
    "tests/data/cornell-box-blend-mask.xml",
    "tests/data/meshes.xml",
    "tests/data/tent-crop.xml",
];

/// One edit of the text.
#[derive(Debug, Clone)]
enum Mutation {
    /// Replace the character at a relative position.
    Replace(f64, char),
    /// Insert a character.
    Insert(f64, char),
    /// Delete a character.
    Delete(f64),
    /// Delete a line.
    DeleteLine(f64),
    /// Duplicate a line.
    DuplicateLine(f64),
    /// Swap two lines.
    SwapLines(f64, f64),
    /// Swap the contents of two `value="…"` attributes.
    SwapValues(f64, f64),
}

fn interesting_char() -> impl Strategy<Value = char> {
    prop_oneof![
        prop::sample::select(vec![
            '<', '>', '/', '"', '=', '$', ',', '.', '-', '0', '1', '9', 'e', 'x', ' ', '\n', '&',
            '!', '?', '\0', 'é', '∞',
        ]),
        any::<char>(),
    ]
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let f = 0.0..1.0f64;
    prop_oneof![
        (f.clone(), interesting_char()).prop_map(|(a, c)| Mutation::Replace(a, c)),
        (f.clone(), interesting_char()).prop_map(|(a, c)| Mutation::Insert(a, c)),
        f.clone().prop_map(Mutation::Delete),
        f.clone().prop_map(Mutation::DeleteLine),
        f.clone().prop_map(Mutation::DuplicateLine),
        (f.clone(), f.clone()).prop_map(|(a, b)| Mutation::SwapLines(a, b)),
        (f.clone(), f).prop_map(|(a, b)| Mutation::SwapValues(a, b)),
    ]
}

fn at(len: usize, x: f64) -> usize {
    ((len as f64 * x) as usize).min(len.saturating_sub(1))
}

fn apply(text: &str, m: &Mutation) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    let mut lines: Vec<&str> = text.lines().collect();
    match *m {
        Mutation::Replace(a, c) if !chars.is_empty() => {
            let i = at(chars.len(), a);
            chars[i] = c;
        }
        Mutation::Insert(a, c) => {
            let i = at(chars.len() + 1, a);
            chars.insert(i, c);
        }
        Mutation::Delete(a) if !chars.is_empty() => {
            chars.remove(at(chars.len(), a));
        }
        Mutation::DeleteLine(a) if !lines.is_empty() => {
            lines.remove(at(lines.len(), a));
            return lines.join("\n");
        }
        Mutation::DuplicateLine(a) if !lines.is_empty() => {
            let i = at(lines.len(), a);
            lines.insert(i, lines[i]);
            return lines.join("\n");
        }
        Mutation::SwapLines(a, b) if !lines.is_empty() => {
            let (i, j) = (at(lines.len(), a), at(lines.len(), b));
            lines.swap(i, j);
            return lines.join("\n");
        }
        Mutation::SwapValues(a, b) => return swap_values(text, a, b),
        _ => {}
    }
    chars.into_iter().collect()
}

/// Swaps the contents of two `value="…"` attributes.
fn swap_values(text: &str, a: f64, b: f64) -> String {
    let key = "value=\"";
    let spans: Vec<(usize, usize)> = text
        .match_indices(key)
        .filter_map(|(i, _)| {
            let start = i + key.len();
            text[start..].find('"').map(|len| (start, start + len))
        })
        .collect();
    if spans.len() < 2 {
        return text.to_string();
    }
    let (i, j) = (at(spans.len(), a), at(spans.len(), b));
    let (first, second) = (spans[i.min(j)], spans[i.max(j)]);
    if first == second {
        return text.to_string();
    }
    format!(
        "{}{}{}{}{}",
        &text[..first.0],
        &text[second.0..second.1],
        &text[first.1..second.0],
        &text[first.0..first.1],
        &text[second.1..]
    )
}

fn config(seed: u64) -> ProptestConfig {
    ProptestConfig {
        cases: 3000,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

fn check(scene: usize, mutations: &[Mutation]) -> Result<(), TestCaseError> {
    let path = Path::new(SCENES[scene]);
    let original = std::fs::read_to_string(path).expect("shipped scene");
    let text = mutations.iter().fold(original, |t, m| apply(&t, m));
    match parse_scene(&text, Some(path), &[]) {
        Ok(_) => Ok(()),
        Err(e) => {
            let msg = e.to_string();
            // The scene file, or the file it includes (a duplicated <include> repeats ids
            // that are then reported where they are declared).
            prop_assert!(
                msg.contains(SCENES[scene]) || msg.contains("tests/data/room.xml"),
                "{msg}"
            );
            prop_assert!(msg.contains("line"), "{msg}");
            prop_assert!(e.line.is_some(), "{msg}");
            Ok(())
        }
    }
}

proptest! {
    #![proptest_config(config(0x5eed_4c0a_d3e5))]

    #[test]
    fn mutated_scenes_never_panic(
        scene in 0..SCENES.len(),
        mutations in prop::collection::vec(mutation(), 1..5),
    ) {
        check(scene, &mutations)?;
    }
}

#[test]
fn swapping_values_is_a_real_mutation() {
    let t = "<a value=\"1\"/><b value=\"22\"/>";
    assert_eq!(
        swap_values(t, 0.0, 0.9),
        "<a value=\"22\"/><b value=\"1\"/>"
    );
}

#[test]
fn some_mutations_are_rejected_and_some_accepted() {
    // The property test is only meaningful if both outcomes occur.
    let path = Path::new(SCENES[0]);
    let original = std::fs::read_to_string(path).unwrap();
    let broken = apply(&original, &Mutation::Delete(0.0));
    assert!(parse_scene(&broken, Some(path), &[]).is_err());
    let swapped = original.replace("0.885809", "0.5");
    assert!(parse_scene(&swapped, Some(path), &[]).is_ok());
}
