//! Shared state of one load: the file name for messages, the folders relative paths are
//! resolved against, the objects that carry an `id`, and the warnings so far.

use super::search_path::SearchPath;
use super::tree::Elem;
use crate::scene_error::{SceneError, SceneErrorKind};
use crate::scene_warning::SceneWarning;
use crate::texture::Image;
use std::cell::RefCell;
use std::collections::HashMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The state of one load.
pub(crate) struct Ctx<'a> {
    /// The scene file, for messages.
    pub file: Option<&'a Path>,
    /// The folders that relative file names are resolved against (the scene's `<path>`s,
    /// its folder, the current directory).
    pub search: SearchPath,
    /// Whether a top-level declaration (a `<bsdf>`, `<texture>` or `<volume>` read only
    /// to check it) is being read: a volume texture is accepted there, as Mitsuba accepts
    /// one in a material no shape uses.
    pub declaration: std::cell::Cell<bool>,
    /// Warnings so far, in file order, each once.
    warnings: RefCell<Vec<SceneWarning>>,
    /// Every element with an `id`.
    pub ids: HashMap<String, &'a Elem>,
    /// Texture images read so far, by path and `raw` (a texture used twice is read once).
    images: RefCell<HashMap<(PathBuf, bool), Arc<Image>>>,
    /// The bytes the images in `images` hold (for the memory budget).
    image_bytes: std::cell::Cell<u64>,
}

/// Type alias for results inside the loader.
pub(crate) type Res<T> = Result<T, SceneError>;

impl<'a> Ctx<'a> {
    /// Collects the ids of `root`'s descendants; a repeated id is an error. `search` is
    /// the scene file's final list of folders.
    pub fn new(file: Option<&'a Path>, root: &'a Elem, search: SearchPath) -> Res<Self> {
        let mut ctx = Self {
            file,
            search,
            declaration: std::cell::Cell::new(false),
            warnings: RefCell::default(),
            ids: HashMap::new(),
            images: RefCell::default(),
            image_bytes: std::cell::Cell::new(0),
        };
        ctx.collect(root)?;
        Ok(ctx)
    }

    fn collect(&mut self, e: &'a Elem) -> Res<()> {
        for c in &e.children {
            if c.tag != "ref" {
                if let Some(id) = c.attr("id") {
                    if id.starts_with('_') {
                        return Err(self.err(
                            c,
                            SceneErrorKind::InvalidValue(format!(
                                "id \"{id}\": leading underscores are reserved"
                            )),
                        ));
                    }
                    if self.ids.insert(id.to_string(), c).is_some() {
                        return Err(self.err(c, SceneErrorKind::DuplicateId(id.to_string())));
                    }
                }
            }
            self.collect(c)?;
        }
        Ok(())
    }

    /// The bytes of the images read so far in this load.
    pub fn image_bytes(&self) -> u64 {
        self.image_bytes.get()
    }

    /// The image read from `path` with `raw` earlier in this load, if any.
    pub fn cached_image(&self, path: &Path, raw: bool) -> Option<Arc<Image>> {
        self.images
            .borrow()
            .get(&(path.to_path_buf(), raw))
            .cloned()
    }

    /// Remembers an image read from `path` with `raw`; returns it.
    pub fn cache_image(&self, path: &Path, raw: bool, image: Arc<Image>) -> Arc<Image> {
        let bytes = self.image_bytes.get().saturating_add(image.memory_bytes());
        self.image_bytes.set(bytes);
        self.images
            .borrow_mut()
            .insert((path.to_path_buf(), raw), Arc::clone(&image));
        image
    }

    /// An error located at element `e`.
    pub fn err(&self, e: &Elem, kind: SceneErrorKind) -> SceneError {
        SceneError::new(
            e.file.as_deref().or(self.file),
            Some(e.line),
            Some(e.column),
            Some(e.describe()),
            kind,
        )
    }

    /// Where element `e` was written, for the description's [`Origins`](
    /// crate::description::Origins).
    pub fn origin(&self, e: &Elem) -> crate::description::Origin {
        crate::description::Origin {
            file: e.file.as_deref().or(self.file).map(Path::to_path_buf),
            line: e.line,
            column: e.column,
            element: e.describe().into(),
        }
    }

    /// A warning located at element `e` (given once, however often `e` is read).
    pub fn warn(&self, e: &Elem, message: String) {
        let w = SceneWarning::new(
            e.file.as_deref().or(self.file),
            Some(e.line),
            Some(e.column),
            Some(e.describe()),
            message,
        );
        let mut all = self.warnings.borrow_mut();
        if !all.contains(&w) {
            all.push(w);
        }
    }

    /// The warnings given so far.
    pub fn take_warnings(&self) -> Vec<SceneWarning> {
        std::mem::take(&mut self.warnings.borrow_mut())
    }

    /// Resolves `name` against the scene's folders (the first that holds it; see
    /// [`SearchPath`]) and checks that it is a regular file that can be opened and read;
    /// `magic`, if given, is the file's first bytes and the format's name.
    pub fn readable_file(
        &self,
        e: &Elem,
        name: &str,
        magic: Option<(&[u8], &str)>,
    ) -> Res<PathBuf> {
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
            return Err(self.err(
                e,
                SceneErrorKind::Io {
                    path: PathBuf::from(name),
                    reason,
                },
            ));
        };
        let io_err = |reason: String| {
            self.err(
                e,
                SceneErrorKind::Io {
                    path: path.clone(),
                    reason,
                },
            )
        };
        let mut f = crate::io::open_regular(&path).map_err(|x| io_err(x.to_string()))?;
        if let Some((magic, format)) = magic {
            let mut head = vec![0u8; magic.len()];
            f.read_exact(&mut head)
                .map_err(|x| io_err(format!("cannot read its header: {x}")))?;
            if head != magic {
                return Err(io_err(format!("not {format} file (wrong magic number)")));
            }
        }
        Ok(path)
    }
}
