//! `cargo xtask view-screenshot`: a real screenshot of `zline view` for the
//! README. The viewer runs on a private Xvfb and the picture is the X
//! server's own framebuffer (`zline::viewer::capture`), not zline's render
//! written to disk; it must match zline's render of the same frame outside
//! the frame-time text, or the task fails. Without Xvfb it says so and
//! succeeds.

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{bail, Context, Result};
use zline::viewer::capture;

/// The least share of the screen that must be zline's frame exactly (the
/// frame-time text darkens a band of 28 rows at the top).
const MIN_MATCHING: f64 = 0.8;

/// Frames the viewer presents before it exits (about 10 ms apart while
/// idle): long enough for several reads of the screen.
const FRAMES: u64 = 60;

/// Builds the `zline` binary, runs `zline view MODEL --size WxH ARGS` under
/// Xvfb and writes the captured screen to `out`.
pub(crate) fn run(out: &Path, model: &Path, size: (u32, u32), extra: &[String]) -> Result<()> {
    let Some(xvfb) = capture::find_xvfb() else {
        println!("skipped: Xvfb not found (apt-get install xvfb)");
        return Ok(());
    };
    let root = root();
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let status = Command::new(cargo)
        .args(["build", "--release", "-p", "zline", "--bin", "zline"])
        .current_dir(&root)
        .status()
        .context("cannot run cargo")?;
    if !status.success() {
        bail!("cargo build -p zline failed ({status})");
    }
    // The xtask binary sits beside it in target/release.
    let exe = std::env::current_exe()?;
    let zline = exe.with_file_name(format!("zline{}", std::env::consts::EXE_SUFFIX));
    let mut args: Vec<OsString> =
        vec![root.join(model).into(), "--size".into(), format!("{}x{}", size.0, size.1).into()];
    args.extend(extra.iter().map(OsString::from));
    let shot = capture::under_xvfb(&xvfb, &zline, &args, size, FRAMES)?;
    if shot.matching < MIN_MATCHING {
        bail!(
            "only {:.1} % of the X screen is zline's frame (at least {:.0} % expected): the window did not show it",
            100.0 * shot.matching,
            100.0 * MIN_MATCHING
        );
    }
    let out = root.join(out);
    zline::save_image(&shot.screen, &out).with_context(|| format!("cannot write {}", out.display()))?;
    println!(
        "wrote {} ({}x{} from Xvfb's framebuffer; {:.1} % of it is zline's own frame, the rest the frame-time text)",
        out.display(),
        shot.screen.width,
        shot.screen.height,
        100.0 * shot.matching
    );
    Ok(())
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("xtask lives in the workspace").to_path_buf()
}
