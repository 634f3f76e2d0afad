//! Software prefetch: asking for a value's cache lines ahead of its use.
//!
//! A tile draws the primitives of its bin in order, and each primitive was
//! written by setup long before (the 1M-triangle sphere writes ~100 MB of
//! them), so its first load misses the caches. Prefetching the primitive a
//! few places ahead in the bin overlaps those misses with drawing.

/// Requests the cache lines of `*value` (a hint: it changes no result and
/// never faults). Does nothing off x86-64.
#[inline(always)]
pub fn prefetch<T>(value: &T) {
    #[cfg(all(target_arch = "x86_64", target_feature = "sse"))]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let start = (value as *const T).cast::<i8>();
        for offset in (0..size_of::<T>()).step_by(64) {
            // SAFETY: SSE is part of the target; `start + offset` lies inside
            // `*value` (offset < size_of::<T>()), so the pointer arithmetic
            // stays in one allocation, and a prefetch reads nothing the
            // program sees and cannot fault.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(start.add(offset)) };
        }
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse")))]
    let _ = value;
}

#[cfg(test)]
mod tests {
    use super::prefetch;

    #[test]
    fn prefetch_changes_nothing() {
        let data = [[1.5f32; 64]; 3];
        prefetch(&data);
        prefetch(&data[2]);
        prefetch(&());
        assert_eq!(data, [[1.5f32; 64]; 3]);
    }
}
