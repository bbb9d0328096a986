//! The folders file names resolve against, as Mitsuba 3's file resolver keeps them: a
//! list tried first to last. A scene file starts with its own folder and the current
//! directory; each `<path value="…"/>` directly inside `<scene>` puts its folder in front
//! (so the last one declared is tried first). An `<include>`d file's list is the including
//! file's list as it stands at the `<include>`, with the included file's folder in front;
//! its own `<path>`s stay in its list. Meshes, textures and environment maps — those in
//! included files too — resolve against the main scene file's final list, since Mitsuba 3
//! builds every object after the whole file is read (checked with Mitsuba 3.9.1,
//! `src/core/parser.cpp`: `TagType::Resource` and `parse_file_impl`).

use crate::scene_error::{clip, MAX_LISTED_FOLDERS};
use std::path::{Path, PathBuf};

/// An ordered list of folders.
#[derive(Debug, Clone, Default)]
pub(crate) struct SearchPath {
    folders: Vec<PathBuf>,
}

impl SearchPath {
    /// The list of a scene file at `file`: its folder, then the current directory (just
    /// the current directory for a scene without a file, or one in it).
    pub fn for_scene(file: Option<&Path>) -> Self {
        let folder = file.and_then(Path::parent).map(Path::to_path_buf);
        let mut folders = Vec::new();
        match folder {
            Some(f) if !f.as_os_str().is_empty() => {
                folders.push(f);
                if let Ok(cwd) = std::env::current_dir() {
                    folders.push(cwd);
                }
            }
            _ => folders.push(PathBuf::new()),
        }
        Self { folders }
    }

    /// This list with `folder` in front (a `<path>`, or an included file's folder).
    pub fn prepend(&mut self, folder: PathBuf) {
        self.folders.insert(0, folder);
    }

    /// The first `folder/name` that exists, or an absolute `name` as it is; `None` if no
    /// folder holds it.
    pub fn resolve(&self, name: &Path) -> Option<PathBuf> {
        if name.is_absolute() {
            return Some(name.to_path_buf());
        }
        self.folders
            .iter()
            .map(|f| f.join(name))
            .find(|p| std::fs::metadata(p).is_ok())
    }

    /// The folders tried, for messages: `"a", "b"` (the current directory as `.`), each
    /// clipped as errors quote text, at most [`MAX_LISTED_FOLDERS`] of them.
    pub fn describe(&self) -> String {
        let mut shown: Vec<String> = self
            .folders
            .iter()
            .take(MAX_LISTED_FOLDERS)
            .map(|f| {
                if f.as_os_str().is_empty() {
                    "\".\"".to_string()
                } else {
                    format!("\"{}\"", clip(&f.display().to_string()))
                }
            })
            .collect();
        if self.folders.len() > MAX_LISTED_FOLDERS {
            shown.push(format!(
                "and {} more",
                self.folders.len() - MAX_LISTED_FOLDERS
            ));
        }
        shown.join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn last_prepended_is_tried_first() {
        let dir = std::env::temp_dir().join(format!("mcrt-search-{}", std::process::id()));
        for sub in ["a", "b"] {
            std::fs::create_dir_all(dir.join(sub)).unwrap();
            std::fs::write(dir.join(sub).join("m.obj"), sub).unwrap();
        }
        let mut s = SearchPath::for_scene(Some(&dir.join("scene.xml")));
        assert_eq!(s.resolve(Path::new("a/m.obj")), Some(dir.join("a/m.obj")));
        s.prepend(dir.join("a"));
        s.prepend(dir.join("b"));
        assert_eq!(s.resolve(Path::new("m.obj")), Some(dir.join("b/m.obj")));
        assert_eq!(s.resolve(Path::new("none.obj")), None);
        assert!(s
            .describe()
            .starts_with(&format!("\"{}\"", dir.join("b").display())));
        std::fs::remove_dir_all(&dir).ok();
    }
}
