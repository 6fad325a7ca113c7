//! The static 4D database (paper 3, items 1-2): every object temporally
//! extruded once, and never modified between frames (paper 3, item 6).

mod build;
mod object;

pub use object::{ObjectRecord, Stretch};

use crate::accel::TwoLevel;
use crate::geometry::{
    nearer, piece, Hit, Miss, PreparedTet, PrimitiveId, Prism, PrismCorners, Sphere, Tetrahedron,
};
use crate::spacetime::Ray;
use crate::trace::{NoTrace, Outcome, Step, Trace};
use glam::DVec3;

/// How rays find candidate tetrahedra. Both give identical hits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Traversal {
    /// Every tetrahedron for every ray.
    BruteForce,
    /// A bounding volume hierarchy over the tetrahedra's 4D bounds.
    Bvh,
}

/// The static 4D database.
pub struct Database {
    records: Vec<ObjectRecord>,
    prisms: Vec<Prism>,
    /// Each prism's corners; its tetrahedra 3p, 3p + 1, 3p + 2 are read off
    /// them (the events are kept once, not once per tetrahedron).
    corners: Vec<PrismCorners>,
    /// Each tetrahedron's prepared solve, three per prism in prism order.
    prepared: Vec<PreparedTet>,
    /// The two-level hierarchy over the prisms.
    accel: TwoLevel,
    /// Analytic spheres, numbered after the tetrahedra in hits.
    spheres: Vec<Sphere>,
    traversal: Traversal,
}

/// The surface a hit lies on: its object, the lab-frame unit normal, and the
/// triangle (0 for a sphere).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// Index of the object in [`Database::objects`].
    pub object: u32,
    /// Lab-frame unit normal at the hit.
    pub normal: DVec3,
    /// Index of the triangle in the object's mesh.
    pub triangle: u32,
}

impl Database {
    /// Chooses how rays find candidate tetrahedra.
    pub fn set_traversal(&mut self, traversal: Traversal) {
        self.traversal = traversal;
    }

    /// How rays find candidate tetrahedra.
    pub fn traversal(&self) -> Traversal {
        self.traversal
    }

    /// The objects as inserted, in scene order.
    pub fn objects(&self) -> &[ObjectRecord] {
        &self.records
    }

    /// Every extruded triangle.
    pub fn prisms(&self) -> &[Prism] {
        &self.prisms
    }

    /// How many tetrahedra there are: three per prism.
    pub fn tetrahedron_count(&self) -> usize {
        self.prepared.len()
    }

    /// Tetrahedron `i`: piece `i % 3` of prism `i / 3`.
    pub fn tetrahedron(&self, i: u32) -> Tetrahedron {
        let (prism, k) = (i / 3, (i % 3) as usize);
        Tetrahedron {
            vertices: piece(&self.corners[prism as usize], k),
            prism,
            piece: k as u8,
        }
    }

    /// Every tetrahedron, three per prism in prism order.
    pub fn tetrahedra(&self) -> impl ExactSizeIterator<Item = Tetrahedron> + '_ {
        (0..self.tetrahedron_count() as u32).map(|i| self.tetrahedron(i))
    }

    /// The surface a hit lies on: a triangle's prism, or an analytic sphere.
    pub fn surface(&self, hit: &Hit) -> Surface {
        match hit.primitive {
            PrimitiveId::Tetrahedron(tet) => {
                let p = self.prism_of(tet);
                Surface {
                    object: p.object,
                    normal: p.normal_at(hit.event.t),
                    triangle: p.triangle,
                }
            }
            PrimitiveId::Sphere(k) => {
                let sp = &self.spheres[k as usize];
                Surface {
                    object: sp.object,
                    normal: sp.normal(hit.event),
                    triangle: 0,
                }
            }
        }
    }

    /// The lab velocity of the surface point at `hit`, and the gamma of
    /// its clock (1 unless the object is Lorentz-transformed). Over a
    /// translation (uniform motion, and every analytic sphere) that is the
    /// stretch's; over a keyframe interval, which may turn or deform the
    /// mesh, each corner of the triangle moves straight between the poses,
    /// and the point's velocity is the corners' velocities weighted by the
    /// point's place in the triangle (the sum of the hit's barycentric
    /// coordinates over the tetrahedron's vertices at each corner).
    pub fn surface_motion(&self, hit: &Hit) -> (DVec3, f64) {
        let surface = self.surface(hit);
        let record = &self.records[surface.object as usize];
        let stretch = record.stretch_at(hit.event.t);
        let tet = match hit.primitive {
            PrimitiveId::Tetrahedron(tet) if !stretch.translation => tet,
            _ => return (stretch.worldline.velocity(), stretch.clock.gamma()),
        };
        let velocity = self.corner_weighted_velocity(tet, &hit.bary);
        let gamma = if record.contracted {
            crate::spacetime::lorentz_factor(velocity.length_squared())
        } else {
            1.0
        };
        (velocity, gamma)
    }

    /// The velocity of the point with barycentric coordinates `bary` in
    /// tetrahedron `tet`, interpolated over its prism's corners. The
    /// prism's pieces are (a0 b0 c0 c1), (a0 b0 b1 c1), (a0 a1 b1 c1)
    /// ([`crate::geometry::split_between`]), so piece 0 holds the bottom
    /// corners and c1, piece 1 holds b1 and piece 2 a1.
    fn corner_weighted_velocity(&self, tet: u32, bary: &[f64; 4]) -> DVec3 {
        const CORNERS: [[usize; 4]; 3] = [[0, 1, 2, 2], [0, 1, 1, 2], [0, 0, 1, 2]];
        let c = &self.corners[(tet / 3) as usize];
        let (bottom, top) = (&c[..3], &c[3..]);
        let mut weights = [0.0; 3];
        for (j, &corner) in CORNERS[(tet % 3) as usize].iter().enumerate() {
            weights[corner] += bary[j];
        }
        (0..3)
            .map(|k| weights[k] * (top[k].x - bottom[k].x) / (top[k].t - bottom[k].t))
            .sum()
    }

    /// The number the debug log gives a primitive: tetrahedra by index,
    /// then the analytic spheres numbered after them.
    pub fn primitive_number(&self, primitive: PrimitiveId) -> u32 {
        match primitive {
            PrimitiveId::Tetrahedron(i) => i,
            PrimitiveId::Sphere(k) => self.tetrahedron_count() as u32 + k,
        }
    }

    /// The prism a tetrahedron belongs to.
    pub fn prism_of(&self, tet: u32) -> &Prism {
        &self.prisms[(tet / 3) as usize]
    }

    /// One tetrahedron's barycentric solve, with the reason for a miss.
    pub fn test(&self, ray: &Ray, tet: u32, range: (f64, f64)) -> Result<Hit, Miss> {
        let corners = &self.corners[(tet / 3) as usize];
        self.prepared[tet as usize].intersect(ray, (tet, corners, (tet % 3) as usize), range)
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
            let prism = &self.prisms[(tet / 3) as usize];
            trace.record(Step::Candidate {
                tet,
                object: self.records[prism.object as usize].name.clone(),
                triangle: prism.triangle,
                prism: tet / 3,
                piece: (tet % 3) as u8,
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
        for (k, sphere) in self.spheres.iter().enumerate() {
            let hi = best.map_or(range.1, |b| b.s);
            if let Some(h) = sphere.intersect(ray, k as u32, (range.0, hi)) {
                best = Some(nearer(best, h));
            }
        }
        best
    }

    fn closest_tet<T: Trace>(&self, ray: &Ray, range: (f64, f64), trace: &mut T) -> Option<Hit> {
        match self.traversal {
            Traversal::BruteForce => {
                let mut best: Option<Hit> = None;
                for i in 0..self.tetrahedron_count() as u32 {
                    let hi = best.map_or(range.1, |b| b.s);
                    if let Ok(h) = self.test_traced(ray, i, (range.0, hi), trace) {
                        best = Some(nearer(best, h));
                    }
                }
                best
            }
            Traversal::Bvh => {
                let (o, d) = (ray.origin.to_xyzt(), ray.direction.to_xyzt());
                self.accel.closest(o, d, range, |prism, r| {
                    let first = 3 * prism;
                    let mut best: Option<Hit> = None;
                    for tet in first..first + 3 {
                        let hi = best.map_or(r.1, |b| b.s);
                        if let Ok(h) = self.test_traced(ray, tet, (r.0, hi), trace) {
                            best = Some(nearer(best, h));
                        }
                    }
                    best
                })
            }
        }
    }
}
