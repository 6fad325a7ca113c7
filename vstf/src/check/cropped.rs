//! Measuring renders cut to where the kept objects are seen: a coarse
//! render of the whole image finds them, and only a window around them is
//! rendered at the measuring size. A measurement that scans the image from
//! its borders to the first pixel that is not background (an outline)
//! reads the same pixels in the window as in the whole image, each the
//! same to the bit, once the window's border is background wide enough
//! for the scan's area window: else the whole image is rendered.

use crate::measure::{color, Pinhole};
use crate::observer::{is_background, Observer};
use image::RgbImage;
use renderer::Window;

/// How many times finer the measuring image is than the coarse render
/// that finds the objects (at one sample a pixel).
const COARSE: u32 = 4;

/// Background kept around the objects found, measuring pixels, beyond the
/// coarse render's own uncertainty (a coarse pixel either side): the area
/// method's window and the two pixels beyond it that must be flat
/// ([`crate::measure::edge`]), and one more.
const RING: u32 = 3 + 2 + 1;

impl Observer<'_> {
    /// [`Observer::measuring_render`] of `keep` at `size` and `spp`, with
    /// only a window around the objects rendered and the rest of the image
    /// filled with the window's corner (background): the pixels an outline
    /// scan reads, the same to the bit, provided nothing is seen outside the
    /// window (the coarse render shows nothing there, and the window's
    /// border, [`RING`] pixels deep, is all background; otherwise the whole
    /// image is rendered).
    pub(super) fn measuring_cropped(
        &self,
        keep: &[&str],
        size: (u32, u32),
        spp: u32,
    ) -> Result<(RgbImage, Pinhole), String> {
        if let Some(window) = self.found(keep, size)? {
            let (part, pinhole) = self.measuring_window(keep, size, (spp, 0), window)?;
            if border_is_background(&part, self.fixture.spec.background) {
                let mut whole = RgbImage::from_pixel(size.0, size.1, *part.get_pixel(0, 0));
                image::imageops::replace(&mut whole, &part, window.x.into(), window.y.into());
                return Ok((whole, pinhole));
            }
        }
        self.measuring_render(keep, size, spp)
    }

    /// The window of the measuring image around every pixel of a coarse
    /// render (one [`COARSE`]-th the size, one sample a pixel) that is not
    /// background, with a coarse pixel and [`RING`] to spare; `None` when
    /// nothing is seen or the window would reach the image's border.
    fn found(&self, keep: &[&str], (w, h): (u32, u32)) -> Result<Option<Window>, String> {
        let (cw, ch) = ((w / COARSE).max(1), (h / COARSE).max(1));
        let (coarse, _) = self.measuring_render(keep, (cw, ch), 1)?;
        let bg = self.fixture.spec.background;
        let seen = coarse
            .enumerate_pixels()
            .map(|(x, y, _)| (x, y))
            .filter(|&(x, y)| !is_background(color(&coarse, x, y), bg));
        let Some((x0, y0, x1, y1)) = seen.fold(None, |b: Option<(u32, u32, u32, u32)>, (x, y)| {
            Some(b.map_or((x, y, x, y), |(x0, y0, x1, y1)| {
                (x0.min(x), y0.min(y), x1.max(x), y1.max(y))
            }))
        }) else {
            return Ok(None);
        };
        // Coarse pixel (i, j) spans measuring pixels i w / cw .. (i + 1) w / cw.
        let (sx, sy) = (f64::from(w) / f64::from(cw), f64::from(h) / f64::from(ch));
        let spare = |s: f64| s.ceil() as i64 + i64::from(RING);
        let left = (f64::from(x0) * sx).floor() as i64 - spare(sx);
        let top = (f64::from(y0) * sy).floor() as i64 - spare(sy);
        let right = (f64::from(x1 + 1) * sx).ceil() as i64 + spare(sx);
        let bottom = (f64::from(y1 + 1) * sy).ceil() as i64 + spare(sy);
        if left < 0 || top < 0 || right > i64::from(w) || bottom > i64::from(h) {
            return Ok(None);
        }
        Ok(Some(Window {
            x: left as u32,
            y: top as u32,
            width: (right - left) as u32,
            height: (bottom - top) as u32,
        }))
    }
}

/// Whether every pixel within [`RING`] of `img`'s border is background.
fn border_is_background(img: &RgbImage, bg: glam::DVec3) -> bool {
    let (w, h) = (img.width(), img.height());
    let inner = |x: u32, y: u32| x >= RING && y >= RING && x + RING < w && y + RING < h;
    img.enumerate_pixels()
        .all(|(x, y, _)| inner(x, y) || is_background(color(img, x, y), bg))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixture::Fixture;
    use std::path::Path;

    fn fixture(name: &str) -> Fixture {
        let file = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../fixtures/{name}.json"));
        Fixture::load(&file).unwrap()
    }

    fn observer(f: &Fixture, camera_t: f64) -> Observer<'_> {
        Observer {
            fixture: f,
            model: crate::observer::fixture_model(f),
            camera_t,
        }
    }

    #[test]
    fn a_cropped_render_is_the_whole_render_to_the_byte() {
        // A small marker seen by an accelerating camera: only a window is
        // rendered, and the image is the whole render's.
        let f = fixture("rocket");
        let o = observer(&f, f.spec.camera.t + 4.0);
        let size = o.size(160);
        let found = o.found(&["south"], size).unwrap().expect("a window");
        assert!(u64::from(found.width) * u64::from(found.height) < u64::from(size.0 * size.1) / 4);
        let (cropped, _) = o.measuring_cropped(&["south"], size, 4).unwrap();
        let (whole, _) = o.measuring_render(&["south"], size, 4).unwrap();
        assert!(cropped == whole, "the cropped render differs");
        // Negative control: the marker's own pixels are not background, so
        // a window that missed it would be caught.
        let bg = f.spec.background;
        assert!(whole
            .enumerate_pixels()
            .any(|(x, y, _)| !is_background(color(&whole, x, y), bg)));
    }

    #[test]
    fn an_object_at_the_border_is_rendered_whole() {
        // The plate fills the view to its edges: no window is found.
        let f = fixture("lit-plate");
        let o = observer(&f, f.spec.camera.t);
        let keep: Vec<&str> = f.spec.objects.iter().map(|o| o.name.as_str()).collect();
        assert_eq!(o.found(&keep, o.size(64)).unwrap(), None);
    }

    #[test]
    fn a_border_with_an_object_pixel_is_not_background() {
        let bg = glam::DVec3::ZERO;
        let mut img = RgbImage::new(20, 20);
        assert!(border_is_background(&img, bg));
        img.put_pixel(RING - 1, 10, image::Rgb([255, 255, 255]));
        assert!(!border_is_background(&img, bg));
        let mut inside = RgbImage::new(20, 20);
        inside.put_pixel(RING, 10, image::Rgb([255, 255, 255]));
        assert!(border_is_background(&inside, bg));
    }
}
