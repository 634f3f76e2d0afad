//! The x86-64-v3 lanes against the baseline ones (which are `wide`'s),
//! bit for bit, on random and special values.

use proptest::prelude::*;

use super::{f32x8, i32x8, Level};
use crate::{vectorize, Vectorized};

/// Values where implementations of float operations tend to differ.
const SPECIAL: [f32; 16] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::NAN,
    -f32::NAN,
    f32::MIN_POSITIVE,
    1.0e-40,
    -1.0e-40,
    2_147_483_648.0,
    -2_147_483_904.0,
    f32::MAX,
    8_388_608.5,
];

fn lane() -> impl Strategy<Value = f32> {
    prop_oneof![
        3 => any::<f32>(),
        2 => -1.0e4f32..1.0e4,
        2 => proptest::sample::select(SPECIAL.to_vec()),
    ]
}

/// Positive, normal and finite: the lanes `log2` computes itself.
fn positive_lane() -> impl Strategy<Value = f32> {
    prop_oneof![
        2 => f32::MIN_POSITIVE..f32::MAX,
        2 => 1.0e-3f32..1.0e3,
        // Both sides of `log2`'s √2/2 switch.
        1 => proptest::sample::select(vec![
            f32::MIN_POSITIVE,
            1.0,
            0.5,
            2.0,
            f32::MAX,
            core::f32::consts::FRAC_1_SQRT_2,
            f32::from_bits(core::f32::consts::FRAC_1_SQRT_2.to_bits() + 1),
        ]),
    ]
}

fn int_lane() -> impl Strategy<Value = i32> {
    prop_oneof![
        3 => any::<i32>(),
        2 => -300i32..300,
        1 => proptest::sample::select(vec![0, -1, 1, i32::MIN, i32::MAX, 31, 32, 33]),
    ]
}

/// Every operation's result as bits, at level `L`.
struct Ops {
    a: [f32; 8],
    /// Positive normal finite lanes (the usual inputs of `log2`).
    p: [f32; 8],
    b: [f32; 8],
    i: [i32; 8],
    j: [i32; 8],
    shift: i32,
}

fn bits(v: f32x8<impl Level>) -> [u32; 8] {
    v.to_array().map(f32::to_bits)
}

/// The bits of an arithmetic result, every NaN as the canonical quiet
/// NaN: Rust (and LLVM) leave the sign and payload of a NaN produced by
/// arithmetic unspecified — LLVM may swap the operands of a commutative
/// `fadd` — so two compilations of one expression may differ there and
/// nowhere else. zline never keeps a NaN's bits: every NaN that reaches a
/// pixel becomes 0 (SPEC §10).
fn num(v: f32x8<impl Level>) -> [u32; 8] {
    v.to_array().map(|x| if x.is_nan() { f32::NAN.to_bits() } else { x.to_bits() })
}

impl Vectorized for &Ops {
    type Output = Vec<[u32; 8]>;

    #[inline(always)]
    fn run<L: Level>(self) -> Vec<[u32; 8]> {
        let a = f32x8::<L>::from(self.a);
        let b = f32x8::<L>::from(self.b);
        let i = i32x8::<L>::from(self.i);
        let j = i32x8::<L>::from(self.j);
        let m = a.cmp_lt(b);
        let k = i.cmp_gt(j);
        let ib = |v: i32x8<L>| v.to_array().map(|x| x as u32);
        vec![
            bits(f32x8::<L>::splat(self.a[3])),
            num(a + b),
            num(a - b),
            num(a * b),
            num(a / b),
            num(a + 0.25),
            num(2.0 - a),
            num(-a),
            bits(a & b),
            bits(a | b),
            bits(a ^ b),
            bits(!a),
            bits(a.cmp_eq(b)),
            bits(a.cmp_lt(b)),
            bits(a.cmp_le(b)),
            bits(a.cmp_gt(b)),
            bits(a.cmp_ge(b)),
            bits(m.blend(a, b)),
            bits(a.abs()),
            num(a.floor()),
            num(a.ceil()),
            bits(a.fast_max(b)),
            bits(a.fast_min(b)),
            bits(a.max(b)),
            bits(a.min(b)),
            bits(a.is_nan()),
            bits(a.is_finite()),
            num(a.sqrt()),
            num(a.log2()),
            num(f32x8::<L>::from(self.p).log2()),
            [m.move_mask() as u32, u32::from(m.any()), u32::from(m.all()), u32::from(m.none()), 0, 0, 0, 0],
            ib(a.fast_trunc_int()),
            ib(a.trunc_int()),
            bits(f32x8::<L>::from_i32x8(i)),
            ib(i32x8::<L>::splat(self.i[5])),
            ib(i + j),
            ib(i - j),
            ib(i * j),
            ib(i + 7),
            ib(i - 7),
            ib(i * 3),
            ib(-i),
            ib(i & j),
            ib(i | j),
            ib(i ^ j),
            ib(!i),
            ib(i << self.shift),
            ib(i >> self.shift),
            ib(i.cmp_eq(j)),
            ib(i.cmp_gt(j)),
            ib(i.cmp_lt(j)),
            ib(k.blend(i, j)),
            ib(i.max(j)),
            ib(i.min(j)),
            [k.move_mask() as u32, u32::from(k.any()), u32::from(k.all()), u32::from(k.none()), 0, 0, 0, 0],
        ]
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn v3_and_v4_lanes_equal_baseline_lanes(
        a in proptest::array::uniform8(lane()),
        b in proptest::array::uniform8(lane()),
        p in proptest::array::uniform8(positive_lane()),
        i in proptest::array::uniform8(int_lane()),
        j in proptest::array::uniform8(int_lane()),
        shift in 0i32..40,
    ) {
        let ops = Ops { a, p, b, i, j, shift };
        let base = (&ops).run::<super::Baseline>();
        let levels = every_level(&ops);
        for (level, got) in &levels {
            for (k, (x, y)) in base.iter().zip(got).enumerate() {
                prop_assert_eq!(
                    x, y, "{}: operation {} differs (a = {:?}, b = {:?}, i = {:?}, j = {:?})", level, k, a, b, i, j
                );
            }
        }
    }
}

/// `job` at the best level and at each level above the baseline that the
/// CPU has, with the level's name.
fn every_level<J: Vectorized + Copy>(job: J) -> Vec<(&'static str, J::Output)> {
    let mut levels = vec![("best", vectorize(job))];
    #[cfg(target_arch = "x86_64")]
    {
        if let Some(v3) = crate::avx2::v3_token() {
            levels.push(("v3", v3.vectorize(job)));
        }
        if let Some(v4) = crate::avx2::v4_token() {
            levels.push(("v4", v4.vectorize(job)));
        }
    }
    levels
}

/// `a.clamp(lo, hi)` and `a.max(lo).min(hi)` per lane pair, at level `L`.
struct Clamp {
    a: [f32; 8],
    lo: [f32; 8],
    hi: [f32; 8],
}

impl Vectorized for &Clamp {
    type Output = ([u32; 8], [u32; 8]);

    #[inline(always)]
    fn run<L: Level>(self) -> ([u32; 8], [u32; 8]) {
        let (a, lo, hi) = (f32x8::<L>::from(self.a), f32x8::<L>::from(self.lo), f32x8::<L>::from(self.hi));
        (bits(a.clamp(lo, hi)), bits(a.max(lo).min(hi)))
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1024))]

    /// `clamp` is `max` then `min`, bit for bit (signed zeros, NaN,
    /// infinities), for bounds that are not NaN, at every level.
    #[test]
    fn clamp_is_max_then_min_for_bounds_that_are_not_nan(
        a in proptest::array::uniform8(lane()),
        lo in proptest::array::uniform8(lane().prop_filter("not NaN", |x| !x.is_nan())),
        hi in proptest::array::uniform8(lane().prop_filter("not NaN", |x| !x.is_nan())),
    ) {
        let job = Clamp { a, lo, hi };
        let mut levels = every_level(&job);
        levels.push(("baseline", (&job).run::<super::Baseline>()));
        for (level, (got, want)) in levels {
            prop_assert_eq!(got, want, "{}: clamp of {:?} to {:?}..{:?}", level, a, lo, hi);
        }
    }
}

/// `log2` of the lanes, at level `L`.
struct Log2([f32; 8]);

impl Vectorized for &Log2 {
    type Output = [u32; 8];

    #[inline(always)]
    fn run<L: Level>(self) -> [u32; 8] {
        num(f32x8::<L>::from(self.0).log2())
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2048))]

    /// `log2` computes `wide`'s polynomial with each level's operations:
    /// the baseline's lanes must be `wide`'s own, not only equal to the
    /// other levels'.
    #[test]
    fn log2_is_wides_at_every_level(
        a in proptest::array::uniform8(lane()),
        p in proptest::array::uniform8(positive_lane()),
    ) {
        for x in [a, p] {
            let want = num(f32x8::<super::Baseline>::from_wide(wide::f32x8::from(x).log2()));
            let job = Log2(x);
            let mut levels = every_level(&job);
            levels.push(("baseline", (&job).run::<super::Baseline>()));
            for (level, got) in levels {
                prop_assert_eq!(got, want, "{}: log2 of {:?}", level, x);
            }
        }
    }
}

#[test]
fn the_v3_level_is_used_where_the_cpu_has_it() {
    // Where the CPU has AVX2 and FMA the property above compares two
    // different code paths; say so, so a run on an older CPU is visible.
    if !crate::v3_available() {
        eprintln!("note: no AVX2/FMA (or ZLINE_SIMD lowers it): the x86-64-v3 lanes are not exercised");
    }
    if !crate::v4_available() {
        eprintln!("note: no AVX-512 (or ZLINE_SIMD lowers it): the x86-64-v4 level is not exercised");
    }
}
