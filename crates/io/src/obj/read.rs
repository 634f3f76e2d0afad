//! OBJ statements read in parallel, into tobj's structures.
//!
//! tobj reads an OBJ one line at a time on one thread; for the 2.4 MB
//! Stanford bunny that was 27–32 ms, the largest step of a whole-process
//! thumbnail. This module reads the same statements in parallel pieces of
//! whole lines (the pieces and the definition counts before each come from
//! [`super::check`], which has already accepted every line) and then
//! replays, in file order, what tobj does with them: objects and groups (`o`, `g`)
//! and material changes (`usemtl`) start new models, `mtllib` loads a
//! material library through the caller's loader, and each model's faces
//! become one single-index mesh — corners deduplicated by their
//! (position, texture coordinate, normal) triple in first-use order, faces
//! fanned into triangles, points and lines left out. The result is tobj's
//! own `Model` and `Material` values, equal to what
//! `tobj::load_obj_buf` returns with zline's options; tests compare the two
//! on the shipped models and on generated text.

use std::collections::HashMap;
use std::path::Path;

use rayon::prelude::*;

use super::check::Defined;

/// tobj's marker for an index a corner does not give.
const MISSING: usize = usize::MAX;

/// One face corner: 0-based indices, [`MISSING`] where not given (tobj's
/// `VertexIndices`, resolved the same way).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
struct Corner {
    v: usize,
    vt: usize,
    vn: usize,
}

/// A statement that shapes the models, at its place in the face stream.
#[derive(Debug)]
enum Event<'a> {
    /// `o` or `g`: the name a new model takes.
    Name(String),
    /// `usemtl`: the material's name.
    UseMaterial(&'a str),
    /// `mtllib`: the library's path as written.
    Library(&'a str),
}

/// What one piece of text holds.
#[derive(Debug, Default)]
struct Piece<'a> {
    pos: Vec<f32>,
    v_color: Vec<f32>,
    texcoord: Vec<f32>,
    normal: Vec<f32>,
    /// Corners of every face, face after face.
    corners: Vec<Corner>,
    /// Corners per face.
    arity: Vec<u32>,
    /// Each event with the piece's [`Counts`] when it came.
    events: Vec<(Counts, Event<'a>)>,
}

/// Where a piece, or the file, stands: the lengths of its arrays in the
/// order pos, v_color, texcoord, normal, corners, arity (faces).
type Counts = [usize; 6];

impl Piece<'_> {
    fn counts(&self) -> Counts {
        let p = self;
        [p.pos.len(), p.v_color.len(), p.texcoord.len(), p.normal.len(), p.corners.len(), p.arity.len()]
    }
}

/// Reads `pieces` (whole lines; `before[i]` counts the definitions ahead of
/// piece i) as tobj would, loading material libraries through `load_mtl` in
/// file order. Returns the models and, like tobj, the materials or the last
/// library's error when none loaded.
pub(crate) fn read_models(
    pieces: &[&str],
    before: &[Defined],
    mut load_mtl: impl FnMut(&Path) -> tobj::MTLLoadResult,
) -> tobj::LoadResult {
    let read: Vec<Piece> = pieces
        .par_iter()
        .zip(before)
        .map(|(text, before)| read_piece(text, *before))
        .collect::<Result<_, _>>()?;

    // The arrays of the whole file, and where each piece starts in them.
    let mut all = Piece::default();
    let mut starts = Vec::with_capacity(read.len());
    for piece in &read {
        starts.push(all.counts());
        all.pos.extend_from_slice(&piece.pos);
        all.v_color.extend_from_slice(&piece.v_color);
        all.texcoord.extend_from_slice(&piece.texcoord);
        all.normal.extend_from_slice(&piece.normal);
        all.corners.extend_from_slice(&piece.corners);
        all.arity.extend_from_slice(&piece.arity);
    }
    // The model made of the faces between two marks, over the attributes
    // defined by the second (as tobj exports a model when it ends).
    let model = |from: &Counts, to: &Counts, name: &str, mat_id| {
        let faces = (&all.arity[from[5]..to[5]], &all.corners[from[4]..to[4]]);
        Ok(tobj::Model::new(export(&all, to, faces, mat_id)?, name.to_owned()))
    };

    // Replay the events in file order over the face stream: a name, or a
    // change of material, ends the current model if it has faces.
    let mut models = Vec::new();
    let mut materials: Vec<tobj::Material> = Vec::new();
    let mut mat_map: HashMap<String, usize> = HashMap::new();
    let mut mtl_error = None;
    let mut name = "unnamed_object".to_owned();
    let mut mat_id = None;
    let mut first: Counts = [0; 6];
    for (piece, start) in read.iter().zip(&starts) {
        for (local, event) in &piece.events {
            let at: Counts = std::array::from_fn(|k| start[k] + local[k]);
            let ends_model = match event {
                Event::Name(_) => true,
                Event::UseMaterial(material) => mat_map.get(*material).copied() != mat_id,
                Event::Library(_) => false,
            };
            if ends_model && at[5] > first[5] {
                models.push(model(&first, &at, &name, mat_id)?);
                first = at;
            }
            match event {
                Event::Name(new) => name.clone_from(new),
                Event::UseMaterial(material) => mat_id = mat_map.get(*material).copied(),
                Event::Library(path) => match load_mtl(Path::new(path)) {
                    Ok((mut mats, map)) => {
                        let offset = materials.len();
                        materials.append(&mut mats);
                        for (k, v) in map {
                            mat_map.insert(k, v + offset);
                        }
                    }
                    Err(e) => mtl_error = Some(e),
                },
            }
        }
    }
    models.push(model(&first, &all.counts(), &name, mat_id)?);
    let materials = match (materials.is_empty(), mtl_error) {
        (true, Some(e)) => Err(e),
        _ => Ok(materials),
    };
    Ok((models, materials))
}

/// Reads one piece: attributes, faces (indices resolved against the counts
/// so far, as tobj does) and events.
fn read_piece(text: &str, before: Defined) -> Result<Piece<'_>, tobj::LoadError> {
    use tobj::LoadError as E;
    let mut p = Piece::default();
    let float = |s: &str| s.parse::<f32>();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                for _ in 0..3 {
                    p.pos.push(words.next().and_then(|w| float(w).ok()).ok_or(E::PositionParseError)?);
                }
                let Some(first) = words.next() else { continue };
                match (words.next(), words.next()) {
                    (None, _) => {
                        let w = float(first).map_err(|_| E::PositionParseError)?;
                        if w == 0.0 {
                            return Err(E::ScalingByZeroError);
                        }
                        let n = p.pos.len();
                        for c in &mut p.pos[n - 3..] {
                            *c /= w;
                        }
                    }
                    (Some(_), None) => return Err(E::ColorParseError),
                    (Some(second), Some(third)) => {
                        if words.next().is_some() {
                            return Err(E::ColorParseError);
                        }
                        for c in [first, second, third] {
                            match float(c) {
                                Ok(x) => p.v_color.push(x),
                                Err(_) => break,
                            }
                        }
                    }
                }
            }
            Some("vt") => {
                for _ in 0..2 {
                    p.texcoord.push(words.next().and_then(|w| float(w).ok()).ok_or(E::TexcoordParseError)?);
                }
            }
            Some("vn") => {
                for _ in 0..3 {
                    p.normal.push(words.next().and_then(|w| float(w).ok()).ok_or(E::NormalParseError)?);
                }
            }
            Some("f" | "l") => {
                let counts = [
                    before.positions + p.pos.len() / 3,
                    before.texcoords + p.texcoord.len() / 2,
                    before.normals + p.normal.len() / 3,
                ];
                let start = p.corners.len();
                for word in words {
                    let corner = parse_corner(word, counts).ok_or(E::FaceParseError)?;
                    p.corners.push(corner);
                }
                p.arity.push((p.corners.len() - start) as u32);
            }
            Some("o" | "g") => {
                let size = line.chars().next().map_or(0, char::len_utf8);
                let name = line[size..].trim();
                let name = if name.is_empty() { "unnamed_object" } else { name };
                p.events.push((p.counts(), Event::Name(name.to_owned())));
            }
            Some("mtllib") => {
                let path = line.split_once(' ').unwrap_or_default().1.trim();
                p.events.push((p.counts(), Event::Library(path)));
            }
            Some("usemtl") => {
                let material = line.split_once(' ').unwrap_or_default().1.trim();
                if material.is_empty() {
                    return Err(E::MaterialParseError);
                }
                p.events.push((p.counts(), Event::UseMaterial(material)));
            }
            _ => {}
        }
    }
    Ok(p)
}

/// tobj's `VertexIndices::parse`: `v`, `v/vt`, `v//vn` or `v/vt/vn`,
/// 1-based, negative counting back from `counts` (positions, texture
/// coordinates, normals defined so far).
fn parse_corner(word: &str, counts: [usize; 3]) -> Option<Corner> {
    let mut indices = [MISSING; 3];
    for (i, part) in word.split('/').enumerate() {
        if part.is_empty() {
            continue;
        }
        let x: isize = part.parse().ok()?;
        let slot = indices.get_mut(i)?;
        *slot = if x < 0 { (counts[i] as isize + x) as usize } else { (x - 1) as usize };
    }
    Some(Corner { v: indices[0], vt: indices[1], vn: indices[2] })
}

/// tobj's `export_faces` with triangulation on and points and lines
/// ignored: the faces (`arity` corners each, from `corners`) as one
/// single-index mesh over the file's attribute arrays as they stood when
/// the model ended (`lens`, whose first four are pos, v_color, texcoord,
/// normal).
fn export(
    all: &Piece,
    lens: &Counts,
    (arity, corners): (&[u32], &[Corner]),
    material_id: Option<usize>,
) -> Result<tobj::Mesh, tobj::LoadError> {
    let (pos, v_color) = (&all.pos[..lens[0]], &all.v_color[..lens[1]]);
    let (texcoord, normal) = (&all.texcoord[..lens[2]], &all.normal[..lens[3]]);
    let mut mesh = tobj::Mesh { material_id, ..Default::default() };
    // Corners given by position alone (the common case) are looked up in a
    // table; others in a map. Either gives each new corner the next index.
    let mut by_position: Vec<u32> = Vec::new();
    let mut by_triple: HashMap<Corner, u32> = HashMap::new();
    let mut next = 0u32;
    let mut add = |c: &Corner, mesh: &mut tobj::Mesh| -> Result<(), tobj::LoadError> {
        let known = if c.vt == MISSING && c.vn == MISSING {
            by_position.get(c.v).copied().filter(|&i| i != u32::MAX)
        } else {
            by_triple.get(c).copied()
        };
        if let Some(i) = known {
            mesh.indices.push(i);
            return Ok(());
        }
        let v = c.v;
        if v.saturating_mul(3).saturating_add(2) >= pos.len() {
            return Err(tobj::LoadError::FaceVertexOutOfBounds);
        }
        mesh.positions.extend_from_slice(&pos[v * 3..v * 3 + 3]);
        if !texcoord.is_empty() && c.vt != MISSING {
            if c.vt.saturating_mul(2).saturating_add(1) >= texcoord.len() {
                return Err(tobj::LoadError::FaceTexCoordOutOfBounds);
            }
            mesh.texcoords.extend_from_slice(&texcoord[c.vt * 2..c.vt * 2 + 2]);
        }
        if !normal.is_empty() && c.vn != MISSING {
            if c.vn.saturating_mul(3).saturating_add(2) >= normal.len() {
                return Err(tobj::LoadError::FaceNormalOutOfBounds);
            }
            mesh.normals.extend_from_slice(&normal[c.vn * 3..c.vn * 3 + 3]);
        }
        if !v_color.is_empty() {
            if v * 3 + 2 >= v_color.len() {
                return Err(tobj::LoadError::FaceColorOutOfBounds);
            }
            mesh.vertex_color.extend_from_slice(&v_color[v * 3..v * 3 + 3]);
        }
        if c.vt == MISSING && c.vn == MISSING {
            if by_position.len() <= v {
                by_position.resize(v + 1, u32::MAX);
            }
            by_position[v] = next;
        } else {
            by_triple.insert(*c, next);
        }
        mesh.indices.push(next);
        next += 1;
        Ok(())
    };
    let mut at = 0;
    for &n in arity {
        let face = &corners[at..at + n as usize];
        at += n as usize;
        match face {
            // Points and lines are ignored (zline's load options).
            [] | [_] | [_, _] => {
                if face.is_empty() {
                    return Err(tobj::LoadError::InvalidPolygon);
                }
            }
            [a, b, c] => {
                for corner in [a, b, c] {
                    add(corner, &mut mesh)?;
                }
            }
            [a, b, c, d] => {
                for corner in [a, b, c, a, c, d] {
                    add(corner, &mut mesh)?;
                }
            }
            [a, rest @ ..] => {
                for pair in rest.windows(2) {
                    for corner in [a, &pair[0], &pair[1]] {
                        add(corner, &mut mesh)?;
                    }
                }
            }
        }
    }
    Ok(mesh)
}
