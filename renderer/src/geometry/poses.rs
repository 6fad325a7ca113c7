//! Accelerated and keyframed motion: the paper's "curved temporal
//! extrusions" (section 6). An object is given at a list of lab times;
//! between consecutive keyframes every vertex moves in a straight line, so
//! each interval is an ordinary temporal extrusion (paper 3.1) whose prisms
//! may shear, turn and deform. Constant proper acceleration (hyperbolic
//! motion) is generated into keyframes with a stated error bound.
//!
//! Rigidity of a V_obj. "Rigid" has no frame-free meaning under
//! acceleration. Two assumptions are used, and stated in docs/physics.md:
//! - *Keyframes of a V_obj* give the shape in the object's rest frame; each
//!   keyframe is Lorentz-contracted along the reference point's velocity at
//!   that keyframe (the instantaneously comoving inertial frame). Exact for
//!   uniform motion; under acceleration a the points of a rest-rigid body
//!   would in fact differ by order a L^2 (L its size, c = 1).
//! - *Hyperbolic motion of a V_obj* is Born-rigid: the point at rest-frame
//!   offset xi along the acceleration has its own proper acceleration
//!   a / (1 + a xi), every point on a hyperbola about the same centre (the
//!   Rindler congruence), so distances in the instantaneous rest frame never
//!   change. The object must lie in front of the horizon, 1 + a xi > 0.
//!   The body's surface is curved in the lab (each point on its own
//!   hyperbola), so its mesh is first cut into pieces flat within the
//!   tolerance (`born_rigid.rs`); the tolerance then bounds every point of
//!   the surface, not only the vertices.

use crate::scene::{
    Fault, Hyperbolic, HyperbolicField as H, Keyframe, Mesh, SceneErrorKind as K, SceneField as F,
    MAX_KEYFRAMES,
};
use crate::spacetime::Boost;
use glam::DVec3;

/// The object at one lab time, resolved from a keyframe (or generated):
/// lab positions of every vertex (after any contraction), and the reference
/// point's state. Consecutive poses bound one stretch of the path.
#[derive(Clone, Debug, PartialEq)]
pub struct Pose {
    /// Lab time, t.units.
    pub t: f64,
    /// Lab position of the reference point, l.units.
    pub reference: DVec3,
    /// Lab positions of the mesh's vertices, l.units.
    pub vertices: Vec<DVec3>,
    /// The reference point's proper time since the start (lab time for an
    /// object inserted without the Lorentz transform).
    pub proper_time: f64,
}

impl Hyperbolic {
    /// The poses of this motion for `mesh`, Born-rigid when
    /// `born_rigid` (a V_obj with the Lorentz transform on), else every
    /// vertex translated with the reference point.
    ///
    /// Error bound: a vertex's position along the line is
    /// s(t) = sqrt(A^2 + T^2) + const, and |s''| = A^2 / (A^2 + T^2)^(3/2)
    /// <= 1/A. Linear interpolation over a lab interval h is off by at most
    /// h^2 max|s''| / 8 <= h^2 / (8 A_min), so intervals of
    /// h = sqrt(8 delta A_min) keep every vertex within delta: the whole
    /// `tolerance`, or half of it when Born-rigid, whose flat pieces
    /// between the vertices take the other half
    /// ([`Hyperbolic::born_rigid_pieces`]). Both errors are along the
    /// acceleration and of one sign (s is convex in t and in xi), so they
    /// add: every point of the surface stays within `tolerance`.
    #[cfg(test)]
    pub(crate) fn poses(&self, mesh: &Mesh, born_rigid: bool) -> Result<Vec<Pose>, Fault> {
        self.poses_in(mesh, born_rigid, self.intervals(mesh, born_rigid)?)
    }

    /// Whether `other` is the same worldline (every parameter but the
    /// tolerance equal): objects on it are cut at the same lab times, so
    /// that the vertices they share stay together between keyframes too.
    pub(crate) fn same_worldline(&self, other: &Hyperbolic) -> bool {
        Hyperbolic {
            tolerance: other.tolerance,
            ..*self
        } == *other
    }

    /// The part of the tolerance the cut in lab time may take: all of it,
    /// or half when Born-rigid (the flat pieces take the rest).
    pub(crate) fn in_time(&self, born_rigid: bool) -> f64 {
        if born_rigid {
            0.5 * self.tolerance
        } else {
            self.tolerance
        }
    }

    /// The offset of each vertex of `mesh` along the acceleration (all 0
    /// unless `born_rigid`).
    fn offsets(&self, mesh: &Mesh, born_rigid: bool) -> Vec<f64> {
        let n = self.direction;
        mesh.vertices
            .iter()
            .map(|p| if born_rigid { p.dot(n) } else { 0.0 })
            .collect()
    }

    /// How many equal lab intervals keep every vertex of `mesh` within
    /// the tolerance (the bound above), or why the motion cannot be cut.
    pub(crate) fn intervals(&self, mesh: &Mesh, born_rigid: bool) -> Result<usize, Fault> {
        self.validate()?;
        let a = self.acceleration;
        let xi_min = self
            .offsets(mesh, born_rigid)
            .into_iter()
            .fold(0.0, f64::min);
        if 1.0 + a * xi_min <= 0.0 {
            return Err(Fault::new(
                F::Hyperbolic(H::Acceleration),
                K::BeyondHorizon {
                    acceleration: a,
                    behind: -xi_min,
                },
            ));
        }
        let a_min = 1.0 / a + xi_min;
        let h = (8.0 * self.in_time(born_rigid) * a_min).sqrt();
        let count = (self.duration / h).ceil().max(1.0);
        if count.is_nan() || count > MAX_KEYFRAMES as f64 {
            return Err(Fault::new(
                F::Hyperbolic(H::Tolerance),
                K::TooManyKeyframes {
                    tolerance: self.tolerance,
                    count,
                    max: MAX_KEYFRAMES,
                },
            ));
        }
        Ok(count as usize)
    }

    /// The poses of this motion for `mesh` at `count` equal lab intervals
    /// (at least [`Hyperbolic::intervals`], so within the tolerance; more
    /// when objects on the same worldline share the finest cut), Born-rigid
    /// when `born_rigid` (a V_obj with the Lorentz transform on), else every
    /// vertex translated with the reference point.
    pub(crate) fn poses_in(
        &self,
        mesh: &Mesh,
        born_rigid: bool,
        count: usize,
    ) -> Result<Vec<Pose>, Fault> {
        self.validate()?;
        let n = self.direction;
        let xi = self.offsets(mesh, born_rigid);
        let (t0, x0) = (self.start.t, self.start.x);
        Ok((0..=count)
            .map(|k| {
                let t = if k == count {
                    t0 + self.duration
                } else {
                    t0 + self.duration * k as f64 / count as f64
                };
                let reference = x0 + n * self.along(0.0, t);
                let vertices = mesh
                    .vertices
                    .iter()
                    .zip(&xi)
                    .map(|(p, &xi)| {
                        let across = *p - n * xi;
                        x0 + across + n * self.along(xi, t)
                    })
                    .collect();
                Pose {
                    t,
                    reference,
                    vertices,
                    proper_time: if born_rigid {
                        self.proper_time(t)
                    } else {
                        t - t0
                    },
                }
            })
            .collect())
    }
}

/// Rejects fewer than two keyframes, non-finite ones, ones out of time
/// order and vertex lists that do not match the mesh.
fn check_keyframes(keyframes: &[Keyframe], mesh: &Mesh) -> Result<(), Fault> {
    if keyframes.len() < 2 {
        return Err(Fault::new(
            F::Keyframes,
            K::TooFewKeyframes(keyframes.len()),
        ));
    }
    for (k, f) in keyframes.iter().enumerate() {
        if !(f.t.is_finite() && f.position.is_finite()) {
            return Err(Fault::new(F::Keyframe(k), K::KeyframeNotFinite));
        }
        if k > 0 && f.t <= keyframes[k - 1].t {
            return Err(Fault::new(
                F::KeyframeTime(k),
                K::KeyframesOutOfOrder {
                    t: f.t,
                    previous: keyframes[k - 1].t,
                },
            ));
        }
        if let Some(o) = &f.offsets {
            if o.len() != mesh.vertices.len() {
                return Err(Fault::new(
                    F::KeyframeVertices(k),
                    K::VertexCount {
                        given: o.len(),
                        mesh: mesh.vertices.len(),
                    },
                ));
            }
            if let Some(v) = o.iter().position(|p| !p.is_finite()) {
                return Err(Fault::new(
                    F::KeyframeVertex {
                        keyframe: k,
                        vertex: v,
                    },
                    K::NotFinite,
                ));
            }
        }
    }
    Ok(())
}

/// Resolves keyframes into lab vertex positions. With `contract` (a V_obj
/// with the Lorentz transform on) each keyframe's rest-frame shape is
/// contracted along the reference point's velocity there (central
/// difference of the neighbouring keyframes; one-sided at the ends), and
/// the proper time accumulates dt / gamma over each interval.
pub(crate) fn resolve(
    keyframes: &[Keyframe],
    mesh: &Mesh,
    contract: bool,
) -> Result<Vec<Pose>, Fault> {
    check_keyframes(keyframes, mesh)?;
    let last = keyframes.len() - 1;
    let velocity = |k: usize| {
        let (i, j) = (k.saturating_sub(1), (k + 1).min(last));
        (keyframes[j].position - keyframes[i].position) / (keyframes[j].t - keyframes[i].t)
    };
    let mut poses: Vec<Pose> = Vec::with_capacity(keyframes.len());
    for (k, f) in keyframes.iter().enumerate() {
        let offsets = f.offsets.as_deref().unwrap_or(&mesh.vertices);
        let boost = if contract {
            Boost::new(velocity(k)).ok_or_else(|| {
                Fault::new(
                    F::KeyframePosition(k),
                    K::KeyframeTooFast {
                        speed: velocity(k).length(),
                    },
                )
            })?
        } else {
            Boost::identity()
        };
        let proper_time = match poses.last() {
            None => 0.0,
            Some(prev) => {
                let dt = f.t - prev.t;
                let v = (f.position - prev.reference) / dt;
                let dtau = if contract {
                    dt * (1.0 - v.length_squared()).max(0.0).sqrt()
                } else {
                    dt
                };
                prev.proper_time + dtau
            }
        };
        poses.push(Pose {
            t: f.t,
            reference: f.position,
            vertices: offsets
                .iter()
                .map(|p| f.position + boost.contract(*p))
                .collect(),
            proper_time,
        });
    }
    if contract {
        for k in 1..poses.len() {
            let dt = poses[k].t - poses[k - 1].t;
            for (v, (a, b)) in poses[k - 1]
                .vertices
                .iter()
                .zip(&poses[k].vertices)
                .enumerate()
            {
                let speed = (*b - *a).length() / dt;
                if speed.is_nan() || speed >= 1.0 {
                    return Err(Fault::new(
                        F::Keyframe(k),
                        K::VertexTooFast {
                            vertex: v,
                            speed,
                            between: (poses[k - 1].t, poses[k].t),
                        },
                    ));
                }
            }
        }
    }
    Ok(poses)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spacetime::Event;
    use approx::assert_abs_diff_eq;

    fn bar() -> Mesh {
        Mesh::cuboid(DVec3::new(-0.5, -1.0, -0.1), DVec3::new(0.5, 1.0, 0.1))
    }

    fn motion(tolerance: f64) -> Hyperbolic {
        Hyperbolic {
            start: Event::new(-3.0, DVec3::new(1.0, 0.0, 0.0)),
            direction: DVec3::X,
            acceleration: 0.8,
            initial_velocity: -0.3,
            duration: 9.0,
            tolerance,
        }
    }

    /// Every vertex's polyline stays within the tolerance of its exact
    /// hyperbola, and uses most of it (the bound is not loose by orders).
    #[test]
    fn polyline_error_is_within_the_stated_bound() {
        for born in [false, true] {
            let m = motion(1e-3);
            let poses = m.poses(&bar(), born).unwrap();
            let mut worst: f64 = 0.0;
            for w in poses.windows(2) {
                for i in 0..10 {
                    let f = (i as f64 + 0.5) / 10.0;
                    let t = w[0].t + f * (w[1].t - w[0].t);
                    for (v, p) in bar().vertices.iter().enumerate() {
                        let lerp = w[0].vertices[v].lerp(w[1].vertices[v], f);
                        let xi = if born { p.x } else { 0.0 };
                        let exact = m.start.x.x + p.x - xi + m.along(xi, t);
                        worst = worst.max((lerp.x - exact).abs());
                        assert_abs_diff_eq!(lerp.y, m.start.x.y + p.y, epsilon = 1e-12);
                    }
                }
            }
            assert!(worst <= 1e-3, "born {born}: error {worst}");
            assert!(
                worst > 1e-4,
                "born {born}: error {worst}: bound far from tight"
            );
        }
    }

    /// The generated path has the proper acceleration asked for: at the
    /// reference point, gamma^3 dv/dt = a; and it starts at the given velocity.
    #[test]
    fn hyperbola_has_the_proper_acceleration() {
        let m = motion(1e-4);
        let v = |t: f64| {
            let h = 1e-5;
            (m.along(0.0, t + h) - m.along(0.0, t - h)) / (2.0 * h)
        };
        assert_abs_diff_eq!(v(m.start.t), m.initial_velocity, epsilon = 1e-8);
        for t in [-2.0, 0.0, 4.0] {
            let h = 1e-3;
            let dv = (v(t + h) - v(t - h)) / (2.0 * h);
            let gamma = crate::spacetime::gamma(DVec3::new(v(t), 0.0, 0.0));
            assert_abs_diff_eq!(
                crate::math::powi(gamma, 3) * dv,
                m.acceleration,
                epsilon = 1e-5
            );
        }
    }

    /// Born rigidity: in the reference point's instantaneous rest frame the
    /// distance between two points on the line stays their rest distance.
    #[test]
    fn born_rigid_points_keep_their_rest_distance() {
        let m = motion(1e-4);
        let xi = 0.7;
        for t in [-3.0, 0.0, 5.0] {
            // The rest frame's simultaneity line through the reference
            // event passes through the hyperbolas' common centre, so the
            // other point is met where its hyperbola crosses that line.
            let a = m.acceleration;
            let phi0 = m.initial_rapidity();
            let big_t = t - m.start.t + crate::math::sinh(phi0) / a;
            let s_ref = m.along(0.0, t) + crate::math::cosh(phi0) / a;
            let ratio = big_t / s_ref; // tanh(rapidity)
            let s_other = (1.0 / a + xi) / (1.0 - ratio * ratio).sqrt();
            let t_other = ratio * s_other;
            let proper = (crate::math::powi(s_other - s_ref, 2)
                - crate::math::powi(t_other - big_t, 2))
            .sqrt();
            assert_abs_diff_eq!(proper, xi, epsilon = 1e-12);
        }
    }

    #[test]
    fn keyframes_out_of_order_are_an_error() {
        let k = |t: f64| Keyframe {
            t,
            position: DVec3::ZERO,
            offsets: None,
        };
        let e = resolve(&[k(0.0), k(2.0), k(1.0)], &bar(), false).unwrap_err();
        assert_eq!(e.field, F::KeyframeTime(2));
        assert_eq!(
            e.kind,
            K::KeyframesOutOfOrder {
                t: 1.0,
                previous: 2.0
            }
        );
        assert!(e.kind.to_string().contains("out of time order"));
    }

    #[test]
    fn a_v_obj_vertex_faster_than_light_is_an_error() {
        // The reference point is at rest but the bar turns: its ends sweep
        // 0.5 * pi l.units in 1 t.unit.
        let turned: Vec<DVec3> = bar().vertices.iter().map(|p| -*p).collect();
        let keyframes = [
            Keyframe {
                t: 0.0,
                position: DVec3::ZERO,
                offsets: None,
            },
            Keyframe {
                t: 1.0,
                position: DVec3::ZERO,
                offsets: Some(turned),
            },
        ];
        let e = resolve(&keyframes, &bar(), true).unwrap_err();
        assert_eq!(e.field, F::Keyframe(1));
        assert!(matches!(e.kind, K::VertexTooFast { .. }), "{:?}", e.kind);
        assert!(e.kind.to_string().contains("slower than light"));
        assert!(resolve(&keyframes, &bar(), false).is_ok(), "an H_obj may");
    }

    #[test]
    fn keyframed_v_obj_is_contracted_along_its_velocity() {
        let keyframes = [0.0, 1.0, 2.0].map(|t| Keyframe {
            t,
            position: DVec3::new(0.6 * t, 0.0, 0.0),
            offsets: None,
        });
        let r = resolve(&keyframes, &bar(), true).unwrap();
        let width = |f: &Pose| {
            let xs = f.vertices.iter().map(|p| p.x);
            xs.clone().fold(f64::MIN, f64::max) - xs.fold(f64::MAX, f64::min)
        };
        for f in &r {
            assert_abs_diff_eq!(width(f), 0.8, epsilon = 1e-12);
        }
        assert_abs_diff_eq!(r[2].proper_time, 1.6, epsilon = 1e-12);
    }

    #[test]
    fn an_object_behind_the_horizon_is_an_error() {
        let mut m = motion(1e-3);
        m.acceleration = 3.0; // 1/a = 0.33 < the bar's half width 0.5
        let e = m.poses(&bar(), true).unwrap_err();
        assert_eq!(e.field, F::Hyperbolic(H::Acceleration));
        assert!(matches!(e.kind, K::BeyondHorizon { .. }), "{:?}", e.kind);
        assert!(m.poses(&bar(), false).is_ok());
    }
}
