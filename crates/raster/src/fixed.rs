//! Fixed-point window coordinates and pixel rectangles.
//!
//! Vertices are snapped to a grid of 1/256 pixel ([`SUBPIXEL_BITS`] = 8, as in
//! most hardware and Mesa's llvmpipe). Every coverage decision is then an
//! exact integer computation, which is what makes shared edges watertight and
//! the result independent of tiling. Sample (pixel centre) of pixel `i` sits
//! at `i·256 + 128`.

/// Bits of sub-pixel precision of snapped window coordinates.
pub const SUBPIXEL_BITS: u32 = 8;
/// One pixel in fixed-point units.
pub const SUBPIXEL_ONE: i64 = 1 << SUBPIXEL_BITS;
/// Half a pixel in fixed-point units: the offset of a pixel centre.
pub const SUBPIXEL_HALF: i64 = SUBPIXEL_ONE / 2;

/// Largest accepted |x| or |y| in pixels. With 8 sub-pixel bits coordinates
/// fit in 30 bits, so every product in the edge arithmetic fits in an `i64`
/// (|product| < 2^61). The pipeline clips to a far smaller guard band.
pub const MAX_WINDOW_COORD: f32 = (1 << 21) as f32;

/// A point in window space on the 1/256-pixel grid (y down, row 0 on top).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct FixedPoint {
    /// x in 1/256 pixels.
    pub x: i32,
    /// y in 1/256 pixels.
    pub y: i32,
}

impl FixedPoint {
    /// Snaps a window-space point to the grid (round to nearest). Returns
    /// `None` for non-finite input or |x|, |y| > [`MAX_WINDOW_COORD`].
    #[inline]
    pub fn snap(x: f32, y: f32) -> Option<FixedPoint> {
        let ok = |v: f32| v.abs() <= MAX_WINDOW_COORD; // false for NaN
        if !(ok(x) && ok(y)) {
            return None;
        }
        let s = SUBPIXEL_ONE as f32;
        // Exact: |v·256| ≤ 2^29 fits in i32, and `as` cannot saturate here.
        Some(FixedPoint { x: round_to_i32(x * s), y: round_to_i32(y * s) })
    }

    /// The point in pixels, exactly (fixed-point values are exact in f64).
    #[inline]
    pub fn to_f64(self) -> (f64, f64) {
        let s = SUBPIXEL_ONE as f64;
        (f64::from(self.x) / s, f64::from(self.y) / s)
    }
}

/// `v.round() as i32` (to nearest, halves away from zero) for |v| ≤ 2^30,
/// without `roundf`: below SSE4.1 that is a library call, once per snapped
/// coordinate. The truncation is exact, and so is `v − t` (below 2^24 both
/// lie in one binade or t is 0; from 2^24 on every float is an integer).
#[inline]
fn round_to_i32(v: f32) -> i32 {
    let t = v as i32;
    let frac = v - t as f32;
    // Flags, not branches: the fraction's side is data, not a pattern.
    t + i32::from(frac >= 0.5) - i32::from(frac <= -0.5)
}

/// A half-open rectangle of pixels: columns `x0..x1`, rows `y0..y1`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Rect {
    /// First column.
    pub x0: i32,
    /// First row.
    pub y0: i32,
    /// One past the last column.
    pub x1: i32,
    /// One past the last row.
    pub y1: i32,
}

impl Rect {
    /// A rectangle from its corner and size.
    #[inline]
    pub fn from_size(x0: i32, y0: i32, width: i32, height: i32) -> Rect {
        Rect { x0, y0, x1: x0 + width, y1: y0 + height }
    }

    /// The common part of two rectangles (possibly empty).
    #[inline]
    pub fn intersect(&self, other: &Rect) -> Rect {
        Rect {
            x0: self.x0.max(other.x0),
            y0: self.y0.max(other.y0),
            x1: self.x1.min(other.x1),
            y1: self.y1.min(other.y1),
        }
    }

    /// True when no pixel is inside.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.x0 >= self.x1 || self.y0 >= self.y1
    }

    /// Width in pixels (0 when empty).
    #[inline]
    pub fn width(&self) -> i32 {
        (self.x1 - self.x0).max(0)
    }

    /// Height in pixels (0 when empty).
    #[inline]
    pub fn height(&self) -> i32 {
        (self.y1 - self.y0).max(0)
    }
}

/// ⌈a / b⌉ for b > 0 and |a| < 2^62.
///
/// 64-bit integer division costs 40–90 cycles on common x86 cores, and the
/// edge walkers need a few per triangle, so the quotient is estimated in f64
/// (off by at most one: a/b < 2^31 and the estimate's relative error is
/// ~2^-52) and corrected with exact integer products.
#[inline]
pub(crate) fn ceil_div(a: i64, b: i64) -> i64 {
    debug_assert!(b > 0);
    let mut q = (a as f64 / b as f64).ceil() as i64;
    while q * b < a {
        q += 1;
    }
    while (q - 1) * b >= a {
        q -= 1;
    }
    q
}

/// ⌊a / b⌋ for b > 0 and |a| < 2^62, as [`ceil_div`].
#[inline]
pub(crate) fn floor_div(a: i64, b: i64) -> i64 {
    debug_assert!(b > 0);
    let mut q = (a as f64 / b as f64).floor() as i64;
    while q * b > a {
        q -= 1;
    }
    while (q + 1) * b <= a {
        q += 1;
    }
    q
}

/// The first row (or column) whose sample coordinate is ≥ `v` (fixed point).
#[inline]
pub fn first_sample_at_or_after(v: i64) -> i64 {
    (v - SUBPIXEL_HALF + SUBPIXEL_ONE - 1) >> SUBPIXEL_BITS
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn snap_rounds_to_nearest_and_rejects_bad_input() {
        assert_eq!(FixedPoint::snap(1.5, -0.25), Some(FixedPoint { x: 384, y: -64 }));
        assert_eq!(FixedPoint::snap(f32::NAN, 0.0), None);
        assert_eq!(FixedPoint::snap(0.0, f32::INFINITY), None);
        assert_eq!(FixedPoint::snap(3e6, 0.0), None);
    }

    #[test]
    fn rounding_matches_round_for_every_float_in_range() {
        // Every float of magnitude ≤ 2^21·256 whose rounding could differ:
        // all of [0, 2^24) at a stride that still visits each binade's
        // halves, plus every x.5 and its neighbours up to 2^23.
        let check = |v: f32| {
            assert_eq!(round_to_i32(v), v.round() as i32, "{v}");
            assert_eq!(round_to_i32(-v), (-v).round() as i32, "{}", -v);
        };
        let mut bits = 0u32;
        while f32::from_bits(bits) <= (1u32 << 29) as f32 {
            check(f32::from_bits(bits));
            bits += 97;
        }
        for i in 0..(1 << 16) {
            let half = i as f32 * 128.0 + 0.5;
            for v in [half, f32::from_bits(half.to_bits() - 1), f32::from_bits(half.to_bits() + 1)] {
                check(v);
            }
        }
        for v in [0.0, 0.5, 0.49999997, 1.5, 2.5, 8_388_607.5, 8_388_608.0, 16_777_217.0, 536_870_912.0] {
            check(v);
        }
    }

    #[test]
    fn divisions_match_integer_division() {
        let big = (1i64 << 61) - 3;
        for a in [-big, -1_000_001, -257, -256, -255, -1, 0, 1, 255, 256, 257, 999_999_937, big] {
            for b in [1, 2, 3, 255, 256, 65_537, (1 << 38) + 7] {
                let floor = a.div_euclid(b);
                let ceil = floor + i64::from(a.rem_euclid(b) != 0);
                assert_eq!(floor_div(a, b), floor, "{a} / {b}");
                assert_eq!(ceil_div(a, b), ceil, "{a} / {b}");
            }
        }
    }

    #[test]
    fn first_sample_handles_exact_hits_and_negatives() {
        assert_eq!(first_sample_at_or_after(128), 0); // exactly on the centre of pixel 0
        assert_eq!(first_sample_at_or_after(129), 1);
        assert_eq!(first_sample_at_or_after(-128), -1);
        assert_eq!(first_sample_at_or_after(-129), -1);
        assert_eq!(first_sample_at_or_after(-383), -1);
        assert_eq!(first_sample_at_or_after(-384), -2);
    }
}
