//! The static 4D database (paper 3, items 1-2): every object temporally
//! extruded once, and never modified between frames (paper 3, item 6).
//! Built in `build`; searched by rays in `query`.

mod build;
mod comoving;
mod object;
mod query;
mod worldlines;

pub(crate) use object::{ObjectRecord, Stretch};

use comoving::ComovingMeshes;

use crate::accel::{StretchPrisms, TwoLevel};
use crate::geometry::{
    corner_order, corners_between, piece, Barycentric, CornerRows, Hit, PreparedTet, PrimitiveId,
    Prism, PrismCorners, Sphere, Tetrahedron,
};
use crate::simd::SimdLevel;
use crate::spacetime::{Event, FourVector};
use glam::DVec3;
use std::sync::OnceLock;

/// How rays find candidate prisms and tetrahedra. Both give identical hits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Traversal {
    /// Every prism and tetrahedron for every ray.
    BruteForce,
    /// A bounding volume hierarchy over their 4D bounds.
    Bvh,
}

/// How [`Database::closest_hits`] searches its rays. Every choice gives
/// the same hits, to the bit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Packing {
    /// One ray at a time.
    Single,
    /// Four rays at a time: each node of a hierarchy is loaded once for the
    /// rays that enter it.
    Packets,
    /// Packets where a ray's work lies mostly below the top level, in the
    /// hierarchies of the stretches: when the top level's time slices hold
    /// on average at least [`Database::PACKED_FROM`] prisms each (a large
    /// mesh), or the database holds one stretch of at least as many (its
    /// slices are passed by); one at a time otherwise (the default).
    Auto,
}

/// The prisms of one stretch of a meshed object's path, numbered
/// consecutively (one per triangle of the mesh, in mesh order).
struct Run {
    /// Index of the object in [`Database::objects`].
    object: u32,
    /// The stretch as the acceleration structure sees it.
    stretch: StretchPrisms,
    /// The lab-frame extrusion of the stretch's reference point.
    extrusion: FourVector,
    /// Index of the run's first prism in [`Database::comoving`] (a
    /// translation) or [`Database::keyframed`] (a keyframe interval).
    slot: usize,
    /// Where a translation's vertices start in [`Database::comoving`].
    vertices: usize,
    /// The largest magnitude of a comoving coordinate of a translation's
    /// triangles (0 for a keyframe interval).
    reach: f64,
}

/// The prisms of keyframe intervals, which may turn or deform their
/// triangles: each tested as the paper's three tetrahedra.
#[derive(Default)]
struct Keyframed {
    prisms: Vec<Prism>,
    /// Each prism's corners; its tetrahedra are read off them.
    corners: Vec<PrismCorners>,
    /// Each tetrahedron's prepared solve, three per prism in prism order.
    prepared: Vec<PreparedTet>,
}

/// The static 4D database.
pub struct Database {
    records: Vec<ObjectRecord>,
    /// Every meshed object's prisms, stretch by stretch, in prism order.
    runs: Vec<Run>,
    /// The triangles of the prisms of translations (uniform motion), at rest
    /// in their stretch's comoving coordinates x' = x - v (t - t0) - x0: all
    /// such a prism needs, since its events are the triangle carried along
    /// the stretch's worldline.
    comoving: ComovingMeshes,
    /// Where each translation prism's triangle is in [`Database::comoving`]:
    /// prism k of a run at `slot` at `slot + stored_at[slot + k]`, its
    /// position in its stretch's hierarchy (a leaf's side by side).
    stored_at: Vec<u32>,
    /// The same triangles in f32, for the filter in front of their exact
    /// test.
    rows: CornerRows,
    keyframed: Keyframed,
    /// The two-level hierarchy over the prisms.
    accel: TwoLevel,
    /// Analytic spheres.
    spheres: Vec<Sphere>,
    traversal: Traversal,
    packing: Packing,
    simd: SimdLevel,
    /// The lab-space box of all geometry ever, found when first asked for.
    reach: OnceLock<(DVec3, DVec3)>,
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
    /// Chooses how rays find candidate prisms and tetrahedra.
    pub fn set_traversal(&mut self, traversal: Traversal) {
        self.traversal = traversal;
    }

    /// How rays find candidate prisms and tetrahedra.
    pub fn traversal(&self) -> Traversal {
        self.traversal
    }

    /// Prisms per time slice of the top level from which [`Packing::Auto`]
    /// searches in packets. Below it the packets' own bookkeeping and the
    /// top level, where neighbouring rays part soonest, cost more than the
    /// shared node loads save. Measured with `vstf bench`: in packets, the
    /// 28 moving boxes (1792 slices; 192 prisms a slice at the most) render
    /// 1.4-1.7x slower, the flange scene about 10% slower; the tori of 10k
    /// triangles trace 8% faster at rest (10080 a slice) and 7% faster at
    /// 0.9c (630 a slice), the larger tori 10-15% faster. A lone stretch
    /// is searched past its slices, so its prisms count whole: 600 of the
    /// tori's triangles at 0.9c over 64 slices trace 25% faster in packets.
    pub const PACKED_FROM: usize = 512;

    /// Chooses how [`Database::closest_hits`] searches its rays.
    pub fn set_packing(&mut self, packing: Packing) {
        self.packing = packing;
    }

    /// Limits the vector level of the hierarchies' node tests: the widest
    /// the machine has up to `level` (the default, [`SimdLevel::X86V3`],
    /// takes AVX2 where there is one). Every level finds the same hits, to
    /// the bit.
    pub fn set_simd(&mut self, level: SimdLevel) {
        self.simd = level;
    }

    /// How many time slices the top level of the hierarchy holds: each
    /// stretch of an object's path cut so that a slice sweeps about its
    /// own size (one for an object at rest).
    pub fn time_slice_count(&self) -> usize {
        self.accel.slice_count()
    }

    /// Whether [`Database::closest_hits`] searches in packets.
    pub fn packs(&self) -> bool {
        let slices = self.accel.searched_slice_count().max(1);
        self.traversal == Traversal::Bvh
            && match self.packing {
                Packing::Single => false,
                Packing::Packets => true,
                Packing::Auto => self.prism_count() >= Self::PACKED_FROM * slices,
            }
    }

    /// The objects as inserted, in scene order.
    pub fn objects(&self) -> &[ObjectRecord] {
        &self.records
    }

    /// The greatest distance from `centre` of any point of any object at
    /// any time (an upper bound; 0 for an empty database, infinite for an
    /// object that lives for ever).
    pub fn reach_from(&self, centre: DVec3) -> f64 {
        let (lo, hi) = self.spatial_bounds();
        if lo.cmpgt(hi).any() {
            return 0.0;
        }
        let far = (centre - lo).abs().max((hi - centre).abs());
        let d = far.length();
        if d.is_nan() {
            f64::INFINITY
        } else {
            d
        }
    }

    /// The least and greatest corners of a box holding every point of
    /// every object at any time (the least above the greatest for an empty
    /// database, infinite along the motion of an object that lives for
    /// ever).
    pub fn spatial_bounds(&self) -> (DVec3, DVec3) {
        *self.reach.get_or_init(|| {
            let (mut lo, mut hi) = self.accel.spatial_box();
            for s in &self.spheres {
                for t in [s.origin.t, s.end] {
                    let c = if s.velocity == DVec3::ZERO {
                        s.origin.x
                    } else {
                        s.origin.x + s.velocity * (t - s.origin.t)
                    };
                    lo = lo.min(c - DVec3::splat(s.radius));
                    hi = hi.max(c + DVec3::splat(s.radius));
                }
            }
            (lo, hi)
        })
    }

    /// How many prisms (extruded triangles) there are.
    pub fn prism_count(&self) -> usize {
        self.comoving.len() + self.keyframed.prisms.len()
    }

    /// The run prism `p` belongs to, and its place in the run.
    fn run_of(&self, p: u32) -> (&Run, usize) {
        let k = self
            .runs
            .partition_point(|r| r.stretch.prisms.end <= p as usize);
        let run = &self.runs[k];
        (run, p as usize - run.stretch.prisms.start)
    }

    /// Where prism `k` of translation `run` keeps its triangle: its
    /// position in the run's part of [`Database::comoving`].
    fn stored(&self, run: &Run, k: usize) -> u32 {
        self.stored_at[run.slot + k]
    }

    /// The comoving triangle of prism `k` of translation `run`.
    fn triangle(&self, run: &Run, k: usize) -> [DVec3; 3] {
        self.comoving
            .triangle(run.vertices, run.slot + self.stored(run, k) as usize)
    }

    /// Prism `p`, by index in `0..prism_count()`: its object, triangle,
    /// normals and lab times.
    pub fn prism(&self, p: u32) -> Prism {
        let (run, k) = self.run_of(p);
        if !run.stretch.translation {
            return self.keyframed.prisms[run.slot + k];
        }
        let normal = unit_normal(&self.triangle(run, k));
        Prism {
            object: run.object,
            triangle: k as u32,
            normal,
            end_normal: normal,
            span: run.stretch.span,
        }
    }

    /// Prism `p`'s six corners in the paper's cut: the corners of its
    /// triangle at its start in the cut's order, then the same corners, in
    /// the same order, at its end.
    pub fn prism_corners(&self, p: u32) -> PrismCorners {
        let (run, k) = self.run_of(p);
        if !run.stretch.translation {
            return self.keyframed.corners[run.slot + k];
        }
        let c = self.triangle(run, k);
        let start = run.stretch.origin;
        let bottom = c.map(|x| Event::new(start.t, start.x + x));
        let top = bottom.map(|e| e + run.extrusion);
        corners_between(bottom, top, corner_order(c))
    }

    /// The corners of prism `p`'s triangle at lab time `t`, in the order of
    /// a [`Barycentric::Triangle`] on it: for a translation, its comoving
    /// corners carried along the stretch's worldline; for a keyframe
    /// interval, each corner moved straight between the poses.
    pub fn triangle_at(&self, p: u32, t: f64) -> [Event; 3] {
        let (run, k) = self.run_of(p);
        let g = &run.stretch;
        if g.translation {
            let at = g.origin.x + g.velocity * (t - g.origin.t);
            return self.triangle(run, k).map(|x| Event::new(t, at + x));
        }
        let c = &self.keyframed.corners[run.slot + k];
        let f = (t - g.span.0) / (g.span.1 - g.span.0);
        [0, 1, 2].map(|i| Event::new(t, c[i].x.lerp(c[i + 3].x, f)))
    }

    /// How many tetrahedra the paper's cut gives: three per prism.
    pub fn tetrahedron_count(&self) -> usize {
        3 * self.prism_count()
    }

    /// Tetrahedron `i` of the paper's cut: piece `i % 3` of prism `i / 3`.
    /// Only keyframe intervals are tested as tetrahedra; a translation's
    /// three tile the prism it tests whole.
    pub fn tetrahedron(&self, i: u32) -> Tetrahedron {
        let (prism, k) = (i / 3, (i % 3) as usize);
        Tetrahedron {
            vertices: piece(&self.prism_corners(prism), k),
            prism,
            piece: k as u8,
        }
    }

    /// Every tetrahedron of the paper's cut, three per prism in prism order.
    pub fn tetrahedra(&self) -> impl ExactSizeIterator<Item = Tetrahedron> + '_ {
        (0..self.tetrahedron_count() as u32).map(|i| self.tetrahedron(i))
    }

    /// The surface a hit lies on: a triangle's prism, or an analytic sphere.
    pub fn surface(&self, hit: &Hit) -> Surface {
        match hit.primitive.prism() {
            Some(p) if hit.stored != Hit::NOT_STORED => {
                // A translated prism's normal, from its triangle where the
                // exact test read it: [`Database::prism`]'s.
                let (run, k) = self.run_of(p);
                let c = self.comoving.triangle(run.vertices, hit.stored as usize);
                Surface {
                    object: run.object,
                    normal: unit_normal(&c),
                    triangle: k as u32,
                }
            }
            Some(p) => {
                let prism = self.prism(p);
                Surface {
                    object: prism.object,
                    normal: prism.normal_at(hit.event.t),
                    triangle: prism.triangle,
                }
            }
            None => {
                let PrimitiveId::Sphere(k) = hit.primitive else {
                    unreachable!("every other primitive is of a prism")
                };
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
        self.motion_on(hit, &self.surface(hit))
    }

    /// [`Database::surface_motion`] at `hit`, whose [`Surface`] is known.
    pub(crate) fn motion_on(&self, hit: &Hit, surface: &Surface) -> (DVec3, f64) {
        let record = &self.records[surface.object as usize];
        let stretch = record.stretch_at(hit.event.t);
        let (PrimitiveId::Tetrahedron(tet), Barycentric::Tetrahedron(bary)) =
            (hit.primitive, hit.bary)
        else {
            return (stretch.worldline.velocity(), stretch.clock.gamma());
        };
        let velocity = self.corner_weighted_velocity(tet, &bary);
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
    /// ([`crate::geometry::piece`]), so piece 0 holds the bottom
    /// corners and c1, piece 1 holds b1 and piece 2 a1.
    fn corner_weighted_velocity(&self, tet: u32, bary: &[f64; 4]) -> DVec3 {
        const CORNERS: [[usize; 4]; 3] = [[0, 1, 2, 2], [0, 1, 1, 2], [0, 0, 1, 2]];
        let c = self.prism_corners(tet / 3);
        let (bottom, top) = (&c[..3], &c[3..]);
        let mut weights = [0.0; 3];
        for (j, &corner) in CORNERS[(tet % 3) as usize].iter().enumerate() {
            weights[corner] += bary[j];
        }
        (0..3)
            .map(|k| weights[k] * (top[k].x - bottom[k].x) / (top[k].t - bottom[k].t))
            .sum()
    }
}

/// The unit lab normal of a translated prism, from its comoving
/// triangle's corners `c` in order (right-handed): a translation moves the
/// triangle without turning or deforming it, so its comoving corners'
/// normal is its normal at every lab time.
fn unit_normal(c: &[DVec3; 3]) -> DVec3 {
    (c[1] - c[0]).cross(c[2] - c[0]).normalize()
}

#[cfg(test)]
mod tests;
