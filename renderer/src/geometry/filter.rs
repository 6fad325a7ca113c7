//! A conservative f32 pre-test of eight comoving triangles at once, one
//! SIMD lane each (a leaf's, at the widest vector level the machine has:
//! one AVX register, or two SSE2 registers at x86-64's baseline), in front
//! of the exact test of [`intersect_prism`]. It rejects
//! a triangle only where the exact test certainly rejects it as outside:
//! two of the three edge functions of opposite signs, each farther from
//! zero than the bound on what f32 can have changed it by. Every other
//! triangle goes on to the exact test, so which triangles are hit, and
//! where, is decided by that test alone, to the bit.
//!
//! The bound. Let u = 2^-24 (f32's unit roundoff) and K bound |c| + |o| on
//! every axis, for the stretch's comoving corners c and the ray's comoving
//! origin o. The exact test sees the f64 sheared corner X = (c_x - o_x) -
//! s_x (c_z - o_z) (and Y alike), with |s_x|, |s_y| <= 1 (z is the axis the
//! direction is largest along). Here c, o and s are rounded to f32 (each
//! moved by at most u times itself) and every operation rounds again: the
//! f32 value X' is within 8.1 u K of X. Take E = 2^-20 K (16 u K). An edge
//! function e = X_C Y_B - Y_C X_B then moves by at most
//! E (m_C + m_B + 2E) + 2.01 u m_C m_B, with m = |X'| + |Y'| of each
//! corner, from its inputs and its three roundings; the bound used is
//! E (m_C + m_B + 2E) + 2^-22 m_C m_B (the slack covers the rounding of
//! the bound itself), plus 2^-120 for results in f32's subnormal range,
//! where rounding is absolute. A NaN anywhere fails both comparisons, so
//! its triangle goes on to the exact test. Rays and stretches with K of
//! 10^15 or more (or not finite) are not filtered: nothing overflows f32.

use super::triangle::ComovingRay;
use crate::scene::Mesh;
use crate::simd::{at_level, Simd8, SimdLevel};
use glam::DVec3;
use rayon::prelude::*;
use wide::f32x8;

/// Triangles a test covers.
pub(crate) const LANES: usize = 8;

/// Largest K (see the module's doc) for which rays are filtered.
const MAX_REACH: f64 = 1e15;

/// Relative bound of the rounding of an edge function's products and
/// difference (2.01 u needed).
const ROUNDING: f32 = 1.0 / (1u32 << 22) as f32;

/// Absolute bound for edge functions in f32's subnormal range.
const TINY: f32 = f32::MIN_POSITIVE * 64.0; // 2^-120

/// Comoving triangles' corners in f32 (rounded to nearest), row by row:
/// row 3 c + a holds coordinate a of corner c of every triangle, so that
/// the same coordinate of [`LANES`] consecutive triangles is one load.
#[derive(Clone, Debug, Default)]
pub(crate) struct CornerRows {
    /// Length of a row: the triangles, and [`LANES`] - 1 of padding so
    /// that a load at any triangle stays inside it.
    stride: usize,
    rows: Vec<f32>,
}

/// The largest magnitude of a coordinate of `triangles`: their part of K
/// (see the module's doc).
pub(crate) fn reach(triangles: impl IntoIterator<Item = [DVec3; 3]>) -> f64 {
    triangles
        .into_iter()
        .flatten()
        .fold(0.0f64, |m, c| m.max(c.abs().max_element()))
}

/// Meshes of at least this many triangles have their [`mesh_reach`] found
/// on every thread.
const PARALLEL_REACH: usize = 1 << 14;

/// [`reach`] of `mesh`'s triangles, a large mesh's on every thread: the
/// largest magnitude, the same whatever the order it is taken in.
pub(crate) fn mesh_reach(mesh: &Mesh) -> f64 {
    let count = mesh.triangles.len();
    if count < PARALLEL_REACH {
        return reach((0..count).map(|t| mesh.corners(t)));
    }
    let of = |t: usize| reach([mesh.corners(t)]);
    (0..count).into_par_iter().map(of).reduce(|| 0.0, f64::max)
}

/// Triangles a task of [`CornerRows::new`] writes into the rows.
const FILL_CHUNK: usize = 1 << 14;

impl CornerRows {
    /// The rows of triangles 0 to `count` - 1, triangle t being
    /// `triangle(t)`; none (and no filtering) when the rows would not be
    /// indexed by u32. Filled on every thread, each task a run of
    /// triangles in all nine rows.
    pub(crate) fn new(count: usize, triangle: impl Fn(usize) -> [DVec3; 3] + Sync) -> CornerRows {
        let stride = count + LANES - 1;
        if 9 * stride > u32::MAX as usize {
            return CornerRows::default();
        }
        let mut rows = vec![0.0f32; 9 * stride];
        let mut runs: Vec<_> = (rows.chunks_mut(stride))
            .map(|row| row[..count].chunks_mut(FILL_CHUNK))
            .collect();
        let tasks: Vec<Vec<&mut [f32]>> = (0..count.div_ceil(FILL_CHUNK))
            .map(|_| runs.iter_mut().filter_map(Iterator::next).collect())
            .collect();
        tasks.into_par_iter().enumerate().for_each(|(k, mut task)| {
            for t in 0..task[0].len() {
                let corners = triangle(k * FILL_CHUNK + t);
                for (c, corner) in corners.iter().enumerate() {
                    for (a, &v) in corner.to_array().iter().enumerate() {
                        task[3 * c + a][t] = v as f32;
                    }
                }
            }
        });
        CornerRows { stride, rows }
    }

    /// `ray` prepared for triangles whose comoving coordinates are at most
    /// `reach` in magnitude; `None` where it is not filtered (see the
    /// module's doc). (Inlined, so that the prepared ray is written where
    /// it is kept rather than copied there.)
    #[inline(always)]
    pub(crate) fn prepare(&self, ray: &ComovingRay, reach: f64) -> Option<FilterRay> {
        let (origin, axes, [sx, sy]) = ray.parts();
        let k = reach + origin.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        // A NaN fails the first test.
        if !(k < MAX_REACH && sx.abs() <= 1.0 && sy.abs() <= 1.0) || self.rows.is_empty() {
            return None;
        }
        // Rounded to nearest: at most u below, well within the slack.
        let e = (k * (1.0 / f64::from(1u32 << 20))) as f32;
        Some(FilterRay {
            rows: [
                self.rows_of(0, axes),
                self.rows_of(1, axes),
                self.rows_of(2, axes),
            ],
            origin: origin.map(|x| x as f32),
            shear: [sx as f32, sy as f32],
            e,
        })
    }

    /// Where corner `c`'s coordinates start, on `axes` in order.
    #[inline(always)]
    fn rows_of(&self, c: usize, [x, y, z]: [usize; 3]) -> [u32; 3] {
        let row = |a: usize| ((3 * c + a) * self.stride) as u32;
        [row(x), row(y), row(z)]
    }

    /// Of the [`LANES`] triangles from `first` on, those (bit i for
    /// triangle `first + i`) the exact test might not reject as outside,
    /// tested at the widest vector level `level` allows on this machine
    /// (every level lets the same triangles through). (Not inlined: its
    /// many vector registers would otherwise be saved around the exact
    /// tests that follow it.)
    #[inline(never)]
    pub(crate) fn candidates(&self, level: SimdLevel, ray: &FilterRay, first: u32) -> u32 {
        at_level!(level, |simd| self.candidates_at(simd, ray, first))
    }

    /// [`CornerRows::candidates`] at the vector level of `s`. (Helpers
    /// rather than closures, which are not always inlined into the level's
    /// code, where an intrinsic not inlined is a call.)
    #[inline(always)]
    fn candidates_at<S: Simd8>(&self, s: S, ray: &FilterRay, first: u32) -> u32 {
        let (a, b, c) = (
            self.sheared(s, ray, 0, first),
            self.sheared(s, ray, 1, first),
            self.sheared(s, ray, 2, first),
        );
        let (u, v, w) = (edge(s, ray, c, b), edge(s, ray, a, c), edge(s, ray, b, a));
        let negative = s.or(s.or(u.0, v.0), w.0);
        let positive = s.or(s.or(u.1, v.1), w.1);
        !s.bits(s.and(negative, positive)) & ((1 << LANES) - 1)
    }

    /// Corner `c` of the [`LANES`] triangles from `first` on, relative to
    /// the ray and sheared (the ray the third axis): X, Y and |X| + |Y|.
    #[inline(always)]
    fn sheared<S: Simd8>(&self, s: S, ray: &FilterRay, c: usize, first: u32) -> Lanes3<S> {
        let load = |row: u32| {
            // Both u32: the sum cannot overflow, one bound to check.
            let at = row as usize + first as usize;
            let lanes: [f32; LANES] = self.rows[at..at + LANES].try_into().expect("eight lanes");
            s.load(f32x8::from(lanes))
        };
        let [rx, ry, rz] = ray.rows[c];
        let (x, y, z) = (load(rx), load(ry), load(rz));
        let [ox, oy, oz] = ray.origin;
        let [sx, sy] = ray.shear;
        let z = s.sub(z, s.splat(oz));
        let x = s.sub(s.sub(x, s.splat(ox)), s.mul(s.splat(sx), z));
        let y = s.sub(s.sub(y, s.splat(oy)), s.mul(s.splat(sy), z));
        (x, y, s.add(s.abs(x), s.abs(y)))
    }
}

/// Per lane: a sheared corner's X and Y, and |X| + |Y|.
type Lanes3<S> = (<S as Simd8>::F, <S as Simd8>::F, <S as Simd8>::F);

/// The edge function p x q of sheared corners p and q, per lane: where it
/// is certainly negative, and where certainly positive (beyond the bound
/// of the module's doc).
#[inline(always)]
fn edge<S: Simd8>(s: S, ray: &FilterRay, p: Lanes3<S>, q: Lanes3<S>) -> (S::F, S::F) {
    let f = s.sub(s.mul(p.0, q.1), s.mul(p.1, q.0));
    let e = s.splat(ray.e);
    let reach = s.add(s.add(p.2, q.2), s.splat(2.0 * ray.e));
    let products = s.mul(s.mul(s.splat(ROUNDING), p.2), q.2);
    let bound = s.add(s.add(s.mul(e, reach), products), s.splat(TINY));
    (s.lt(f, s.sub(s.splat(0.0), bound)), s.lt(bound, f))
}

/// A comoving ray prepared for [`CornerRows::candidates`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct FilterRay {
    /// Where each corner's coordinates start, in the ray's axis order.
    rows: [[u32; 3]; 3],
    /// The comoving origin in f32, in the ray's axis order.
    origin: [f32; 3],
    /// The shear's first two components in f32.
    shear: [f32; 2],
    /// E (see the module's doc).
    e: f32,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::intersect_prism;
    use crate::geometry::Miss;
    use crate::rng::SplitMix64;
    use glam::DVec4;

    /// A triangle at a random place of scale `scale`, of size `size`.
    fn triangle(rng: &mut SplitMix64, scale: f64, size: f64) -> [DVec3; 3] {
        let mut at = || DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) - 0.5;
        let centre = at() * scale;
        [
            centre + at() * size,
            centre + at() * size,
            centre + at() * size,
        ]
    }

    /// A ray from a random origin (up to 1000 sizes away) aimed at a corner
    /// or an edge of `t` or near it, at a random lab time and light speed.
    fn aimed(rng: &mut SplitMix64, t: &[DVec3; 3], size: f64) -> (DVec4, DVec4) {
        let (i, j) = ((rng.next_u64() % 3) as usize, (rng.next_u64() % 3) as usize);
        let f = [0.0, 1.0, rng.next_f64()][(rng.next_u64() % 3) as usize];
        let nudge = [0.0, 1e-7, -1e-7, 1e-15][(rng.next_u64() % 4) as usize] * size;
        let target = t[i] + (t[j] - t[i]) * f + DVec3::splat(nudge);
        let from = target
            + (DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) - 0.5)
                * size
                * crate::math::powf(10.0, 3.0 * rng.next_f64());
        let d = (target - from).extend(-(target - from).length() * rng.next_f64());
        (from.extend(rng.next_f64()), d)
    }

    /// Counts triangles the filter rejects, and of those the ones the exact
    /// test does not reject as outside, with the bound's coefficient E
    /// scaled by `slack` (1 in use).
    fn rejections(slack: f32, seed: u64) -> (usize, usize) {
        let mut rng = SplitMix64::new(seed);
        let (mut rejected, mut wrong) = (0, 0);
        for scale in [0.05, 1.0, 1e5] {
            for size in [scale * 1e-6, scale * 1e-3, scale] {
                for _ in 0..2000 {
                    let tris: Vec<[DVec3; 3]> = (0..LANES)
                        .map(|_| triangle(&mut rng, scale, size))
                        .collect();
                    let rows = CornerRows::new(tris.len(), |t| tris[t]);
                    let reach = reach(tris.iter().copied());
                    let aim = (rng.next_u64() % LANES as u64) as usize;
                    let (o, d) = aimed(&mut rng, &tris[aim], size);
                    let v = DVec3::new(rng.next_f64() - 0.5, 0.0, 0.0) * 1.8;
                    let Some(ray) = ComovingRay::new(o, d, (0.0, DVec3::ZERO), v) else {
                        continue;
                    };
                    let mut filter = rows.prepare(&ray, reach).expect("filtered");
                    filter.e *= slack;
                    let mask = rows.candidates(SimdLevel::Baseline, &filter, 0);
                    for (i, t) in tris.iter().enumerate() {
                        if mask & (1 << i) == 0 {
                            rejected += 1;
                            let exact = intersect_prism(t, &ray, (-1e300, 1e300), (-1e300, 1e300));
                            if !matches!(exact, Err(Miss::Outside { .. })) {
                                wrong += 1;
                            }
                        }
                    }
                }
            }
        }
        (rejected, wrong)
    }

    /// Every triangle the filter rejects, the exact test rejects as
    /// outside, for rays aimed at corners and edges at every scale; and the
    /// filter does reject most triangles a ray misses.
    #[test]
    fn the_filter_rejects_only_what_the_exact_test_rejects() {
        let (rejected, wrong) = rejections(1.0, 7);
        assert_eq!(wrong, 0, "of {rejected} rejected");
        assert!(rejected > 40_000, "{rejected}");
    }

    /// Negative control: with no allowance for rounding the same rays find
    /// triangles rejected that the exact test does not reject.
    #[test]
    fn without_its_bound_the_filter_rejects_wrongly() {
        let (_, wrong) = rejections(0.0, 7);
        assert!(wrong > 0);
    }

    /// Every vector level this machine runs lets the same triangles
    /// through as the baseline, at every scale, leaves of fewer than
    /// [`LANES`] triangles included (their lanes past the rows' end read
    /// the padding); the control: the same rays with no allowance for
    /// rounding let other triangles through, so the masks compared are
    /// ones the arithmetic decides.
    #[test]
    fn every_level_lets_the_same_triangles_through() {
        let mut rng = SplitMix64::new(11);
        let (mut compared, mut decided) = (0, 0);
        for scale in [0.05, 1.0, 1e5] {
            for size in [scale * 1e-3, scale] {
                for _ in 0..500 {
                    let count = 1 + (rng.next_u64() % (2 * LANES as u64)) as usize;
                    let tris: Vec<[DVec3; 3]> = (0..count)
                        .map(|_| triangle(&mut rng, scale, size))
                        .collect();
                    let rows = CornerRows::new(count, |t| tris[t]);
                    let aim = (rng.next_u64() % count as u64) as usize;
                    let (o, d) = aimed(&mut rng, &tris[aim], size);
                    let Some(ray) = ComovingRay::new(o, d, (0.0, DVec3::ZERO), DVec3::ZERO) else {
                        continue;
                    };
                    let filter = rows.prepare(&ray, reach(tris.iter().copied()));
                    let filter = filter.expect("filtered");
                    let loose = FilterRay { e: 0.0, ..filter };
                    for first in 0..count as u32 {
                        let mask = |level, f: &FilterRay| rows.candidates(level, f, first);
                        let baseline = mask(SimdLevel::Baseline, &filter);
                        for level in SimdLevel::supported() {
                            assert_eq!(mask(level, &filter), baseline, "{level}");
                            compared += 1;
                        }
                        decided += usize::from(mask(SimdLevel::Baseline, &loose) != baseline);
                    }
                }
            }
        }
        assert!(compared > 10_000, "{compared}");
        assert!(decided > 0, "the control");
    }

    /// Rows filled on two threads hold, at row 3 c + a and column t,
    /// coordinate a of corner c of triangle t rounded to f32, as rows
    /// filled on one thread do; the control, one triangle moved, changes
    /// them.
    #[test]
    fn rows_hold_each_corner_whatever_the_threads() {
        let mut rng = SplitMix64::new(3);
        let tris: Vec<[DVec3; 3]> = (0..3 * FILL_CHUNK + 5)
            .map(|_| triangle(&mut rng, 1.0, 0.1))
            .collect();
        let on = |threads: usize, tris: &[[DVec3; 3]]| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build();
            pool.unwrap()
                .install(|| CornerRows::new(tris.len(), |t| tris[t]))
        };
        let (one, two) = (on(1, &tris), on(2, &tris));
        assert_eq!(one.rows, two.rows);
        for (t, corners) in tris.iter().enumerate() {
            for (c, corner) in corners.iter().enumerate() {
                for a in 0..3 {
                    assert_eq!(two.rows[(3 * c + a) * two.stride + t], corner[a] as f32);
                }
            }
        }
        let mut moved = tris.clone();
        moved[2 * FILL_CHUNK + 1][2].y += 1.0;
        assert_ne!(on(2, &moved).rows, two.rows);
    }

    /// A ray or stretch too far out for f32 is not filtered.
    #[test]
    fn far_rays_are_not_filtered() {
        let rows = CornerRows::new(1, |_| [DVec3::X, DVec3::Y, DVec3::Z]);
        let ray = |o: DVec4| {
            ComovingRay::new(
                o,
                DVec4::new(0.0, 0.0, -1.0, -1.0),
                (0.0, DVec3::ZERO),
                DVec3::ZERO,
            )
            .unwrap()
        };
        assert!(rows
            .prepare(&ray(DVec4::new(0.0, 0.0, 5.0, 0.0)), 1.0)
            .is_some());
        assert!(rows
            .prepare(&ray(DVec4::new(0.0, 0.0, 2e15, 0.0)), 1.0)
            .is_none());
        assert!(rows
            .prepare(&ray(DVec4::new(0.0, 0.0, 5.0, 0.0)), f64::NAN)
            .is_none());
    }

    /// A large mesh's reach, found on both threads, is the one found
    /// triangle by triangle on one, and on one thread the same; the
    /// control: one corner moved farther out than any changes it. A
    /// vertex no triangle uses does not count.
    #[test]
    fn a_large_meshs_reach_is_that_of_its_triangles_in_order() {
        let mut rng = SplitMix64::new(41);
        let n = 3 * PARALLEL_REACH;
        let mut vertices: Vec<DVec3> = (0..n + 2)
            .map(|_| (DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) - 0.5) * 40.0)
            .collect();
        vertices[n + 1] = DVec3::splat(-1e9); // used by no triangle
        let triangles = (0..n as u32)
            .map(|i| [i, i + 1, (i * 7919) % n as u32])
            .collect();
        let mut mesh = Mesh {
            vertices,
            triangles,
            materials: Vec::new(),
        };
        let in_order = |m: &Mesh| reach((0..m.triangles.len()).map(|t| m.corners(t)));
        let on = |threads: usize, m: &Mesh| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| mesh_reach(m))
        };
        let expected = in_order(&mesh);
        assert!(expected > 19.0 && expected <= 20.0, "{expected}");
        assert_eq!(on(2, &mesh).to_bits(), expected.to_bits());
        assert_eq!(on(1, &mesh).to_bits(), expected.to_bits());
        mesh.vertices[n / 2].y = -75.5;
        assert_eq!(on(2, &mesh), 75.5);
    }
}
