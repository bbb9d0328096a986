//! `<spectrum>` values, converted to linear sRGB as Mitsuba 3's RGB variants convert them.
//!
//! A single value `v` is a constant spectrum: `v` for a reflectance or another unitless
//! parameter, and `v` times the sRGB colour of the equal-energy illuminant,
//! (1.2048, 0.9483, 0.9089), for emitted radiance. A list of `wavelength:value` pairs
//! (nm, strictly increasing) is interpolated linearly (zero outside its range), weighted by
//! the CIE 1931 colour-matching functions — times the D65 illuminant, except for emitters —
//! summed at 1000 evenly spaced wavelengths over 360–830 nm, and mapped from XYZ to linear
//! sRGB; reflectances are then clamped to [0, 1], other values to ≥ 0. Checked against
//! Mitsuba 3.9.1's `spectrum_list_to_srgb` (tests below; `docs/scene-format.md`).

use super::cie_tables::{CIE_1931_D65, CIE_MAX, CIE_MIN, CIE_Y_NORMALIZATION};
use super::values::{parse_float, tokens};
use glam::{DVec3, Mat3, Vec3};

/// How a spectrum parameter is converted to RGB.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum SpectrumUse {
    /// A reflectance or transmittance: D65-weighted, clamped to [0, 1].
    Reflectance,
    /// A unitless parameter that may exceed 1 (`eta`, `k`): D65-weighted, clamped to ≥ 0.
    Unbounded,
    /// Emitted radiance or intensity: not D65-weighted, clamped to ≥ 0.
    Emission,
}

/// A parsed `<spectrum value="…">`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Spectrum {
    /// One value at every wavelength.
    Constant(f32),
    /// Samples (wavelength in nm, value), wavelengths strictly increasing.
    Samples(Vec<(f32, f32)>),
}

/// The linear sRGB colour of the equal-energy spectrum of value 1 (XYZ = (1, 1, 1)).
const EQUAL_ENERGY_RGB: Vec3 = Vec3::new(1.204_794, 0.948_292, 0.908_916);

/// XYZ to linear sRGB, rows (IEC 61966-2-1:1999).
const XYZ_TO_SRGB: [[f32; 3]; 3] = [
    [3.240_479, -1.537_15, -0.498_535],
    [-0.969_256, 1.875_991, 0.041_556],
    [0.055_648, -0.204_043, 1.057_311],
];

impl Spectrum {
    /// Parses one number, or `wavelength:value` pairs separated by commas or spaces.
    pub fn parse(s: &str) -> Result<Self, String> {
        let t = tokens(s);
        if t.len() == 1 && !t[0].contains(':') {
            return Ok(Self::Constant(parse_float(t[0])?));
        }
        let mut pairs = Vec::with_capacity(t.len());
        for tok in t {
            let (w, v) = tok.split_once(':').ok_or_else(|| {
                format!("spectrum \"{s}\": \"{tok}\" is not a wavelength:value pair")
            })?;
            let (w, v) = (parse_float(w)?, parse_float(v)?);
            if pairs.last().is_some_and(|&(last, _)| w <= last) {
                return Err(format!("spectrum \"{s}\": wavelengths must increase"));
            }
            pairs.push((w, v));
        }
        if pairs.len() < 2 {
            return Err(format!(
                "spectrum \"{s}\" needs one value or at least two pairs"
            ));
        }
        Ok(Self::Samples(pairs))
    }

    /// The linear sRGB colour of this spectrum used as `usage`.
    pub fn to_rgb(&self, usage: SpectrumUse) -> Vec3 {
        let rgb = match self {
            Self::Constant(v) if usage == SpectrumUse::Emission => *v * EQUAL_ENERGY_RGB,
            Self::Constant(v) => return Vec3::splat(*v),
            Self::Samples(p) => samples_to_rgb(p, usage != SpectrumUse::Emission),
        };
        match usage {
            SpectrumUse::Reflectance => rgb.clamp(Vec3::ZERO, Vec3::ONE),
            _ => rgb.max(Vec3::ZERO),
        }
    }
}

/// ∫ spectrum · (x̄, ȳ, z̄) [· D65] dλ by a 1000-point sum over the table's range, in sRGB.
fn samples_to_rgb(p: &[(f32, f32)], d65: bool) -> Vec3 {
    const STEPS: usize = 1000;
    let (first, last) = (p[0].0, p[p.len() - 1].0);
    let mut xyz = DVec3::ZERO;
    let mut k = 0;
    for i in 0..STEPS {
        let x = CIE_MIN + (i as f32 / (STEPS - 1) as f32) * (CIE_MAX - CIE_MIN);
        if x < first || x > last {
            continue;
        }
        while k + 2 < p.len() && p[k + 1].0 <= x {
            k += 1;
        }
        let ((x0, y0), (x1, y1)) = (p[k], p[k + 1]);
        let y = y0 + (y1 - y0) * (x - x0) / (x1 - x0);
        let t = (x - CIE_MIN) / 5.0;
        let j = (t as usize).min(CIE_1931_D65.len() - 2);
        let f = t - j as f32;
        let row = |c: usize| CIE_1931_D65[j][c] * (1.0 - f) + CIE_1931_D65[j + 1][c] * f;
        let w = if d65 { y * row(3) } else { y };
        xyz += DVec3::new(row(0).into(), row(1).into(), row(2).into()) * f64::from(w);
    }
    let scale = f64::from(CIE_MAX - CIE_MIN) / STEPS as f64 * CIE_Y_NORMALIZATION;
    Mat3::from_cols_array_2d(&XYZ_TO_SRGB).transpose() * (xyz * scale).as_vec3()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: [f32; 3]) -> bool {
        let d = (a - Vec3::from(b)).abs().max_element();
        d.is_finite() && d < 2e-5
    }

    /// Mitsuba 3.9.1 (`scalar_rgb`): `mi.spectrum_list_to_srgb(wavelengths, values,
    /// bounded, d65)` and the values `mi.traverse` reads back from a scene's
    /// `<spectrum>`, clamping included.
    #[test]
    fn matches_mitsuba() {
        let s = Spectrum::parse("400:0.1, 500:0.2, 600:0.3, 700:0.4").unwrap();
        let refl = s.to_rgb(SpectrumUse::Reflectance);
        assert!(close(refl, [0.340779, 0.242912, 0.140303]), "{refl}");
        let emit = s.to_rgb(SpectrumUse::Emission);
        assert!(close(emit, [0.402062, 0.231368, 0.124453]), "{emit}");
        let flat = Spectrum::parse("360:1 830:1").unwrap();
        let e = flat.to_rgb(SpectrumUse::Emission);
        assert!(close(e, [1.20488, 0.948228, 0.909267]), "{e}");
        assert!(close(
            flat.to_rgb(SpectrumUse::Reflectance),
            [0.998983, 0.998872, 0.998802]
        ));
        let narrow = Spectrum::parse("500:10, 510:10").unwrap();
        assert!(close(
            narrow.to_rgb(SpectrumUse::Emission),
            [0.0, 0.712441, 0.133142]
        ));
        let eta = Spectrum::parse("400:2, 700:2").unwrap();
        assert!(close(
            eta.to_rgb(SpectrumUse::Unbounded),
            [1.99068, 1.99951, 1.98982]
        ));
        let three = Spectrum::parse("400:3, 700:3").unwrap();
        assert_eq!(three.to_rgb(SpectrumUse::Reflectance), Vec3::ONE);
        let two = Spectrum::parse("2").unwrap();
        assert!(close(
            two.to_rgb(SpectrumUse::Emission),
            [2.40959, 1.89658, 1.81783]
        ));
        assert_eq!(two.to_rgb(SpectrumUse::Unbounded), Vec3::splat(2.0));
    }

    #[test]
    fn malformed() {
        for bad in [
            "",
            "0.5, 0.2",
            "400:1",
            "500:1, 400:2",
            "400:x, 500:1",
            "a",
            "400:1 400:2",
        ] {
            assert!(Spectrum::parse(bad).is_err(), "{bad}");
        }
    }
}
