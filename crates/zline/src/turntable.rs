//! `zline turntable`: a model seen from all around, the camera orbiting a
//! full turn about its up vector, written as an animated GIF, an animated
//! PNG (APNG) or numbered PNGs in a folder.
//!
//! Frame k of N is exactly `zline render --azimuth A+360·k/N` with the same
//! flags (A: `--azimuth`, default 0): a bare model is framed again from each
//! side with the render command's tight fit, so every frame is framed the
//! way `render` frames it and any frame can be rendered alone. The fit
//! follows the model's silhouette, so a long model comes a little closer
//! when seen end-on; `--distance` fixes the eye's distance instead.

use std::ops::Range;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{anyhow, bail, Context, Result};
use clap::Args;
use zline::pipeline::{render, Image};

use crate::job::Job;
use crate::progress::{Progress, ProgressArgs};

/// The most frames in a turn.
const MAX_FRAMES: u32 = 3600;

/// The options of `zline turntable` besides the common ones.
#[derive(Args)]
pub(crate) struct TurntableArgs {
    /// An `.obj`, `.gltf`, `.glb`, `.stl`, `.ply` or `.3mf` model or a `.toml`
    /// scene file.
    input: PathBuf,
    /// Frames in the full turn: frame k is seen from 360·k/N degrees of
    /// azimuth past the starting view.
    #[arg(long, value_name = "N", default_value_t = 36,
          value_parser = clap::value_parser!(u32).range(1..=MAX_FRAMES as i64))]
    frames: u32,
    /// Render only frames A to B−1 of the N-frame turn (e.g. 0..18, the
    /// first half), numbered as in the whole turn: a folder of frames can be
    /// split among machines.
    #[arg(long, value_name = "A..B", value_parser = parse_range)]
    frame_range: Option<Range<u32>>,
    /// Frames per second of a GIF or animated PNG (a GIF's delay is in
    /// hundredths of a second: 12 plays at 8/100 s a frame).
    #[arg(long, value_name = "FPS", default_value_t = 12, value_parser = clap::value_parser!(u16).range(1..=100))]
    fps: u16,
    /// As for `render`: read files the input names outside its folder.
    #[arg(long)]
    pub(crate) allow_paths_outside: bool,
    #[command(flatten)]
    progress: ProgressArgs,
}

/// `-o` for `zline turntable`.
pub(crate) fn output_arg(arg: clap::Arg) -> clap::Arg {
    arg.value_name("OUT").help(
        "OUT.gif (animated GIF, looping forever), OUT.png (animated PNG) or a folder (a path \
         ending in / or an existing folder; created if missing) for frame-0000.png, frame-0001.png, …; \
         written atomically",
    )
}

fn parse_range(s: &str) -> Result<Range<u32>, String> {
    let bad = || format!("expected A..B, frame indices with A < B, e.g. 0..18, got '{s}'");
    let (a, b) = s.split_once("..").ok_or_else(bad)?;
    match (a.trim().parse::<u32>(), b.trim().parse::<u32>()) {
        (Ok(a), Ok(b)) if a < b => Ok(a..b),
        _ => Err(bad()),
    }
}

/// Where the frames go.
enum Target {
    Gif,
    Apng,
    Folder,
}

impl Target {
    fn of(out: &Path) -> Result<Target> {
        let text = out.as_os_str().to_string_lossy();
        if text.ends_with('/') || text.ends_with(std::path::MAIN_SEPARATOR) || out.is_dir() {
            return Ok(Target::Folder);
        }
        match out.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
            Some("gif") => Ok(Target::Gif),
            Some("png") => Ok(Target::Apng),
            _ => bail!(
                "{}: the output must be a .gif or .png file, or a folder (a path ending in /)",
                out.display()
            ),
        }
    }
}

/// `zline turntable`.
pub(crate) fn run(args: &TurntableArgs, job: &Job) -> Result<()> {
    let out = &job.output;
    let target = Target::of(out)?;
    let n = args.frames;
    let frames = args.frame_range.clone().unwrap_or(0..n);
    if frames.end > n {
        bail!("--frame-range {}..{}: the turn has {n} frames, 0..{n}", frames.start, frames.end);
    }
    match target {
        Target::Folder => std::fs::create_dir_all(out)
            .with_context(|| format!("{}: cannot create the folder", out.display()))?,
        Target::Gif | Target::Apng => check_folder(out)?,
    }
    let started = Instant::now();
    let (scene, framed) = (job.load)(&args.input)?;
    let progress =
        Progress::new(u64::from(frames.end - frames.start), &args.progress, (job.quiet, job.timings));
    let (width, height) = (scene.settings.width, scene.settings.height);
    let each_frame = |add: &mut dyn FnMut(u32, &Image) -> Result<()>| -> Result<()> {
        for k in frames.clone() {
            progress.show(&format!("frame {k}"));
            let mut frame = scene.clone();
            let turn = (360.0 * f64::from(k) / f64::from(n)) as f32;
            (job.aim)(&mut frame, framed, turn);
            let start = Instant::now();
            let options = &job.options;
            let (image, _) = job.pool.install(|| render(&frame, options));
            add(k, &image)?;
            progress.done(&format!("frame {k} (azimuth +{turn}°)"), start.elapsed());
        }
        Ok(())
    };
    let delay = image::Delay::from_numer_denom_ms(1000, u32::from(args.fps));
    let result = match target {
        Target::Folder => each_frame(&mut |k, image| {
            let png = out.join(format!("frame-{k:04}.png"));
            zline::save_png(image, &png).with_context(|| format!("{}: cannot write PNG", png.display()))
        }),
        Target::Gif => {
            let mut bytes = Vec::new();
            {
                use image::codecs::gif::{GifEncoder, Repeat};
                // Speed 10 of 1..=30: NeuQuant's palette per frame, about
                // ten times faster than its best with little loss.
                let mut gif = GifEncoder::new_with_speed(&mut bytes, 10);
                gif.set_repeat(Repeat::Infinite)?;
                each_frame(&mut |_, image| {
                    let rgba = image::RgbaImage::from_fn(image.width, image.height, |x, y| {
                        let [r, g, b] = image.pixel(x, y);
                        image::Rgba([r, g, b, 255])
                    });
                    Ok(gif.encode_frame(image::Frame::from_parts(rgba, 0, 0, delay))?)
                })?;
            }
            write_atomically(out, &bytes)
        }
        Target::Apng => {
            let mut bytes = Vec::new();
            {
                let mut png = png::Encoder::new(&mut bytes, width, height);
                png.set_color(png::ColorType::Rgb);
                png.set_depth(png::BitDepth::Eight);
                png.set_compression(png::Compression::Fast);
                // Plays forever (0), each frame 1/fps s.
                png.set_animated(frames.end - frames.start, 0)?;
                png.set_frame_delay(1, args.fps)?;
                let mut writer = png.write_header()?;
                each_frame(&mut |_, image| Ok(writer.write_image_data(&image.to_rgb())?))?;
                writer.finish()?;
            }
            write_atomically(out, &bytes)
        }
    };
    progress.finish();
    result?;
    progress.say(&format!(
        "wrote {} ({} of {n} frames, {width}x{height}, {:.2} s)",
        out.display(),
        frames.end - frames.start,
        started.elapsed().as_secs_f64()
    ));
    Ok(())
}

/// The folder `out` is written in exists and takes a new file.
fn check_folder(out: &Path) -> Result<()> {
    zline::check_writable(out).with_context(|| format!("{}: cannot write there", out.display()))
}

/// `bytes` written atomically over `path` ([`zline::write_atomically`]).
fn write_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    zline::write_atomically(path, |out| out.write_all(bytes))
        .map_err(|e| anyhow!("{}: cannot write: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_ranges_are_a_to_b_with_a_below_b() {
        assert_eq!(parse_range("0..36"), Ok(0..36));
        assert_eq!(parse_range(" 5 .. 7 "), Ok(5..7));
        for bad in ["3..3", "4..2", "..5", "1..", "1-5", "a..b", "-1..2", ""] {
            assert!(parse_range(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn the_output_name_chooses_the_format() {
        assert!(matches!(Target::of(Path::new("a.gif")), Ok(Target::Gif)));
        assert!(matches!(Target::of(Path::new("a.GIF")), Ok(Target::Gif)));
        assert!(matches!(Target::of(Path::new("a.png")), Ok(Target::Apng)));
        assert!(matches!(Target::of(Path::new("frames/")), Ok(Target::Folder)));
        assert!(matches!(Target::of(Path::new(".")), Ok(Target::Folder)));
        assert!(Target::of(Path::new("a.jpg")).is_err());
        assert!(Target::of(Path::new("no-extension")).is_err());
    }
}
