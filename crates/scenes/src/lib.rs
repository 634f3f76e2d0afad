//! The zline built-in scenes, built in code from the scene model of
//! zline-scene and its procedural meshes: no files, no loaders.
//!
//! Modules: `coverage` (white triangles on black whose pixels are areas,
//! for measuring anti-aliasing), `demo` (the demo scene: the three shading modes side by side,
//! texture, transparency and fog), `room` (the course's realistic room: a
//! globe on a table under a pendant lamp, textured floor and walls, planar
//! shadows on the floor), `whitted` (the classic ray-tracing scene: a
//! checkerboard floor, a mirror sphere and a glass sphere) and [`hard_cases`](mod@hard_cases) (scenes that stress
//! numerical stability, each with the outcome a correct render shows).
//! [`terrain`] makes a height field into a landscape scene, its grid
//! simplified to a screen-space error bound.

mod coverage;
mod demo;
pub mod hard_cases;
mod room;
pub mod terrain;
mod whitted;

pub use coverage::coverage_scene;
pub use demo::demo_scene;
pub use hard_cases::{hard_cases, HardCase};
pub use room::{room_scene, ROOM_HALF_WIDTH, ROOM_HEIGHT};
pub use whitted::{whitted_scene, WHITTED_GLASS_IOR};
