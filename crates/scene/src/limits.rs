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

// ---- Command-line and pipeline limits: threads, tiles, samples ----
//
// Checked by the `zline` command line before it loads or renders anything;
// the pipeline clamps the tile size itself, so no value can make it panic.

/// Largest number of samples in one frame, width × height × ssaa²: 2^28
/// (268 435 456). A sample takes 16 bytes in the tile buffers (depth and
/// three colour planes, `f32` each), so even a frame whose every sample is
/// held at once stays within 4 GiB. It admits every image side up to
/// [`MAX_IMAGE_SIDE`] without supersampling, 8192² at ssaa 2, 4096² at ssaa
/// 4 and 2048² at ssaa 8.
pub const MAX_SAMPLES: u64 = 1 << 28;

/// Smallest tile edge, in pixels, the command line accepts. Smaller tiles
/// give the same image but one bin list (48 bytes) per tile: a 16384² image
/// in 1-pixel tiles would need 12 GiB of bins; in 8-pixel tiles, 200 MB.
pub const MIN_TILE_SIZE: u32 = 8;

/// Largest tile edge, in pixels. The command line refuses larger values;
/// the pipeline takes a larger one (up to `u32::MAX`) as this one, and a
/// tile larger than the image as the whole image: the image never depends
/// on the tile size.
pub const MAX_TILE_SIZE: u32 = 1024;

/// Most worker threads the command line starts; `--threads` above it is
/// clamped to it with a warning (10 000 threads brought a two-core machine
/// to a load average of 469).
pub const MAX_THREADS: usize = 256;
