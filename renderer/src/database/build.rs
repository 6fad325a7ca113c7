//! Insertion: every object of the scene temporally extruded once into
//! prisms (paper 3, items 1-2), its path cut into straight stretches.

use super::{Database, ObjectRecord, Stretch, Traversal};
use crate::accel::{StretchPrisms, TwoLevel};
use crate::geometry::{
    self, extrude, extrude_between, piece, Pose, PreparedTet, Prism, PrismCorners, Sphere,
};
use crate::scene::{
    Fault, Mesh, Motion, ObjectKind, Scene, SceneError, SceneErrorKind as K, SceneField as F,
    SceneObject, Shape, NO_MESH,
};
use crate::spacetime::{Boost, Event, FourVector, Worldline};

/// An object's mesh; none for an analytic sphere.
fn mesh_of(obj: &SceneObject) -> &Mesh {
    match &obj.shape {
        Shape::Mesh(mesh) => mesh,
        Shape::Sphere { .. } => &NO_MESH,
    }
}

/// The database under construction.
#[derive(Default)]
struct Builder {
    prisms: Vec<Prism>,
    /// Each prism's corners, from which its three tetrahedra are read.
    corners: Vec<PrismCorners>,
    spheres: Vec<Sphere>,
    stretch_prisms: Vec<StretchPrisms>,
}

/// The straight worldline of a uniformly moving object and the boost of
/// its rest frame (identity unless a V_obj under the Lorentz transform).
fn straight(obj: &SceneObject, lorentz: bool) -> Result<(Worldline, Boost), Fault> {
    let v = match obj.motion {
        Motion::Extrusion { extrusion, .. } => extrusion.velocity(),
        Motion::Velocity { velocity, .. } => velocity,
        Motion::Keyframes(_) | Motion::Hyperbolic(_) => unreachable!("resolved into keyframes"),
    };
    let bad = |f: F, k: K| Err(Fault::new(f, k));
    if !v.is_finite() {
        return bad(F::Motion, K::VelocityNotFinite);
    }
    if obj.kind == ObjectKind::VObj && v.length() >= 1.0 {
        return bad(F::Motion, K::VObjTooFast { speed: v.length() });
    }
    let boost = match (obj.kind, lorentz) {
        (ObjectKind::VObj, true) => Boost::new(v).expect("checked above"),
        _ => Boost::identity(),
    };
    let worldline = match obj.motion {
        Motion::Extrusion { start, extrusion } => {
            if !start.is_finite() {
                return bad(F::Start, K::NotFinite);
            }
            if !extrusion.is_finite() {
                return bad(F::Extrusion, K::NotFinite);
            }
            if extrusion.t == 0.0 {
                return bad(F::Extrusion, K::ZeroDuration);
            }
            if extrusion.t < 0.0 {
                Worldline {
                    start: start + extrusion,
                    extrusion: -extrusion,
                }
            } else {
                Worldline { start, extrusion }
            }
        }
        Motion::Velocity {
            start,
            velocity,
            proper_lifetime,
        } => {
            if !start.is_finite() {
                return bad(F::Start, K::NotFinite);
            }
            if !(proper_lifetime > 0.0 && proper_lifetime.is_finite()) {
                return bad(F::ProperLifetime, K::ProperLifetime);
            }
            let dt = boost.gamma() * proper_lifetime;
            Worldline {
                start,
                extrusion: FourVector::new(dt, velocity * dt),
            }
        }
        Motion::Keyframes(_) | Motion::Hyperbolic(_) => unreachable!("resolved into keyframes"),
    };
    Ok((worldline, boost))
}

impl Builder {
    /// Extrudes a keyframed object pose to pose, each interval one stretch
    /// of its path.
    fn keyframed(
        &mut self,
        object: u32,
        mesh: &Mesh,
        poses: &[Pose],
        contracted: bool,
    ) -> Result<Vec<Stretch>, Fault> {
        for (k, f) in poses.iter().enumerate() {
            let shape = Mesh {
                vertices: f.vertices.clone(),
                triangles: mesh.triangles.clone(),
            };
            shape
                .validate()
                .map_err(|error| Fault::new(F::Keyframe(k), K::PoseMesh { t: f.t, error }))?;
        }
        let mut stretches = Vec::with_capacity(poses.len() - 1);
        for (k, w) in poses.windows(2).enumerate() {
            let worldline = Worldline {
                start: Event::new(w[0].t, w[0].reference),
                extrusion: FourVector::new(w[1].t - w[0].t, w[1].reference - w[0].reference),
            };
            let v = worldline.velocity();
            let clock = if contracted {
                Boost::new(v).ok_or_else(|| {
                    Fault::new(F::Keyframe(k + 1), K::StretchTooFast { speed: v.length() })
                })?
            } else {
                Boost::identity()
            };
            let first = self.prisms.len();
            extrude_between(
                mesh,
                &w[0],
                &w[1],
                object,
                &mut self.prisms,
                &mut self.corners,
            );
            self.stretch_prisms.push(StretchPrisms {
                origin: worldline.start,
                velocity: v,
                span: (w[0].t, w[1].t),
                prisms: first..self.prisms.len(),
                translation: false,
            });
            stretches.push(Stretch {
                worldline,
                clock,
                proper_start: w[0].proper_time,
                translation: false,
            });
        }
        Ok(stretches)
    }

    /// Inserts a uniformly moving object: one stretch, an analytic sphere
    /// or the mesh (Lorentz-contracted for a V_obj) extruded along it.
    fn uniform(&mut self, i: usize, obj: &SceneObject, lorentz: bool) -> Result<Stretch, Fault> {
        let (worldline, boost) = straight(obj, lorentz)?;
        if let Shape::Sphere { radius } = obj.shape {
            self.spheres.push(Sphere {
                object: i as u32,
                radius,
                origin: worldline.start,
                velocity: worldline.velocity(),
                gamma: boost.gamma(),
                end: worldline.end().t,
            });
        } else {
            let mesh = mesh_of(obj).map_vertices(|p| boost.contract(p));
            mesh.validate()
                .map_err(|e| Fault::new(F::Shape, K::ContractedMesh(e)))?;
            let first = self.prisms.len();
            extrude(
                &mesh,
                &worldline,
                i as u32,
                &mut self.prisms,
                &mut self.corners,
            );
            self.stretch_prisms.push(StretchPrisms {
                origin: worldline.start,
                velocity: worldline.velocity(),
                span: (worldline.start.t, worldline.end().t),
                prisms: first..self.prisms.len(),
                translation: true,
            });
        }
        Ok(Stretch {
            worldline,
            clock: boost,
            proper_start: 0.0,
            translation: true,
        })
    }

    /// Inserts object `i`, returning its path as stretches.
    fn insert(
        &mut self,
        i: usize,
        obj: &SceneObject,
        lorentz: bool,
    ) -> Result<Vec<Stretch>, Fault> {
        match &obj.shape {
            Shape::Sphere { radius: r } if !(*r > 0.0 && r.is_finite()) => {
                return Err(Fault::new(F::Shape, K::SphereRadius(*r)));
            }
            Shape::Sphere { .. } => {}
            Shape::Mesh(mesh) => mesh
                .validate()
                .map_err(|e| Fault::new(F::Shape, K::Mesh(e)))?,
        }
        let mesh = mesh_of(obj);
        let contracted = lorentz && obj.kind == ObjectKind::VObj;
        let poses = match &obj.motion {
            Motion::Keyframes(k) => Some(geometry::resolve(k, mesh, contracted)?),
            Motion::Hyperbolic(h) => Some(h.poses(mesh, contracted)?),
            _ => None,
        };
        match poses {
            Some(_) if matches!(obj.shape, Shape::Sphere { .. }) => {
                Err(Fault::new(F::Motion, K::SphereNotUniform))
            }
            Some(poses) => self.keyframed(i as u32, mesh, &poses, contracted),
            None => Ok(vec![self.uniform(i, obj, lorentz)?]),
        }
    }
}

/// Every object inserted, before the acceleration structure is built.
struct Inserted {
    builder: Builder,
    records: Vec<ObjectRecord>,
    prepared: Vec<PreparedTet>,
}

/// Extrudes every object and prepares every tetrahedron's solve; the
/// errors are those of [`Database::build`].
fn insert_all(scene: &Scene, lorentz: bool) -> Result<Inserted, SceneError> {
    let mut b = Builder::default();
    let mut records = Vec::new();
    let mut prepared = Vec::new();
    for (i, obj) in scene.objects.iter().enumerate() {
        let first = b.prisms.len();
        let stretches = b.insert(i, obj, lorentz).map_err(|f| f.of(i, &obj.name))?;
        prepare(&b, first, &mut prepared).map_err(|f| f.of(i, &obj.name))?;
        records.push(ObjectRecord {
            name: obj.name.clone(),
            kind: obj.kind,
            material: obj.material.clone(),
            contracted: lorentz && obj.kind == ObjectKind::VObj,
            stretches,
        });
    }
    Ok(Inserted {
        builder: b,
        records,
        prepared,
    })
}

/// Prepares the solves of the tetrahedra of the builder's prisms from
/// `first` on (one object's), or the fault of the first with no 3-volume.
fn prepare(b: &Builder, first: usize, prepared: &mut Vec<PreparedTet>) -> Result<(), Fault> {
    prepared.reserve(3 * (b.prisms.len() - first));
    for (p, corners) in b.corners.iter().enumerate().skip(first) {
        for k in 0..3 {
            let solve = PreparedTet::new(&piece(corners, k)).ok_or_else(|| {
                Fault::new(
                    F::Shape,
                    K::FlatTetrahedron {
                        triangle: b.prisms[p].triangle,
                    },
                )
            })?;
            prepared.push(solve);
        }
    }
    Ok(())
}

impl Database {
    /// Temporally extrudes every object of `scene`. With `lorentz` on, V_obj
    /// objects are contracted along their velocity and their lifetimes and
    /// clocks dilated; with it off every object is inserted as an H_obj.
    pub fn build(scene: &Scene, lorentz: bool) -> Result<Database, SceneError> {
        let Inserted {
            builder: b,
            records,
            prepared,
        } = insert_all(scene, lorentz)?;
        let accel = TwoLevel::build(&b.stretch_prisms, &b.corners);
        Ok(Database {
            records,
            prisms: b.prisms,
            corners: b.corners,
            prepared,
            accel,
            spheres: b.spheres,
            traversal: Traversal::Bvh,
        })
    }

    /// Whether [`Database::build`] would accept `scene`: the same insertion
    /// and the same errors (object by object, in order), without building
    /// the acceleration structure and holding one object's prisms at a
    /// time. `lorentz` only matters for V_obj objects.
    pub fn validate(scene: &Scene, lorentz: bool) -> Result<(), SceneError> {
        for (i, obj) in scene.objects.iter().enumerate() {
            let mut b = Builder::default();
            b.insert(i, obj, lorentz).map_err(|f| f.of(i, &obj.name))?;
            for (p, corners) in b.corners.iter().enumerate() {
                if (0..3).any(|k| PreparedTet::new(&piece(corners, k)).is_none()) {
                    let triangle = b.prisms[p].triangle;
                    return Err(
                        Fault::new(F::Shape, K::FlatTetrahedron { triangle }).of(i, &obj.name)
                    );
                }
            }
        }
        Ok(())
    }
}
