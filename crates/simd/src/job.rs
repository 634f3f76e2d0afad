//! Jobs: code compiled once per SIMD level, which [`crate::vectorize`],
//! [`crate::dispatch`] and [`crate::vectorize_at`] run at the level chosen.

use crate::lanes::Level;

/// A job whose body [`crate::vectorize`] compiles for the best level the CPU has.
///
/// [`Vectorized::run`] is generic over the [`Level`] its lane types
/// use; implementations mark it `#[inline(always)]`, and everything hot
/// that it calls `#[inline]` or `#[inline(always)]`: only what is inlined
/// into the job's body is compiled with the level's instructions (a
/// function called out of line is compiled for the build's baseline and
/// reaches the level's lane operations through calls, correct but slow).
pub trait Vectorized {
    /// What the job returns.
    type Output;
    /// The job's body at level `L`.
    fn run<L: Level>(self) -> Self::Output;
}

/// A closure as a job of [`crate::vectorize_at`]. The closure takes no level: it
/// runs the code its caller instantiated, for the level the caller was
/// given (so it is sound by the caller's own level), and it should be
/// marked `#[inline(always)]` so that its body lands in the job's function.
#[derive(Debug)]
pub struct Call<F>(pub F);

impl<R, F: FnOnce() -> R> Vectorized for Call<F> {
    type Output = R;
    #[inline(always)]
    fn run<L: Level>(self) -> R {
        (self.0)()
    }
}
