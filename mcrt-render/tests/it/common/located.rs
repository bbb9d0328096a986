//! The located-error check of the loader tests: an error the loader reports for a scene
//! given under a made-up file name names that file, the line, the element and what is
//! wrong.

use mcrt_render::loader::SceneError;

/// Asserts that `e` is at `line` and that its message names `file`, `line N`, `element`
/// and `words`.
pub fn check_located(e: &SceneError, file: &str, line: u32, element: &str, words: &str) {
    let msg = e.to_string();
    assert_eq!(e.line, Some(line), "{msg}");
    assert!(msg.contains(file), "{msg}");
    assert!(msg.contains(&format!("line {line}")), "{msg}");
    assert!(msg.contains(element), "{msg}");
    assert!(msg.contains(words), "{msg}");
}
