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
    /// Each event with the piece's face and corner counts and attribute
    /// lengths (pos, v_color, texcoord, normal) when it came.
    events: Vec<((usize, usize), [usize; 4], Event<'a>)>,
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

    // The attribute arrays of the whole file, and where each piece's start.
    let mut all = Piece::default();
    let mut offsets = Vec::with_capacity(read.len());
    for piece in &read {
        offsets.push((
            [all.pos.len(), all.v_color.len(), all.texcoord.len(), all.normal.len()],
            all.corners.len(),
            all.arity.len(),
        ));
        all.pos.extend_from_slice(&piece.pos);
        all.v_color.extend_from_slice(&piece.v_color);
        all.texcoord.extend_from_slice(&piece.texcoord);
        all.normal.extend_from_slice(&piece.normal);
        all.corners.extend_from_slice(&piece.corners);
        all.arity.extend_from_slice(&piece.arity);
    }

    // Replay the events in file order over the face stream.
    let mut models = Vec::new();
    let mut materials: Vec<tobj::Material> = Vec::new();
    let mut mat_map: HashMap<String, usize> = HashMap::new();
    let mut mtl_error = None;
    let mut name = "unnamed_object".to_owned();
    let mut mat_id = None;
    // The current model's faces: from `first` (face index, corner index).
    let mut first = (0, 0);
    for (piece, (starts, corner0, face0)) in read.iter().zip(&offsets) {
        for ((faces, corners), lens, event) in &piece.events {
            let (at, corner_at) = (face0 + faces, corner0 + corners);
            let has_faces = at > first.0;
            let lens = [0, 1, 2, 3].map(|k| starts[k] + lens[k]);
            let pop = |models: &mut Vec<tobj::Model>, name: &str, mat_id| -> Result<(), tobj::LoadError> {
                let faces = (&all.arity[first.0..at], &all.corners[first.1..corner_at]);
                models.push(tobj::Model::new(export(&all, lens, faces, mat_id)?, name.to_owned()));
                Ok(())
            };
            match event {
                Event::Name(new) => {
                    if has_faces {
                        pop(&mut models, &name, mat_id)?;
                        first = (at, corner_at);
                    }
                    name.clone_from(new);
                }
                Event::UseMaterial(material) => {
                    let new = mat_map.get(*material).copied();
                    if mat_id != new && has_faces {
                        pop(&mut models, &name, mat_id)?;
                        first = (at, corner_at);
                    }
                    mat_id = new;
                }
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
    let lens = [all.pos.len(), all.v_color.len(), all.texcoord.len(), all.normal.len()];
    let faces = (&all.arity[first.0..], &all.corners[first.1..]);
    models.push(tobj::Model::new(export(&all, lens, faces, mat_id)?, name));
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
                p.events.push(((p.arity.len(), p.corners.len()), lens(&p), Event::Name(name.to_owned())));
            }
            Some("mtllib") => {
                let path = line.split_once(' ').unwrap_or_default().1.trim();
                p.events.push(((p.arity.len(), p.corners.len()), lens(&p), Event::Library(path)));
            }
            Some("usemtl") => {
                let material = line.split_once(' ').unwrap_or_default().1.trim();
                if material.is_empty() {
                    return Err(E::MaterialParseError);
                }
                p.events.push(((p.arity.len(), p.corners.len()), lens(&p), Event::UseMaterial(material)));
            }
            _ => {}
        }
    }
    Ok(p)
}

fn lens(p: &Piece) -> [usize; 4] {
    [p.pos.len(), p.v_color.len(), p.texcoord.len(), p.normal.len()]
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
/// single-index mesh over the first `lens` values of the file's attribute
/// arrays (pos, v_color, texcoord, normal), as they stood when the model
/// ended.
fn export(
    all: &Piece,
    lens: [usize; 4],
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
