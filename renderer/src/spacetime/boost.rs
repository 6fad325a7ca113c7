//! Lorentz boosts between an object's rest frame and the lab frame
//! (paper 3, item 2c: beta = dx/dt, rapidity theta = artanh(beta), and the
//! boost matrix LT; generalised here to a velocity in any direction).

use super::{lorentz_factor, FourVector};
use glam::DVec3;

/// The pure boost carrying rest-frame 4-vectors of an object moving with lab
/// velocity `beta` (|beta| < 1, c = 1) into the lab frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Boost {
    beta: DVec3,
    gamma: f64,
}

impl Boost {
    /// `None` unless |beta| < 1 and finite.
    pub fn new(beta: DVec3) -> Option<Self> {
        let b2 = beta.length_squared();
        if !beta.is_finite() || b2 >= 1.0 {
            return None;
        }
        Some(Self {
            beta,
            gamma: lorentz_factor(b2),
        })
    }

    /// The boost of an object at rest: changes nothing.
    pub fn identity() -> Self {
        Self {
            beta: DVec3::ZERO,
            gamma: 1.0,
        }
    }

    /// The lab velocity of the rest frame (fraction of c).
    pub fn beta(&self) -> DVec3 {
        self.beta
    }

    /// Lorentz factor, paper eq. (2).
    pub fn gamma(&self) -> f64 {
        self.gamma
    }

    /// Rapidity artanh|beta| (paper 3, item 2c.ii).
    pub fn rapidity(&self) -> f64 {
        crate::math::atanh(self.beta.length())
    }

    /// Rest frame -> lab frame:
    /// t = gamma (t' + beta.x'),  x = x' + (gamma - 1)(n.x') n + gamma t' beta.
    pub fn to_lab(&self, rest: FourVector) -> FourVector {
        self.apply(rest, self.beta)
    }

    /// Lab frame -> rest frame (the boost by -beta).
    pub fn to_rest(&self, lab: FourVector) -> FourVector {
        self.apply(lab, -self.beta)
    }

    fn apply(&self, v: FourVector, beta: DVec3) -> FourVector {
        let b2 = beta.length_squared();
        if b2 == 0.0 {
            return v;
        }
        let g = self.gamma;
        let bx = beta.dot(v.x);
        let t = g * (v.t + bx);
        let x = v.x + beta * ((g - 1.0) * bx / b2 + g * v.t);
        FourVector::new(t, x)
    }

    /// Length contraction: a displacement between two points of the body,
    /// simultaneous in its rest frame, becomes this lab-simultaneous
    /// displacement: the component along beta shrinks by 1/gamma.
    pub fn contract(&self, rest: DVec3) -> DVec3 {
        let b2 = self.beta.length_squared();
        if b2 == 0.0 {
            return rest;
        }
        let along = self.beta * (self.beta.dot(rest) / b2);
        rest - along + along / self.gamma
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn rejects_light_speed_and_beyond() {
        assert!(Boost::new(DVec3::new(1.0, 0.0, 0.0)).is_none());
        assert!(Boost::new(DVec3::new(0.8, 0.7, 0.0)).is_none());
        assert!(Boost::new(DVec3::new(f64::NAN, 0.0, 0.0)).is_none());
    }

    #[test]
    fn gamma_is_two_at_0866() {
        let b = Boost::new(DVec3::new(3f64.sqrt() / 2.0, 0.0, 0.0)).unwrap();
        assert_relative_eq!(b.gamma(), 2.0, max_relative = 1e-12);
    }

    #[test]
    fn boost_preserves_interval_and_inverts() {
        let b = Boost::new(DVec3::new(0.3, -0.5, 0.6)).unwrap();
        let v = FourVector::new(1.7, DVec3::new(-0.2, 3.0, 0.9));
        let lab = b.to_lab(v);
        assert_relative_eq!(lab.interval(), v.interval(), max_relative = 1e-12);
        let back = b.to_rest(lab);
        assert_relative_eq!(back.t, v.t, max_relative = 1e-12);
        assert_relative_eq!((back.x - v.x).length(), 0.0, epsilon = 1e-12);
    }

    #[test]
    fn contraction_is_the_lab_simultaneous_slice_of_the_boost() {
        let beta = DVec3::new(0.4, 0.2, -0.6);
        let b = Boost::new(beta).unwrap();
        let r = DVec3::new(1.0, 2.0, 3.0);
        // A rest-frame point at rest time t' has lab time gamma (t' + beta.r);
        // it is lab-simultaneous with the origin's t' = 0 event when t' = -beta.r.
        let ev = b.to_lab(FourVector::new(-beta.dot(r), r));
        assert_relative_eq!(ev.t, 0.0, epsilon = 1e-12);
        assert_relative_eq!((ev.x - b.contract(r)).length(), 0.0, epsilon = 1e-12);
    }
}
