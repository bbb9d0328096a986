//! Parsing of the textual values: numbers, booleans, colours, points and matrices.
//! Every function returns a message on failure; the caller adds file, line and element.

use glam::{Mat4, Vec3};

/// Splits a list on commas and whitespace, as Mitsuba's tokenizer does.
pub(crate) fn tokens(s: &str) -> Vec<&str> {
    s.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .collect()
}

/// A finite `f32`.
pub(crate) fn parse_float(s: &str) -> Result<f32, String> {
    let t = s.trim();
    match t.parse::<f32>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(format!("\"{s}\" is not a finite number")),
        Err(_) => Err(format!("could not parse floating point value \"{s}\"")),
    }
}

/// A signed 64-bit integer.
pub(crate) fn parse_int(s: &str) -> Result<i64, String> {
    s.trim()
        .parse::<i64>()
        .map_err(|_| format!("could not parse integer value \"{s}\""))
}

/// `true` or `false`, any case.
pub(crate) fn parse_bool(s: &str) -> Result<bool, String> {
    match s.trim().to_ascii_lowercase().as_str() {
        "true" => Ok(true),
        "false" => Ok(false),
        _ => Err(format!(
            "could not parse boolean value \"{s}\" (must be \"true\" or \"false\")"
        )),
    }
}

/// One value (splat to all three components) or three values.
pub(crate) fn parse_triple(s: &str, what: &str) -> Result<Vec3, String> {
    let t = tokens(s);
    let nums: Vec<f32> = t
        .iter()
        .map(|x| parse_float(x))
        .collect::<Result<_, _>>()
        .map_err(|e| format!("{what} \"{s}\": {e}"))?;
    match nums.len() {
        1 => Ok(Vec3::splat(nums[0])),
        3 => Ok(Vec3::new(nums[0], nums[1], nums[2])),
        n => Err(format!(
            "{what} \"{s}\" needs one or three values, found {n}"
        )),
    }
}

/// Exactly three values.
pub(crate) fn parse_vec3_exact(s: &str, what: &str) -> Result<Vec3, String> {
    let t = tokens(s);
    if t.len() != 3 {
        return Err(format!(
            "{what} \"{s}\" needs exactly three values, found {}",
            t.len()
        ));
    }
    parse_triple(s, what)
}

/// A row-major 4×4 (16 values) or 3×3 (9 values, linear part) matrix.
pub(crate) fn parse_matrix(s: &str) -> Result<Mat4, String> {
    let t = tokens(s);
    let nums: Vec<f32> = t
        .iter()
        .map(|x| parse_float(x))
        .collect::<Result<_, _>>()
        .map_err(|e| format!("matrix: {e}"))?;
    let mut m = [[0.0f32; 4]; 4];
    match nums.len() {
        16 => {
            for (i, v) in nums.iter().enumerate() {
                m[i / 4][i % 4] = *v;
            }
        }
        9 => {
            for (i, v) in nums.iter().enumerate() {
                m[i / 3][i % 3] = *v;
            }
            m[3][3] = 1.0;
        }
        n => return Err(format!("matrix needs 16 or 9 values, found {n}")),
    }
    // `m` is row-major; glam's from_cols_array_2d takes columns, so transpose.
    Ok(Mat4::from_cols_array_2d(&m).transpose())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers() {
        assert_eq!(parse_float(" 1e-3 "), Ok(1e-3));
        assert!(parse_float("nan").is_err());
        assert!(parse_float("inf").is_err());
        assert!(parse_float("1.0.0").is_err());
        assert_eq!(parse_int("-1"), Ok(-1));
        assert!(parse_int("1.5").is_err());
        assert_eq!(parse_bool("TRUE"), Ok(true));
        assert!(parse_bool("yes").is_err());
    }

    #[test]
    fn triples_and_matrices() {
        assert_eq!(parse_triple("0.5", "rgb"), Ok(Vec3::splat(0.5)));
        assert_eq!(parse_triple("1, 2 ,3", "rgb"), Ok(Vec3::new(1.0, 2.0, 3.0)));
        assert!(parse_triple("1, 2", "rgb").is_err());
        assert!(parse_vec3_exact("1", "origin").is_err());
        let m = parse_matrix("1 0 0 5  0 1 0 6  0 0 1 7  0 0 0 1").unwrap();
        assert_eq!(m.w_axis, glam::Vec4::new(5.0, 6.0, 7.0, 1.0));
        let m3 = parse_matrix("0 -1 0 1 0 0 0 0 1").unwrap();
        assert_eq!(m3.transform_vector3(Vec3::X), Vec3::Y);
        assert!(parse_matrix("1 2 3").is_err());
    }
}
