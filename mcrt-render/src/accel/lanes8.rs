//! Eight f32 lanes for the 8-wide BVH's box tests and its leaves' triangle and quad tests
//! (`geometry/query/tri8.rs`, `quad8.rs`), and the run-time choice of how to compute them: AVX2 (one 256-bit instruction per operation) where the processor has it, else two
//! 4-lane halves through glam (SSE2 on any x86-64, NEON or scalar elsewhere).
//!
//! The AVX2 path goes through `pulp` (safe SIMD: its `V3` token exists only where AVX2 and
//! FMA were detected, and `V3::vectorize` compiles the closure it runs with those features
//! enabled), so this crate keeps `#![forbid(unsafe_code)]`. On x86-64 both paths do the
//! same IEEE operations lane by lane in the same order (`min`/`max` with SSE's rule: the
//! second operand when either is NaN; no fused multiply-add), so they agree bit for bit.
//!
//! The choice is made once, when a tree is built ([`Simd8::detect`]), and taken once per
//! query ([`Simd8::dispatch`]): the whole traversal runs inside it, with whatever of the
//! caller's leaf visit is inlined into it.

use glam::{BVec4A, Vec4};

/// Operations on eight f32 lanes (`V`) and lane masks (`M`), as the slab test and the leaf
/// tests need them. Comparisons are ordered (false when either lane is NaN) but for
/// [`Lanes8::ne`].
pub(crate) trait Lanes8: Copy {
    /// Eight lanes.
    type V: Copy;
    /// Eight lane masks.
    type M: Copy;
    /// `x` in every lane.
    fn splat(self, x: f32) -> Self::V;
    /// The lanes from memory.
    fn load(self, x: &[f32; 8]) -> Self::V;
    /// `a − b` per lane.
    fn sub(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a · b` per lane.
    fn mul(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a < b ? a : b` per lane (on x86-64 SSE's `minps`: `b` when either is NaN).
    fn min(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a > b ? a : b` per lane (on x86-64 SSE's `maxps`: `b` when either is NaN).
    fn max(self, a: Self::V, b: Self::V) -> Self::V;
    /// Bit `i` set when `a[i] ≤ b[i]` (false for NaN).
    fn le_bits(self, a: Self::V, b: Self::V) -> u32;
    /// The lanes as an array.
    fn to_array(self, v: Self::V) -> [f32; 8];
    /// `a + b` per lane.
    fn add(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a / b` per lane (IEEE division, as glam's `recip` and `/`).
    fn div(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a = b` per lane.
    fn eq(self, a: Self::V, b: Self::V) -> Self::M;
    /// `a ≠ b` per lane (true when either is NaN).
    fn ne(self, a: Self::V, b: Self::V) -> Self::M;
    /// `a < b` per lane.
    fn lt(self, a: Self::V, b: Self::V) -> Self::M;
    /// `a > b` per lane.
    fn gt(self, a: Self::V, b: Self::V) -> Self::M;
    /// `a ≤ b` per lane.
    fn le(self, a: Self::V, b: Self::V) -> Self::M;
    /// `a ≥ b` per lane.
    fn ge(self, a: Self::V, b: Self::V) -> Self::M;
    /// `a ∧ b`.
    fn and(self, a: Self::M, b: Self::M) -> Self::M;
    /// `a ∨ b`.
    fn or(self, a: Self::M, b: Self::M) -> Self::M;
    /// `¬a ∧ b`.
    fn and_not(self, a: Self::M, b: Self::M) -> Self::M;
    /// Bit `i` set when lane `i` of the mask is.
    fn bits(self, m: Self::M) -> u32;
    /// `m ? a : b` per lane.
    fn select(self, m: Self::M, a: Self::V, b: Self::V) -> Self::V;
}

/// Two 4-lane halves through glam: the baseline on every target.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Portable;

impl Lanes8 for Portable {
    type V = [Vec4; 2];
    type M = [BVec4A; 2];
    #[inline(always)]
    fn splat(self, x: f32) -> Self::V {
        [Vec4::splat(x); 2]
    }
    #[inline(always)]
    fn load(self, x: &[f32; 8]) -> Self::V {
        [
            Vec4::new(x[0], x[1], x[2], x[3]),
            Vec4::new(x[4], x[5], x[6], x[7]),
        ]
    }
    #[inline(always)]
    fn sub(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0] - b[0], a[1] - b[1]]
    }
    #[inline(always)]
    fn mul(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0] * b[0], a[1] * b[1]]
    }
    #[inline(always)]
    fn min(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0].min(b[0]), a[1].min(b[1])]
    }
    #[inline(always)]
    fn max(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0].max(b[0]), a[1].max(b[1])]
    }
    #[inline(always)]
    fn le_bits(self, a: Self::V, b: Self::V) -> u32 {
        a[0].cmple(b[0]).bitmask() | a[1].cmple(b[1]).bitmask() << 4
    }
    #[inline(always)]
    fn to_array(self, v: Self::V) -> [f32; 8] {
        let (a, b) = (v[0].to_array(), v[1].to_array());
        [a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]]
    }
    #[inline(always)]
    fn add(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0] + b[0], a[1] + b[1]]
    }
    #[inline(always)]
    fn div(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0] / b[0], a[1] / b[1]]
    }
    #[inline(always)]
    fn eq(self, a: Self::V, b: Self::V) -> Self::M {
        [a[0].cmpeq(b[0]), a[1].cmpeq(b[1])]
    }
    #[inline(always)]
    fn ne(self, a: Self::V, b: Self::V) -> Self::M {
        [a[0].cmpne(b[0]), a[1].cmpne(b[1])]
    }
    #[inline(always)]
    fn lt(self, a: Self::V, b: Self::V) -> Self::M {
        [a[0].cmplt(b[0]), a[1].cmplt(b[1])]
    }
    #[inline(always)]
    fn gt(self, a: Self::V, b: Self::V) -> Self::M {
        [a[0].cmpgt(b[0]), a[1].cmpgt(b[1])]
    }
    #[inline(always)]
    fn le(self, a: Self::V, b: Self::V) -> Self::M {
        [a[0].cmple(b[0]), a[1].cmple(b[1])]
    }
    #[inline(always)]
    fn ge(self, a: Self::V, b: Self::V) -> Self::M {
        [a[0].cmpge(b[0]), a[1].cmpge(b[1])]
    }
    #[inline(always)]
    fn and(self, a: Self::M, b: Self::M) -> Self::M {
        [a[0] & b[0], a[1] & b[1]]
    }
    #[inline(always)]
    fn or(self, a: Self::M, b: Self::M) -> Self::M {
        [a[0] | b[0], a[1] | b[1]]
    }
    #[inline(always)]
    fn and_not(self, a: Self::M, b: Self::M) -> Self::M {
        [!a[0] & b[0], !a[1] & b[1]]
    }
    #[inline(always)]
    fn bits(self, m: Self::M) -> u32 {
        m[0].bitmask() | m[1].bitmask() << 4
    }
    #[inline(always)]
    fn select(self, m: Self::M, a: Self::V, b: Self::V) -> Self::V {
        [
            Vec4::select(m[0], a[0], b[0]),
            Vec4::select(m[1], a[1], b[1]),
        ]
    }
}

/// AVX2 through pulp's `V3` token (x86-64 with AVX2 and FMA detected at run time).
#[cfg(target_arch = "x86_64")]
#[derive(Debug, Clone, Copy)]
pub(crate) struct Avx2(pulp::x86::V3);

#[cfg(target_arch = "x86_64")]
impl Lanes8 for Avx2 {
    type V = std::arch::x86_64::__m256;
    type M = std::arch::x86_64::__m256;
    #[inline(always)]
    fn splat(self, x: f32) -> Self::V {
        // (`_mm256_set1_ps` through pulp was left as a call per splat.)
        pulp::cast([x; 8])
    }
    #[inline(always)]
    fn load(self, x: &[f32; 8]) -> Self::V {
        pulp::cast(*x)
    }
    #[inline(always)]
    fn sub(self, a: Self::V, b: Self::V) -> Self::V {
        self.0.avx._mm256_sub_ps(a, b)
    }
    #[inline(always)]
    fn mul(self, a: Self::V, b: Self::V) -> Self::V {
        self.0.avx._mm256_mul_ps(a, b)
    }
    #[inline(always)]
    fn min(self, a: Self::V, b: Self::V) -> Self::V {
        self.0.avx._mm256_min_ps(a, b)
    }
    #[inline(always)]
    fn max(self, a: Self::V, b: Self::V) -> Self::V {
        self.0.avx._mm256_max_ps(a, b)
    }
    #[inline(always)]
    fn le_bits(self, a: Self::V, b: Self::V) -> u32 {
        use std::arch::x86_64::_CMP_LE_OQ;
        let m = self.0.avx._mm256_cmp_ps::<_CMP_LE_OQ>(a, b);
        self.0.avx._mm256_movemask_ps(m) as u32
    }
    #[inline(always)]
    fn to_array(self, v: Self::V) -> [f32; 8] {
        pulp::cast(v)
    }
    #[inline(always)]
    fn add(self, a: Self::V, b: Self::V) -> Self::V {
        self.0.avx._mm256_add_ps(a, b)
    }
    #[inline(always)]
    fn div(self, a: Self::V, b: Self::V) -> Self::V {
        self.0.avx._mm256_div_ps(a, b)
    }
    #[inline(always)]
    fn eq(self, a: Self::V, b: Self::V) -> Self::M {
        self.0
            .avx
            ._mm256_cmp_ps::<{ std::arch::x86_64::_CMP_EQ_OQ }>(a, b)
    }
    #[inline(always)]
    fn ne(self, a: Self::V, b: Self::V) -> Self::M {
        self.0
            .avx
            ._mm256_cmp_ps::<{ std::arch::x86_64::_CMP_NEQ_UQ }>(a, b)
    }
    #[inline(always)]
    fn lt(self, a: Self::V, b: Self::V) -> Self::M {
        self.0
            .avx
            ._mm256_cmp_ps::<{ std::arch::x86_64::_CMP_LT_OQ }>(a, b)
    }
    #[inline(always)]
    fn gt(self, a: Self::V, b: Self::V) -> Self::M {
        self.0
            .avx
            ._mm256_cmp_ps::<{ std::arch::x86_64::_CMP_GT_OQ }>(a, b)
    }
    #[inline(always)]
    fn le(self, a: Self::V, b: Self::V) -> Self::M {
        self.0
            .avx
            ._mm256_cmp_ps::<{ std::arch::x86_64::_CMP_LE_OQ }>(a, b)
    }
    #[inline(always)]
    fn ge(self, a: Self::V, b: Self::V) -> Self::M {
        self.0
            .avx
            ._mm256_cmp_ps::<{ std::arch::x86_64::_CMP_GE_OQ }>(a, b)
    }
    #[inline(always)]
    fn and(self, a: Self::M, b: Self::M) -> Self::M {
        self.0.avx._mm256_and_ps(a, b)
    }
    #[inline(always)]
    fn or(self, a: Self::M, b: Self::M) -> Self::M {
        self.0.avx._mm256_or_ps(a, b)
    }
    #[inline(always)]
    fn and_not(self, a: Self::M, b: Self::M) -> Self::M {
        self.0.avx._mm256_andnot_ps(a, b)
    }
    #[inline(always)]
    fn bits(self, m: Self::M) -> u32 {
        self.0.avx._mm256_movemask_ps(m) as u32
    }
    #[inline(always)]
    fn select(self, m: Self::M, a: Self::V, b: Self::V) -> Self::V {
        // Takes the second operand where the mask is set.
        self.0.avx._mm256_blendv_ps(b, a, m)
    }
}

/// Work to run on some [`Lanes8`]: what [`Simd8::dispatch`] takes.
pub(crate) trait WithLanes8 {
    /// The result.
    type Output;
    /// Runs the work on lanes `l`.
    fn run<L: Lanes8>(self, l: L) -> Self::Output;
}

/// How a tree computes its eight lanes, chosen once at build time.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Simd8 {
    /// AVX2 (and FMA, unused) detected.
    #[cfg(target_arch = "x86_64")]
    Avx2(pulp::x86::V3),
    /// Two 4-lane halves.
    Portable,
}

impl Simd8 {
    /// The widest lanes this processor has.
    pub(crate) fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        if let Some(v3) = pulp::x86::V3::try_new() {
            return Simd8::Avx2(v3);
        }
        Simd8::Portable
    }

    /// Runs `op` on these lanes; on the AVX2 path with AVX2 enabled for everything `op`
    /// inlines.
    #[inline(always)]
    pub(crate) fn dispatch<W: WithLanes8>(self, op: W) -> W::Output {
        match self {
            #[cfg(target_arch = "x86_64")]
            Simd8::Avx2(v3) => v3.vectorize(
                #[inline(always)]
                move || op.run(Avx2(v3)),
            ),
            Simd8::Portable => op.run(Portable),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every operation gives the same bits on both paths, NaN and infinities included.
    #[test]
    fn both_paths_agree_bit_for_bit() {
        struct Ops([f32; 8], [f32; 8]);
        impl WithLanes8 for Ops {
            type Output = ([[u32; 8]; 7], u32, [u32; 10]);
            fn run<L: Lanes8>(self, l: L) -> Self::Output {
                let (a, b) = (l.load(&self.0), l.load(&self.1));
                let bits = |v: L::V| l.to_array(v).map(f32::to_bits);
                let (lt, gt) = (l.lt(a, b), l.gt(a, b));
                (
                    [
                        bits(l.sub(a, b)),
                        bits(l.mul(a, l.splat(3.0))),
                        bits(l.min(a, b)),
                        bits(l.max(a, b)),
                        bits(l.add(a, b)),
                        bits(l.div(a, b)),
                        bits(l.select(lt, a, b)),
                    ],
                    l.le_bits(a, b),
                    [
                        l.bits(l.eq(a, b)),
                        l.bits(l.ne(a, b)),
                        l.bits(lt),
                        l.bits(gt),
                        l.bits(l.le(a, b)),
                        l.bits(l.ge(a, b)),
                        l.bits(l.and(lt, l.ne(a, b))),
                        l.bits(l.or(lt, gt)),
                        l.bits(l.and_not(lt, l.le(a, b))),
                        l.bits(l.and_not(gt, l.ne(a, b))),
                    ],
                )
            }
        }
        let a = [1.0, f32::NAN, -0.0, f32::INFINITY, 2.0, -3.0, 0.0, 5.0];
        let b = [2.0, 1.0, 0.0, f32::NEG_INFINITY, f32::NAN, -3.0, -0.0, 4.0];
        let want = Ops(a, b).run(Portable);
        assert_eq!(want.1, 0b0110_0101);
        // Lanes: 1 < 2, NaN, -0 = 0, ∞ > -∞, NaN, -3 = -3, 0 = -0, 5 > 4.
        assert_eq!(want.2[0], 0b0110_0100, "eq");
        assert_eq!(want.2[1], 0b1001_1011, "ne: true on NaN");
        assert_eq!(want.2[2], 0b0000_0001, "lt");
        assert_eq!(want.2[3], 0b1000_1000, "gt");
        assert_eq!(want.2[5], 0b1110_1100, "ge");
        assert_eq!(want.0[2][1], 1.0f32.to_bits(), "min takes b on NaN");
        let got = Simd8::detect().dispatch(Ops(a, b));
        assert_eq!(got, want);
    }
}
