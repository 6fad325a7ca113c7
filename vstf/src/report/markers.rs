//! Expected points marked on a copy of a view, numbered by the row they
//! belong to.

use image::{Rgb, RgbImage};

/// Markers of one row that lie closer than this to one another (pixels,
/// directly or through others of the row) carry the row's number once,
/// beside them: the points on an object under this size get one label.
pub const SMALL_GROUP: f64 = 40.0;

/// The longest arm of a marker's cross (pixels from its centre).
const ARM: i64 = 3;

/// The markers of one row of the legend.
#[derive(Clone, Debug, PartialEq)]
pub struct MarkerGroup {
    /// The number the image and the legend give the row, from 1.
    pub number: usize,
    /// The row's quantity (empty: markers no row names).
    pub row: String,
    /// The markers' pixel positions.
    pub points: Vec<(f64, f64)>,
}

/// The markers grouped by the row each belongs to, numbered from 1 in the
/// order the rows first appear: each row once.
pub fn marker_groups(markers: &[(f64, f64)], rows: &[String]) -> Vec<MarkerGroup> {
    let mut groups: Vec<MarkerGroup> = Vec::new();
    for (k, &p) in markers.iter().enumerate() {
        let row = rows.get(k).cloned().unwrap_or_default();
        match groups.iter_mut().find(|g| g.row == row) {
            Some(g) => g.points.push(p),
            None => groups.push(MarkerGroup {
                number: groups.len() + 1,
                row,
                points: vec![p],
            }),
        }
    }
    groups
}

/// The pixel of a marker.
fn pixel((x, y): (f64, f64)) -> (i64, i64) {
    (x.floor() as i64, y.floor() as i64)
}

/// The arm of the cross at `p`: the longest (at most [`ARM`]) whose cross
/// and outline keep clear of every other marker's, so that markers a few
/// pixels apart stay apart (at 4 pixels or closer, dots).
fn arm(p: (i64, i64), all: &[(i64, i64)]) -> i64 {
    let nearest = all
        .iter()
        .filter(|&&q| q != p)
        .map(|&(x, y)| (x - p.0).abs().max((y - p.1).abs()))
        .min()
        .unwrap_or(i64::MAX);
    (nearest / 2 - 1).clamp(0, ARM)
}

/// The points split where they lie [`SMALL_GROUP`] or more apart: each
/// part holds the points reached from one another in steps under it.
fn clusters(points: &[(i64, i64)]) -> Vec<Vec<(i64, i64)>> {
    let near = |a: (i64, i64), b: (i64, i64)| {
        let (dx, dy) = ((a.0 - b.0) as f64, (a.1 - b.1) as f64);
        dx.hypot(dy) < SMALL_GROUP
    };
    let mut parts: Vec<Vec<(i64, i64)>> = Vec::new();
    for &p in points {
        let (joined, apart): (Vec<_>, Vec<_>) = parts
            .into_iter()
            .partition(|part| part.iter().any(|&q| near(p, q)));
        let mut merged: Vec<(i64, i64)> = joined.into_iter().flatten().collect();
        merged.push(p);
        parts = apart;
        parts.push(merged);
    }
    parts
}

/// Where a part's label goes: beside a lone marker as before, else right
/// of the part's top right corner.
fn label_at(part: &[(i64, i64)]) -> (i64, i64) {
    match part {
        [c] => (c.0 + ARM + 2, c.1 + ARM + 2),
        _ => (
            part.iter().map(|p| p.0).max().unwrap_or(0) + 3,
            part.iter().map(|p| p.1).min().unwrap_or(0),
        ),
    }
}

/// Draws each marker on a copy of the image as a cross in the colour that
/// contrasts with the pixels under it (black on light, white on dark),
/// outlined in the other, its arms shortened where markers crowd (down to
/// a dot) so that none touches another; and numbers the markers of each
/// row once for each part of them closer than [`SMALL_GROUP`] together.
pub fn with_markers(img: &RgbImage, groups: &[MarkerGroup]) -> RgbImage {
    let mut out = img.clone();
    let (w, h) = (i64::from(out.width()), i64::from(out.height()));
    let inside = |(x, y): (i64, i64)| x >= 0 && y >= 0 && x < w && y < h;
    let shown: Vec<Vec<(i64, i64)>> = groups
        .iter()
        .map(|g| {
            let points = g.points.iter().map(|&p| pixel(p));
            points.filter(|&p| inside(p)).collect()
        })
        .collect();
    let all: Vec<(i64, i64)> = shown.iter().flatten().copied().collect();
    for &c in &all {
        cross(&mut out, img, c, arm(c, &all));
    }
    for (g, points) in groups.iter().zip(&shown) {
        for part in clusters(points) {
            let (x, y) = label_at(&part);
            let at = (x.clamp(0, w - 1) as u32, y.clamp(0, h - 1) as u32);
            crate::label::draw_at(&mut out, &g.number.to_string(), at, 1);
        }
    }
    out
}

/// One cross of arm `arm` centred on `c`, in the colour contrasting with
/// `under` there, outlined in the other.
fn cross(out: &mut RgbImage, under: &RgbImage, c: (i64, i64), arm: i64) {
    let (w, h) = (i64::from(out.width()), i64::from(out.height()));
    let inside = |x: i64, y: i64| x >= 0 && y >= 0 && x < w && y < h;
    let p = under.get_pixel(c.0 as u32, c.1 as u32).0;
    let luma = 0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]);
    let (ink, rim) = if luma > 110.0 {
        (Rgb([0, 0, 0]), Rgb([255, 255, 255]))
    } else {
        (Rgb([255, 255, 255]), Rgb([0, 0, 0]))
    };
    let arms = |d: i64| [(c.0 + d, c.1), (c.0, c.1 + d)];
    for d in -arm..=arm {
        for (px, py) in arms(d) {
            for (ox, oy) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
                if inside(px + ox, py + oy) {
                    out.put_pixel((px + ox) as u32, (py + oy) as u32, rim);
                }
            }
        }
    }
    for d in -arm..=arm {
        for (px, py) in arms(d) {
            if inside(px, py) {
                out.put_pixel(px as u32, py as u32, ink);
            }
        }
    }
}
