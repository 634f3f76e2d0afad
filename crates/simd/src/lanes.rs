//! Eight-lane vectors whose instruction set is a type parameter: the
//! kernels' arithmetic, compiled once per [`Level`] from one source.
//!
//! [`f32x8<L>`](f32x8) and [`i32x8<L>`](i32x8) have the API of `wide`'s
//! types of the same names (the subset zline uses) and the same results,
//! bit for bit: at [`Baseline`] every operation *is* `wide`'s (SSE2 halves
//! on a plain x86-64 build, AVX where the build targets it, NEON or scalar
//! elsewhere), and at the x86-64-v3 level every operation is one or a few
//! AVX2 instructions chosen so that the lanes equal `wide`'s (the tests
//! compare them on random and special values: NaN, infinities, signed
//! zeros, subnormals, the ends of the integer range).
//!
//! The x86-64-v3 and v4 levels have no public name. Code generic over `L:
//! Level` gets them only from [`crate::vectorize`], which instantiates a job
//! with one after run-time detection found AVX2 and FMA (and AVX-512 for
//! v4), and calls that instantiation from a `#[target_feature]` function so
//! that the job's inlined body is compiled for those instructions (or from
//! [`crate::dispatch`] and [`crate::vectorize_at`], after the same
//! detection). That is the soundness argument of every `unsafe` block here:
//! a function that runs with `L::V3` true runs in a process whose CPU has
//! AVX2 and FMA (v4 uses v3's intrinsics).
//!
//! Storage is `wide`'s: `f32x8<L>` is `#[repr(transparent)]` over
//! `wide::f32x8` (32 bytes, aligned to 32), so buffers of `wide` vectors
//! are read and written at any level with [`f32x8::from_wide`] and
//! [`f32x8::to_wide`] at no cost.

#![allow(non_camel_case_types, reason = "the names of `wide`'s types, which these replace")]

use core::marker::PhantomData;
use core::ops::{
    Add, AddAssign, BitAnd, BitOr, BitXor, Div, DivAssign, Mul, MulAssign, Neg, Not, Shl, Shr, Sub, SubAssign,
};

#[cfg(target_arch = "x86_64")]
use core::arch::x86_64::*;

use bytemuck::{Pod, Zeroable};

mod level;
mod math;

pub(crate) use level::private;
pub use level::{Baseline, Level};

/// `$v3` (an expression using AVX2 intrinsics) at the x86-64-v3 level,
/// `$base` otherwise.
macro_rules! at_level {
    ($v3:expr, $base:expr) => {{
        #[cfg(target_arch = "x86_64")]
        if L::V3 {
            // SAFETY: `L::V3` is true only for the levels (v3, v4) that
            // `crate::vectorize` and `crate::dispatch` instantiate after
            // they detected AVX2 and FMA (module docs), so the CPU has these instructions.
            #[allow(unused_unsafe, reason = "some intrinsics are safe to call in an AVX2 context")]
            return unsafe { $v3 };
        }
        $base
    }};
}

/// Eight `f32` lanes at level `L` (`wide::f32x8`'s API and results).
#[derive(Clone, Copy, Default, PartialEq, Debug)]
#[repr(transparent)]
pub struct f32x8<L: Level = Baseline> {
    w: wide::f32x8,
    level: PhantomData<L>,
}

/// Eight `i32` lanes at level `L` (`wide::i32x8`'s API and results).
#[derive(Clone, Copy, Default, PartialEq, Eq, Debug)]
#[repr(transparent)]
pub struct i32x8<L: Level = Baseline> {
    w: wide::i32x8,
    level: PhantomData<L>,
}

// SAFETY: `#[repr(transparent)]` over `wide`'s Pod types (a zero-sized
// PhantomData beside them); every bit pattern is a valid value, and
// creating a value executes no instruction of its level.
unsafe impl<L: Level> Zeroable for f32x8<L> {}
// SAFETY: as above.
unsafe impl<L: Level> Pod for f32x8<L> {}
// SAFETY: as above.
unsafe impl<L: Level> Zeroable for i32x8<L> {}
// SAFETY: as above.
unsafe impl<L: Level> Pod for i32x8<L> {}

#[cfg(target_arch = "x86_64")]
impl<L: Level> f32x8<L> {
    #[inline(always)]
    fn m(self) -> __m256 {
        bytemuck::cast(self.w)
    }
    #[inline(always)]
    fn from_m(m: __m256) -> Self {
        Self::from_wide(bytemuck::cast(m))
    }
}

#[cfg(target_arch = "x86_64")]
impl<L: Level> i32x8<L> {
    #[inline(always)]
    fn m(self) -> __m256i {
        bytemuck::cast(self.w)
    }
    #[inline(always)]
    fn from_m(m: __m256i) -> Self {
        Self::from_wide(bytemuck::cast(m))
    }
}

impl<L: Level> f32x8<L> {
    /// All lanes 0.
    pub const ZERO: Self = Self::from_wide(wide::f32x8::ZERO);
    /// All lanes 1.
    pub const ONE: Self = Self::from_wide(wide::f32x8::ONE);

    /// The vector stored as `wide`'s.
    #[inline(always)]
    pub const fn from_wide(w: wide::f32x8) -> Self {
        Self { w, level: PhantomData }
    }

    /// The vector as `wide`'s, for storage.
    #[inline(always)]
    pub const fn to_wide(self) -> wide::f32x8 {
        self.w
    }

    /// The same lanes at level `M` (no instruction: storage is shared).
    #[inline(always)]
    pub const fn at<M: Level>(self) -> f32x8<M> {
        f32x8::from_wide(self.w)
    }

    /// The lanes of `array`.
    #[inline(always)]
    pub const fn new(array: [f32; 8]) -> Self {
        Self::from_wide(wide::f32x8::new(array))
    }

    /// `v` in every lane.
    #[inline(always)]
    pub fn splat(v: f32) -> Self {
        at_level!(Self::from_m(_mm256_set1_ps(v)), Self::from_wide(wide::f32x8::splat(v)))
    }

    /// The lanes as an array.
    #[inline(always)]
    pub fn to_array(self) -> [f32; 8] {
        bytemuck::cast(self.w)
    }

    /// The lanes as an array, by reference.
    #[inline(always)]
    pub fn as_array_ref(&self) -> &[f32; 8] {
        bytemuck::cast_ref(&self.w)
    }

    /// The lanes as a mutable array.
    #[inline(always)]
    pub fn as_array_mut(&mut self) -> &mut [f32; 8] {
        bytemuck::cast_mut(&mut self.w)
    }

    /// Each lane of `v` converted (rounded to nearest even where inexact).
    #[inline(always)]
    pub fn from_i32x8(v: i32x8<L>) -> Self {
        at_level!(Self::from_m(_mm256_cvtepi32_ps(v.m())), Self::from_wide(wide::f32x8::from_i32x8(v.w)))
    }

    /// `t` where the lane of `self` is all ones, `f` where it is zero
    /// (lanes of `self` are masks: all ones or all zeros).
    #[inline(always)]
    pub fn blend(self, t: Self, f: Self) -> Self {
        at_level!(
            Self::from_m(_mm256_blendv_ps(f.m(), t.m(), self.m())),
            Self::from_wide(self.w.blend(t.w, f.w))
        )
    }

    /// |x| (the sign bit cleared).
    #[inline(always)]
    pub fn abs(self) -> Self {
        at_level!(
            Self::from_m(_mm256_and_ps(self.m(), _mm256_castsi256_ps(_mm256_set1_epi32(i32::MAX)))),
            Self::from_wide(self.w.abs())
        )
    }

    /// ⌊x⌋.
    #[inline(always)]
    pub fn floor(self) -> Self {
        at_level!(Self::from_m(_mm256_floor_ps(self.m())), Self::from_wide(self.w.floor()))
    }

    /// ⌈x⌉.
    #[inline(always)]
    pub fn ceil(self) -> Self {
        at_level!(Self::from_m(_mm256_ceil_ps(self.m())), Self::from_wide(self.w.ceil()))
    }

    /// `maxps`: `rhs` when either lane is NaN.
    #[inline(always)]
    pub fn fast_max(self, rhs: Self) -> Self {
        at_level!(Self::from_m(_mm256_max_ps(self.m(), rhs.m())), Self::from_wide(self.w.fast_max(rhs.w)))
    }

    /// `minps`: `rhs` when either lane is NaN.
    #[inline(always)]
    pub fn fast_min(self, rhs: Self) -> Self {
        at_level!(Self::from_m(_mm256_min_ps(self.m(), rhs.m())), Self::from_wide(self.w.fast_min(rhs.w)))
    }

    /// The larger lane; `self` where `rhs` is NaN.
    #[inline(always)]
    pub fn max(self, rhs: Self) -> Self {
        at_level!(rhs.is_nan().blend(self, self.fast_max(rhs)), Self::from_wide(self.w.max(rhs.w)))
    }

    /// The smaller lane; `self` where `rhs` is NaN.
    #[inline(always)]
    pub fn min(self, rhs: Self) -> Self {
        at_level!(rhs.is_nan().blend(self, self.fast_min(rhs)), Self::from_wide(self.w.min(rhs.w)))
    }

    /// `self.max(lo).min(hi)` (NaN becomes `lo`) for bounds that are not
    /// NaN, in two instructions: `max` and `min` test their right-hand
    /// lanes for NaN, which bounds never are, so `fast_max` and `fast_min`
    /// give the same bits (a property test holds them to it at every
    /// level). With the tests, a shading kernel's final clamp to [0, 1]
    /// cost about ten more instructions a block at v4. A NaN bound gives
    /// unspecified (but not undefined) lanes.
    #[inline(always)]
    pub fn clamp(self, lo: Self, hi: Self) -> Self {
        self.fast_max(lo).fast_min(hi)
    }

    /// All ones where the lane is NaN.
    #[inline(always)]
    pub fn is_nan(self) -> Self {
        at_level!(
            Self::from_m(_mm256_cmp_ps::<_CMP_UNORD_Q>(self.m(), self.m())),
            Self::from_wide(self.w.is_nan())
        )
    }

    /// All ones where the lane is neither infinite nor NaN.
    #[inline(always)]
    pub fn is_finite(self) -> Self {
        at_level!(
            {
                let exp = _mm256_set1_epi32(0xFF00_0000_u32 as i32);
                let shifted = _mm256_and_si256(_mm256_slli_epi32::<1>(_mm256_castps_si256(self.m())), exp);
                let inf_or_nan = _mm256_cmpeq_epi32(shifted, exp);
                Self::from_m(_mm256_castsi256_ps(_mm256_xor_si256(inf_or_nan, _mm256_set1_epi32(-1))))
            },
            Self::from_wide(self.w.is_finite())
        )
    }

    /// √x, correctly rounded.
    #[inline(always)]
    pub fn sqrt(self) -> Self {
        at_level!(Self::from_m(_mm256_sqrt_ps(self.m())), Self::from_wide(self.w.sqrt()))
    }

    /// The lanes' sign bits, lane k in bit k.
    #[inline(always)]
    pub fn move_mask(self) -> i32 {
        at_level!(_mm256_movemask_ps(self.m()), self.w.move_mask())
    }

    /// eˣ, `wide`'s polynomial at every level (its operations in the
    /// baseline's encoding; one source, so the same bits).
    #[inline(always)]
    pub fn exp(self) -> Self {
        Self::from_wide(self.w.exp())
    }

    /// True when any lane's sign bit is set.
    #[inline(always)]
    pub fn any(self) -> bool {
        self.move_mask() != 0
    }

    /// True when every lane's sign bit is set.
    #[inline(always)]
    pub fn all(self) -> bool {
        self.move_mask() == 0xFF
    }

    /// True when no lane's sign bit is set.
    #[inline(always)]
    pub fn none(self) -> bool {
        !self.any()
    }

    /// `cvttps2dq`: truncation; NaN and out-of-range lanes give `i32::MIN`.
    #[inline(always)]
    pub fn fast_trunc_int(self) -> i32x8<L> {
        at_level!(i32x8::from_m(_mm256_cvttps_epi32(self.m())), i32x8::from_wide(self.w.fast_trunc_int()))
    }

    /// Truncation saturating like `as i32`'s ends: NaN gives 0, lanes at or
    /// above 2³¹ give `i32::MAX`, lanes below −2³¹ `i32::MIN`.
    #[inline(always)]
    pub fn trunc_int(self) -> i32x8<L> {
        at_level!(
            {
                let m = self.m();
                let non_nan = _mm256_and_ps(m, _mm256_cmp_ps::<_CMP_EQ_OQ>(m, m));
                let flip =
                    _mm256_castps_si256(_mm256_cmp_ps::<_CMP_GE_OQ>(m, _mm256_set1_ps(2_147_483_648.0)));
                i32x8::from_m(_mm256_xor_si256(flip, _mm256_cvttps_epi32(non_nan)))
            },
            i32x8::from_wide(self.w.trunc_int())
        )
    }

    /// All ones where the lanes are equal (ordered).
    #[inline(always)]
    pub fn cmp_eq(self, rhs: Self) -> Self {
        at_level!(
            Self::from_m(_mm256_cmp_ps::<_CMP_EQ_OQ>(self.m(), rhs.m())),
            Self::from_wide(wide::CmpEq::cmp_eq(self.w, rhs.w))
        )
    }

    /// All ones where `self` < `rhs` (ordered).
    #[inline(always)]
    pub fn cmp_lt(self, rhs: Self) -> Self {
        at_level!(
            Self::from_m(_mm256_cmp_ps::<_CMP_LT_OQ>(self.m(), rhs.m())),
            Self::from_wide(wide::CmpLt::cmp_lt(self.w, rhs.w))
        )
    }

    /// All ones where `self` ≤ `rhs` (ordered).
    #[inline(always)]
    pub fn cmp_le(self, rhs: Self) -> Self {
        at_level!(
            Self::from_m(_mm256_cmp_ps::<_CMP_LE_OQ>(self.m(), rhs.m())),
            Self::from_wide(wide::CmpLe::cmp_le(self.w, rhs.w))
        )
    }

    /// All ones where `self` > `rhs` (ordered).
    #[inline(always)]
    pub fn cmp_gt(self, rhs: Self) -> Self {
        at_level!(
            Self::from_m(_mm256_cmp_ps::<_CMP_GT_OQ>(self.m(), rhs.m())),
            Self::from_wide(wide::CmpGt::cmp_gt(self.w, rhs.w))
        )
    }

    /// All ones where `self` ≥ `rhs` (ordered).
    #[inline(always)]
    pub fn cmp_ge(self, rhs: Self) -> Self {
        at_level!(
            Self::from_m(_mm256_cmp_ps::<_CMP_GE_OQ>(self.m(), rhs.m())),
            Self::from_wide(wide::CmpGe::cmp_ge(self.w, rhs.w))
        )
    }
}

impl<L: Level> From<[f32; 8]> for f32x8<L> {
    #[inline(always)]
    fn from(a: [f32; 8]) -> Self {
        Self::new(a)
    }
}

impl<L: Level> From<f32> for f32x8<L> {
    #[inline(always)]
    fn from(v: f32) -> Self {
        Self::splat(v)
    }
}

/// Binary operators of `f32x8<L>`: vector–vector, vector–scalar and
/// scalar–vector, with their assigning forms.
macro_rules! f32_binary {
    ($($Op:ident $op:ident $OpAssign:ident $op_assign:ident $intr:ident;)*) => {$(
        impl<L: Level> $Op for f32x8<L> {
            type Output = Self;
            #[inline(always)]
            fn $op(self, rhs: Self) -> Self {
                at_level!(Self::from_m($intr(self.m(), rhs.m())), Self::from_wide($Op::$op(self.w, rhs.w)))
            }
        }
        impl<L: Level> $Op<f32> for f32x8<L> {
            type Output = Self;
            #[inline(always)]
            fn $op(self, rhs: f32) -> Self {
                $Op::$op(self, Self::splat(rhs))
            }
        }
        impl<L: Level> $Op<f32x8<L>> for f32 {
            type Output = f32x8<L>;
            #[inline(always)]
            fn $op(self, rhs: f32x8<L>) -> f32x8<L> {
                $Op::$op(f32x8::splat(self), rhs)
            }
        }
        impl<L: Level> $OpAssign for f32x8<L> {
            #[inline(always)]
            fn $op_assign(&mut self, rhs: Self) {
                *self = $Op::$op(*self, rhs);
            }
        }
    )*};
}

f32_binary! {
    Add add AddAssign add_assign _mm256_add_ps;
    Sub sub SubAssign sub_assign _mm256_sub_ps;
    Mul mul MulAssign mul_assign _mm256_mul_ps;
    Div div DivAssign div_assign _mm256_div_ps;
}

/// Bitwise operators shared by both lane types.
macro_rules! bitwise {
    ($T:ident, $($Op:ident $op:ident $intr:ident;)*) => {$(
        impl<L: Level> $Op for $T<L> {
            type Output = Self;
            #[inline(always)]
            fn $op(self, rhs: Self) -> Self {
                at_level!(Self::from_m($intr(self.m(), rhs.m())), Self::from_wide($Op::$op(self.w, rhs.w)))
            }
        }
    )*};
}

bitwise! { f32x8,
    BitAnd bitand _mm256_and_ps;
    BitOr bitor _mm256_or_ps;
    BitXor bitxor _mm256_xor_ps;
}

bitwise! { i32x8,
    BitAnd bitand _mm256_and_si256;
    BitOr bitor _mm256_or_si256;
    BitXor bitxor _mm256_xor_si256;
    Add add _mm256_add_epi32;
    Sub sub _mm256_sub_epi32;
    Mul mul _mm256_mullo_epi32;
}

impl<L: Level> Neg for f32x8<L> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        at_level!(Self::from_m(_mm256_sub_ps(_mm256_setzero_ps(), self.m())), Self::from_wide(-self.w))
    }
}

impl<L: Level> Not for f32x8<L> {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        at_level!(
            Self::from_m(_mm256_xor_ps(self.m(), _mm256_castsi256_ps(_mm256_set1_epi32(-1)))),
            Self::from_wide(!self.w)
        )
    }
}

impl<L: Level> Not for i32x8<L> {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        at_level!(Self::from_m(_mm256_xor_si256(self.m(), _mm256_set1_epi32(-1))), Self::from_wide(!self.w))
    }
}

impl<L: Level> Neg for i32x8<L> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        at_level!(Self::from_m(_mm256_sub_epi32(_mm256_setzero_si256(), self.m())), Self::from_wide(-self.w))
    }
}

impl<L: Level> Add<i32> for i32x8<L> {
    type Output = Self;
    #[inline(always)]
    fn add(self, rhs: i32) -> Self {
        self + Self::splat(rhs)
    }
}

impl<L: Level> Sub<i32> for i32x8<L> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, rhs: i32) -> Self {
        self - Self::splat(rhs)
    }
}

impl<L: Level> Mul<i32> for i32x8<L> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, rhs: i32) -> Self {
        self * Self::splat(rhs)
    }
}

impl<L: Level> AddAssign for i32x8<L> {
    #[inline(always)]
    fn add_assign(&mut self, rhs: Self) {
        *self = *self + rhs;
    }
}

impl<L: Level> Shl<i32> for i32x8<L> {
    type Output = Self;
    /// Every lane shifted left by `rhs` (0 when `rhs` is 32 or more).
    #[inline(always)]
    fn shl(self, rhs: i32) -> Self {
        at_level!(
            Self::from_m(_mm256_sll_epi32(self.m(), _mm_cvtsi64_si128(i64::from(rhs)))),
            Self::from_wide(self.w << rhs)
        )
    }
}

impl<L: Level> Shr<i32> for i32x8<L> {
    type Output = Self;
    /// Every lane shifted right arithmetically by `rhs` (the sign in every
    /// bit when `rhs` is 32 or more).
    #[inline(always)]
    fn shr(self, rhs: i32) -> Self {
        at_level!(
            Self::from_m(_mm256_sra_epi32(self.m(), _mm_cvtsi64_si128(i64::from(rhs)))),
            Self::from_wide(self.w >> rhs)
        )
    }
}

impl<L: Level> i32x8<L> {
    /// All lanes 0.
    pub const ZERO: Self = Self::from_wide(wide::i32x8::ZERO);

    /// The vector stored as `wide`'s.
    #[inline(always)]
    pub const fn from_wide(w: wide::i32x8) -> Self {
        Self { w, level: PhantomData }
    }

    /// The vector as `wide`'s, for storage.
    #[inline(always)]
    pub const fn to_wide(self) -> wide::i32x8 {
        self.w
    }

    /// The same lanes at level `M` (no instruction: storage is shared).
    #[inline(always)]
    pub const fn at<M: Level>(self) -> i32x8<M> {
        i32x8::from_wide(self.w)
    }

    /// The lanes of `array`.
    #[inline(always)]
    pub fn new(array: [i32; 8]) -> Self {
        Self::from_wide(wide::i32x8::new(array))
    }

    /// `v` in every lane.
    #[inline(always)]
    pub fn splat(v: i32) -> Self {
        at_level!(Self::from_m(_mm256_set1_epi32(v)), Self::from_wide(wide::i32x8::splat(v)))
    }

    /// The lanes as an array.
    #[inline(always)]
    pub fn to_array(self) -> [i32; 8] {
        bytemuck::cast(self.w)
    }

    /// The lanes as an array, by reference.
    #[inline(always)]
    pub fn as_array_ref(&self) -> &[i32; 8] {
        bytemuck::cast_ref(&self.w)
    }

    /// `t` where the lane of `self` is all ones, `f` where it is zero.
    #[inline(always)]
    pub fn blend(self, t: Self, f: Self) -> Self {
        at_level!(
            Self::from_m(_mm256_blendv_epi8(f.m(), t.m(), self.m())),
            Self::from_wide(self.w.blend(t.w, f.w))
        )
    }

    /// The larger lane.
    #[inline(always)]
    pub fn max(self, rhs: Self) -> Self {
        at_level!(Self::from_m(_mm256_max_epi32(self.m(), rhs.m())), Self::from_wide(self.w.max(rhs.w)))
    }

    /// The smaller lane.
    #[inline(always)]
    pub fn min(self, rhs: Self) -> Self {
        at_level!(Self::from_m(_mm256_min_epi32(self.m(), rhs.m())), Self::from_wide(self.w.min(rhs.w)))
    }

    /// All ones where the lanes are equal.
    #[inline(always)]
    pub fn cmp_eq(self, rhs: Self) -> Self {
        at_level!(
            Self::from_m(_mm256_cmpeq_epi32(self.m(), rhs.m())),
            Self::from_wide(wide::CmpEq::cmp_eq(self.w, rhs.w))
        )
    }

    /// All ones where `self` > `rhs`.
    #[inline(always)]
    pub fn cmp_gt(self, rhs: Self) -> Self {
        at_level!(
            Self::from_m(_mm256_cmpgt_epi32(self.m(), rhs.m())),
            Self::from_wide(wide::CmpGt::cmp_gt(self.w, rhs.w))
        )
    }

    /// All ones where `self` < `rhs`.
    #[inline(always)]
    pub fn cmp_lt(self, rhs: Self) -> Self {
        at_level!(
            Self::from_m(_mm256_cmpgt_epi32(rhs.m(), self.m())),
            Self::from_wide(wide::CmpLt::cmp_lt(self.w, rhs.w))
        )
    }

    /// The lanes' sign bits, lane k in bit k.
    #[inline(always)]
    pub fn move_mask(self) -> i32 {
        at_level!(_mm256_movemask_ps(_mm256_castsi256_ps(self.m())), self.w.move_mask())
    }

    /// True when any lane's sign bit is set.
    #[inline(always)]
    pub fn any(self) -> bool {
        self.move_mask() != 0
    }

    /// True when every lane's sign bit is set.
    #[inline(always)]
    pub fn all(self) -> bool {
        self.move_mask() == 0xFF
    }

    /// True when no lane's sign bit is set.
    #[inline(always)]
    pub fn none(self) -> bool {
        !self.any()
    }
}

impl<L: Level> From<[i32; 8]> for i32x8<L> {
    #[inline(always)]
    fn from(a: [i32; 8]) -> Self {
        Self::new(a)
    }
}

impl<L: Level> From<i32> for i32x8<L> {
    #[inline(always)]
    fn from(v: i32) -> Self {
        Self::splat(v)
    }
}

#[cfg(test)]
mod tests;
