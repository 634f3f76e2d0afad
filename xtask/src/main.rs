//! zline developer tasks. `cargo xtask bench` measures frame times;
//! `cargo xtask regress` compares renders with reference images;
//! `cargo xtask modules` checks that no crate has a module cycle;
//! `cargo xtask kernels` counts the compiled kernel jobs against a budget.

use std::path::PathBuf;

use anyhow::Result;
use clap::{Parser, Subcommand};

mod bench;
mod chart;
mod contact;
mod docs;
mod kernels;
mod modules;
mod radiosity_report;
mod radiosity_subdivision;
mod ray_batch;
mod regress;
mod report;
mod report_lod;
mod report_models;
mod report_renderers;
mod report_shadows;
mod scaling;
mod terrain;
mod timing;
mod trace_aa;
mod trace_embree;
mod trace_report;
mod trace_truth;
mod versus;
mod view_screenshot;

/// Developer tasks for zline.
#[derive(Parser)]
struct Cli {
    #[command(subcommand)]
    task: Task,
}

/// The benchmark scenes to draw, and how (`bench`, `scaling`).
#[derive(clap::Args)]
struct Scenes {
    /// The shared asset folder holding obj/bunny/bunny.obj (skipped with
    /// a message when missing).
    #[arg(long, default_value = "../shared/assets")]
    assets: PathBuf,
    /// Only cases whose name contains this text.
    #[arg(long)]
    filter: Option<String>,
    /// Tile edge in pixels.
    #[arg(long, default_value_t = zline::pipeline::RenderOptions::default().tile_size)]
    tile_size: u32,
}

impl Scenes {
    fn options(&self) -> zline::pipeline::RenderOptions {
        zline::pipeline::RenderOptions { tile_size: self.tile_size }
    }
}

#[derive(Subcommand)]
enum Task {
    /// Median frame times at 1920x1080 for the benchmark scenes, with 1 and
    /// 2 threads, as a markdown table.
    Bench {
        /// Frames timed per case (after one warm-up frame); the median is
        /// reported.
        #[arg(long, default_value_t = 9)]
        frames: usize,
        /// Thread counts to run.
        #[arg(long, value_delimiter = ',', default_value = "1,2")]
        threads: Vec<usize>,
        /// Cut each band of tile rows into this many pieces (1 keeps the
        /// bands whole); by default each thread count chooses its cut.
        #[arg(long, value_parser = clap::value_parser!(u16).range(1..))]
        band_pieces: Option<u16>,
        #[command(flatten)]
        scenes: Scenes,
    },
    /// A model of the frame at more threads than this machine has: each
    /// benchmark scene timed at 1 and 2 threads (alternated), geometry and
    /// binning extrapolated by Amdahl's law, the raster stage from its units
    /// of work (bands of tile rows, cut as each thread count cuts them)
    /// timed at one thread; a markdown table.
    Scaling {
        /// Frames timed per thread count and round (after a warm-up).
        #[arg(long, default_value_t = 15)]
        frames: usize,
        /// Rounds, each timing 1 then 2 threads.
        #[arg(long, default_value_t = 3)]
        rounds: usize,
        /// Thread counts the model predicts.
        #[arg(long, value_delimiter = ',', default_value = "4,8,16,32,64")]
        model: Vec<usize>,
        #[command(flatten)]
        scenes: Scenes,
    },
    /// Count the compiled kernel jobs per SIMD level in the zline binary,
    /// hold them against the budget in xtask/kernels.toml and check that no
    /// AVX intrinsic was left out of line (fails otherwise).
    Kernels {
        /// The binary to read (default: the zline beside this xtask, else
        /// target/release/zline, else xtask itself).
        #[arg(long)]
        binary: Option<PathBuf>,
        /// Build zline with v0 symbol names (target/kernels) and list the
        /// jobs by the kernel they were made from.
        #[arg(long)]
        by_kernel: bool,
    },
    /// Render the texture-mapping pictures of the docs (checkerboard floor:
    /// perspective-correct vs affine, nearest vs trilinear).
    DocsImages {
        /// Output folder.
        #[arg(long, default_value = "docs/images")]
        out: PathBuf,
    },
    /// Render every model of the asset folder (obj/*/*.obj, and per glTF
    /// model its glTF variant, else glTF-Binary) into one grid PNG with each
    /// model's name under its cell, and print the time per model.
    ContactSheet {
        /// The shared asset folder holding obj/ and gltf/.
        #[arg(long, default_value = "../shared/assets")]
        assets: PathBuf,
        /// Output PNG file.
        #[arg(long, default_value = "docs/images/contact-sheet.png")]
        out: PathBuf,
        /// Size of each cell's picture, WxH.
        #[arg(long, default_value = "320x240", value_parser = contact::parse_cell)]
        cell: (u32, u32),
    },
    /// Render every tests/scenes/*.toml and compare it exactly with its
    /// reference PNG; failures are drawn into target/regress/.
    Regress {
        /// Only scenes whose name contains this text.
        #[arg(long)]
        filter: Option<String>,
    },
    /// Rewrite the reference PNGs of tests/scenes/ and say what changed.
    Bless {
        /// Only scenes whose name contains this text.
        #[arg(long)]
        filter: Option<String>,
    },
    /// Speed against error: every setting on every report scene, timed
    /// and compared with the f64 truth; writes a markdown table and a chart.
    Report {
        /// The shared asset folder holding obj/bunny/bunny.obj (skipped with
        /// a message when missing).
        #[arg(long, default_value = "../shared/assets")]
        assets: PathBuf,
        /// The markdown table.
        #[arg(long, default_value = "docs/report.md")]
        out: PathBuf,
        /// The chart.
        #[arg(long, default_value = "docs/images/report-chart.png")]
        chart: PathBuf,
        /// Frames timed per cell (median).
        #[arg(long, default_value_t = 5)]
        frames: usize,
        /// Image size of the benchmark scenes, WxH.
        #[arg(long, default_value = "1920x1080", value_parser = contact::parse_cell)]
        size: (u32, u32),
        /// Only scenes whose name contains this text.
        #[arg(long)]
        filter: Option<String>,
        /// TrueType font for the chart's text.
        #[arg(long, default_value = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf")]
        font: PathBuf,
    },
    /// zline against Mesa's llvmpipe on glref's benchmark scenes
    /// (benches/glref/*.toml beside `<glref>/scenes/*.json`), timed
    /// interleaved: per round every scene with zline at each thread count,
    /// then with llvmpipe; prints the median of the round medians and the
    /// ratio. Needs glref built by its setup.sh.
    Versus(versus::Args),
    /// Write the elevation files of assets/terrain/ (deterministic
    /// diamond-square hills): hills.png, 257x257 16-bit greyscale, and
    /// hills-65.asc, an ESRI ASCII grid of every fourth sample.
    TerrainAsset {
        /// Output folder.
        #[arg(long, default_value = "assets/terrain")]
        out: PathBuf,
    },
    /// Time a 4096x4096 fractal terrain: error pyramid, simplified mesh
    /// and render (median), and the triangles drawn against the full
    /// grid's 2·4095².
    TerrainBench {
        /// Image size, WxH.
        #[arg(long, default_value = "1920x1080", value_parser = contact::parse_cell)]
        size: (u32, u32),
        /// The screen-space error bound in pixels.
        #[arg(long, default_value_t = zline::scenes::terrain::DEFAULT_TERRAIN_ERROR)]
        terrain_error: f32,
        /// Frames rendered after a warm-up frame; the median is reported.
        #[arg(long, default_value_t = 5)]
        frames: usize,
    },
    /// The Ray recipe (docs/ray_batch.py) on a local Ray cluster, one
    /// worker killed mid-shard and retried, checked byte for byte against
    /// a one-machine `zline batch` of the same models; skipped without Ray
    /// (`pip install ray`).
    RayBatch {
        /// Ray tasks, one `zline batch --shard I/N` each.
        #[arg(long, default_value_t = 3)]
        shards: u32,
        /// Image size, WxH.
        #[arg(long, default_value = "320x240")]
        size: String,
    },
    /// The module import graph of every crate (crates/*/src, xtask/src):
    /// module, edge and cycle counts; fails if a module imports one that
    /// imports it back.
    Modules {
        /// Print every module's imports too.
        #[arg(long)]
        verbose: bool,
    },
    /// The ray tracer measured: its acceleration structures side by side
    /// (build, size, rays per second, nodes and triangles per ray, equal
    /// hits; a million random rays against brute force), adaptive against
    /// regular supersampling at equal error, and its error against the
    /// f64 truth beside the rasterizer's.
    TraceReport {
        /// The shared asset folder holding obj/teapot/teapot.obj (a sphere
        /// stands in when missing).
        #[arg(long, default_value = "../shared/assets")]
        assets: PathBuf,
        /// Frame width of the camera rays, in pixels.
        #[arg(long, default_value_t = 640)]
        width: u32,
        /// The acceleration structures (with none of the three: all).
        #[arg(long)]
        accel: bool,
        /// The anti-aliasing.
        #[arg(long)]
        antialias: bool,
        /// The error against the f64 truth (at most 320 pixels wide).
        #[arg(long)]
        truth: bool,
        /// Against Embree's viewer (Debian's embree-tools), this many
        /// alternated rounds; 640-pixel frames whatever --width says.
        #[arg(long, value_name = "ROUNDS", num_args = 0..=1, default_missing_value = "3")]
        embree: Option<usize>,
    },
    /// Radiosity on the Cornell box: the three solvers to the same
    /// residual, the time to a first useful picture, convergence curves
    /// as CSV.
    RadiosityReport {
        /// Where the convergence curves go (CSV).
        #[arg(long, default_value = "target/radiosity-convergence.csv")]
        out: PathBuf,
    },
    /// A real screenshot of `zline view`: the viewer on a private Xvfb
    /// (started here; skipped with a message when Xvfb is not installed),
    /// the picture read from the X server's framebuffer and checked
    /// against zline's own render of the frame.
    ViewScreenshot {
        /// Where the PNG goes (relative to the workspace).
        #[arg(long, default_value = "docs/images/view.png")]
        out: PathBuf,
        /// The window size, WxH.
        #[arg(long, default_value = "640x480", value_parser = contact::parse_cell)]
        size: (u32, u32),
        /// The model or scene file (relative to the workspace).
        #[arg(default_value = "assets/obj/spot/spot.obj")]
        model: PathBuf,
        /// More `zline view` flags, after `--` (e.g. -- --ssaa 2).
        #[arg(last = true)]
        flags: Vec<String>,
    },
}

fn main() -> Result<()> {
    match Cli::parse().task {
        Task::Bench { frames, threads, band_pieces, scenes } => bench::run(
            (frames, band_pieces.map(usize::from)),
            &threads,
            &scenes.assets,
            scenes.filter.as_deref(),
            &scenes.options(),
        ),
        Task::Scaling { frames, rounds, model, scenes } => scaling::run(
            (frames, rounds),
            &model,
            &scenes.assets,
            scenes.filter.as_deref(),
            &scenes.options(),
        ),
        Task::DocsImages { out } => docs::run(&out),
        Task::ContactSheet { assets, out, cell } => contact::run(&assets, &out, cell),
        Task::Regress { filter } => regress::run(regress::Mode::Check, filter.as_deref()),
        Task::Bless { filter } => regress::run(regress::Mode::Bless, filter.as_deref()),
        Task::Report { assets, out, chart, frames, size, filter, font } => {
            report::run(&report::Args { assets, out, chart, frames, size, filter, font })
        }
        Task::Versus(args) => versus::run(&args),
        Task::Modules { verbose } => modules::run(verbose),
        Task::TraceReport { assets, width, accel, antialias, truth, embree } => {
            let all = !(accel || antialias || truth || embree.is_some());
            trace_report::run(&trace_report::Args {
                assets: &assets,
                width,
                accel: accel || all,
                antialias: antialias || all,
                truth: truth || all,
            })?;
            embree.map_or(Ok(()), trace_embree::run)
        }
        Task::RadiosityReport { out } => radiosity_report::run(&out),
        Task::RayBatch { shards, size } => ray_batch::run(shards, &size),
        Task::ViewScreenshot { out, size, model, flags } => view_screenshot::run(&out, &model, size, &flags),
        Task::TerrainAsset { out } => terrain::write_assets(&out),
        Task::Kernels { binary, by_kernel } => kernels::run(binary, by_kernel),
        Task::TerrainBench { size, terrain_error, frames } => terrain::bench(size, terrain_error, frames),
    }
}
