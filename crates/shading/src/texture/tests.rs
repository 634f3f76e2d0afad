//! Tests of texture storage and sampling (SPEC §7), values computed by hand.
use super::*;
use proptest::prelude::*;

/// Tolerance for expected values written as decimals or byte fractions:
/// byte/255 and the filter weights round in f32, so results differ from
/// the exact value by a few ulps (f32::EPSILON ≈ 1.2e-7 at 1.0).
const TOL: f32 = 1e-6;

fn sampler(filter: Filter, wrap: Wrap) -> Sampler {
    Sampler { filter, wrap_s: wrap, wrap_t: wrap }
}

const NEAREST: Sampler = Sampler { filter: Filter::Nearest, wrap_s: Wrap::Repeat, wrap_t: Wrap::Repeat };
const BILINEAR: Sampler = Sampler { filter: Filter::Bilinear, wrap_s: Wrap::Repeat, wrap_t: Wrap::Repeat };
const TRILINEAR: Sampler = Sampler { filter: Filter::Trilinear, wrap_s: Wrap::Repeat, wrap_t: Wrap::Repeat };

fn rgba(bytes: [u8; 4]) -> Vec4 {
    Vec4::new(bytes[0].into(), bytes[1].into(), bytes[2].into(), bytes[3].into()) / 255.0
}

/// Bytes of texel (column x, image row r, r = 0 at the top) of the 4×2
/// test texture: R = 51·x (0, 0.2, 0.4, 0.6), G = 255 on the top row and
/// 0 on the bottom row, B = 20·(4r + x) (top 0 20 40 60, bottom 80 100
/// 120 140), A = 255. All eight texels differ.
fn bytes_4x2(x: u32, r: u32) -> [u8; 4] {
    [51 * x as u8, if r == 0 { 255 } else { 0 }, 20 * (4 * r + x) as u8, 255]
}

fn texture_4x2() -> Texture {
    let pixels: Vec<u8> = (0..2).flat_map(|r| (0..4).flat_map(move |x| bytes_4x2(x, r))).collect();
    Texture::from_rgba8(4, 2, &pixels).unwrap()
}

/// Texel x of the top row of the 4×2 texture (t ∈ [0.5, 1)).
fn top(x: u32) -> Vec4 {
    rgba(bytes_4x2(x, 0))
}

/// Texel x of the bottom row (t ∈ [0, 0.5)).
fn bottom(x: u32) -> Vec4 {
    rgba(bytes_4x2(x, 1))
}

/// Test-only view of one level.
fn level(tex: &Texture, l: usize) -> &[Vec4] {
    let lv = tex.levels[l];
    &tex.texels[lv.offset..lv.offset + (lv.width * lv.height) as usize]
}

fn level_sizes(tex: &Texture) -> Vec<(u32, u32)> {
    tex.levels.iter().map(|l| (l.width, l.height)).collect()
}

#[track_caller]
fn check_exact(tex: &Texture, sampler: Sampler, (s, t): (f32, f32), lod: f32, expected: Vec4) {
    let got = tex.sample(&sampler, s, t, lod);
    assert_eq!(got, expected, "{sampler:?} at (s, t) = ({s}, {t}), lod {lod}");
}

#[track_caller]
fn check_close(got: Vec4, expected: Vec4) {
    assert!(got.abs_diff_eq(expected, TOL), "got {got}, expected {expected}");
}

#[track_caller]
fn check_sample_close(tex: &Texture, sampler: Sampler, (s, t): (f32, f32), lod: f32, expected: Vec4) {
    check_close(tex.sample(&sampler, s, t, lod), expected);
}

#[test]
fn nearest_picks_the_texel_containing_the_coordinate_with_t_up() {
    let tex = texture_4x2();
    // Columns cover s ∈ [0, .25), [.25, .5), [.5, .75), [.75, 1);
    // the bottom row t ∈ [0, .5), the top row [.5, 1).
    check_exact(&tex, NEAREST, (0.1, 0.1), 0.0, bottom(0)); // t near 0: last row of `pixels`
    check_exact(&tex, NEAREST, (0.01, 0.01), 0.0, bottom(0));
    check_exact(&tex, NEAREST, (0.3, 0.2), 0.0, bottom(1));
    check_exact(&tex, NEAREST, (0.6, 0.9), 0.0, top(2)); // t near 1: first row of `pixels`
    check_exact(&tex, NEAREST, (0.99, 0.99), 0.0, top(3));
    check_exact(&tex, NEAREST, (0.875, 0.75), 0.0, top(3)); // a texel centre
}

#[test]
fn nearest_at_texel_boundaries_takes_the_right_and_upper_texel() {
    let tex = texture_4x2();
    // s = 0.25 is as far from centre 0.125 as from 0.375; ⌊0.25·4⌋ = 1
    // gives the tie to column 1, matching the half-open intervals.
    check_exact(&tex, NEAREST, (0.25, 0.1), 0.0, bottom(1));
    check_exact(&tex, NEAREST, (0.5, 0.1), 0.0, bottom(2));
    check_exact(&tex, NEAREST, (0.75, 0.1), 0.0, bottom(3));
    // t = 0.5 lies between the rows' centres 0.25 and 0.75: ⌊0.5·2⌋ = 1,
    // the upper row (row 0 of the image).
    check_exact(&tex, NEAREST, (0.1, 0.5), 0.0, top(0));
    // s = 0 is column 0; s = 1 is column 4, which wraps to 0 or clamps to 3.
    check_exact(&tex, NEAREST, (0.0, 0.0), 0.0, bottom(0));
    check_exact(&tex, NEAREST, (1.0, 0.1), 0.0, bottom(0));
    check_exact(&tex, sampler(Filter::Nearest, Wrap::ClampToEdge), (1.0, 1.0), 0.0, top(3));
}

#[test]
fn bilinear_at_texel_centre_is_that_texel_exactly() {
    let tex = texture_4x2();
    // (0.375, 0.75): u = 0.375·4 − 0.5 = 1, v = 0.75·2 − 0.5 = 1, weights 0.
    check_exact(&tex, BILINEAR, (0.375, 0.75), 0.0, top(1));
    check_exact(&tex, BILINEAR, (0.125, 0.25), 0.0, bottom(0));
    check_exact(&tex, sampler(Filter::Bilinear, Wrap::ClampToEdge), (0.875, 0.25), 0.0, bottom(3));
}

#[test]
fn bilinear_midway_and_block_centre_are_averages() {
    let tex = texture_4x2();
    // s = 0.5 is midway between centres 0.375 and 0.625 on the bottom
    // row's centre line: (bottom 1 + bottom 2)/2 =
    // R (0.2 + 0.4)/2 = 0.3, G 0, B (100 + 120)/2 = 110, A 1.
    let mid = Vec4::new(0.3, 0.0, 110.0 / 255.0, 1.0);
    check_sample_close(&tex, BILINEAR, (0.5, 0.25), 0.0, mid);
    check_close(mid, (bottom(1) + bottom(2)) / 2.0);
    // (0.5, 0.5) is the centre of columns 1–2 × both rows: R 0.3,
    // G (0 + 0 + 1 + 1)/4 = 0.5, B (100 + 120 + 20 + 40)/4 = 70, A 1.
    let centre = Vec4::new(0.3, 0.5, 70.0 / 255.0, 1.0);
    check_sample_close(&tex, BILINEAR, (0.5, 0.5), 0.0, centre);
    check_close(centre, (bottom(1) + bottom(2) + top(1) + top(2)) / 4.0);
}

#[test]
fn bilinear_at_a_non_symmetric_point_weights_each_axis() {
    let tex = texture_4x2();
    // s = 0.4375: u = 1.75 − 0.5 = 1.25, columns 1 and 2, weight 0.25 on 2.
    // t = 0.625: v = 1.25 − 0.5 = 0.75, rows bottom and top, 0.75 on top.
    // R: 0.2 + (0.4 − 0.2)·0.25 = 0.25 on both rows → 0.25.
    // G: 0 on the bottom, 1 on the top → 0.75.
    // B (bytes): bottom 100 + 20·0.25 = 105, top 20 + 20·0.25 = 25,
    //   then 105 + (25 − 105)·0.75 = 45.
    let expected = Vec4::new(0.25, 0.75, 45.0 / 255.0, 1.0);
    check_sample_close(&tex, BILINEAR, (0.4375, 0.625), 0.0, expected);
}

#[test]
fn repeat_wraps_coordinates_modulo_one() {
    let tex = texture_4x2();
    for filter in [Filter::Nearest, Filter::Bilinear] {
        let sm = sampler(filter, Wrap::Repeat);
        for (outside, inside) in [(-0.1, 0.9), (1.1, 0.1), (-0.9, 0.1), (2.3, 0.3)] {
            // s·4 rounds differently outside and inside, so the
            // bilinear weights may differ in the last bits.
            let t = 0.3;
            check_close(tex.sample(&sm, outside, t, 0.0), tex.sample(&sm, inside, t, 0.0));
            check_close(tex.sample(&sm, t, outside, 0.0), tex.sample(&sm, t, inside, 0.0));
        }
    }
    // Nearest is exact: ⌊−0.4⌋ = −1 → column 3, ⌊3.6⌋ = 3.
    check_exact(&tex, NEAREST, (-0.1, 0.2), 0.0, bottom(3));
    check_exact(&tex, NEAREST, (1.1, 0.2), 0.0, bottom(0));
    check_exact(&tex, NEAREST, (0.2, -0.1), 0.0, top(0)); // v = ⌊−0.2⌋ = −1 → top row
}

#[test]
fn wrapped_indices_cover_negatives_and_the_i32_range() {
    // Repeat is the Euclidean remainder: −1 → 3, −4 → 0, −5 → 3, 4 → 0;
    // i32::MIN = −4·536870912 → 0, i32::MAX = 4·536870911 + 3 → 3.
    let repeat: Vec<u32> = [-5, -4, -1, 0, 3, 4, 9, i32::MIN, i32::MAX].map(|i| repeat(i, 4)).into();
    assert_eq!(repeat, [3, 0, 3, 0, 3, 0, 1, 0, 3]);
    assert_eq!(Wrap::Repeat.pair(3, 4), (3, 0));
    assert_eq!(Wrap::Repeat.pair(-1, 4), (3, 0));
    assert_eq!(Wrap::Repeat.pair(0, 1), (0, 0));
    assert_eq!(Wrap::ClampToEdge.pair(-1, 4), (0, 0));
    assert_eq!(Wrap::ClampToEdge.pair(3, 4), (3, 3));
    assert_eq!(Wrap::ClampToEdge.pair(i32::MAX, 4), (3, 3));
    assert_eq!(Wrap::ClampToEdge.index(i32::MIN, 4), 0);
}

#[test]
fn bilinear_across_the_seam_of_a_repeating_texture_blends_first_and_last_columns() {
    let tex = texture_4x2();
    // s = 0: u = −0.5, columns −1 → 3 and 0, weight 0.5; bottom row:
    // R 0.6 + (0 − 0.6)·0.5 = 0.3, G 0, B 140 + (80 − 140)·0.5 = 110, A 1.
    let seam = Vec4::new(0.3, 0.0, 110.0 / 255.0, 1.0);
    check_sample_close(&tex, BILINEAR, (0.0, 0.25), 0.0, seam);
    // s = 1: u = 3.5, columns 3 and 4 → 0: the same arithmetic.
    check_exact(&tex, BILINEAR, (1.0, 0.25), 0.0, tex.sample(&BILINEAR, 0.0, 0.25, 0.0));
    // Along t the seam joins the top and bottom rows: t = 0 is midway.
    let t_seam = tex.sample(&BILINEAR, 0.125, 0.0, 0.0);
    check_close(t_seam, (top(0) + bottom(0)) / 2.0);
}

#[test]
fn clamp_to_edge_returns_edge_texels() {
    let tex = texture_4x2();
    let nearest = sampler(Filter::Nearest, Wrap::ClampToEdge);
    let bilinear = sampler(Filter::Bilinear, Wrap::ClampToEdge);
    check_exact(&tex, nearest, (-5.0, 0.25), 0.0, bottom(0));
    check_exact(&tex, nearest, (7.0, 0.25), 0.0, bottom(3));
    check_exact(&tex, nearest, (7.0, 7.0), 0.0, top(3));
    check_exact(&tex, nearest, (-5.0, -5.0), 0.0, bottom(0));
    // Bilinear at and beyond the border: both taps are the edge texel,
    // and a + (a − a)·f = a exactly.
    check_exact(&tex, bilinear, (0.0, 0.25), 0.0, bottom(0));
    check_exact(&tex, bilinear, (0.05, 0.25), 0.0, bottom(0));
    check_exact(&tex, bilinear, (-5.0, 0.25), 0.0, bottom(0));
    check_exact(&tex, bilinear, (7.0, 0.75), 0.0, top(3));
    check_exact(&tex, bilinear, (1.0, 1.0), 0.0, top(3)); // corner
    check_exact(&tex, bilinear, (0.0, 0.0), 0.0, bottom(0));
    // Mixed: clamp along s, repeat along t (t = 0 blends top and bottom).
    let mixed = Sampler { filter: Filter::Bilinear, wrap_s: Wrap::ClampToEdge, wrap_t: Wrap::Repeat };
    check_close(tex.sample(&mixed, -1.0, 0.0, 0.0), (top(0) + bottom(0)) / 2.0);
}

#[test]
fn non_finite_coordinates_read_texel_zero_along_that_axis() {
    let tex = texture_4x2();
    let filters = [Filter::Nearest, Filter::Bilinear, Filter::Trilinear];
    for wrap in [Wrap::Repeat, Wrap::ClampToEdge] {
        for filter in filters {
            let sm = sampler(filter, wrap);
            for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, f32::MAX, f32::MIN] {
                // t = 0.25 is the bottom row's centre, s = 0.375 column 1's.
                check_exact(&tex, sm, (bad, 0.25), 0.0, bottom(0));
                check_exact(&tex, sm, (0.375, bad), 0.0, bottom(1));
                check_exact(&tex, sm, (bad, bad), f32::NAN, bottom(0));
            }
        }
    }
    // Huge but finite s·w saturates to i32::MAX = 4·536870911 + 3.
    check_exact(&tex, NEAREST, (1e30, 0.25), 0.0, bottom(3));
    check_exact(&tex, sampler(Filter::Nearest, Wrap::ClampToEdge), (-1e30, 0.25), 0.0, bottom(0));
}

#[test]
fn mip_level_sizes_halve_rounding_down_to_one_by_one() {
    let sizes =
        |w: u32, h: u32| level_sizes(&Texture::from_rgba8(w, h, &vec![0; (w * h * 4) as usize]).unwrap());
    assert_eq!(sizes(8, 4), [(8, 4), (4, 2), (2, 1), (1, 1)]);
    assert_eq!(sizes(5, 3), [(5, 3), (2, 1), (1, 1)]);
    assert_eq!(sizes(1, 5), [(1, 5), (1, 2), (1, 1)]);
    assert_eq!(sizes(1, 1), [(1, 1)]);
    assert_eq!(sizes(MAX_TEXTURE_SIZE, 1).len(), 15); // 2^14 → 1: 15 levels
    let tex = texture_4x2();
    assert_eq!((tex.width(), tex.height(), tex.levels()), (4, 2, 3));
}

#[test]
fn even_mip_levels_are_two_by_two_box_averages() {
    let tex = texture_4x2();
    // Level 1 is 2×1. Texel 0 = (bottom 0 + bottom 1 + top 0 + top 1)/4:
    // R (0 + 0.2 + 0 + 0.2)/4 = 0.1, G (0 + 0 + 1 + 1)/4 = 0.5,
    // B (80 + 100 + 0 + 20)/4 = 50. Texel 1 (columns 2, 3):
    // R (0.4 + 0.6)/2 = 0.5, G 0.5, B (120 + 140 + 40 + 60)/4 = 90.
    let l1 = level(&tex, 1);
    check_close(l1[0], Vec4::new(0.1, 0.5, 50.0 / 255.0, 1.0));
    check_close(l1[1], Vec4::new(0.5, 0.5, 90.0 / 255.0, 1.0));
    // Level 2 (1×1) = (l1[0] + l1[1])/2 = R 0.3, G 0.5, B 70.
    check_close(level(&tex, 2)[0], Vec4::new(0.3, 0.5, 70.0 / 255.0, 1.0));
}

#[test]
fn odd_mip_levels_average_the_covered_area() {
    // 5×3: R = 51·x (0, 0.2, 0.4, 0.6, 0.8) by column; G by image row,
    // top to bottom 255, 51, 0 (1, 0.2, 0); B = 255 only at the middle
    // texel (x 2, row 1); A = 255.
    let mut pixels = Vec::new();
    for (r, g) in [255u8, 51, 0].into_iter().enumerate() {
        for x in 0..5u8 {
            pixels.extend([51 * x, g, if (x, r) == (2, 1) { 255 } else { 0 }, 255]);
        }
    }
    let tex = Texture::from_rgba8(5, 3, &pixels).unwrap();
    // Level 1 is 2×1. Columns 5 → 2 (n = 2): texel 0 weights columns
    // 0, 1, 2 by 0.4, 0.4, 0.2; texel 1 columns 2, 3, 4 by 0.2, 0.4, 0.4.
    // Rows 3 → 1 (n = 1): 1/3 each.
    // Texel 0: R 0.4·0 + 0.4·0.2 + 0.2·0.4 = 0.16, G (1 + 0.2 + 0)/3 = 0.4,
    //   B 0.2·(1/3) = 1/15 (the middle texel's share).
    // Texel 1: R 0.2·0.4 + 0.4·0.6 + 0.4·0.8 = 0.64, G 0.4, B 1/15.
    let l1 = level(&tex, 1);
    check_close(l1[0], Vec4::new(0.16, 0.4, 1.0 / 15.0, 1.0));
    check_close(l1[1], Vec4::new(0.64, 0.4, 1.0 / 15.0, 1.0));
    // Level 2 = their average = the image mean: R 0.4, G 0.4, B 1/15.
    check_close(level(&tex, 2)[0], Vec4::new(0.4, 0.4, 1.0 / 15.0, 1.0));

    // 3×1 → 1×1: a third of each texel. (0 + 51 + 255)/3 = 102 → 0.4.
    let row = Texture::from_rgba8(3, 1, &[0, 0, 0, 0, 51, 0, 0, 0, 255, 0, 0, 0]).unwrap();
    check_close(level(&row, 1)[0], Vec4::new(0.4, 0.0, 0.0, 0.0));
}

#[test]
fn trilinear_blends_the_two_levels_around_the_lod() {
    let tex = texture_4x2();
    let (s, t) = (0.3, 0.6);
    let on = |l| tex.bilinear(l, &TRILINEAR, s, t);
    // lod 0.5: halfway between levels 0 and 1.
    check_sample_close(&tex, TRILINEAR, (s, t), 0.5, (on(0) + on(1)) / 2.0);
    // lod 1.25: a quarter of the way from level 1 to level 2.
    check_sample_close(&tex, TRILINEAR, (s, t), 1.25, on(1) * 0.75 + on(2) * 0.25);
    // A whole lod reads that level exactly.
    check_exact(&tex, TRILINEAR, (s, t), 1.0, on(1));
    // Magnification (lod ≤ 0, −∞, NaN) is bilinear on level 0.
    for lod in [0.0, -2.0, f32::NEG_INFINITY, f32::NAN] {
        check_exact(&tex, TRILINEAR, (s, t), lod, tex.sample(&BILINEAR, s, t, 0.0));
    }
    // Nearest and bilinear ignore the lod.
    check_exact(&tex, BILINEAR, (s, t), 2.0, tex.sample(&BILINEAR, s, t, 0.0));
    check_exact(&tex, NEAREST, (s, t), 2.0, top(1)); // column ⌊1.2⌋ = 1, row ⌊1.2⌋ = 1
}

#[test]
fn trilinear_beyond_the_last_level_reads_the_last_level() {
    let tex = texture_4x2();
    let mean = level(&tex, 2)[0]; // R 0.3, G 0.5, B 70/255: see above
    for lod in [2.0, 2.5, 10.0, f32::INFINITY] {
        for (s, t) in [(0.3, 0.6), (-4.2, 9.1)] {
            check_exact(&tex, TRILINEAR, (s, t), lod, mean);
        }
    }
    let solid = Texture::solid(Vec4::new(0.1, 0.2, 0.3, 0.4));
    assert_eq!((solid.width(), solid.height(), solid.levels()), (1, 1, 1));
    for filter in [Filter::Nearest, Filter::Bilinear, Filter::Trilinear] {
        check_exact(&solid, sampler(filter, Wrap::Repeat), (0.7, -3.0), 4.0, Vec4::new(0.1, 0.2, 0.3, 0.4));
    }
}

#[track_caller]
fn check_lod(derivatives: [f32; 4], (w, h): (u32, u32), expected: f32) {
    let [dsdx, dtdx, dsdy, dtdy] = derivatives;
    let got = lod(dsdx, dtdx, dsdy, dtdy, w, h);
    assert!((got - expected).abs() <= TOL || got == expected, "lod {got}, expected {expected}");
}

#[test]
fn lod_is_log2_of_the_larger_footprint_in_texels() {
    let d = 1.0 / 256.0;
    check_lod([d, 0.0, 0.0, d], (256, 256), 0.0); // one texel per pixel
    check_lod([2.0 * d, 0.0, 0.0, d], (256, 256), 1.0); // x footprint 2
    check_lod([d, 0.0, 0.0, 8.0 * d], (256, 256), 3.0); // y footprint 8 wins
    check_lod([3.0 * d, 4.0 * d, 0.0, 0.0], (256, 256), 5f32.log2()); // |(3, 4)| = 5: 2.3219
    check_lod([0.5 * d, 0.0, 0.0, 0.5 * d], (256, 256), -1.0); // magnification
                                                               // Non-square: ∂t/∂x = 0.25 on 16 rows = 4 texels; ∂s/∂y = 1/64 on 64 columns = 1.
    check_lod([0.0, 0.25, 1.0 / 64.0, 0.0], (64, 16), 2.0);
    check_lod([0.0; 4], (64, 16), f32::NEG_INFINITY);
    check_lod([f32::NAN, f32::NAN, 0.0, 4.0 / 16.0], (64, 16), 2.0); // NaN direction ignored
    assert!(lod(f32::NAN, 0.0, f32::NAN, 0.0, 8, 8).is_nan());
}

#[test]
fn from_rgba8_rejects_bad_sizes_with_a_message_naming_the_problem() {
    let err = Texture::from_rgba8(0, 4, &[]).unwrap_err();
    assert_eq!(err, TextureError::ZeroSize { width: 0, height: 4 });
    assert!(err.to_string().contains("0x4 is empty"), "{err}");
    assert!(Texture::from_rgba8(4, 0, &[]).is_err());

    let err = Texture::from_rgba8(4, 2, &[0; 31]).unwrap_err();
    assert_eq!(err, TextureError::WrongLength { width: 4, height: 2, expected: 32, actual: 31 });
    assert!(err.to_string().contains("needs 32 bytes"), "{err}");
    assert!(err.to_string().contains("got 31"), "{err}");
    assert!(Texture::from_rgba8(4, 2, &[0; 33]).is_err());

    let err = Texture::from_rgba8(MAX_TEXTURE_SIZE + 1, 1, &[]).unwrap_err();
    assert_eq!(err, TextureError::TooLarge { width: 16385, height: 1 });
    assert!(err.to_string().contains("16385x1 exceeds the limit of 16384"), "{err}");
    assert!(Texture::from_rgba8(1, MAX_TEXTURE_SIZE + 1, &[]).is_err());
}

#[test]
fn sampler_defaults_to_trilinear_repeat() {
    assert_eq!(Sampler::default(), TRILINEAR);
}

/// Slack for the bound checks: each lerp or weighted sum of values in
/// [0, 1] may round past its inputs by an ulp or so, and a trilinear
/// sample chains up to a dozen of them through the mip chain.
const SLACK: f32 = 1e-6;

fn any_texture() -> impl Strategy<Value = Texture> {
    (1u32..=7, 1u32..=7)
        .prop_flat_map(|(w, h)| (Just(w), Just(h), prop::collection::vec(any::<u8>(), (w * h * 4) as usize)))
        .prop_map(|(w, h, pixels)| Texture::from_rgba8(w, h, &pixels).unwrap())
}

fn any_wrap() -> impl Strategy<Value = Wrap> {
    prop_oneof![Just(Wrap::Repeat), Just(Wrap::ClampToEdge)]
}

fn any_sampler(filter: Filter) -> impl Strategy<Value = Sampler> {
    (any_wrap(), any_wrap()).prop_map(move |(wrap_s, wrap_t)| Sampler { filter, wrap_s, wrap_t })
}

#[track_caller]
fn check_within_texels(tex: &Texture, v: Vec4) {
    let texels = level(tex, 0);
    let lo = texels.iter().fold(Vec4::INFINITY, |a, &b| a.min(b));
    let hi = texels.iter().fold(Vec4::NEG_INFINITY, |a, &b| a.max(b));
    assert!(
        v.cmpge(lo - SLACK).all() && v.cmple(hi + SLACK).all(),
        "{v} outside the texel range {lo} .. {hi}"
    );
}

proptest! {
    #[test]
    fn bilinear_stays_within_the_texel_range(
        tex in any_texture(), sm in any_sampler(Filter::Bilinear), s in -3.0f32..3.0, t in -3.0f32..3.0,
    ) {
        check_within_texels(&tex, tex.sample(&sm, s, t, 0.0));
    }

    #[test]
    fn trilinear_stays_within_the_texel_range(
        tex in any_texture(), sm in any_sampler(Filter::Trilinear),
        s in -3.0f32..3.0, t in -3.0f32..3.0, lod in -1.0f32..4.0,
    ) {
        check_within_texels(&tex, tex.sample(&sm, s, t, lod));
    }

    #[test]
    fn nearest_returns_one_of_the_texels(
        tex in any_texture(), sm in any_sampler(Filter::Nearest), s in -3.0f32..3.0, t in -3.0f32..3.0,
    ) {
        let v = tex.sample(&sm, s, t, 0.0);
        prop_assert!(level(&tex, 0).contains(&v), "{} is not a texel", v);
    }

    #[test]
    fn every_mip_level_keeps_the_image_mean(tex in any_texture()) {
        let mean = |l| {
            let texels = level(&tex, l);
            texels.iter().sum::<Vec4>() / texels.len() as f32
        };
        for l in 1..tex.levels() {
            prop_assert!(mean(l).abs_diff_eq(mean(0), 1e-5), "level {}: {} vs {}", l, mean(l), mean(0));
        }
    }
}

/// Any f32 the sampler may meet: ordinary coordinates, exact texel
/// boundaries and centres, huge values, infinities and NaN.
fn any_coordinate() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -3.0f32..3.0,
        1 => (-64i32..64, 1u32..=14).prop_map(|(k, d)| k as f32 / d as f32),
        1 => prop_oneof![
            Just(f32::NAN), Just(f32::INFINITY), Just(f32::NEG_INFINITY), Just(f32::MAX), Just(-f32::MAX),
            Just(3.0e9f32), Just(-3.0e9f32), Just(2.1e9f32), Just(-2.1e9f32), Just(1.0e30f32),
        ],
        1 => any::<f32>(),
        1 => -1.0e7f32..1.0e7,
    ]
}

fn any_lod() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -1.0f32..5.0,
        1 => (0u32..5).prop_map(|l| l as f32),
        1 => prop_oneof![Just(f32::NAN), Just(f32::INFINITY), Just(f32::NEG_INFINITY), Just(-0.0f32)],
        1 => any::<f32>(),
    ]
}

fn any_filter() -> impl Strategy<Value = Filter> {
    prop_oneof![Just(Filter::Nearest), Just(Filter::Bilinear), Just(Filter::Trilinear)]
}

fn odd_texture() -> impl Strategy<Value = Texture> {
    (1u32..=13, 1u32..=13, prop_oneof![Just(1u32), Just(16), Just(33)])
        .prop_map(|(w, h, scale)| (w * scale, h))
        .prop_flat_map(|(w, h)| (Just(w), Just(h), prop::collection::vec(any::<u8>(), (w * h * 4) as usize)))
        .prop_map(|(w, h, pixels)| Texture::from_rgba8(w, h, &pixels).unwrap())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn eight_lanes_match_the_scalar_sampler_bit_for_bit(
        tex in odd_texture(), filter in any_filter(), wrap_s in any_wrap(), wrap_t in any_wrap(),
        s in prop::array::uniform8(any_coordinate()), t in prop::array::uniform8(any_coordinate()),
        lod in prop::array::uniform8(any_lod()),
    ) {
        let sm = Sampler { filter, wrap_s, wrap_t };
        for (level, got) in sample_x8_at_each_level(&tex, &sm, s, t, lod).iter().enumerate() {
            for k in 0..8 {
                let want = tex.sample(&sm, s[k], t[k], lod[k]).to_array().map(f32::to_bits);
                let lane = [got[0][k], got[1][k], got[2][k], got[3][k]].map(f32::to_bits);
                prop_assert_eq!(lane, want, "level {}, lane {} of {:?}: s {}, t {}, lod {}", level, k, sm, s[k], t[k], lod[k]);
            }
        }
    }
}

/// `sample_x8` at the baseline level and at the best level the CPU has
/// (`zline_simd::vectorize`; the same level twice on a CPU without AVX2).
fn sample_x8_at_each_level(
    tex: &Texture,
    sm: &Sampler,
    s: [f32; 8],
    t: [f32; 8],
    lod: [f32; 8],
) -> [[[f32; 8]; 4]; 2] {
    use zline_simd::lanes::{f32x8, Baseline, Level};
    struct Job<'a>(&'a Texture, &'a Sampler, [f32; 8], [f32; 8], [f32; 8]);
    impl zline_simd::Vectorized for &Job<'_> {
        type Output = [[f32; 8]; 4];
        #[inline(always)]
        fn run<L: Level>(self) -> [[f32; 8]; 4] {
            let v = |a: [f32; 8]| f32x8::<L>::from(a);
            self.0.sample_x8(self.1, v(self.2), v(self.3), v(self.4)).map(|c| c.to_array())
        }
    }
    let job = Job(tex, sm, s, t, lod);
    [zline_simd::Vectorized::run::<Baseline>(&job), zline_simd::vectorize(&job)]
}

/// Every lane of `sample_x8` against `sample`, bit for bit, at each level.
#[track_caller]
fn check_lanes(tex: &Texture, sm: Sampler, s: [f32; 8], t: [f32; 8], lod: [f32; 8]) {
    for (level, got) in sample_x8_at_each_level(tex, &sm, s, t, lod).iter().enumerate() {
        for k in 0..8 {
            let want = tex.sample(&sm, s[k], t[k], lod[k]).to_array().map(f32::to_bits);
            let lane = [got[0][k], got[1][k], got[2][k], got[3][k]].map(f32::to_bits);
            assert_eq!(
                lane, want,
                "level {level}, lane {k} of {sm:?}: s {}, t {}, lod {}",
                s[k], t[k], lod[k]
            );
        }
    }
}

/// The texel buffer's first and last texels through each way the eight
/// lanes load texels: single texels (nearest), adjacent pairs (no lane's
/// columns wrap apart), and separate pairs (the 1×1 last level, whose two
/// columns are the same texel, the buffer's last).
#[test]
fn eight_lanes_read_the_first_and_last_texels_of_the_buffer() {
    let tex = texture_4x2();
    let clamp = |filter| sampler(filter, Wrap::ClampToEdge);
    let corners = ([0.0, 0.99, 0.0, 0.99, 0.1, 0.9, 0.2, 0.8], [0.0, 0.99, 0.99, 0.0, 0.1, 0.9, 0.9, 0.1]);
    check_lanes(&tex, clamp(Filter::Nearest), corners.0, corners.1, [0.0; 8]);
    let nearest = sample_x8_at_each_level(&tex, &clamp(Filter::Nearest), corners.0, corners.1, [0.0; 8])[1];
    assert_eq!((nearest[2][0], nearest[2][1]), (bottom(0).z, top(3).z));
    // Columns 2–3 of the top row (the last pair of level 0) in every lane,
    // then columns 0–1 of the bottom row (the first pair).
    let s_right = [0.63, 0.65, 0.7, 0.75, 0.8, 0.85, 0.87, 0.874];
    check_lanes(&tex, clamp(Filter::Bilinear), s_right, [0.9; 8], [0.0; 8]);
    check_lanes(&tex, clamp(Filter::Bilinear), s_right.map(|s| s - 0.5), [0.1; 8], [0.0; 8]);
    let beyond = sample_x8_at_each_level(&tex, &clamp(Filter::Trilinear), [0.3; 8], [0.6; 8], [9.0; 8])[1];
    assert_eq!(beyond.map(|c| c[5]), tex.texel(2, 0, 0).to_array());
    for wrap in [Wrap::Repeat, Wrap::ClampToEdge] {
        let lods = [9.0, 2.0, 1.5, 1.0, 0.5, 0.0, -1.0, f32::NAN];
        check_lanes(&tex, sampler(Filter::Trilinear, wrap), corners.0, corners.1, lods);
        check_lanes(&tex, sampler(Filter::Trilinear, wrap), corners.1, corners.0, [1.75; 8]);
    }
}
