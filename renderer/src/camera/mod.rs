//! The camera that casts rays on its past light cone (paper 3, item 3, and
//! 3.2, eq. 11-12), and the light-speed models of paper 4.1.5 (Figure 1)
//! that decide how its rays and a moving camera behave.

use crate::math;
use crate::scene::Hyperbolic;
use crate::spacetime::{Boost, Event, FourVector, LightSpeed, Ray};

mod worldline;
use glam::DVec3;
#[cfg(feature = "serde")]
use serde::{Deserialize, Serialize};
use std::fmt;
pub use worldline::CameraWorldline;

/// Camera attitude: either a target to look at, or yaw and pitch.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(rename_all = "snake_case", deny_unknown_fields)
)]
pub enum Attitude {
    /// Look from the camera position towards `look_at`, with `up` giving the image's up.
    LookAt {
        /// The point looked at.
        look_at: DVec3,
        /// Approximately up in the image.
        up: DVec3,
    },
    /// Yaw: right-handed rotation about +y, degrees; 0 looks along -z and
    /// 90 along -x. Pitch: degrees above the horizontal. Image up follows +y.
    YawPitch {
        /// Yaw, degrees.
        yaw_deg: f64,
        /// Pitch, degrees.
        pitch_deg: f64,
    },
}

/// How a moving camera's lines of sight are carried into the lab frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kinematics {
    /// Light is instantaneous: the camera's motion does not turn its rays.
    None,
    /// Galilean addition of the camera's velocity to the light's (classical model).
    Galilean,
    /// The Lorentz boost of the light's 4-vector: relativistic aberration.
    Lorentz,
}

impl Kinematics {
    /// The kinematics of a model's moving camera.
    pub fn of(model: Model) -> Kinematics {
        match (model.light_speed, model.lorentz) {
            (LightSpeed::Infinite, _) => Kinematics::None,
            (LightSpeed::Finite, false) => Kinematics::Galilean,
            (LightSpeed::Finite, true) => Kinematics::Lorentz,
        }
    }
}

/// A pinhole camera at `event`, moving through the lab with `velocity`
/// (at rest by default, as in the paper). Its attitude (forward, right, up)
/// and image plane are defined in its own rest frame; its lines of sight
/// are carried into the lab by `kinematics`. Its viewplane is spherical in
/// time (paper 3.2): every pixel's ray starts at the camera event, so the
/// image adds no light delay of its own. Pixel (0, 0) is the top left; pixel
/// centres are at half-integers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Where and when the camera is (at the view's time).
    pub event: Event,
    /// Unit view direction, camera frame.
    pub forward: DVec3,
    /// Unit right of the image, camera frame.
    pub right: DVec3,
    /// Unit up of the image, camera frame.
    pub up: DVec3,
    /// Vertical field of view, degrees.
    pub(crate) vfov_deg: f64,
    /// tan(vfov / 2): the image plane's half height at unit distance,
    /// computed once rather than for every ray.
    pub(crate) tan_half_v: f64,
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Lab velocity (fraction of c).
    pub velocity: DVec3,
    /// How lines of sight are carried into the lab.
    pub kinematics: Kinematics,
    /// The camera's worldline when it accelerates (`None`: inertial).
    /// `event` and `velocity` are then the worldline's at the frame's
    /// time: the frame is formed in the camera's instantaneous rest frame,
    /// and each sample of a shutter takes the camera at its own time.
    pub worldline: Option<CameraWorldline>,
}

impl Camera {
    /// `None` when the attitude is degenerate (look-at at the camera, up parallel to the view).
    pub fn new(
        event: Event,
        attitude: Attitude,
        vfov_deg: f64,
        width: u32,
        height: u32,
    ) -> Option<Camera> {
        let (forward, up_hint) = match attitude {
            Attitude::LookAt { look_at, up } => ((look_at - event.x).try_normalize()?, up),
            Attitude::YawPitch { yaw_deg, pitch_deg } => {
                let (y, p) = (yaw_deg.to_radians(), pitch_deg.to_radians());
                (
                    DVec3::new(
                        -math::sin(y) * math::cos(p),
                        math::sin(p),
                        -math::cos(y) * math::cos(p),
                    ),
                    DVec3::Y,
                )
            }
        };
        let right = forward.cross(up_hint).try_normalize()?;
        let up = right.cross(forward);
        Some(Camera {
            event,
            forward,
            right,
            up,
            vfov_deg,
            tan_half_v: math::tan(vfov_deg.to_radians() / 2.0),
            width,
            height,
            velocity: DVec3::ZERO,
            kinematics: Kinematics::None,
            worldline: None,
        })
    }

    /// The same camera (attitude and image) at `event`.
    pub fn placed(self, event: Event) -> Camera {
        Camera { event, ..self }
    }

    /// The same camera moving with lab `velocity`, its rays carried into the
    /// lab as `model` says; `None` at or above light speed.
    pub fn moving(self, velocity: DVec3, model: Model) -> Option<Camera> {
        (velocity.is_finite() && velocity.length_squared() < 1.0).then_some(Camera {
            velocity,
            kinematics: Kinematics::of(model),
            ..self
        })
    }

    /// The same camera on the hyperbolic `worldline`, at its event there at
    /// lab time `t` and moving with its velocity then; `None` if that is
    /// not slower than light.
    pub fn accelerating(self, worldline: Hyperbolic, t: f64, model: Model) -> Option<Camera> {
        self.on_worldline(CameraWorldline::Hyperbolic(worldline), t, model)
    }

    /// The same camera on `worldline`, at its event there at lab time `t`
    /// and moving with its velocity then; `None` if that is not slower
    /// than light.
    pub fn on_worldline(self, worldline: CameraWorldline, t: f64, model: Model) -> Option<Camera> {
        let (event, velocity) = worldline.event_at(t);
        Camera {
            event,
            worldline: Some(worldline),
            ..self
        }
        .moving(velocity, model)
    }

    /// The inertial camera that the camera is at lab time `t`: itself when
    /// it does not accelerate or `t` is its event's time; otherwise its
    /// worldline's event and velocity at `t` (the instantaneous rest
    /// frame there).
    pub fn at(&self, t: f64) -> Camera {
        *self.at_in(t, &mut None)
    }

    /// [`Camera::at`] without a copy where the camera stays itself: put in
    /// `slot` where it differs (and `slot` emptied otherwise), `self`
    /// where it does not. A camera holds its worldline's waypoints inline,
    /// about a kilobyte, which a copy for every sample of a frame would
    /// move.
    pub(crate) fn at_in<'a>(&'a self, t: f64, slot: &'a mut Option<Camera>) -> &'a Camera {
        *slot = None;
        match self.worldline {
            Some(w) if t != self.event.t => {
                let (event, velocity) = w.event_at(t);
                slot.insert(Camera {
                    event,
                    velocity,
                    ..*self
                })
            }
            _ => self,
        }
    }

    /// The lab time of a sample taken `offset` of camera time after lab
    /// time `t`: for a camera on a worldline the offset is of its own
    /// proper time (a shutter integrates over the camera's clock).
    pub fn sample_time(&self, t: f64, offset: f64) -> f64 {
        match self.worldline {
            Some(w) if offset != 0.0 => w.lab_time_after(t, offset),
            _ => t + offset,
        }
    }

    /// Where the camera is at lab time `t`.
    pub fn position_at(&self, t: f64) -> DVec3 {
        self.event.x + self.velocity * (t - self.event.t)
    }

    /// A line of sight from the camera's rest frame into the lab.
    #[inline]
    fn sight_to_lab(&self, n: DVec3) -> DVec3 {
        let v = self.velocity;
        match self.kinematics {
            _ if v == DVec3::ZERO => n,
            Kinematics::None => n,
            // The past-directed null vector (-1, n) of the camera's frame, boosted.
            Kinematics::Lorentz => {
                let lab = Boost::new(v)
                    .expect("checked in moving()")
                    .to_lab(FourVector::new(-1.0, n));
                (lab.x / -lab.t).normalize()
            }
            // Light moves at c in the lab; in the camera's frame its velocity is
            // u - v, along -n: so n_lab = lambda n - v with |n_lab| = 1.
            Kinematics::Galilean => {
                let nv = n.dot(v);
                let lambda = nv + (nv * nv - v.length_squared() + 1.0).sqrt();
                (n * lambda - v).normalize()
            }
        }
    }

    /// A lab line of sight into the camera's rest frame (inverse of `sight_to_lab`).
    fn sight_from_lab(&self, d: DVec3) -> DVec3 {
        let v = self.velocity;
        match self.kinematics {
            _ if v == DVec3::ZERO => d,
            Kinematics::None => d,
            Kinematics::Lorentz => {
                let rest = Boost::new(v)
                    .expect("checked in moving()")
                    .to_rest(FourVector::new(-1.0, d));
                (rest.x / -rest.t).normalize()
            }
            Kinematics::Galilean => (d + v).normalize(),
        }
    }

    /// Vertical field of view, degrees.
    pub fn vfov_deg(&self) -> f64 {
        self.vfov_deg
    }

    /// The least angle, radians, between the lab lines of sight of
    /// neighbouring pixels: the centre pixel's 2 tan(vfov / 2) / height,
    /// times cos^2 of the angle out to the image's corner (a flat image's
    /// pixels subtend less away from its centre), times
    /// sqrt((1 - v) / (1 + v)) for a camera moving at v (aberration
    /// narrows a solid angle's extent by at most that, paper eq. 6).
    pub fn pixel_angle(&self) -> f64 {
        let th = self.tan_half_v();
        let aspect = f64::from(self.width) / f64::from(self.height);
        let corner2 = th * th * (1.0 + aspect * aspect);
        let v = self.velocity.length().min(1.0);
        2.0 * th / f64::from(self.height) / (1.0 + corner2) * ((1.0 - v) / (1.0 + v)).sqrt()
    }

    /// Half-extent of the image plane at unit distance, vertically.
    fn tan_half_v(&self) -> f64 {
        self.tan_half_v
    }

    /// Unit direction in the camera's own frame through the continuous
    /// pixel position (px, py).
    #[inline]
    pub fn camera_direction(&self, px: f64, py: f64) -> DVec3 {
        let th = self.tan_half_v();
        let aspect = f64::from(self.width) / f64::from(self.height);
        let u = (2.0 * px / f64::from(self.width) - 1.0) * th * aspect;
        let v = (1.0 - 2.0 * py / f64::from(self.height)) * th;
        (self.forward + self.right * u + self.up * v).normalize()
    }

    /// Unit direction (lab frame, from the camera into the scene) of the line
    /// of sight through the continuous pixel position (px, py).
    #[inline]
    pub fn direction(&self, px: f64, py: f64) -> DVec3 {
        self.sight_to_lab(self.camera_direction(px, py))
    }

    /// Inverse of [`Camera::direction`]: the continuous pixel position where
    /// light arriving from lab direction `dir` lands; `None` if behind.
    pub fn pixel_of(&self, dir: DVec3) -> Option<(f64, f64)> {
        self.project(self.sight_from_lab(dir))
    }

    /// The continuous pixel position of a direction given in the camera's
    /// own frame (for directions behind the camera, a point off the image).
    pub fn pixel_of_camera(&self, dir: DVec3) -> (f64, f64) {
        self.project(dir).unwrap_or((-1.0, -1.0))
    }

    fn project(&self, dir: DVec3) -> Option<(f64, f64)> {
        let f = dir.dot(self.forward);
        if f <= 0.0 {
            return None;
        }
        let th = self.tan_half_v();
        let aspect = f64::from(self.width) / f64::from(self.height);
        let u = dir.dot(self.right) / f / (th * aspect);
        let v = dir.dot(self.up) / f / th;
        Some((
            (u + 1.0) * f64::from(self.width) / 2.0,
            (1.0 - v) * f64::from(self.height) / 2.0,
        ))
    }

    /// The primary ray through (px, py) for the camera at lab time `t`.
    pub fn ray(&self, px: f64, py: f64, t: f64, light: LightSpeed) -> Ray {
        Ray::backwards(
            Event::new(t, self.position_at(t)),
            self.direction(px, py),
            light,
        )
    }

    /// [`Camera::ray`] of each lane: `cameras[j]` through its pixel position
    /// and lab time `at[j]` = (px, py, t), the same rays to the bit. Each
    /// stage is taken for every lane before the next, so that the lanes'
    /// chains of divisions and square roots are in flight together rather
    /// than one after another.
    #[inline]
    pub(crate) fn rays<const N: usize>(
        cameras: &[&Camera; N],
        at: &[(f64, f64, f64); N],
        light: LightSpeed,
    ) -> [Ray; N] {
        let own: [DVec3; N] =
            std::array::from_fn(|j| cameras[j].camera_direction(at[j].0, at[j].1));
        let lab: [DVec3; N] = std::array::from_fn(|j| cameras[j].sight_to_lab(own[j]));
        std::array::from_fn(|j| {
            let t = at[j].2;
            Ray::backwards(Event::new(t, cameras[j].position_at(t)), lab[j], light)
        })
    }
}

/// Light speed (infinite | finite) and Lorentz transform (off | on).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Model {
    /// Whether light is instantaneous or travels at c = 1.
    pub light_speed: LightSpeed,
    /// Whether V_obj objects are Lorentz-transformed on insertion; when off
    /// every object is inserted as an H_obj.
    pub lorentz: bool,
}

impl Model {
    /// Conventional ray tracing of the lab slice t = t_c (Figure 1, top band).
    pub const INFINITE: Model = Model {
        light_speed: LightSpeed::Infinite,
        lorentz: false,
    };
    /// Finite light speed, no Lorentz transform (Figure 1, centre band).
    pub const CLASSICAL: Model = Model {
        light_speed: LightSpeed::Finite,
        lorentz: false,
    };
    /// Finite light speed with the Lorentz transform (Figure 1, bottom band).
    pub const RELATIVISTIC: Model = Model {
        light_speed: LightSpeed::Finite,
        lorentz: true,
    };

    /// `infinite`, `classical` or `relativistic`.
    pub fn from_name(name: &str) -> Option<Model> {
        match name {
            "infinite" => Some(Model::INFINITE),
            "classical" => Some(Model::CLASSICAL),
            "relativistic" => Some(Model::RELATIVISTIC),
            _ => None,
        }
    }
}

impl fmt::Display for Model {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.light_speed, self.lorentz) {
            (LightSpeed::Infinite, false) => write!(f, "infinite"),
            (LightSpeed::Finite, false) => write!(f, "classical"),
            (LightSpeed::Finite, true) => write!(f, "relativistic"),
            (LightSpeed::Infinite, true) => write!(f, "infinite+lorentz"),
        }
    }
}

#[cfg(test)]
mod tests;
