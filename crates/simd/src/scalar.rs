//! The scalar twins: plain Rust that defines what each function of the
//! crate returns. Every explicit SIMD version equals its twin bit for bit.

/// Channel c of texel `idx[k]` at position k of element c; see
/// [`crate::gather_texels_x8`].
#[inline]
pub fn gather_texels_x8(texels: &[[f32; 4]], idx: [i32; 8]) -> [[f32; 8]; 4] {
    let t = idx.map(|i| texels[index(i)]);
    std::array::from_fn(|c| std::array::from_fn(|k| t[k][c]))
}

/// The channels of `texels[a[k]]` then of `texels[b[k]]`; see
/// [`crate::gather_texel_pairs_x8`].
#[inline]
pub fn gather_texel_pairs_x8(texels: &[[f32; 4]], a: [i32; 8], b: [i32; 8]) -> [[f32; 8]; 8] {
    let [a0, a1, a2, a3] = gather_texels_x8(texels, a);
    let [b0, b1, b2, b3] = gather_texels_x8(texels, b);
    [a0, a1, a2, a3, b0, b1, b2, b3]
}

/// The channels of `texels[a[k]]` then of `texels[a[k] + 1]`; see
/// [`crate::gather_adjacent_texels_x8`].
#[inline]
pub fn gather_adjacent_texels_x8(texels: &[[f32; 4]], a: [i32; 8]) -> [[f32; 8]; 8] {
    // i32::MAX + 1 wraps to a negative index, which panics like the others.
    gather_texel_pairs_x8(texels, a, a.map(|i| i.wrapping_add(1)))
}

/// A lane's index as a slice index; a negative one panics like an index
/// past the end.
#[inline]
fn index(i: i32) -> usize {
    usize::try_from(i).unwrap_or(usize::MAX)
}
