//! Images rendered as they are read: an edge traced from the image's
//! side reads the background up to the edge and a few pixels past it,
//! never the object's inside, so only the tiles a scan reaches need be
//! rendered. A tile is a window of the whole render
//! ([`renderer::render_window`]), each pixel the same to the bit, so a
//! reading is the same as on the whole image.

use crate::fixture::{Fixture, View};
use image::RgbImage;
use renderer::{Database, Window};
use std::sync::{Arc, Mutex, OnceLock};

/// Side of a tile, pixels.
const TILE: u32 = 16;

/// A view of a fixture whose pixels are rendered a tile at a time, as
/// they are first read.
pub struct LazyImage {
    fixture: Fixture,
    view: View,
    db: Arc<Database>,
    tiles: Vec<OnceLock<RgbImage>>,
    /// The first render that failed: its tile reads as black, and the
    /// reading made on it is discarded ([`LazyImage::failure`]).
    failed: Mutex<Option<String>>,
}

impl LazyImage {
    /// `view` of `fixture` with its database `db` (built with the view's
    /// Lorentz setting), nothing rendered yet.
    pub(crate) fn new(fixture: Fixture, view: View, db: Arc<Database>) -> LazyImage {
        let (w, h) = (view.camera.width, view.camera.height);
        let count = w.div_ceil(TILE) as usize * h.div_ceil(TILE) as usize;
        LazyImage {
            fixture,
            view,
            db,
            tiles: (0..count).map(|_| OnceLock::new()).collect(),
            failed: Mutex::new(None),
        }
    }

    /// Why a tile could not be rendered, if one could not: a reading made
    /// on this image is then not to be trusted.
    pub(crate) fn failure(&self) -> Option<String> {
        self.failed.lock().map_or(None, |f| f.clone())
    }

    /// How many tiles have been rendered, of how many.
    #[cfg(test)]
    pub(crate) fn rendered(&self) -> (usize, usize) {
        let done = self.tiles.iter().filter(|t| t.get().is_some()).count();
        (done, self.tiles.len())
    }

    /// Width and height, pixels.
    pub(crate) fn dimensions(&self) -> (u32, u32) {
        (self.view.camera.width, self.view.camera.height)
    }

    /// Pixel (x, y) in 8 bits, its tile rendered if it was not.
    pub(crate) fn pixel(&self, x: u32, y: u32) -> image::Rgb<u8> {
        *self.tile(x, y).get_pixel(x % TILE, y % TILE)
    }

    /// Bytes of the pixels once all are rendered.
    pub(crate) fn bytes(&self) -> usize {
        let (w, h) = self.dimensions();
        3 * w as usize * h as usize
    }

    /// The tile holding pixel (x, y), rendered if it was not.
    fn tile(&self, x: u32, y: u32) -> &RgbImage {
        let (w, h) = self.dimensions();
        let (tx, ty) = (x / TILE, y / TILE);
        let index = (ty * w.div_ceil(TILE) + tx) as usize;
        self.tiles[index].get_or_init(|| {
            let window = Window {
                x: tx * TILE,
                y: ty * TILE,
                width: TILE,
                height: TILE,
            };
            let cut = window.within(w, h).unwrap_or(window);
            let view = View {
                window: Some(cut),
                ..self.view
            };
            match crate::run::render_with(&self.db, &self.fixture, &view) {
                Ok(img) => crate::output::rgb8(&img),
                Err(e) => {
                    if let Ok(mut f) = self.failed.lock() {
                        f.get_or_insert(e.to_string());
                    }
                    RgbImage::new(cut.width, cut.height)
                }
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixture::Overrides;
    use renderer::Traversal;
    use std::path::Path;

    #[test]
    fn a_lazy_image_reads_the_whole_render_and_renders_only_what_is_read() {
        let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/flange.json");
        let f = Fixture::load(&file).unwrap();
        let o = Overrides {
            width: Some(45),
            height: Some(37),
            spp: Some(4),
            ..Overrides::default()
        };
        let view = crate::run::view(&f, &o).unwrap();
        let whole = crate::output::rgb8(&crate::run::render(&f, &view, Traversal::Bvh).unwrap());
        let db = crate::run::database_shared(&f, view.model.lorentz, Traversal::Bvh).unwrap();
        let lazy = LazyImage::new(f.clone(), view, db);
        assert_eq!(lazy.rendered(), (0, 3 * 3));
        // One pixel renders one tile (the last, cut to the image).
        assert_eq!(lazy.pixel(44, 36), *whole.get_pixel(44, 36));
        assert_eq!(lazy.rendered(), (1, 9));
        for (x, y, p) in whole.enumerate_pixels() {
            assert_eq!(lazy.pixel(x, y), *p, "({x}, {y})");
        }
        assert_eq!(lazy.rendered(), (9, 9));
        assert_eq!(lazy.failure(), None);
        // Negative control: the image is not one colour.
        assert!(whole.pixels().any(|p| p != whole.get_pixel(0, 0)));
    }

    #[test]
    fn a_lazy_image_is_shared_by_the_renders_of_the_same_view() {
        let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/flange.json");
        let f = Fixture::load(&file).unwrap();
        let view = crate::run::view(&f, &Overrides::default()).unwrap();
        let a = crate::run::render_lazy(&f, &view).unwrap();
        let b = crate::run::render_lazy(&f.clone(), &view).unwrap();
        assert!(std::sync::Arc::ptr_eq(&a, &b));
        // Negative control: another time is another image.
        let later = View {
            camera_t: view.camera_t + 1.0,
            ..view
        };
        let c = crate::run::render_lazy(&f, &later).unwrap();
        assert!(!std::sync::Arc::ptr_eq(&a, &c));
    }
}
