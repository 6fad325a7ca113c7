//! Arbitrary output variables: per pixel, what the primary ray through the
//! pixel's centre at the camera time meets, read from the renderer's own
//! record of that ray (`renderer::Recorder`, as `vstf debug` reads it), so
//! the values are those the image was shaded with.
//!
//! - `event_t`: the lab time of the hit event, the retarded time of the
//!   light that reaches the camera (paper 3: the most recent event on the
//!   past light cone);
//! - `proper_time`: the object's own time there, counted from its start;
//! - `doppler`: nu_camera / nu_surface, the frequency ratio of the light from
//!   the surface's rest frame into the camera's (paper 6, eq. for D);
//! - `searchlight`: D^4, the ratio of frequency-integrated radiance (I/nu^4
//!   is invariant), the factor the searchlight effect applies to it;
//! - `object`: the object's index in the scene (-1 where nothing is hit);
//! - `distance`: lab distance from the camera at the camera time to the
//!   hit event;
//! - `normal`: the surface's lab-frame unit normal, turned to the side the
//!   camera sees (the side the surface's own frame shows it, as shading
//!   uses it; docs/physics.md, "Which side a moving surface shows").
//!
//! Where the ray meets nothing every float is NaN.

use crate::fixture::{Fixture, View};
use glam::DVec3;
use rayon::prelude::*;
use renderer::{Database, Frame, RayKind, Recorder, RenderSettings, Step};

/// The output variables of one pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelAov {
    /// Lab time of the hit event (the retarded time).
    pub event_t: f64,
    /// The object's own time at the hit.
    pub proper_time: f64,
    /// nu_camera / nu_surface.
    pub doppler: f64,
    /// D^4.
    pub searchlight: f64,
    /// Index of the object hit, -1 for none.
    pub object: i64,
    /// Lab distance from the camera to the hit event.
    pub distance: f64,
    /// Lab unit normal, turned to the side the camera sees.
    pub normal: DVec3,
}

impl PixelAov {
    /// A pixel whose ray meets nothing.
    pub const NOTHING: PixelAov = PixelAov {
        event_t: f64::NAN,
        proper_time: f64::NAN,
        doppler: f64::NAN,
        searchlight: f64::NAN,
        object: -1,
        distance: f64::NAN,
        normal: DVec3::NAN,
    };
}

/// The output variables of every pixel of `view`, row-major from the top
/// left, with the database built for the view.
pub fn aovs(f: &Fixture, view: &View, db: &Database) -> Vec<PixelAov> {
    // One ray through the centre at the camera time; the searchlight on so
    // that the Doppler factors are recorded (it changes no hit).
    let settings = RenderSettings {
        spp: 1,
        effects: renderer::Effects {
            searchlight: true,
            ..view.settings.effects
        },
        ..view.settings
    };
    let frame = Frame {
        camera: &view.camera,
        camera_t: view.camera_t,
        model: view.model,
        settings: &settings,
    };
    let shader = renderer::shader(db, &f.scene, &frame);
    let camera = view.camera.position_at(view.camera_t);
    let (w, h) = (view.camera.width, view.camera.height);
    (0..w * h)
        .into_par_iter()
        .map(|i| {
            let mut rec = Recorder::default();
            renderer::pixel_traced(&shader, &frame, i % w, i / w, &mut rec);
            of_record(f, &rec.steps, camera)
        })
        .collect()
}

/// The output variables from one primary ray's record.
fn of_record(f: &Fixture, steps: &[Step], camera: DVec3) -> PixelAov {
    let hit = steps.iter().find_map(|s| match s {
        Step::Hit {
            kind: RayKind::Primary,
            object,
            event,
            proper_time,
            facing_normal,
            ..
        } => Some((object, event, *proper_time, *facing_normal)),
        _ => None,
    });
    let Some((object, event, proper_time, normal)) = hit else {
        return PixelAov::NOTHING;
    };
    let to_origin = steps.iter().find_map(|s| match s {
        Step::Doppler {
            depth: 0,
            to_origin,
            ..
        } => Some(*to_origin),
        _ => None,
    });
    let observed = steps.iter().find_map(|s| match s {
        Step::Observed { doppler, .. } => Some(*doppler),
        _ => None,
    });
    let doppler = match (to_origin, observed) {
        (Some(a), Some(b)) => a * b,
        _ => f64::NAN,
    };
    let index = f.scene.objects.iter().position(|o| &o.name == object);
    PixelAov {
        event_t: event.t,
        proper_time,
        doppler,
        searchlight: doppler * doppler * doppler * doppler,
        object: index.map_or(-1, |i| i as i64),
        distance: (event.x - camera).length(),
        normal,
    }
}
