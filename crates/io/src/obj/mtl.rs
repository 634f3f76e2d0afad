//! MTL files: read (within the size limit), checked and handed to tobj.
//!
//! Contract: [`load_mtl`] returns tobj's result for the file — a failure
//! there (a missing file, a line tobj cannot read) is a warning and the
//! meshes get the default material — or a [`SceneError`] for what must
//! stop the load: a file refused by its size or type, and a non-finite
//! value (`nan`, `inf`) of `Ka`, `Kd`, `Ks`, `Ke`, `Ns`, `d` or `Tr`,
//! named by file, line and key. Finite values outside their range (SPEC
//! §5: colours in [0, 1]; `Ns` in [0, f32::MAX]; `d` and `Tr` in [0, 1])
//! are clamped, in the text handed to tobj, with a warning each.

use std::io::Cursor;
use std::path::Path;

use crate::error::SceneError;
use crate::files::{read_text, FileKind, ReadError};

use super::check::quote;

/// The material loader handed to tobj: reads and checks an MTL file (see
/// the module doc). The outer error stops the load; the inner one is
/// tobj's, reported as a warning (tobj then uses no material).
pub(super) fn load_mtl(path: &Path, warnings: &mut Vec<String>) -> Result<tobj::MTLLoadResult, SceneError> {
    let fail = |warnings: &mut Vec<String>, why: String| {
        warnings.push(format!("{why}; using the default material"));
        Err(tobj::LoadError::OpenFileFailed)
    };
    let text = match read_text(path, FileKind::Text) {
        Ok(text) => text,
        Err(ReadError::Io(e)) => {
            return Ok(fail(warnings, format!("{}: cannot read material library: {e}", path.display())))
        }
        Err(refused) => return Err(refused.into_error(path)),
    };
    let text = match check_mtl_text(&text) {
        Ok(text) => text,
        Err((line, why)) => return Ok(fail(warnings, format!("{}: line {line}: {why}", path.display()))),
    };
    let (text, clamped) = check_mtl_values(&text).map_err(|(line, message)| SceneError::Line {
        path: path.to_path_buf(),
        line,
        message,
    })?;
    warnings.extend(clamped.into_iter().map(|(line, why)| format!("{}: line {line}: {why}", path.display())));
    Ok(tobj::load_mtl_buf(&mut Cursor::new(text.as_bytes()))
        .or_else(|e| fail(warnings, format!("{}: cannot load material library: {e}", path.display()))))
}

/// Checks the MTL statements that tobj would reject without saying where,
/// or panic on, and expands the one-number colour form `Kd 0.5` (which
/// means `Kd 0.5 0.5 0.5`) that tobj does not know. Returns the text to
/// hand to tobj, or the 1-based line and what is wrong with it.
pub(super) fn check_mtl_text(text: &str) -> Result<String, (usize, String)> {
    let mut out = String::with_capacity(text.len() + 64);
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let key = words.next().unwrap_or("");
        let args: Vec<&str> = words.collect();
        let bad = |what: &str| Err((i + 1, format!("{what} in {}", quote(line))));
        match key {
            "Ka" | "Kd" | "Ks" | "Ke" => match args.len() {
                1 => {
                    let v = args[0];
                    if v.parse::<f32>().is_err() {
                        return bad("cannot parse colour");
                    }
                    out.push_str(&format!("{key} {v} {v} {v}\n"));
                    continue;
                }
                0 | 2 => return bad("a colour needs 3 numbers"),
                _ if args[..3].iter().any(|a| a.parse::<f32>().is_err()) => {
                    return bad("cannot parse colour (only 'r g b' is supported)")
                }
                _ => {}
            },
            "Ns" | "Ni" | "d" | "Pr" | "Pm" if args.first().and_then(|a| a.parse::<f32>().ok()).is_none() => {
                return bad("cannot parse number")
            }
            "illum" if args.first().and_then(|a| a.parse::<u8>().ok()).is_none() => {
                return bad("cannot parse illumination model")
            }
            "newmtl" if args.is_empty() => return bad("material without a name"),
            k if (k.starts_with("map_") || k == "bump") && args.is_empty() => {
                return bad("texture map without a file name")
            }
            _ => {}
        }
        out.push_str(line);
        out.push('\n');
    }
    Ok(out)
}

/// A 1-based line number and what is said about it.
pub(super) type LineNote = (usize, String);

/// The values zline uses, checked on text that passed [`check_mtl_text`]:
/// the text with the values outside their range clamped, and a note for
/// each, or the first non-finite value's line and message. Numbers are
/// read as f64, so `1e300` is a (large) finite value clamped, not an
/// infinity.
pub(super) fn check_mtl_values(text: &str) -> Result<(String, Vec<LineNote>), LineNote> {
    let mut out = String::with_capacity(text.len());
    let mut clamped = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let key = words.next().unwrap_or("");
        let (count, lo, hi) = match key {
            "Ka" | "Kd" | "Ks" | "Ke" => (3, 0.0, 1.0),
            "Ns" => (1, 0.0, f64::from(f32::MAX)),
            "d" | "Tr" | "Pr" | "Pm" => (1, 0.0, 1.0),
            // The index of refraction, in the scene files' range (SPEC §12).
            "Ni" => (1, 0.01, 100.0),
            _ => {
                out.push_str(line);
                out.push('\n');
                continue;
            }
        };
        let mut rewritten = vec![key.to_owned()];
        for (k, word) in words.enumerate() {
            // `Tr` is not checked by check_mtl_text: tobj ignores what
            // does not parse, and so does zline.
            let Some(value) = word.parse::<f64>().ok().filter(|_| k < count) else {
                rewritten.push(word.to_owned());
                continue;
            };
            if !value.is_finite() {
                return Err((i + 1, format!("{key}: non-finite value '{word}' in {}", quote(line))));
            }
            let to = value.clamp(lo, hi);
            if to != value {
                clamped.push((
                    i + 1,
                    format!("{key} value {word} is outside [{lo}, {}]; clamped to {}", short(hi), short(to)),
                ));
            }
            rewritten.push(if to == value { word.to_owned() } else { to.to_string() });
        }
        out.push_str(&rewritten.join(" "));
        out.push('\n');
    }
    Ok((out, clamped))
}

/// A number for messages: `3.4028234663852886e38` rather than 39 digits.
fn short(x: f64) -> String {
    if x.abs() >= 1e9 {
        format!("{x:e}")
    } else {
        x.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mtl_one_number_colours_are_expanded_and_two_rejected() {
        let text = check_mtl_text("newmtl a\nKd 0.5\nKs 1 1 1\n").unwrap();
        assert_eq!(text, "newmtl a\nKd 0.5 0.5 0.5\nKs 1 1 1\n");
        assert_eq!(check_mtl_text("newmtl a\n\nKd 0.5 0.5\n").unwrap_err().0, 3);
        assert!(check_mtl_text("Ns high").unwrap_err().1.contains("cannot parse number in 'Ns high'"));
        assert!(check_mtl_text("Kd spectral x.rfl").is_err());
    }

    #[test]
    fn non_finite_values_are_errors_with_line_and_key() {
        let (line, message) = check_mtl_values("newmtl a\nKd nan 1e300 -5\n").unwrap_err();
        assert_eq!(line, 2);
        assert!(message.starts_with("Kd: non-finite value 'nan'"), "{message}");
        for text in ["Ns inf", "d -inf", "Ke 0 0 NaN", "Tr infinity"] {
            assert!(check_mtl_values(text).is_err(), "{text}");
        }
    }

    #[test]
    fn out_of_range_values_are_clamped_with_a_note_each() {
        let (text, notes) =
            check_mtl_values("newmtl a\nKd 0.5 1e300 -5\nNs -1\nd 7\nTr 0.5\nKs  1 1 1\nNs 1e300\n").unwrap();
        let expected =
            "newmtl a\nKd 0.5 1 0\nNs 0\nd 1\nTr 0.5\nKs 1 1 1\nNs 340282346638528860000000000000000000000\n";
        assert_eq!(text, expected);
        assert_eq!(text.lines().last().unwrap()[3..].parse::<f32>(), Ok(f32::MAX), "tobj reads a finite Ns");
        let lines: Vec<usize> = notes.iter().map(|n| n.0).collect();
        assert_eq!(lines, [2, 2, 3, 4, 7], "{notes:?}");
        assert_eq!(notes[0].1, "Kd value 1e300 is outside [0, 1]; clamped to 1");
        assert_eq!(notes[1].1, "Kd value -5 is outside [0, 1]; clamped to 0");
        assert_eq!(notes[2].1, "Ns value -1 is outside [0, 3.4028234663852886e38]; clamped to 0");
        assert_eq!(notes[3].1, "d value 7 is outside [0, 1]; clamped to 1");
    }
}
