//! The eight-lane f32 arithmetic of the searches (the node tests and the
//! triangle filter), at the vector level the machine offers, chosen when
//! a search starts.
//!
//! The hierarchies are searched, and the filter run, through [`Simd8`], a
//! token whose methods are the few lanewise operations they need.
//! [`Baseline`] is the `wide` crate's f32x8 as the build's target compiles
//! it (at x86-64's baseline, two SSE2 registers); `pulp::x86::V3` is one
//! AVX register, a token that exists only where `pulp` has found AVX2 and
//! FMA on the CPU, so that its safe intrinsics are sound. A search generic
//! over the token is run inside `pulp::x86::V3::vectorize`, which compiles
//! what it inlines for those features (every step of the search down to
//! the leaf callbacks is `#[inline(always)]`; the filter enters its own).
//!
//! Both levels run the same IEEE operations lane by lane (a subtraction,
//! a product, a sum, the maximum and minimum of SSE's `maxps`/`minps`,
//! which return their second operand where either is NaN, ordered
//! comparisons, and the bitwise operations of masks and of the absolute
//! value), and no operation is fused, so every level finds the same boxes
//! entered at the same parameters, lets the same triangles through, and
//! so finds the same hits to the bit.

use std::sync::atomic::{AtomicU8, Ordering};
use wide::f32x8;

/// How wide the node tests may go: the widest the machine has, up to the
/// level given (see [`Database::set_simd`](crate::Database::set_simd) and
/// [`SimdLevel::limit_process`]). Every level finds the same hits, to the
/// bit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub enum SimdLevel {
    /// The build's own target (at x86-64's baseline, SSE2: two 4-lane
    /// registers a node test).
    Baseline,
    /// x86-64-v3 (AVX2 and FMA) where the CPU has it: a node's eight boxes
    /// in one 8-lane register.
    #[default]
    X86V3,
}

impl SimdLevel {
    /// The levels this machine runs, the baseline first (whatever this
    /// process's limit).
    pub fn supported() -> Vec<SimdLevel> {
        #[cfg(target_arch = "x86_64")]
        let wider = pulp::x86::V3::try_new().map(|_| SimdLevel::X86V3);
        #[cfg(not(target_arch = "x86_64"))]
        let wider = None;
        std::iter::once(SimdLevel::Baseline).chain(wider).collect()
    }

    /// The widest level searches run at in this process: the machine's,
    /// within [`SimdLevel::limit_process`]'s.
    pub fn best() -> SimdLevel {
        #[cfg(target_arch = "x86_64")]
        if v3(SimdLevel::X86V3).is_some() {
            return SimdLevel::X86V3;
        }
        SimdLevel::Baseline
    }

    /// Limits every search of this process to `level` at the widest,
    /// whatever its database asks for (as a thread count limits the
    /// threads): a user's way to run the baseline where the machine has
    /// wider units, and see the same images. Hits do not change.
    pub fn limit_process(level: SimdLevel) {
        PROCESS_LIMIT.store(level as u8, Ordering::Relaxed);
    }

    /// The limit [`SimdLevel::limit_process`] set ([`SimdLevel::X86V3`],
    /// no limit, until it is called).
    fn process_limit() -> SimdLevel {
        match PROCESS_LIMIT.load(Ordering::Relaxed) {
            0 => SimdLevel::Baseline,
            _ => SimdLevel::X86V3,
        }
    }

    /// The level's name as a command line gives it: `baseline` or
    /// `x86-64-v3`.
    pub fn name(self) -> &'static str {
        match self {
            SimdLevel::Baseline => "baseline",
            SimdLevel::X86V3 => "x86-64-v3",
        }
    }

    /// Every level, narrowest first (whatever this machine runs).
    pub const ALL: [SimdLevel; 2] = [SimdLevel::Baseline, SimdLevel::X86V3];

    /// The level [`SimdLevel::name`] names.
    pub fn from_name(name: &str) -> Option<SimdLevel> {
        SimdLevel::ALL.into_iter().find(|l| l.name() == name)
    }
}

/// The process's limit on the level, as `SimdLevel as u8`.
static PROCESS_LIMIT: AtomicU8 = AtomicU8::new(SimdLevel::X86V3 as u8);

impl std::fmt::Display for SimdLevel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            SimdLevel::Baseline => "the build's baseline",
            SimdLevel::X86V3 => "x86-64-v3 (AVX2)",
        })
    }
}

/// The AVX token where `level` allows it and the CPU has x86-64-v3 (found
/// once, then cached by `pulp`).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn v3(level: SimdLevel) -> Option<pulp::x86::V3> {
    match level.min(SimdLevel::process_limit()) {
        SimdLevel::Baseline => None,
        SimdLevel::X86V3 => pulp::x86::V3::try_new(),
    }
}

/// `$body` with `$s` the token of the widest vector level `$level` allows
/// on this machine, compiled for that level: inside
/// `pulp::x86::V3::vectorize` for x86-64-v3, so that what `$body` inlines
/// is compiled for AVX2 and FMA.
#[cfg(target_arch = "x86_64")]
macro_rules! at_level {
    ($level:expr, |$s:ident| $body:expr) => {
        match $crate::simd::v3($level) {
            Some(v3) => v3.vectorize(
                #[inline(always)]
                || {
                    let $s = v3;
                    $body
                },
            ),
            None => {
                let $s = $crate::simd::Baseline;
                $body
            }
        }
    };
}

/// `$body` with `$s` the baseline's token: no wider level here.
#[cfg(not(target_arch = "x86_64"))]
macro_rules! at_level {
    ($level:expr, |$s:ident| $body:expr) => {{
        let _ = $level;
        let $s = $crate::simd::Baseline;
        $body
    }};
}
pub(crate) use at_level;

/// Lanewise f32 operations on eight lanes, by a token of the vector
/// level they run at.
pub(crate) trait Simd8: Copy {
    /// Eight f32 lanes.
    type F: Copy;
    /// Every lane `x`.
    fn splat(self, x: f32) -> Self::F;
    /// The lanes of a node's face as stored.
    fn load(self, x: f32x8) -> Self::F;
    /// `a * b`.
    fn mul(self, a: Self::F, b: Self::F) -> Self::F;
    /// `a - b`.
    fn sub(self, a: Self::F, b: Self::F) -> Self::F;
    /// `a + b`.
    fn add(self, a: Self::F, b: Self::F) -> Self::F;
    /// Lanewise max(a, b), and `b` where `a` is NaN (SSE's `maxps`; no
    /// caller passes a NaN `b`).
    fn max_or_second(self, a: Self::F, b: Self::F) -> Self::F;
    /// Lanewise min(a, b), and `b` where `a` is NaN (SSE's `minps`; no
    /// caller passes a NaN `b`).
    fn min_or_second(self, a: Self::F, b: Self::F) -> Self::F;
    /// All ones where `a <= b` (ordered), zeros elsewhere.
    fn le(self, a: Self::F, b: Self::F) -> Self::F;
    /// All ones where `a < b` (ordered), zeros elsewhere.
    fn lt(self, a: Self::F, b: Self::F) -> Self::F;
    /// `a` with its sign bits cleared.
    fn abs(self, a: Self::F) -> Self::F;
    /// The bits of `a` or `b` (of masks: either set).
    fn or(self, a: Self::F, b: Self::F) -> Self::F;
    /// The bits of `a` and `b` (of masks: both set).
    fn and(self, a: Self::F, b: Self::F) -> Self::F;
    /// Bit i set where lane i of the mask `m` is set.
    fn bits(self, m: Self::F) -> u32;
    /// `a` where the mask `m` is set, `b` elsewhere (`m` a comparison's:
    /// each lane all ones or all zeros).
    fn select(self, m: Self::F, a: Self::F, b: Self::F) -> Self::F;
    /// The lanes.
    fn to_array(self, a: Self::F) -> [f32; 8];
}

/// The build's own target's lanes: `wide`'s f32x8.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Baseline;

impl Simd8 for Baseline {
    type F = f32x8;

    #[inline(always)]
    fn splat(self, x: f32) -> f32x8 {
        f32x8::splat(x)
    }

    #[inline(always)]
    fn load(self, x: f32x8) -> f32x8 {
        x
    }

    #[inline(always)]
    fn mul(self, a: f32x8, b: f32x8) -> f32x8 {
        a * b
    }

    #[inline(always)]
    fn sub(self, a: f32x8, b: f32x8) -> f32x8 {
        a - b
    }

    #[inline(always)]
    fn add(self, a: f32x8, b: f32x8) -> f32x8 {
        a + b
    }

    #[inline(always)]
    fn max_or_second(self, a: f32x8, b: f32x8) -> f32x8 {
        #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
        let m = a.fast_max(b);
        // (Elsewhere `max` takes the operand that is not NaN.)
        #[cfg(not(any(target_arch = "x86", target_arch = "x86_64")))]
        let m = b.max(a);
        m
    }

    #[inline(always)]
    fn min_or_second(self, a: f32x8, b: f32x8) -> f32x8 {
        #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
        let m = a.fast_min(b);
        #[cfg(not(any(target_arch = "x86", target_arch = "x86_64")))]
        let m = b.min(a);
        m
    }

    #[inline(always)]
    fn le(self, a: f32x8, b: f32x8) -> f32x8 {
        use wide::CmpLe;
        a.cmp_le(b)
    }

    #[inline(always)]
    fn lt(self, a: f32x8, b: f32x8) -> f32x8 {
        use wide::CmpLt;
        a.cmp_lt(b)
    }

    #[inline(always)]
    fn abs(self, a: f32x8) -> f32x8 {
        a.abs()
    }

    #[inline(always)]
    fn or(self, a: f32x8, b: f32x8) -> f32x8 {
        a | b
    }

    #[inline(always)]
    fn and(self, a: f32x8, b: f32x8) -> f32x8 {
        a & b
    }

    #[inline(always)]
    fn bits(self, m: f32x8) -> u32 {
        m.move_mask() as u32
    }

    #[inline(always)]
    fn select(self, m: f32x8, a: f32x8, b: f32x8) -> f32x8 {
        m.blend(a, b)
    }

    #[inline(always)]
    fn to_array(self, a: f32x8) -> [f32; 8] {
        a.to_array()
    }
}

#[cfg(target_arch = "x86_64")]
mod x86_v3 {
    use super::Simd8;
    use core::arch::x86_64::{__m256, _CMP_LE_OQ, _CMP_LT_OQ};
    use pulp::x86::V3;
    use wide::f32x8;

    /// One AVX register: the same operations as SSE's, eight lanes wide.
    impl Simd8 for V3 {
        type F = __m256;

        #[inline(always)]
        fn splat(self, x: f32) -> __m256 {
            self.avx._mm256_set1_ps(x)
        }

        #[inline(always)]
        fn load(self, x: f32x8) -> __m256 {
            bytemuck::cast(x)
        }

        #[inline(always)]
        fn mul(self, a: __m256, b: __m256) -> __m256 {
            self.avx._mm256_mul_ps(a, b)
        }

        #[inline(always)]
        fn sub(self, a: __m256, b: __m256) -> __m256 {
            self.avx._mm256_sub_ps(a, b)
        }

        #[inline(always)]
        fn add(self, a: __m256, b: __m256) -> __m256 {
            self.avx._mm256_add_ps(a, b)
        }

        #[inline(always)]
        fn max_or_second(self, a: __m256, b: __m256) -> __m256 {
            self.avx._mm256_max_ps(a, b)
        }

        #[inline(always)]
        fn min_or_second(self, a: __m256, b: __m256) -> __m256 {
            self.avx._mm256_min_ps(a, b)
        }

        #[inline(always)]
        fn le(self, a: __m256, b: __m256) -> __m256 {
            self.avx._mm256_cmp_ps::<_CMP_LE_OQ>(a, b)
        }

        #[inline(always)]
        fn lt(self, a: __m256, b: __m256) -> __m256 {
            self.avx._mm256_cmp_ps::<_CMP_LT_OQ>(a, b)
        }

        #[inline(always)]
        fn abs(self, a: __m256) -> __m256 {
            let magnitude = self.avx._mm256_set1_ps(f32::from_bits(i32::MAX as u32));
            self.avx._mm256_and_ps(a, magnitude)
        }

        #[inline(always)]
        fn or(self, a: __m256, b: __m256) -> __m256 {
            self.avx._mm256_or_ps(a, b)
        }

        #[inline(always)]
        fn and(self, a: __m256, b: __m256) -> __m256 {
            self.avx._mm256_and_ps(a, b)
        }

        #[inline(always)]
        fn bits(self, m: __m256) -> u32 {
            self.avx._mm256_movemask_ps(m) as u32
        }

        #[inline(always)]
        fn select(self, m: __m256, a: __m256, b: __m256) -> __m256 {
            self.avx._mm256_blendv_ps(b, a, m)
        }

        #[inline(always)]
        fn to_array(self, a: __m256) -> [f32; 8] {
            bytemuck::cast(a)
        }
    }
}

/// The widest level above the baseline this machine has, for tests.
#[cfg(test)]
pub(crate) fn wider() -> Option<impl Simd8> {
    #[cfg(target_arch = "x86_64")]
    return v3(SimdLevel::X86V3);
    #[cfg(not(target_arch = "x86_64"))]
    return None::<Baseline>;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    /// Eight lanes drawn from what a node test meets: zeros of both signs,
    /// infinities, NaN, subnormals, f32's extremes and ordinary values.
    fn lanes(rng: &mut SplitMix64) -> [f32; 8] {
        const SPECIAL: [f32; 10] = [
            0.0,
            -0.0,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            1e-40,
            -1e-40,
            f32::MAX,
            f32::MIN_POSITIVE,
            1.0,
        ];
        std::array::from_fn(|_| {
            let r = rng.next_u64();
            if r % 3 == 0 {
                SPECIAL[(r / 3 % 10) as usize]
            } else {
                ((rng.next_f64() - 0.5) * 10f64.powi((r / 3 % 9) as i32 - 4)) as f32
            }
        })
    }

    /// Every operation of a level on the lanes `a`, `b`, `c`, as bits.
    fn results(s: impl Simd8, a: [f32; 8], b: [f32; 8], c: [f32; 8]) -> Vec<[u32; 8]> {
        let [a, b, c] = [a, b, c].map(|x| s.load(f32x8::from(x)));
        let (m, n) = (s.le(a, b), s.lt(b, c));
        let out = [
            s.splat(-0.0),
            s.mul(a, c),
            s.sub(a, b),
            s.add(a, b),
            s.max_or_second(a, b),
            s.min_or_second(a, b),
            m,
            n,
            s.select(m, a, c),
            s.abs(a),
            s.or(m, n),
            s.and(m, n),
        ];
        let mut bits: Vec<[u32; 8]> = out
            .iter()
            .map(|&x| s.to_array(x).map(f32::to_bits))
            .collect();
        bits.push([s.bits(m), s.bits(n), 0, 0, 0, 0, 0, 0]);
        bits
    }

    /// Each wider level gives every operation's result to the bit as the
    /// baseline does, NaN lanes, signed zeros and subnormals included.
    #[test]
    fn every_level_computes_the_baselines_bits() {
        let Some(wider) = wider() else {
            return; // the baseline alone: nothing to compare
        };
        let mut rng = SplitMix64::new(31);
        for _ in 0..20_000 {
            let (a, b, c) = (lanes(&mut rng), lanes(&mut rng), lanes(&mut rng));
            assert_eq!(
                results(Baseline, a, b, c),
                results(wider, a, b, c),
                "{a:?} {b:?} {c:?}"
            );
        }
    }

    /// The control: the inputs reach the cases where the operations'
    /// order of operands decides (a NaN lane, or zeros of both signs), so
    /// a level that swapped them would be caught above.
    #[test]
    fn the_inputs_reach_the_operand_order() {
        let mut rng = SplitMix64::new(31);
        let swapped = (0..20_000).any(|_| {
            let (a, b) = (lanes(&mut rng), lanes(&mut rng));
            let s = Baseline;
            let (a, b) = (f32x8::from(a), f32x8::from(b));
            let bits = |x: f32x8| s.to_array(x).map(f32::to_bits);
            bits(s.max_or_second(a, b)) != bits(s.max_or_second(b, a))
        });
        assert!(swapped);
    }
}
