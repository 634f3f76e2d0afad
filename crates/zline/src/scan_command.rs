//! `zline scan`: the scan trace of one triangle, given in window space
//! or taken from a model by its camera (`zline::scan`, `zline::scan_page`).

use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context, Result};
use clap::Args;
use zline::io::LoadOptions;

use crate::cli::load::load_input;

/// `zline scan`'s arguments.
#[derive(Args)]
pub(crate) struct ScanArgs {
    /// A model or scene file whose triangle `--index` (of object
    /// `--object`) to trace, seen by its camera (a model framed as
    /// `render` frames it).
    #[arg(conflicts_with = "triangle", required_unless_present = "triangle")]
    input: Option<PathBuf>,
    /// The input's object (default 0).
    #[arg(long, default_value_t = 0, requires = "input")]
    object: usize,
    /// The input's triangle (default 0).
    #[arg(long, default_value_t = 0, requires = "input")]
    index: usize,
    /// A triangle of its own: three vertices `x,y,z` in pixels (y down;
    /// z the depth), e.g. `--triangle "0,0,0 0,4,0 4,0,1"`.
    #[arg(long, value_name = "X,Y,Z X,Y,Z X,Y,Z", allow_hyphen_values = true)]
    triangle: Option<String>,
    /// The window, which clips the rows and columns (default 64x64 for
    /// --triangle, the scene's size for an input).
    #[arg(long, value_name = "WxH", value_parser = crate::cli::parse::parse_size)]
    size: Option<(u32, u32)>,
    /// Print JSON for scripts instead of text.
    #[arg(long)]
    json: bool,
    /// Also draw the trace: the pixel grid magnified, the covered
    /// samples, the edges (PNG).
    #[arg(long, value_name = "OUT.png")]
    image: Option<PathBuf>,
    /// Also write a self-contained HTML page that steps through the
    /// trace row by row (←/→, or #step=N in its address).
    #[arg(long, value_name = "OUT.html")]
    html: Option<PathBuf>,
}

/// Traces the triangle the arguments name and prints it.
pub(crate) fn run(args: &ScanArgs) -> Result<()> {
    let (vertices, size) = match (&args.input, &args.triangle) {
        (Some(input), _) => {
            let mut scene = load_input(input, LoadOptions::default())?;
            let framed = zline::view::is_framed(&scene);
            if let Some((w, h)) = args.size {
                (scene.settings.width, scene.settings.height) = (w, h);
                if framed {
                    scene.camera = zline::io::model_camera(&scene.objects, w as f32 / h.max(1) as f32);
                }
            }
            let v = zline::scan::window_triangle(&scene, args.object, args.index)
                .map_err(|why| anyhow!("{}: {why}", input.display()))?;
            (v, (scene.settings.width, scene.settings.height))
        }
        (None, Some(triangle)) => (parse_triangle(triangle)?, args.size.unwrap_or((64, 64))),
        (None, None) => bail!("give an input or --triangle"),
    };
    write(vertices, size, args.json, args.image.as_deref(), args.html.as_deref())
}

/// `--triangle`'s three vertices.
fn parse_triangle(triangle: &str) -> Result<[[f32; 3]; 3]> {
    let numbers: Vec<f32> = triangle
        .split(|c: char| c == ',' || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .map(|t| t.parse::<f32>().map_err(|_| anyhow!("--triangle: '{t}' is not a number")))
        .collect::<Result<_>>()?;
    let [x0, y0, z0, x1, y1, z1, x2, y2, z2] = numbers[..] else {
        bail!("--triangle takes three vertices x,y,z (9 numbers), got {} numbers", numbers.len());
    };
    Ok([[x0, y0, z0], [x1, y1, z1], [x2, y2, z2]])
}

/// Prints (and draws, and pages) the trace of a window-space triangle.
fn write(
    vertices: [[f32; 3]; 3],
    (width, height): (u32, u32),
    json: bool,
    image: Option<&Path>,
    html: Option<&Path>,
) -> Result<()> {
    let trace = zline::scan::trace(vertices, width, height).map_err(|why| anyhow!("the triangle: {why}"))?;
    if let Some(path) = image {
        let picture = zline::scan_page::picture(&trace, usize::MAX)
            .ok_or_else(|| anyhow!("{}: the triangle is too large to draw magnified", path.display()))?;
        zline::save_image(&picture, path)
            .with_context(|| format!("{}: cannot write the image", path.display()))?;
        eprintln!("wrote {}", path.display());
    }
    if let Some(path) = html {
        let page = zline::scan_page::page(&trace);
        zline::write_atomically(path, |out| out.write_all(page.as_bytes()))
            .with_context(|| format!("{}: cannot write the page", path.display()))?;
        eprintln!("wrote {}", path.display());
    }
    if json {
        println!("{}", serde_json::to_string_pretty(&trace)?);
    } else {
        print!("{}", trace.text());
    }
    Ok(())
}
