//! A read the optimizer cannot see through.
//!
//! A kernel that writes a colour block back as `select(live, new, old)`,
//! with `old` read from the same place, invites LLVM to turn the read, the
//! blend and the write into one masked store (`vmaskmovps`). On Intel
//! cores that is cheap; on AMD's (Zen 1–4) a 256-bit masked store is
//! microcoded and was the hottest instruction of the flat and Gouraud
//! kernels. Reading `old` through [`read_opaque`] keeps the plain load,
//! blend and aligned store.

/// `*r`, read so that the compiler cannot fold the read into a masked store
/// (or anything else) with a later write to the same place. Costs one
/// ordinary load.
#[inline(always)]
pub fn read_opaque<T: Copy>(r: &T) -> T {
    // SAFETY: `r` is a reference, so it is valid for reads, aligned and
    // initialized; `T: Copy`, so the copy does not duplicate ownership.
    unsafe { std::ptr::read_volatile(r) }
}

#[cfg(test)]
mod tests {
    use super::read_opaque;

    #[test]
    fn reads_the_value() {
        let block = [1.5f32, -0.0, f32::NAN, 3.0, 4.0, 5.0, 6.0, f32::INFINITY];
        let read = read_opaque(&block);
        assert_eq!(read.map(f32::to_bits), block.map(f32::to_bits));
    }
}
