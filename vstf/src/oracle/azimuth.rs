//! When a uniformly moving point is seen crossing a given azimuth.
//!
//! The point moves on x(t) = x0 + v (t - t0); the camera is at rest at c.
//! Light that reaches the camera from lab azimuth phi (about +y, from -z
//! towards +x) left a point on the half-plane through c that holds +y and
//! the direction a = (sin phi, 0, -cos phi). The point is on that
//! half-plane at the emission time t_e where (x(t_e) - c) . n = 0, with
//! n = (cos phi, 0, sin phi) the half-plane's normal, and
//! (x(t_e) - c) . a > 0; the equation is linear in t_e:
//! t_e = t0 - (x0 - c) . n / (v . n). That light arrives at the camera
//! time t_c = t_e + |x(t_e) - c| (the past light cone, c = 1); with
//! infinitely fast light, at t_c = t_e.
//!
//! The angles go through `libm`, as everything on a path to a pixel does
//! (the result is a camera time).

use super::seen::PointWorldline;
use glam::DVec3;
use std::fmt;

/// The event at which a point is seen crossing an azimuth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AzimuthCrossing {
    /// Lab time at which the point is on the azimuth's half-plane.
    pub emitted: f64,
    /// Where it is then.
    pub x: DVec3,
    /// The camera time at which that light arrives.
    pub seen: f64,
}

/// Why a point is never seen at an azimuth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AzimuthMiss {
    /// It moves parallel to the azimuth's half-plane (or not at all), so it
    /// is on it always or never.
    Parallel,
    /// It crosses the plane behind the camera (at the opposite azimuth).
    Behind,
}

impl fmt::Display for AzimuthMiss {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            AzimuthMiss::Parallel => {
                "it moves parallel to that azimuth's vertical plane (or not at all), so it never crosses it"
            }
            AzimuthMiss::Behind => {
                "it crosses that azimuth's vertical plane behind the camera (at the opposite azimuth)"
            }
        })
    }
}

/// The event at which `p` is seen from a camera at rest at `camera`
/// crossing lab azimuth `azimuth_deg`, with light of finite speed or
/// (`finite` false) infinitely fast.
pub fn seen_at_azimuth(
    p: &PointWorldline,
    camera: DVec3,
    azimuth_deg: f64,
    finite: bool,
) -> Result<AzimuthCrossing, AzimuthMiss> {
    let phi = azimuth_deg.to_radians();
    let (s, c) = (libm::sin(phi), libm::cos(phi));
    let normal = DVec3::new(c, 0.0, s);
    let ahead = DVec3::new(s, 0.0, -c);
    let rate = p.v.dot(normal);
    if rate.abs() < 1e-12 {
        return Err(AzimuthMiss::Parallel);
    }
    let emitted = p.t0 - (p.x0 - camera).dot(normal) / rate;
    let x = p.at(emitted);
    if (x - camera).dot(ahead) <= 0.0 {
        return Err(AzimuthMiss::Behind);
    }
    let delay = if finite { x.distance(camera) } else { 0.0 };
    Ok(AzimuthCrossing {
        emitted,
        x,
        seen: emitted + delay,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::oracle::retarded;

    fn rod() -> PointWorldline {
        PointWorldline {
            t0: 0.0,
            x0: DVec3::new(-20.0, 0.0, -10.0),
            v: DVec3::new(0.9, 0.0, 0.0),
        }
    }

    #[test]
    fn straight_ahead_is_seen_one_light_time_after_crossing() {
        let hit = seen_at_azimuth(&rod(), DVec3::ZERO, 0.0, true).unwrap();
        assert!((hit.emitted - 20.0 / 0.9).abs() < 1e-12, "{hit:?}");
        assert!((hit.seen - (20.0 / 0.9 + 10.0)).abs() < 1e-12, "{hit:?}");
        let inf = seen_at_azimuth(&rod(), DVec3::ZERO, 0.0, false).unwrap();
        assert_eq!(inf.seen, inf.emitted);
    }

    #[test]
    fn the_retarded_direction_at_the_solved_time_has_that_azimuth() {
        for az in [-30.0, -5.0, 12.5, 40.0] {
            let hit = seen_at_azimuth(&rod(), DVec3::new(1.0, 2.0, 3.0), az, true).unwrap();
            let seen = retarded(&rod(), hit.seen, DVec3::new(1.0, 2.0, 3.0)).unwrap();
            let d = seen.direction;
            let measured = d.x.atan2(-d.z).to_degrees();
            assert!((measured - az).abs() < 1e-9, "{az}: {measured}");
            // Negative control: a camera time a little off is another azimuth.
            let off = retarded(&rod(), hit.seen + 0.5, DVec3::new(1.0, 2.0, 3.0)).unwrap();
            let other = off.direction.x.atan2(-off.direction.z).to_degrees();
            assert!((other - az).abs() > 0.1, "{az}: {other}");
        }
    }

    #[test]
    fn parallel_and_behind_are_refused() {
        let mut p = rod();
        p.v = DVec3::new(0.0, 0.0, -0.5);
        assert_eq!(
            seen_at_azimuth(&p, DVec3::ZERO, 0.0, true),
            Err(AzimuthMiss::Parallel)
        );
        p = rod();
        p.x0.z = 10.0;
        assert_eq!(
            seen_at_azimuth(&p, DVec3::ZERO, 0.0, true),
            Err(AzimuthMiss::Behind)
        );
    }
}
