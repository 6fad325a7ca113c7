//! The ray queries: the closest hit of a ray, or of a packet of
//! neighbouring rays, over every prism or through the two-level hierarchy,
//! and one ray's tests against the prisms of the leaves it reaches.

use super::{Database, Run, Traversal};
use crate::accel::{Lanes, PACKET};
use crate::geometry::{
    intersect_prism, nearer, Barycentric, ComovingRay, FilterRay, Hit, Miss, PrimitiveId, LANES,
};
use crate::spacetime::{Event, Ray};
use crate::trace::{NoTrace, Outcome, Step, Trace};
use glam::DVec4;

/// Whether a search along `ray` within `range` means anything: its origin
/// and direction finite and its range's end not NaN. Any other ray meets
/// nothing (given a direction that is not a number, the hierarchy's box
/// tests would let it into every box).
fn searchable(ray: &Ray, range: (f64, f64)) -> bool {
    let (o, d) = (ray.origin, ray.direction);
    o.x.is_finite() && o.t.is_finite() && d.x.is_finite() && d.t.is_finite() && !range.1.is_nan()
}

impl Database {
    /// The hit with the smallest ray parameter in `range`: on a light-cone
    /// ray, the most recent event (paper 3.2). A ray runs forward from its
    /// origin: a range starting below zero is searched from zero.
    pub fn closest_hit(&self, ray: &Ray, range: (f64, f64)) -> Option<Hit> {
        self.closest_hit_traced(ray, range, &mut NoTrace)
    }

    /// [`Database::closest_hit`], recording every prism and tetrahedron
    /// tested.
    pub fn closest_hit_traced<T: Trace>(
        &self,
        ray: &Ray,
        range: (f64, f64),
        trace: &mut T,
    ) -> Option<Hit> {
        if !searchable(ray, range) {
            return None;
        }
        let range = (range.0.max(0.0), range.1);
        let best = self.closest_in_runs(ray, range, trace);
        self.nearer_on_spheres(ray, range, best)
    }

    /// [`Database::closest_hit`] of each of `rays` within `range`, into
    /// `hits`: the same hits to the bit, found by searching the rays four
    /// at a time as [`Packing`](super::Packing) says, which saves work when
    /// neighbours in `rays` are coherent (as the primary rays of
    /// neighbouring pixels are) and the database is a large mesh.
    pub fn closest_hits(&self, rays: &[Ray], range: (f64, f64), hits: &mut [Option<Hit>]) {
        assert_eq!(rays.len(), hits.len(), "one hit for each ray");
        if !self.packs() {
            for (hit, ray) in hits.iter_mut().zip(rays) {
                *hit = self.closest_hit(ray, range);
            }
            return;
        }
        let range = (range.0.max(0.0), range.1);
        for (rays, hits) in rays.chunks(PACKET).zip(hits.chunks_mut(PACKET)) {
            if !rays.iter().all(|ray| searchable(ray, range)) {
                for (hit, ray) in hits.iter_mut().zip(rays) {
                    *hit = self.closest_hit(ray, range);
                }
                continue;
            }
            let found = match rays {
                [ray] => {
                    let mut one = [None; PACKET];
                    one[0] = self.closest_in_runs(ray, range, &mut NoTrace);
                    one
                }
                _ => self.closest_in_runs_packet(rays, range),
            };
            for ((hit, ray), best) in hits.iter_mut().zip(rays).zip(found) {
                *hit = self.nearer_on_spheres(ray, range, best);
            }
        }
    }

    /// The nearer of `best` and the closest hit on the analytic spheres
    /// (few: the same for every traversal).
    fn nearer_on_spheres(
        &self,
        ray: &Ray,
        range: (f64, f64),
        mut best: Option<Hit>,
    ) -> Option<Hit> {
        for (k, sphere) in self.spheres.iter().enumerate() {
            let hi = best.map_or(range.1, |b| b.s);
            if let Some(h) = sphere.intersect(ray, k as u32, (range.0, hi)) {
                best = Some(nearer(best, h));
            }
        }
        best
    }

    /// [`Database::closest_in_runs`] of a packet of at most [`PACKET`]
    /// rays, searched together.
    fn closest_in_runs_packet(&self, rays: &[Ray], range: (f64, f64)) -> [Option<Hit>; PACKET] {
        // Lanes past the rays repeat the last, and are not searched.
        let ray = |i: usize| &rays[i.min(rays.len() - 1)];
        let mut traces = [NoTrace, NoTrace, NoTrace, NoTrace];
        let [t0, t1, t2, t3] = traces.each_mut();
        // (Literals rather than `from_fn`, which is not always inlined.)
        let mut testers: [Tester<NoTrace>; PACKET] = [
            Tester::new(self, ray(0), t0),
            Tester::new(self, ray(1), t1),
            Tester::new(self, ray(2), t2),
            Tester::new(self, ray(3), t3),
        ];
        let mut lab = [(DVec4::ZERO, DVec4::ZERO); PACKET];
        for (l, t) in lab.iter_mut().zip(&testers) {
            *l = (t.o, t.d);
        }
        self.accel.closest_packet(
            self.simd,
            &lab,
            Lanes::first(rays.len()),
            range,
            |i, run, first, items, r| testers[i].leaf(run, first, items, r),
        )
    }

    fn closest_in_runs<T: Trace>(
        &self,
        ray: &Ray,
        range: (f64, f64),
        trace: &mut T,
    ) -> Option<Hit> {
        let mut tester = Tester::new(self, ray, trace);
        match self.traversal {
            Traversal::BruteForce => {
                let mut best: Option<Hit> = None;
                for (k, run) in self.runs.iter().enumerate() {
                    for p in run.stretch.prisms.clone() {
                        let hi = best.map_or(range.1, |b| b.s);
                        let local = p - run.stretch.prisms.start;
                        // Keyframe intervals keep mesh order: no position.
                        let j = if run.stretch.translation {
                            self.stored(run, local)
                        } else {
                            0
                        };
                        if let Some(h) = tester.prism(k as u32, p as u32, j, (range.0, hi)) {
                            best = Some(nearer(best, h));
                        }
                    }
                }
                best
            }
            Traversal::Bvh => {
                let (o, d) = (tester.o, tester.d);
                self.accel
                    .closest(self.simd, o, d, range, |run, first, items, r| {
                        tester.leaf(run, first, items, r)
                    })
            }
        }
    }
}

/// One ray's tests against the database's prisms, with the ray in the
/// comoving coordinates of the last translation tested kept for the next.
struct Tester<'a, T> {
    db: &'a Database,
    ray: &'a Ray,
    o: DVec4,
    d: DVec4,
    /// The stretch the comoving ray is of ([`NO_STRETCH`] before the
    /// first), the ray (none when it is at rest there) and its f32 filter
    /// (none where it is not filtered).
    stretch: u32,
    comoving: Option<ComovingRay>,
    filter: Option<FilterRay>,
    trace: &'a mut T,
}

/// The hit on prism `p`, whose triangle is kept at position `stored` of
/// [`Database::comoving`], of the ray `o + s d` where the exact test found
/// it: at ray parameter s, with barycentric coordinates `bary`.
#[inline(always)]
fn hit(o: DVec4, d: DVec4, p: u32, stored: usize, (s, bary): (f64, [f64; 3])) -> Hit {
    Hit {
        s,
        event: Event::from_xyzt(o + d * s),
        primitive: PrimitiveId::Prism(p),
        bary: Barycentric::Triangle(bary.map(|x| x.clamp(0.0, 1.0))),
        stored: stored as u32,
    }
}

/// The closest hit within `range` of the lab ray `o + s d` on the prisms
/// `items` of translation `run`, stored side by side from position `first`
/// of the run: filtered up to eight at a time, and those the filter lets through
/// tested exactly (the ray in the run's comoving form), in order.
#[inline(always)]
fn filtered_leaf(
    (db, run): (&Database, &Run),
    (o, d): (DVec4, DVec4),
    (ray, filter): (&ComovingRay, &FilterRay),
    first: u32,
    items: &[u32],
    range: (f64, f64),
) -> Option<Hit> {
    let (p0, at) = (run.stretch.prisms.start as u32, run.slot + first as usize);
    db.comoving.read_ahead(at, at + items.len());
    let mut best: Option<Hit> = None;
    let mut chunk = 0;
    while chunk < items.len() {
        let count = (items.len() - chunk).min(LANES);
        let mut candidates = db
            .rows
            .candidates(db.simd, filter, (at + chunk) as u32, count);
        while candidates != 0 {
            let i = chunk + candidates.trailing_zeros() as usize;
            candidates &= candidates - 1;
            let hi = best.map_or(range.1, |b| b.s);
            let corners = &db.comoving.triangle(run.vertices, at + i);
            let exact = intersect_prism(corners, ray, run.stretch.span, (range.0, hi));
            if let Ok(found) = exact {
                best = Some(nearer(best, hit(o, d, p0 + items[i], at + i, found)));
            }
        }
        chunk += LANES;
    }
    best
}

/// [`Tester::stretch`] before any stretch is prepared.
const NO_STRETCH: u32 = u32::MAX;

impl<'a, T: Trace> Tester<'a, T> {
    fn new(db: &'a Database, ray: &'a Ray, trace: &'a mut T) -> Tester<'a, T> {
        Tester {
            db,
            ray,
            o: ray.origin.to_xyzt(),
            d: ray.direction.to_xyzt(),
            stretch: NO_STRETCH,
            comoving: None,
            filter: None,
            trace,
        }
    }

    /// The closest hit within `range` on the prisms `items` (counted from
    /// the run's first) of a leaf of run `k`'s hierarchy, which are stored
    /// side by side from position `first` of the run. A translation's are
    /// filtered up to eight at a time (in f32, conservatively) and only those the
    /// filter lets through are tested exactly, in order; when recording,
    /// every one is tested.
    #[inline(never)]
    fn leaf(&mut self, k: u32, first: u32, items: &[u32], range: (f64, f64)) -> Option<Hit> {
        let run = &self.db.runs[k as usize];
        if T::ENABLED || !run.stretch.translation {
            return self.each(k, first, items, range);
        }
        self.prepare(k);
        match (&self.comoving, &self.filter) {
            (Some(ray), Some(filter)) => filtered_leaf(
                (self.db, run),
                (self.o, self.d),
                (ray, filter),
                first,
                items,
                range,
            ),
            (Some(_), None) => self.each(k, first, items, range),
            // At rest in the comoving frame: parallel to every triangle.
            (None, _) => None,
        }
    }

    /// The closest hit within `range` on the prisms `items` of run `k`
    /// stored side by side from position `first`, each tested exactly.
    #[inline(never)]
    fn each(&mut self, k: u32, first: u32, items: &[u32], range: (f64, f64)) -> Option<Hit> {
        let p0 = self.db.runs[k as usize].stretch.prisms.start as u32;
        let mut best: Option<Hit> = None;
        for (i, &item) in items.iter().enumerate() {
            let hi = best.map_or(range.1, |b| b.s);
            if let Some(h) = self.prism(k, p0 + item, first + i as u32, (range.0, hi)) {
                best = Some(nearer(best, h));
            }
        }
        best
    }

    /// Prepares the ray in the comoving coordinates of translation run `k`
    /// and its filter, unless they are the last prepared.
    #[inline(always)]
    fn prepare(&mut self, k: u32) {
        if self.stretch != k {
            self.prepare_new(k);
        }
    }

    /// [`Tester::prepare`] for a stretch other than the last prepared.
    #[inline(never)]
    fn prepare_new(&mut self, k: u32) {
        let run = &self.db.runs[k as usize];
        let g = &run.stretch;
        self.stretch = k;
        self.comoving = ComovingRay::new(self.o, self.d, (g.origin.t, g.origin.x), g.velocity);
        self.filter = (self.comoving.as_ref()).and_then(|ray| self.db.rows.prepare(ray, run.reach));
    }

    /// The closest hit on prism `p` of run `k` within `range`: a
    /// translation's whole (its triangle stored at position `j` of the run),
    /// or a keyframe interval's three tetrahedra.
    #[inline(always)]
    fn prism(&mut self, k: u32, p: u32, j: u32, range: (f64, f64)) -> Option<Hit> {
        let run = &self.db.runs[k as usize];
        if !run.stretch.translation {
            return self.keyframe_prism(run, p, range);
        }
        self.prepare(k);
        let stored = run.slot + j as usize;
        let corners = &self.db.comoving.triangle(run.vertices, stored);
        let result = match &self.comoving {
            None => Err(Miss::Parallel),
            Some(c) => intersect_prism(corners, c, run.stretch.span, range)
                .map(|found| hit(self.o, self.d, p, stored, found)),
        };
        self.record(run, PrimitiveId::Prism(p), &result);
        result.ok()
    }

    /// The closest hit on keyframe prism `p` of `run` within `range`: the
    /// nearest of its three tetrahedra's.
    #[inline(never)]
    fn keyframe_prism(&mut self, run: &Run, p: u32, range: (f64, f64)) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        for tet in 3 * p..3 * p + 3 {
            let hi = best.map_or(range.1, |b| b.s);
            if let Ok(h) = self.tetrahedron(run, tet, (range.0, hi)) {
                best = Some(nearer(best, h));
            }
        }
        best
    }

    /// The barycentric solve of keyframe tetrahedron `tet` of `run`.
    fn tetrahedron(&mut self, run: &Run, tet: u32, range: (f64, f64)) -> Result<Hit, Miss> {
        let slot = run.slot + (tet / 3) as usize - run.stretch.prisms.start;
        let kf = &self.db.keyframed;
        let result = kf.prepared[3 * slot + (tet % 3) as usize].intersect(
            self.ray,
            (tet, &kf.corners[slot], (tet % 3) as usize),
            range,
        );
        self.record(run, PrimitiveId::Tetrahedron(tet), &result);
        result
    }

    fn record(&mut self, run: &Run, primitive: PrimitiveId, result: &Result<Hit, Miss>) {
        if T::ENABLED {
            let prism = primitive.prism().expect("a prism's");
            self.trace.record(Step::Candidate {
                primitive,
                object: self.db.records[run.object as usize].name.clone(),
                triangle: prism - run.stretch.prisms.start as u32,
                prism,
                outcome: Outcome::from(result),
            });
        }
    }
}
