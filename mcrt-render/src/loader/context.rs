//! Shared state of one load: the file name for messages, the folder relative paths are
//! resolved against, and the objects that carry an `id`.

use super::tree::Elem;
use crate::scene_error::{SceneError, SceneErrorKind};
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
    /// The folder that relative file names are resolved against.
    pub base_dir: PathBuf,
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
    /// Collects the ids of `root`'s descendants; a repeated id is an error.
    pub fn new(file: Option<&'a Path>, root: &'a Elem) -> Res<Self> {
        let base_dir = file
            .and_then(Path::parent)
            .map(Path::to_path_buf)
            .unwrap_or_default();
        let mut ctx = Self {
            file,
            base_dir,
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

    /// Resolves `name` against the scene's folder and checks that it is a regular file
    /// that can be opened and read; `magic`, if given, must be the file's first bytes.
    pub fn readable_file(&self, e: &Elem, name: &str, magic: Option<&[u8]>) -> Res<PathBuf> {
        let p = Path::new(name);
        let path = if p.is_absolute() {
            p.to_path_buf()
        } else {
            self.base_dir.join(p)
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
        if name.is_empty() {
            return Err(io_err("empty file name".into()));
        }
        let mut f = crate::io::open_regular(&path).map_err(|x| io_err(x.to_string()))?;
        if let Some(magic) = magic {
            let mut head = vec![0u8; magic.len()];
            f.read_exact(&mut head)
                .map_err(|x| io_err(format!("cannot read its header: {x}")))?;
            if head != magic {
                return Err(io_err("not an OpenEXR file (wrong magic number)".into()));
            }
        }
        Ok(path)
    }
}
