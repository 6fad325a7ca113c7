//! Where a point of an object is seen from a camera event, for every kind
//! of worldline: straight (extrusion or velocity), hyperbolic (constant
//! proper acceleration, the H_obj on one hyperbola, the Born-rigid V_obj on
//! one per point) and keyframed (each point straight between its keyframe
//! positions; a V_obj's keyframes are its rest shape, contracted along the
//! reference point's central-difference velocity, as docs/physics.md
//! states).

use crate::fixture::Fixture;
use crate::observer::{motion_of, UniformMotion};
use crate::oracle::{
    contract, instantaneous, retarded, retarded_hyperbolic, retarded_polyline, PointHyperbola,
    PointPolyline, Retarded,
};
use glam::DVec3;
use renderer::{Hyperbolic, Keyframe, LightSpeed, Mesh, Model, Motion, ObjectKind, Shape};

/// An object's path, read from the fixture's scene data.
#[derive(Clone, Debug)]
pub(super) enum BodyPath {
    /// A straight worldline.
    Uniform(UniformMotion),
    /// Constant proper acceleration; `born_rigid` for a Lorentz-transformed V_obj.
    Hyperbolic {
        /// The motion as the fixture gives it.
        motion: Hyperbolic,
        /// Each point on its own hyperbola (a V_obj under the Lorentz transform).
        born_rigid: bool,
    },
    /// Keyframes: the mesh's vertices at each keyframe's lab time, in lab
    /// coordinates, straight in between.
    Keyframed(KeyframedMesh),
}

/// A keyframed mesh in the lab: its rest vertices and triangles, and at
/// each keyframe the lab time and the lab positions of its vertices.
#[derive(Clone, Debug)]
pub(super) struct KeyframedMesh {
    rest: Mesh,
    frames: Vec<(f64, Vec<DVec3>)>,
}

impl KeyframedMesh {
    /// The lab vertices of `mesh` at each keyframe; contracted along the
    /// reference point's velocity there (central differences, one-sided at
    /// the ends) when `contracted`.
    fn of(mesh: &Mesh, keyframes: &[Keyframe], contracted: bool) -> KeyframedMesh {
        let n = keyframes.len();
        let velocity = |k: usize| {
            let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
            let (ka, kb) = (&keyframes[a], &keyframes[b]);
            (kb.position - ka.position) / (kb.t - ka.t)
        };
        let frames = keyframes
            .iter()
            .enumerate()
            .map(|(k, kf)| {
                let offsets = kf.offsets.as_ref().unwrap_or(&mesh.vertices);
                let v = velocity(k);
                let lab = offsets
                    .iter()
                    .map(|r| kf.position + if contracted { contract(*r, v) } else { *r })
                    .collect();
                (kf.t, lab)
            })
            .collect();
        KeyframedMesh {
            rest: mesh.clone(),
            frames,
        }
    }

    /// The largest lab speed of any vertex between keyframes.
    fn fastest(&self) -> f64 {
        self.frames
            .windows(2)
            .flat_map(|w| {
                let ((t0, a), (t1, b)) = (&w[0], &w[1]);
                a.iter()
                    .zip(b)
                    .map(move |(p, q)| p.distance(*q) / (t1 - t0))
            })
            .fold(0.0, f64::max)
    }

    /// The rest mesh's largest coordinate: the scale of its rounding.
    fn scale(&self) -> f64 {
        self.rest
            .vertices
            .iter()
            .map(|v| v.abs().max_element())
            .fold(1e-300, f64::max)
    }

    /// The triangle side (i, j) that the rest point `r` lies on, and its
    /// parameter along it.
    fn side_of(&self, r: DVec3) -> Option<(usize, usize, f64)> {
        let m = &self.rest;
        let scale = self.scale();
        m.triangles.iter().find_map(|t| {
            (0..3).find_map(|k| {
                let (i, j) = (t[k] as usize, t[(k + 1) % 3] as usize);
                let (a, b) = (m.vertices[i], m.vertices[j]);
                let s = (r - a).dot(b - a) / (b - a).length_squared();
                let on = (-1e-9..=1.0 + 1e-9).contains(&s)
                    && (a + (b - a) * s).distance(r) <= 1e-9 * scale;
                on.then_some((i, j, s))
            })
        })
    }

    /// The triangle holding the rest point `r` (within rounding of its
    /// plane and borders), and r's barycentric weights in it.
    fn triangle_of(&self, r: DVec3) -> Option<([usize; 3], [f64; 3])> {
        let m = &self.rest;
        let scale = self.scale();
        m.triangles.iter().find_map(|t| {
            let ids = t.map(|i| i as usize);
            let [a, b, c] = ids.map(|i| m.vertices[i]);
            let n = (b - a).cross(c - a);
            let nn = n.length_squared();
            if n.dot(r - a).abs() > 1e-9 * scale * nn.sqrt() {
                return None;
            }
            let wa = (c - b).cross(r - b).dot(n) / nn;
            let wb = (a - c).cross(r - c).dot(n) / nn;
            let w = [wa, wb, 1.0 - wa - wb];
            w.iter().all(|&x| x >= -1e-9).then_some((ids, w))
        })
    }

    /// The worldline of the mesh point at rest position `r`: on a triangle
    /// side, interpolated along it; inside a triangle, by its weights.
    fn point(&self, r: DVec3) -> Option<PointPolyline> {
        let at = |v: &Vec<DVec3>| -> Option<DVec3> {
            if let Some((i, j, s)) = self.side_of(r) {
                return Some(v[i] + (v[j] - v[i]) * s);
            }
            let (ids, w) = self.triangle_of(r)?;
            Some((0..3).map(|k| v[ids[k]] * w[k]).sum())
        };
        let events = self
            .frames
            .iter()
            .map(|(t, v)| at(v).map(|x| (*t, x)))
            .collect::<Option<Vec<_>>>()?;
        Some(PointPolyline { events })
    }

    /// How far the velocity the renderer gives the surface seen where the
    /// point `r` is seen may differ from r's own, at lab time `t`. The
    /// renderer weights the triangle's corner velocities by the hit's
    /// place in its tetrahedron; on a turning triangle that place lies up
    /// to the triangle's bend (2 f (1 - f) times the largest change of a
    /// side's vector over the interval) from r's, and the light-cone
    /// intersection slides a further bend / (1 - v.k) along the worldline
    /// (`approach` = 1 - v.k). The velocity over the triangle is affine with
    /// gradient G, so the difference is at most |G|_F (bend + slide).
    fn velocity_slack(&self, r: DVec3, t: f64, approach: f64) -> f64 {
        let Some((ids, _)) = self.triangle_of(r) else {
            return 0.0;
        };
        let Some(k) = self
            .frames
            .windows(2)
            .position(|w| w[0].0 <= t && t <= w[1].0)
        else {
            return 0.0;
        };
        let ((t0, a), (t1, b)) = (&self.frames[k], &self.frames[k + 1]);
        let f = (t - t0) / (t1 - t0);
        let x = ids.map(|i| a[i].lerp(b[i], f));
        let v = ids.map(|i| (b[i] - a[i]) / (t1 - t0));
        let change =
            |i: usize, j: usize| ((b[ids[j]] - b[ids[i]]) - (a[ids[j]] - a[ids[i]])).length();
        let bend = 2.0 * f * (1.0 - f) * change(0, 1).max(change(1, 2)).max(change(0, 2));
        let (e1, e2) = (x[1] - x[0], x[2] - x[0]);
        let (d1, d2) = (v[1] - v[0], v[2] - v[0]);
        let gram = glam::DMat2::from_cols_array(&[e1.dot(e1), e1.dot(e2), e1.dot(e2), e2.dot(e2)]);
        let inv = gram.inverse();
        // G = d1 w1^T + d2 w2^T with w the dual basis of (e1, e2).
        let w1 = e1 * inv.x_axis.x + e2 * inv.y_axis.x;
        let w2 = e1 * inv.x_axis.y + e2 * inv.y_axis.y;
        let g2 = d1.length_squared() * w1.length_squared()
            + d2.length_squared() * w2.length_squared()
            + 2.0 * d1.dot(d2) * w1.dot(w2);
        g2.max(0.0).sqrt() * (bend + bend / approach)
    }

    /// How far the renderer's flat tetrahedra may put the side through `r`
    /// (a point inside it, so that the side is unambiguous)
    /// from its straight interpolation at lab time `t`: 2 f (1 - f) times the
    /// change of the side's vector over the interval, f the fraction of the
    /// interval (docs/physics.md, a turning triangle bends).
    fn bend(&self, r: DVec3, t: f64) -> f64 {
        let Some((i, j, _)) = self.side_of(r) else {
            return 0.0;
        };
        let k = self
            .frames
            .windows(2)
            .position(|w| w[0].0 <= t && t <= w[1].0);
        k.map_or(0.0, |k| {
            let ((t0, a), (t1, b)) = (&self.frames[k], &self.frames[k + 1]);
            let f = (t - t0) / (t1 - t0);
            let change = (b[j] - b[i]) - (a[j] - a[i]);
            2.0 * f * (1.0 - f) * change.length()
        })
    }
}

/// The hyperbola of the body point at offset `r` from the reference point
/// (rest frame for a Born-rigid body): the reference point's hyperbola
/// shifted across the motion by r's transverse part, and, when Born-rigid,
/// with A = 1/a + xi for the offset xi along it.
pub(super) fn hyperbola_of(h: &Hyperbolic, r: DVec3, born_rigid: bool) -> PointHyperbola {
    let xi = if born_rigid { r.dot(h.direction) } else { 0.0 };
    let across = r - h.direction * xi;
    let p = PointHyperbola::starting(
        h.start.t,
        h.start.x + across,
        h.direction,
        h.acceleration,
        h.initial_velocity,
    );
    PointHyperbola {
        big_a: p.big_a + xi,
        ..p
    }
}

impl BodyPath {
    /// The path of the object `name` under `model`.
    pub(super) fn of(fixture: &Fixture, name: &str, model: Model) -> Result<BodyPath, String> {
        let obj = fixture.object(name)?;
        match &obj.motion {
            Motion::Hyperbolic(h) => Ok(BodyPath::Hyperbolic {
                motion: *h,
                born_rigid: model.lorentz && obj.kind == ObjectKind::VObj,
            }),
            Motion::Keyframes(keyframes) => {
                let Shape::Mesh(mesh) = &obj.shape else {
                    return Err(format!(
                        "{name:?}: a keyframed sphere has no edges to follow"
                    ));
                };
                let contracted = model.lorentz && obj.kind == ObjectKind::VObj;
                let path = KeyframedMesh::of(mesh, keyframes, contracted);
                if path.fastest() >= 1.0 {
                    return Err(format!(
                        "{name:?}: a vertex moves at {:.6}c between keyframes; the oracle follows \
                         points slower than light (a faster one may be seen more than once)",
                        path.fastest()
                    ));
                }
                Ok(BodyPath::Keyframed(path))
            }
            _ => Ok(BodyPath::Uniform(motion_of(fixture, name, model)?)),
        }
    }

    /// Where the body point at `r` is seen from the camera at (`tc`,
    /// `camera`): on its past light cone, or at `tc` with infinite light speed.
    pub(super) fn seen(&self, r: DVec3, tc: f64, camera: DVec3, model: Model) -> Option<Retarded> {
        let finite = model.light_speed == LightSpeed::Finite;
        match self {
            BodyPath::Uniform(m) if finite => retarded(&m.point(r), tc, camera),
            BodyPath::Uniform(m) => Some(instantaneous(&m.point(r), tc, camera)),
            BodyPath::Hyperbolic { motion, born_rigid } => {
                let p = hyperbola_of(motion, r, *born_rigid);
                if finite {
                    retarded_hyperbolic(&p, tc, camera)
                } else {
                    let x = p.at(tc);
                    Some(Retarded {
                        t: tc,
                        x,
                        direction: (x - camera).normalize(),
                    })
                }
            }
            BodyPath::Keyframed(k) => {
                let p = k.point(r)?;
                if finite {
                    retarded_polyline(&p, tc, camera)
                } else {
                    let x = p.at(tc)?;
                    Some(Retarded {
                        t: tc,
                        x,
                        direction: (x - camera).normalize(),
                    })
                }
            }
        }
    }

    /// The lab velocity of the body point at `r` at lab time `t`.
    pub(super) fn velocity(&self, r: DVec3, t: f64) -> Option<DVec3> {
        match self {
            BodyPath::Uniform(m) => Some(m.velocity),
            BodyPath::Hyperbolic { motion, born_rigid } => {
                Some(hyperbola_of(motion, r, *born_rigid).velocity(t))
            }
            BodyPath::Keyframed(k) => k.point(r)?.segment_at(t).map(|(_, w)| w.v),
        }
    }

    /// How far the renderer's velocity of the surface seen where the point
    /// `r` is seen may differ from r's own (zero unless keyframed; see
    /// `KeyframedMesh::velocity_slack`).
    pub(super) fn velocity_slack(&self, r: DVec3, seen: &Retarded, camera: DVec3) -> f64 {
        let BodyPath::Keyframed(m) = self else {
            return 0.0;
        };
        let k = (camera - seen.x).normalize();
        let v = self.velocity(r, seen.t).unwrap_or(DVec3::ZERO);
        m.velocity_slack(r, seen.t, 1.0 - v.dot(k))
    }

    /// How far the seen position of the point at `r` may lie from the
    /// exact one because the renderer follows the path through keyframes
    /// within a stated bound delta (a hyperbola's generation tolerance, or
    /// the bend of a turning side): the light-cone intersection slides along
    /// the worldline, so the seen point moves by delta / (1 - v.k), k the
    /// unit vector from the emission towards the camera. Zero for a straight
    /// path.
    ///
    /// `ends` is the edge the point lies on, at parameter `s` along it (a
    /// side's bend is a property of the whole side).
    pub(super) fn keyframe_shift(
        &self,
        ends: [DVec3; 2],
        s: f64,
        seen: &Retarded,
        camera: DVec3,
    ) -> f64 {
        let r = ends[0] + (ends[1] - ends[0]) * s;
        let k = (camera - seen.x).normalize();
        match self {
            BodyPath::Uniform(_) => 0.0,
            BodyPath::Hyperbolic { motion, born_rigid } => {
                let p = hyperbola_of(motion, r, *born_rigid);
                motion.tolerance / (1.0 - p.velocity(seen.t).dot(k))
            }
            BodyPath::Keyframed(m) => {
                let v = m
                    .point(r)
                    .and_then(|p| p.segment_at(seen.t))
                    .map_or(DVec3::ZERO, |(_, w)| w.v);
                m.bend((ends[0] + ends[1]) / 2.0, seen.t) / (1.0 - v.dot(k))
            }
        }
    }
}
