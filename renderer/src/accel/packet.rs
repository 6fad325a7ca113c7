//! Packets: a few rays searched together, as coherent primary rays are
//! (neighbouring pixels, one camera event). Each node is loaded once for
//! the packet and its boxes tested against every ray still searching it;
//! a child is visited when any of them enters it, and only by those that
//! do. Each ray's leaves are tested alone, with its own range shrunk to
//! its own best hit, so every ray meets every leaf it would meet alone
//! (and perhaps more, which cannot change its hit: ties go to the lower
//! primitive, whatever the order) and finds the same hit to the bit.

/// The most rays a packet holds.
pub(crate) const PACKET: usize = 4;

/// A set of a packet's rays: bit i for ray i.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Lanes(pub(crate) u32);

impl Lanes {
    /// The first `n` rays (at most [`PACKET`]).
    pub(crate) fn first(n: usize) -> Lanes {
        debug_assert!(n <= PACKET);
        Lanes((1 << n) - 1)
    }

    pub(crate) fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// The set's rays, lowest first.
    #[inline(always)]
    pub(crate) fn iter(self) -> LanesIter {
        LanesIter(self.0)
    }

    /// Those of the set for which `keep(i)` holds.
    #[inline(always)]
    pub(crate) fn filter(self, mut keep: impl FnMut(usize) -> bool) -> Lanes {
        let mut out = 0;
        for i in 0..PACKET {
            out |= u32::from(self.0 >> i & 1 != 0 && keep(i)) << i;
        }
        Lanes(out)
    }

    /// Those of the set whose range's end `hi[i]` is at or beyond `entry`
    /// (`filter(|i| entry <= hi[i])`, every lane compared at once rather
    /// than one branch a lane).
    #[inline(always)]
    pub(crate) fn reaching(self, entry: f32, hi: &[f32; PACKET]) -> Lanes {
        let mut out = 0;
        for (i, &h) in hi.iter().enumerate() {
            out |= u32::from(entry <= h) << i;
        }
        Lanes(out & self.0)
    }

    /// The set's one ray, if it holds exactly one.
    #[inline(always)]
    pub(crate) fn single(self) -> Option<usize> {
        (self.0 != 0 && self.0 & (self.0 - 1) == 0).then(|| self.0.trailing_zeros() as usize)
    }

    /// Whether ray `i` is in the set.
    #[inline(always)]
    pub(crate) fn holds(self, i: usize) -> bool {
        self.0 >> i & 1 != 0
    }
}

/// The rays of a [`Lanes`], lowest first.
pub(crate) struct LanesIter(u32);

impl Iterator for LanesIter {
    type Item = usize;

    #[inline(always)]
    fn next(&mut self) -> Option<usize> {
        if self.0 == 0 {
            return None;
        }
        let i = self.0.trailing_zeros() as usize;
        self.0 &= self.0 - 1;
        Some(i)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_iterate_lowest_first_and_filter() {
        let l = Lanes(0b1011);
        assert_eq!(l.iter().collect::<Vec<_>>(), [0, 1, 3]);
        assert_eq!(l.filter(|i| i != 1), Lanes(0b1001));
        assert_eq!(Lanes::first(3), Lanes(0b111));
        assert!(l.holds(3) && !l.holds(2));
        assert_eq!(Lanes(0b100).single(), Some(2));
        assert_eq!(l.single(), None);
        assert_eq!(Lanes(0).single(), None);
        assert!(Lanes::default().iter().next().is_none());
        assert!(Lanes::first(0).is_empty());
    }

    /// `reaching` keeps what `filter` with the same comparison keeps, on
    /// every set of lanes, NaN and infinite ends included; the control:
    /// the strict comparison differs where an end equals the entry.
    #[test]
    fn reaching_is_filter_by_the_range_end() {
        let values = [
            f32::NAN,
            f32::NEG_INFINITY,
            -1.0,
            0.0,
            0.5,
            1.0,
            f32::INFINITY,
        ];
        let mut strict_differs = false;
        for set in 0..16 {
            for (k, &entry) in values.iter().enumerate() {
                let hi: [f32; PACKET] = std::array::from_fn(|i| values[(k + 3 * i + set) % 7]);
                let lanes = Lanes(set as u32);
                assert_eq!(lanes.reaching(entry, &hi), lanes.filter(|i| entry <= hi[i]));
                strict_differs |= lanes.reaching(entry, &hi) != lanes.filter(|i| entry < hi[i]);
            }
        }
        assert!(strict_differs);
    }
}
