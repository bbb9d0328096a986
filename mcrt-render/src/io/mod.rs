//! Reading files from users, at the bottom of the crate: regular files only and never more
//! than a stated number of bytes ([`MAX_SCENE_BYTES`], [`MAX_OBJ_BYTES`]), and OpenEXR
//! and Radiance RGBE images with a bound on their pixels. The loader, the mesh readers, textures and the
//! environment map all read through here.

mod exr;
mod file;
mod rgbe;

pub(crate) use exr::err;
pub use exr::{read_exr, read_exr_at_most, ImageError};
pub(crate) use file::{canonical, open_regular, read_capped};
pub use file::{MAX_OBJ_BYTES, MAX_SCENE_BYTES};
pub(crate) use rgbe::{is_rgbe, read_rgbe};
