//! `zline inspect INPUT --pixel X,Y [--json] [-- RENDER FLAGS]`: the pixel
//! inspector over `zline render`'s own argument parsing, the image written
//! to a temporary file (`render --inspect` does the same with an image
//! kept).

use std::ffi::OsString;
use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;

/// The arguments of `zline inspect`.
#[derive(Args)]
pub(crate) struct InspectArgs {
    /// A model (`.obj`, `.gltf`, `.glb`, `.stl`, `.ply`, `.3mf`) or a `.toml`
    /// scene file.
    input: PathBuf,
    /// The pixel: column X and row Y from the top left, in the image's
    /// pixels.
    #[arg(long, value_name = "X,Y")]
    pixel: String,
    /// The report as JSON instead of text.
    #[arg(long)]
    json: bool,
    /// As for `render`: read files the input names outside its folder.
    #[arg(long)]
    allow_paths_outside: bool,
    /// `zline render` flags (size, shading, camera, …), after `--`.
    #[arg(last = true, value_name = "RENDER FLAGS")]
    flags: Vec<String>,
}

/// Renders through `render` (the CLI's own parsing) with `--inspect`.
pub(crate) fn run(args: &InspectArgs, render: &dyn Fn(Vec<OsString>) -> Result<()>) -> Result<()> {
    let dir = tempfile::tempdir().context("cannot make a temporary folder for the image")?;
    let image = dir.path().join("inspected.png");
    let mut argv: Vec<OsString> = vec![
        "zline".into(),
        "render".into(),
        args.input.clone().into(),
        "-o".into(),
        image.into(),
        "--quiet".into(),
    ];
    argv.extend(["--inspect".into(), args.pixel.clone().into()]);
    if args.json {
        argv.push("--inspect-json".into());
    }
    if args.allow_paths_outside {
        argv.push("--allow-paths-outside".into());
    }
    argv.extend(args.flags.iter().map(OsString::from));
    render(argv)
}
