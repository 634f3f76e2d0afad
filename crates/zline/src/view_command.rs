//! `zline view`: the command line of the interactive window
//! (`zline::viewer`). The input is loaded and set up by the same closures
//! as `turntable` and `batch` (`job::Job`), so the first frame is the image
//! `zline render` draws with the same flags.

use std::path::PathBuf;

use anyhow::{anyhow, Context, Result};
use clap::Args;
use zline::viewer::state::ViewerState;
use zline::viewer::window::ViewOptions;

use crate::job::Job;

/// The keys and mouse, after `zline view --help`.
pub(crate) const KEYS: &str = "\
Mouse:
  left drag               orbit about the target
  right or middle drag    pan (also shift + left drag)
  wheel                   zoom
Keys:
  1, 2, 3   flat, Gouraud, Phong shading
  T         textures on/off
  F         fog on/off (a scene without fog gets one fitted to its size)
  W         wireframe: none, all, hidden removed, hidden dashed
  M         shadows: none, planar (scenes with shadow planes), map
  + / -     supersampling of the still frame up/down (1..8)
  R         reset the camera
  Z         hidden surfaces: z-buffer or painter's algorithm
  C         back-face culling on/off
  I         interpolation: perspective-correct or affine (screen-linear)
  P         step mode: draw the first triangles only; . one more, , one fewer
  ] / [     step mode: the last triangle one scanline further / back
  O         overdraw heat map: top-left rule, closed triangles, open, off
  D         the depth buffer as an image (near white, far dark)
  X         each mesh's triangles in a shuffled order, or their own
  click     the pixel inspector on the pixel clicked: its report on stdout, a line over the frame
  H         hide/show the frame time
  S         screenshot: the full frame to -o with a number (zline-view-1.png, ...)
  Esc, Q    quit
While the camera moves, frames are drawn at a lower resolution to keep
about 30 frames a second; the full frame follows 150 ms after the input
stops. Nothing is drawn while nothing changes. With --renderer raytrace
(or a scene file's renderer = \"raytrace\") the picture refines
progressively when still: 1/8, 1/4, 1/2 of the resolution, then full.";

/// `zline view`'s own options (the look flags are `render`'s).
#[derive(Args)]
pub(crate) struct ViewArgs {
    /// An `.obj`, `.gltf`, `.glb`, `.stl`, `.ply` or `.3mf` model or a `.toml`
    /// scene file.
    input: PathBuf,
    /// As for `render`: read files the input names outside its folder.
    #[arg(long)]
    pub(crate) allow_paths_outside: bool,
    /// Close the window after N frames were shown (the last frame is shown
    /// again about every 10 ms while nothing changes): for scripts and
    /// tests.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    exit_after_frames: Option<u64>,
    /// Write the first frame the window would show (the full frame, no
    /// text over it) to FILE and exit without opening a window: the image
    /// `zline render` draws with the same flags.
    #[arg(long, value_name = "FILE")]
    save_first_frame: Option<PathBuf>,
    /// Keys pressed before the first frame, as if typed, separated by
    /// spaces, `N*KEY` for N presses: e.g. `--keys "P 299*."` opens in
    /// step mode at the 300th triangle, `--keys "O O"` with the overdraw
    /// map of closed triangles (the keys of `zline view --help` but S, Esc
    /// and Q). Also with --save-first-frame.
    #[arg(long, value_name = "KEYS", allow_hyphen_values = true)]
    keys: Option<String>,
    /// A click on window pixel X,Y before the first frame, after --keys:
    /// the pixel inspector's report on standard output and its line over
    /// the frame, as a click in the window gives.
    #[arg(long, value_name = "X,Y")]
    click: Option<String>,
}

/// `-o` of `zline view`: where S saves screenshots.
pub(crate) fn output_arg(arg: clap::Arg) -> clap::Arg {
    arg.required(false).default_value("zline-view.png").value_name("SHOT.png").help(
        "Where S saves screenshots: SHOT-1.png, SHOT-2.png, … (the first free names; .jpg for JPEG), \
         each written atomically",
    )
}

/// `--timings` of `zline view`: a line per frame.
pub(crate) fn timings_arg(arg: clap::Arg) -> clap::Arg {
    arg.help("Print a line per frame drawn: preview or full, its size and its time in ms")
}

/// Loads the input as `render` does and opens the window (or writes the
/// first frame).
pub(crate) fn run(args: &ViewArgs, job: &Job<'_>, trace: &crate::cli::trace::TraceArgs) -> Result<()> {
    match &args.save_first_frame {
        Some(path) => zline::check_output(path).map_err(|e| anyhow!("{}: {e}", path.display()))?,
        // A folder that takes no file only matters when S is pressed: a
        // warning now, an error line then (the window stays open).
        None => match zline::check_output(&job.output) {
            Err(e) if e.kind() == std::io::ErrorKind::InvalidInput => {
                return Err(anyhow!("{}: {e}", job.output.display()))
            }
            Err(e) => eprintln!("warning: {}: {e}; S will not save screenshots there", job.output.display()),
            Ok(()) => {}
        },
    }
    let (mut scene, framed) = (job.load)(&args.input)?;
    (job.aim)(&mut scene, framed, 0.0);
    let traced = trace.traces(&scene)?.then(|| trace.options(scene.settings.trace));
    let mut state = ViewerState::new(scene);
    if traced.is_some() {
        state.refine_progressively();
    }
    for token in args.keys.iter().flat_map(|k| k.split_whitespace()) {
        let (count, name) = match token.split_once('*') {
            Some((n, name)) => {
                let n = n.parse::<u32>().ok().filter(|n| (1..=100_000).contains(n));
                (n.ok_or_else(|| anyhow!("--keys: {token:?}: the count before * must be 1 to 100000"))?, name)
            }
            None => (1, token),
        };
        let action = zline::viewer::state::Action::from_key_name(name).ok_or_else(|| {
            anyhow!("--keys: {name:?} is not a key of zline view (see zline view --help; S, Esc and Q are not taken)")
        })?;
        for _ in 0..count {
            state.handle(zline::viewer::state::Event::Key(action));
        }
    }
    if let Some(click) = &args.click {
        let pixel = click
            .split_once(',')
            .and_then(|(x, y)| Some((x.trim().parse::<u32>().ok()?, y.trim().parse::<u32>().ok()?)))
            .ok_or_else(|| anyhow!("--click: expected X,Y in window pixels, got {click:?}"))?;
        state.handle(zline::viewer::state::Event::Click(pixel.0, pixel.1));
    }
    if let Some(path) = &args.save_first_frame {
        let scene = state.scene(&state.full_request());
        let options = job.options;
        // As the window draws it.
        let mut image = zline::pipeline::Image::empty();
        let mut renderer = zline::pipeline::Renderer::default();
        let how = (&options, traced.as_ref());
        zline::viewer::window::draw((&scene, state.toggles()), how, &job.pool, &mut renderer, &mut image);
        if let Some((row, previous)) = state.scanline_step(&state.full_request()) {
            let mut below = zline::pipeline::Image::empty();
            zline::viewer::window::draw(
                (&previous, state.toggles()),
                how,
                &job.pool,
                &mut renderer,
                &mut below,
            );
            zline::viewer::window::scanline_compose(&mut image, &below, row);
        }
        zline::save_image(&image, path)
            .with_context(|| format!("{}: cannot write the image", path.display()))?;
        eprintln!("wrote {} ({}x{})", path.display(), image.width, image.height);
        // --click without a window: the report alone.
        if let Some(pixel) = state.take_inspection() {
            let mut renderer = zline::pipeline::Renderer::default();
            let mut frame = zline::pipeline::Image::empty();
            let trace = job.pool.install(|| renderer.inspect(&scene, &options, pixel, &mut frame))?;
            println!("{}", zline::inspect::text(&trace, &scene).trim_end());
        }
        return Ok(());
    }
    let title = args
        .input
        .file_name()
        .map_or_else(|| args.input.display().to_string(), |n| n.to_string_lossy().into());
    let options = ViewOptions {
        title,
        screenshot: job.output.clone(),
        exit_after_frames: args.exit_after_frames,
        render: job.options,
        timings: job.timings,
        trace: traced,
    };
    zline::viewer::window::run(&mut state, &options, &job.pool)
}
