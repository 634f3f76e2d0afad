//! The `zline` command line: render a model or scene file, the demo, or a
//! terrain from elevation data (`terrain`).

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

mod cli;

use cli::choices::BuiltIn;
use cli::common::Common;
use cli::load::{info, load_input};

use anyhow::{anyhow, bail, Context, Result};
use clap::{Parser, Subcommand};
use glam::Vec3;
use zline::io::LoadOptions;
use zline::pipeline::RenderOptions;
use zline::pipeline::RenderStats;
use zline::scene::{Scene, MAX_SAMPLES, MAX_THREADS};

mod batch;
mod check_command;
mod flags;
mod inspect_command;
mod job;
mod progress;
mod scan_command;
mod sheet;
mod terrain;
mod thumbnail;
mod turntable;
#[cfg(feature = "view")]
mod view_command;

use flags::{apply_camera, apply_environment, apply_fog, apply_model, apply_overrides, apply_shadows};

/// zline — a CPU renderer for the classical rendering pipeline.
#[derive(Parser)]
#[command(
    version,
    about = "Render 3D models (OBJ, glTF, STL, PLY, 3MF) and scene files to PNG images on the CPU, no GPU needed: \
             z-buffer, flat, Gouraud and Phong shading, textures, fog, transparency, shadows."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a model (OBJ, glTF, STL, PLY, 3MF) or a TOML scene file to a PNG.
    Render {
        /// An `.obj`, `.gltf`, `.glb`, `.stl`, `.ply` or `.3mf` model (framed automatically unless a
        /// glTF file brings its own camera; a key and a fill light unless it
        /// brings lights) or a `.toml` scene file; `-` reads standard input
        /// (the format told from its bytes, files it names looked up in the
        /// current folder).
        input: PathBuf,
        /// Read the files the input names (mtllib, map_Kd, glTF URIs, a
        /// scene's models) even outside the folder of the file naming them;
        /// by default absolute paths and `..` leading out are refused.
        #[arg(long)]
        allow_paths_outside: bool,
        #[command(flatten)]
        common: Common,
    },
    /// Render and compare against a reference PNG: exact by default, with
    /// tolerances as options; on a failure the rendered image and a heat
    /// map of the differences are written. Exit code 0: passed; 1: failed.
    /// Render flags go after `--`, e.g. `zline check scene.toml -- --ssaa 2`.
    Check(check_command::CheckArgs),
    /// A square PNG thumbnail of a model: framed, transparent (or on
    /// --background), 2 × 2 supersampled, with a time and an input size
    /// cap; what a file manager's thumbnailer runs.
    Thumbnail(thumbnail::ThumbnailArgs),
    /// Install or remove zline as the desktop's thumbnailer for model files
    /// (a freedesktop .thumbnailer file and the MIME types).
    Thumbnailer {
        #[command(subcommand)]
        action: thumbnail::ThumbnailerAction,
    },
    /// The pixel inspector: every fragment that touched pixel X,Y of the
    /// render, in draw order, with the edge table's span, the depth test,
    /// the colours before and after, fog, the resolve and the 8-bit result
    /// (checked against the rendered image). Render flags go after `--`,
    /// e.g. `zline inspect bunny.ply --pixel 320,240 -- --ssaa 2`.
    Inspect(inspect_command::InspectArgs),
    /// Scan conversion step by step: the edge table, the active edge list
    /// row by row, the spans and the depth along them, for one triangle
    /// in window space (the renderer's own fixed-point walk).
    Scan(scan_command::ScanArgs),
    /// Render a built-in scene (needs no files).
    Demo {
        /// Which built-in scene: the demo (shading modes, texture,
        /// transparency, fog) or the room (a globe and a lamp, planar
        /// shadows on the floor).
        #[arg(long, value_enum, default_value_t = BuiltIn::Demo)]
        scene: BuiltIn,
        #[command(flatten)]
        common: Common,
    },
    /// Describe a model or scene file: triangles, vertices, bounds,
    /// materials, textures, lights, camera and warnings.
    Info {
        /// An `.obj`, `.gltf`, `.glb`, `.stl`, `.ply` or `.3mf` model or a `.toml`
        /// scene file; `-` reads standard input.
        input: PathBuf,
        /// Print JSON (one object) for scripts instead of text.
        #[arg(long)]
        json: bool,
        /// As for `render`: read files the input names outside its folder.
        #[arg(long)]
        allow_paths_outside: bool,
    },
    /// Render an elevation file (a greyscale PNG, 8 or 16 bits, or an ESRI
    /// ASCII grid .asc) as a lit, fogged landscape seen from above at an
    /// angle; the grid is simplified to the triangles the view needs
    /// (default size 1280x720).
    Terrain {
        /// The elevation file: .png or .asc.
        heights: PathBuf,
        #[command(flatten)]
        terrain: terrain::TerrainArgs,
        #[command(flatten)]
        common: Common,
    },
    /// Render a model turning a full circle about its up axis: an animated
    /// GIF (.gif), an animated PNG (.png) or numbered PNGs in a folder.
    #[command(mut_arg("output", turntable::output_arg))]
    Turntable {
        #[command(flatten)]
        turntable: turntable::TurntableArgs,
        #[command(flatten)]
        common: Common,
    },
    /// Render many models or scene files to OUTDIR/<stem>.png, skipping
    /// those already there; `--shard I/N` splits the work among machines.
    #[command(mut_arg("output", batch::output_arg))]
    Batch {
        #[command(flatten)]
        batch: batch::BatchArgs,
        #[command(flatten)]
        common: Common,
    },
    /// Open a window on a model or scene file and turn it with the mouse:
    /// drawn on the CPU as `render` draws it, the same flags setting the
    /// first view (--size is the window's). Needs an X display (X11 or
    /// XWayland).
    #[cfg(feature = "view")]
    #[command(
        mut_arg("output", view_command::output_arg),
        mut_arg("timings", view_command::timings_arg),
        after_help = view_command::KEYS
    )]
    View {
        #[command(flatten)]
        view: view_command::ViewArgs,
        #[command(flatten)]
        common: Common,
    },
}

fn main() -> ExitCode {
    ExitCode::from(exit_code(|| run(Cli::parse())))
}

/// Runs `f` and gives the process's exit code: 0 on success, 1 with one
/// `error:` line on an error — and 1 with one `error: internal error` line
/// on a panic, in this thread or a worker, rather than Rust's exit code 101
/// and its multi-line report (a backtrace follows only when
/// `RUST_BACKTRACE` asks for one). A panic is a bug in zline: the tests
/// look for that line.
fn exit_code(f: impl FnOnce() -> Result<()> + std::panic::UnwindSafe) -> u8 {
    static REPORTED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
    std::panic::set_hook(Box::new(|info| {
        // Workers may panic together: the first one is reported.
        if REPORTED.swap(true, std::sync::atomic::Ordering::SeqCst) {
            return;
        }
        let payload = info.payload();
        let message = payload
            .downcast_ref::<&str>()
            .copied()
            .or_else(|| payload.downcast_ref::<String>().map(String::as_str))
            .unwrap_or("a panic");
        let at = info.location().map(|l| format!(" at {}:{}", l.file(), l.line())).unwrap_or_default();
        eprintln!("error: internal error (a bug in zline, please report it): {message}{at}");
        let trace = std::backtrace::Backtrace::capture();
        if trace.status() == std::backtrace::BacktraceStatus::Captured {
            eprintln!("{trace}");
        }
    }));
    let result = std::panic::catch_unwind(f);
    let _ = std::panic::take_hook();
    match result {
        Ok(Ok(())) => 0,
        Ok(Err(e)) => {
            eprintln!("error: {}", zline::error_line(&e));
            1
        }
        Err(_) => 1,
    }
}

/// Runs `zline render` (or any command) on an argument list, as the
/// command line would: `check` and `thumbnail` render through it.
fn render_argv(argv: Vec<std::ffi::OsString>) -> Result<()> {
    let cli = Cli::try_parse_from(argv).map_err(|e| {
        let text = e.to_string();
        anyhow!("{}", text.lines().next().unwrap_or("bad render flags").trim_start_matches("error: "))
    })?;
    run(cli)
}

fn run(cli: Cli) -> Result<()> {
    let (input, built_in, allow_paths_outside, common, terrain) = match cli.command {
        Command::Info { input, json, allow_paths_outside } => {
            return info(&input, json, LoadOptions { allow_outside: allow_paths_outside })
        }
        Command::Check(check) => return check_command::run(&check, &render_argv),
        Command::Thumbnail(thumbnail) => return thumbnail::run(&thumbnail, &render_argv),
        Command::Thumbnailer { action } => return thumbnail::thumbnailer(&action),
        Command::Scan(scan) => return scan_command::run(&scan),
        Command::Inspect(inspect) => return inspect_command::run(&inspect, &render_argv),
        Command::Render { input, allow_paths_outside, common } => {
            (Some(input), BuiltIn::Demo, allow_paths_outside, common, None)
        }
        Command::Demo { scene, common } => (None, scene, false, common, None),
        Command::Terrain { heights, terrain, common } => {
            (Some(heights), BuiltIn::Demo, false, common, Some(terrain))
        }
        Command::Turntable { turntable, common } => {
            common.layers.refuse("turntable")?;
            common.trace.refuse("turntable")?;
            let allow_outside = turntable.allow_paths_outside;
            return turntable::run(&turntable, &job(&common, allow_outside)?);
        }
        Command::Batch { batch, common } => {
            common.layers.refuse("batch")?;
            common.trace.refuse("batch")?;
            let allow_outside = batch.allow_paths_outside;
            return batch::run(&batch, &job(&common, allow_outside)?);
        }
        #[cfg(feature = "view")]
        Command::View { view, common } => {
            common.layers.refuse("view")?;
            common.trace.check()?;
            let allow_outside = view.allow_paths_outside;
            return view_command::run(&view, &job(&common, allow_outside)?, &common.trace);
        }
    };
    // Everything that can be checked without the scene is checked before
    // loading it: a bad output path or thread count fails at once.
    zline::check_output(&common.output).map_err(|e| anyhow!("{}: {e}", common.output.display()))?;
    common.layers.check(&common.output)?;
    common.trace.check()?;
    if common.trace.asks_to_trace() {
        common.layers.refuse("render --renderer raytrace")?;
    }
    let threads = thread_count(common.threads)?;
    if let (Some((w, h)), Some(n)) = (common.size, common.ssaa) {
        // Both from the flags: no need to load the scene to refuse them.
        check_samples(w, h, n)?;
    }
    let loading = Instant::now();
    let mut scene = match (&input, &terrain) {
        (Some(heights), Some(terrain)) => terrain::scene(heights, terrain, common.size)?,
        (Some(input), None) => load_input(input, LoadOptions { allow_outside: allow_paths_outside })?,
        (None, _) => built_in.scene(),
    };
    // Judged before the size changes: a camera that is zline's framing of a
    // model is framed again for the final image's shape.
    let framed = input.is_some() && zline::view::is_framed(&scene);
    set_up(&mut scene, &common)?;
    if common.views.is_none() {
        apply_camera(&mut scene, &common, framed, 0.0);
    }
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        pool = pool.num_threads(n);
    }
    let pool = pool.build().context("cannot start the worker threads")?;
    let loaded = loading.elapsed();
    let options = RenderOptions { tile_size: common.tile_size };
    if common.trace.radiosity(&scene) {
        scene = pool.install(|| common.radiosity.display(&scene))?;
    } else {
        common.radiosity.check_unused()?;
    }
    if let Some(views) = &common.views {
        common.layers.refuse("--views")?;
        if common.trace.traces(&scene)? {
            bail!("--views draws its sheet with the rasterizer (or radiosity), not the ray tracer");
        }
        return sheet::write(&scene, &common, &views.0, framed, &pool, &options);
    }
    if common.trace.traces(&scene)? {
        common.layers.refuse("the ray tracer")?;
        return ray_trace(&scene, &common, &pool, loaded);
    }
    let start = Instant::now();
    let (image, stats, depth) = pool.install(|| common.layers.render(&scene, &options));
    let elapsed = start.elapsed();
    let saved = save_output(&image, &common)?;
    let count = |n: u64, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
    say_written(
        &image,
        &common,
        format_args!(
            "{}, {} drawn, {} shaded, {:.2} ms",
            count(stats.triangles, "triangle", "triangles"),
            stats.primitives,
            count(stats.fragments, "sample", "samples"),
            elapsed.as_secs_f64() * 1e3
        ),
    );
    common.layers.write(&scene, &options, &pool, (depth, common.quiet))?;
    if let Some(why) = blank_image(&scene, &stats) {
        let name = input.as_deref().map_or_else(|| built_in.name().into(), |p| p.display().to_string());
        eprintln!("warning: {name}: the image is blank: {why}");
    }
    if common.timings {
        let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
        eprintln!(
            "timings: load {:.1} ms, render {:.1} ms (geometry {:.1}, binning {:.1}, raster {:.1}), PNG {:.1} ms ({} bytes)",
            ms(loaded),
            ms(elapsed),
            ms(stats.geometry),
            ms(stats.binning),
            ms(stats.raster),
            ms(saved),
            std::fs::metadata(&common.output).map_or(0, |m| m.len())
        );
        if stats.hidden > 0 {
            eprintln!(
                "timings: hierarchical depth: {} primitives skipped whole in tiles already drawn nearer (once per tile and pass)",
                stats.hidden
            );
        }
        if scene.settings.adaptive_tolerance.is_some() {
            eprintln!(
                "timings: level of detail: {} of {} objects simplified, {} -> {} triangles",
                stats.simplified,
                scene.objects.len(),
                stats.triangles,
                stats.triangles_drawn
            );
        }
    }
    Ok(())
}

/// The `wrote OUT (WxH, details)` line, unless `--quiet`.
fn say_written(image: &zline::pipeline::Image, common: &Common, details: std::fmt::Arguments<'_>) {
    if !common.quiet {
        eprintln!("wrote {} ({}x{}, {details})", common.output.display(), image.width, image.height);
    }
}

/// Writes the image to `--output` and returns how long that took.
fn save_output(image: &zline::pipeline::Image, common: &Common) -> Result<std::time::Duration> {
    let saving = Instant::now();
    zline::save_image(image, &common.output)
        .with_context(|| format!("{}: cannot write the image", common.output.display()))?;
    Ok(saving.elapsed())
}

/// `render --renderer raytrace`: traces, writes the image and says what it
/// cost.
fn ray_trace(
    scene: &Scene,
    common: &Common,
    pool: &rayon::ThreadPool,
    loaded: std::time::Duration,
) -> Result<()> {
    let options = common.trace.options(scene.settings.trace);
    let (image, traced) = pool.install(|| zline::ray_traced_image(scene, &options));
    for warning in &traced.warnings {
        eprintln!("warning: {warning}");
    }
    let saved = save_output(&image, common)?;
    let w = traced.work;
    let pixels = (u64::from(image.width) * u64::from(image.height)).max(1);
    let rays = w.primary.rays + w.secondary.rays + w.shadow.rays;
    say_written(
        &image,
        common,
        format_args!(
        "ray traced: {} camera, {} reflected or transmitted, {} shadow rays, {:.2} a pixel, tree depth {}, {:.2} ms + {:.2} ms to build the {}",
        w.primary.rays,
        w.secondary.rays,
        w.shadow.rays,
        rays as f64 / pixels as f64,
        w.depth,
        traced.trace.as_secs_f64() * 1e3,
        traced.build.as_secs_f64() * 1e3,
        options.accel.name()
        ),
    );
    if common.timings {
        let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
        let per_ray = |c: zline::trace::accel::Counters| {
            let n = c.rays.max(1) as f64;
            format!("{:.1} nodes, {:.1} triangles", c.nodes as f64 / n, c.tests as f64 / n)
        };
        eprintln!(
            "timings: load {:.1} ms, build {:.1} ms, trace {:.1} ms ({:.2} Mrays/s), PNG {:.1} ms; per camera ray {}, per shadow ray {}",
            ms(loaded),
            ms(traced.build),
            ms(traced.trace),
            rays as f64 / traced.trace.as_secs_f64().max(1e-9) / 1e6,
            ms(saved),
            per_ray(w.primary),
            per_ray(w.shadow)
        );
    }
    Ok(())
}

/// The common options as `turntable` and `batch` take them, checked as
/// `render` checks them before loading anything.
fn job(common: &Common, allow_outside: bool) -> Result<job::Job<'_>> {
    if common.views.is_some() {
        bail!(
            "--views writes one contact sheet: an option of render and demo, not of view, turntable or batch"
        );
    }
    let threads = thread_count(common.threads)?;
    if let (Some((w, h)), Some(n)) = (common.size, common.ssaa) {
        check_samples(w, h, n)?;
    }
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        pool = pool.num_threads(n);
    }
    let pool = std::sync::Arc::new(pool.build().context("cannot start the worker threads")?);
    let solver = pool.clone();
    Ok(job::Job {
        output: common.output.clone(),
        timings: common.timings,
        quiet: common.quiet,
        options: RenderOptions { tile_size: common.tile_size },
        pool,
        load: Box::new(move |input| {
            let mut scene = load_input(input, LoadOptions { allow_outside })?;
            let framed = zline::view::is_framed(&scene);
            set_up(&mut scene, common)?;
            // Radiosity is solved once an input; its frames only rasterize.
            if common.trace.radiosity(&scene) {
                scene = solver.install(|| common.radiosity.display(&scene))?;
            } else {
                common.radiosity.check_unused()?;
            }
            Ok((scene, framed))
        }),
        aim: Box::new(|scene, framed, turn| apply_camera(scene, common, framed, turn)),
        describe: zline::error_line,
    })
}

/// The flags other than the camera's applied to a loaded scene, as
/// `render` does: normal maps, `--bump`, `--model`, the settings, fog and
/// shadows; then the sample budget checked.
fn set_up(scene: &mut Scene, common: &Common) -> Result<()> {
    if common.no_normal_maps {
        for object in &mut scene.objects {
            if object.mesh.normal_map.is_some() {
                object.mesh =
                    std::sync::Arc::new(zline::scene::Mesh { normal_map: None, ..(*object.mesh).clone() });
            }
        }
    }
    if let Some(file) = &common.bump {
        if zline::io::apply_bump_map(scene, file, common.bump_scale)? == 0 {
            eprintln!("warning: --bump: no mesh has texture coordinates; nothing is bump-mapped");
        }
    }
    apply_model(scene, common);
    apply_environment(scene, common)?;
    apply_overrides(&mut scene.settings, common);
    apply_fog(scene, common);
    apply_shadows(scene, common);
    common.visibility.apply_scene(scene);
    check_samples(scene.settings.width, scene.settings.height, scene.settings.ssaa)?;
    Ok(())
}

/// `--threads`: at least 1; more than [`MAX_THREADS`] are clamped to it
/// with a warning. Without the flag, rayon's default: `RAYON_NUM_THREADS`
/// (clamped the same way) or one per core.
fn thread_count(threads: Option<usize>) -> Result<Option<usize>> {
    let clamp = |n: usize, what: &str| {
        eprintln!(
            "warning: {what}{n} is more than the {MAX_THREADS} threads zline starts; using {MAX_THREADS}"
        );
        Ok(Some(MAX_THREADS))
    };
    match threads {
        Some(0) => bail!("--threads must be at least 1"),
        Some(n) if n > MAX_THREADS => clamp(n, "--threads "),
        Some(n) => Ok(Some(n)),
        None => match std::env::var("RAYON_NUM_THREADS").ok().and_then(|v| v.trim().parse::<usize>().ok()) {
            Some(n) if n > MAX_THREADS => clamp(n, "RAYON_NUM_THREADS="),
            _ => Ok(None),
        },
    }
}

/// Refuses a frame of more than [`MAX_SAMPLES`] samples (width × height ×
/// ssaa², after the flags), before anything is allocated for it.
fn check_samples(w: u32, h: u32, ssaa: u32) -> Result<()> {
    let n = ssaa.max(1);
    let samples = u128::from(w) * u128::from(h) * u128::from(n) * u128::from(n);
    if samples > u128::from(MAX_SAMPLES) {
        bail!(
            "{w}x{h} pixels at ssaa {n} are {samples} samples, more than the limit of {MAX_SAMPLES} \
             (2^28, 4 GiB of sample buffers at 16 bytes each): lower --size or --ssaa"
        );
    }
    Ok(())
}

/// Why a frame drew nothing, when it drew nothing: no triangles, every
/// triangle culled, clipped or degenerate (with the scene's bounds, which
/// show a model too large or too small for `f32`), or no sample covered.
fn blank_image(scene: &Scene, stats: &RenderStats) -> Option<String> {
    // Lines alone shade no samples.
    let lines_only = scene.settings.wireframe.only && scene.settings.wireframe.drawn();
    if stats.fragments > 0 || lines_only {
        return None;
    }
    if stats.triangles == 0 {
        return Some("the scene has no triangles".into());
    }
    let tris = |n: u64| format!("{n} triangle{}", if n == 1 { "" } else { "s" });
    if stats.primitives > 0 {
        return Some(format!(
            "{} drawn, but none covers a sample (all smaller than a pixel, or outside the image)",
            tris(stats.primitives)
        ));
    }
    let points = scene
        .objects
        .iter()
        .flat_map(|o| o.mesh.positions.iter().map(move |p| o.world_from_object.transform_point3(*p)));
    let (min, max) = points.fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| (lo.min(p), hi.max(p)));
    let (size, (lo, hi)) = (max - min, (short(min), short(max)));
    let bounds = if size.is_finite() {
        format!("the scene spans {lo} to {hi}, a size of {}", short(size))
    } else {
        format!("the scene spans {lo} to {hi}, more than f32 can measure")
    };
    let all = match stats.triangles {
        1 => "its one triangle was".to_string(),
        n => format!("all {} were", tris(n)),
    };
    Some(format!(
        "{all} culled, clipped or degenerate (too small or too large to draw, or facing away); {bounds}"
    ))
}

/// A point for a message: plain numbers when they read well, else
/// scientific (1e38, not 39 digits).
fn short(v: Vec3) -> String {
    let num =
        |x: f32| if x == 0.0 || (1e-3..1e6).contains(&x.abs()) { format!("{x}") } else { format!("{x:e}") };
    format!("({}, {}, {})", num(v.x), num(v.y), num(v.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_anywhere_is_exit_code_1() {
        assert_eq!(exit_code(|| Ok(())), 0);
        assert_eq!(exit_code(|| bail!("a plain error")), 1);
        assert_eq!(exit_code(|| panic!("in the main thread")), 1);
        let in_workers = || {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
            pool.install(|| {
                rayon::prelude::ParallelIterator::for_each(
                    rayon::prelude::IntoParallelIterator::into_par_iter(0..64),
                    |i| assert!(i < 60, "in a worker"),
                )
            });
            Ok(())
        };
        assert_eq!(exit_code(in_workers), 1);
    }

    #[test]
    fn a_blank_image_says_why() {
        let scene = zline::scenes::demo_scene();
        let stats = |triangles, primitives, fragments| RenderStats {
            triangles,
            primitives,
            fragments,
            ..Default::default()
        };
        assert_eq!(blank_image(&scene, &stats(10, 5, 1)), None);
        assert_eq!(blank_image(&scene, &stats(0, 0, 0)).unwrap(), "the scene has no triangles");
        let why = blank_image(&scene, &stats(10, 5, 0)).unwrap();
        assert!(why.starts_with("5 triangles drawn, but none covers a sample"), "{why}");
        let why = blank_image(&scene, &stats(10, 0, 0)).unwrap();
        assert!(
            why.starts_with("all 10 triangles were culled") && why.contains("the scene spans ("),
            "{why}"
        );
    }

    #[test]
    fn the_sample_budget_is_width_height_and_ssaa_squared() {
        assert!(check_samples(16384, 16384, 1).is_ok());
        assert!(check_samples(8192, 8192, 2).is_ok());
        assert!(check_samples(2048, 2048, 8).is_ok());
        assert!(check_samples(2049, 2048, 8).is_err());
        assert!(check_samples(16384, 16384, 2).is_err());
        let e = check_samples(u32::MAX, u32::MAX, u32::MAX).unwrap_err().to_string();
        assert!(e.contains("268435456") && e.contains("--ssaa"), "{e}");
    }
}
