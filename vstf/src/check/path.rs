//! Where a point of an object is seen from a camera event, for the
//! worldlines the oracle has in closed form: straight (extrusion or
//! velocity) and hyperbolic (constant proper acceleration, the H_obj on one
//! hyperbola, the Born-rigid V_obj on one per point).

use super::setup::{motion_of, uniform, UniformMotion};
use crate::fixture::Fixture;
use crate::oracle::{instantaneous, retarded, retarded_hyperbolic, PointHyperbola, Retarded};
use glam::DVec3;
use renderer::{Hyperbolic, LightSpeed, Model, Motion, ObjectKind};

/// An object's path, read from the fixture's scene data.
#[derive(Clone, Copy, Debug)]
pub enum BodyPath {
    /// A straight worldline.
    Uniform(UniformMotion),
    /// Constant proper acceleration; `born_rigid` for a Lorentz-transformed V_obj.
    Hyperbolic {
        /// The motion as the fixture gives it.
        motion: Hyperbolic,
        /// Each point on its own hyperbola (a V_obj under the Lorentz transform).
        born_rigid: bool,
    },
}

/// The hyperbola of the body point at offset `r` from the reference point
/// (rest frame for a Born-rigid body): the reference point's hyperbola
/// shifted across the motion by r's transverse part, and, when Born-rigid,
/// with A = 1/a + xi for the offset xi along it.
pub fn hyperbola_of(h: &Hyperbolic, r: DVec3, born_rigid: bool) -> PointHyperbola {
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
    pub fn of(fixture: &Fixture, name: &str, model: Model) -> Result<BodyPath, String> {
        let obj = fixture
            .scene
            .objects
            .iter()
            .find(|o| o.name == name)
            .ok_or_else(|| format!("{}: no object {name:?}", fixture.file.display()))?;
        match &obj.motion {
            Motion::Hyperbolic(h) => Ok(BodyPath::Hyperbolic {
                motion: *h,
                born_rigid: model.lorentz && obj.kind == ObjectKind::VObj,
            }),
            m if uniform(m).is_some() => Ok(BodyPath::Uniform(motion_of(fixture, name, model)?)),
            _ => Err(format!(
                "{}: object {name:?} moves by keyframes, for which the oracle has no closed form; \
                 checks measure straight and hyperbolic worldlines",
                fixture.file.display()
            )),
        }
    }

    /// Where the body point at `r` is seen from the camera at (`tc`,
    /// `camera`): on its past light cone, or at `tc` with infinite light speed.
    pub fn seen(&self, r: DVec3, tc: f64, camera: DVec3, model: Model) -> Option<Retarded> {
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
        }
    }

    /// How far the seen position of the point at `r` may lie from the
    /// exact one because the renderer follows the path through keyframes
    /// within a stated bound: the light-cone intersection slides along the
    /// worldline, so the seen point moves by delta / (1 - v.k), k the unit
    /// vector from the emission towards the camera. Zero for a straight path.
    pub fn keyframe_shift(&self, r: DVec3, seen: &Retarded, camera: DVec3) -> f64 {
        match self {
            BodyPath::Uniform(_) => 0.0,
            BodyPath::Hyperbolic { motion, born_rigid } => {
                let p = hyperbola_of(motion, r, *born_rigid);
                let k = (camera - seen.x).normalize();
                motion.tolerance / (1.0 - p.velocity(seen.t).dot(k))
            }
        }
    }
}
