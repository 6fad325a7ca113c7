//! A camera through keyframes of lab position and velocity (docs/physics.md,
//! "The accelerated observer"): its event, velocity and proper time,
//! written independently of the fixture's and the renderer's evaluation of
//! the curve. Each interval's cubic is taken in power form, its
//! coefficients solved from the four conditions x(0) = p0, x(1) = p1,
//! x'(0) = dt v0, x'(1) = dt v1 in s = (t - t0) / dt, and evaluated by
//! Horner's rule; the proper time is the integral of sqrt(1 - |v|^2) dt by
//! composite Simpson's rule.

use glam::DVec3;

/// Simpson intervals per keyframe interval for the proper time.
const SIMPSON: u32 = 2048;

/// One keyframe: lab time, position and velocity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraKey {
    /// Lab time.
    pub t: f64,
    /// Lab position.
    pub position: DVec3,
    /// Lab velocity (fraction of c).
    pub velocity: DVec3,
}

/// A camera's worldline through keyframes (lab time increasing).
#[derive(Clone, Debug, PartialEq)]
pub struct KeyframedCamera {
    /// The keyframes.
    pub keys: Vec<CameraKey>,
}

impl KeyframedCamera {
    /// The interval holding lab time `t` and the power-form coefficients
    /// c0 + c1 s + c2 s^2 + c3 s^3 of its cubic: c0 = p0, c1 = dt v0,
    /// c2 = 3 (p1 - p0) - dt (2 v0 + v1), c3 = 2 (p0 - p1) + dt (v0 + v1);
    /// `None` outside the keyframes.
    fn cubic(&self, t: f64) -> Option<(f64, f64, [DVec3; 4])> {
        let i = self
            .keys
            .windows(2)
            .position(|w| t >= w[0].t && t <= w[1].t)?;
        let (a, b) = (self.keys[i], self.keys[i + 1]);
        let dt = b.t - a.t;
        let c = [
            a.position,
            a.velocity * dt,
            (b.position - a.position) * 3.0 - (a.velocity * 2.0 + b.velocity) * dt,
            (a.position - b.position) * 2.0 + (a.velocity + b.velocity) * dt,
        ];
        Some(((t - a.t) / dt, dt, c))
    }

    /// The camera's lab position and velocity at lab time `t`; `None`
    /// outside the keyframes.
    pub fn at(&self, t: f64) -> Option<(DVec3, DVec3)> {
        let (s, dt, c) = self.cubic(t)?;
        let x = c[0] + s * (c[1] + s * (c[2] + s * c[3]));
        let v = (c[1] + s * (c[2] * 2.0 + s * c[3] * 3.0)) / dt;
        Some((x, v))
    }

    /// The camera's proper time from the first keyframe to lab time `t`
    /// (within the keyframes), by Simpson's rule on each interval.
    pub fn proper_time(&self, t: f64) -> f64 {
        let rate = |u: f64| {
            let v = self.at(u).map_or(DVec3::ZERO, |(_, v)| v);
            (1.0 - v.length_squared()).max(0.0).sqrt()
        };
        let mut tau = 0.0;
        for w in self.keys.windows(2) {
            if t <= w[0].t {
                break;
            }
            let (a, b) = (w[0].t, t.min(w[1].t));
            let h = (b - a) / f64::from(SIMPSON);
            let inner: f64 = (1..SIMPSON)
                .map(|k| rate(a + h * f64::from(k)) * if k % 2 == 1 { 4.0 } else { 2.0 })
                .sum();
            tau += h / 3.0 * (rate(a) + inner + rate(b));
        }
        tau
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(t: f64, x: f64, v: f64) -> CameraKey {
        CameraKey {
            t,
            position: DVec3::new(x, 0.0, 0.0),
            velocity: DVec3::new(v, 0.0, 0.0),
        }
    }

    #[test]
    fn the_cubic_passes_its_keyframes_with_their_velocities() {
        let cam = KeyframedCamera {
            keys: vec![key(1.0, 0.0, 0.0), key(3.0, 1.0, 0.6), key(6.0, 2.0, -0.2)],
        };
        for k in &cam.keys {
            let (x, v) = cam.at(k.t).unwrap();
            assert!((x - k.position).length() < 1e-14 && (v - k.velocity).length() < 1e-14);
        }
        // The velocity is the position's derivative.
        let h = 1e-6;
        for t in [1.5, 2.99, 4.2] {
            let dx = (cam.at(t + h).unwrap().0 - cam.at(t - h).unwrap().0) / (2.0 * h);
            assert!((dx - cam.at(t).unwrap().1).length() < 1e-8, "{t}");
        }
        assert!(cam.at(0.5).is_none() && cam.at(6.5).is_none());
    }

    #[test]
    fn uniform_motion_keeps_the_clock_of_time_dilation() {
        // 0.6c: proper time runs at 0.8 of lab time.
        let cam = KeyframedCamera {
            keys: vec![key(2.0, 0.0, 0.6), key(7.0, 3.0, 0.6)],
        };
        assert!((cam.proper_time(4.5) - 2.0).abs() < 1e-13);
        assert!((cam.at(4.5).unwrap().0.x - 1.5).abs() < 1e-14);
        // The control: a camera at rest keeps lab time.
        let rest = KeyframedCamera {
            keys: vec![key(2.0, 0.0, 0.0), key(7.0, 0.0, 0.0)],
        };
        assert!((rest.proper_time(4.5) - 2.5).abs() < 1e-13);
    }
}
