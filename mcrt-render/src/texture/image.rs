//! A texture image (its pixels as the file stores them, [`Texels`]) and its lookup at texture coordinates: Mitsuba 3's
//! `bitmap` filters (`nearest`, `bilinear`) and wrap modes (`repeat`, `mirror`, `clamp`).

use super::texels::Texels;
use glam::{Vec2, Vec3};
use std::borrow::Cow;

/// How a lookup outside `[0, 1)²` maps back onto the image (Mitsuba's `wrap_mode`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum WrapMode {
    /// Tile the image (the default).
    #[default]
    Repeat,
    /// Tile it mirrored: every other copy is flipped.
    Mirror,
    /// Repeat the edge pixels.
    Clamp,
}

impl WrapMode {
    /// Parses Mitsuba's names `repeat`, `mirror` and `clamp`.
    pub fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "repeat" => Self::Repeat,
            "mirror" => Self::Mirror,
            "clamp" => Self::Clamp,
            _ => return None,
        })
    }

    /// The pixel index that index `i` (any integer) reads in a row of `n ≥ 1` pixels.
    #[inline]
    pub fn index(self, i: i64, n: u32) -> usize {
        let n = i64::from(n.max(1));
        let k = match self {
            Self::Repeat => i.rem_euclid(n),
            Self::Clamp => i.clamp(0, n - 1),
            Self::Mirror => {
                let k = i.rem_euclid(2 * n);
                if k >= n {
                    2 * n - 1 - k
                } else {
                    k
                }
            }
        };
        k as usize
    }
}

/// How pixels are reconstructed between their centres (Mitsuba's `filter_type`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FilterType {
    /// Linear interpolation of the four nearest pixel centres (the default).
    #[default]
    Bilinear,
    /// The pixel the point falls in.
    Nearest,
}

impl FilterType {
    /// Parses Mitsuba's names `bilinear` and `nearest`.
    pub fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "bilinear" => Self::Bilinear,
            "nearest" => Self::Nearest,
            _ => return None,
        })
    }
}

/// Largest pixel coordinate a lookup computes with (2³⁰).
const LIMIT: f32 = 1_073_741_824.0;

/// Pixels read as linear RGB, row-major from the top-left, kept in the file's precision
/// (8-bit values as bytes, half floats as halves) and converted at lookup. Texture coordinate `(u, v)` lies in
/// pixel `(⌊u·w⌋, ⌊v·h⌋)`: `v = 0` is the top row, with no flip (as Mitsuba 3 reads
/// images; its `obj` loader flips the files' `v` instead).
#[derive(Clone, PartialEq)]
pub struct Image {
    width: u32,
    height: u32,
    pixels: Texels,
}

/// The size and a hash of the pixels (FNV-1a of their linear values), not every pixel: a
/// scene's identity is hashed from its description's `Debug` text, which must not grow to
/// gigabytes with a large texture.
impl std::fmt::Debug for Image {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut h = 0xcbf2_9ce4_8422_2325u64;
        for i in 0..self.pixels.len() {
            for c in self.pixels.get(i).to_array() {
                for b in c.to_bits().to_le_bytes() {
                    h = (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
                }
            }
        }
        f.debug_struct("Image")
            .field("width", &self.width)
            .field("height", &self.height)
            .field("pixels_fnv1a", &format_args!("{h:016x}"))
            .finish()
    }
}

impl Image {
    /// An image of `width × height` pixels; `None` unless both are at least 1 and
    /// `pixels` holds exactly their product.
    pub fn new(width: u32, height: u32, pixels: Vec<Vec3>) -> Option<Self> {
        Self::from_texels(width, height, Texels::Linear(pixels))
    }

    /// [`Image::new`] of pixels in any precision.
    pub(crate) fn from_texels(width: u32, height: u32, pixels: Texels) -> Option<Self> {
        let n = (width as usize).checked_mul(height as usize)?;
        (width > 0 && height > 0 && pixels.len() == n).then_some(Self {
            width,
            height,
            pixels,
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The pixels in linear RGB, row-major from the top-left (converted from the file's
    /// precision unless they are floats already).
    pub fn pixels(&self) -> Cow<'_, [Vec3]> {
        match &self.pixels {
            Texels::Linear(v) => Cow::Borrowed(v),
            t => Cow::Owned((0..t.len()).map(|i| t.get(i)).collect()),
        }
    }

    /// The bytes its pixels take (for the memory budget).
    pub fn memory_bytes(&self) -> u64 {
        crate::memory::bytes(self.pixels.len() as u64, self.pixels.pixel_bytes())
    }

    #[inline]
    fn texel(&self, x: i64, y: i64, wrap: WrapMode) -> Vec3 {
        let (x, y) = (wrap.index(x, self.width), wrap.index(y, self.height));
        self.pixels.get(y * self.width as usize + x)
    }

    /// The reconstructed value at texture coordinates `uv`. Bilinear: pixel centres sit at
    /// `((i + ½)/w, (j + ½)/h)` and the four around `uv` are weighted by the usual tent
    /// weights, each index wrapped by `wrap`. A non-finite `uv` reads pixel (0, 0).
    #[inline]
    pub fn lookup(&self, uv: Vec2, filter: FilterType, wrap: WrapMode) -> Vec3 {
        // Far outside [0, 1)² every index is meaningless in f32 anyway; the bound keeps the
        // integer arithmetic below in range.
        let uv = if uv.is_finite() { uv } else { Vec2::ZERO };
        let size = Vec2::new(self.width as f32, self.height as f32);
        let bound = Vec2::splat(LIMIT);
        match filter {
            FilterType::Nearest => {
                let p = (uv * size).floor().clamp(-bound, bound);
                self.texel(p.x as i64, p.y as i64, wrap)
            }
            FilterType::Bilinear => {
                let p = (uv * size - 0.5).clamp(-bound, bound);
                let p0 = p.floor();
                let f = p - p0;
                let (x, y) = (p0.x as i64, p0.y as i64);
                let top = self.texel(x, y, wrap) * (1.0 - f.x) + self.texel(x + 1, y, wrap) * f.x;
                let bottom =
                    self.texel(x, y + 1, wrap) * (1.0 - f.x) + self.texel(x + 1, y + 1, wrap) * f.x;
                top * (1.0 - f.y) + bottom * f.y
            }
        }
    }

    /// The gradient `(∂f/∂x, ∂f/∂y)` of `f`, the bilinear interpolation of the pixels'
    /// luminance, at texture coordinates `uv`, per unit of the pixel coordinates
    /// `(x, y) = (u·w − ½, v·h − ½)` (the derivative of the tent weights of
    /// [`Image::lookup`], as Mitsuba 3's `bitmap::eval_1_grad` takes it; a non-finite `uv`
    /// reads pixel (0, 0)'s neighbourhood).
    pub fn luminance_gradient(&self, uv: Vec2, wrap: WrapMode) -> Vec2 {
        let uv = if uv.is_finite() { uv } else { Vec2::ZERO };
        let size = Vec2::new(self.width as f32, self.height as f32);
        let bound = Vec2::splat(LIMIT);
        let p = (uv * size - 0.5).clamp(-bound, bound);
        let p0 = p.floor();
        let f = p - p0;
        let (x, y) = (p0.x as i64, p0.y as i64);
        let lum = |dx: i64, dy: i64| super::luminance(self.texel(x + dx, y + dy, wrap));
        let (f00, f10, f01, f11) = (lum(0, 0), lum(1, 0), lum(0, 1), lum(1, 1));
        Vec2::new(
            (1.0 - f.y) * (f10 - f00) + f.y * (f11 - f01),
            (1.0 - f.x) * (f01 - f00) + f.x * (f11 - f10),
        )
    }

    /// The mean luminance of the pixels (what Mitsuba's `bitmap` reports as its mean).
    pub fn mean_luminance(&self) -> f32 {
        let sum: f64 = (0..self.pixels.len())
            .map(|i| f64::from(super::luminance(self.pixels.get(i))))
            .sum();
        (sum / self.pixels.len() as f64) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 2 × 2: red, green / blue, grey 0.5.
    fn image() -> Image {
        let px = vec![Vec3::X, Vec3::Y, Vec3::Z, Vec3::splat(0.5)];
        Image::new(2, 2, px).unwrap()
    }

    fn close(a: Vec3, b: Vec3) -> bool {
        a.is_finite() && (a - b).abs().max_element() < 1e-6
    }

    #[test]
    fn wrap_indices() {
        let idx = |w: WrapMode| [-3, -2, -1, 0, 1, 2, 3, 4].map(|i| w.index(i, 2));
        assert_eq!(idx(WrapMode::Repeat), [1, 0, 1, 0, 1, 0, 1, 0]);
        assert_eq!(idx(WrapMode::Clamp), [0, 0, 0, 0, 1, 1, 1, 1]);
        assert_eq!(idx(WrapMode::Mirror), [1, 1, 0, 0, 1, 1, 0, 0]);
        assert_eq!(WrapMode::Mirror.index(5, 3), 0);
        assert_eq!(WrapMode::Mirror.index(3, 3), 2);
    }

    /// Pixel centres return the pixel; v = 0.25 is the top row (no flip).
    #[test]
    fn centres_and_orientation() {
        let im = image();
        for f in [FilterType::Bilinear, FilterType::Nearest] {
            let at = |u, v| im.lookup(Vec2::new(u, v), f, WrapMode::Repeat);
            assert!(close(at(0.25, 0.25), Vec3::X));
            assert!(close(at(0.75, 0.25), Vec3::Y));
            assert!(close(at(0.25, 0.75), Vec3::Z));
            assert!(close(at(0.75, 0.75), Vec3::splat(0.5)));
        }
    }

    /// Hand-computed bilinear weights, the values Mitsuba 3.9.1 returns for the same image
    /// (scripts recorded in tests/data/REFERENCES.md, "Textures").
    #[test]
    fn bilinear_weights_and_wraps() {
        let im = image();
        let bl = |u, v, w| im.lookup(Vec2::new(u, v), FilterType::Bilinear, w);
        // The centre: the mean of all four.
        let mean = (Vec3::X + Vec3::Y + Vec3::Z + Vec3::splat(0.5)) / 4.0;
        assert!(close(bl(0.5, 0.5, WrapMode::Repeat), mean));
        // u = 0.4 on the top row: x = 0.3, weights 0.7 (red), 0.3 (green).
        assert!(close(
            bl(0.4, 0.25, WrapMode::Repeat),
            Vec3::new(0.7, 0.3, 0.0)
        ));
        // u = 1.1: x = 1.7 between pixel 1 (green) and pixel 2, which repeat reads as red,
        // clamp and mirror as green.
        assert!(close(
            bl(1.1, 0.25, WrapMode::Repeat),
            Vec3::new(0.7, 0.3, 0.0)
        ));
        assert!(close(bl(1.1, 0.25, WrapMode::Clamp), Vec3::Y));
        assert!(close(bl(1.1, 0.25, WrapMode::Mirror), Vec3::Y));
        // u = 1.6 on the bottom row: x = 2.7; mirror reads pixels 1 then 0 (grey, blue).
        let m = Vec3::splat(0.5) * 0.3 + Vec3::Z * 0.7;
        assert!(close(bl(1.6, 0.75, WrapMode::Mirror), m));
        // The corner (0, 0): repeat averages all four, clamp reads red.
        assert!(close(bl(0.0, 0.0, WrapMode::Repeat), mean));
        assert!(close(bl(0.0, 0.0, WrapMode::Clamp), Vec3::X));
    }

    #[test]
    fn nearest_wraps_and_bad_uv() {
        let im = image();
        let nn = |u, v, w| im.lookup(Vec2::new(u, v), FilterType::Nearest, w);
        assert!(close(nn(1.1, 0.25, WrapMode::Repeat), Vec3::X));
        assert!(close(nn(-0.1, 0.25, WrapMode::Repeat), Vec3::Y));
        assert!(close(nn(-0.1, 0.25, WrapMode::Clamp), Vec3::X));
        assert!(close(nn(-0.1, 0.25, WrapMode::Mirror), Vec3::X));
        assert!(close(nn(f32::NAN, 0.25, WrapMode::Repeat), Vec3::X));
        for w in [WrapMode::Repeat, WrapMode::Mirror, WrapMode::Clamp] {
            for f in [FilterType::Nearest, FilterType::Bilinear] {
                let far = im.lookup(Vec2::new(1e30, -1e30), f, w);
                assert!(far.is_finite() && far.max_element() <= 1.0, "{far}");
            }
        }
    }

    #[test]
    fn constructor_checks_size() {
        assert!(Image::new(0, 1, vec![]).is_none());
        assert!(Image::new(2, 1, vec![Vec3::ZERO]).is_none());
        assert!(Image::new(1, 1, vec![Vec3::ZERO]).is_some());
    }
}
