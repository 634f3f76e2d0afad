//! The limits of the render settings and procedural meshes (the largest
//! values a scene file may ask for) and of the loaders (the largest files,
//! textures and meshes one load may read and build), in one place. The
//! loaders of zline-io enforce them; the pipeline and the CLI rely on them
//! (the pipeline clamps supersampling to [`MAX_SSAA`]). README.md, "Limits
//! and safety", lists them.

/// Largest image side a scene file may ask for.
pub const MAX_IMAGE_SIDE: u32 = 16384;

/// Largest supersampling factor a scene file may ask for (`ssaa = 8`: 64
/// samples per pixel).
pub const MAX_SSAA: u32 = 8;

/// Largest adaptive tolerance, in 8-bit units: a whole channel's range.
pub const MAX_ADAPTIVE_TOLERANCE: f32 = 255.0;

/// Largest ring, segment or subdivision count of a primitive.
pub const MAX_PRIMITIVE_DIVISIONS: u32 = 4096;

// ---- Loader limits: what one load may read, decode and build ----
//
// Enforced by zline-io before the work they bound: a file's size before
// it is read (and while it is read, for files that grow), an image's
// header before its pixels are decoded, a primitive's triangle count
// before it is tessellated.

/// Largest model file (OBJ, glTF, GLB) or glTF buffer file, in bytes
/// (1 GiB).
pub const MAX_MODEL_FILE_BYTES: u64 = 1 << 30;

/// Largest image file (a texture), in bytes (256 MiB).
pub const MAX_IMAGE_FILE_BYTES: u64 = 256 << 20;

/// Largest MTL or TOML scene file, in bytes (16 MiB).
pub const MAX_TEXT_FILE_BYTES: u64 = 16 << 20;

/// Largest number of material libraries (`mtllib`) one OBJ file may read: each reads an
/// MTL file and appends its materials, so a few bytes of OBJ repeating one
/// must not read it a million times.
pub const MAX_MATERIAL_LIBRARIES: usize = 256;

/// Largest texture, in pixels: 4096 × 4096 (16 Mi pixels, about 360 MiB
/// once stored as f32 RGBA with its mip chain). Each side is also at most
/// `zline_shading::MAX_TEXTURE_SIZE` (16384), so 16384 × 1024 passes and
/// 8192 × 8192 does not.
pub const MAX_TEXTURE_PIXELS: u64 = 1 << 24;

/// Largest number of texture pixels one model file may decode in all:
/// 64 Mi, four textures of 4096 × 4096 (about 1.4 GiB as f32 RGBA with
/// their mip chains).
pub const MAX_TEXTURE_PIXELS_PER_MODEL: u64 = 1 << 26;

/// Largest number of triangles of one model file, and of one scene (every
/// object counted as often as it is placed): 16 Mi.
pub const MAX_TRIANGLES: usize = 1 << 24;

/// Largest number of vertices of one model file, and of one scene (every
/// object counted as often as it is placed): 16 Mi.
pub const MAX_VERTICES: usize = 1 << 24;

/// Largest number of triangles a scene file's primitives (spheres, planes,
/// cubes, tori) may make together: 4 Mi, a sphere of about 1448 × 1448.
/// A few bytes of scene file must not ask for minutes of tessellation and
/// gigabytes of memory, so the budget is lower than [`MAX_TRIANGLES`].
pub const MAX_PRIMITIVE_TRIANGLES: u64 = 1 << 22;

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

/// Samples along each side of an area light: k × k point lights, at most
/// 256 per light (every sample costs a light per lit sample).
pub const MAX_AREA_SAMPLES_PER_SIDE: u32 = 16;

/// Shadow map side (each cube face of a point light), in texels.
pub const MAX_SHADOW_MAP_SIZE: u32 = 8192;
