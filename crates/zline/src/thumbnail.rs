//! `zline thumbnail` and `zline thumbnailer install|uninstall`: desktop
//! thumbnails for model files, the way freedesktop file managers ask for
//! them.
//!
//! A file manager (Nautilus, Nemo, Caja, Thunar's tumbler) runs the
//! `Exec=` line of a `.thumbnailer` file for every file of a listed MIME
//! type it shows, GNOME's inside a bubblewrap sandbox: no network, no
//! display, a read-only `/usr`, a private `/tmp`, a time limit. zline needs
//! neither a display nor a GPU, so the thumbnail is the `render` of the
//! model: square, framed, on a transparent background, 2 × 2 supersampled.
//! A watchdog ends the process after `--timeout`; an input above
//! `--max-input-bytes` is refused before it is read.

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::time::Duration;

use anyhow::{bail, Context, Result};
use clap::{Args, Subcommand};
use glam::Vec3;

/// `zline thumbnail`'s arguments.
#[derive(Args)]
pub(crate) struct ThumbnailArgs {
    /// The model (or scene file) to show.
    input: PathBuf,
    /// The PNG to write.
    output: PathBuf,
    /// The thumbnail's side in pixels (16..=2048).
    #[arg(short, long, default_value_t = 256, value_parser = clap::value_parser!(u32).range(16..=2048))]
    size: u32,
    /// An opaque background instead of a transparent one, each channel in
    /// [0, 1].
    #[arg(long, value_name = "R,G,B", value_parser = crate::cli::parse::parse_color)]
    background: Option<Vec3>,
    /// Give up after this many seconds (0.1..=600).
    #[arg(long, value_name = "SECONDS", default_value_t = 10.0, value_parser = parse_timeout)]
    timeout: f64,
    /// Refuse inputs larger than this many bytes.
    #[arg(long, value_name = "BYTES", default_value_t = 256 << 20)]
    max_input_bytes: u64,
}

fn parse_timeout(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (0.1..=600.0).contains(&v) => Ok(v),
        _ => Err(format!("expected seconds in [0.1, 600], got '{s}'")),
    }
}

/// Writes the thumbnail; `render` runs `zline render` on an argument list.
pub(crate) fn run(args: &ThumbnailArgs, render: &dyn Fn(Vec<OsString>) -> Result<()>) -> Result<()> {
    let size = std::fs::metadata(&args.input)
        .with_context(|| format!("{}: cannot read the file", args.input.display()))?
        .len();
    if size > args.max_input_bytes {
        bail!(
            "{}: {size} bytes, more than the thumbnail's limit of {} (--max-input-bytes)",
            args.input.display(),
            args.max_input_bytes
        );
    }
    let (input, timeout) = (args.input.clone(), args.timeout);
    // The watchdog: a render that runs past the limit ends the process
    // (the file manager kills it anyway; this says why, and exits 1).
    std::thread::spawn(move || {
        std::thread::sleep(Duration::from_secs_f64(timeout));
        eprintln!("error: {}: no thumbnail within {timeout} s (--timeout)", input.display());
        std::process::exit(1);
    });
    let side = args.size.to_string();
    let mut argv: Vec<OsString> = vec!["zline".into(), "render".into(), args.input.clone().into()];
    argv.extend(["-o".into(), args.output.clone().into()]);
    argv.extend(["--size".into(), format!("{side}x{side}").into(), "--ssaa".into(), "2".into()]);
    match args.background {
        Some(c) => argv.extend(["--background".into(), format!("{},{},{}", c.x, c.y, c.z).into()]),
        None => argv.push("--transparent".into()),
    }
    render(argv)
}

/// `zline thumbnailer`'s actions.
#[derive(Subcommand)]
pub(crate) enum ThumbnailerAction {
    /// Write the `.thumbnailer` file and the MIME types shared-mime-info
    /// lacks, then update the MIME database; prints what it wrote.
    Install(Place),
    /// Remove what `install` wrote.
    Uninstall(Place),
}

/// Where the files go.
#[derive(Args)]
pub(crate) struct Place {
    /// For this user only: under $XDG_DATA_HOME (~/.local/share); without
    /// it, for everyone, under /usr/local/share.
    #[arg(long, conflicts_with = "prefix")]
    user: bool,
    /// Under this data folder instead (its `thumbnailers/` and
    /// `mime/packages/`).
    #[arg(long, value_name = "DIR")]
    prefix: Option<PathBuf>,
}

/// The MIME types the thumbnailer serves, as file managers name them
/// (shared-mime-info's names and aliases, and zline's own package).
pub(crate) const MIME_TYPES: &[&str] = &[
    "model/gltf+json",
    "model/gltf-binary",
    "model/obj",
    "model/stl",
    "model/x.stl-ascii",
    "model/x.stl-binary",
    "application/sla",
    "application/x-ply",
    "model/3mf",
];

/// zline's MIME package: the model types with their globs and magic, for
/// systems whose shared-mime-info lacks them (or knows `.obj` only as a
/// TGIF drawing). The weights put them above older definitions.
pub(crate) const MIME_PACKAGE: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<!-- Model file types for zline's thumbnailer (zline thumbnailer install). -->
<mime-info xmlns="http://www.freedesktop.org/standards/shared-mime-info">
  <mime-type type="model/gltf+json">
    <comment>glTF 3D model</comment>
    <glob pattern="*.gltf" weight="60"/>
  </mime-type>
  <mime-type type="model/gltf-binary">
    <comment>glTF binary 3D model</comment>
    <glob pattern="*.glb" weight="60"/>
    <magic priority="60"><match type="string" offset="0" value="glTF"/></magic>
  </mime-type>
  <mime-type type="model/obj">
    <comment>Wavefront OBJ 3D model</comment>
    <glob pattern="*.obj" weight="60"/>
  </mime-type>
  <mime-type type="model/stl">
    <comment>STL 3D model</comment>
    <alias type="application/sla"/>
    <glob pattern="*.stl" weight="60"/>
  </mime-type>
  <mime-type type="application/x-ply">
    <comment>PLY 3D model</comment>
    <glob pattern="*.ply" weight="60"/>
    <magic priority="60"><match type="string" offset="0" value="ply"/></magic>
  </mime-type>
  <mime-type type="model/3mf">
    <comment>3MF 3D model</comment>
    <glob pattern="*.3mf" weight="60"/>
  </mime-type>
</mime-info>
"#;

/// The `.thumbnailer` file for the zline at `exe`.
pub(crate) fn thumbnailer_entry(exe: &Path) -> String {
    format!(
        "[Thumbnailer Entry]\nTryExec={exe}\nExec={exe} thumbnail -s %s %i %o\nMimeType={types};\n",
        exe = exe.display(),
        types = MIME_TYPES.join(";")
    )
}

/// The data folder a [`Place`] names.
fn data_folder(place: &Place) -> Result<PathBuf> {
    if let Some(prefix) = &place.prefix {
        return Ok(prefix.clone());
    }
    if !place.user {
        return Ok(PathBuf::from("/usr/local/share"));
    }
    match std::env::var_os("XDG_DATA_HOME").filter(|v| !v.is_empty()) {
        Some(home) => Ok(PathBuf::from(home)),
        None => match std::env::var_os("HOME").filter(|v| !v.is_empty()) {
            Some(home) => Ok(PathBuf::from(home).join(".local/share")),
            None => bail!("neither XDG_DATA_HOME nor HOME is set: give --prefix"),
        },
    }
}

/// Installs or uninstalls the thumbnailer.
pub(crate) fn thumbnailer(action: &ThumbnailerAction) -> Result<()> {
    let (place, install) = match action {
        ThumbnailerAction::Install(place) => (place, true),
        ThumbnailerAction::Uninstall(place) => (place, false),
    };
    let data = data_folder(place)?;
    let entry = data.join("thumbnailers/zline.thumbnailer");
    let package = data.join("mime/packages/zline-models.xml");
    if install {
        let exe = std::env::current_exe().context("cannot find this program's path")?;
        for (path, text) in [(&entry, thumbnailer_entry(&exe)), (&package, MIME_PACKAGE.to_string())] {
            let folder = path.parent().expect("a file in a folder");
            std::fs::create_dir_all(folder)
                .with_context(|| format!("{}: cannot create the folder", folder.display()))?;
            zline::write_atomically(path, |out| out.write_all(text.as_bytes()))
                .with_context(|| format!("{}: cannot write", path.display()))?;
            println!("wrote {}", path.display());
        }
        print!("{}", thumbnailer_entry(&exe));
        if !exe.starts_with("/usr") {
            eprintln!(
                "note: GNOME runs thumbnailers in a sandbox that sees only /usr: for Nautilus, install zline under /usr/local (cargo install --root /usr/local) and run this again from there"
            );
        }
    } else {
        for path in [&entry, &package] {
            match std::fs::remove_file(path) {
                Ok(()) => println!("removed {}", path.display()),
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                    println!("{} was not there", path.display())
                }
                Err(e) => return Err(e).with_context(|| format!("{}: cannot remove", path.display())),
            }
        }
    }
    update_mime_database(&data.join("mime"));
    Ok(())
}

/// Runs `update-mime-database` on `folder` when it is installed, and says
/// what happened.
fn update_mime_database(folder: &Path) {
    match std::process::Command::new("update-mime-database").arg(folder).status() {
        Ok(s) if s.success() => println!("ran update-mime-database {}", folder.display()),
        Ok(s) => eprintln!("warning: update-mime-database {} exited with {s}", folder.display()),
        Err(_) => eprintln!(
            "note: update-mime-database (shared-mime-info) is not installed: the MIME package takes effect once it runs"
        ),
    }
}
