//! A flat mirror in uniform motion, reflecting a static marker: where the
//! camera sees the marker's reflected edge, and the reflected light's
//! frequency shift, from Einstein's law for a moving mirror (1905,
//! section 7; derived in docs/physics.md, "Moving mirrors").
//!
//! Only the velocity's component along the normal matters: motion in the
//! mirror's plane sweeps out the same world-sheet. With b the speed at
//! which the mirror recedes from the light falling on it (b < 0:
//! approaching), theta_i the angle of incidence and theta_r that of
//! reflection, both from the normal on the lit side,
//!
//!   cos theta_r = ((1 + b^2) cos theta_i - 2b) / (1 - 2b cos theta_i + b^2),
//!   nu_r / nu_i = (1 - 2b cos theta_i + b^2) / (1 - b^2),
//!
//! and the incident and reflected rays lie in one plane with the normal.
//! b = 0 is the static law theta_r = theta_i with no shift.

use glam::DVec3;

/// cos theta_i of the light a mirror receding at `b` reflects into
/// cos theta_r: the law above solved for theta_i (time reversal: the same
/// law with b -> -b).
pub fn incidence_for(cos_r: f64, b: f64) -> f64 {
    ((1.0 + b * b) * cos_r + 2.0 * b) / (1.0 + b * b + 2.0 * b * cos_r)
}

/// nu_r / nu_i for light falling at cos theta_i on a mirror receding at `b`.
pub fn frequency_ratio(cos_i: f64, b: f64) -> f64 {
    (1.0 - 2.0 * b * cos_i + b * b) / (1.0 - b * b)
}

/// A flat mirror: at lab time `t0` it passes through `point` with unit
/// normal `normal`, moving with lab velocity `velocity`.
#[derive(Clone, Copy, Debug)]
pub struct MovingMirror {
    /// Lab time of `point`.
    pub t0: f64,
    /// A point of the mirror's plane at `t0`.
    pub point: DVec3,
    /// The plane's unit normal (either side).
    pub normal: DVec3,
    /// Lab velocity (fraction of c).
    pub velocity: DVec3,
}

/// A static flat marker with a straight edge through `a` and `b`, lying
/// in the plane through them with unit normal `normal`.
#[derive(Clone, Copy, Debug)]
pub struct Marker {
    /// One end of the edge.
    pub a: DVec3,
    /// The other end.
    pub b: DVec3,
    /// The marker's unit normal.
    pub normal: DVec3,
}

/// The light seen along one line of sight by way of the mirror.
#[derive(Clone, Copy, Debug)]
pub struct Bounce {
    /// Lab time and place of the reflection.
    pub at: (f64, DVec3),
    /// cos theta_r and cos theta_i.
    pub cos_r: f64,
    /// cos theta_i.
    pub cos_i: f64,
    /// Where the incident light left the marker's plane.
    pub on_marker: DVec3,
    /// Which side of the edge's line `on_marker` lies (signed distance
    /// within the marker's plane, l.units).
    pub side: f64,
    /// nu_seen / nu_emitted.
    pub factor: f64,
}

/// The path of the light a camera at (`tc`, `camera`) receives from unit
/// direction `d` (towards where it came from): back to the moving mirror
/// (where the light cone meets its plane), reflected by Einstein's law,
/// and back to the marker's plane. `None` if the line of sight never meets
/// the mirror ahead, or the reflected light does not come from in front of
/// the marker's plane.
pub fn bounce(
    m: &MovingMirror,
    marker: &Marker,
    tc: f64,
    camera: DVec3,
    d: DVec3,
) -> Option<Bounce> {
    // The photon arriving at the camera at tc from d was at camera + s d at
    // tc - s; the mirror's plane holds x with n.(x - point - v (t - t0)) = 0.
    let n = m.normal;
    let offset = camera - m.point - m.velocity * (tc - m.t0);
    let s = -n.dot(offset) / (n.dot(d) + n.dot(m.velocity));
    if !(s > 0.0 && s.is_finite()) {
        return None;
    }
    let (t, x) = (tc - s, camera + d * s);
    // The lit side faces the camera: the normal there, the outgoing
    // photon's direction and the mirror's recession from the light.
    let k_out = -d;
    let lit = if k_out.dot(n) >= 0.0 { n } else { -n };
    let cos_r = k_out.dot(lit);
    let b = -m.velocity.dot(lit);
    let cos_i = incidence_for(cos_r, b);
    if !(cos_i > 0.0 && cos_i <= 1.0 + 1e-12) {
        return None;
    }
    let tangential = k_out - lit * cos_r;
    let sin_i = (1.0 - cos_i * cos_i).max(0.0).sqrt();
    let along = tangential.try_normalize().unwrap_or(DVec3::ZERO);
    // The incident photon keeps its direction along the mirror and falls
    // towards it: it came from back along r.
    let r = lit * cos_i - along * sin_i;
    let depth = marker.normal.dot(marker.a - x) / marker.normal.dot(r);
    if !(depth > 0.0 && depth.is_finite()) {
        return None;
    }
    let on_marker = x + r * depth;
    let line = (marker.b - marker.a).normalize();
    let side = (on_marker - marker.a).cross(line).dot(marker.normal);
    Some(Bounce {
        at: (t, x),
        cos_r,
        cos_i,
        on_marker,
        side,
        factor: frequency_ratio(cos_i, b),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The law inverts itself, keeps normal incidence normal, gives the
    /// head-on double shift (1+w)/(1-w) for a mirror approaching at w, and
    /// at b = 0 is the static law.
    #[test]
    fn einsteins_law_and_its_limits() {
        for b in [-0.7, -0.3, 0.0, 0.4, 0.8] {
            for cos_i in [1.0, 0.9, 0.6, 0.2] {
                let cos_r = ((1.0 + b * b) * cos_i - 2.0 * b) / (1.0 - 2.0 * b * cos_i + b * b);
                assert!((incidence_for(cos_r, b) - cos_i).abs() < 1e-12);
            }
            assert!((incidence_for(1.0, b) - 1.0).abs() < 1e-12);
        }
        let w: f64 = 0.5;
        assert!((frequency_ratio(1.0, -w) - (1.0 + w) / (1.0 - w)).abs() < 1e-12);
        assert_eq!(incidence_for(0.3, 0.0), 0.3);
        assert_eq!(frequency_ratio(0.3, 0.0), 1.0);
    }

    /// A static mirror at z = -10 facing a camera at the origin, marker
    /// edge at x = 4 on the plane z = 2: the edge is seen where
    /// 22 tan(alpha) = 4, by the image method.
    #[test]
    fn a_static_mirror_shows_the_mirror_image() {
        let m = MovingMirror {
            t0: 0.0,
            point: DVec3::new(0.0, 0.0, -10.0),
            normal: DVec3::Z,
            velocity: DVec3::ZERO,
        };
        let marker = Marker {
            a: DVec3::new(4.0, -1.0, 2.0),
            b: DVec3::new(4.0, 1.0, 2.0),
            normal: DVec3::Z,
        };
        let alpha = (4.0f64 / 22.0).atan();
        let d = DVec3::new(alpha.sin(), 0.0, -alpha.cos());
        let hit = bounce(&m, &marker, 0.0, DVec3::ZERO, d).unwrap();
        assert!(hit.side.abs() < 1e-12, "{}", hit.side);
        assert!((hit.at.0 + 10.0 / alpha.cos()).abs() < 1e-12);
        assert_eq!(hit.factor, 1.0);
    }
}
