//! Why a solve is refused.

use glam::Vec3;

/// What stopped a solve before it began.
#[derive(Debug, Clone, PartialEq)]
pub enum RadiosityError {
    /// The patch size is not a positive finite length.
    PatchSize(f32),
    /// The patch size would cut the scene into too many patches.
    TooManyPatches {
        /// The size asked for.
        size: f32,
        /// The patches it would give.
        patches: f64,
        /// The limit.
        max: usize,
    },
    /// The sweeps' matrix would be too large.
    Matrix {
        /// The patches.
        patches: usize,
        /// The most the sweeps accept.
        max: usize,
    },
    /// A material's emission is not finite.
    Emission {
        /// The triangle's index in the scene's world order.
        triangle: usize,
        /// Its emission.
        emission: Vec3,
    },
}

impl std::fmt::Display for RadiosityError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RadiosityError::PatchSize(size) => write!(f, "radiosity: the patch size {size} is not a positive length"),
            RadiosityError::TooManyPatches { size, patches, max } => write!(
                f,
                "radiosity: a patch size of {size} cuts the scene into {patches:.3e} patches, more than {max}; give a larger --patch-size"
            ),
            RadiosityError::Matrix { patches, max } => write!(
                f,
                "radiosity: Jacobi and Gauss-Seidel keep a {patches} × {patches} matrix of form factors, more than {max} patches allow; use --solver progressive or a larger --patch-size"
            ),
            RadiosityError::Emission { triangle, emission } => {
                write!(f, "radiosity: triangle {triangle} emits {emission} (not finite)")
            }
        }
    }
}

impl std::error::Error for RadiosityError {}
