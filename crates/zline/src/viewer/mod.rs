//! `zline view`: an interactive window on a model or scene, drawn by the
//! CPU renderer (no GPU).
//!
//! - `state`: the state machine — camera orbit, pan and zoom, the keys'
//!   settings, the preview resolution from the last frames' times, the
//!   full frame after the input stops — driven by `Event`s, with no
//!   window: tested headless.
//! - `window`: the minifb window (X11, libX11 loaded at run time) that
//!   feeds the state machine and presents its frames.
//! - `keys`: keys named on the command line (`--keys`) as actions.
//! - `scene_edits`: the scene changes the keys make that need no state.
//! - `overlay`: nearest-neighbour upscaling and the frame-time text.
//! - `xwd` and `capture`: a real screenshot under Xvfb, read back from the
//!   X server's framebuffer (`cargo xtask view-screenshot` and the tests).

pub mod capture;
pub mod keys;
pub mod overlay;
mod scene_edits;
pub mod state;
pub mod window;
pub mod xwd;
