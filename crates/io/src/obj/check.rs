//! The OBJ check: every line of an OBJ file looked at before it is read,
//! so that what tobj (and [`super::read`], which reads as tobj does) would
//! reject without saying where, or trip over, becomes an error naming the
//! line and its text (see the parent module's doc). The text is checked in
//! pieces of whole lines in parallel, each piece starting from the counts
//! of the definitions before it.

use std::path::Path;

use rayon::prelude::*;

use crate::error::SceneError;

/// Counts of the vertex attributes defined so far while scanning an OBJ
/// (and, for [`super::read`], before each piece of it).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Defined {
    pub(super) positions: usize,
    pub(super) texcoords: usize,
    pub(super) normals: usize,
}

/// OBJ statements that tobj ignores but that are valid OBJ (free-form
/// geometry, display attributes): accepted and skipped.
const IGNORED_STATEMENTS: &[&str] = &[
    "s",
    "vp",
    "cstype",
    "deg",
    "bmat",
    "step",
    "curv",
    "curv2",
    "surf",
    "parm",
    "trim",
    "hole",
    "scrv",
    "sp",
    "end",
    "con",
    "mg",
    "bevel",
    "c_interp",
    "d_interp",
    "lod",
    "maplib",
    "usemap",
    "shadow_obj",
    "trace_obj",
    "ctech",
    "stech",
    "call",
    "csh",
    "p",
];

/// Checks every line (see [`check_obj_line`]) and returns the text's pieces
/// with the definitions before each, for [`super::read::read_models`].
pub(super) fn check_obj_text<'a>(
    path: &Path,
    text: &'a str,
) -> Result<(Vec<&'a str>, Vec<Defined>), SceneError> {
    check_obj_text_in(path, text, CHECK_PIECE)
}

/// [`check_obj_text`] with pieces of `piece` bytes.
pub(super) fn check_obj_text_in<'a>(
    path: &Path,
    text: &'a str,
    piece: usize,
) -> Result<(Vec<&'a str>, Vec<Defined>), SceneError> {
    if text.contains('\0') {
        return Err(SceneError::File {
            path: path.to_path_buf(),
            message: "binary data, not an OBJ text file".into(),
        });
    }
    // The text in pieces of whole lines, checked in parallel: a first pass
    // counts each piece's lines and definitions, so each piece starts from
    // the counts before it, as a scan from the top would; the first error
    // in file order is reported.
    let pieces = line_pieces(text, piece);
    let totals: Vec<(usize, Defined, usize)> =
        pieces.par_iter().map(|piece| count_definitions(piece)).collect();
    let mut starts = Vec::with_capacity(pieces.len());
    let (mut line, mut defined) = (0, Defined::default());
    for (lines, d, _) in &totals {
        starts.push((line, defined));
        line += lines;
        defined = Defined {
            positions: defined.positions + d.positions,
            texcoords: defined.texcoords + d.texcoords,
            normals: defined.normals + d.normals,
        };
    }
    // The limits, before anything is built (splitting vertices by their
    // index triples can only add vertices; the reader's result is checked
    // again).
    SceneError::check_size(path, totals.iter().map(|t| t.2).sum(), defined.positions)?;
    let errors: Vec<Option<(usize, String)>> = pieces
        .par_iter()
        .zip(&starts)
        .map(|(piece, &(first_line, mut defined))| {
            let mut args = Vec::new();
            for (i, line) in piece.lines().enumerate() {
                if let Err(message) = check_obj_line(line, &mut defined, &mut args) {
                    return Some((first_line + i + 1, message));
                }
            }
            None
        })
        .collect();
    if let Some((line, message)) = errors.into_iter().flatten().next() {
        return Err(SceneError::Line { path: path.to_path_buf(), line, message });
    }
    Ok((pieces, starts.into_iter().map(|(_, d)| d).collect()))
}

/// Bytes of OBJ text checked by one task.
pub(super) const CHECK_PIECE: usize = 256 * 1024;

/// `text` cut after the first line break at or beyond every `size` bytes:
/// pieces of whole lines (each but the last ends with `\n`).
pub(super) fn line_pieces(text: &str, size: usize) -> Vec<&str> {
    let mut pieces = Vec::new();
    let mut rest = text;
    while rest.len() > size {
        match rest.as_bytes()[size..].iter().position(|&b| b == b'\n') {
            Some(at) => {
                let (piece, tail) = rest.split_at(size + at + 1);
                pieces.push(piece);
                rest = tail;
            }
            None => break,
        }
    }
    pieces.push(rest);
    pieces
}

/// The lines of `piece`, its `v`, `vt` and `vn` statements and the
/// triangles its faces make (corners − 2 each).
fn count_definitions(piece: &str) -> (usize, Defined, usize) {
    let mut d = Defined::default();
    let (mut lines, mut triangles) = (0, 0);
    for line in piece.lines() {
        lines += 1;
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => d.positions += 1,
            Some("vt") => d.texcoords += 1,
            Some("vn") => d.normals += 1,
            Some("f") => triangles += words.count().saturating_sub(2),
            _ => {}
        }
    }
    (lines, d, triangles)
}

/// Checks one line, counting what it defines. `args` is scratch space for
/// the line's words (kept across lines, so checking allocates nothing).
pub(super) fn check_obj_line<'a>(
    line: &'a str,
    defined: &mut Defined,
    args: &mut Vec<&'a str>,
) -> Result<(), String> {
    let mut words = line.split_whitespace();
    let Some(key) = words.next() else { return Ok(()) };
    args.clear();
    args.extend(words);
    let args = &args[..];
    match key {
        "v" => check_vertex(line, args).map(|()| defined.positions += 1),
        "vt" => check_numbers(line, args, 2, "texture coordinate").map(|()| defined.texcoords += 1),
        "vn" => check_numbers(line, args, 3, "normal").map(|()| defined.normals += 1),
        "f" | "l" => check_face(line, args, defined),
        "usemtl" if args.is_empty() => Err(format!("'usemtl' without a material name in {}", quote(line))),
        "o" | "g" | "mtllib" | "usemtl" => Ok(()),
        k if k.starts_with('#') || IGNORED_STATEMENTS.contains(&k) => Ok(()),
        k => Err(format!("unknown statement '{}' in {}", truncate(k), quote(line))),
    }
}

/// `v x y z [w | r g b]`: three finite coordinates, an optional non-zero w.
fn check_vertex(line: &str, args: &[&str]) -> Result<(), String> {
    if !matches!(args.len(), 3 | 4 | 6) {
        return Err(format!("a vertex needs 3 coordinates (then optionally w, or r g b) in {}", quote(line)));
    }
    let mut xyz = [0.0f32; 3];
    for (c, a) in xyz.iter_mut().zip(args) {
        *c = a.parse().map_err(|_| format!("cannot parse vertex position {}", quote(line)))?;
        if !c.is_finite() {
            return Err(format!("vertex has non-finite coordinate '{}'", truncate(a)));
        }
    }
    if let [_, _, _, w] = args {
        let w: f32 = w.parse().map_err(|_| format!("cannot parse vertex w in {}", quote(line)))?;
        if w == 0.0 || !w.is_finite() || xyz.iter().any(|c| !(c / w).is_finite()) {
            return Err(format!("vertex has unusable w = {w} in {}", quote(line)));
        }
    }
    Ok(())
}

/// At least `n` numbers (tobj reads the first `n` and ignores the rest).
fn check_numbers(line: &str, args: &[&str], n: usize, what: &str) -> Result<(), String> {
    if args.len() < n || args[..n].iter().any(|a| a.parse::<f32>().is_err()) {
        return Err(format!("cannot parse {what} {} ({n} numbers expected)", quote(line)));
    }
    Ok(())
}

/// `f v[/vt][/vn] ...`: every index parses and refers to an element
/// defined earlier (negative indices count back from the last one).
fn check_face(line: &str, args: &[&str], defined: &Defined) -> Result<(), String> {
    if args.is_empty() {
        return Err(format!("a face needs vertices in {}", quote(line)));
    }
    let kinds = [
        ("vertex", defined.positions),
        ("texture coordinate", defined.texcoords),
        ("normal", defined.normals),
    ];
    for corner in args {
        if corner.split('/').count() > 3 || corner.starts_with('/') {
            return Err(format!("cannot parse face vertex '{}' in {}", truncate(corner), quote(line)));
        }
        for (part, &(what, count)) in corner.split('/').zip(&kinds).filter(|(p, _)| !p.is_empty()) {
            let index: i64 = part
                .parse()
                .map_err(|_| format!("cannot parse face index '{}' in {}", truncate(part), quote(line)))?;
            let resolved = if index < 0 { count as i64 + index + 1 } else { index };
            if resolved < 1 || resolved > count as i64 {
                return Err(format!(
                    "face refers to {what} {index}, but the file defines {count} before this line: {}",
                    quote(line)
                ));
            }
        }
    }
    Ok(())
}

/// A line quoted for a message: trimmed, shortened, control characters
/// escaped, so the message stays one line.
pub(super) fn quote(line: &str) -> String {
    format!("'{}'", truncate(line.trim()))
}

pub(super) fn truncate(s: &str) -> String {
    const MAX: usize = 60;
    let mut out: String = s.chars().take(MAX).flat_map(char::escape_debug).collect();
    if s.chars().count() > MAX {
        out.push('…');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[track_caller]
    fn check_line_error(line: &str, expected: &str) {
        let mut defined = Defined { positions: 4, texcoords: 2, normals: 0 };
        let message = check_obj_line(line, &mut defined, &mut Vec::new()).unwrap_err();
        assert!(message.contains(expected), "{message:?} does not contain {expected:?}");
    }

    #[test]
    fn faces_are_counted_as_triangles_before_reading() {
        let (lines, defined, triangles) = count_definitions("v 0 0 0\nf 1 2 3 4\nf 1 2 3\nf 1 2\nvn 0 0 1\n");
        assert_eq!((lines, defined.positions, defined.normals, triangles), (5, 1, 1, 3));
        // One face of MAX_TRIANGLES + 3 corners: refused by the count,
        // before any line is checked or read.
        let corners = zline_scene::MAX_TRIANGLES + 3;
        let text = format!("v 0 0 0\nf{}\n", " 1".repeat(corners));
        match check_obj_text(Path::new("huge.obj"), &text) {
            Err(e) => assert_eq!(
                e.to_string(),
                format!(
                    "huge.obj: {} triangles, more than the limit of {}",
                    corners - 2,
                    zline_scene::MAX_TRIANGLES
                )
            ),
            Ok(_) => panic!("accepted"),
        }
    }

    #[test]
    fn pieces_are_whole_lines() {
        let text = "v 1 2 3\nvt 0 0\n\nf 1 2 3\n# end";
        for size in 0..text.len() + 2 {
            let pieces = line_pieces(text, size);
            assert_eq!(pieces.concat(), text, "size {size}");
            assert!(pieces[..pieces.len() - 1].iter().all(|p| p.ends_with('\n')), "size {size}");
        }
    }

    /// A file of many pieces: faces see the definitions of earlier pieces,
    /// and an error deep in the file names its line, as a scan from the
    /// top would.
    #[test]
    fn pieces_are_checked_in_file_order() {
        let path = Path::new("big.obj");
        let mut text: String = (0..60_000).map(|i| format!("v {i} 0 0\n")).collect();
        assert!(line_pieces(&text, CHECK_PIECE).len() > 2);
        text += "f 1 2 60000\nf -1 -2 -60000\n";
        check_obj_text(path, &text).unwrap();
        let good = text.clone();
        text += "f 1 2 60001\n";
        match check_obj_text(path, &text) {
            Err(SceneError::Line { line, message, .. }) => {
                assert_eq!(line, 60_003);
                assert!(message.contains("defines 60000 before this line"), "{message}");
            }
            other => panic!("{other:?}"),
        }
        let mut early = good.clone();
        early.replace_range(0..0, "v 1 2\n");
        let late = good.replacen("v 59000 0 0\n", "v 59000 0\n", 1);
        for (text, want) in [(early, 1), (late, 59_001)] {
            match check_obj_text(path, &text) {
                Err(SceneError::Line { line, .. }) => assert_eq!(line, want),
                other => panic!("{other:?}"),
            }
        }
    }

    #[test]
    fn good_lines_pass() {
        let mut defined = Defined { positions: 4, texcoords: 2, normals: 1 };
        for line in [
            "v 1 2 3",
            "v 1 2 3 0.5",
            "v 1 2 3 1 0 0",
            "vt 0.5 0.5",
            "vt 0.5 0.5 0",
            "vn 0 0 1",
            "f 1 2 3",
            "f 1/1 2/2 -1/-1",
            "f 1//1 2//1 3//1 4//1",
            "f 1/1/1 2/2/1 3/1/1",
            "# comment",
            "#comment",
            "",
            "   ",
            "s off",
            "g group one",
            "usemtl red",
            "mtllib a b.mtl",
            "l 1 2",
        ] {
            check_obj_line(line, &mut defined, &mut Vec::new()).unwrap_or_else(|e| panic!("{line:?}: {e}"));
        }
    }

    #[test]
    fn bad_lines_are_named() {
        check_line_error("v 1.0 abc 2", "cannot parse vertex position 'v 1.0 abc 2'");
        check_line_error("v 1 2", "a vertex needs 3 coordinates");
        check_line_error("v nan 0 0", "vertex has non-finite coordinate 'nan'");
        check_line_error("v 1e39 0 0", "vertex has non-finite coordinate '1e39'");
        check_line_error("v 1 1 1 0", "unusable w = 0");
        check_line_error("v 1e30 1 1 1e-30", "unusable w");
        check_line_error("vt 0.5", "cannot parse texture coordinate");
        check_line_error("vn 0 x 1", "cannot parse normal");
        check_line_error(
            "f 1 2 5",
            "face refers to vertex 5, but the file defines 4 before this line: 'f 1 2 5'",
        );
        check_line_error("f 0 1 2", "face refers to vertex 0");
        check_line_error("f -5 1 2", "face refers to vertex -5");
        check_line_error("f 1/0 2/1 3/1", "face refers to texture coordinate 0");
        check_line_error("f 1/-5 2/1 3/1", "face refers to texture coordinate -5");
        check_line_error("f 1//1 2//1 3//1", "face refers to normal 1, but the file defines 0");
        check_line_error("f 1 2 x", "cannot parse face index 'x'");
        check_line_error("f 1/1/1/1 2 3", "cannot parse face vertex");
        check_line_error("f 99999999999999999999 1 2", "cannot parse face index");
        check_line_error("f", "a face needs vertices");
        check_line_error("usemtl", "without a material name");
        check_line_error("hello world", "unknown statement 'hello' in 'hello world'");
    }

    #[test]
    fn quotes_stay_one_line_and_short() {
        assert_eq!(quote("  a\tb\u{1}  "), "'a\\tb\\u{1}'");
        assert!(quote(&"x".repeat(500)).chars().count() < 70);
    }
}
