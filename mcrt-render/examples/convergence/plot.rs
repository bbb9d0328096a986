//! Log–log line plots as PNG (plotters, bitmap backend), labelled with the DejaVu Sans font
//! shipped in `assets/fonts/`.

use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};
use std::path::Path;
use std::sync::Once;

/// DejaVu Sans (Bitstream Vera license, see `assets/fonts/LICENSE`).
static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// One line of a plot.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// Points `(x, y)`; non-positive or non-finite ones are skipped (log axes).
    pub points: Vec<(f64, f64)>,
    /// Drawn dashed and grey, without markers (reference slopes).
    pub guide: bool,
    /// Colour and marker.
    pub look: Look,
}

/// Point markers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Marker {
    /// Filled circle.
    #[default]
    Circle,
    /// Filled triangle.
    Triangle,
    /// Open square.
    Square,
}

/// How a series is drawn: a palette index (else the next free colour) and a marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Look {
    /// Index into the palette.
    pub colour: Option<usize>,
    /// Marker at each point.
    pub marker: Marker,
}

/// Eight colours that stay apart for readers with common colour-vision deficiencies
/// reasonably well (the usual categorical set of plotting tools).
const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

/// A log–log plot.
#[derive(Debug, Clone, PartialEq)]
pub struct Plot {
    /// Caption.
    pub title: String,
    /// x-axis label.
    pub x_label: String,
    /// y-axis label.
    pub y_label: String,
    /// The lines.
    pub series: Vec<Series>,
    /// Factor of empty space above the highest point (room for the legend); 1.5 is snug.
    pub headroom: f64,
}

fn register() -> Result<(), String> {
    static ONCE: Once = Once::new();
    let mut result = Ok(());
    ONCE.call_once(|| {
        result = register_font("sans-serif", FontStyle::Normal, FONT)
            .map_err(|_| "the bundled font does not parse".to_string());
    });
    result
}

/// The usable points of a series on log axes.
fn positive(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let ok = |v: f64| v.is_finite() && v > 0.0;
    points
        .iter()
        .copied()
        .filter(|&(x, y)| ok(x) && ok(y))
        .collect()
}

/// The range of all plotted values along one axis, widened by a factor 1.5 each side.
pub fn log_range(series: &[Series], axis: impl Fn((f64, f64)) -> f64) -> Option<(f64, f64)> {
    let vals = series.iter().flat_map(|s| positive(&s.points)).map(axis);
    let (lo, hi) = vals.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    (lo <= hi).then_some((lo / 1.5, hi * 1.5))
}

/// Draws `plot` into a PNG of `size` pixels.
pub fn draw(plot: &Plot, path: &Path, size: (u32, u32)) -> Result<(), String> {
    register()?;
    let err = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    let xr = log_range(&plot.series, |p| p.0).ok_or("nothing to plot")?;
    let yr = log_range(&plot.series, |p| p.1).ok_or("nothing to plot")?;
    let yr = (yr.0, yr.1 / 1.5 * plot.headroom.max(1.0));
    let root = BitMapBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(&plot.title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(48)
        .y_label_area_size(72)
        .build_cartesian_2d((xr.0..xr.1).log_scale(), (yr.0..yr.1).log_scale())
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc(plot.x_label.as_str())
        .y_desc(plot.y_label.as_str())
        .x_labels(10)
        .y_labels(10)
        .x_label_formatter(&|v| tick(*v))
        .y_label_formatter(&|v| tick(*v))
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(|e| err(&e))?;
    let mut colour = 0;
    for s in &plot.series {
        let pts = positive(&s.points);
        if s.guide {
            let style = ShapeStyle::from(&RGBColor(120, 120, 120)).stroke_width(2);
            chart
                .draw_series(DashedLineSeries::new(pts, 8, 6, style))
                .map_err(|e| err(&e))?
                .label(s.label.as_str())
                .legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], RGBColor(120, 120, 120))
                });
            continue;
        }
        let c = PALETTE[s.look.colour.unwrap_or(colour) % PALETTE.len()];
        colour += 1;
        let marker = s.look.marker;
        chart
            .draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))
            .map_err(|e| err(&e))?
            .label(s.label.as_str())
            .legend(move |(x, y)| {
                EmptyElement::at((x + 10, y))
                    + PathElement::new(vec![(-10, 0), (10, 0)], c.stroke_width(2))
                    + mark(marker, c)
            });
        chart
            .draw_series(pts.iter().map(|&p| EmptyElement::at(p) + mark(marker, c)))
            .map_err(|e| err(&e))?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 13))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))
}

/// A marker centred on the origin of its element.
fn mark<DB: DrawingBackend>(m: Marker, c: RGBColor) -> DynElement<'static, DB, (i32, i32)> {
    match m {
        Marker::Circle => Circle::new((0, 0), 4, c.filled()).into_dyn(),
        Marker::Triangle => TriangleMarker::new((0, 0), 5, c.filled()).into_dyn(),
        Marker::Square => Rectangle::new([(-4, -4), (4, 4)], c.stroke_width(2)).into_dyn(),
    }
}

/// A tick label: plain below 10⁵ and above 10⁻³, else `1e-5` style.
pub fn tick(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    if (1e-3..1e5).contains(&v.abs()) {
        let s = format!("{v:.3}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    } else {
        let s = format!("{v:.1e}");
        s.replace(".0e", "e")
    }
}

/// A guide line `y = y0 · (x / x0)^slope` across `[x0, x1]`.
pub fn slope_guide(label: &str, (x0, y0): (f64, f64), x1: f64, slope: f64) -> Series {
    let n = 16;
    let points = (0..=n)
        .map(|i| {
            let x = x0 * (x1 / x0).powf(i as f64 / n as f64);
            (x, y0 * (x / x0).powf(slope))
        })
        .collect();
    Series {
        label: label.to_string(),
        points,
        guide: true,
        look: Look::default(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn guide_has_the_slope() {
        let g = slope_guide("1/N", (1.0, 1.0), 100.0, -1.0);
        let (a, b) = (g.points[0], g.points[g.points.len() - 1]);
        assert!((b.0 - 100.0).abs() < 1e-9 && (b.1 - 0.01).abs() < 1e-12 && a == (1.0, 1.0));
    }

    #[test]
    fn ticks() {
        assert_eq!(tick(100.0), "100");
        assert_eq!(tick(0.25), "0.25");
        assert_eq!(tick(1e-5), "1e-5");
        assert_eq!(tick(2.5e7), "2.5e7");
    }

    #[test]
    fn range_skips_non_positive_points() {
        let s = Series {
            label: String::new(),
            points: vec![(0.0, 1.0), (2.0, f64::NAN), (3.0, 4.0), (6.0, 2.0)],
            guide: false,
            look: Look::default(),
        };
        let (lo, hi) = log_range(&[s], |p| p.0).expect("two usable points");
        assert!((lo - 2.0).abs() < 1e-12 && (hi - 9.0).abs() < 1e-12);
        assert_eq!(log_range(&[], |p| p.0), None);
    }

    #[test]
    fn draws_a_png() {
        let dir = std::env::temp_dir().join("mcrt-convergence-plot-test");
        std::fs::create_dir_all(&dir).expect("temp dir");
        let path = dir.join("t.png");
        let plot = Plot {
            title: "test ∝ 1/N".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![
                Series {
                    label: "a".into(),
                    points: vec![(1.0, 1.0), (10.0, 0.1)],
                    guide: false,
                    look: Look::default(),
                },
                slope_guide("1/N", (1.0, 2.0), 10.0, -1.0),
            ],
            headroom: 1.5,
        };
        draw(&plot, &path, (400, 300)).expect("drawn");
        let bytes = std::fs::read(&path).expect("written");
        assert!(bytes.len() > 1000 && bytes.starts_with(b"\x89PNG"));
    }
}
