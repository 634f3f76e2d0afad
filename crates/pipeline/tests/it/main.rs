//! Integration tests of the pipeline: scenes with answers computed by hand
//! from the SPEC formulas, clipping, draw order and determinism.

mod adaptive;
mod clipping;
mod conventions;
mod coverage;
mod depth_image;
mod depth_modes;
mod determinism;
mod environment;
mod fog;
mod hidden;
mod inspect;
mod interpolation;
mod lines;
mod lit_square;
#[cfg(feature = "simplify")]
mod lod;
mod normal_image;
mod normal_map;
mod object_ids;
mod overdraw;
mod painter;
mod shadows;
mod ssaa;
mod support;
mod texture;
mod transparency;
mod vertex_colors;
