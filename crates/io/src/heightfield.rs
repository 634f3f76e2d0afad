//! Elevation files → [`HeightField`]s: greyscale PNG height maps and ESRI
//! ASCII grids (`.asc`), chosen by the file's extension.
//!
//! Contract of [`load_heightfield`]:
//! - **PNG** (`.png`): an 8- or 16-bit greyscale image (a grey+alpha image
//!   has its alpha ignored; a colour image is refused). Row 0 of the image
//!   is the north edge. Each height is the sample divided by its largest
//!   value (255 or 65535), so heights lie in [0, 1]; the cell size is 1.
//!   The caller scales both (`zline terrain --height-scale`,
//!   `--cell-size`).
//! - **ESRI ASCII grid** (`.asc`): a header of `key value` lines —
//!   `ncols`, `nrows`, `xllcorner` or `xllcenter`, `yllcorner` or
//!   `yllcenter`, `cellsize` (all required, keys in any case and order) and
//!   `NODATA_value` (optional) — then `ncols × nrows` numbers, rows from
//!   north to south (line breaks between them are free). Heights and cell
//!   size are in the file's units. **NODATA cells** (values equal to
//!   `NODATA_value`) take the lowest valid height of the grid, so holes
//!   read as flat ground at the grid's floor rather than spikes; a grid of
//!   NODATA only is an error.
//!
//! Every error names the file and, in a grid's text, the line (and column
//! for a bad token): a missing or repeated header key, a header value that
//! is not a number, a token that is not a number or not finite (`nan`,
//! `inf`), too few or too many values. Files are read through the size
//! limits of the other loaders (a grid up to the model limit, a PNG up to
//! the image limit), and a grid of more than
//! [`MAX_HEIGHTFIELD_SAMPLES`] samples is refused from its header, before
//! its values are read.

use std::io::Cursor;
use std::path::Path;

use image::{ColorType, ImageFormat, ImageReader, Limits};
use zline_scene::{HeightField, MAX_HEIGHTFIELD_SAMPLES};
use zline_shading::Texture;

use crate::error::{line_column, SceneError};
use crate::files::{read_limited, FileKind};
use crate::texture_file::TextureCache;

/// Reads a height field from a `.png` or `.asc` file (see the module
/// documentation for the formats and the NODATA rule).
pub fn load_heightfield(path: &Path) -> Result<HeightField, SceneError> {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("png") => {
            let bytes = read_limited(path, FileKind::Image).map_err(|e| e.into_error(path))?;
            decode_png(&bytes).map_err(|message| file_error(path, message))
        }
        Some("asc") => {
            let bytes = read_limited(path, FileKind::Model).map_err(|e| e.into_error(path))?;
            let text = String::from_utf8(bytes).map_err(|e| {
                file_error(
                    path,
                    format!("not a text file (invalid UTF-8 at byte {})", e.utf8_error().valid_up_to()),
                )
            })?;
            parse_ascii_grid(path, &text)
        }
        _ => Err(file_error(
            path,
            "unsupported elevation file; expected a greyscale .png or an ESRI ASCII grid (.asc)".into(),
        )),
    }
}

/// Reads an image file (PNG or JPEG) as a texture, e.g. one to drape over
/// a terrain. Errors name the file: unreadable, not an image zline reads,
/// corrupt, or larger than the texture limits.
pub fn load_texture(path: &Path) -> Result<Texture, SceneError> {
    let mut warnings = Vec::new();
    match TextureCache::default().file(path, &mut warnings)? {
        Some(texture) => Ok(Texture::clone(&texture)),
        None => {
            let why = warnings.pop().unwrap_or_else(|| format!("{}: cannot read texture", path.display()));
            let prefix = format!("{}: ", path.display());
            Err(file_error(
                path,
                why.strip_prefix(&prefix)
                    .unwrap_or(&why)
                    .replace("; meshes using it are drawn untextured", ""),
            ))
        }
    }
}

fn file_error(path: &Path, message: String) -> SceneError {
    SceneError::File { path: path.to_path_buf(), message }
}

/// A greyscale PNG's samples over their largest value.
fn decode_png(bytes: &[u8]) -> Result<HeightField, String> {
    if image::guess_format(bytes).ok() != Some(ImageFormat::Png) {
        return Err("not a PNG image".into());
    }
    let reader = ImageReader::with_format(Cursor::new(bytes), ImageFormat::Png);
    let (width, height) = reader.into_dimensions().map_err(|e| format!("cannot decode PNG: {e}"))?;
    let samples = u64::from(width) * u64::from(height);
    if samples > MAX_HEIGHTFIELD_SAMPLES as u64 || width < 2 || height < 2 {
        return Err(format!(
            "height map of {width}x{height} pixels: a height map needs at least 2x2 and at most \
             {MAX_HEIGHTFIELD_SAMPLES} pixels"
        ));
    }
    let mut reader = ImageReader::with_format(Cursor::new(bytes), ImageFormat::Png);
    let mut limits = Limits::default();
    // 16-bit RGBA, the widest PNG.
    limits.max_alloc = Some(samples * 8);
    reader.limits(limits);
    let image = reader.decode().map_err(|e| format!("cannot decode PNG: {e}"))?;
    let heights: Vec<f32> = match image.color() {
        ColorType::L8 | ColorType::La8 => {
            image.into_luma8().into_raw().into_iter().map(|v| f32::from(v) / 255.0).collect()
        }
        ColorType::L16 | ColorType::La16 => {
            image.into_luma16().into_raw().into_iter().map(|v| f32::from(v) / 65535.0).collect()
        }
        other => {
            return Err(format!(
                "a height map must be a greyscale PNG (8 or 16 bits), this one is {other:?}; convert it to greyscale"
            ))
        }
    };
    HeightField::new(width as usize, height as usize, heights, 1.0).map_err(|e| e.to_string())
}

/// The header keys of an ESRI ASCII grid.
const HEADER_KEYS: [&str; 5] = ["ncols", "nrows", "xll", "yll", "cellsize"];

/// Parses an ESRI ASCII grid (see the module documentation).
fn parse_ascii_grid(path: &Path, text: &str) -> Result<HeightField, SceneError> {
    let line_error =
        |line: usize, message: String| SceneError::Line { path: path.to_path_buf(), line, message };
    // ncols, nrows, xll, yll, cellsize; and NODATA_value.
    let mut header: [Option<f64>; 5] = [None; 5];
    let mut nodata: Option<f64> = None;
    let mut lines = text.lines().enumerate().peekable();
    let mut last_header_line = 0;
    while let Some(&(index, line)) = lines.peek() {
        let mut tokens = line.split_whitespace();
        let Some(key) = tokens.next() else {
            lines.next();
            continue;
        };
        if key.parse::<f64>().is_ok() || key.starts_with(['-', '+', '.']) {
            break; // the first value
        }
        let number = index + 1;
        let lower = key.to_ascii_lowercase();
        let slot = match lower.as_str() {
            "ncols" => Some(0),
            "nrows" => Some(1),
            "xllcorner" | "xllcenter" => Some(2),
            "yllcorner" | "yllcenter" => Some(3),
            "cellsize" => Some(4),
            "nodata_value" => None,
            _ => {
                return Err(line_error(
                    number,
                    format!("unknown header key '{key}' (expected ncols, nrows, xllcorner or xllcenter, yllcorner or yllcenter, cellsize, NODATA_value)"),
                ))
            }
        };
        let value = match (tokens.next(), tokens.next()) {
            (Some(v), None) => v
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| line_error(number, format!("{key}: '{v}' is not a finite number")))?,
            (None, _) => return Err(line_error(number, format!("{key}: no value"))),
            (Some(_), Some(extra)) => {
                return Err(line_error(number, format!("{key}: unexpected '{extra}' after the value")))
            }
        };
        let target = match slot {
            Some(i) => &mut header[i],
            None => &mut nodata,
        };
        if target.replace(value).is_some() {
            return Err(line_error(number, format!("{key} given twice")));
        }
        last_header_line = number;
        lines.next();
    }
    if let Some(missing) = header.iter().position(Option::is_none) {
        let name = match HEADER_KEYS[missing] {
            "xll" => "xllcorner or xllcenter",
            "yll" => "yllcorner or yllcenter",
            k => k,
        };
        return Err(line_error(last_header_line.max(1), format!("the header has no {name}")));
    }
    let count = |i: usize, key: &str| {
        let v = header[i].unwrap_or_default();
        if v.fract() == 0.0 && v >= 2.0 && v <= MAX_HEIGHTFIELD_SAMPLES as f64 {
            Ok(v as usize)
        } else {
            Err(line_error(last_header_line, format!("{key} must be a whole number of at least 2, got {v}")))
        }
    };
    let (columns, rows) = (count(0, "ncols")?, count(1, "nrows")?);
    if columns.saturating_mul(rows) > MAX_HEIGHTFIELD_SAMPLES {
        return Err(file_error(
            path,
            format!(
                "a grid of {columns} x {rows} samples is more than the limit of {MAX_HEIGHTFIELD_SAMPLES}"
            ),
        ));
    }
    let cell = header[4].unwrap_or_default() as f32;
    if !(cell.is_finite() && cell > 0.0) {
        return Err(line_error(
            last_header_line,
            format!("cellsize must be greater than 0, got {}", header[4].unwrap_or_default()),
        ));
    }
    let expected = columns * rows;
    let mut heights: Vec<f32> = Vec::with_capacity(expected);
    let mut holes = Vec::new();
    let mut last_value_line = last_header_line;
    for (index, line) in lines {
        for token in line.split_whitespace() {
            let column_of = || {
                let offset = token.as_ptr() as usize - text.as_ptr() as usize;
                line_column(text, offset).1
            };
            if heights.len() == expected {
                return Err(SceneError::At {
                    path: path.to_path_buf(),
                    line: index + 1,
                    column: column_of(),
                    message: format!(
                        "more values than ncols x nrows = {columns} x {rows} = {expected}: '{token}'"
                    ),
                });
            }
            let value: f64 = token.parse().map_err(|_| SceneError::At {
                path: path.to_path_buf(),
                line: index + 1,
                column: column_of(),
                message: format!("'{token}' is not a number"),
            })?;
            let height = value as f32;
            if nodata == Some(value) {
                holes.push(heights.len());
            } else if !height.is_finite() {
                return Err(SceneError::At {
                    path: path.to_path_buf(),
                    line: index + 1,
                    column: column_of(),
                    message: format!("'{token}' is not a finite height"),
                });
            }
            heights.push(height);
            last_value_line = index + 1;
        }
    }
    if heights.len() < expected {
        return Err(line_error(
            last_value_line,
            format!(
                "the grid ends after {} values, ncols x nrows = {columns} x {rows} needs {expected}",
                heights.len()
            ),
        ));
    }
    if !holes.is_empty() {
        let valid = heights.iter().enumerate().filter(|(i, _)| holes.binary_search(i).is_err());
        let Some(floor) = valid.map(|(_, h)| *h).reduce(f32::min) else {
            return Err(file_error(path, "every value of the grid is NODATA".into()));
        };
        for i in holes {
            heights[i] = floor;
        }
    }
    HeightField::new(columns, rows, heights, cell).map_err(|e| file_error(path, e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(text: &str) -> Result<HeightField, String> {
        parse_ascii_grid(Path::new("t.asc"), text).map_err(|e| e.to_string())
    }

    #[test]
    fn a_small_grid_reads_north_to_south() {
        let text = "ncols 3\nNROWS 2\nxllcorner 100\nyllcenter -5.5\ncellsize 30\nNODATA_value -9999\n\
                    1 2 3\n4.5 -9999 -6e-1\n";
        let field = grid(text).unwrap();
        assert_eq!((field.columns(), field.rows(), field.cell_size()), (3, 2, 30.0));
        // The NODATA cell takes the lowest valid height, −0.6.
        assert_eq!(field.heights(), &[1.0, 2.0, 3.0, 4.5, -0.6, -0.6]);
        assert_eq!(field.at(2, 0), 3.0);
        // Values may wrap lines freely.
        let field = grid("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1\n2 3\n4").unwrap();
        assert_eq!(field.heights(), &[1.0, 2.0, 3.0, 4.0]);
    }

    #[test]
    fn malformed_grids_name_the_file_and_line() {
        let head = "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
        let cases = [
            (
                "ncols 2\nnrows 2\nxllcorner 0\ncellsize 1\n1 2\n3 4\n",
                "t.asc: line 4: the header has no yllcorner or yllcenter",
            ),
            (&format!("{head}1 2\n3 x\n") as &str, "t.asc: line 7, column 3: 'x' is not a number"),
            (&format!("{head}1 2\n3 nan\n"), "t.asc: line 7, column 3: 'nan' is not a finite height"),
            (&format!("{head}1 2\n3\n"), "t.asc: line 7: the grid ends after 3 values"),
            (&format!("{head}1 2\n3 4 5\n"), "t.asc: line 7, column 5: more values than ncols x nrows"),
            ("ncols 2\nnrows 2\nncols 3\n", "t.asc: line 3: ncols given twice"),
            (
                "ncols 2.5\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n",
                "t.asc: line 5: ncols must be a whole number",
            ),
            (
                "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 0\n1 2 3 4",
                "t.asc: line 5: cellsize must be greater than 0",
            ),
            ("ncols two\n", "t.asc: line 1: ncols: 'two' is not a finite number"),
            ("colour 2\n", "t.asc: line 1: unknown header key 'colour'"),
            (&format!("{head}NODATA_value 0\n0 0\n0 0\n"), "t.asc: every value of the grid is NODATA"),
        ];
        for (text, expect) in cases {
            let e = grid(text).unwrap_err();
            assert!(e.starts_with(expect), "{e}\n  expected: {expect}");
        }
    }

    #[test]
    fn sixteen_bit_png_round_trips() {
        let (w, h) = (5u32, 3u32);
        let values: Vec<u16> = (0..w * h).map(|i| (i * 4099 % 65536) as u16).collect();
        let image = image::ImageBuffer::<image::Luma<u16>, _>::from_raw(w, h, values.clone()).unwrap();
        let mut bytes = Vec::new();
        image.write_to(&mut Cursor::new(&mut bytes), ImageFormat::Png).unwrap();
        let field = decode_png(&bytes).unwrap();
        assert_eq!((field.columns(), field.rows()), (5, 3));
        for (got, v) in field.heights().iter().zip(&values) {
            assert_eq!((got * 65535.0).round() as u16, *v);
        }
        let grey = image::GrayImage::from_raw(2, 2, vec![0, 51, 255, 102]).unwrap();
        let mut bytes = Vec::new();
        grey.write_to(&mut Cursor::new(&mut bytes), ImageFormat::Png).unwrap();
        assert_eq!(decode_png(&bytes).unwrap().heights(), &[0.0, 0.2, 1.0, 0.4]);
        let rgb = image::RgbImage::new(2, 2);
        let mut bytes = Vec::new();
        rgb.write_to(&mut Cursor::new(&mut bytes), ImageFormat::Png).unwrap();
        assert!(decode_png(&bytes).unwrap_err().contains("must be a greyscale PNG"));
        assert_eq!(decode_png(b"P5 junk").unwrap_err(), "not a PNG image");
    }
}
