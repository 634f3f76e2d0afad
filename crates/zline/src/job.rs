//! What the command line hands to `zline turntable` and `zline batch`: the
//! common render options already checked and turned into closures, so that
//! those commands depend on no item of the binary's root.

use std::path::{Path, PathBuf};

use anyhow::Result;
use zline::pipeline::RenderOptions;
use zline::scene::Scene;

/// Loads an input and applies the common flags but the camera's (as
/// `render` does); gives the scene and whether its camera is zline's
/// framing.
pub(crate) type Load<'a> = Box<dyn Fn(&Path) -> Result<(Scene, bool)> + 'a>;

/// Applies the camera flags to a loaded scene (framed or not), the azimuth
/// turned by the given degrees more.
pub(crate) type Aim<'a> = Box<dyn Fn(&mut Scene, bool, f32) + 'a>;

/// The common options of a render, for commands that render many images.
pub(crate) struct Job<'a> {
    /// `-o`.
    pub(crate) output: PathBuf,
    /// `--timings`: per-file lines with their times.
    pub(crate) timings: bool,
    /// `--quiet`: no progress bar and no per-file lines.
    pub(crate) quiet: bool,
    /// The tile size.
    pub(crate) options: RenderOptions,
    /// The worker threads (`--threads`).
    pub(crate) pool: std::sync::Arc<rayon::ThreadPool>,
    /// Loading and setting up an input.
    pub(crate) load: Load<'a>,
    /// The camera flags.
    pub(crate) aim: Aim<'a>,
    /// An error and its causes on one line.
    pub(crate) describe: fn(&anyhow::Error) -> String,
}
