//! Probe images rendered as they are read: an edge traced from the image's
//! side reads the background up to the edge and a few pixels past it,
//! never the object's inside, so only the tiles a scan reaches are
//! rendered. A tile is a window of the whole render
//! ([`renderer::render_window`]), each pixel the same to the bit, so a
//! reading is the same as on the whole image.

use crate::fixture::{Fixture, View};
use crate::measure::{color, Pixels};
use glam::DVec3;
use image::RgbImage;
use renderer::{Database, Traversal, Window};
use std::sync::{Mutex, OnceLock};

/// Side of a tile, pixels.
const TILE: u32 = 16;

/// A view of a fixture whose pixels are rendered a tile at a time, as
/// they are first read.
pub(crate) struct LazyImage {
    fixture: Fixture,
    view: View,
    db: Database,
    tiles: Vec<OnceLock<RgbImage>>,
    /// The first render that failed: its tile reads as black, and the
    /// reading made on it is discarded ([`LazyImage::failure`]).
    failed: Mutex<Option<String>>,
}

impl LazyImage {
    /// `view` of `fixture`, its database built, nothing rendered yet.
    pub(crate) fn new(fixture: Fixture, view: View) -> Result<LazyImage, String> {
        let db = crate::run::database(&fixture, view.model.lorentz, Traversal::Bvh)
            .map_err(|e| e.to_string())?;
        let (w, h) = (view.camera.width, view.camera.height);
        let count = w.div_ceil(TILE) as usize * h.div_ceil(TILE) as usize;
        Ok(LazyImage {
            fixture,
            view,
            db,
            tiles: (0..count).map(|_| OnceLock::new()).collect(),
            failed: Mutex::new(None),
        })
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

impl Pixels for LazyImage {
    fn dimensions(&self) -> (u32, u32) {
        (self.view.camera.width, self.view.camera.height)
    }

    fn color(&self, x: u32, y: u32) -> DVec3 {
        color(self.tile(x, y), x % TILE, y % TILE)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixture::Overrides;
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
        let lazy = LazyImage::new(f.clone(), view).unwrap();
        assert_eq!(lazy.rendered(), (0, 3 * 3));
        // One pixel renders one tile (the last, cut to the image).
        assert_eq!(lazy.color(44, 36), color(&whole, 44, 36));
        assert_eq!(lazy.rendered(), (1, 9));
        for (x, y, _) in whole.enumerate_pixels() {
            assert_eq!(lazy.color(x, y), color(&whole, x, y), "({x}, {y})");
        }
        assert_eq!(lazy.rendered(), (9, 9));
        assert_eq!(lazy.failure(), None);
        // Negative control: the image is not one colour.
        assert!(whole.pixels().any(|p| p != whole.get_pixel(0, 0)));
    }
}
