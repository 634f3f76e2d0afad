//! Which explicit SIMD instruction set the crate's functions use, detected
//! once at run time.

use std::sync::atomic::{AtomicU8, Ordering};

/// [`Isa::current`] once known: 1 + its position in [`Isa::ALL`]; 0 before.
static CURRENT: AtomicU8 = AtomicU8::new(0);

/// An explicit SIMD instruction set for the functions of this crate,
/// ordered from least to most capable.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Isa {
    /// No explicit SIMD: the portable [`scalar`](crate::scalar) twins.
    Scalar,
    /// x86-64's own SSE2 (every x86-64 processor; no detection needed).
    Sse2,
    /// x86-64 with AVX2 (Intel Haswell, AMD Excavator and later), detected
    /// at run time.
    Avx2,
    /// x86-64 with AVX-512 F, VL, BW and DQ besides AVX2 and FMA (Intel
    /// Skylake-SP, Ice Lake; AMD Zen 4 and later), detected at run time:
    /// the same eight-lane kernels, encoded with AVX-512VL and its 32
    /// vector registers.
    Avx512,
}

impl Isa {
    /// Every instruction set, least capable first.
    pub const ALL: [Isa; 4] = [Isa::Scalar, Isa::Sse2, Isa::Avx2, Isa::Avx512];

    /// The instruction set in use: the best one this CPU has, lowered to
    /// `ZLINE_SIMD` when the environment names a less capable one
    /// ("scalar", "sse2", "avx2"). Detected on the first call, then cached (one
    /// relaxed atomic load).
    #[inline]
    pub fn current() -> Isa {
        match CURRENT.load(Ordering::Relaxed) {
            0 => Isa::detect(),
            n => Isa::ALL[usize::from(n - 1) % Isa::ALL.len()],
        }
    }

    /// The first [`Isa::current`]: reads the environment and the CPU, and
    /// caches the answer (threads racing here all store the same value).
    #[cold]
    #[inline(never)]
    fn detect() -> Isa {
        let wanted =
            std::env::var("ZLINE_SIMD").ok().and_then(|name| Isa::ALL.into_iter().find(|i| i.name() == name));
        let isa = wanted.map_or(Isa::best(), |w| w.min(Isa::best()));
        let index = Isa::ALL.iter().position(|&i| i == isa).unwrap_or(0);
        CURRENT.store(index as u8 + 1, Ordering::Relaxed);
        isa
    }

    /// The best instruction set this CPU has, ignoring the environment.
    pub fn best() -> Isa {
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx2") {
            let avx512 = std::is_x86_feature_detected!("fma")
                && std::is_x86_feature_detected!("avx512f")
                && std::is_x86_feature_detected!("avx512vl")
                && std::is_x86_feature_detected!("avx512bw")
                && std::is_x86_feature_detected!("avx512dq");
            return if avx512 { Isa::Avx512 } else { Isa::Avx2 };
        }
        if cfg!(all(target_arch = "x86_64", target_feature = "sse2")) {
            Isa::Sse2
        } else {
            Isa::Scalar
        }
    }

    /// The name `ZLINE_SIMD` takes: "scalar", "sse2", "avx2", "avx512".
    pub fn name(self) -> &'static str {
        match self {
            Isa::Scalar => "scalar",
            Isa::Sse2 => "sse2",
            Isa::Avx2 => "avx2",
            Isa::Avx512 => "avx512",
        }
    }
}
