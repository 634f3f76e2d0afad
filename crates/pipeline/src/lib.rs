//! The zline pipeline: a [`Scene`](zline_scene::Scene) in, an [`Image`] out.
//!
//! How a frame is made, one module per step:
//! 1. [`vertex`]: object → eye → clip space for every vertex; normals by the
//!    inverse transpose; Gouraud colours lit at the vertices.
//! 2. [`clip`]: triangles that leave the view volume's near/far planes or the
//!    guard band are clipped in clip space, before any divide.
//! 3. [`setup`]: divide by w, map to the window, snap to the 1/256 grid, cull
//!    back faces, build the edge table and the depth and attribute planes:
//!    one [`setup::Primitive`] per drawn triangle.
//! 4. [`bin`]: each primitive is listed in the tiles its bounds touch, in
//!    draw order.
//! 5. [`tile`]: every tile is rasterized on its own (rayon over tiles): the
//!    opaque pass with a depth buffer in NC depth (or the painter's
//!    algorithm), the mesh edges of [`lines`] when asked for, then
//!    quantization into the image.
//!
//! Steps 1–3 run once per frame and in parallel over chunks of vertices and
//! triangles; their output order does not depend on the thread count, and
//! tiles only read it, so the image is bit-identical for any number of
//! threads and any tile size.

pub mod adaptive;
pub mod bin;
pub mod clip;
mod coverage;
pub mod fog;
pub mod image;
pub mod layers;
pub mod lines;
pub mod lod;
mod normal_map;
pub mod object_ids;
mod render;
pub mod resolve;
pub mod setup;
mod shadow;
mod shadow_map;
mod sky;
mod tasks;
pub mod tile;
pub mod vertex;
pub mod volume;

pub use bin::{pieces_per_band, MAX_PIECES};
pub use image::Image;
pub use layers::{render_depth, render_normals, DepthImage, DepthRange};
pub use object_ids::{render_object_ids, ObjectIds};
pub use render::inspect::{
    FragmentTrace, Outcome, OutsideImage, Pass, PixelTrace, SampleAttributes, SampleTrace, TextureRead,
};
pub use render::overdraw::{render_overdraw, Overdraw};
pub use render::{render, RenderOptions, RenderStats, Renderer};
