//! Textures: Mitsuba 3's `bitmap` (PNG, JPEG, OpenEXR) and `checkerboard`, looked up at a
//! surface point's texture coordinates.
//!
//! A [`Texture`] maps texture coordinates `uv` (Mitsuba's, as
//! [`Geometry::tex_coords`](crate::geometry::Geometry::tex_coords) gives them) through
//! its `to_uv` transform and returns linear RGB. [`BsdfDesc::Textured`] attaches textures to
//! colour (and weight) parameters of a material; the renderer forms the material of each hit
//! with the looked-up values (`scene::render`), so the estimators never see a texture.
//!
//! Conventions established against Mitsuba 3.9.1 (`tests/data/REFERENCES.md`, "Textures"):
//! image row 0 is `v ∈ [0, 1/h)` (no flip); pixel centres at `(i + ½)/w`; 8- and 16-bit
//! PNG and JPEG values are sRGB-decoded at load (before any filtering) unless `raw`; EXR
//! values are linear; `to_uv` is the 2D affine part (x and y rows, x, y and translation
//! columns) of the 4×4 transform; a bitmap used for a single value (`blendbsdf`'s
//! `weight`, `mask`'s `opacity`) gives its luminance, a checkerboard the channel mean of
//! the *other* square's colour (Mitsuba 3.9.1's `eval_1` swaps them); means are the
//! bitmap's mean luminance and the checkerboard's mean channel value.
//!
//! [`BsdfDesc::Textured`]: crate::description::BsdfDesc::Textured

mod decode;
mod image;
mod texels;

pub use decode::{read_image, read_image_beside, srgb_to_linear, MAX_TEXTURE_PIXELS};
pub use image::{FilterType, Image, WrapMode};

use glam::{Affine2, Mat4, Vec2, Vec3};
use std::sync::Arc;

/// Luminance of linear sRGB-primaries RGB (Rec. 709 weights, as Mitsuba 3's `luminance`).
#[inline]
pub fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.212_671, 0.715_160, 0.072_169))
}

/// The 2D affine map of a `to_uv` 4×4 transform: its x and y rows, over the x, y and
/// translation columns (what Mitsuba 3 applies to texture coordinates).
pub fn uv_transform(m: &Mat4) -> Affine2 {
    Affine2::from_cols_array(&[
        m.x_axis.x, m.x_axis.y, m.y_axis.x, m.y_axis.y, m.w_axis.x, m.w_axis.y,
    ])
}

/// Mitsuba's `bitmap`: an image looked up with a filter and a wrap mode.
#[derive(Debug, Clone, PartialEq)]
pub struct Bitmap {
    /// The decoded image (linear RGB), shared between the materials that use it.
    pub image: Arc<Image>,
    /// `filter_type` (default bilinear).
    pub filter: FilterType,
    /// `wrap_mode` (default repeat).
    pub wrap: WrapMode,
    /// `to_uv` (default identity).
    pub to_uv: Affine2,
}

/// Mitsuba's `checkerboard`: `color0` where `frac(u) < ½` and `frac(v) < ½` agree, `color1`
/// elsewhere (two by two squares per unit of `uv`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Checkerboard {
    /// `color0` (default 0.4).
    pub color0: Vec3,
    /// `color1` (default 0.2).
    pub color1: Vec3,
    /// `to_uv` (default identity).
    pub to_uv: Affine2,
}

impl Default for Checkerboard {
    fn default() -> Self {
        Self {
            color0: Vec3::splat(0.4),
            color1: Vec3::splat(0.2),
            to_uv: Affine2::IDENTITY,
        }
    }
}

impl Checkerboard {
    /// Whether `uv` (before `to_uv`) lies on a `color0` square.
    #[inline]
    fn on_color0(&self, uv: Vec2) -> bool {
        let p = self.to_uv.transform_point2(uv);
        let f = p - p.floor();
        (f.x < 0.5) == (f.y < 0.5)
    }

    /// The colour at `uv` (before `to_uv`).
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Vec3 {
        if self.on_color0(uv) {
            self.color0
        } else {
            self.color1
        }
    }

    /// The single value at `uv` as Mitsuba 3.9.1 computes it: the mean of the channels of
    /// the *other* square's colour (its `eval_1` swaps the two colours relative to `eval`;
    /// a blend weight or opacity so textured follows that).
    #[inline]
    pub fn eval_1(&self, uv: Vec2) -> f32 {
        let c = if self.on_color0(uv) {
            self.color1
        } else {
            self.color0
        };
        c.element_sum() / 3.0
    }
}

/// A texture.
#[derive(Debug, Clone, PartialEq)]
pub enum Texture {
    /// `bitmap`.
    Bitmap(Bitmap),
    /// `checkerboard`.
    Checkerboard(Checkerboard),
}

impl Texture {
    /// Linear RGB at texture coordinates `uv`.
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Vec3 {
        match self {
            Self::Bitmap(b) => b
                .image
                .lookup(b.to_uv.transform_point2(uv), b.filter, b.wrap),
            Self::Checkerboard(c) => c.eval(uv),
        }
    }

    /// The value at `uv` where a single number is wanted, as Mitsuba 3.9.1 gives it: a
    /// bitmap's luminance, a checkerboard's [`Checkerboard::eval_1`].
    #[inline]
    pub fn eval_1(&self, uv: Vec2) -> f32 {
        match self {
            Self::Bitmap(_) => luminance(self.eval(uv)),
            Self::Checkerboard(c) => c.eval_1(uv),
        }
    }

    /// The gradient `(∂f/∂u, ∂f/∂v)` of the single value [`Texture::eval_1`] at `uv`, as
    /// Mitsuba 3.9.1's `eval_1_grad` computes it (what `bumpmap` reads): for a bilinear
    /// bitmap, the pixel-space gradient of its interpolated luminance
    /// ([`Image::luminance_gradient`]) carried through `to_uv` by the transpose of its
    /// linear part and scaled per axis by the resolution, `(w, h) ∘ (Aᵀ ∇ₓf)` (exact when
    /// `to_uv` does not mix u and v, or the image is square; Mitsuba's form otherwise); 0
    /// for a `nearest` bitmap and for a checkerboard (which Mitsuba 3.9.1 cannot
    /// differentiate: its `bumpmap` fails on one, and the loader refuses it).
    pub fn eval_1_grad(&self, uv: Vec2) -> Vec2 {
        match self {
            Self::Bitmap(b) if b.filter == FilterType::Bilinear => {
                let d = b
                    .image
                    .luminance_gradient(b.to_uv.transform_point2(uv), b.wrap);
                let a = b.to_uv.matrix2;
                let size = Vec2::new(b.image.width() as f32, b.image.height() as f32);
                size * Vec2::new(a.x_axis.dot(d), a.y_axis.dot(d))
            }
            Self::Bitmap(_) | Self::Checkerboard(_) => Vec2::ZERO,
        }
    }

    /// The mean as Mitsuba 3.9.1 reports it: a bitmap's mean luminance over its pixels, a
    /// checkerboard's mean of its two colours' channel means.
    pub fn mean(&self) -> f32 {
        match self {
            Self::Bitmap(b) => b.image.mean_luminance(),
            Self::Checkerboard(c) => (c.color0 + c.color1).element_sum() / 6.0,
        }
    }
}

/// A material parameter that a texture may drive.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextureParam {
    /// `diffuse`'s `reflectance`.
    Reflectance,
    /// `plastic`'s and `roughplastic`'s `diffuse_reflectance`.
    DiffuseReflectance,
    /// `specular_reflectance` of conductors, dielectrics and plastics.
    SpecularReflectance,
    /// `specular_transmittance` of dielectrics.
    SpecularTransmittance,
    /// `blendbsdf`'s `weight` (the texture's luminance).
    Weight,
    /// `mask`'s `opacity` (the texture's luminance).
    Opacity,
    /// `principled`'s `base_color`.
    BaseColor,
    /// The roughness `alpha` of `roughconductor` and `roughdielectric` (the texture's
    /// luminance; both αᵤ and αᵥ).
    Alpha,
    /// Their roughness `alpha_u` along the shading tangent `dp/du`.
    AlphaU,
    /// Their roughness `alpha_v` along the bitangent.
    AlphaV,
}

impl TextureParam {
    /// Every parameter, for lookups by name.
    pub const ALL: [TextureParam; 10] = [
        Self::Reflectance,
        Self::DiffuseReflectance,
        Self::SpecularReflectance,
        Self::SpecularTransmittance,
        Self::Weight,
        Self::Opacity,
        Self::BaseColor,
        Self::Alpha,
        Self::AlphaU,
        Self::AlphaV,
    ];

    /// The parameter's name in a scene file.
    pub fn name(self) -> &'static str {
        match self {
            Self::Reflectance => "reflectance",
            Self::DiffuseReflectance => "diffuse_reflectance",
            Self::SpecularReflectance => "specular_reflectance",
            Self::SpecularTransmittance => "specular_transmittance",
            Self::Weight => "weight",
            Self::Opacity => "opacity",
            Self::BaseColor => "base_color",
            Self::Alpha => "alpha",
            Self::AlphaU => "alpha_u",
            Self::AlphaV => "alpha_v",
        }
    }

    /// Whether the parameter is one number (the texture's luminance) rather than a colour.
    pub fn is_scalar(self) -> bool {
        matches!(
            self,
            Self::Weight | Self::Opacity | Self::Alpha | Self::AlphaU | Self::AlphaV
        )
    }

    /// Whether the parameter is a microfacet roughness (`alpha`, `alpha_u`, `alpha_v`).
    pub fn is_roughness(self) -> bool {
        matches!(self, Self::Alpha | Self::AlphaU | Self::AlphaV)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Mitsuba 3.9.1's checkerboard at these points (defaults 0.4 and 0.2).
    #[test]
    fn checkerboard_pattern_and_defaults() {
        let c = Checkerboard::default();
        let at = |u, v| c.eval(Vec2::new(u, v)).x;
        let want = [
            ((0.25, 0.25), 0.4),
            ((0.75, 0.25), 0.2),
            ((0.25, 0.75), 0.2),
            ((0.75, 0.75), 0.4),
            ((1.25, 0.25), 0.4),
            ((-0.25, 0.25), 0.2),
        ];
        for ((u, v), w) in want {
            assert_eq!(at(u, v), w, "({u}, {v})");
        }
        let t = Texture::Checkerboard(c);
        let m = t.mean();
        assert!(m.is_finite() && (m - 0.3).abs() < 1e-6);
    }

    /// Mitsuba 3.9.1 with color0 = (0.9, 0.5, 0.1), color1 = 0.1: `eval_1` is 0.1 on the
    /// color0 squares and 0.5 (color0's channel mean) on the others; the mean 0.3.
    #[test]
    fn checkerboard_scalar_value_swaps_colours() {
        let t = Texture::Checkerboard(Checkerboard {
            color0: Vec3::new(0.9, 0.5, 0.1),
            color1: Vec3::splat(0.1),
            to_uv: Affine2::IDENTITY,
        });
        let want = [
            ((0.25, 0.25), 0.1),
            ((0.75, 0.25), 0.5),
            ((0.25, 0.75), 0.5),
            ((1.3, 0.1), 0.1),
        ];
        for ((u, v), w) in want {
            let got = t.eval_1(Vec2::new(u, v));
            assert!(
                got.is_finite() && (got - w).abs() < 1e-6,
                "({u}, {v}): {got}"
            );
        }
        let m = t.mean();
        assert!(m.is_finite() && (m - 0.3).abs() < 1e-6, "{m}");
    }

    /// `to_uv` as Mitsuba applies it: scale (4, 2); translate 0.5 in u; rotate 90° about z.
    #[test]
    fn to_uv_transforms() {
        let with = |m: Mat4| Checkerboard {
            to_uv: uv_transform(&m),
            ..Checkerboard::default()
        };
        let c = with(Mat4::from_scale(Vec3::new(4.0, 2.0, 1.0)));
        let got = [(0.1, 0.1), (0.3, 0.1), (0.1, 0.3), (0.3, 0.6)]
            .map(|(u, v)| c.eval(Vec2::new(u, v)).x);
        assert_eq!(got, [0.4, 0.4, 0.2, 0.4]);
        let c = with(Mat4::from_translation(Vec3::new(0.5, 0.0, 0.0)));
        let got = [(0.1, 0.1), (0.6, 0.1), (0.1, 0.6)].map(|(u, v)| c.eval(Vec2::new(u, v)).x);
        assert_eq!(got, [0.2, 0.4, 0.4]);
        let c = with(Mat4::from_rotation_z(std::f32::consts::FRAC_PI_2));
        let got = [(0.1, 0.1), (0.6, 0.1)].map(|(u, v)| c.eval(Vec2::new(u, v)).x);
        assert_eq!(got, [0.2, 0.4]);
    }

    /// The bump gradient of a linear ramp is its slope: f = 0.1 i at pixel column i of an
    /// 8-pixel row, so ∂f/∂u = 0.1 · 8 anywhere between the outer pixel centres and ∂f/∂v
    /// = 0; a `to_uv` that scales u by 2 doubles it; a `nearest` bitmap has none.
    #[test]
    fn gradient_of_a_ramp_is_its_slope() {
        let px: Vec<Vec3> = (0..16).map(|k| Vec3::splat(0.1 * (k % 8) as f32)).collect();
        let image = Arc::new(Image::new(8, 2, px).unwrap());
        let bitmap = |to_uv, filter| {
            Texture::Bitmap(Bitmap {
                image: image.clone(),
                filter,
                wrap: WrapMode::Clamp,
                to_uv,
            })
        };
        let t = bitmap(Affine2::IDENTITY, FilterType::Bilinear);
        for u in [0.2, 0.35, 0.5, 0.8] {
            let g = t.eval_1_grad(Vec2::new(u, 0.4));
            assert!(
                g.is_finite() && (g - Vec2::new(0.8, 0.0)).length() < 1e-5,
                "{u}: {g}"
            );
        }
        let t = bitmap(
            Affine2::from_scale(Vec2::new(2.0, 1.0)),
            FilterType::Bilinear,
        );
        let g = t.eval_1_grad(Vec2::new(0.2, 0.4));
        assert!(
            g.is_finite() && (g - Vec2::new(1.6, 0.0)).length() < 1e-5,
            "{g}"
        );
        let t = bitmap(Affine2::IDENTITY, FilterType::Nearest);
        assert_eq!(t.eval_1_grad(Vec2::new(0.3, 0.4)), Vec2::ZERO);
    }

    /// On a square image the gradient is the derivative of `eval_1`, through a `to_uv` that
    /// turns and scales (central differences inside a pixel cell, where the bilinear
    /// interpolation is smooth).
    #[test]
    fn gradient_is_the_derivative_of_the_value() {
        let px: Vec<Vec3> = (0..16u32)
            .map(|k| {
                let h = k.wrapping_mul(2_654_435_761) >> 8;
                Vec3::new((h % 97) as f32, (h % 89) as f32, (h % 83) as f32) / 100.0
            })
            .collect();
        let t = Texture::Bitmap(Bitmap {
            image: Arc::new(Image::new(4, 4, px).unwrap()),
            filter: FilterType::Bilinear,
            wrap: WrapMode::Repeat,
            to_uv: Affine2::from_scale_angle_translation(Vec2::new(1.5, 0.7), 0.5, Vec2::ZERO),
        });
        let h = 1e-3;
        for uv in [
            Vec2::new(0.31, 0.62),
            Vec2::new(0.77, 0.18),
            Vec2::new(0.05, 0.93),
        ] {
            let d = |e: Vec2| (t.eval_1(uv + e * h) - t.eval_1(uv - e * h)) / (2.0 * h);
            let want = Vec2::new(d(Vec2::X), d(Vec2::Y));
            let got = t.eval_1_grad(uv);
            assert!(
                got.is_finite() && (got - want).length() < 2e-2 * want.length().max(1.0),
                "{uv}: {got} vs {want}"
            );
        }
    }

    /// Mitsuba 3.9.1: an RGB texture used as one number gives its luminance.
    #[test]
    fn scalar_use_is_luminance() {
        let l = luminance(Vec3::new(0.2, 0.4, 0.9));
        assert!(l.is_finite() && (l - 0.393_550).abs() < 1e-5, "{l}");
        let img = Image::new(2, 1, vec![Vec3::X, Vec3::new(0.2, 0.4, 0.9)]).unwrap();
        let t = Texture::Bitmap(Bitmap {
            image: Arc::new(img),
            filter: FilterType::Nearest,
            wrap: WrapMode::Repeat,
            to_uv: Affine2::IDENTITY,
        });
        let (a, m) = (t.eval_1(Vec2::new(0.25, 0.5)), t.mean());
        assert!(a.is_finite() && (a - 0.212_671).abs() < 1e-6);
        assert!(m.is_finite() && (m - 0.303_111).abs() < 1e-5, "{m}");
    }
}
