//! `cargo xtask contact-sheet`: every model of the shared asset folder
//! (`obj/*/*.obj`, and one glTF variant per model under `gltf/*/`) loaded
//! with the zline facade, rendered at the cell size with Phong shading and
//! laid out in a grid PNG with each model's name under its cell. A model
//! that fails to load gets a cell with the start of its error instead of a
//! picture; the sheet is written anyway.

use std::any::Any;
use std::fs::File;
use std::io::BufWriter;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ExtendedColorType, ImageEncoder, Rgb, RgbImage};
use zline::io::{load_gltf, load_obj, scene_for_gltf, scene_for_model};
use zline::pipeline::{render, Image, RenderOptions, RenderStats};
use zline::scene::{RenderSettings, Scene, ShadingMode, MAX_IMAGE_SIDE};

/// Cells per row of the sheet.
const COLUMNS: usize = 4;
/// Pixels between cells and around the sheet.
const GUTTER: u32 = 4;
/// Pixels between the label text and the edges of its strip.
const LABEL_PAD: u32 = 4;

const GUTTER_COLOR: Rgb<u8> = Rgb([48, 48, 48]);
const LABEL_BACKGROUND: Rgb<u8> = Rgb([24, 24, 24]);
const LABEL_TEXT: Rgb<u8> = Rgb([232, 232, 232]);
const FAILED_BACKGROUND: Rgb<u8> = Rgb([96, 24, 24]);
const FAILED_TEXT: Rgb<u8> = Rgb([255, 236, 236]);

/// A model file found under the asset folder.
struct Model {
    /// The file name, written under the cell.
    name: String,
    path: PathBuf,
    format: Format,
}

#[derive(Clone, Copy)]
enum Format {
    Obj,
    Gltf,
}

/// What goes into a cell.
enum Cell {
    Picture(Image),
    Failed(String),
}

/// Parses `WxH` for `--cell`.
pub(crate) fn parse_cell(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(|| format!("expected WxH, e.g. 320x240, got '{s}'"))?;
    let parse = |v: &str| v.trim().parse::<u32>().ok().filter(|n| (1..=MAX_IMAGE_SIDE).contains(n));
    match (parse(w), parse(h)) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => Err(format!("width and height must be whole numbers in 1..={MAX_IMAGE_SIDE}, got '{s}'")),
    }
}

pub(crate) fn run(assets: &Path, out: &Path, (width, height): (u32, u32)) -> Result<()> {
    if !assets.is_dir() {
        bail!(
            "asset folder {} not found: pass --assets DIR (the folder holding obj/ and gltf/)",
            assets.display()
        );
    }
    let models = find_models(assets)?;
    if models.is_empty() {
        bail!("no models in {} (expected obj/*/*.obj or gltf/*/glTF/*.gltf)", assets.display());
    }
    let settings = RenderSettings { width, height, shading: ShadingMode::Phong, ..RenderSettings::default() };
    let options = RenderOptions::default();
    let mut cells = Vec::with_capacity(models.len());
    let mut failures = 0;
    for model in &models {
        let cell = match catch_unwind(AssertUnwindSafe(|| load_and_render(model, settings, &options))) {
            Ok(Ok((image, stats, load, draw))) => {
                println!(
                    "{:<28} load {:>8.1} ms  render {:>7.1} ms  {:>7} triangles",
                    model.name,
                    ms(load),
                    ms(draw),
                    stats.triangles
                );
                Cell::Picture(image)
            }
            Ok(Err(e)) => {
                let message = format!("{e:#}");
                eprintln!("error: {}: {message}", model.name);
                Cell::Failed(strip_path(&message, &model.path))
            }
            Err(payload) => {
                let message = format!("panic: {}", panic_message(payload.as_ref()));
                eprintln!("error: {}: {message}", model.name);
                Cell::Failed(message)
            }
        };
        if matches!(cell, Cell::Failed(_)) {
            failures += 1;
        }
        cells.push((model.name.as_str(), cell));
    }
    let sheet = sheet(&cells, width, height);
    save(&sheet, out)?;
    eprintln!(
        "wrote {} ({}x{}, {} models, {failures} failed)",
        out.display(),
        sheet.width(),
        sheet.height(),
        models.len()
    );
    Ok(())
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// Loads and renders one model; returns the image, the render statistics
/// and the load and render times.
fn load_and_render(
    model: &Model,
    settings: RenderSettings,
    options: &RenderOptions,
) -> Result<(Image, RenderStats, Duration, Duration)> {
    let start = Instant::now();
    let scene: Scene = match model.format {
        Format::Obj => scene_for_model(load_obj(&model.path)?, settings),
        Format::Gltf => scene_for_gltf(load_gltf(&model.path)?, settings),
    };
    let load = start.elapsed();
    let start = Instant::now();
    let (image, stats) = render(&scene, options);
    Ok((image, stats, load, start.elapsed()))
}

fn panic_message(payload: &(dyn Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "(no message)".to_string())
}

/// The error message without the leading file path (the cell is named
/// already, and the path would fill it).
fn strip_path(message: &str, path: &Path) -> String {
    let shown = path.display().to_string();
    message
        .strip_prefix(&shown)
        .map(|rest| rest.trim_start_matches([':', ' ']))
        .unwrap_or(message)
        .to_string()
}

/// The entries of `dir` sorted by name, or none if it cannot be read.
fn sorted_entries(dir: &Path) -> Vec<PathBuf> {
    let mut entries: Vec<PathBuf> = match std::fs::read_dir(dir) {
        Ok(read) => read.filter_map(|e| e.ok().map(|e| e.path())).collect(),
        Err(_) => Vec::new(),
    };
    entries.sort();
    entries
}

fn has_extension(path: &Path, ext: &str) -> bool {
    path.is_file() && path.extension().is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

/// Every `obj/*/*.obj`, then per `gltf/*/` model folder the `.gltf` files
/// of its `glTF` variant, or the `.glb` files of `glTF-Binary` when it has
/// no `glTF` folder (other variants of the same model are skipped).
fn find_models(assets: &Path) -> Result<Vec<Model>> {
    let mut models = Vec::new();
    let mut add = |path: PathBuf, format| {
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        models.push(Model { name, path, format });
    };
    for folder in sorted_entries(&assets.join("obj")).into_iter().filter(|p| p.is_dir()) {
        for path in sorted_entries(&folder).into_iter().filter(|p| has_extension(p, "obj")) {
            add(path, Format::Obj);
        }
    }
    for folder in sorted_entries(&assets.join("gltf")).into_iter().filter(|p| p.is_dir()) {
        let (variant, ext) = if folder.join("glTF").is_dir() {
            (folder.join("glTF"), "gltf")
        } else {
            (folder.join("glTF-Binary"), "glb")
        };
        let found: Vec<PathBuf> =
            sorted_entries(&variant).into_iter().filter(|p| has_extension(p, ext)).collect();
        if found.is_empty() {
            eprintln!("note: {}: no glTF/*.gltf or glTF-Binary/*.glb; skipped", folder.display());
        }
        for path in found {
            add(path, Format::Gltf);
        }
    }
    Ok(models)
}

/// The label scale for a cell `width` pixels wide.
fn text_scale(width: u32) -> u32 {
    if width >= 200 {
        2
    } else {
        1
    }
}

/// Lays the cells out `COLUMNS` to a row, each with its name in a strip
/// below it.
fn sheet(cells: &[(&str, Cell)], width: u32, height: u32) -> RgbImage {
    let columns = COLUMNS.min(cells.len()).max(1) as u32;
    let rows = cells.len().div_ceil(columns as usize) as u32;
    let scale = text_scale(width);
    let label = GLYPH_HEIGHT * scale + 2 * LABEL_PAD;
    let sheet_width = columns * (width + GUTTER) + GUTTER;
    let sheet_height = rows * (height + label + GUTTER) + GUTTER;
    let mut sheet = RgbImage::from_pixel(sheet_width, sheet_height, GUTTER_COLOR);
    for (i, (name, cell)) in cells.iter().enumerate() {
        let (column, row) = (i as u32 % columns, i as u32 / columns);
        let x0 = GUTTER + column * (width + GUTTER);
        let y0 = GUTTER + row * (height + label + GUTTER);
        match cell {
            Cell::Picture(image) => {
                for y in 0..height.min(image.height) {
                    for x in 0..width.min(image.width) {
                        sheet.put_pixel(x0 + x, y0 + y, Rgb(image.pixel(x, y)));
                    }
                }
            }
            Cell::Failed(message) => {
                fill(&mut sheet, x0, y0, width, height, FAILED_BACKGROUND);
                let mut lines = vec!["load failed:".to_string()];
                lines.extend(wrap(message, width.saturating_sub(2 * LABEL_PAD), scale));
                let line_height = (GLYPH_HEIGHT + 2) * scale;
                let fit = ((height.saturating_sub(2 * LABEL_PAD)) / line_height).max(1) as usize;
                if lines.len() > fit {
                    lines.truncate(fit);
                    let last = lines.pop().unwrap_or_default();
                    lines.push(ellipsize(&format!("{last} ..."), width.saturating_sub(2 * LABEL_PAD), scale));
                }
                for (k, line) in lines.iter().enumerate() {
                    let y = y0 + LABEL_PAD + k as u32 * line_height;
                    draw_text(&mut sheet, x0 + LABEL_PAD, y, line, scale, FAILED_TEXT);
                }
            }
        }
        fill(&mut sheet, x0, y0 + height, width, label, LABEL_BACKGROUND);
        let text = ellipsize(name, width.saturating_sub(2 * LABEL_PAD), scale);
        draw_text(&mut sheet, x0 + LABEL_PAD, y0 + height + LABEL_PAD, &text, scale, LABEL_TEXT);
    }
    sheet
}

fn fill(image: &mut RgbImage, x0: u32, y0: u32, width: u32, height: u32, color: Rgb<u8>) {
    for y in y0..y0 + height {
        for x in x0..x0 + width {
            image.put_pixel(x, y, color);
        }
    }
}

fn save(sheet: &RgbImage, out: &Path) -> Result<()> {
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("{}: cannot create", dir.display()))?;
    }
    let file = File::create(out).with_context(|| format!("{}: cannot create", out.display()))?;
    let encoder =
        PngEncoder::new_with_quality(BufWriter::new(file), CompressionType::Best, FilterType::Adaptive);
    encoder
        .write_image(sheet.as_raw(), sheet.width(), sheet.height(), ExtendedColorType::Rgb8)
        .with_context(|| format!("{}: cannot write PNG", out.display()))
}

// ---- text: a built-in 5×7 bitmap font ----

/// Glyph cell: 5 columns plus 1 of spacing; 7 rows plus a descender row.
const GLYPH_ADVANCE: u32 = 6;
const GLYPH_HEIGHT: u32 = 8;

/// How many characters fit in `width` pixels at `scale`.
fn chars_that_fit(width: u32, scale: u32) -> usize {
    (width / (GLYPH_ADVANCE * scale)) as usize
}

/// `text` cut to `width` pixels, ending in ".." when cut (and there is
/// room for more than the dots).
fn ellipsize(text: &str, width: u32, scale: u32) -> String {
    let fit = chars_that_fit(width, scale);
    if text.chars().count() <= fit {
        text.to_string()
    } else if fit < 3 {
        text.chars().take(fit).collect()
    } else {
        let mut cut: String = text.chars().take(fit.saturating_sub(2)).collect();
        cut.push_str("..");
        cut
    }
}

/// `text` broken into lines of whole words that fit `width` pixels (a word
/// longer than a line is cut into pieces).
fn wrap(text: &str, width: u32, scale: u32) -> Vec<String> {
    let fit = chars_that_fit(width, scale).max(1);
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        let chars: Vec<char> = word.chars().collect();
        for piece in chars.chunks(fit) {
            let piece: String = piece.iter().collect();
            let len = line.chars().count();
            if len > 0 && len + 1 + piece.chars().count() > fit {
                lines.push(std::mem::take(&mut line));
            }
            if !line.is_empty() {
                line.push(' ');
            }
            line.push_str(&piece);
        }
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

/// Draws `text` with its top-left corner at (x, y), each font pixel a
/// `scale`×`scale` square; characters without a glyph are drawn as '?'
/// (space is blank). Pixels outside the image are skipped.
fn draw_text(image: &mut RgbImage, x: u32, y: u32, text: &str, scale: u32, color: Rgb<u8>) {
    for (i, c) in text.chars().enumerate() {
        let Some(rows) = glyph(c) else { continue };
        let gx = x + i as u32 * GLYPH_ADVANCE * scale;
        for (r, bits) in rows.iter().enumerate() {
            for col in 0..5u32 {
                if bits & (0x10 >> col) == 0 {
                    continue;
                }
                for dy in 0..scale {
                    for dx in 0..scale {
                        let (px, py) = (gx + col * scale + dx, y + r as u32 * scale + dy);
                        if px < image.width() && py < image.height() {
                            image.put_pixel(px, py, color);
                        }
                    }
                }
            }
        }
    }
}

/// The rows of `c`'s glyph, none for a space.
fn glyph(c: char) -> Option<&'static [u8; 8]> {
    if c == ' ' {
        return None;
    }
    let index =
        GLYPH_CHARS.chars().position(|g| g == c).or_else(|| GLYPH_CHARS.chars().position(|g| g == '?'));
    index.map(|i| &GLYPHS[i])
}

/// The characters of [`GLYPHS`], in order.
///
/// Each glyph is 8 rows from the top, bit 4 the leftmost of its 5 columns;
/// rows 0–6 hold capitals and digits, row 7 the descenders of g j p q y.
const GLYPH_CHARS: &str = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._-:/(),'`?=+";
/// The glyphs of [`GLYPH_CHARS`], laid out as described there.
const GLYPHS: [[u8; 8]; 75] = [
    [0x0e, 0x11, 0x11, 0x1f, 0x11, 0x11, 0x11, 0x00],
    [0x1e, 0x11, 0x11, 0x1e, 0x11, 0x11, 0x1e, 0x00],
    [0x0e, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0e, 0x00],
    [0x1e, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1e, 0x00],
    [0x1f, 0x10, 0x10, 0x1e, 0x10, 0x10, 0x1f, 0x00],
    [0x1f, 0x10, 0x10, 0x1e, 0x10, 0x10, 0x10, 0x00],
    [0x0e, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0f, 0x00],
    [0x11, 0x11, 0x11, 0x1f, 0x11, 0x11, 0x11, 0x00],
    [0x0e, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0e, 0x00],
    [0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0c, 0x00],
    [0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11, 0x00],
    [0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1f, 0x00],
    [0x11, 0x1b, 0x15, 0x15, 0x11, 0x11, 0x11, 0x00],
    [0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11, 0x00],
    [0x0e, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e, 0x00],
    [0x1e, 0x11, 0x11, 0x1e, 0x10, 0x10, 0x10, 0x00],
    [0x0e, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0d, 0x00],
    [0x1e, 0x11, 0x11, 0x1e, 0x14, 0x12, 0x11, 0x00],
    [0x0f, 0x10, 0x10, 0x0e, 0x01, 0x01, 0x1e, 0x00],
    [0x1f, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04, 0x00],
    [0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e, 0x00],
    [0x11, 0x11, 0x11, 0x11, 0x11, 0x0a, 0x04, 0x00],
    [0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0a, 0x00],
    [0x11, 0x11, 0x0a, 0x04, 0x0a, 0x11, 0x11, 0x00],
    [0x11, 0x11, 0x0a, 0x04, 0x04, 0x04, 0x04, 0x00],
    [0x1f, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1f, 0x00],
    [0x00, 0x00, 0x0e, 0x01, 0x0f, 0x11, 0x0f, 0x00],
    [0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x1e, 0x00],
    [0x00, 0x00, 0x0e, 0x10, 0x10, 0x11, 0x0e, 0x00],
    [0x01, 0x01, 0x0d, 0x13, 0x11, 0x11, 0x0f, 0x00],
    [0x00, 0x00, 0x0e, 0x11, 0x1f, 0x10, 0x0e, 0x00],
    [0x06, 0x09, 0x08, 0x1c, 0x08, 0x08, 0x08, 0x00],
    [0x00, 0x00, 0x0f, 0x11, 0x11, 0x0f, 0x01, 0x0e],
    [0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x11, 0x00],
    [0x04, 0x00, 0x0c, 0x04, 0x04, 0x04, 0x0e, 0x00],
    [0x02, 0x00, 0x06, 0x02, 0x02, 0x02, 0x12, 0x0c],
    [0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12, 0x00],
    [0x0c, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0e, 0x00],
    [0x00, 0x00, 0x1a, 0x15, 0x15, 0x11, 0x11, 0x00],
    [0x00, 0x00, 0x16, 0x19, 0x11, 0x11, 0x11, 0x00],
    [0x00, 0x00, 0x0e, 0x11, 0x11, 0x11, 0x0e, 0x00],
    [0x00, 0x00, 0x1e, 0x11, 0x11, 0x1e, 0x10, 0x10],
    [0x00, 0x00, 0x0f, 0x11, 0x11, 0x0f, 0x01, 0x01],
    [0x00, 0x00, 0x16, 0x19, 0x10, 0x10, 0x10, 0x00],
    [0x00, 0x00, 0x0f, 0x10, 0x0e, 0x01, 0x1e, 0x00],
    [0x08, 0x08, 0x1c, 0x08, 0x08, 0x09, 0x06, 0x00],
    [0x00, 0x00, 0x11, 0x11, 0x11, 0x13, 0x0d, 0x00],
    [0x00, 0x00, 0x11, 0x11, 0x11, 0x0a, 0x04, 0x00],
    [0x00, 0x00, 0x11, 0x11, 0x15, 0x15, 0x0a, 0x00],
    [0x00, 0x00, 0x11, 0x0a, 0x04, 0x0a, 0x11, 0x00],
    [0x00, 0x00, 0x11, 0x11, 0x11, 0x0f, 0x01, 0x0e],
    [0x00, 0x00, 0x1f, 0x02, 0x04, 0x08, 0x1f, 0x00],
    [0x0e, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0e, 0x00],
    [0x04, 0x0c, 0x04, 0x04, 0x04, 0x04, 0x0e, 0x00],
    [0x0e, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1f, 0x00],
    [0x1f, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0e, 0x00],
    [0x02, 0x06, 0x0a, 0x12, 0x1f, 0x02, 0x02, 0x00],
    [0x1f, 0x10, 0x1e, 0x01, 0x01, 0x11, 0x0e, 0x00],
    [0x06, 0x08, 0x10, 0x1e, 0x11, 0x11, 0x0e, 0x00],
    [0x1f, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08, 0x00],
    [0x0e, 0x11, 0x11, 0x0e, 0x11, 0x11, 0x0e, 0x00],
    [0x0e, 0x11, 0x11, 0x0f, 0x01, 0x02, 0x0c, 0x00],
    [0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x0c, 0x00],
    [0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1f, 0x00],
    [0x00, 0x00, 0x00, 0x1f, 0x00, 0x00, 0x00, 0x00],
    [0x00, 0x0c, 0x0c, 0x00, 0x0c, 0x0c, 0x00, 0x00],
    [0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00, 0x00],
    [0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02, 0x00],
    [0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08, 0x00],
    [0x00, 0x00, 0x00, 0x00, 0x0c, 0x04, 0x08, 0x00],
    [0x04, 0x04, 0x08, 0x00, 0x00, 0x00, 0x00, 0x00],
    [0x08, 0x04, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00],
    [0x0e, 0x11, 0x01, 0x02, 0x04, 0x00, 0x04, 0x00],
    [0x00, 0x00, 0x1f, 0x00, 0x1f, 0x00, 0x00, 0x00],
    [0x00, 0x04, 0x04, 0x1f, 0x04, 0x04, 0x00, 0x00],
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_glyph_has_its_character() {
        assert_eq!(GLYPH_CHARS.chars().count(), GLYPHS.len());
        assert!(GLYPHS.iter().all(|g| g.iter().all(|row| row >> 5 == 0)));
    }

    #[test]
    fn wrap_keeps_words_within_the_width() {
        let lines = wrap("cannot read glTF: missing buffer Duck0.bin", 6 * 12, 1);
        assert!(lines.iter().all(|l| l.chars().count() <= 12), "{lines:?}");
        assert_eq!(lines.join(" "), "cannot read glTF: missing buffer Duck0.bin");
    }

    #[test]
    fn cell_size_parses() {
        assert_eq!(parse_cell("320x240"), Ok((320, 240)));
        assert!(parse_cell("0x240").is_err());
        assert!(parse_cell("320").is_err());
    }
}
