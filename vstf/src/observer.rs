//! What a fixture looks like to a measurement: the observer's event and
//! model, the measurements' own pinhole model of the fixture's camera, image
//! sizes, and the uniform motions read from the scene's description.
//!
//! Built from the fixture's plain data with [`crate::measure`] and
//! [`crate::oracle`] only, never the renderer's camera or boosts, so that a
//! check's expectation cannot share a bug with the image it measures.

use crate::fixture::checks::ViewSpec;
use crate::fixture::CameraSpec;
use crate::fixture::{Fixture, Overrides};
use crate::measure::{Kinematics, Pinhole};
use crate::oracle::keyframed::{CameraKey, KeyframedCamera};
use crate::oracle::rocket::RocketWorldline;
use crate::oracle::{body_point, PointWorldline};
use glam::DVec3;
use renderer::{Event, LightSpeed, Model};

/// The model the fixture names (no overrides).
pub(crate) fn fixture_model(fixture: &Fixture) -> Model {
    fixture.model(&Overrides::default())
}

/// A fixture with a model and camera time chosen: the observer a check
/// measures as.
pub(crate) struct Observer<'a> {
    /// The fixture looked at (possibly a modified copy of the loaded one).
    pub fixture: &'a Fixture,
    /// The physics the renders use.
    pub model: Model,
    /// The camera's lab time, t.units.
    pub camera_t: f64,
}

impl<'a> Observer<'a> {
    /// The observer of the declared view `v` of `f`: its camera time and
    /// model, the fixture's where the view sets none.
    pub(crate) fn declared(f: &'a Fixture, v: &ViewSpec) -> Observer<'a> {
        let mut model = match v.model {
            Some(m) => m.model(),
            None => fixture_model(f),
        };
        if let Some(l) = v.lorentz {
            model.lorentz = l;
        }
        Observer {
            fixture: f,
            model,
            camera_t: v.camera_t(f.spec.camera.t),
        }
    }
}

impl Observer<'_> {
    /// The camera's position at this setup's time: where the fixture puts
    /// it at its own time, moved on with the camera's velocity (a camera at
    /// rest stays put), or on its worldline.
    pub(crate) fn camera_x(&self) -> DVec3 {
        let c = &self.fixture.spec.camera;
        if let Some((x, _)) = camera_path(c).and_then(|p| p.at(self.camera_t)) {
            return x;
        }
        match c.velocity {
            Some(v) if v != DVec3::ZERO => c.position + v * (self.camera_t - c.t),
            _ => c.position,
        }
    }

    /// The image size at `width` with the fixture's aspect ratio.
    pub(crate) fn size(&self, width: u32) -> (u32, u32) {
        let im = &self.fixture.spec.image;
        let height =
            ((f64::from(width) * f64::from(im.height) / f64::from(im.width)).round() as u32).max(1);
        (width, height)
    }

    /// How this setup's model turns a moving camera's lines of sight.
    pub(crate) fn kinematics(&self) -> Kinematics {
        Kinematics::of(
            self.model.light_speed == LightSpeed::Finite,
            self.model.lorentz,
        )
    }

    /// The measurements' model of the fixture's camera at `width` x
    /// `height`, built from the camera description as the fixture's view is.
    pub(crate) fn pinhole(&self, (width, height): (u32, u32)) -> Result<Pinhole, String> {
        let c = &self.fixture.spec.camera;
        let still = match (c.look_at, c.yaw_deg, c.pitch_deg) {
            (Some(look_at), _, _) => {
                Pinhole::looking_at(c.position, look_at, c.up, c.vfov_deg, (width, height))
            }
            (None, yaw, pitch) => Pinhole::yaw_pitch(
                c.position,
                (yaw.unwrap_or(0.0), pitch.unwrap_or(0.0)),
                c.vfov_deg,
                (width, height),
            ),
        };
        let velocity = match camera_path(c).and_then(|p| p.at(self.camera_t)) {
            Some((_, v)) => v,
            None => c.velocity.unwrap_or(DVec3::ZERO),
        };
        still
            .and_then(|p| p.moving(velocity, self.kinematics()))
            .ok_or_else(|| format!("{}: degenerate camera", self.fixture.name))
    }
}

/// The oracle's worldline of an accelerating camera, read from its
/// description (its proper time 0 at the camera's `t` and `position`).
pub(crate) fn rocket(c: &CameraSpec) -> Option<RocketWorldline> {
    let h = c.worldline.as_ref()?.hyperbolic?;
    Some(RocketWorldline {
        t0: c.t,
        x0: c.position,
        direction: h.acceleration.try_normalize()?,
        acceleration: h.acceleration.length(),
        initial_velocity: h.initial_velocity,
    })
}

/// The oracle's worldline of an accelerating camera: hyperbolic, or
/// through keyframes.
pub(crate) enum CameraPath {
    /// Constant proper acceleration.
    Rocket(RocketWorldline),
    /// Through keyframes.
    Keyframed(KeyframedCamera),
}

impl CameraPath {
    /// The camera's lab position and velocity at lab time `t`; `None`
    /// outside its keyframes.
    pub(crate) fn at(&self, t: f64) -> Option<(DVec3, DVec3)> {
        match self {
            CameraPath::Rocket(w) => {
                let tau = w.proper_time(t);
                Some((w.position(tau), w.velocity(tau)))
            }
            CameraPath::Keyframed(k) => k.at(t),
        }
    }
}

/// The oracle's worldline of camera `c`, read from its description, if
/// it accelerates.
pub(crate) fn camera_path(c: &CameraSpec) -> Option<CameraPath> {
    if let Some(w) = rocket(c) {
        return Some(CameraPath::Rocket(w));
    }
    let keys = c.worldline.as_ref()?.keyframes.as_ref()?;
    Some(CameraPath::Keyframed(KeyframedCamera {
        keys: keys
            .iter()
            .map(|k| CameraKey {
                t: k.t,
                position: k.position,
                velocity: k.velocity,
            })
            .collect(),
    }))
}

/// Whether a colour is the (flat) background of a probe.
pub(crate) fn is_background(c: DVec3, bg: DVec3) -> bool {
    (c - bg).abs().max_element() < 12.0 / 255.0
}

/// An object's straight worldline as the fixture gives it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct UniformMotion {
    /// The event where its reference point starts.
    pub start: Event,
    /// Its lab velocity, as a fraction of light speed.
    pub velocity: DVec3,
    /// Whether it is Lorentz-contracted under the model (a V_obj under the
    /// Lorentz transform).
    pub contracted: bool,
}

impl UniformMotion {
    /// The worldline of the body point at `r` (object coordinates; rest
    /// frame for a contracted object).
    pub(crate) fn point(&self, r: DVec3) -> PointWorldline {
        body_point(
            self.start.t,
            self.start.x,
            self.velocity,
            r,
            self.contracted,
        )
    }
}

/// The uniform motion under `model` of the object named `name`, read from
/// the fixture.
pub(crate) fn motion_of(
    fixture: &Fixture,
    name: &str,
    model: Model,
) -> Result<UniformMotion, String> {
    let obj = fixture.object(name)?;
    let contracted = model.lorentz && obj.kind == renderer::ObjectKind::VObj;
    let (start, velocity) = uniform(&obj.motion).ok_or_else(|| {
        format!(
            "{}: object {name:?} does not move uniformly",
            fixture.file.display()
        )
    })?;
    Ok(UniformMotion {
        start,
        velocity,
        contracted,
    })
}

/// The background colour of probes, as stored in 8 bits.
pub(crate) fn background(fixture: &Fixture) -> DVec3 {
    (fixture.scene.background.clamp(DVec3::ZERO, DVec3::ONE) * 255.0).round() / 255.0
}

pub(crate) use crate::fixture::solve::uniform;
