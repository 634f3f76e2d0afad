//! Scan conversion for zline: window-space triangles in, covered samples and
//! interpolated values out (SPEC §3–4).
//!
//! The stages, each a module:
//! - [`fixed`]: window coordinates snapped to a 1/256-pixel grid, so coverage
//!   is decided with exact integer arithmetic.
//! - [`edge_table`]: the seed's method — an edge table sorted by y and an
//!   active edge list walked one scan line at a time, emitting half-open
//!   [`Span`]s under the top-left rule, clipped to a rectangle (a tile).
//! - [`tie_rule`]: one sample's coverage by edge functions, under the
//!   top-left rule or without it (closed or open triangles), for showing
//!   what the rule prevents.
//! - [`interpolate`]: plane equations for depth and attributes, evaluated
//!   incrementally along spans and re-anchored on a fixed global grid.
//! - [`lanes`]: the edge tables and planes of eight triangles at a time,
//!   bit for bit the scalar ones, for setup vectorized across triangles.
//!
//! This crate knows nothing of lighting, files, threads or colour buffers.

pub mod edge_table;
pub mod fixed;
pub mod interpolate;
pub mod lanes;
pub mod tie_rule;

pub use edge_table::{EdgeTable, Span};
pub use fixed::{first_sample_at_or_after, FixedPoint, Rect, MAX_WINDOW_COORD, SUBPIXEL_BITS, SUBPIXEL_ONE};
pub use interpolate::{
    for_each_block, for_each_sample, AttributePlanes, DepthPlane, PlaneBasis, SampleBlock, LANES,
    REANCHOR_BLOCK,
};
pub use tie_rule::{covers, TieRule};
