//! Rendering an image: one or more light-cone rays per pixel, in parallel,
//! with 4D anti-aliasing (paper 5): samples jittered over the pixel and over
//! the shutter interval of the camera's t, which gives motion blur. A
//! camera on a worldline takes each sample at its own event and velocity,
//! the shutter spanning its proper time.
//!
//! Each pixel's samples come from a generator seeded by (seed, pixel), and
//! pixels are independent, so the image is the same bit for bit whatever
//! the number of threads.

use crate::accel::PACKET;
use crate::camera::{Camera, Kinematics, Model};
use crate::database::Database;
use crate::rng::SplitMix64;
use crate::scene::Scene;
use crate::shading::{BackgroundBand, Effects, Found, Shader};
use crate::trace::{NoTrace, Step, Trace};
use glam::DVec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

mod image;

pub use image::Image;

/// Per-image settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Samples per pixel. 1 samples the pixel centre at the camera's t exactly.
    pub spp: u32,
    /// Length of the shutter interval of camera time, centred on t_c
    /// (t.units): lab time for an inertial camera, proper time for a camera
    /// on a worldline.
    pub shutter: f64,
    /// Seed of the per-pixel sample generators.
    pub seed: u64,
    /// Mirror bounces followed.
    pub max_depth: u32,
    /// Whether shadow rays are traced (off: every lit-facing surface is lit).
    pub shadows: bool,
    /// Doppler shift and searchlight (both off by default).
    pub effects: Effects,
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            spp: 1,
            shutter: 0.0,
            seed: 1,
            max_depth: 4,
            shadows: true,
            effects: Effects::NONE,
        }
    }
}
/// The shader for one render of `frame`: the database, the scene's light
/// and background, the model's light speed, the settings' bounce limit and
/// the angle the camera's pixels subtend.
pub fn shader<'a>(db: &'a Database, scene: &'a Scene, frame: &Frame) -> Shader<'a> {
    let (model, settings) = (frame.model, frame.settings);
    Shader {
        db,
        light: &scene.light,
        background: scene.background,
        sky: scene.sky.as_deref(),
        light_speed: model.light_speed,
        max_depth: settings.max_depth,
        shadows: settings.shadows,
        effects: settings.effects,
        spacetime: scene.spacetime,
        pixel_angle: frame.camera.at(frame.camera_t).pixel_angle(),
        background_band: BackgroundBand::of(
            scene.background,
            scene.sky.as_deref(),
            settings.effects,
        ),
    }
}

/// Renders the view from `camera` at lab time `camera_t`.
pub fn render(
    db: &Database,
    scene: &Scene,
    camera: &Camera,
    camera_t: f64,
    model: Model,
    settings: &RenderSettings,
) -> Image {
    let frame = Frame {
        camera,
        camera_t,
        model,
        settings,
    };
    let never = AtomicBool::new(false);
    render_stoppable(db, scene, &frame, &never).unwrap_or_else(|| unreachable!("never stopped"))
}

/// [`render`], giving up (`None`) once `stop` is set: each pair of rows
/// checks it before it starts, so a front end can interrupt a long frame
/// within a row's time. An image it returns is [`render`]'s to the bit.
pub fn render_stoppable(
    db: &Database,
    scene: &Scene,
    frame: &Frame,
    stop: &AtomicBool,
) -> Option<Image> {
    render_reusing(db, scene, frame, stop, Image::default())
}

/// [`render_stoppable`] into the memory of `spent`, an earlier frame's
/// image (or none, [`Image::default`]): frame after frame, the same pages
/// are written again rather than fresh ones asked of the system, which
/// clears each before handing it out. Every pixel is rendered anew, so
/// nothing of `spent` shows; the image is [`render`]'s to the bit.
pub fn render_reusing(
    db: &Database,
    scene: &Scene,
    frame: &Frame,
    stop: &AtomicBool,
    spent: Image,
) -> Option<Image> {
    let whole = Window::whole(frame.camera.width, frame.camera.height);
    render_window(db, scene, frame, whole, stop, spent)
}

/// A rectangle of an image's pixels: columns `x..x + width` and rows
/// `y..y + height`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Window {
    /// The first column.
    pub x: u32,
    /// The first row.
    pub y: u32,
    /// Columns, at least 1.
    pub width: u32,
    /// Rows, at least 1.
    pub height: u32,
}

impl Window {
    /// Every pixel of a `width` x `height` image.
    pub fn whole(width: u32, height: u32) -> Window {
        Window {
            x: 0,
            y: 0,
            width,
            height,
        }
    }

    /// This window cut to a `width` x `height` image (`None` when nothing
    /// of it is left).
    pub fn within(&self, width: u32, height: u32) -> Option<Window> {
        let (x0, y0) = (self.x.min(width), self.y.min(height));
        let x1 = self.x.saturating_add(self.width).min(width);
        let y1 = self.y.saturating_add(self.height).min(height);
        (x1 > x0 && y1 > y0).then_some(Window {
            x: x0,
            y: y0,
            width: x1 - x0,
            height: y1 - y0,
        })
    }
}

/// The pixels of `window` (cut to the camera's image) of the frame
/// [`render_reusing`] renders, the same to the bit: an image `window.width`
/// x `window.height` whose pixel (i, j) is the frame's (x + i, y + j). A
/// pixel's samples depend on nothing but its place in the whole image, so
/// a measurement that reads only part of a frame renders only that part.
pub fn render_window(
    db: &Database,
    scene: &Scene,
    frame: &Frame,
    window: Window,
    stop: &AtomicBool,
    spent: Image,
) -> Option<Image> {
    let shader = shader(db, scene, frame);
    let camera = &Camera {
        kinematics: Kinematics::of(frame.model),
        ..*frame.camera
    };
    let frame = Frame { camera, ..*frame };
    let window = window
        .within(camera.width, camera.height)
        .unwrap_or(Window::whole(0, 0));
    let (w, h) = (window.width, window.height);
    let n = w as usize * h as usize;
    let mut pixels = spent.pixels;
    if pixels.len() < n {
        pixels = vec![DVec3::ZERO; n];
    }
    pixels.truncate(n);
    // Two rows at a time, in blocks of 2 x 2 pixels (one packet).
    const _: () = assert!(PACKET == 4, "a packet is a block of 2 x 2 pixels");
    pixels
        .par_chunks_mut(2 * w.max(1) as usize)
        .enumerate()
        .for_each(|(pair, rows)| {
            if stop.load(Ordering::Relaxed) {
                return;
            }
            let y0 = window.y + 2 * pair as u32;
            let (x0, x_end, y_end) = (window.x, window.x + w, window.y + h);
            // Pixel (x, y)'s place in `rows`.
            let at = |x: u32, y: u32| ((y - y0) * w + (x - x0)) as usize;
            for bx in (x0..x_end).step_by(2) {
                let mut block = [(0, 0); PACKET];
                let mut n = 0;
                for y in y0..(y0 + 2).min(y_end) {
                    for x in bx..(bx + 2).min(x_end) {
                        block[n] = (x, y);
                        n += 1;
                    }
                }
                let colors = pixels_packed(&shader, &frame, &block[..n]);
                for (&(x, y), c) in block[..n].iter().zip(colors) {
                    rows[at(x, y)] = c;
                }
            }
        });
    (!stop.load(Ordering::Relaxed)).then_some(Image {
        width: w,
        height: h,
        pixels,
    })
}

/// What every pixel of one frame is rendered with: the camera at its lab
/// time (the only thing animation changes), the light-speed model and the
/// sampling settings.
#[derive(Clone, Copy, Debug)]
pub struct Frame<'a> {
    /// The camera casting the rays.
    pub camera: &'a Camera,
    /// The camera's lab time, t.units.
    pub camera_t: f64,
    /// Light speed and Lorentz transform.
    pub model: Model,
    /// Samples per pixel, shutter and seed.
    pub settings: &'a RenderSettings,
}

/// [`pixel`] of each of a few neighbouring pixels (at most [`PACKET`]),
/// the same colours to the bit: their k-th samples' primary rays are
/// searched together ([`Shader::search_primary`]), then each is shaded.
fn pixels_packed(shader: &Shader, frame: &Frame, at: &[(u32, u32)]) -> [DVec3; PACKET] {
    let Frame {
        camera,
        camera_t,
        model,
        settings,
    } = *frame;
    let m = at.len();
    // (Lanes past the pixels repeat the last, and are not used.) One
    // sample a pixel, at its centre, draws nothing.
    let rng = |j: usize| {
        let (x, y) = at[j.min(m - 1)];
        SplitMix64::for_pixel(settings.seed, x, y)
    };
    let mut rngs: [SplitMix64; PACKET] = match settings.spp {
        0 | 1 => std::array::from_fn(|_| SplitMix64::new(0)),
        _ => [rng(0), rng(1), rng(2), rng(3)],
    };
    let n = (f64::from(settings.spp).sqrt().ceil()) as u32;
    // Each sample's camera where it is not `camera` itself (Camera::at_in).
    let mut moved: [Option<Camera>; PACKET] = [None, None, None, None];
    let mut found = [Found::Straight(None); PACKET];
    let mut colors = [DVec3::ZERO; PACKET];
    for k in 0..settings.spp.max(1) {
        // Each lane's pixel position and lab time (px, py, t).
        let mut samples = [(0.0, 0.0, camera_t); PACKET];
        for j in 0..m {
            let (x, y) = at[j];
            samples[j] = if settings.spp <= 1 {
                (f64::from(x) + 0.5, f64::from(y) + 0.5, camera_t)
            } else {
                stratified(&mut rngs[j], (x, y), (k, n), frame)
            };
            camera.at_in(samples[j].2, &mut moved[j]);
        }
        let last = samples[m - 1];
        samples[m..].fill(last);
        let cameras: [&Camera; PACKET] =
            std::array::from_fn(|j| moved[j.min(m - 1)].as_ref().unwrap_or(camera));
        let rays = Camera::rays(&cameras, &samples, model.light_speed);
        shader.search_primary(&rays[..m], &mut found[..m]);
        for j in 0..m {
            let here = moved[j].as_ref().unwrap_or(camera);
            let c = shader.observed_found(here, &rays[j], &found[j]);
            colors[j] = if settings.spp <= 1 { c } else { colors[j] + c };
        }
    }
    if settings.spp > 1 {
        colors = colors.map(|c| c / f64::from(settings.spp));
    }
    colors
}

/// Sample k of pixel (x, y) with n*n strata: its place in the image
/// (stratum k, row-major, jittered within it) and its camera time
/// (jittered over the shutter).
fn stratified(
    rng: &mut SplitMix64,
    (x, y): (u32, u32),
    (k, n): (u32, u32),
    frame: &Frame,
) -> (f64, f64, f64) {
    let (sx, sy) = (k % n, (k / n) % n);
    let px = f64::from(x) + (f64::from(sx) + rng.next_f64()) / f64::from(n);
    let py = f64::from(y) + (f64::from(sy) + rng.next_f64()) / f64::from(n);
    let t = frame.camera.sample_time(
        frame.camera_t,
        (rng.next_f64() - 0.5) * frame.settings.shutter,
    );
    (px, py, t)
}

/// One pixel: the mean of its samples. With n*n >= spp strata, sample k
/// falls in stratum k (row-major), jittered within it.
pub fn pixel(shader: &Shader, frame: &Frame, x: u32, y: u32) -> DVec3 {
    pixel_traced(shader, frame, x, y, &mut NoTrace)
}

/// [`pixel`], recording every sample's variables.
pub fn pixel_traced<T: Trace>(
    shader: &Shader,
    frame: &Frame,
    x: u32,
    y: u32,
    trace: &mut T,
) -> DVec3 {
    let Frame {
        camera,
        camera_t,
        model,
        settings,
    } = *frame;
    let sample = |index: u32, px: f64, py: f64, t: f64, trace: &mut T| {
        if T::ENABLED {
            trace.record(Step::Sample {
                index,
                px,
                py,
                camera_t: t,
            });
        }
        let mut moved = None;
        let camera = camera.at_in(t, &mut moved);
        let ray = camera.ray(px, py, t, model.light_speed);
        shader.observed_traced(camera, &ray, trace)
    };
    if settings.spp <= 1 {
        return sample(0, f64::from(x) + 0.5, f64::from(y) + 0.5, camera_t, trace);
    }
    let mut rng = SplitMix64::for_pixel(settings.seed, x, y);
    let n = (f64::from(settings.spp).sqrt().ceil()) as u32;
    let mut sum = DVec3::ZERO;
    for k in 0..settings.spp {
        let (px, py, t) = stratified(&mut rng, (x, y), (k, n), frame);
        sum += sample(k, px, py, t, trace);
    }
    sum / f64::from(settings.spp)
}
