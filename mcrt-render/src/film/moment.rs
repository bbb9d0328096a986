//! Mitsuba 3's `moment` integrator's outputs: the per-pixel mean and second moment of the
//! samples in CIE XYZ, written as extra EXR channels beside the image.

use glam::Vec3;

/// Linear sRGB (Rec. 709 primaries, D65 white) to CIE 1931 XYZ, row by row: IEC 61966-2-1
/// (1999), "Colour management — Default RGB colour space — sRGB", the matrix of Mitsuba 3's
/// `srgb_to_xyz` (to its six digits).
const SRGB_TO_XYZ: [[f64; 3]; 3] = [
    [0.412453, 0.357580, 0.180423],
    [0.212671, 0.715160, 0.072169],
    [0.019334, 0.119193, 0.950227],
];

/// `v` (linear sRGB) in CIE XYZ.
#[inline]
pub(crate) fn srgb_to_xyz(v: [f64; 3]) -> [f64; 3] {
    SRGB_TO_XYZ.map(|row| row[0] * v[0] + row[1] * v[1] + row[2] * v[2])
}

/// The squares of the XYZ components of a sample: what the second moment accumulates.
#[inline]
pub(crate) fn xyz_squared(v: Vec3) -> [f64; 3] {
    srgb_to_xyz([v.x as f64, v.y as f64, v.z as f64]).map(|c| c * c)
}

/// The sums a film keeps for the moment channels: per pixel, of the squared XYZ samples.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Moment {
    /// The nested integrator's name, the prefix of the channel names.
    pub name: String,
    pub sum_sq_xyz: Vec<[f64; 3]>,
}

impl Moment {
    /// The channels `NAME.X`, `NAME.Y`, `NAME.Z` (the mean, from the pixel means `mean` in
    /// linear sRGB) and `m2_NAME.X`, `m2_NAME.Y`, `m2_NAME.Z` (the mean of the squares, from
    /// the per-pixel sample counts `count`; `unsampled` where a pixel has none), in that
    /// order, as Mitsuba 3 names them.
    pub(crate) fn channels(
        &self,
        mean: &[Vec3],
        count: &[u32],
        unsampled: f32,
    ) -> Vec<(String, Vec<f32>)> {
        let xyz: Vec<[f64; 3]> = mean
            .iter()
            .map(|m| srgb_to_xyz([m.x as f64, m.y as f64, m.z as f64]))
            .collect();
        let m2: Vec<[f64; 3]> = self
            .sum_sq_xyz
            .iter()
            .zip(count)
            .map(|(s, &n)| {
                if n == 0 {
                    [unsampled as f64; 3]
                } else {
                    s.map(|v| v / n as f64)
                }
            })
            .collect();
        let mut out = Vec::with_capacity(6);
        for (prefix, values) in [("", &xyz), ("m2_", &m2)] {
            for (c, axis) in ["X", "Y", "Z"].into_iter().enumerate() {
                out.push((
                    format!("{prefix}{}.{axis}", self.name),
                    values.iter().map(|v| v[c] as f32).collect(),
                ));
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn white_maps_to_the_d65_white_point() {
        let w = srgb_to_xyz([1.0, 1.0, 1.0]);
        for (got, want) in w.iter().zip([0.950456, 1.0, 1.088754]) {
            assert!(got.is_finite() && (got - want).abs() < 1e-5, "{w:?}");
        }
    }

    #[test]
    fn channels_are_named_and_ordered_as_mitsuba_does() {
        let m = Moment {
            name: "_arg_0".into(),
            sum_sq_xyz: vec![[2.0, 4.0, 6.0], [0.0; 3]],
        };
        let ch = m.channels(&[Vec3::ONE, Vec3::ZERO], &[2, 0], f32::NAN);
        let names: Vec<&str> = ch.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(
            names,
            [
                "_arg_0.X",
                "_arg_0.Y",
                "_arg_0.Z",
                "m2__arg_0.X",
                "m2__arg_0.Y",
                "m2__arg_0.Z"
            ]
        );
        assert_eq!(ch[4].1[0], 2.0);
        assert!(ch[3].1[1].is_nan());
    }
}
