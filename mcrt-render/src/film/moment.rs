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

/// The sums a film keeps for the moment channels: per pixel, of the squared XYZ samples
/// of the first nested integrator (whose mean is the image), and the sums of the further
/// nested integrators.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Moment {
    /// The nested integrator's name, the prefix of the channel names.
    pub name: String,
    pub sum_sq_xyz: Vec<[f64; 3]>,
    /// The further nested integrators, in file order.
    pub more: Vec<MoreSums>,
}

/// A further nested integrator's per-pixel sums: of its samples (linear sRGB) and of their
/// squared XYZ components. Every nested integrator takes every pixel sample, so the
/// film's counts are its counts.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct MoreSums {
    /// Its name, the prefix of its channel names.
    pub name: String,
    pub sum: Vec<[f64; 3]>,
    pub sum_sq_xyz: Vec<[f64; 3]>,
}

impl Moment {
    /// The channels `NAME.X`, `NAME.Y`, `NAME.Z` (the mean, from the pixel means `mean` in
    /// linear sRGB) for each nested integrator, then `m2_NAME.X`, `m2_NAME.Y`, `m2_NAME.Z`
    /// (the mean of the squares, from the per-pixel sample counts `count`; `unsampled`
    /// where a pixel has none) for each, in that order, as Mitsuba 3 names and orders them
    /// (its `moment` integrator's `aov_names`).
    pub(crate) fn channels(
        &self,
        mean: &[Vec3],
        count: &[u32],
        unsampled: f32,
    ) -> Vec<(String, Vec<f32>)> {
        let to_xyz = |m: &Vec3| srgb_to_xyz([m.x as f64, m.y as f64, m.z as f64]);
        let mut means = vec![(&self.name, mean.iter().map(to_xyz).collect::<Vec<_>>())];
        let mut m2s = vec![(&self.name, mean_of(&self.sum_sq_xyz, count, unsampled))];
        for m in &self.more {
            // As the film's own mean is formed (`Film::mean_or`).
            let more_mean: Vec<Vec3> = m
                .sum
                .iter()
                .zip(count)
                .map(|(s, &n)| match n {
                    0 => Vec3::splat(unsampled),
                    n => Vec3::from(s.map(|v| (v / n as f64) as f32)),
                })
                .collect();
            means.push((&m.name, more_mean.iter().map(to_xyz).collect()));
            m2s.push((&m.name, mean_of(&m.sum_sq_xyz, count, unsampled)));
        }
        let mut out = Vec::with_capacity(6 * means.len());
        for (prefix, list) in [("", &means), ("m2_", &m2s)] {
            for (name, values) in list {
                for (c, axis) in ["X", "Y", "Z"].into_iter().enumerate() {
                    out.push((
                        format!("{prefix}{name}.{axis}"),
                        values.iter().map(|v| v[c] as f32).collect(),
                    ));
                }
            }
        }
        out
    }
}

/// The per-pixel means of the sums `sum` over the counts `count`; `unsampled` where a
/// pixel has no sample.
fn mean_of(sum: &[[f64; 3]], count: &[u32], unsampled: f32) -> Vec<[f64; 3]> {
    sum.iter()
        .zip(count)
        .map(|(s, &n)| {
            if n == 0 {
                [unsampled as f64; 3]
            } else {
                s.map(|v| v / n as f64)
            }
        })
        .collect()
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
            more: Vec::new(),
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

#[cfg(test)]
mod more_tests {
    use super::*;

    /// With several nested integrators, Mitsuba 3.9.1 names and orders the channels so
    /// (`aov_names()` of a `moment` around unnamed `path` and `direct`, a `path` named `c`
    /// and an unnamed `direct`, read from Mitsuba 3.9.1 in Python): every mean first, then
    /// every second moment, each in file order.
    #[test]
    fn several_nested_integrators_are_named_and_ordered_as_mitsuba_does() {
        let more = |name: &str, v: f64| MoreSums {
            name: name.into(),
            sum: vec![[v, v, v]],
            sum_sq_xyz: vec![[v; 3]],
        };
        let m = Moment {
            name: "_arg_0".into(),
            sum_sq_xyz: vec![[1.0; 3]],
            more: vec![more("_arg_1", 2.0), more("c", 4.0), more("_arg_2", 6.0)],
        };
        let ch = m.channels(&[Vec3::ONE], &[2], f32::NAN);
        let names: Vec<&str> = ch.iter().map(|(n, _)| n.as_str()).collect();
        let mitsuba = [
            "_arg_0.X",
            "_arg_0.Y",
            "_arg_0.Z",
            "_arg_1.X",
            "_arg_1.Y",
            "_arg_1.Z",
            "c.X",
            "c.Y",
            "c.Z",
            "_arg_2.X",
            "_arg_2.Y",
            "_arg_2.Z",
            "m2__arg_0.X",
            "m2__arg_0.Y",
            "m2__arg_0.Z",
            "m2__arg_1.X",
            "m2__arg_1.Y",
            "m2__arg_1.Z",
            "m2_c.X",
            "m2_c.Y",
            "m2_c.Z",
            "m2__arg_2.X",
            "m2__arg_2.Y",
            "m2__arg_2.Z",
        ];
        assert_eq!(names, mitsuba);
        // `c`'s mean: a sum of 4 over 2 samples, white 2 in XYZ; its second moment 4/2.
        let y = ch[7].1[0];
        assert!(y.is_finite() && (y - 2.0).abs() < 1e-5, "{y}");
        assert_eq!(ch[19].1[0], 2.0);
    }
}
