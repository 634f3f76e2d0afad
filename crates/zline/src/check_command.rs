//! `zline check`: render and compare against a reference PNG
//! (`zline::check`). Exact by default; on a failure the rendered image and
//! a heat map of the differences are written for a look; a JSON result
//! when asked, and the exit code in every case: 0 when every check
//! passes, 1 when one fails (images differ, a reference is missing, a
//! render fails), 2 for a usage error.
//!
//! A check renders exactly what `zline render INPUT -o OUT.png` would with
//! the render flags given after `--`, into a temporary file, and reads it
//! back: the image compared is the one `render` writes.

use std::ffi::OsString;
use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context, Result};
use clap::Args;
use serde::Serialize;
use zline::check::{compare, heat_map, Comparison, Tolerance};
use zline::pipeline::Image;

/// `zline check`'s arguments.
#[derive(Args)]
pub(crate) struct CheckArgs {
    /// A model or scene file to render (as `zline render` reads it).
    #[arg(required_unless_present = "folder", conflicts_with = "folder")]
    input: Option<PathBuf>,
    /// The reference PNG (default: the input's path with `.png`).
    #[arg(long, value_name = "REF.png", conflicts_with = "folder")]
    reference: Option<PathBuf>,
    /// Check every `*.toml` scene file of FOLDER against the PNG of the
    /// same name beside it.
    #[arg(long, value_name = "FOLDER")]
    folder: Option<PathBuf>,
    /// A pixel fails when a channel differs by more than this (0..=255;
    /// default 0, exact).
    #[arg(long, value_name = "LEVELS", default_value_t = 0)]
    max_difference: u8,
    /// The share of pixels, in percent, that may fail (default 0).
    #[arg(long, value_name = "PERCENT", default_value_t = 0.0, value_parser = parse_percent)]
    max_percent: f64,
    /// Also require the mean SSIM of the luma to be at least this (0..=1).
    #[arg(long, value_name = "MIN", value_parser = parse_unit)]
    min_ssim: Option<f64>,
    /// Accept the new image: write it over the reference (or as the
    /// reference where there is none) and pass.
    #[arg(long)]
    update: bool,
    /// Where a failed check writes `NAME.actual.png` and `NAME.diff.png`
    /// (default: beside the reference).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Write the results as JSON to FILE (`-`: standard output).
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// Print a failure as a GitHub Actions annotation (`::error file=…`);
    /// on by default where GITHUB_ACTIONS=true.
    #[arg(long)]
    github: bool,
    /// Flags for the render, as `zline render` takes them (after `--`).
    #[arg(last = true, value_name = "RENDER FLAGS")]
    render: Vec<OsString>,
}

fn parse_percent(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (0.0..=100.0).contains(&v) => Ok(v),
        _ => Err(format!("expected a percentage in [0, 100], got '{s}'")),
    }
}

fn parse_unit(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (0.0..=1.0).contains(&v) => Ok(v),
        _ => Err(format!("expected a number in [0, 1], got '{s}'")),
    }
}

/// One check's outcome, as the JSON result lists it.
#[derive(Serialize)]
struct Outcome {
    input: PathBuf,
    reference: PathBuf,
    passed: bool,
    /// What went wrong, when something did before a comparison.
    error: Option<String>,
    /// The comparison, when both images were there.
    comparison: Option<Comparison>,
    /// The rendered image, written on a failure.
    actual: Option<PathBuf>,
    /// The heat map, written on a failure with images of one size.
    diff: Option<PathBuf>,
    /// True when `--update` wrote the reference.
    updated: bool,
}

/// Runs the checks; `render` runs `zline render` on an argument list.
pub(crate) fn run(args: &CheckArgs, render: &dyn Fn(Vec<OsString>) -> Result<()>) -> Result<()> {
    let tolerance = Tolerance {
        max_difference: args.max_difference,
        max_share: args.max_percent / 100.0,
        min_ssim: args.min_ssim,
    };
    let pairs: Vec<(PathBuf, PathBuf)> = match (&args.folder, &args.input) {
        (Some(folder), _) => scenes_in(folder)?,
        (None, Some(input)) => {
            let reference = args.reference.clone().unwrap_or_else(|| input.with_extension("png"));
            vec![(input.clone(), reference)]
        }
        (None, None) => bail!("give an input or --folder"),
    };
    let github = args.github || std::env::var("GITHUB_ACTIONS").is_ok_and(|v| v == "true");
    let scratch = tempfile::tempdir().context("cannot make a temporary folder")?;
    let mut outcomes = Vec::new();
    for (k, (input, reference)) in pairs.iter().enumerate() {
        let actual = scratch.path().join(format!("{k}.png"));
        let outcome = check_one(args, tolerance, input, reference, &actual, render);
        let line = describe(&outcome);
        eprintln!("{line}");
        if github && !outcome.passed {
            // Commas and colons in the message would end its fields.
            println!(
                "::error file={},title=zline check::{}",
                input.display(),
                line.replace(['\n', '\r'], " ")
            );
        }
        outcomes.push(outcome);
    }
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&outcomes)? + "\n";
        if path.as_os_str() == "-" {
            print!("{text}");
        } else {
            std::fs::write(path, text)
                .with_context(|| format!("{}: cannot write the JSON result", path.display()))?;
        }
    }
    let failed = outcomes.iter().filter(|o| !o.passed).count();
    if failed > 0 {
        bail!("{failed} of {} checks failed", outcomes.len());
    }
    eprintln!("check: {} passed", outcomes.len());
    Ok(())
}

/// The `*.toml` files of `folder`, sorted, each with its `.png`.
fn scenes_in(folder: &Path) -> Result<Vec<(PathBuf, PathBuf)>> {
    let entries =
        std::fs::read_dir(folder).with_context(|| format!("{}: cannot read the folder", folder.display()))?;
    let mut scenes: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    scenes.sort();
    if scenes.is_empty() {
        bail!("{}: no *.toml scene file to check", folder.display());
    }
    Ok(scenes.into_iter().map(|s| (s.clone(), s.with_extension("png"))).collect())
}

/// Renders `input` into `actual` and compares it with `reference`.
fn check_one(
    args: &CheckArgs,
    tolerance: Tolerance,
    input: &Path,
    reference: &Path,
    actual: &Path,
    render: &dyn Fn(Vec<OsString>) -> Result<()>,
) -> Outcome {
    let mut outcome = Outcome {
        input: input.to_path_buf(),
        reference: reference.to_path_buf(),
        passed: false,
        error: None,
        comparison: None,
        actual: None,
        diff: None,
        updated: false,
    };
    let mut argv: Vec<OsString> =
        vec!["zline".into(), "render".into(), input.into(), "-o".into(), actual.into(), "--quiet".into()];
    argv.extend(args.render.iter().cloned());
    if let Err(e) = render(argv) {
        outcome.error = Some(format!("the render failed: {}", zline::error_line(&e)));
        return outcome;
    }
    if args.update {
        match std::fs::copy(actual, reference) {
            Ok(_) => (outcome.passed, outcome.updated) = (true, true),
            Err(e) => {
                outcome.error = Some(format!("{}: cannot write the reference: {e}", reference.display()))
            }
        }
        return outcome;
    }
    let result = read(actual).and_then(|a| match read(reference) {
        Ok(r) => Ok((a, r)),
        Err(e) if !reference.exists() => {
            Err(anyhow!("{}: no reference ({e}); --update writes it", reference.display()))
        }
        Err(e) => Err(e),
    });
    let (a, r) = match result {
        Ok(pair) => pair,
        Err(e) => {
            outcome.error = Some(zline::error_line(&e));
            keep(args, &mut outcome, actual, None);
            return outcome;
        }
    };
    match compare(&a, &r, tolerance) {
        Some(c) => {
            outcome.passed = c.passed;
            let failed = !c.passed;
            outcome.comparison = Some(c);
            if failed {
                keep(args, &mut outcome, actual, Some(heat_map(&a, &r)));
            }
        }
        None => {
            outcome.error = Some(format!(
                "the image is {}x{}, the reference {}x{}",
                a.width, a.height, r.width, r.height
            ));
            keep(args, &mut outcome, actual, None);
        }
    }
    outcome
}

/// Writes the failed check's rendered image and heat map where `--out`
/// says (or beside the reference), noting their paths.
fn keep(args: &CheckArgs, outcome: &mut Outcome, actual: &Path, diff: Option<Image>) {
    let folder = args
        .out
        .clone()
        .unwrap_or_else(|| outcome.reference.parent().map(Path::to_path_buf).unwrap_or_default());
    let stem =
        outcome.reference.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or("check".into());
    if std::fs::create_dir_all(&folder).is_err() {
        return;
    }
    let kept = folder.join(format!("{stem}.actual.png"));
    if std::fs::copy(actual, &kept).is_ok() {
        outcome.actual = Some(kept);
    }
    if let Some(map) = diff {
        let path = folder.join(format!("{stem}.diff.png"));
        if zline::save_image(&map, &path).is_ok() {
            outcome.diff = Some(path);
        }
    }
}

/// A PNG as an RGBA image.
fn read(path: &Path) -> Result<Image> {
    let rgba =
        image::open(path).with_context(|| format!("{}: cannot read the image", path.display()))?.to_rgba8();
    let (width, height) = rgba.dimensions();
    let pixels = rgba.pixels().map(|p| u32::from_le_bytes(p.0)).collect();
    Ok(Image { width, height, pixels, transparent: true })
}

/// One line on a check's outcome.
fn describe(o: &Outcome) -> String {
    let name = o.input.display();
    match (&o.error, &o.comparison) {
        (Some(e), _) => format!("FAIL {name}: {e}"),
        (None, _) if o.updated => format!("updated {}", o.reference.display()),
        (None, Some(c)) => {
            let ssim = c.ssim.map(|s| format!(", SSIM {s:.5}")).unwrap_or_default();
            let verdict = if c.passed { "ok" } else { "FAIL" };
            let kept = o.diff.as_ref().map(|d| format!(" (heat map {})", d.display())).unwrap_or_default();
            format!(
                "{verdict} {name}: {} of {} pixels differ, {} past {} levels ({:.3} %), largest {}, RMS {:.3}{ssim}{kept}",
                c.differing_pixels,
                u64::from(c.size.0) * u64::from(c.size.1),
                c.failing_pixels,
                c.tolerance.max_difference,
                c.failing_share * 100.0,
                c.max_difference,
                c.rms
            )
        }
        (None, None) => format!("FAIL {name}"),
    }
}
