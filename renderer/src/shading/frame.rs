//! The surface's own frame, where it forms its local term: the Lambert
//! cosine and the Phong lobe take the directions of the light and of the
//! viewer as the moving surface sees them (aberration), not as the lab does.
//! Derivation in docs/physics.md ("Shading in the surface's frame").
//!
//! A Lorentz-transformed object (a V_obj under the transform) aberrates
//! relativistically: a photon's 4-wavevector (1, k) is boosted into the
//! frame of the surface point (velocity u), and the world-sheet's normal
//! N = (n.u, n) ([`super::mirror`]) into (0, n'). A Lorentz-decoupled
//! object, like its classical Doppler factor, aberrates as Galilean
//! kinematics has it: light of lab velocity k has velocity k - u relative
//! to the surface, and planes of constant lab time stay planes of constant
//! time, so n' = n.

use crate::spacetime::{Boost, FourVector};
use glam::DVec3;

/// The rest frame of a moving surface point, with its unit normal there.
#[derive(Clone, Copy, Debug)]
pub(super) enum SurfaceFrame {
    /// Reached by the boost with the point's velocity.
    Lorentz {
        /// The boost from the surface's frame to the lab.
        boost: Boost,
        /// The facing normal in the surface's frame.
        normal: DVec3,
    },
    /// Reached by subtracting the point's velocity from light's.
    Galilean {
        /// The point's lab velocity.
        velocity: DVec3,
        /// The facing normal (the same in both frames).
        normal: DVec3,
    },
}

impl SurfaceFrame {
    /// The frame of a surface point moving with `u`, its lab facing normal
    /// `n`; `None` for a point at rest (the lab is its frame) or a
    /// Lorentz-transformed point without a rest frame.
    pub(super) fn of(n: DVec3, u: DVec3, lorentz: bool) -> Option<SurfaceFrame> {
        if u == DVec3::ZERO {
            return None;
        }
        if !lorentz {
            return Some(SurfaceFrame::Galilean {
                velocity: u,
                normal: n,
            });
        }
        let boost = Boost::new(u)?;
        let normal = boost.to_rest(FourVector::new(n.dot(u), n)).x.normalize();
        Some(SurfaceFrame::Lorentz { boost, normal })
    }

    /// The same frame with the normal turned to the other side (exactly
    /// the frame of the negated lab normal: the boost is linear).
    pub(super) fn flipped(self) -> SurfaceFrame {
        match self {
            SurfaceFrame::Lorentz { boost, normal } => SurfaceFrame::Lorentz {
                boost,
                normal: -normal,
            },
            SurfaceFrame::Galilean { velocity, normal } => SurfaceFrame::Galilean {
                velocity,
                normal: -normal,
            },
        }
    }

    /// The facing unit normal in the surface's frame.
    pub(super) fn normal(&self) -> DVec3 {
        match self {
            SurfaceFrame::Lorentz { normal, .. } | SurfaceFrame::Galilean { normal, .. } => *normal,
        }
    }

    /// The unit direction, in the surface's frame, of light propagating
    /// along the lab unit vector `k`.
    pub(super) fn propagation(&self, k: DVec3) -> DVec3 {
        match self {
            SurfaceFrame::Lorentz { boost, .. } => {
                let r = boost.to_rest(FourVector::new(1.0, k));
                r.x / r.t
            }
            SurfaceFrame::Galilean { velocity, .. } => (k - *velocity).normalize(),
        }
    }

    /// The unit direction, in the surface's frame, towards a source whose
    /// light arrives from the lab unit direction `s`.
    pub(super) fn towards(&self, s: DVec3) -> DVec3 {
        -self.propagation(-s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    /// Light falling straight down on a plate sliding along x at b is seen
    /// in the plate's frame to come in at cos theta' = 1/gamma
    /// (relativistic), or 1/sqrt(1 + b^2) (Galilean: velocity (-b, -1)
    /// relative to the plate), from ahead of the plate.
    #[test]
    fn light_from_above_a_sliding_plate_comes_in_slanted() {
        let (n, b) = (DVec3::Y, 0.6);
        let u = DVec3::new(b, 0.0, 0.0);
        let rel = SurfaceFrame::of(n, u, true).unwrap();
        assert_abs_diff_eq!(rel.normal().y, 1.0, epsilon = 1e-12);
        let l = rel.towards(DVec3::Y);
        assert_abs_diff_eq!(l.dot(rel.normal()), (1.0 - b * b).sqrt(), epsilon = 1e-12);
        assert!(l.x > 0.0, "the lamp is seen ahead: {l}");
        let gal = SurfaceFrame::of(n, u, false).unwrap();
        let l = gal.towards(DVec3::Y);
        assert_abs_diff_eq!(l.dot(n), 1.0 / (1.0 + b * b).sqrt(), epsilon = 1e-12);
        assert!(SurfaceFrame::of(n, DVec3::ZERO, true).is_none());
    }

    /// The side a moving surface shows: light leaving along lab k leaves
    /// it on the side n' . k' > 0 in its frame, which is the sign of
    /// n . (k - u) in both kinematics (docs/physics.md, "Which side a
    /// moving surface shows"), and not the lab's sign of n . k when the
    /// surface outruns the light along its normal. The flipped frame is
    /// the frame of the negated normal, to the bit.
    #[test]
    fn the_side_shown_is_the_sign_of_n_dot_k_minus_u() {
        let n = DVec3::X;
        let ks = [
            DVec3::new(0.287, 0.0, 0.958),
            DVec3::new(0.95, 0.3, 0.0),
            DVec3::new(-0.6, 0.0, 0.8),
            DVec3::new(0.5, -0.5, 0.707),
        ];
        for u in [DVec3::new(0.9, 0.0, 0.0), DVec3::new(0.6, 0.3, -0.5)] {
            for lorentz in [true, false] {
                let f = SurfaceFrame::of(n, u, lorentz).unwrap();
                for k in ks.map(|k| k.normalize()) {
                    let side = f.normal().dot(f.propagation(k));
                    let expected = n.dot(k - u);
                    assert!(
                        side * expected > 0.0,
                        "{k} {u} {lorentz}: {side} vs {expected}"
                    );
                }
                let back = SurfaceFrame::of(-n, u, lorentz).unwrap();
                assert_eq!(back.normal(), f.flipped().normal());
            }
        }
        // The fixture's case: the lab sees +x, the face's frame -x.
        let k = DVec3::new(3.0, 0.0, 10.0).normalize();
        let f = SurfaceFrame::of(n, DVec3::new(0.9, 0.0, 0.0), true).unwrap();
        assert!(n.dot(k) > 0.0);
        assert_abs_diff_eq!(f.propagation(k).x, -0.826, epsilon = 1e-3);
    }
}
