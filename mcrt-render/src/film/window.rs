//! The two ways a render is divided for distributed rendering: by pixel sample indices
//! ([`SampleRange`], `render --samples START..END`) and by pixels ([`Crop`],
//! `render --crop x0,y0,x1,y1`). Both are half-open.

use std::fmt;
use std::str::FromStr;

/// Pixel samples with indices in `[start, end)` of every pixel's samples per pixel: the
/// samples a single render draws for those indices (same seeds, any sampler).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SampleRange {
    /// First sample index.
    pub start: u32,
    /// One past the last sample index.
    pub end: u32,
}

/// A window of pixels `[x0, x1) × [y0, y1)`, `x` from the left and `y` from the top.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Crop {
    /// First column.
    pub x0: u32,
    /// First row.
    pub y0: u32,
    /// One past the last column.
    pub x1: u32,
    /// One past the last row.
    pub y1: u32,
}

/// A sample range or crop window could not be read, or does not fit the render.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum WindowError {
    /// The text is not `START..END` or `x0,y0,x1,y1` with non-negative integers.
    Syntax(String),
    /// The range or window is empty or reaches past the samples per pixel or the image.
    OutOfBounds(String),
}

impl fmt::Display for WindowError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Syntax(m) | Self::OutOfBounds(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for WindowError {}

impl SampleRange {
    /// Every sample of `spp` per pixel.
    pub fn all(spp: u32) -> Self {
        Self { start: 0, end: spp }
    }

    /// Samples in the range (0 if `end <= start`).
    pub fn len(&self) -> u32 {
        self.end.saturating_sub(self.start)
    }

    /// Whether the range holds no sample.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Whether the two ranges share a sample index.
    pub fn overlaps(&self, other: &SampleRange) -> bool {
        self.start < other.end && other.start < self.end
    }

    /// `Ok` if the range is not empty and lies in `[0, spp)`.
    pub fn check(&self, spp: u32) -> Result<(), WindowError> {
        if self.is_empty() || self.end > spp {
            return Err(WindowError::OutOfBounds(format!(
                "samples {self}: the range must be non-empty and lie in 0..{spp} (the samples \
                 per pixel)"
            )));
        }
        Ok(())
    }
}

impl Crop {
    /// The whole of a `width` × `height` image.
    pub fn full(width: u32, height: u32) -> Self {
        Self {
            x0: 0,
            y0: 0,
            x1: width,
            y1: height,
        }
    }

    /// Width in pixels (0 if empty).
    pub fn width(&self) -> u32 {
        self.x1.saturating_sub(self.x0)
    }

    /// Height in pixels (0 if empty).
    pub fn height(&self) -> u32 {
        self.y1.saturating_sub(self.y0)
    }

    /// Pixels in the window.
    pub fn area(&self) -> u64 {
        self.width() as u64 * self.height() as u64
    }

    /// Whether the window holds pixel `(x, y)`.
    pub fn contains(&self, x: u32, y: u32) -> bool {
        (self.x0..self.x1).contains(&x) && (self.y0..self.y1).contains(&y)
    }

    /// The pixels both windows hold, if any.
    pub fn intersection(&self, other: &Crop) -> Option<Crop> {
        let c = Crop {
            x0: self.x0.max(other.x0),
            y0: self.y0.max(other.y0),
            x1: self.x1.min(other.x1),
            y1: self.y1.min(other.y1),
        };
        (c.area() > 0).then_some(c)
    }

    /// `Ok` if the window is not empty and lies inside a `width` × `height` image.
    pub fn check(&self, width: u32, height: u32) -> Result<(), WindowError> {
        if self.area() == 0 || self.x1 > width || self.y1 > height {
            return Err(WindowError::OutOfBounds(format!(
                "crop {self}: the window must be non-empty and lie inside the {width}×{height} \
                 image (x1 ≤ {width}, y1 ≤ {height})"
            )));
        }
        Ok(())
    }
}

impl fmt::Display for SampleRange {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}..{}", self.start, self.end)
    }
}

impl fmt::Display for Crop {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{},{},{},{}", self.x0, self.y0, self.x1, self.y1)
    }
}

/// Reads `START..END`.
///
/// ```
/// use mcrt_render::film::SampleRange;
/// let r: SampleRange = "8..16".parse().unwrap();
/// assert_eq!((r.start, r.end, r.len()), (8, 16, 8));
/// assert!("8-16".parse::<SampleRange>().is_err());
/// ```
impl FromStr for SampleRange {
    type Err = WindowError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || WindowError::Syntax(format!("samples \"{s}\": expected START..END"));
        let (a, b) = s.split_once("..").ok_or_else(bad)?;
        Ok(Self {
            start: a.trim().parse().map_err(|_| bad())?,
            end: b.trim().parse().map_err(|_| bad())?,
        })
    }
}

/// Reads `x0,y0,x1,y1`.
///
/// ```
/// use mcrt_render::film::Crop;
/// let c: Crop = "0,16,32,48".parse().unwrap();
/// assert_eq!((c.width(), c.height()), (32, 32));
/// assert!("0,16,32".parse::<Crop>().is_err());
/// ```
impl FromStr for Crop {
    type Err = WindowError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || WindowError::Syntax(format!("crop \"{s}\": expected x0,y0,x1,y1"));
        let v = s
            .split(',')
            .map(|t| t.trim().parse::<u32>().map_err(|_| bad()))
            .collect::<Result<Vec<_>, _>>()?;
        match v[..] {
            [x0, y0, x1, y1] => Ok(Self { x0, y0, x1, y1 }),
            _ => Err(bad()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_and_windows() {
        let r = SampleRange { start: 4, end: 8 };
        assert!(r.overlaps(&SampleRange { start: 7, end: 9 }));
        assert!(!r.overlaps(&SampleRange { start: 8, end: 9 }));
        assert!(r.check(8).is_ok() && r.check(7).is_err());
        assert!(SampleRange { start: 3, end: 3 }.check(8).is_err());
        let c = Crop::full(4, 3);
        assert_eq!(c.area(), 12);
        assert!(c.check(4, 3).is_ok() && c.check(3, 3).is_err());
        let d: Crop = "2,1,6,2".parse().expect("crop");
        assert_eq!(c.intersection(&d), Some("2,1,4,2".parse().expect("crop")));
        assert_eq!(c.intersection(&"4,0,5,1".parse().expect("crop")), None);
        assert!(d.contains(5, 1) && !d.contains(6, 1));
        for bad in ["1,2,3,4,5", "a,b,c,d", "-1,0,2,2"] {
            assert!(bad.parse::<Crop>().is_err(), "{bad}");
        }
        assert_eq!(
            "0..8".parse::<SampleRange>().map(|r| r.to_string()),
            Ok("0..8".into())
        );
    }
}
