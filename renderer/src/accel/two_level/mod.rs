//! The two-level structure over the database's prisms. Each stretch of an
//! object's path gets a hierarchy over its prisms in the stretch's comoving
//! (sheared) coordinates x' = x - v (t - t0) - x0, where a constant-velocity
//! object is static, so its bounds stay tight however fast or long-lived it
//! is (instancing with a per-stretch transform). Over all stretches, a
//! hierarchy of the lab-frame 4D bounds of their time slices.

use super::bvh::{rounding_margin, Bounds4, LEAF_SIZE};
use super::packet::{Lanes, PACKET};
use super::wide::{down, up, AxisRay, SliceBvh, SpaceBvh};
use crate::geometry::{comoving_line, nearer, Hit};
use crate::simd::{at_level, Simd8, SimdLevel};
use crate::spacetime::Event;
use glam::{DVec3, DVec4};

/// Most time slices one stretch is cut into in the top-level hierarchy.
const MAX_SLICES: usize = 64;

/// The prisms of one stretch, as the acceleration structure sees them: a
/// run of prisms moving together, whose comoving frame follows the
/// reference point from `origin` with `velocity`.
pub(crate) struct StretchPrisms {
    /// The reference point at the start of the stretch.
    pub(crate) origin: Event,
    /// Lab velocity of the reference point over the stretch.
    pub(crate) velocity: DVec3,
    /// Lab times covered.
    pub(crate) span: (f64, f64),
    /// Indices of the stretch's prisms in the database.
    pub(crate) prisms: std::ops::Range<usize>,
    /// Whether every prism is a pure translation along `velocity` (uniform
    /// motion), rather than a keyframe interval that may turn or deform.
    pub(crate) translation: bool,
}

/// Stretches of uniform motion from this many prisms have leaves of up to
/// [`LARGE_LEAF`] prisms.
const LARGE_FROM: usize = 1 << 18;

/// The most prisms a leaf of a large uniformly moving stretch holds: two
/// passes of the f32 filter. Its search waits on memory more than on its
/// leaves' tests, so a ray tests as much (the benchmark's 1M and 3M tori
/// trace as fast), while its build takes a level less (docs/performance.md).
const LARGE_LEAF: usize = 8;
const _: () = assert!(
    LARGE_LEAF > LEAF_SIZE,
    "a large stretch's leaves are larger"
);

impl StretchPrisms {
    /// The most prisms a leaf of its hierarchy holds: [`LARGE_LEAF`] for
    /// a uniformly moving stretch of [`LARGE_FROM`] prisms or more,
    /// [`LEAF_SIZE`] otherwise (a keyframe interval's prism is three
    /// tetrahedra, each solved exactly).
    fn leaf_size(&self) -> usize {
        match self.translation && self.prisms.len() >= LARGE_FROM {
            true => LARGE_LEAF,
            false => LEAF_SIZE,
        }
    }
}

/// One stretch's hierarchy over its prisms, in its comoving coordinates.
struct StretchBvh {
    origin: Event,
    velocity: DVec3,
    /// Lab times covered.
    span: (f64, f64),
    bvh: SpaceBvh,
}

impl StretchBvh {
    /// The ray `o + s d` in comoving coordinates (x, y, z), with the same
    /// parameter s, as the stretch's hierarchy takes it: (o, 1/d).
    #[inline]
    fn to_comoving(&self, o: DVec4, d: DVec4) -> AxisRay<3> {
        let (o, d) = comoving_line(o, d, (self.origin.t, self.origin.x), self.velocity);
        (o.to_array(), (DVec3::ONE / d).to_array())
    }
}

/// One entry of the top-level hierarchy: a stretch over a slice of its lab
/// times, bounded by its sweep over that slice only (so a fast or
/// long-lived object does not cover the whole scene; cf. STBVH).
struct TimeSlice {
    stretch: u32,
    /// The slice's box, padded as the top level pads a leaf's, in f32
    /// rounded outward (lower x, y, z, t then upper).
    bounds: [f32; 8],
    /// Whether it is its stretch's only slice.
    alone: bool,
}

/// The f32 box that holds `b`, rounded outward (lower then upper).
fn outward(b: Bounds4) -> [f32; 8] {
    let (lo, hi) = (b.min.to_array().map(down), b.max.to_array().map(up));
    [lo[0], lo[1], lo[2], lo[3], hi[0], hi[1], hi[2], hi[3]]
}

impl TimeSlice {
    /// Whether the ray `o + s d` (`inv` = 1/d) enters the slice's box
    /// within `range` (in f64, on its f32 faces: no sooner than its f64
    /// box).
    #[inline(always)]
    fn entered(&self, o: DVec4, inv: DVec4, range: (f64, f64)) -> bool {
        let b = self.bounds.map(f64::from);
        let (min, max) = (DVec4::from_slice(&b[..4]), DVec4::from_slice(&b[4..]));
        Bounds4::new(min, max).entry(o, inv, range).is_some()
    }
}

/// The part of `range` where the ray `o + s d` is within the lab times
/// `t0..t1` (a stretch's), widened by a billionth of its ends for the
/// rounding of both it and the solves (a hit exactly at the time two
/// stretches meet is then tested on both sides, as brute force would);
/// `None` if it never is.
#[inline]
fn window((t0, t1): (f64, f64), o: DVec4, d: DVec4, range: (f64, f64)) -> Option<(f64, f64)> {
    if d.w == 0.0 {
        return (t0 <= o.w && o.w <= t1).then_some(range);
    }
    let (a, b) = ((t0 - o.w) / d.w, (t1 - o.w) / d.w);
    let margin = (a.abs() + b.abs()) * 1e-9;
    let (lo, hi) = (
        range.0.max(a.min(b) - margin),
        range.1.min(a.max(b) + margin),
    );
    (lo <= hi).then_some((lo, hi))
}

/// Stretches a ray has searched over all their lab times (at most
/// [`Searched::MAX`] recorded; a stretch not recorded is searched again, to
/// the same hit).
#[derive(Default)]
struct Searched {
    stretches: [u32; Searched::MAX],
    len: usize,
}

impl Searched {
    const MAX: usize = 4;

    fn holds(&self, k: u32) -> bool {
        self.stretches[..self.len].contains(&k)
    }

    fn add(&mut self, k: u32) {
        if self.len < Self::MAX {
            self.stretches[self.len] = k;
            self.len += 1;
        }
    }
}

/// The two-level structure: per stretch, a hierarchy over its prisms'
/// comoving bounds; over all stretches, a hierarchy of the lab-frame 4D
/// bounds of their time slices.
pub(crate) struct TwoLevel {
    top: SliceBvh,
    stretches: Vec<StretchBvh>,
    slices: Vec<TimeSlice>,
}

/// Cuts a stretch into as many time slices as it takes for each to sweep
/// about its own size (at most [`MAX_SLICES`]), given the comoving box
/// `lo..hi` of all its prisms; returns each slice's bounds.
fn slices(g: &StretchPrisms, lo: DVec3, hi: DVec3) -> Vec<Bounds4> {
    let (t0, t1) = g.span;
    let v = g.velocity;
    let size = (hi - lo).max_element().max(1e-9);
    let sweep = (v * (t1 - t0)).length();
    let count = ((sweep / size).ceil() as usize).clamp(1, MAX_SLICES);
    (0..count)
        .map(|k| {
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
            let pad =
                rounding_margin(bl.extend(0.0), bh.extend(0.0)).truncate() + DVec3::splat(1e-300);
            Bounds4::new((bl - pad).extend(ta), (bh + pad).extend(tb))
        })
        .collect()
}

impl TwoLevel {
    /// Builds both levels over the prisms of `stretches`, given each
    /// prism's box in its stretch's comoving coordinates, by stretch and
    /// prism: `comoving_box(k, p)`.
    pub(crate) fn build<'a>(
        stretches: impl Iterator<Item = &'a StretchPrisms>,
        comoving_box: impl Fn(usize, usize) -> (DVec3, DVec3) + Sync,
    ) -> TwoLevel {
        let mut built = Vec::new();
        let mut all_slices = Vec::new();
        let mut slice_bounds = Vec::new();
        for (k, g) in stretches.enumerate() {
            let (t0, t1) = g.span;
            let (tree, extent) = SpaceBvh::build_with_leaves(g.prisms.len(), g.leaf_size(), |i| {
                let (a, b) = comoving_box(k, g.prisms.start + i);
                Bounds4::new(a.extend(t0), b.extend(t1))
            });
            let cut = slices(g, extent.min.truncate(), extent.max.truncate());
            let alone = cut.len() == 1;
            for bounds in cut {
                slice_bounds.push(bounds);
                all_slices.push(TimeSlice {
                    stretch: built.len() as u32,
                    bounds: outward(bounds.padded()),
                    alone,
                });
            }
            built.push(StretchBvh {
                origin: g.origin,
                velocity: g.velocity,
                span: g.span,
                bvh: tree,
            });
        }
        TwoLevel {
            top: SliceBvh::build(slice_bounds.len(), |i| slice_bounds[i]).0,
            stretches: built,
            slices: all_slices,
        }
    }

    /// The lab-space box holding every slice's box: all the prisms ever
    /// are inside it (empty, lower above upper, when there are none).
    pub(crate) fn spatial_box(&self) -> (DVec3, DVec3) {
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for s in &self.slices {
            let b = s.bounds.map(f64::from);
            lo = lo.min(DVec3::new(b[0], b[1], b[2]));
            hi = hi.max(DVec3::new(b[4], b[5], b[6]));
        }
        (lo, hi)
    }

    /// How many time slices the top level holds.
    pub(crate) fn slice_count(&self) -> usize {
        self.slices.len()
    }

    /// How many time slices a search passes through: none where the
    /// structure holds one stretch (its own hierarchy is searched
    /// straight away), all of them otherwise.
    pub(crate) fn searched_slice_count(&self) -> usize {
        match self.lone_stretch() {
            Some(_) => 0,
            None => self.slices.len(),
        }
    }

    /// The stretch the structure holds, where it holds one: searched in
    /// its own hierarchy straight away, whose boxes cull every ray its
    /// time slices would.
    fn lone_stretch(&self) -> Option<&StretchBvh> {
        match &self.stretches[..] {
            [stretch] => Some(stretch),
            _ => None,
        }
    }

    /// The order in which stretch `k`'s hierarchy holds its prisms: at
    /// position j, prism `order(k)[j]` of the stretch (counted from its
    /// first).
    pub(crate) fn order(&self, k: usize) -> &[u32] {
        self.stretches[k].bvh.order()
    }

    /// The closest hit along the ray `o + s d` (lab frame, (x, y, z, t))
    /// within `range`: `leaf(stretch, first, items, range)` is called for
    /// every leaf of a stretch's hierarchy whose boxes the ray enters, with
    /// the stretch's index, the position in [`TwoLevel::order`] of the
    /// leaf's first item, its items (prisms counted from the stretch's
    /// first, side by side there) and the range shrunk to the best hit so
    /// far, and returns the best hit among them. With one stretch, the top
    /// level is passed by: the stretch's own boxes cull every ray its time
    /// slices would. The node tests run at the widest vector level `level`
    /// allows on this machine.
    pub(crate) fn closest(
        &self,
        level: SimdLevel,
        o: DVec4,
        d: DVec4,
        range: (f64, f64),
        leaf: impl FnMut(u32, u32, &[u32], (f64, f64)) -> Option<Hit>,
    ) -> Option<Hit> {
        at_level!(level, |simd| self.closest_at(simd, o, d, range, leaf))
    }

    /// [`TwoLevel::closest`] at the vector level of `simd`.
    #[inline(always)]
    fn closest_at<S: Simd8>(
        &self,
        simd: S,
        o: DVec4,
        d: DVec4,
        range: (f64, f64),
        mut leaf: impl FnMut(u32, u32, &[u32], (f64, f64)) -> Option<Hit>,
    ) -> Option<Hit> {
        if let Some(stretch) = self.lone_stretch() {
            // Its own hierarchy culls every ray the top level would.
            let r = window(stretch.span, o, d, range)?;
            let ray = stretch.to_comoving(o, d);
            return (stretch.bvh).closest(simd, ray, r, |first, items, r| leaf(0, first, items, r));
        }
        let inv = DVec4::ONE / d;
        let mut searched = Searched::default();
        let ray = (o.to_array(), inv.to_array());
        self.top.closest(
            simd,
            ray,
            range,
            #[inline(always)]
            |_, slices, r| {
                let mut best: Option<Hit> = None;
                for &k in slices {
                    let r = (r.0, best.map_or(r.1, |b| b.s));
                    let slice = &self.slices[k as usize];
                    let stretch = &self.stretches[slice.stretch as usize];
                    if !slice.alone {
                        // A leaf of the top level may hold several slices, and
                        // its box theirs. The first slice of a stretch the ray
                        // enters has the stretch searched over all its lab
                        // times: its hierarchy's boxes hold its prisms at every
                        // one of them, so it is entered only where the ray
                        // meets the stretch's sweep, and each prism is tested
                        // once.
                        if searched.holds(slice.stretch) || !slice.entered(o, inv, r) {
                            continue;
                        }
                        searched.add(slice.stretch);
                    }
                    let Some(r) = window(stretch.span, o, d, r) else {
                        continue;
                    };
                    let ray = stretch.to_comoving(o, d);
                    let found = (stretch.bvh).closest(simd, ray, r, |first, items, r| {
                        leaf(slice.stretch, first, items, r)
                    });
                    if let Some(h) = found {
                        best = Some(nearer(best, h));
                    }
                }
                best
            },
        )
    }

    /// [`TwoLevel::closest`] for a packet of lab rays `rays[i]` = (o, d),
    /// those of `lanes`, within `range`: `leaf(i, stretch, first, items,
    /// range)` is called for ray i. Each ray finds the hit it finds alone.
    pub(crate) fn closest_packet(
        &self,
        level: SimdLevel,
        rays: &[(DVec4, DVec4); PACKET],
        lanes: Lanes,
        range: (f64, f64),
        leaf: impl FnMut(usize, u32, u32, &[u32], (f64, f64)) -> Option<Hit>,
    ) -> [Option<Hit>; PACKET] {
        at_level!(level, |simd| self.packet_at(simd, rays, lanes, range, leaf))
    }

    /// [`TwoLevel::closest_packet`] at the vector level of `simd`.
    #[inline(always)]
    fn packet_at<S: Simd8>(
        &self,
        simd: S,
        rays: &[(DVec4, DVec4); PACKET],
        lanes: Lanes,
        range: (f64, f64),
        mut leaf: impl FnMut(usize, u32, u32, &[u32], (f64, f64)) -> Option<Hit>,
    ) -> [Option<Hit>; PACKET] {
        if let Some(stretch) = self.lone_stretch() {
            return only_stretch(simd, stretch, rays, lanes, range, |i, first, items, r| {
                leaf(i, 0, first, items, r)
            });
        }
        let mut inv = [DVec4::ZERO; PACKET];
        let mut lab = [([0.0; 4], [0.0; 4]); PACKET];
        for i in 0..PACKET {
            inv[i] = DVec4::ONE / rays[i].1;
            lab[i] = (rays[i].0.to_array(), inv[i].to_array());
        }
        let mut searched: [Searched; PACKET] = Default::default();
        let mut best: [Option<Hit>; PACKET] = [None; PACKET];
        self.top.search_packet(
            simd,
            &lab,
            lanes,
            range,
            #[inline(always)]
            |slices, lanes, hi| {
                for &k in slices {
                    let slice = &self.slices[k as usize];
                    let stretch = &self.stretches[slice.stretch as usize];
                    let mut comoving = [([0.0; 3], [0.0; 3]); PACKET];
                    let mut windows = [(0.0, 0.0); PACKET];
                    // As in `closest`, ray by ray (written out again: a helper
                    // shared with it cost its slice step 14% more instructions,
                    // by callgrind on the flange).
                    let lanes = lanes.filter(|i| {
                        let ((o, d), r) = (rays[i], (range.0, hi[i]));
                        if !slice.alone {
                            if searched[i].holds(slice.stretch) || !slice.entered(o, inv[i], r) {
                                return false;
                            }
                            searched[i].add(slice.stretch);
                        }
                        let Some(w) = window(stretch.span, o, d, r) else {
                            return false;
                        };
                        (windows[i], comoving[i]) = (w, stretch.to_comoving(o, d));
                        true
                    });
                    if lanes.is_empty() {
                        continue;
                    }
                    let found = stretch.bvh.closest_packet(
                        simd,
                        &comoving,
                        lanes,
                        &windows,
                        |i, first, items, r| leaf(i, slice.stretch, first, items, r),
                    );
                    for i in lanes.iter() {
                        if let Some(h) = found[i] {
                            let b = nearer(best[i], h);
                            (best[i], hi[i]) = (Some(b), b.s);
                        }
                    }
                }
            },
        );
        best
    }
}

/// [`TwoLevel::closest_packet`] where the database holds one stretch,
/// `stretch`: its own hierarchy culls every ray the top level's time
/// slices would (both hold the stretch's sweep, conservatively), so the
/// packet searches it straight away, each ray within its window of the
/// stretch's lab times. (For a moving object the top level holds many
/// slices, and the packet's search of them cost a tenth of its frame.)
#[inline(always)]
fn only_stretch<S: Simd8>(
    simd: S,
    stretch: &StretchBvh,
    rays: &[(DVec4, DVec4); PACKET],
    lanes: Lanes,
    range: (f64, f64),
    leaf: impl FnMut(usize, u32, &[u32], (f64, f64)) -> Option<Hit>,
) -> [Option<Hit>; PACKET] {
    let mut comoving = [([0.0; 3], [0.0; 3]); PACKET];
    let mut windows = [(0.0, 0.0); PACKET];
    let lanes = lanes.filter(|i| {
        let (o, d) = rays[i];
        let Some(w) = window(stretch.span, o, d, range) else {
            return false;
        };
        (windows[i], comoving[i]) = (w, stretch.to_comoving(o, d));
        true
    });
    if lanes.is_empty() {
        return [None; PACKET];
    }
    stretch
        .bvh
        .closest_packet(simd, &comoving, lanes, &windows, leaf)
}

#[cfg(test)]
mod tests;
