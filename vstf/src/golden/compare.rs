//! Comparing a view with its golden image: the fuzzy verdict with the worst
//! pixel, the change shown for review, and the difference image.

use super::names::slug;
pub use crate::fixture::Fuzzy;
use image::{Rgb, RgbImage};
use std::fmt;
use std::path::PathBuf;

/// The result of comparing one view with its golden.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Comparison {
    /// Fixture name.
    pub fixture: String,
    /// View name within the fixture.
    pub view: String,
    /// The fixture's stated tolerance.
    pub allowed: Fuzzy,
    /// `None` when there is no golden (or it has another size).
    pub max_diff: Option<u8>,
    /// Number of pixels that differ at all.
    pub differing: u64,
    /// Whether no golden exists for the view.
    pub missing: bool,
    /// Within the tolerance.
    pub pass: bool,
    /// Where the pending actual, expected and diff images were written.
    pub pending: Option<PathBuf>,
    /// The first pixel (column, row) with the largest difference, when
    /// any differs.
    pub worst_at: Option<(u32, u32)>,
    /// The size the view was rendered at.
    pub size: (u32, u32),
    /// The golden image compared with, when there is one.
    pub golden: Option<PathBuf>,
}

impl fmt::Display for Comparison {
    /// One greppable line per image.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let status = if self.pass {
            "pass"
        } else if self.missing {
            "MISSING"
        } else {
            "FAIL"
        };
        write!(
            f,
            "golden {status} fixture={} view={}",
            slug(&self.fixture),
            slug(&self.view)
        )?;
        if let Some(d) = self.max_diff {
            write!(f, " max_diff={d} differing={}", self.differing)?;
        }
        if let (Some((x, y)), false) = (self.worst_at, self.pass) {
            write!(
                f,
                " worst_pixel={x},{y} size={}x{}",
                self.size.0, self.size.1
            )?;
        }
        write!(f, " allowed={}", self.allowed)?;
        if let Some(p) = &self.pending {
            write!(f, " pending={}", p.display())?;
        }
        Ok(())
    }
}

/// How two images of one size differ.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Difference {
    /// The largest channel difference.
    pub max: u8,
    /// The number of pixels that differ at all.
    pub pixels: u64,
    /// The first pixel (column, row) with the largest difference.
    pub worst_at: Option<(u32, u32)>,
}

/// How `actual` differs from `expected`; `None` for images of other sizes.
pub fn compare(actual: &RgbImage, expected: &RgbImage) -> Option<Difference> {
    if actual.dimensions() != expected.dimensions() {
        return None;
    }
    let mut out = Difference {
        max: 0,
        pixels: 0,
        worst_at: None,
    };
    for ((x, y, a), e) in actual.enumerate_pixels().zip(expected.pixels()) {
        let d = (0..3).map(|i| a.0[i].abs_diff(e.0[i])).max().unwrap_or(0);
        if d > 0 {
            out.pixels += 1;
            if d > out.max {
                (out.max, out.worst_at) = (d, Some((x, y)));
            }
        }
    }
    Some(out)
}

/// A faded grey copy of `expected` with every differing pixel in red,
/// brighter for larger differences (amplified x8, at least half bright).
pub fn diff_image(actual: &RgbImage, expected: &RgbImage) -> RgbImage {
    RgbImage::from_fn(actual.width(), actual.height(), |x, y| {
        let a = actual.get_pixel(x, y).0;
        let e = if x < expected.width() && y < expected.height() {
            expected.get_pixel(x, y).0
        } else {
            [0, 0, 0]
        };
        let d = (0..3).map(|i| a[i].abs_diff(e[i])).max().unwrap_or(0);
        if d > 0 {
            Rgb([(128 + u16::from(d) * 8).min(255) as u8, 0, 0])
        } else {
            let grey = (u16::from(e[0]) + u16::from(e[1]) + u16::from(e[2])) / 3;
            let faded = (64 + grey / 4) as u8;
            Rgb([faded, faded, faded])
        }
    })
}

/// Where a pending image differs from its golden: the bounding box of the
/// differing pixels, their number and the largest channel difference.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Change {
    /// Smallest and largest differing column and row: (x0, y0, x1, y1).
    pub bounds: (u32, u32, u32, u32),
    /// Pixels that differ at all.
    pub pixels: u64,
    /// The largest channel difference.
    pub worst: u8,
    /// The image's size.
    pub size: (u32, u32),
}

/// The change from `expected` to `actual` (same size), `None` if none.
pub fn change(actual: &RgbImage, expected: &RgbImage) -> Option<Change> {
    if actual.dimensions() != expected.dimensions() {
        return None;
    }
    let mut c: Option<Change> = None;
    for (x, y, a) in actual.enumerate_pixels() {
        let e = expected.get_pixel(x, y);
        let d = (0..3).map(|i| a.0[i].abs_diff(e.0[i])).max().unwrap_or(0);
        if d == 0 {
            continue;
        }
        let b = c.map_or((x, y, x, y), |c| c.bounds);
        c = Some(Change {
            bounds: (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y)),
            pixels: c.map_or(0, |c| c.pixels) + 1,
            worst: c.map_or(0, |c| c.worst).max(d),
            size: actual.dimensions(),
        });
    }
    c
}

impl fmt::Display for Change {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (x0, y0, x1, y1) = self.bounds;
        write!(
            f,
            "{} pixels differ (worst by {}) within x {x0}..={x1}, y {y0}..={y1} of {}x{}",
            self.pixels, self.worst, self.size.0, self.size.1
        )
    }
}
