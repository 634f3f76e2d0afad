//! The levels the lane types are compiled for: [`Baseline`] (the build's
//! own target) and the run-time x86-64-v3 and v4 levels.

/// An instruction-set level the lane types are compiled for. Sealed: the
/// levels are [`Baseline`] and the x86-64-v3 and v4 levels that only
/// [`crate::vectorize`] and its siblings name.
pub trait Level: Copy + Send + Sync + Default + core::fmt::Debug + 'static + private::Sealed {
    /// True at the x86-64-v3 level and above (AVX2 and FMA present): the
    /// lane operations use their AVX2 intrinsics.
    const V3: bool;
    /// True at the x86-64-v4 level (AVX-512 F, VL, BW, DQ present too):
    /// the same intrinsics as v3, in code compiled for AVX-512.
    const V4: bool;
}

/// The level the build targets: `wide`'s own code paths.
#[derive(Clone, Copy, Default, Debug, PartialEq, Eq)]
pub struct Baseline;

impl Level for Baseline {
    const V3: bool = false;
    const V4: bool = false;
}

impl private::Sealed for Baseline {}

pub(crate) mod private {
    /// Keeps [`super::Level`] closed to this crate's types.
    #[allow(unreachable_pub, reason = "a supertrait of the public `Level`")]
    pub trait Sealed {}

    /// The x86-64-v3 level (AVX2, FMA). Public in a private module: it can
    /// appear as a type argument, but no other crate can name it.
    #[allow(unreachable_pub, reason = "public so that it may be a type argument of public generics")]
    #[derive(Clone, Copy, Default, Debug, PartialEq, Eq)]
    pub struct V3;

    impl Sealed for V3 {}

    impl super::Level for V3 {
        const V3: bool = true;
        const V4: bool = false;
    }

    /// The x86-64-v4 level (AVX-512 F, VL, BW, DQ besides v3's). Its lane
    /// operations are v3's; only the code around them is compiled for
    /// AVX-512.
    #[allow(unreachable_pub, reason = "public so that it may be a type argument of public generics")]
    #[derive(Clone, Copy, Default, Debug, PartialEq, Eq)]
    pub struct V4;

    impl Sealed for V4 {}

    impl super::Level for V4 {
        const V3: bool = true;
        const V4: bool = true;
    }
}
