//! Twin tests: each SSE2 and AVX2 kernel against its scalar twin, bit for
//! bit, on
//! texels of arbitrary bits (NaN payloads, infinities, subnormals, −0)
//! and on indices that include both ends of the slice; and the panics of
//! out-of-range indices.

use proptest::prelude::*;

use super::*;

/// Texels of arbitrary bit patterns, 2 to 64 of them.
fn any_texels() -> impl Strategy<Value = Vec<[f32; 4]>> {
    prop::collection::vec(any::<[u32; 4]>().prop_map(|t| t.map(f32::from_bits)), 2..=64)
}

/// Eight indices into a slice of `len`, each lane 0, len − 1 or anywhere.
fn any_indices(len: usize) -> impl Strategy<Value = [i32; 8]> {
    let last = len as i32 - 1;
    prop::array::uniform8(prop_oneof![Just(0), Just(last), 0..=last])
}

fn bits<const N: usize>(v: [[f32; 8]; N]) -> [[u32; 8]; N] {
    v.map(|c| c.map(f32::to_bits))
}

/// Texels and eight indices, every a[k] + 1 in range too.
fn texels_and_adjacent() -> impl Strategy<Value = (Vec<[f32; 4]>, [i32; 8])> {
    any_texels().prop_flat_map(|t| {
        let len = t.len();
        (Just(t), any_indices(len - 1))
    })
}

fn texels_and_pairs() -> impl Strategy<Value = (Vec<[f32; 4]>, [i32; 8], [i32; 8])> {
    any_texels().prop_flat_map(|t| {
        let len = t.len();
        (Just(t), any_indices(len), any_indices(len))
    })
}

/// The AVX2 token, or a note that this CPU cannot run the kernels (the
/// dispatching functions then run the twins, which the tests still check).
#[cfg(target_arch = "x86_64")]
fn avx2() -> Option<avx2::Avx2> {
    let token = avx2::detect();
    if token.is_none() {
        eprintln!("note: no AVX2 on this CPU; the AVX2 kernels are not tested");
    }
    token
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn texels_match_the_scalar_twin((texels, idx, _) in texels_and_pairs()) {
        let twin = bits(scalar::gather_texels_x8(&texels, idx));
        for (k, &i) in idx.iter().enumerate() {
            for c in 0..4 {
                prop_assert_eq!(twin[c][k], texels[i as usize][c].to_bits());
            }
        }
        prop_assert_eq!(bits(gather_texels_x8(&texels, idx)), twin);
        #[cfg(target_arch = "x86_64")]
        {
            prop_assert_eq!(bits(sse2::gather_texels_x8(&texels, idx)), twin);
            if let Some(avx2) = avx2() {
                prop_assert_eq!(bits(avx2.gather_texels_x8(&texels, idx)), twin);
            }
        }
    }

    #[test]
    fn texel_pairs_match_the_scalar_twin((texels, a, b) in texels_and_pairs()) {
        let twin = bits(scalar::gather_texel_pairs_x8(&texels, a, b));
        for k in 0..8 {
            for c in 0..4 {
                prop_assert_eq!(twin[c][k], texels[a[k] as usize][c].to_bits());
                prop_assert_eq!(twin[4 + c][k], texels[b[k] as usize][c].to_bits());
            }
        }
        prop_assert_eq!(bits(gather_texel_pairs_x8(&texels, a, b)), twin);
        #[cfg(target_arch = "x86_64")]
        {
            prop_assert_eq!(bits(sse2::gather_texel_pairs_x8(&texels, a, b)), twin);
            if let Some(avx2) = avx2() {
                prop_assert_eq!(bits(avx2.gather_texel_pairs_x8(&texels, a, b)), twin);
            }
        }
    }

    #[test]
    fn adjacent_texels_match_the_scalar_twin((texels, a) in texels_and_adjacent()) {
        let twin = bits(scalar::gather_adjacent_texels_x8(&texels, a));
        prop_assert_eq!(twin, bits(scalar::gather_texel_pairs_x8(&texels, a, a.map(|i| i + 1))));
        prop_assert_eq!(bits(gather_adjacent_texels_x8(&texels, a)), twin);
        #[cfg(target_arch = "x86_64")]
        {
            prop_assert_eq!(bits(sse2::gather_adjacent_texels_x8(&texels, a)), twin);
            if let Some(avx2) = avx2() {
                prop_assert_eq!(bits(avx2.gather_adjacent_texels_x8(&texels, a)), twin);
            }
        }
    }
}

/// The texels 0..len with channel c of texel i holding 4i + c.
fn numbered(len: usize) -> Vec<[f32; 4]> {
    (0..len).map(|i| std::array::from_fn(|c| (4 * i + c) as f32)).collect()
}

#[test]
fn lanes_and_channels_land_in_place() {
    let texels = numbered(20);
    let a = [3, 0, 19, 7, 7, 12, 1, 18];
    let b = [19, 18, 0, 1, 2, 3, 4, 5];
    let pairs = gather_texel_pairs_x8(&texels, a, b);
    let adjacent = gather_adjacent_texels_x8(&texels, a.map(|i| i.min(18)));
    for k in 0..8 {
        for c in 0..4 {
            assert_eq!(pairs[c][k], (4 * a[k] + c as i32) as f32);
            assert_eq!(pairs[4 + c][k], (4 * b[k] + c as i32) as f32);
            assert_eq!(adjacent[c][k], (4 * a[k].min(18) + c as i32) as f32);
            assert_eq!(adjacent[4 + c][k], (4 * a[k].min(18) + 4 + c as i32) as f32);
        }
    }
    assert_eq!(gather_texels_x8(&texels, b), [pairs[4], pairs[5], pairs[6], pairs[7]]);
}

#[test]
#[should_panic(expected = "out of bounds")]
fn a_negative_index_panics() {
    gather_texels_x8(&numbered(4), [0, 1, 2, 3, -1, 0, 0, 0]);
}

#[test]
#[should_panic(expected = "out of bounds")]
fn an_index_at_the_length_panics() {
    gather_texel_pairs_x8(&numbered(4), [0; 8], [0, 1, 2, 3, 4, 0, 0, 0]);
}

#[test]
#[should_panic(expected = "out of bounds")]
fn an_adjacent_pair_past_the_end_panics() {
    gather_adjacent_texels_x8(&numbered(4), [0, 1, 2, 3, 0, 0, 0, 0]);
}

#[test]
#[should_panic(expected = "out of bounds")]
fn the_largest_index_panics_without_wrapping() {
    gather_adjacent_texels_x8(&numbered(4), [i32::MAX; 8]);
}

#[test]
fn the_range_check_caps_the_length_at_2_pow_31() {
    #[cfg(target_arch = "x86_64")]
    {
        use crate::bounds::all_in_range;
        assert!(all_in_range(&[[0, 1, i32::MAX, 5, 0, 0, 0, 0]], usize::MAX));
        assert!(!all_in_range(&[[0, 1, i32::MIN, 5, 0, 0, 0, 0]], usize::MAX));
        assert!(!all_in_range(&[[0, 1, -1, 5, 0, 0, 0, 0]], usize::MAX));
        assert!(!all_in_range(&[[0; 8], [0, 0, 0, 0, 0, 0, 0, 4]], 4));
        assert!(all_in_range(&[[0; 8], [0, 0, 0, 0, 0, 0, 0, 3]], 4));
        assert!(!all_in_range(&[[0; 8]], 0));
    }
}

#[cfg(target_arch = "x86_64")]
proptest::proptest! {
    /// The AVX2 range check gives the scalar one's answer: indices drawn
    /// near 0, near the length, negative and at the i32 extremes, lengths
    /// from 0 past 2^32.
    #[test]
    fn the_vector_range_check_equals_the_scalar_one(
        picks in proptest::collection::vec(proptest::collection::vec((0usize..8, -3i64..3), 8), 1..4),
        len_pick in 0usize..8,
    ) {
        let lens = [0, 1, 4, 100, (1 << 31) - 1, 1 << 31, 1 << 32, usize::MAX];
        let len = lens[len_pick];
        let near = |base: i64, d: i64| (base + d).clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
        let idx: Vec<[i32; 8]> = picks
            .iter()
            .map(|row| {
                let mut lanes = [0; 8];
                for (lane, &(kind, d)) in lanes.iter_mut().zip(row) {
                    let len = len.min(i32::MAX as usize) as i64;
                    *lane = match kind {
                        0 => near(0, d),
                        1 => near(len, d),
                        2 => near(len / 2, d),
                        3 => near(i64::from(i32::MIN), d + 3),
                        4 => near(i64::from(i32::MAX), d - 3),
                        _ => near(0, d.abs()),
                    };
                }
                lanes
            })
            .collect();
        if let Some(avx2) = crate::avx2::token() {
            proptest::prop_assert_eq!(avx2.all_in_range(&idx, len), crate::bounds::all_in_range(&idx, len));
        }
    }
}

#[test]
fn the_environment_can_only_lower_the_instruction_set() {
    let current = Isa::current();
    assert!(current <= Isa::best(), "{current:?} above {:?}", Isa::best());
    if let Ok(name) = std::env::var("ZLINE_SIMD") {
        if let Some(wanted) = Isa::ALL.into_iter().find(|i| i.name() == name) {
            assert_eq!(current, wanted.min(Isa::best()));
        }
    } else {
        assert_eq!(current, Isa::best());
    }
    #[cfg(target_arch = "x86_64")]
    assert_eq!(Isa::best() >= Isa::Avx2, std::is_x86_feature_detected!("avx2"));
    #[cfg(target_arch = "x86_64")]
    {
        use std::is_x86_feature_detected as has;
        let v4 = has!("avx2")
            && has!("fma")
            && has!("avx512f")
            && has!("avx512vl")
            && has!("avx512bw")
            && has!("avx512dq");
        assert_eq!(Isa::best() == Isa::Avx512, v4);
    }
    #[cfg(target_arch = "x86_64")]
    assert!(Isa::best() >= Isa::Sse2);
    assert_eq!(Isa::ALL.map(Isa::name), ["scalar", "sse2", "avx2", "avx512"]);
}
