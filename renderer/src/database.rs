//! The static 4D database (paper 3, items 1-2): every object temporally
//! extruded once, and never modified between frames (paper 3, item 6).

use crate::boost::Boost;
use crate::bvh::Bvh;
use crate::extrude::{extrude, extrude_between, Prism, Tetrahedron};
use crate::intersect::{nearer, Hit, Miss, PreparedTet};
use crate::keyframe::{self, Frame};
use crate::lightcone::Ray;
use crate::mesh::Mesh;
use crate::scene::{Motion, ObjectKind, Scene, SceneObject};
use crate::shade::Material;
use crate::spacetime::{Event, FourVector, Worldline};
use crate::trace::{NoTrace, Outcome, Step, Trace};
use glam::{DVec3, DVec4};
use std::fmt;

/// A scene that cannot be inserted, with the field at fault.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneError {
    /// Location of the offending field, e.g. `objects[2].worldline.velocity`.
    pub path: String,
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path, self.message)
    }
}

impl std::error::Error for SceneError {}

/// One straight stretch of an object's path: its whole worldline for
/// uniform motion, or one interval between keyframes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Piece {
    /// Lab-frame worldline of the reference point over the stretch.
    pub worldline: Worldline,
    /// Boost from the stretch's comoving frame (identity when
    /// Lorentz-decoupled).
    pub clock: Boost,
    /// The object's proper time at the start of the stretch.
    pub proper_start: f64,
}

/// An object as inserted into the database.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjectRecord {
    pub name: String,
    pub kind: ObjectKind,
    pub material: Material,
    /// Its path in lab-time order: one piece for uniform motion, one per
    /// keyframe interval otherwise.
    pub pieces: Vec<Piece>,
}

impl ObjectRecord {
    /// The stretch of the path at lab time `t` (the first or last outside
    /// the lifetime).
    pub fn piece_at(&self, t: f64) -> &Piece {
        let k = self.pieces.partition_point(|p| p.worldline.end().t < t);
        &self.pieces[k.min(self.pieces.len() - 1)]
    }

    /// Lab times of the start and end of the object's existence.
    pub fn lifetime(&self) -> (f64, f64) {
        let (first, last) = (self.pieces[0], self.pieces[self.pieces.len() - 1]);
        (first.worldline.start.t, last.worldline.end().t)
    }

    /// The object's own time at a lab event on it: the comoving frame's
    /// time coordinate, zero at the start event; for a decoupled object, lab
    /// time since the start. Drives time-dependent materials (paper 3,
    /// item 2d).
    pub fn proper_time(&self, event: Event) -> f64 {
        let p = self.piece_at(event.t);
        p.proper_start + p.clock.to_rest(event - p.worldline.start).t
    }

    /// Where a lab event on the object lies in the object's frame:
    /// comoving coordinates relative to the reference point at the start
    /// of the stretch.
    pub fn local_point(&self, event: Event) -> DVec3 {
        let p = self.piece_at(event.t);
        p.clock.to_rest(event - p.worldline.start).x
    }
}

/// How rays find candidate tetrahedra. Both give identical hits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Traversal {
    /// Every tetrahedron for every ray.
    BruteForce,
    /// A bounding volume hierarchy over the tetrahedra's 4D bounds.
    Bvh,
}

/// One object's acceleration structure: a hierarchy over its prisms in its
/// comoving (sheared) coordinates x' = x - v (t - t0) - x0, where a
/// constant-velocity object is static, so its bounds stay tight however
/// fast or long-lived it is (instancing with a per-object transform).
struct Instance {
    origin: Event,
    velocity: DVec3,
    first_prism: u32,
    bvh: Bvh,
}

impl Instance {
    /// The ray `o + s d` in comoving coordinates, with the same parameter s.
    #[inline]
    fn to_comoving(&self, o: DVec4, d: DVec4) -> (DVec4, DVec4) {
        let x = o.truncate() - self.velocity * (o.w - self.origin.t) - self.origin.x;
        let dx = d.truncate() - self.velocity * d.w;
        (x.extend(o.w), dx.extend(d.w))
    }
}

/// The static 4D database.
pub struct Database {
    objects: Vec<ObjectRecord>,
    prisms: Vec<Prism>,
    tets: Vec<Tetrahedron>,
    prepared: Vec<PreparedTet>,
    /// Over the lab-frame 4D bounds of the objects' time segments.
    top: Bvh,
    instances: Vec<Instance>,
    segments: Vec<Segment>,
    /// Analytic spheres, numbered after the tetrahedra in hits.
    spheres: Vec<Sphere>,
    traversal: Traversal,
}

/// An analytic sphere: in its object's comoving coordinates
/// x' = x - v (t - t0) - x0 it is static; Lorentz-contracted (a V_obj) it is
/// the ellipsoid |S x'| = R, S stretching by gamma along v.
struct Sphere {
    object: u32,
    radius: f64,
    origin: Event,
    velocity: DVec3,
    /// 1 when not contracted.
    gamma: f64,
    /// Lab time the object's life ends.
    end: f64,
}

impl Sphere {
    /// S applied to a comoving offset: its component along v times gamma.
    fn stretch(&self, p: DVec3) -> DVec3 {
        let b2 = self.velocity.length_squared();
        if b2 == 0.0 || self.gamma == 1.0 {
            return p;
        }
        let along = self.velocity * (self.velocity.dot(p) / b2);
        p + along * (self.gamma - 1.0)
    }

    fn comoving(&self, e: Event) -> DVec3 {
        e.x - self.velocity * (e.t - self.origin.t) - self.origin.x
    }

    /// The nearest crossing of the sphere's worldtube within `range` and
    /// its lifetime: |S (o' + s d')| = R, a quadratic in s.
    fn intersect(&self, ray: &Ray, id: u32, range: (f64, f64)) -> Option<Hit> {
        let a = self.stretch(self.comoving(ray.origin));
        let b = self.stretch(ray.direction.x - self.velocity * ray.direction.t);
        let (qa, qb, qc) = (
            b.length_squared(),
            2.0 * a.dot(b),
            a.length_squared() - self.radius * self.radius,
        );
        let disc = qb * qb - 4.0 * qa * qc;
        if qa == 0.0 || disc < 0.0 {
            return None;
        }
        let q = -0.5 * (qb + qb.signum() * disc.sqrt());
        let (r1, r2) = (q / qa, if q != 0.0 { qc / q } else { q / qa });
        let alive = |s: f64| {
            let t = ray.origin.t + s * ray.direction.t;
            s >= range.0 && s <= range.1 && t >= self.origin.t && t <= self.end
        };
        let s = [r1.min(r2), r1.max(r2)].into_iter().find(|s| alive(*s))?;
        Some(Hit {
            s,
            event: ray.at(s),
            tet: id,
            bary: [0.0; 4],
        })
    }

    /// Outward unit normal at an event on the surface (lab frame): the
    /// gradient of |S x'|^2, S^T S x'.
    fn normal(&self, e: Event) -> DVec3 {
        self.stretch(self.stretch(self.comoving(e))).normalize()
    }
}

/// The surface a hit lies on: its object, the lab-frame unit normal, and the
/// triangle (0 for a sphere).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    pub object: u32,
    pub normal: DVec3,
    pub triangle: u32,
}

fn err(path: String, message: String) -> SceneError {
    SceneError { path, message }
}

/// The straight worldline of a uniformly moving object and the boost of
/// its rest frame (identity unless a V_obj under the Lorentz transform);
/// errors name the field relative to the object.
fn straight(obj: &SceneObject, lorentz: bool) -> Result<(Worldline, Boost), (String, String)> {
    let v = match obj.motion {
        Motion::Extrusion { extrusion, .. } => extrusion.velocity(),
        Motion::Velocity { velocity, .. } => velocity,
        Motion::Keyframes(_) | Motion::Hyperbolic(_) => unreachable!("resolved into keyframes"),
    };
    let bad = |f: &str, m: &str| Err((f.to_string(), m.to_string()));
    if !v.is_finite() {
        return bad(
            "worldline",
            "the velocity is not finite (zero-duration extrusion?)",
        );
    }
    if obj.kind == ObjectKind::VObj && v.length() >= 1.0 {
        return Err((
            "worldline".into(),
            format!(
                "a V_obj moves at {:.6}c; it must be slower than light (use an H_obj for a Lorentz-decoupled, superluminal object)",
                v.length()
            ),
        ));
    }
    let boost = match (obj.kind, lorentz) {
        (ObjectKind::VObj, true) => Boost::new(v).expect("checked above"),
        _ => Boost::identity(),
    };
    let worldline = match obj.motion {
        Motion::Extrusion { start, extrusion } => {
            if !start.is_finite() {
                return bad("worldline.start", "must be finite numbers");
            }
            if !extrusion.is_finite() {
                return bad("worldline.extrusion", "must be finite numbers");
            }
            if extrusion.t == 0.0 {
                return bad(
                    "worldline.extrusion",
                    "zero-duration extrusion (dt = 0): the object would exist for no time",
                );
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
                return bad("worldline.start", "must be finite numbers");
            }
            if !(proper_lifetime > 0.0 && proper_lifetime.is_finite()) {
                return bad(
                    "worldline.proper_lifetime",
                    "must be a positive finite time",
                );
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

/// Extrudes a keyframed object interval by interval, each interval one
/// piece of its path and one instance of the acceleration structure.
/// Errors name the keyframe, relative to the keyframe list.
#[allow(clippy::too_many_arguments)]
fn keyframed(
    object: u32,
    mesh: &Mesh,
    frames: &[Frame],
    contracted: bool,
    prisms: &mut Vec<Prism>,
    tets: &mut Vec<Tetrahedron>,
    groups: &mut Vec<Group>,
) -> Result<Vec<Piece>, (String, String)> {
    for (k, f) in frames.iter().enumerate() {
        let shape = Mesh {
            vertices: f.vertices.clone(),
            triangles: mesh.triangles.clone(),
        };
        shape
            .validate()
            .map_err(|e| (format!("[{k}]"), format!("at t = {}: {e}", f.t)))?;
    }
    let mut pieces = Vec::with_capacity(frames.len() - 1);
    for (k, w) in frames.windows(2).enumerate() {
        let worldline = Worldline {
            start: Event::new(w[0].t, w[0].reference),
            extrusion: FourVector::new(w[1].t - w[0].t, w[1].reference - w[0].reference),
        };
        let v = worldline.velocity();
        let clock = if contracted {
            Boost::new(v).ok_or_else(|| {
                (
                    format!("[{}]", k + 1),
                    format!(
                        "the reference point moves at {:.6}c; a V_obj must be slower than light",
                        v.length()
                    ),
                )
            })?
        } else {
            Boost::identity()
        };
        let first = prisms.len();
        extrude_between(mesh, &w[0], &w[1], object, prisms, tets);
        groups.push(Group {
            origin: worldline.start,
            velocity: v,
            span: (w[0].t, w[1].t),
            prisms: first..prisms.len(),
            translation: false,
        });
        pieces.push(Piece {
            worldline,
            clock,
            proper_start: w[0].proper_time,
        });
    }
    Ok(pieces)
}

impl Database {
    /// Temporally extrudes every object of `scene`. With `lorentz` on, V_obj
    /// objects are contracted along their velocity and their lifetimes and
    /// clocks dilated; with it off every object is inserted as an H_obj.
    pub fn build(scene: &Scene, lorentz: bool) -> Result<Database, SceneError> {
        let mut objects = Vec::new();
        let mut prisms = Vec::new();
        let mut tets = Vec::new();
        let mut spheres = Vec::new();
        let mut groups = Vec::new();
        for (i, obj) in scene.objects.iter().enumerate() {
            let at = |field: &str| format!("objects[{i}].{field}");
            let named = |m: String| format!("object {:?}: {m}", obj.name);
            match obj.sphere {
                Some(r) if !(r > 0.0 && r.is_finite()) => {
                    return Err(err(
                        at("mesh"),
                        named(format!("sphere radius {r}: expected a positive length")),
                    ));
                }
                Some(_) => {}
                None => obj
                    .mesh
                    .validate()
                    .map_err(|e| err(at("mesh"), named(e.to_string())))?,
            }
            let contracted = lorentz && obj.kind == ObjectKind::VObj;
            let frames = match &obj.motion {
                Motion::Keyframes(k) => Some(
                    keyframe::resolve(k, &obj.mesh, contracted)
                        .map_err(|(f, m)| err(at(&format!("worldline.keyframes{f}")), named(m)))?,
                ),
                Motion::Hyperbolic(h) => {
                    Some(h.keyframes(&obj.mesh, contracted).map_err(|(f, m)| {
                        err(at(&format!("worldline.hyperbolic.{f}")), named(m))
                    })?)
                }
                _ => None,
            };
            let pieces = match frames {
                Some(_) if obj.sphere.is_some() => {
                    return Err(err(
                        at("worldline"),
                        named("an analytic sphere moves uniformly (extrusion or velocity); give a tessellated sphere keyframes or hyperbolic motion".into()),
                    ));
                }
                Some(frames) => keyframed(
                    i as u32,
                    &obj.mesh,
                    &frames,
                    contracted,
                    &mut prisms,
                    &mut tets,
                    &mut groups,
                )
                .map_err(|(f, m)| err(at(&format!("worldline.keyframes{f}")), named(m)))?,
                None => {
                    let (worldline, boost) =
                        straight(obj, lorentz).map_err(|(f, m)| err(at(&f), named(m)))?;
                    if let Some(radius) = obj.sphere {
                        spheres.push(Sphere {
                            object: i as u32,
                            radius,
                            origin: worldline.start,
                            velocity: worldline.velocity(),
                            gamma: boost.gamma(),
                            end: worldline.end().t,
                        });
                    } else {
                        let mesh = obj.mesh.map_vertices(|p| boost.contract(p));
                        mesh.validate().map_err(|e| {
                            err(at("mesh"), named(format!("after Lorentz contraction: {e}")))
                        })?;
                        let first = prisms.len();
                        extrude(&mesh, &worldline, i as u32, &mut prisms, &mut tets);
                        groups.push(Group {
                            origin: worldline.start,
                            velocity: worldline.velocity(),
                            span: (worldline.start.t, worldline.end().t),
                            prisms: first..prisms.len(),
                            translation: true,
                        });
                    }
                    vec![Piece {
                        worldline,
                        clock: boost,
                        proper_start: 0.0,
                    }]
                }
            };
            objects.push(ObjectRecord {
                name: obj.name.clone(),
                kind: obj.kind,
                material: obj.material.clone(),
                pieces,
            });
        }
        let mut prepared = Vec::with_capacity(tets.len());
        for t in &tets {
            let p = PreparedTet::new(t).ok_or_else(|| {
                let prism = prisms[t.prism as usize];
                err(
                    format!("objects[{}].mesh", prism.object),
                    format!(
                        "triangle {} extrudes to a tetrahedron with no 3-volume",
                        prism.triangle
                    ),
                )
            })?;
            prepared.push(p);
        }
        let (top, instances, segments) = accelerate(&groups, &tets);
        Ok(Database {
            objects,
            prisms,
            tets,
            prepared,
            top,
            instances,
            segments,
            spheres,
            traversal: Traversal::Bvh,
        })
    }

    pub fn set_traversal(&mut self, traversal: Traversal) {
        self.traversal = traversal;
    }

    pub fn traversal(&self) -> Traversal {
        self.traversal
    }

    pub fn objects(&self) -> &[ObjectRecord] {
        &self.objects
    }

    pub fn prisms(&self) -> &[Prism] {
        &self.prisms
    }

    pub fn tetrahedra(&self) -> &[Tetrahedron] {
        &self.tets
    }

    /// The surface a hit lies on: a triangle's prism, or an analytic sphere.
    pub fn surface(&self, hit: &Hit) -> Surface {
        let n = self.tets.len() as u32;
        if hit.tet < n {
            let p = self.prism_of(hit.tet);
            Surface {
                object: p.object,
                normal: p.normal_at(hit.event.t),
                triangle: p.triangle,
            }
        } else {
            let sp = &self.spheres[(hit.tet - n) as usize];
            Surface {
                object: sp.object,
                normal: sp.normal(hit.event),
                triangle: 0,
            }
        }
    }

    /// The prism a tetrahedron belongs to.
    pub fn prism_of(&self, tet: u32) -> &Prism {
        &self.prisms[self.tets[tet as usize].prism as usize]
    }

    /// One tetrahedron's barycentric solve, with the reason for a miss.
    pub fn test(&self, ray: &Ray, tet: u32, range: (f64, f64)) -> Result<Hit, Miss> {
        self.prepared[tet as usize].intersect(ray, tet, range)
    }

    /// The solve of `tet`, recorded as a candidate.
    fn test_traced<T: Trace>(
        &self,
        ray: &Ray,
        tet: u32,
        range: (f64, f64),
        trace: &mut T,
    ) -> Result<Hit, Miss> {
        let result = self.test(ray, tet, range);
        if T::ENABLED {
            let t = &self.tets[tet as usize];
            let prism = &self.prisms[t.prism as usize];
            trace.record(Step::Candidate {
                tet,
                object: self.objects[prism.object as usize].name.clone(),
                triangle: prism.triangle,
                prism: t.prism,
                piece: t.piece,
                outcome: Outcome::from(&result),
            });
        }
        result
    }

    /// The hit with the smallest ray parameter in `range`: on a light-cone
    /// ray, the most recent event (paper 3.2).
    pub fn closest_hit(&self, ray: &Ray, range: (f64, f64)) -> Option<Hit> {
        self.closest_hit_traced(ray, range, &mut NoTrace)
    }

    /// [`Database::closest_hit`], recording every tetrahedron tested.
    pub fn closest_hit_traced<T: Trace>(
        &self,
        ray: &Ray,
        range: (f64, f64),
        trace: &mut T,
    ) -> Option<Hit> {
        let mut best = self.closest_tet(ray, range, trace);
        // Analytic spheres (few): the same for every traversal.
        let first = self.tets.len() as u32;
        for (k, sphere) in self.spheres.iter().enumerate() {
            let hi = best.map_or(range.1, |b| b.s);
            if let Some(h) = sphere.intersect(ray, first + k as u32, (range.0, hi)) {
                best = Some(nearer(best, h));
            }
        }
        best
    }

    fn closest_tet<T: Trace>(&self, ray: &Ray, range: (f64, f64), trace: &mut T) -> Option<Hit> {
        match self.traversal {
            Traversal::BruteForce => {
                let mut best: Option<Hit> = None;
                for i in 0..self.tets.len() as u32 {
                    let hi = best.map_or(range.1, |b| b.s);
                    if let Ok(h) = self.test_traced(ray, i, (range.0, hi), trace) {
                        best = Some(nearer(best, h));
                    }
                }
                best
            }
            Traversal::Bvh => {
                let (o, d) = (ray.origin.to_xyzt(), ray.direction.to_xyzt());
                self.top.closest(o, d, range, |k, r| {
                    let seg = &self.segments[k as usize];
                    let r = seg.window(o, d, r)?;
                    let inst = &self.instances[seg.instance as usize];
                    let (oc, dc) = inst.to_comoving(o, d);
                    inst.bvh.closest(oc, dc, r, |p, r| {
                        let first = 3 * (inst.first_prism + p);
                        let mut best: Option<Hit> = None;
                        for tet in first..first + 3 {
                            let hi = best.map_or(r.1, |b| b.s);
                            if let Ok(h) = self.test_traced(ray, tet, (r.0, hi), trace) {
                                best = Some(nearer(best, h));
                            }
                        }
                        best
                    })
                })
            }
        }
    }
}

/// Most time segments one object is cut into in the top-level hierarchy.
const MAX_SEGMENTS: usize = 64;

/// One entry of the top-level hierarchy: an object over a stretch of its
/// lifetime, bounded by its sweep over that stretch only (so a fast or
/// long-lived object does not cover the whole scene; cf. STBVH).
struct Segment {
    instance: u32,
    /// Lab times of the stretch.
    t0: f64,
    t1: f64,
}

impl Segment {
    /// The part of `range` where the ray `o + s d` is within the stretch's
    /// lab times; `None` if it never is.
    #[inline]
    fn window(&self, o: DVec4, d: DVec4, range: (f64, f64)) -> Option<(f64, f64)> {
        if d.w == 0.0 {
            return (self.t0 <= o.w && o.w <= self.t1).then_some(range);
        }
        let (a, b) = ((self.t0 - o.w) / d.w, (self.t1 - o.w) / d.w);
        let (lo, hi) = (range.0.max(a.min(b)), range.1.min(a.max(b)));
        (lo <= hi).then_some((lo, hi))
    }
}

/// A run of prisms moving together: an object's whole extrusion, or one
/// keyframe interval of it. Its comoving frame follows the reference point
/// from `origin` with `velocity`.
struct Group {
    origin: Event,
    velocity: DVec3,
    /// Lab times covered.
    span: (f64, f64),
    prisms: std::ops::Range<usize>,
    /// Whether every prism is a pure translation along `velocity`.
    translation: bool,
}

/// The two-level structure: per group, a hierarchy over its prisms'
/// comoving bounds (the box of all six corners in comoving coordinates,
/// which holds the prism since comoving coordinates are affine in the
/// event, times the group's span); over all groups, a hierarchy of the
/// lab-frame 4D bounds of their time segments. A group is cut into as many
/// segments as it takes for each to sweep about its own size (at most
/// [`MAX_SEGMENTS`]).
fn accelerate(groups: &[Group], tets: &[Tetrahedron]) -> (Bvh, Vec<Instance>, Vec<Segment>) {
    let mut instances = Vec::new();
    let mut segments = Vec::new();
    let mut seg_bounds = Vec::new();
    for g in groups {
        let (t0, t1) = g.span;
        let v = g.velocity;
        let mut comoving = Vec::with_capacity(g.prisms.len());
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for p in g.prisms.clone() {
            let (mut a, mut b) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
            // A translated prism's box is that of its start corners, which
            // the first piece holds; a keyframe interval's takes all six
            // corners, which the three pieces hold, padded for the rounding
            // of the comoving transform.
            let pieces = if g.translation { 1 } else { 3 };
            for tet in &tets[3 * p..3 * p + pieces] {
                for e in &tet.vertices[..if g.translation { 3 } else { 4 }] {
                    let x = e.x - v * (e.t - t0) - g.origin.x;
                    a = a.min(x);
                    b = b.max(x);
                }
            }
            if !g.translation {
                let pad = (b - a) * 1e-9 + (a.abs() + b.abs()) * 1e-12;
                (a, b) = (a - pad, b + pad);
            }
            comoving.push((a.extend(t0), b.extend(t1)));
            lo = lo.min(a);
            hi = hi.max(b);
        }
        let size = (hi - lo).max_element().max(1e-9);
        let sweep = (v * (t1 - t0)).length();
        let count = ((sweep / size).ceil() as usize).clamp(1, MAX_SEGMENTS);
        for k in 0..count {
            let (ta, tb) = (
                t0 + (t1 - t0) * k as f64 / count as f64,
                if k + 1 == count {
                    t1
                } else {
                    t0 + (t1 - t0) * (k + 1) as f64 / count as f64
                },
            );
            let (pa, pb) = (g.origin.x + v * (ta - t0), g.origin.x + v * (tb - t0));
            let (bl, bh) = ((lo + pa).min(lo + pb), (hi + pa).max(hi + pb));
            // Pad for the rounding of positions computed along the worldline.
            let pad = (bh - bl) * 1e-9 + (bl.abs() + bh.abs()) * 1e-12 + DVec3::splat(1e-300);
            seg_bounds.push(((bl - pad).extend(ta), (bh + pad).extend(tb)));
            segments.push(Segment {
                instance: instances.len() as u32,
                t0: ta,
                t1: tb,
            });
        }
        instances.push(Instance {
            origin: g.origin,
            velocity: v,
            first_prism: g.prisms.start as u32,
            bvh: Bvh::build(&comoving),
        });
    }
    (Bvh::build(&seg_bounds), instances, segments)
}
