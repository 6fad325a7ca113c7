//! Rendering an image: one or more light-cone rays per pixel, in parallel,
//! with 4D anti-aliasing (paper 5): samples jittered over the pixel and over
//! the shutter interval of the camera's t, which gives motion blur.
//!
//! Each pixel's samples come from a generator seeded by (seed, pixel), and
//! pixels are independent, so the image is the same bit for bit whatever
//! the number of threads.

use crate::camera::{Camera, Kinematics, Model};
use crate::database::Database;
use crate::rng::SplitMix64;
use crate::scene::Scene;
use crate::shading::{Effects, Shader};
use crate::trace::{NoTrace, Step, Trace};
use glam::DVec3;
use rayon::prelude::*;

/// Per-image settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Samples per pixel. 1 samples the pixel centre at the camera's t exactly.
    pub spp: u32,
    /// Length of the shutter interval of camera time, centred on t_c (t.units).
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

/// Linear RGB pixels, row-major from the top left.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// Linear RGB, `width * height` of them.
    pub pixels: Vec<DVec3>,
}

impl Image {
    /// 8 bits per channel; values are stored linearly (no sRGB curve) so
    /// that a pixel's value is proportional to the coverage of an edge.
    pub fn to_rgb8(&self) -> image::RgbImage {
        let mut out = image::RgbImage::new(self.width, self.height);
        for (p, c) in out.pixels_mut().zip(&self.pixels) {
            let q = |v: f64| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
            *p = image::Rgb([q(c.x), q(c.y), q(c.z)]);
        }
        out
    }
}

/// The shader for one render: the database, the scene's light and
/// background, the model's light speed and the settings' bounce limit.
pub fn shader<'a>(
    db: &'a Database,
    scene: &'a Scene,
    model: Model,
    settings: &RenderSettings,
) -> Shader<'a> {
    Shader {
        db,
        light: &scene.light,
        background: scene.background,
        light_speed: model.light_speed,
        max_depth: settings.max_depth,
        shadows: settings.shadows,
        effects: settings.effects,
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
    let shader = shader(db, scene, model, settings);
    let camera = &Camera {
        kinematics: Kinematics::of(model),
        ..*camera
    };
    let frame = Frame {
        camera,
        camera_t,
        model,
        settings,
    };
    let (w, h) = (camera.width, camera.height);
    let mut pixels = vec![DVec3::ZERO; w as usize * h as usize];
    pixels
        .par_chunks_mut(w as usize)
        .enumerate()
        .for_each(|(y, row)| {
            for (x, px) in row.iter_mut().enumerate() {
                *px = pixel(&shader, &frame, x as u32, y as u32);
            }
        });
    Image {
        width: w,
        height: h,
        pixels,
    }
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
        let (sx, sy) = (k % n, (k / n) % n);
        let px = f64::from(x) + (f64::from(sx) + rng.next_f64()) / f64::from(n);
        let py = f64::from(y) + (f64::from(sy) + rng.next_f64()) / f64::from(n);
        let t = camera_t + (rng.next_f64() - 0.5) * settings.shutter;
        sum += sample(k, px, py, t, trace);
    }
    sum / f64::from(settings.spp)
}
