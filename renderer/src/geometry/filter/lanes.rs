//! The lanewise f32 operations the filter runs in, at two widths: four
//! lanes of SSE2 (`wide`'s f32x4, every x86-64), or eight at a vector level
//! of [`Simd8`]. Each is the same IEEE operation lane by lane, unfused, so
//! a triangle's lane decides the same at every width and level.

use crate::simd::Simd8;
use wide::{f32x4, f32x8, CmpLt};

/// Lanewise f32 operations on `WIDTH` lanes, by a token of the width.
pub(super) trait Lanes: Copy {
    /// `WIDTH` f32 lanes.
    type F: Copy;
    /// Triangles a pass covers.
    const WIDTH: usize;
    /// The first `WIDTH` values of `row`.
    fn load(self, row: &[f32]) -> Self::F;
    /// Every lane `x`.
    fn splat(self, x: f32) -> Self::F;
    /// `a - b`.
    fn sub(self, a: Self::F, b: Self::F) -> Self::F;
    /// `a * b`.
    fn mul(self, a: Self::F, b: Self::F) -> Self::F;
    /// `a + b`.
    fn add(self, a: Self::F, b: Self::F) -> Self::F;
    /// `a` with its sign bits cleared.
    fn abs(self, a: Self::F) -> Self::F;
    /// All ones where `a < b` (ordered), zeros elsewhere.
    fn lt(self, a: Self::F, b: Self::F) -> Self::F;
    /// The bits of `a` or `b`.
    fn or(self, a: Self::F, b: Self::F) -> Self::F;
    /// The bits of `a` and `b`.
    fn and(self, a: Self::F, b: Self::F) -> Self::F;
    /// Bit i set where lane i of the mask `m` is set.
    fn bits(self, m: Self::F) -> u32;
}

/// Four lanes in one SSE2 register (at x86-64's baseline).
#[derive(Clone, Copy, Debug)]
pub(super) struct Four;

impl Lanes for Four {
    type F = f32x4;
    const WIDTH: usize = 4;

    #[inline(always)]
    fn load(self, row: &[f32]) -> f32x4 {
        let lanes: [f32; 4] = row[..4].try_into().expect("four lanes");
        f32x4::from(lanes)
    }

    #[inline(always)]
    fn splat(self, x: f32) -> f32x4 {
        f32x4::splat(x)
    }

    #[inline(always)]
    fn sub(self, a: f32x4, b: f32x4) -> f32x4 {
        a - b
    }

    #[inline(always)]
    fn mul(self, a: f32x4, b: f32x4) -> f32x4 {
        a * b
    }

    #[inline(always)]
    fn add(self, a: f32x4, b: f32x4) -> f32x4 {
        a + b
    }

    #[inline(always)]
    fn abs(self, a: f32x4) -> f32x4 {
        a.abs()
    }

    #[inline(always)]
    fn lt(self, a: f32x4, b: f32x4) -> f32x4 {
        a.cmp_lt(b)
    }

    #[inline(always)]
    fn or(self, a: f32x4, b: f32x4) -> f32x4 {
        a | b
    }

    #[inline(always)]
    fn and(self, a: f32x4, b: f32x4) -> f32x4 {
        a & b
    }

    #[inline(always)]
    fn bits(self, m: f32x4) -> u32 {
        m.move_mask() as u32
    }
}

/// Eight lanes at the vector level of the token `S`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Eight<S>(pub(super) S);

impl<S: Simd8> Lanes for Eight<S> {
    type F = S::F;
    const WIDTH: usize = 8;

    #[inline(always)]
    fn load(self, row: &[f32]) -> S::F {
        let lanes: [f32; 8] = row[..8].try_into().expect("eight lanes");
        self.0.load(f32x8::from(lanes))
    }

    #[inline(always)]
    fn splat(self, x: f32) -> S::F {
        self.0.splat(x)
    }

    #[inline(always)]
    fn sub(self, a: S::F, b: S::F) -> S::F {
        self.0.sub(a, b)
    }

    #[inline(always)]
    fn mul(self, a: S::F, b: S::F) -> S::F {
        self.0.mul(a, b)
    }

    #[inline(always)]
    fn add(self, a: S::F, b: S::F) -> S::F {
        self.0.add(a, b)
    }

    #[inline(always)]
    fn abs(self, a: S::F) -> S::F {
        self.0.abs(a)
    }

    #[inline(always)]
    fn lt(self, a: S::F, b: S::F) -> S::F {
        self.0.lt(a, b)
    }

    #[inline(always)]
    fn or(self, a: S::F, b: S::F) -> S::F {
        self.0.or(a, b)
    }

    #[inline(always)]
    fn and(self, a: S::F, b: S::F) -> S::F {
        self.0.and(a, b)
    }

    #[inline(always)]
    fn bits(self, m: S::F) -> u32 {
        self.0.bits(m)
    }
}
