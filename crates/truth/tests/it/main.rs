//! Integration tests of the ground truth: scenes with hand-computed
//! answers, property tests against the fast renderer, and determinism.

mod bump;
mod cook_torrance;
mod emission_colors;
mod environment;
mod hand;
mod sample_viewer;
mod shadows;
mod supersampling;
mod support;
mod surface_maps;
mod threads;
mod versus_fast;
mod whitted;
