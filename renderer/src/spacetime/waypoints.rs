//! A worldline given by waypoints: lab events and the lab velocities
//! there, joined by cubic Hermite curves in lab time, and the proper time
//! along it.
//!
//! Between waypoints a and b (dt = t_b - t_a, s = (t - t_a) / dt) the
//! point is at x(t) = h00(s) x_a + h01(s) x_b + dt (h10(s) v_a + h11(s) v_b)
//! and moves with its derivative, so it passes each waypoint at its
//! position with its velocity. Its proper time is the integral of
//! sqrt(1 - |v|^2) dt, taken by 5-point Gauss-Legendre on equal pieces.

use super::Event;
use glam::DVec3;

/// A lab event on a worldline and the lab velocity there (|v| < 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Waypoint {
    /// Lab time, t.units.
    pub t: f64,
    /// Lab position, l.units.
    pub position: DVec3,
    /// Lab velocity, fraction of c.
    pub velocity: DVec3,
}

impl Waypoint {
    /// The cubic Hermite curve from `self` to `next` at lab time `t`:
    /// position and velocity (its derivative).
    pub fn hermite(&self, next: &Waypoint, t: f64) -> (DVec3, DVec3) {
        let (a, b) = (self, next);
        let dt = b.t - a.t;
        let s = (t - a.t) / dt;
        let (s2, s3) = (s * s, s * s * s);
        let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
        let h01 = -2.0 * s3 + 3.0 * s2;
        let h10 = s3 - 2.0 * s2 + s;
        let h11 = s3 - s2;
        let d00 = 6.0 * s2 - 6.0 * s;
        let d10 = 3.0 * s2 - 4.0 * s + 1.0;
        let d11 = 3.0 * s2 - 2.0 * s;
        let x = a.position * h00 + b.position * h01 + (a.velocity * h10 + b.velocity * h11) * dt;
        let v = (a.position * d00 - b.position * d00) / dt + a.velocity * d10 + b.velocity * d11;
        (x, v)
    }

    /// The proper time on the curve from `self` to `next` between lab
    /// times `t0` and `t1` (both within the segment; negative if
    /// `t1 < t0`): 5-point Gauss-Legendre on `pieces` equal pieces.
    pub fn proper_time(&self, next: &Waypoint, (t0, t1): (f64, f64), pieces: u32) -> f64 {
        const NODES: [(f64, f64); 5] = [
            (0.0, 0.568_888_888_888_888_9),
            (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
            (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
            (0.906_179_845_938_664, 0.236_926_885_056_189_1),
            (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
        ];
        let piece = (t1 - t0) / f64::from(pieces);
        let mut tau = 0.0;
        for p in 0..pieces {
            let mid = t0 + piece * (f64::from(p) + 0.5);
            for (x, w) in NODES {
                let v2 = self.hermite(next, mid + x * piece / 2.0).1.length_squared();
                tau += w * (1.0 - v2).max(0.0).sqrt() * piece / 2.0;
            }
        }
        tau
    }
}

/// Most waypoints a camera carries for its shutter ([`WaypointWindow`]).
pub const MAX_WINDOW_WAYPOINTS: usize = 16;

/// Gauss-Legendre pieces per segment within a window.
const WINDOW_PIECES: u32 = 4;

/// The stretch of a worldline on waypoints that a camera's frame and its
/// shutter span: two to [`MAX_WINDOW_WAYPOINTS`] consecutive waypoints,
/// lab time increasing (held inline, so that a camera stays `Copy`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WaypointWindow {
    points: [Waypoint; MAX_WINDOW_WAYPOINTS],
    len: usize,
}

impl WaypointWindow {
    /// The window through `points`; `None` unless there are two to
    /// [`MAX_WINDOW_WAYPOINTS`] of them with increasing lab times.
    pub fn new(points: &[Waypoint]) -> Option<WaypointWindow> {
        let ordered = points.windows(2).all(|w| w[0].t < w[1].t);
        if !(2..=MAX_WINDOW_WAYPOINTS).contains(&points.len()) || !ordered {
            return None;
        }
        let mut window = WaypointWindow {
            points: [points[0]; MAX_WINDOW_WAYPOINTS],
            len: points.len(),
        };
        window.points[..points.len()].copy_from_slice(points);
        Some(window)
    }

    fn points(&self) -> &[Waypoint] {
        &self.points[..self.len]
    }

    /// The first and last waypoints' lab times.
    pub fn span(&self) -> (f64, f64) {
        (self.points[0].t, self.points[self.len - 1].t)
    }

    /// The event and lab velocity at lab time `t` (clamped to the span):
    /// a waypoint's own, as given, at its time.
    pub fn event_at(&self, t: f64) -> (Event, DVec3) {
        let (t0, t1) = self.span();
        let t = t.clamp(t0, t1);
        let p = self.points();
        if let Some(k) = p.iter().find(|k| k.t == t) {
            return (Event::new(k.t, k.position), k.velocity);
        }
        let i = p.partition_point(|k| k.t <= t) - 1;
        let (x, v) = p[i].hermite(&p[i + 1], t);
        (Event::new(t, x), v)
    }

    /// The proper time from lab time `t0` to `t1` (both within the span;
    /// negative if `t1 < t0`), the quadrature split at the waypoints.
    pub fn proper_time(&self, t0: f64, t1: f64) -> f64 {
        if t1 < t0 {
            return -self.proper_time(t1, t0);
        }
        self.points()
            .windows(2)
            .filter(|w| w[1].t > t0 && w[0].t < t1)
            .map(|w| w[0].proper_time(&w[1], (t0.max(w[0].t), t1.min(w[1].t)), WINDOW_PIECES))
            .sum()
    }

    /// The lab time at which proper time `offset` has passed since lab
    /// time `t` (clamped to the span): Newton's method on the proper time,
    /// whose derivative is sqrt(1 - |v|^2), kept within a bisection
    /// bracket, until a step is within a few units of the last place.
    pub fn lab_time_after(&self, t: f64, offset: f64) -> f64 {
        let (mut lo, mut hi) = self.span();
        let mut x = t.clamp(lo, hi);
        for _ in 0..100 {
            let miss = self.proper_time(t, x) - offset;
            if miss == 0.0 {
                return x;
            }
            if miss < 0.0 {
                lo = x;
            } else {
                hi = x;
            }
            let rate = (1.0 - self.event_at(x).1.length_squared()).max(0.0).sqrt();
            let newton = x - miss / rate;
            let next = if newton >= lo && newton <= hi {
                newton
            } else {
                lo + (hi - lo) / 2.0
            };
            if (next - x).abs() <= 4.0 * f64::EPSILON * x.abs().max(1.0) {
                return next;
            }
            x = next;
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn w(t: f64, x: f64, v: f64) -> Waypoint {
        Waypoint {
            t,
            position: DVec3::new(x, 0.0, 0.0),
            velocity: DVec3::new(v, 0.0, 0.0),
        }
    }

    #[test]
    fn uniform_motion_keeps_its_clock() {
        // At 0.6c proper time runs at 0.8 of lab time.
        let win =
            WaypointWindow::new(&[w(1.0, 0.0, 0.6), w(3.0, 1.2, 0.6), w(9.0, 4.8, 0.6)]).unwrap();
        assert!((win.proper_time(2.0, 5.0) - 2.4).abs() < 1e-14);
        assert!((win.proper_time(5.0, 2.0) + 2.4).abs() < 1e-14);
        let t = win.lab_time_after(2.0, 2.4);
        assert!((t - 5.0).abs() < 1e-13, "{t}");
        let back = win.lab_time_after(5.0, -0.8);
        assert!((back - 4.0).abs() < 1e-13, "{back}");
        // The control: a lab-time offset is not a proper-time one.
        assert!((win.lab_time_after(2.0, 1.0) - 3.0).abs() > 0.2);
        assert_eq!(
            win.event_at(3.0),
            (
                Event::new(3.0, DVec3::new(1.2, 0.0, 0.0)),
                DVec3::new(0.6, 0.0, 0.0)
            )
        );
    }

    #[test]
    fn the_clock_of_a_curve_that_speeds_up_is_inverted() {
        let win =
            WaypointWindow::new(&[w(0.0, 0.0, 0.0), w(4.0, 2.0, 0.8), w(6.0, 2.5, -0.5)]).unwrap();
        for (t, u) in [(1.0, 2.5), (3.9, 1.0), (5.0, -3.0)] {
            let s = win.lab_time_after(t, u);
            assert!((win.proper_time(t, s) - u).abs() < 1e-13, "{t} {u}: {s}");
        }
        assert!(WaypointWindow::new(&[w(0.0, 0.0, 0.0)]).is_none());
        assert!(WaypointWindow::new(&[w(1.0, 0.0, 0.0), w(1.0, 0.0, 0.0)]).is_none());
    }
}
