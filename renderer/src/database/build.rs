//! Insertion: every object of the scene temporally extruded once into
//! prisms (paper 3, items 1-2), its path cut into straight stretches.

use super::worldlines::{resolve_hyperbolic, shared_cuts, Resolved, Shared};
use super::{ComovingMeshes, Database, Keyframed, ObjectRecord, Packing, Run, Stretch, Traversal};
use crate::accel::{rounding_margin, StretchPrisms, TwoLevel};
use crate::geometry::{
    self, extrude_between, piece, CornerRows, Pose, PreparedTet, PrismCorners, Sphere,
};
use crate::scene::{
    Fault, Material, Mesh, Motion, ObjectKind, Scene, SceneError, SceneErrorKind as K,
    SceneField as F, SceneObject, Shape, NO_MESH,
};
use crate::simd::SimdLevel;
use crate::spacetime::{Boost, Event, FourVector, Worldline};
use glam::DVec3;
use rayon::prelude::*;
use std::borrow::Cow;
use std::sync::OnceLock;

/// An object's mesh; none for an analytic sphere.
fn mesh_of(obj: &SceneObject) -> &Mesh {
    match &obj.shape {
        Shape::Mesh(mesh) => mesh,
        Shape::Sphere { .. } => &NO_MESH,
    }
}

/// Whether every triangle of `mesh` names one of the object's `count`
/// materials.
fn material_indices(mesh: &Mesh, count: usize) -> Result<(), Fault> {
    match mesh.materials.iter().position(|&k| k as usize >= count) {
        Some(triangle) => Err(Fault::new(
            F::Shape,
            K::MaterialIndex {
                triangle,
                index: mesh.materials[triangle],
                materials: count,
            },
        )),
        None => Ok(()),
    }
}

/// The database under construction.
#[derive(Default)]
struct Builder<'a> {
    runs: Vec<Run>,
    /// Run by run, the mesh a translation's prisms hold in its comoving
    /// coordinates: the scene's own, or its Lorentz-contracted copy (`None`
    /// for a keyframe interval). Its triangles are gathered in leaf order
    /// once the hierarchy is built ([`in_leaf_order`]), so that no copy of
    /// them in insertion order lives through the build.
    meshes: Vec<Option<Cow<'a, Mesh>>>,
    /// How many prisms of translations there are.
    translated: usize,
    /// How many vertices their meshes have.
    vertex_count: usize,
    keyframed: Keyframed,
    spheres: Vec<Sphere>,
    /// Only checking that the scene inserts ([`Database::validate`]): a
    /// uniformly moving mesh's comoving triangles, which cannot fail, are
    /// not kept.
    checking: bool,
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
    let given = match obj.motion {
        Motion::Velocity { .. } => F::Velocity,
        _ => F::Extrusion,
    };
    if !v.is_finite() {
        return bad(given, K::VelocityNotFinite);
    }
    if obj.kind == ObjectKind::VObj && v.length() >= 1.0 {
        return bad(given, K::VObjTooFast { speed: v.length() });
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

impl<'a> Builder<'a> {
    /// How many prisms have been inserted.
    fn prism_count(&self) -> usize {
        self.translated + self.keyframed.prisms.len()
    }

    /// The corners of prism `p` of run `k`, in the run's comoving
    /// coordinates, if the run is a translation.
    fn comoving(&self, k: usize, p: usize) -> Option<[DVec3; 3]> {
        let run = &self.runs[k];
        let mesh = self.meshes[k].as_ref()?;
        Some(mesh.corners(p - run.stretch.prisms.start))
    }

    /// Extrudes a keyframed object pose to pose, each interval one stretch
    /// of its path; `parents` names each triangle's triangle of the given
    /// mesh (empty: its own).
    fn keyframed(
        &mut self,
        object: u32,
        (mesh, parents): (&Mesh, &[u32]),
        poses: &[Pose],
        contracted: bool,
    ) -> Result<Vec<Stretch>, Fault> {
        for (k, f) in poses.iter().enumerate() {
            let shape = Mesh {
                vertices: f.vertices.clone(),
                triangles: mesh.triangles.clone(),
                materials: Vec::new(),
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
            let (first, slot) = (self.prism_count(), self.keyframed.prisms.len());
            let kf = &mut self.keyframed;
            let (prisms, corners) = (&mut kf.prisms, &mut kf.corners);
            extrude_between(mesh, parents, &w[0], &w[1], object, prisms, corners);
            self.runs.push(Run {
                object,
                stretch: StretchPrisms {
                    origin: worldline.start,
                    velocity: v,
                    span: (w[0].t, w[1].t),
                    prisms: first..first + mesh.triangles.len(),
                    translation: false,
                },
                extrusion: worldline.extrusion,
                slot,
                vertices: 0,
                reach: 0.0,
            });
            self.meshes.push(None);
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
    fn uniform(&mut self, i: usize, obj: &'a SceneObject, lorentz: bool) -> Result<Stretch, Fault> {
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
            let mesh = if boost.beta() == DVec3::ZERO {
                // Contraction changes nothing, and `insert` has validated it.
                Cow::Borrowed(mesh_of(obj))
            } else {
                let contracted = mesh_of(obj).map_vertices(|p| boost.contract(p));
                contracted
                    .validate()
                    .map_err(|e| Fault::new(F::Shape, K::ContractedMesh(e)))?;
                Cow::Owned(contracted)
            };
            let (first, slot, vertices) = (self.prism_count(), self.translated, self.vertex_count);
            let count = mesh.triangles.len();
            self.translated += count;
            self.vertex_count += mesh.vertices.len();
            let reach = match self.checking {
                true => 0.0,
                false => geometry::mesh_reach(&mesh),
            };
            self.meshes.push((!self.checking).then_some(mesh));
            self.runs.push(Run {
                object: i as u32,
                stretch: StretchPrisms {
                    origin: worldline.start,
                    velocity: worldline.velocity(),
                    span: (worldline.start.t, worldline.end().t),
                    prisms: first..first + count,
                    translation: true,
                },
                extrusion: worldline.extrusion,
                slot,
                vertices,
                reach,
            });
        }
        Ok(Stretch {
            worldline,
            clock: boost,
            proper_start: 0.0,
            translation: true,
        })
    }

    /// Inserts object `i`, returning its path as stretches; hyperbolic
    /// motion is cut as its worldline's objects share ([`shared_cuts`]).
    fn insert(
        &mut self,
        i: usize,
        obj: &'a SceneObject,
        lorentz: bool,
        shared: Option<Shared>,
    ) -> Result<Vec<Stretch>, Fault> {
        match &obj.shape {
            Shape::Sphere { radius: r } if !(*r > 0.0 && r.is_finite()) => {
                return Err(Fault::new(F::Shape, K::SphereRadius(*r)));
            }
            Shape::Sphere { .. } => {}
            Shape::Mesh(mesh) => {
                mesh.validate()
                    .map_err(|e| Fault::new(F::Shape, K::Mesh(e)))?;
                material_indices(mesh, obj.face_materials.len() + 1)?;
            }
        }
        let mesh = mesh_of(obj);
        let contracted = lorentz && obj.kind == ObjectKind::VObj;
        let resolved = match &obj.motion {
            Motion::Keyframes(k) => Some(Resolved {
                pieces: None,
                poses: geometry::resolve(k, mesh, contracted)?,
            }),
            Motion::Hyperbolic(h) => Some(resolve_hyperbolic(h, mesh, contracted, shared)?),
            _ => None,
        };
        match resolved {
            Some(_) if matches!(obj.shape, Shape::Sphere { .. }) => {
                Err(Fault::new(F::Motion, K::SphereNotUniform))
            }
            Some(r) => {
                let surface = (r.mesh(mesh), r.parents());
                self.keyframed(i as u32, surface, &r.poses, contracted)
            }
            None => Ok(vec![self.uniform(i, obj, lorentz)?]),
        }
    }
}

/// Every object inserted, before the acceleration structure is built.
struct Inserted<'a> {
    builder: Builder<'a>,
    records: Vec<ObjectRecord>,
}

/// Extrudes every object and prepares every keyframe tetrahedron's solve;
/// the errors are those of [`Database::build`].
fn insert_all(scene: &Scene, lorentz: bool) -> Result<Inserted<'_>, SceneError> {
    let mut b = Builder::default();
    let mut records = Vec::new();
    let cuts = shared_cuts(scene, lorentz, mesh_of);
    for (i, obj) in scene.objects.iter().enumerate() {
        let first = b.keyframed.prisms.len();
        let stretches = b
            .insert(i, obj, lorentz, cuts[i])
            .map_err(|f| f.of(i, &obj.name))?;
        prepare(&mut b.keyframed, first).map_err(|f| f.of(i, &obj.name))?;
        records.push(ObjectRecord {
            name: obj.name.clone(),
            kind: obj.kind,
            material: obj.material.clone(),
            face_materials: obj.face_materials.clone(),
            triangle_materials: mesh_of(obj).materials.clone(),
            contracted: lorentz && obj.kind == ObjectKind::VObj,
            stretches,
            emission_rgb: std::iter::once(&obj.material)
                .chain(&obj.face_materials)
                .map(Material::emission_rgb)
                .collect(),
        });
    }
    Ok(Inserted {
        builder: b,
        records,
    })
}

/// Prepares the solves of the tetrahedra of the keyframe prisms from
/// `first` on (one object's), or the fault of the first with no 3-volume.
fn prepare(kf: &mut Keyframed, first: usize) -> Result<(), Fault> {
    kf.prepared.reserve(3 * (kf.prisms.len() - first));
    for (p, corners) in kf.corners.iter().enumerate().skip(first) {
        for k in 0..3 {
            let solve = PreparedTet::new(&piece(corners, k)).ok_or_else(|| {
                Fault::new(
                    F::Shape,
                    K::FlatTetrahedron {
                        triangle: kf.prisms[p].triangle,
                    },
                )
            })?;
            kf.prepared.push(solve);
        }
    }
    Ok(())
}

/// A keyframe prism's box in its stretch's comoving coordinates: the box of
/// all six corners (which holds the prism, comoving coordinates being affine
/// in the event), padded for the rounding of the comoving transform.
fn keyframed_box(g: &StretchPrisms, corners: &PrismCorners) -> (DVec3, DVec3) {
    let (t0, v) = (g.span.0, g.velocity);
    let (mut a, mut b) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for e in corners {
        let x = e.x - v * (e.t - t0) - g.origin.x;
        a = a.min(x);
        b = b.max(x);
    }
    let pad = rounding_margin(a.extend(0.0), b.extend(0.0)).truncate();
    (a - pad, b + pad)
}

/// Runs of at least this many triangles are put in leaf order on both
/// threads (handing a small one to the thread pool would cost more).
const PARALLEL_GATHER: usize = 1 << 14;

/// The triangles of translations in their comoving coordinates, their
/// corners stored in the order their stretch's hierarchy holds them (so
/// that a leaf's triangles lie side by side, read in one sweep), and where
/// each prism's is: at `slot + stored_at[slot + k]` for prism k of a run at
/// `slot`. Gathered from the runs' meshes on both threads (the build's
/// scratch, which sets the peak of memory, is freed by now).
fn in_leaf_order(b: &Builder, accel: &TwoLevel) -> (ComovingMeshes, Vec<u32>) {
    let mut stored_at = vec![0u32; b.translated];
    let mut sorted = ComovingMeshes {
        vertices: Vec::with_capacity(b.vertex_count),
        corners: vec![[0; 3]; b.translated],
    };
    for (k, run) in b.runs.iter().enumerate() {
        let Some(mesh) = &b.meshes[k] else {
            continue;
        };
        sorted.vertices.extend_from_slice(&mesh.vertices);
        let order = accel.order(k);
        let to = &mut sorted.corners[run.slot..];
        let gather = |(t, &i): (&mut [u32; 3], &u32)| *t = mesh.triangles[i as usize];
        if order.len() >= PARALLEL_GATHER {
            (to[..order.len()].par_iter_mut().zip(order)).for_each(gather);
        } else {
            to.iter_mut().zip(order).for_each(gather);
        }
        for (j, &i) in order.iter().enumerate() {
            stored_at[run.slot + i as usize] = j as u32;
        }
    }
    (sorted, stored_at)
}

/// The comoving triangle stored at each place `j`: translations' runs hold
/// the places from their `slot` on, in order, each with its vertices from
/// its `vertices` on.
fn stored_triangle<'a>(
    runs: &[Run],
    comoving: &'a ComovingMeshes,
) -> impl Fn(usize) -> [DVec3; 3] + Sync + 'a {
    let starts: Vec<(usize, usize)> = (runs.iter())
        .filter(|r| r.stretch.translation)
        .map(|r| (r.slot, r.vertices))
        .collect();
    move |j| {
        let run = starts.partition_point(|&(slot, _)| slot <= j) - 1;
        comoving.triangle(starts[run].1, j)
    }
}

impl Database {
    /// Temporally extrudes every object of `scene`. With `lorentz` on, V_obj
    /// objects are contracted along their velocity and their lifetimes and
    /// clocks dilated; with it off every object is inserted as an H_obj.
    pub fn build(scene: &Scene, lorentz: bool) -> Result<Database, SceneError> {
        let Inserted {
            builder: b,
            records,
        } = insert_all(scene, lorentz)?;
        let accel = TwoLevel::build(b.runs.iter().map(|r| &r.stretch), |k, p| {
            let run = &b.runs[k];
            match b.comoving(k, p) {
                Some(c) => (c[0].min(c[1]).min(c[2]), c[0].max(c[1]).max(c[2])),
                None => {
                    let slot = run.slot + p - run.stretch.prisms.start;
                    keyframed_box(&run.stretch, &b.keyframed.corners[slot])
                }
            }
        });
        let (comoving, stored_at) = in_leaf_order(&b, &accel);
        Ok(Database {
            rows: CornerRows::new(comoving.len(), stored_triangle(&b.runs, &comoving)),
            records,
            runs: b.runs,
            comoving,
            stored_at,
            keyframed: b.keyframed,
            accel,
            spheres: b.spheres,
            traversal: Traversal::Bvh,
            packing: Packing::Auto,
            simd: SimdLevel::default(),
            reach: OnceLock::new(),
        })
    }

    /// Whether [`Database::build`] would accept `scene`: the same insertion
    /// and the same errors (object by object, in order), without building
    /// the acceleration structure and holding one object's prisms at a
    /// time. `lorentz` only matters for V_obj objects.
    pub fn validate(scene: &Scene, lorentz: bool) -> Result<(), SceneError> {
        let cuts = shared_cuts(scene, lorentz, mesh_of);
        for (i, obj) in scene.objects.iter().enumerate() {
            let mut b = Builder {
                checking: true,
                ..Builder::default()
            };
            b.insert(i, obj, lorentz, cuts[i])
                .map_err(|f| f.of(i, &obj.name))?;
            let kf = &b.keyframed;
            for (p, corners) in kf.corners.iter().enumerate() {
                if (0..3).any(|k| PreparedTet::new(&piece(corners, k)).is_none()) {
                    let triangle = kf.prisms[p].triangle;
                    return Err(
                        Fault::new(F::Shape, K::FlatTetrahedron { triangle }).of(i, &obj.name)
                    );
                }
            }
        }
        Ok(())
    }
}
