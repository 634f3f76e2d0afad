//! Lane functions built from the level's own operations: `wide`'s
//! algorithms, operation for operation, so that every level gives
//! `wide`'s bits while the x86-64-v3 and v4 levels run them as 256-bit
//! AVX2 instructions (`wide` itself, in the baseline's encoding, runs each
//! 8-lane integer step as two 128-bit halves).

use super::{f32x8, i32x8, Level};

impl<L: Level> f32x8<L> {
    /// log₂ x, bit for bit `wide`'s (its `ln` times log₂ e).
    ///
    /// The usual case — every lane a positive, normal, finite float, as the
    /// texture level of detail's footprints are — runs `wide`'s `ln` here
    /// with this level's operations: its fused multiply–adds are, like
    /// `wide`'s without the `fma` target feature, a product then a sum
    /// (Rust never fuses them). Any other lane (zero, subnormal, negative,
    /// infinite, NaN) sends the whole vector to `wide` itself, whose special
    /// cases define the result. On the textured floor's trilinear blocks
    /// this is about 45 fewer instructions a block than `wide`'s halves.
    #[inline(always)]
    pub fn log2(self) -> Self {
        let (one, half) = (Self::ONE, Self::splat(0.5));
        let bits: i32x8<L> = bytemuck::cast(self);
        // `wide`'s `fraction_2`: the mantissa with the exponent of 0.5.
        let x: Self = bytemuck::cast((bits & i32x8::splat(0x007F_FFFF)) | i32x8::splat(0x3F00_0000));
        // `wide`'s `exponent`, whose shift is logical: equal to this
        // arithmetic one for the lanes with the sign clear, the only ones
        // whose result is kept.
        let pow2_23 = Self::splat(8_388_608.0);
        let biased: Self = bytemuck::cast((bits >> 23) | bytemuck::cast::<Self, i32x8<L>>(pow2_23));
        let e = biased - (pow2_23 + Self::splat(127.0));
        let mask = x.cmp_gt(Self::splat(core::f32::consts::SQRT_2) * half);
        let x = (!mask).blend(x + x, x);
        let fe = mask.blend(e + one, e);
        let x = x - one;
        let res = polynomial_8(x, LN_POLYNOMIAL);
        let x2 = x * x;
        let res = x2 * x * res;
        let res = fe * Self::splat(LN2_LO) + res;
        let res = res + (x - x2 * half);
        let res = fe * Self::splat(LN2_HI) + res;
        let special = !self.is_finite() | self.cmp_lt(Self::splat(f32::MIN_POSITIVE));
        if special.any() {
            return Self::from_wide(self.to_wide().log2());
        }
        res * Self::splat(core::f32::consts::LOG2_E)
    }
}

/// `wide`'s coefficients of ln(1 + x)'s polynomial part and its split of
/// ln 2, as written there.
#[allow(clippy::excessive_precision, reason = "wide's literals, as written there")]
const LN_POLYNOMIAL: [f32; 9] = [
    3.3333331174E-1,
    -2.4999993993E-1,
    2.0000714765E-1,
    -1.6668057665E-1,
    1.4249322787E-1,
    -1.2420140846E-1,
    1.1676998740E-1,
    -1.1514610310E-1,
    7.0376836292E-2,
];
#[allow(clippy::excessive_precision, reason = "wide's literals, as written there")]
const LN2_HI: f32 = 0.693359375;
#[allow(clippy::excessive_precision, reason = "wide's literals, as written there")]
const LN2_LO: f32 = -2.12194440e-4;

/// `wide`'s `polynomial_8!`: c₀ + c₁x + … + c₈x⁸ in its Estrin order,
/// each `mul_add` a product then a sum.
#[inline(always)]
fn polynomial_8<L: Level>(x: f32x8<L>, c: [f32; 9]) -> f32x8<L> {
    let k = |i: usize| f32x8::<L>::splat(c[i]);
    let x2 = x * x;
    let x4 = x2 * x2;
    let x8 = x4 * x4;
    let high = x2 * (k(7) * x + k(6)) + (x * k(5) + k(4));
    let low = x8 * k(8) + (x2 * (x * k(3) + k(2)) + (x * k(1) + k(0)));
    x4 * high + low
}
