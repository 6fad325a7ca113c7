//! Expected points marked on a copy of a view.

/// Draws each marker on a copy of the image as a cross in the colour that
/// contrasts with the pixels under it (black on light, white on dark),
/// outlined in the other, and numbered from 1 beside it.
pub fn with_markers(img: &image::RgbImage, markers: &[(f64, f64)]) -> image::RgbImage {
    let mut out = img.clone();
    let (w, h) = (i64::from(out.width()), i64::from(out.height()));
    let inside = |x: i64, y: i64| x >= 0 && y >= 0 && x < w && y < h;
    for (k, &(x, y)) in markers.iter().enumerate() {
        let (cx, cy) = (x.floor() as i64, y.floor() as i64);
        if !inside(cx, cy) {
            continue;
        }
        let under = img.get_pixel(cx as u32, cy as u32).0;
        let luma = 0.2126 * f64::from(under[0])
            + 0.7152 * f64::from(under[1])
            + 0.0722 * f64::from(under[2]);
        let (ink, rim) = if luma > 110.0 {
            (image::Rgb([0, 0, 0]), image::Rgb([255, 255, 255]))
        } else {
            (image::Rgb([255, 255, 255]), image::Rgb([0, 0, 0]))
        };
        let arm = |d: i64| [(cx + d, cy), (cx, cy + d)];
        for d in -4i64..=4 {
            for (px, py) in arm(d) {
                for (ox, oy) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
                    if inside(px + ox, py + oy) {
                        out.put_pixel((px + ox) as u32, (py + oy) as u32, rim);
                    }
                }
            }
        }
        for d in -3i64..=3 {
            for (px, py) in arm(d) {
                if inside(px, py) {
                    out.put_pixel(px as u32, py as u32, ink);
                }
            }
        }
        let at = (
            (cx + 5).clamp(0, w - 1) as u32,
            (cy + 5).clamp(0, h - 1) as u32,
        );
        crate::label::draw_at(&mut out, &(k + 1).to_string(), at, 1);
    }
    out
}
