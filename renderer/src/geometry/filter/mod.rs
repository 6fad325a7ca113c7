//! A conservative f32 pre-test of a leaf's comoving triangles at once, one
//! SIMD lane each (`lanes`: a leaf of up to four in one SSE2 register, a
//! large stretch's leaf of five to eight in eight lanes at the widest
//! vector level the machine has, one AVX register where it has AVX2), in
//! front of the exact test of [`intersect_prism`]. It rejects
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

mod lanes;

use super::triangle::ComovingRay;
use crate::scene::Mesh;
use crate::simd::{at_level, SimdLevel};
use glam::DVec3;
use lanes::{Eight, Four, Lanes};
use rayon::prelude::*;

/// The most triangles a test covers.
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

    /// Of the `count` triangles from `first` on (at most [`LANES`]),
    /// those (bit i for triangle `first + i`) the exact test might not
    /// reject as outside: more than four in eight lanes at the widest
    /// vector level `level` allows on this machine, four or fewer in four
    /// SSE2 lanes (entering the wider level costs more than it saves on
    /// them). Every width and level lets the same triangles through. (Not
    /// inlined: its many vector registers would otherwise be saved around
    /// the exact tests that follow it.)
    #[inline(never)]
    pub(crate) fn candidates(
        &self,
        level: SimdLevel,
        ray: &FilterRay,
        first: u32,
        count: usize,
    ) -> u32 {
        let found = if count <= Four::WIDTH {
            self.pass(Four, ray, first)
        } else {
            at_level!(level, |simd| self.pass(Eight(simd), ray, first))
        };
        found & ((1 << count.min(LANES)) - 1)
    }

    /// [`CornerRows::candidates`] of the `L::WIDTH` triangles from
    /// `first` on, in the lanes of `s`. (Helpers rather than closures,
    /// which are not always inlined into a vector level's code, where an
    /// intrinsic not inlined is a call.)
    #[inline(always)]
    fn pass<L: Lanes>(&self, s: L, ray: &FilterRay, first: u32) -> u32 {
        let (a, b, c) = (
            self.sheared(s, ray, 0, first),
            self.sheared(s, ray, 1, first),
            self.sheared(s, ray, 2, first),
        );
        let (u, v, w) = (edge(s, ray, c, b), edge(s, ray, a, c), edge(s, ray, b, a));
        let negative = s.or(s.or(u.0, v.0), w.0);
        let positive = s.or(s.or(u.1, v.1), w.1);
        !s.bits(s.and(negative, positive)) & ((1 << L::WIDTH) - 1)
    }

    /// Corner `c` of the `L::WIDTH` triangles from `first` on, relative to
    /// the ray and sheared (the ray the third axis): X, Y and |X| + |Y|.
    #[inline(always)]
    fn sheared<L: Lanes>(&self, s: L, ray: &FilterRay, c: usize, first: u32) -> Lanes3<L> {
        let [rx, ry, rz] = ray.rows[c];
        let (x, y, z) = (
            self.lanes(s, rx, first),
            self.lanes(s, ry, first),
            self.lanes(s, rz, first),
        );
        let [ox, oy, oz] = ray.origin;
        let [sx, sy] = ray.shear;
        let z = s.sub(z, s.splat(oz));
        let x = s.sub(s.sub(x, s.splat(ox)), s.mul(s.splat(sx), z));
        let y = s.sub(s.sub(y, s.splat(oy)), s.mul(s.splat(sy), z));
        (x, y, s.add(s.abs(x), s.abs(y)))
    }

    /// The `L::WIDTH` values of the row starting at `row` from triangle
    /// `first` on.
    #[inline(always)]
    fn lanes<L: Lanes>(&self, s: L, row: u32, first: u32) -> L::F {
        // Both u32: the sum cannot overflow, one bound to check.
        s.load(&self.rows[row as usize + first as usize..])
    }
}

/// Per lane: a sheared corner's X and Y, and |X| + |Y|.
type Lanes3<L> = (<L as Lanes>::F, <L as Lanes>::F, <L as Lanes>::F);

/// The edge function p x q of sheared corners p and q, per lane: where it
/// is certainly negative, and where certainly positive (beyond the bound
/// of the module's doc).
#[inline(always)]
fn edge<L: Lanes>(s: L, ray: &FilterRay, p: Lanes3<L>, q: Lanes3<L>) -> (L::F, L::F) {
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
mod tests;
