//! Sub-pixel edges along scanlines.
//!
//! An edge between two flat-coloured regions is located by the area method:
//! with anti-aliasing, a pixel's value is the coverage-weighted mix of the
//! two colours (images are stored linearly), so the coverages summed across
//! the transition give the boundary's position to a fraction of a pixel.

use glam::DVec3;
use image::RgbImage;

/// The colour of pixel (x, y) in [0, 1]^3.
pub fn color(img: &RgbImage, x: u32, y: u32) -> DVec3 {
    color_of(*img.get_pixel(x, y))
}

/// An 8-bit pixel's colour in [0, 1]^3.
pub fn color_of(p: image::Rgb<u8>) -> DVec3 {
    let [r, g, b] = p.0;
    DVec3::new(f64::from(r), f64::from(g), f64::from(b)) / 255.0
}

/// An image the scans read pixel by pixel: an [`RgbImage`], or one whose
/// pixels are made as they are first read.
pub trait Pixels {
    /// Width and height, pixels.
    fn dimensions(&self) -> (u32, u32);
    /// The colour of pixel (x, y) in [0, 1]^3 ([`color`]).
    fn color(&self, x: u32, y: u32) -> DVec3;
    /// Why a pixel read could not be made (then read as black), if one
    /// could not: a reading made on the image is not to be trusted.
    fn failure(&self) -> Option<String> {
        None
    }
}

impl<P: Pixels + ?Sized> Pixels for std::sync::Arc<P> {
    fn dimensions(&self) -> (u32, u32) {
        P::dimensions(self)
    }

    fn color(&self, x: u32, y: u32) -> DVec3 {
        P::color(self, x, y)
    }

    fn failure(&self) -> Option<String> {
        P::failure(self)
    }
}

impl Pixels for RgbImage {
    fn dimensions(&self) -> (u32, u32) {
        RgbImage::dimensions(self)
    }

    fn color(&self, x: u32, y: u32) -> DVec3 {
        color(self, x, y)
    }
}

/// A line of pixels to scan: a row (`horizontal`) or a column, at index `at`.
#[derive(Clone, Copy, Debug)]
pub struct Scan {
    /// A row (true) or a column (false).
    pub horizontal: bool,
    /// The row's or column's index.
    pub at: u32,
}

impl Scan {
    fn len(&self, img: &(impl Pixels + ?Sized)) -> i64 {
        let (w, h) = img.dimensions();
        i64::from(if self.horizontal { w } else { h })
    }

    fn get(&self, img: &(impl Pixels + ?Sized), i: i64) -> DVec3 {
        if self.horizontal {
            img.color(i as u32, self.at)
        } else {
            img.color(self.at, i as u32)
        }
    }

    /// Continuous pixel coordinates of position `u` along the scan.
    pub fn point(&self, u: f64) -> (f64, f64) {
        let c = f64::from(self.at) + 0.5;
        if self.horizontal {
            (u, c)
        } else {
            (c, u)
        }
    }
}

/// Half-width (pixels) of the window in which coverages are summed.
const HALF: i64 = 3;

/// The boundary where the scan, going from `from` in direction `step` (+1 or
/// -1), leaves the first run of pixels for which `inside` holds. Returns the
/// boundary's continuous coordinate along the scan, or `None` when no clean
/// transition is found: the run never starts or ends, the window leaves the
/// image, or the colours just beyond the window are not flat (another edge
/// nearby), so that the area method would be biased.
pub fn edge(
    img: &(impl Pixels + ?Sized),
    scan: Scan,
    from: i64,
    step: i64,
    inside: impl Fn(DVec3) -> bool,
) -> Option<f64> {
    let n = scan.len(img);
    let ok = |i: i64| (0..n).contains(&i);
    let mut i = from;
    while ok(i) && !inside(scan.get(img, i)) {
        i += step;
    }
    while ok(i) && inside(scan.get(img, i)) {
        i += step;
    }
    // i is the first pixel not inside: the boundary is near it.
    let (lo, hi) = (i - HALF * step, i + HALF * step);
    let (a1, a2, b1, b2) = (lo - step, lo - 2 * step, hi + step, hi + 2 * step);
    if ![a2, b2].iter().all(|&k| ok(k)) {
        return None;
    }
    let c_in = (scan.get(img, lo) + scan.get(img, a1) + scan.get(img, a2)) / 3.0;
    let c_out = (scan.get(img, hi) + scan.get(img, b1) + scan.get(img, b2)) / 3.0;
    let flat = |a: DVec3, b: DVec3| (a - b).abs().max_element() <= 2.5 / 255.0;
    if !(flat(scan.get(img, lo), scan.get(img, a2)) && flat(scan.get(img, hi), scan.get(img, b2))) {
        return None;
    }
    let contrast = c_in - c_out;
    if contrast.length_squared() < (20.0f64 / 255.0).powi(2) {
        return None;
    }
    let mut covered = 0.0;
    let mut k = lo;
    loop {
        let f = (scan.get(img, k) - c_out).dot(contrast) / contrast.length_squared();
        covered += f.clamp(0.0, 1.0);
        if k == hi {
            break;
        }
        k += step;
    }
    // Pixel k spans [k, k + 1]; the inside run ends `covered` pixels past the window's start.
    Some(if step > 0 {
        lo as f64 + covered
    } else {
        (lo + 1) as f64 - covered
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A synthetic anti-aliased vertical edge at x = 10.3 between two colours.
    fn synthetic(edge_x: f64, a: [u8; 3], b: [u8; 3]) -> RgbImage {
        RgbImage::from_fn(24, 4, |x, _| {
            let f = (edge_x - f64::from(x)).clamp(0.0, 1.0);
            let mix = |i: usize| (f * f64::from(a[i]) + (1.0 - f) * f64::from(b[i])).round() as u8;
            image::Rgb([mix(0), mix(1), mix(2)])
        })
    }

    #[test]
    fn area_method_finds_a_sub_pixel_edge_from_either_side() {
        for edge_x in [10.3, 11.0, 12.77] {
            let img = synthetic(edge_x, [200, 40, 30], [10, 10, 20]);
            let red = |c: DVec3| c.x > 0.4;
            let x = edge(
                &img,
                Scan {
                    horizontal: true,
                    at: 1,
                },
                0,
                1,
                red,
            )
            .unwrap();
            assert!((x - edge_x).abs() < 0.01, "{x} vs {edge_x}");
            let dark = |c: DVec3| c.x < 0.4;
            let x = edge(
                &img,
                Scan {
                    horizontal: true,
                    at: 1,
                },
                23,
                -1,
                dark,
            )
            .unwrap();
            assert!((x - edge_x).abs() < 0.01, "{x} vs {edge_x}");
        }
    }
}
