//! Frames encoded behind the tracing: while frame k+1 traces on the
//! render threads, frame k is encoded as PNG and written (and synced to
//! disk) on a thread of its own. At most one frame waits between them, so
//! an animation holds at most three frames in memory (one tracing, one
//! waiting, one being written) however long it is. A frame is made 8-bit
//! and labelled where it was traced: its linear image, eight times the
//! size, stays with the thread that made it, which renders the next frame
//! into the same memory.

use super::{frame_path, time_label};
use crate::fixture::{Fixture, View};
use crate::output::write_png;
use image::RgbImage;
use renderer::{Database, Image};
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;

/// A frame handed to the writer: rendered, or kept whole from a resumed
/// run (`None`: nothing to write).
struct Handed {
    index: usize,
    image: Option<RgbImage>,
}

/// What each frame needs besides its index and time.
pub(super) struct Frames<'a> {
    pub scene: (&'a Fixture, &'a View, &'a Database),
    pub dir: &'a Path,
    pub label: bool,
    /// Whether frame `i` is on disk whole already and is kept.
    pub kept: &'a (dyn Fn(usize) -> bool + Sync),
}

impl Frames<'_> {
    /// Renders and writes frames `owned` at `times`, in order, calling
    /// `done` (on this thread) with the count written after each; stops
    /// before the next frame once `stop` is raised. Returns how many were
    /// written (or kept); the first error of a render or a write ends the
    /// run, and a frame is either written whole or not at all.
    pub(super) fn run(
        &self,
        (owned, times): (&[usize], &[f64]),
        stop: &AtomicBool,
        done: &mut dyn FnMut(usize),
    ) -> Result<usize, String> {
        std::thread::scope(|s| {
            let (to_writer, handed) = mpsc::sync_channel::<Handed>(1);
            let (to_main, written) = mpsc::channel::<usize>();
            let writer = s.spawn(move || -> Result<(), String> {
                for (k, frame) in handed.into_iter().enumerate() {
                    if let Some(image) = frame.image {
                        write_png(&frame_path(self.dir, frame.index), &image)?;
                    }
                    // The main thread may have ended on an error of its own.
                    let _ = to_main.send(k + 1);
                }
                Ok(())
            });
            let mut finished = 0;
            let mut report = |finished: &mut usize| {
                for k in written.try_iter() {
                    *finished = k;
                    done(k);
                }
            };
            let mut spent = Image::default();
            for &i in owned {
                if stop.load(Ordering::SeqCst) {
                    break;
                }
                let image = if (self.kept)(i) {
                    None
                } else {
                    Some(self.render(times[i], &mut spent)?)
                };
                let frame = Handed { index: i, image };
                if to_writer.send(frame).is_err() {
                    // The writer has ended on an error, read below.
                    break;
                }
                report(&mut finished);
            }
            drop(to_writer);
            let wrote = writer.join();
            report(&mut finished);
            wrote.map_err(|_| "the frame writer stopped unexpectedly".to_string())??;
            Ok(finished)
        })
    }

    /// The frame at camera time `t` in 8 bits, labelled with its time
    /// when asked; its linear image is rendered into `spent`, the last
    /// frame's, and left there for the next.
    fn render(&self, t: f64, spent: &mut Image) -> Result<RgbImage, String> {
        let (f, view, db) = self.scene;
        let frame = View {
            camera_t: t,
            ..*view
        };
        *spent = crate::run::render_reusing(db, f, &frame, std::mem::take(spent))?;
        let mut img = crate::output::rgb8(spent);
        if self.label {
            let scale = crate::label::label_scale(img.width());
            crate::label::draw_label(&mut img, &format!("t = {}", time_label(t)), scale);
        }
        Ok(img)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use renderer::Traversal;

    /// `fixtures/lit-plate.json` at 32 x 24, without its views and checks:
    /// the fixture, its view and its database.
    fn plate() -> (Fixture, View, Database) {
        let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/lit-plate.json");
        let mut v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
        (v["image"]["width"], v["image"]["height"]) = (32.into(), 24.into());
        let o = v.as_object_mut().unwrap();
        o.remove("views");
        o.remove("checks");
        let f = Fixture::parse(&v.to_string(), &file).unwrap();
        let view = crate::run::view(&f, &crate::Overrides::default()).unwrap();
        let db = crate::run::database(&f, view.model.lorentz, Traversal::Bvh).unwrap();
        (f, view, db)
    }

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("vstf-behind-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// Each frame written behind the tracing is the frame rendered alone,
    /// byte for byte once decoded; `done` counts every frame in order, and
    /// a frame kept from a resumed run is counted and not rewritten.
    #[test]
    fn frames_written_behind_are_the_frames_rendered_alone() {
        let (f, view, db) = plate();
        let dir = scratch("alone");
        let times = [-24.0, -12.0, 0.0, 12.0];
        let kept = |i: usize| i == 2;
        let frames = Frames {
            scene: (&f, &view, &db),
            dir: &dir,
            label: false,
            kept: &kept,
        };
        let mut counts = Vec::new();
        let n = frames
            .run((&[0, 1, 2, 3], &times), &AtomicBool::new(false), &mut |k| {
                counts.push(k)
            })
            .unwrap();
        assert_eq!((n, counts), (4, vec![1, 2, 3, 4]));
        assert!(
            !frame_path(&dir, 2).exists(),
            "a kept frame is not rewritten"
        );
        for i in [0, 1, 3] {
            let alone = frames.render(times[i], &mut Image::default()).unwrap();
            let written = image::open(frame_path(&dir, i)).unwrap().to_rgb8();
            assert_eq!(written, alone, "frame {i}");
        }
        // Negative control: neighbouring frames differ, so the comparison
        // would see a frame written in another's place.
        let mut spent = Image::default();
        assert_ne!(
            frames.render(times[0], &mut spent).unwrap(),
            frames.render(times[3], &mut spent).unwrap()
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A frame that cannot be written (a folder stands at its path) ends
    /// the run with the write's error naming the file, after the frames
    /// before it; raised `stop` writes nothing.
    #[test]
    fn a_failed_write_ends_the_run_with_its_error_and_stop_writes_nothing() {
        let (f, view, db) = plate();
        let dir = scratch("fails");
        std::fs::create_dir_all(frame_path(&dir, 1)).unwrap();
        let never = |_: usize| false;
        let frames = Frames {
            scene: (&f, &view, &db),
            dir: &dir,
            label: true,
            kept: &never,
        };
        let times = [0.0, 0.5, 1.0];
        let mut counts = Vec::new();
        let err = frames
            .run((&[0, 1, 2], &times), &AtomicBool::new(false), &mut |k| {
                counts.push(k)
            })
            .unwrap_err();
        assert!(err.contains("frame-00001.png"), "{err}");
        assert_eq!(counts, vec![1]);
        assert!(frame_path(&dir, 0).is_file());
        assert!(!frame_path(&dir, 2).exists());
        std::fs::remove_file(frame_path(&dir, 0)).unwrap();
        let n = frames
            .run((&[0, 2], &times), &AtomicBool::new(true), &mut |_| {})
            .unwrap();
        assert_eq!(n, 0);
        assert!(!frame_path(&dir, 0).exists() && !frame_path(&dir, 2).exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
