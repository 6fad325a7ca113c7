//! The worldline of an accelerating camera: its event and velocity at a
//! lab time, and the lab time a proper time later (a shutter spans the
//! camera's own clock).

use crate::scene::Hyperbolic;
use crate::spacetime::{Event, WaypointWindow};
use glam::DVec3;

/// The worldline of an accelerating camera.
// The waypoints are held inline, not boxed, so that a camera stays `Copy`
// and a shutter sample's camera is made without an allocation.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CameraWorldline {
    /// Constant proper acceleration along a line.
    Hyperbolic(Hyperbolic),
    /// Through waypoints: the stretch of them that the frame's shutter
    /// spans.
    Waypoints(WaypointWindow),
}

impl CameraWorldline {
    /// The event and lab velocity at lab time `t`.
    pub(super) fn event_at(&self, t: f64) -> (Event, DVec3) {
        match self {
            CameraWorldline::Hyperbolic(w) => w.event_at(t),
            CameraWorldline::Waypoints(w) => w.event_at(t),
        }
    }

    /// The lab time at which proper time `offset` has passed since lab
    /// time `t`.
    pub(super) fn lab_time_after(&self, t: f64, offset: f64) -> f64 {
        match self {
            CameraWorldline::Hyperbolic(w) => w.lab_time(w.proper_time(t) + offset),
            CameraWorldline::Waypoints(w) => w.lab_time_after(t, offset),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::{Attitude, Camera, Model};
    use approx::assert_abs_diff_eq;

    fn cam(attitude: Attitude) -> Camera {
        Camera::new(
            Event::new(0.0, DVec3::new(1.0, 2.0, 3.0)),
            attitude,
            60.0,
            64,
            48,
        )
        .unwrap()
    }

    fn rocket() -> Hyperbolic {
        Hyperbolic {
            start: Event::new(1.0, DVec3::new(1.0, 2.0, 3.0)),
            direction: DVec3::NEG_Z,
            acceleration: 0.25,
            initial_velocity: 0.3,
            duration: 100.0,
            tolerance: 1e-4,
        }
    }

    #[test]
    fn an_accelerating_camera_at_its_event_is_the_inertial_camera_there() {
        let still = cam(Attitude::YawPitch {
            yaw_deg: 20.0,
            pitch_deg: 5.0,
        });
        let w = rocket();
        let moving = still
            .accelerating(w, 7.5, Model::RELATIVISTIC)
            .expect("slower than light");
        let (event, velocity) = w.event_at(7.5);
        let inertial = Camera { event, ..still }
            .moving(velocity, Model::RELATIVISTIC)
            .unwrap();
        assert_eq!(
            Camera {
                worldline: None,
                ..moving
            },
            inertial
        );
        assert_eq!(moving.at(7.5), moving);
        let later = moving.at(9.0);
        assert_eq!(later.event, w.event_at(9.0).0);
        assert_ne!(later.velocity, moving.velocity);
        // The velocity is the derivative of the position; the speed tanh(phi).
        let h = 1e-6;
        let dx = (w.event_at(7.5 + h).0.x - w.event_at(7.5 - h).0.x) / (2.0 * h);
        assert_abs_diff_eq!((dx - velocity).length(), 0.0, epsilon = 1e-8);
        assert_abs_diff_eq!(velocity.length(), w.rapidity(7.5).tanh(), epsilon = 1e-12);
    }

    #[test]
    fn a_shutter_spans_the_accelerating_cameras_own_time() {
        let w = rocket();
        let moving = cam(Attitude::YawPitch {
            yaw_deg: 0.0,
            pitch_deg: 0.0,
        })
        .accelerating(w, 5.0, Model::RELATIVISTIC)
        .unwrap();
        assert_eq!(moving.sample_time(5.0, 0.0), 5.0);
        let t = moving.sample_time(5.0, 0.5);
        assert_abs_diff_eq!(w.proper_time(t) - w.proper_time(5.0), 0.5, epsilon = 1e-12);
        // Lab time runs faster than the moving camera's clock.
        assert!(t - 5.0 > 0.5);
        assert_abs_diff_eq!(w.lab_time(w.proper_time(12.0)), 12.0, epsilon = 1e-12);
        // An inertial camera's shutter is of lab time.
        let inertial = Camera {
            worldline: None,
            ..moving
        };
        assert_eq!(inertial.sample_time(5.0, 0.5), 5.5);
    }
}
