//! Markdown tables and number formatting.

/// A Markdown table: a header row, a separator and the rows (right-aligned except the first
/// column).
pub fn markdown(headers: &[&str], rows: &[Vec<String>]) -> String {
    let mut out = format!("| {} |\n", headers.join(" | "));
    let seps: Vec<&str> = (0..headers.len())
        .map(|i| if i == 0 { "---" } else { "---:" })
        .collect();
    out += &format!("|{}|\n", seps.join("|"));
    for r in rows {
        out += &format!("| {} |\n", r.join(" | "));
    }
    out
}

/// A number in three significant digits, scientific outside [0.01, 10⁴); `∞` for infinity.
pub fn num(x: f64) -> String {
    if x.is_nan() {
        "NaN".into()
    } else if x.is_infinite() {
        "∞".into()
    } else if x == 0.0 {
        "0".into()
    } else if (0.01..1e4).contains(&x.abs()) {
        let digits = (2 - x.abs().log10().floor() as i32).max(0) as usize;
        format!("{x:.digits$}")
    } else {
        format!("{x:.2e}")
    }
}

/// An error in ulps: one decimal below 10, whole numbers below 10⁶, else scientific.
pub fn ulps(x: f64) -> String {
    if x.is_infinite() {
        "∞".into()
    } else if x < 10.0 {
        format!("{x:.1}")
    } else if x < 1e6 {
        format!("{x:.0}")
    } else {
        format!("{x:.1e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_shape() {
        let t = markdown(&["a", "b"], &[vec!["1".into(), "2".into()]]);
        assert_eq!(t, "| a | b |\n|---|---:|\n| 1 | 2 |\n");
    }

    #[test]
    fn numbers() {
        assert_eq!(num(1234.6), "1235");
        assert_eq!(num(0.012345), "0.0123");
        assert_eq!(num(3.14159), "3.14");
        assert_eq!(num(1.5e-5), "1.50e-5");
        assert_eq!(num(f64::INFINITY), "∞");
        assert_eq!(ulps(0.43), "0.4");
        assert_eq!(ulps(512.06), "512");
        assert_eq!(ulps(8388607.9), "8.4e6");
    }
}
