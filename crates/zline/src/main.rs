//! The `zline` command line: render a model or scene file, or the demo.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{bail, Context, Result};
use clap::{Args, Parser, Subcommand, ValueEnum};
use zline::pipeline::{render, RenderOptions};
use zline::scene::{Interpolation, RenderSettings, Scene, ShadingMode};

/// zline — a CPU renderer for the classical rendering pipeline.
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render an OBJ model or a TOML scene file to a PNG.
    Render {
        /// An `.obj` model (framed automatically, with a key and a fill
        /// light) or a `.toml` scene file.
        input: PathBuf,
        #[command(flatten)]
        common: Common,
    },
    /// Render the built-in demo scene (needs no files).
    Demo {
        #[command(flatten)]
        common: Common,
    },
}

#[derive(Args)]
struct Common {
    /// Output PNG file.
    #[arg(short, long, value_name = "OUT.png")]
    output: PathBuf,
    /// Image size, e.g. 1280x720 (default: the scene's, or 800x600).
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Shading mode for objects that do not set their own.
    #[arg(long, value_enum)]
    shading: Option<Shading>,
    /// Attribute interpolation.
    #[arg(long, value_enum)]
    interpolation: Option<Interp>,
    /// Worker threads (default: one per core).
    #[arg(long, value_name = "N")]
    threads: Option<usize>,
    /// Tile edge in pixels; the image does not depend on it.
    #[arg(long, value_name = "PIXELS", default_value_t = RenderOptions::default().tile_size)]
    tile_size: u32,
}

#[derive(Clone, Copy, ValueEnum)]
enum Shading {
    Flat,
    Gouraud,
    Phong,
}

#[derive(Clone, Copy, ValueEnum)]
enum Interp {
    /// Perspective-correct (a/w and 1/w).
    Perspective,
    /// Screen-linear (the seed's formulas).
    Linear,
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(|| format!("expected WxH, e.g. 800x600, got '{s}'"))?;
    let parse = |v: &str| v.trim().parse::<u32>().ok().filter(|n| (1..=16384).contains(n));
    match (parse(w), parse(h)) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => Err(format!("width and height must be whole numbers in 1..=16384, got '{s}'")),
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", one_line(&e));
            ExitCode::FAILURE
        }
    }
}

/// The error and its causes on one line, skipping a cause whose text the
/// message already quotes (loader errors name their source in their own
/// message).
fn one_line(e: &anyhow::Error) -> String {
    let mut line = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if line.contains(&text) {
            continue;
        }
        if !line.is_empty() {
            line.push_str(": ");
        }
        line.push_str(&text);
    }
    line
}

fn run(cli: Cli) -> Result<()> {
    let (mut scene, common) = match cli.command {
        Command::Render { input, common } => (load_input(&input)?, common),
        Command::Demo { common } => (zline::scene::demo_scene(), common),
    };
    apply_overrides(&mut scene.settings, &common);
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(n) = common.threads {
        if n == 0 {
            bail!("--threads must be at least 1");
        }
        pool = pool.num_threads(n);
    }
    let pool = pool.build().context("cannot start the worker threads")?;
    let options = RenderOptions { tile_size: common.tile_size.max(1) };
    let start = Instant::now();
    let (image, stats) = pool.install(|| render(&scene, &options));
    let elapsed = start.elapsed();
    zline::save_png(&image, &common.output)
        .with_context(|| format!("{}: cannot write PNG", common.output.display()))?;
    eprintln!(
        "wrote {} ({}x{}, {} triangles, {} drawn, {} samples shaded, {:.2} ms)",
        common.output.display(),
        image.width,
        image.height,
        stats.triangles,
        stats.primitives,
        stats.fragments,
        elapsed.as_secs_f64() * 1e3
    );
    Ok(())
}

fn load_input(input: &Path) -> Result<Scene> {
    let ext = input.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    Ok(match ext.as_deref() {
        Some("obj") => {
            let meshes = zline::scene::load_obj(input)?;
            zline::scene::scene_for_model(meshes, RenderSettings::default())
        }
        Some("toml") => zline::scene::load_scene(input)?,
        _ => bail!("{}: unsupported input; expected an .obj model or a .toml scene file", input.display()),
    })
}

fn apply_overrides(settings: &mut RenderSettings, common: &Common) {
    if let Some((w, h)) = common.size {
        settings.width = w;
        settings.height = h;
    }
    if let Some(s) = common.shading {
        settings.shading = match s {
            Shading::Flat => ShadingMode::Flat,
            Shading::Gouraud => ShadingMode::Gouraud,
            Shading::Phong => ShadingMode::Phong,
        };
    }
    if let Some(i) = common.interpolation {
        settings.interpolation = match i {
            Interp::Perspective => Interpolation::PerspectiveCorrect,
            Interp::Linear => Interpolation::ScreenLinear,
        };
    }
}
