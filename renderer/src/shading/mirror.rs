//! Reflection by a moving mirror (Einstein 1905, section 7): light is
//! reflected by the ordinary law in the mirror's rest frame. Derivation and
//! the closed form for a mirror moving along its normal are in
//! docs/physics.md ("Moving mirrors").
//!
//! The law is applied frame-free. The mirror's world-sheet near the hit,
//! swept by the surface point moving with lab velocity u, has the
//! Minkowski normal N = (n.u, n) (n the lab unit normal at constant lab
//! time): N is orthogonal, in the metric diag(1, -1, -1, -1), to the
//! point's 4-velocity direction (1, u) and to every direction (0, e) in the
//! surface. In the rest frame N is (0, n'), and the ordinary law
//! k -> k - 2 (k.n') n' is the Minkowski reflection
//! K -> K - 2 <K, N> / <N, N> N of the photon's 4-wavevector K. That
//! reflection commutes with every boost, so applying it in the lab is the
//! same as boosting into the rest frame, reflecting and boosting back, and
//! it also gives the reflected frequency (the double Doppler shift).
//! The classical model's mirror reflects by the same law: it is Huygens'
//! construction for waves of speed c in the lab meeting a moving plane
//! (phases matched along the world-sheet), which needs no kinematics of the
//! mirror's frame.

use crate::spacetime::{Boost, FourVector};
use glam::DVec3;

/// What a moving mirror does to one photon leaving it along the lab unit
/// direction `k_out`: where the photon came from, and its frequencies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reflection {
    /// Lab unit direction the incident photon propagated along.
    pub k_in: DVec3,
    /// nu_out / nu_in, both in the lab: the mirror's double Doppler factor.
    pub frequency_ratio: f64,
}

/// The Minkowski product diag(1, -1, -1, -1).
fn minkowski(a: FourVector, b: FourVector) -> f64 {
    a.t * b.t - a.x.dot(b.x)
}

/// The incident photon that a mirror with lab unit normal `n`, its surface
/// point moving with lab velocity `u`, reflects into `k_out` (a lab unit
/// vector). The reflection is its own inverse in the rest frame, so the
/// incident wavevector is the reflection of the outgoing one. `None` when
/// the mirror moves along its normal at light speed or faster (no rest
/// frame, and no reflection: |n.u| >= 1).
pub fn incident(k_out: DVec3, n: DVec3, u: DVec3) -> Option<Reflection> {
    let normal = FourVector::new(n.dot(u), n);
    let norm = minkowski(normal, normal);
    if norm >= 0.0 || !norm.is_finite() {
        return None;
    }
    let k = FourVector::new(1.0, k_out);
    let k_in = k - normal * (2.0 * minkowski(k, normal) / norm);
    if k_in.t <= 0.0 {
        return None;
    }
    Some(Reflection {
        k_in: k_in.x / k_in.t,
        frequency_ratio: 1.0 / k_in.t,
    })
}

/// The same reflection seen in the mirror's rest frame, for the debug log:
/// the rest-frame unit normal and the unit propagation directions of the
/// outgoing and incident photons there. `None` without a rest frame
/// (|u| >= 1).
pub fn in_rest_frame(k_out: DVec3, k_in: DVec3, n: DVec3, u: DVec3) -> Option<[DVec3; 3]> {
    let boost = Boost::new(u)?;
    let rest_dir = |k: DVec3| {
        let r = boost.to_rest(FourVector::new(1.0, k));
        r.x / r.t
    };
    let normal = boost.to_rest(FourVector::new(n.dot(u), n)).x.normalize();
    Some([normal, rest_dir(k_out), rest_dir(k_in)])
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    /// The frame-free reflection equals boosting into the rest frame,
    /// reflecting about the rest-frame normal and boosting back, for
    /// mirrors moving along, across and obliquely to their normals.
    #[test]
    fn the_lab_reflection_is_the_rest_frame_law() {
        let n = DVec3::new(0.3, -0.2, 0.9).normalize();
        for u in [
            DVec3::ZERO,
            n * 0.5,
            n * -0.7,
            DVec3::new(0.6, 0.1, -0.2),
            n.cross(DVec3::X).normalize() * 0.9,
        ] {
            let boost = Boost::new(u).unwrap();
            for k_out in [
                n,
                (n + DVec3::new(0.4, 0.5, 0.0)).normalize(),
                (n + DVec3::Y).normalize(),
            ] {
                let r = incident(k_out, n, u).unwrap();
                let [n_rest, out_rest, in_rest] = in_rest_frame(k_out, r.k_in, n, u).unwrap();
                let mirrored = out_rest - 2.0 * out_rest.dot(n_rest) * n_rest;
                assert_abs_diff_eq!(in_rest.x, mirrored.x, epsilon = 1e-12);
                assert_abs_diff_eq!(in_rest.y, mirrored.y, epsilon = 1e-12);
                assert_abs_diff_eq!(in_rest.z, mirrored.z, epsilon = 1e-12);
                assert_abs_diff_eq!(r.k_in.length(), 1.0, epsilon = 1e-12);
                // The rest-frame frequency is the same on both legs.
                let f_out = boost.to_rest(FourVector::new(1.0, k_out)).t;
                let f_in = boost.to_rest(FourVector::new(1.0, r.k_in)).t / r.frequency_ratio;
                assert_abs_diff_eq!(f_out, f_in, epsilon = 1e-12);
            }
        }
    }

    /// Head-on on a mirror approaching at b: nu_out / nu_in = (1+b)/(1-b),
    /// and the photon came straight in; the static law is the control.
    #[test]
    fn a_mirror_met_head_on_doubles_the_shift() {
        let n = DVec3::Z;
        let b = 0.5;
        let r = incident(n, n, n * b).unwrap();
        assert_abs_diff_eq!(r.frequency_ratio, (1.0 + b) / (1.0 - b), epsilon = 1e-12);
        assert_abs_diff_eq!(r.k_in.z, -1.0, epsilon = 1e-12);
        let still = incident(n, n, DVec3::ZERO).unwrap();
        assert_eq!(still.frequency_ratio, 1.0);
        assert!(incident(n, n, n * 1.0).is_none());
    }
}
