//! The limits of the render settings and procedural meshes: the largest
//! values a scene file may ask for. The loaders enforce them; the pipeline
//! and the CLI rely on them (the pipeline clamps supersampling to
//! [`MAX_SSAA`]).

/// Largest image side a scene file may ask for.
pub const MAX_IMAGE_SIDE: u32 = 16384;

/// Largest supersampling factor a scene file may ask for (`ssaa = 8`: 64
/// samples per pixel).
pub const MAX_SSAA: u32 = 8;

/// Largest adaptive tolerance, in 8-bit units: a whole channel's range.
pub const MAX_ADAPTIVE_TOLERANCE: f32 = 255.0;

/// Largest ring, segment or subdivision count of a primitive.
pub const MAX_PRIMITIVE_DIVISIONS: u32 = 4096;
