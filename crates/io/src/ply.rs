//! PLY (the Stanford polygon format, in which scanned models such as the
//! bunny and the dragon are published): ASCII and binary, through the
//! `ply-rs-bw` crate.
//!
//! What is read: the `vertex` element's `x`, `y`, `z` (any scalar type),
//! `nx`, `ny`, `nz` when all three are present, and `red`, `green`, `blue`
//! (8-bit 0..=255, or floating point 0..=1) as vertex colours; the `face`
//! element's `vertex_indices` (or `vertex_index`) lists, each polygon cut
//! into a fan of triangles. Other elements (edges, materials, range grids)
//! and properties are read past and ignored. The mesh gets the default
//! material; its normals, when the file has none, are computed as for
//! every mesh (SPEC §6).
//!
//! The header and the payload are checked before `ply-rs-bw` reads them
//! ([`check_payload`]): every element's count within the scene's limits
//! (`zline_scene::MAX_VERTICES`, `MAX_TRIANGLES`), and every entry and
//! every list length backed by bytes (binary) or numbers (ASCII) of the
//! file — the reader reserves memory by those counts, so a hostile file
//! could otherwise make it ask for more than any machine has.

use std::io::Cursor;
use std::path::Path;

use glam::Vec3;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{Encoding, Header, Property, PropertyAccess, PropertyType, ScalarType};
use zline_scene::{Material, Mesh, MAX_TRIANGLES, MAX_VERTICES};

use crate::error::SceneError;
use crate::files::{read_limited, FileKind};

/// Loads a PLY file as one mesh.
pub fn load_ply(path: &Path) -> Result<Vec<Mesh>, SceneError> {
    let bytes = read_limited(path, FileKind::Model).map_err(|e| e.into_error(path))?;
    parse_ply(path, &bytes)
}

/// One entry of any element: the properties zline reads, the rest dropped.
#[derive(Default)]
struct Entry {
    position: [f64; 3],
    /// Which of x, y, z were given (bits 0, 1, 2).
    has_position: u8,
    normal: [f32; 3],
    has_normal: u8,
    color: [f32; 3],
    has_color: u8,
    indices: Option<Vec<i64>>,
    /// A property of the right name with a type zline cannot use.
    bad: Option<String>,
}

/// A scalar property as f64; `None` for a list.
fn scalar(p: &Property) -> Option<f64> {
    Some(match *p {
        Property::Char(v) => f64::from(v),
        Property::UChar(v) => f64::from(v),
        Property::Short(v) => f64::from(v),
        Property::UShort(v) => f64::from(v),
        Property::Int(v) => f64::from(v),
        Property::UInt(v) => f64::from(v),
        Property::Float(v) => f64::from(v),
        Property::Double(v) => v,
        _ => return None,
    })
}

/// An integer list property as i64 values; `None` for a scalar or a list
/// of floating-point values.
fn index_list(p: Property) -> Option<Vec<i64>> {
    Some(match p {
        Property::ListChar(v) => v.into_iter().map(i64::from).collect(),
        Property::ListUChar(v) => v.into_iter().map(i64::from).collect(),
        Property::ListShort(v) => v.into_iter().map(i64::from).collect(),
        Property::ListUShort(v) => v.into_iter().map(i64::from).collect(),
        Property::ListInt(v) => v.into_iter().map(i64::from).collect(),
        Property::ListUInt(v) => v.into_iter().map(i64::from).collect(),
        _ => return None,
    })
}

impl PropertyAccess for Entry {
    fn new() -> Self {
        Entry::default()
    }

    fn set_property(&mut self, name: &String, property: Property) {
        let axis = |n: &str| match n {
            "x" | "nx" | "red" => Some(0),
            "y" | "ny" | "green" => Some(1),
            "z" | "nz" | "blue" => Some(2),
            _ => None,
        };
        match name.as_str() {
            "vertex_indices" | "vertex_index" => match index_list(property) {
                Some(list) => self.indices = Some(list),
                None => self.bad = Some(format!("'{name}' is not a list of integers")),
            },
            n @ ("x" | "y" | "z") => match scalar(&property) {
                Some(v) => {
                    let k = axis(n).unwrap_or(0);
                    self.position[k] = v;
                    self.has_position |= 1 << k;
                }
                None => self.bad = Some(format!("'{name}' is a list, not a number")),
            },
            n @ ("nx" | "ny" | "nz") => {
                if let Some(v) = scalar(&property) {
                    let k = axis(n).unwrap_or(0);
                    self.normal[k] = v as f32;
                    self.has_normal |= 1 << k;
                }
            }
            n @ ("red" | "green" | "blue") => {
                let v = match property {
                    Property::UChar(v) => Some(f32::from(v) / 255.0),
                    Property::Float(v) => Some(v),
                    Property::Double(v) => Some(v as f32),
                    _ => None,
                };
                if let Some(v) = v {
                    let k = axis(n).unwrap_or(0);
                    self.color[k] = v.clamp(0.0, 1.0);
                    self.has_color |= 1 << k;
                }
            }
            _ => {}
        }
    }
}

/// Parses PLY bytes read from `path` (which names the file in messages).
pub(crate) fn parse_ply(path: &Path, bytes: &[u8]) -> Result<Vec<Mesh>, SceneError> {
    let error = |message: String| SceneError::File { path: path.to_path_buf(), message };
    let mut reader = Cursor::new(bytes);
    let parser = Parser::<Entry>::new();
    let header = parser.read_header(&mut reader).map_err(|e| error(format!("bad PLY header: {e}")))?;
    check_payload(&header, &bytes[reader.position() as usize..]).map_err(error)?;
    let Some(vertex) = header.elements.get("vertex") else {
        return Err(error("no 'vertex' element".into()));
    };
    let face_count = header.elements.get("face").map_or(0, |f| f.count);
    SceneError::check_size(path, face_count, vertex.count)?;
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for (name, element) in &header.elements {
        let entries = parser
            .read_payload_for_element(&mut reader, element, &header)
            .map_err(|e| error(format!("element '{name}': {e}")))?;
        match name.as_str() {
            "vertex" => vertices = entries,
            "face" => faces = entries,
            _ => {}
        }
    }
    build(path, &vertices, &faces)
}

/// The size in bytes of a binary scalar.
fn scalar_size(t: &ScalarType) -> usize {
    match t {
        ScalarType::Char | ScalarType::UChar => 1,
        ScalarType::Short | ScalarType::UShort => 2,
        ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
        ScalarType::Double => 8,
    }
}

/// Walks the payload as the header describes it, without keeping
/// anything: every element's count at most [`MAX_VERTICES`] (and at least
/// one property when non-zero), every entry present, every list's length
/// backed by the values that follow it.
fn check_payload(header: &Header, payload: &[u8]) -> Result<(), String> {
    let binary = match header.encoding {
        Encoding::Ascii => None,
        Encoding::BinaryLittleEndian => Some(true),
        Encoding::BinaryBigEndian => Some(false),
    };
    let mut lines = std::str::from_utf8(payload).ok().map(str::lines).filter(|_| binary.is_none());
    if binary.is_none() && lines.is_none() {
        return Err("the ASCII payload is not UTF-8 text".into());
    }
    let mut at = 0usize;
    for (name, element) in &header.elements {
        if element.count > MAX_VERTICES.max(MAX_TRIANGLES) {
            return Err(format!(
                "element '{name}' claims {} entries, more than the limit of {MAX_VERTICES}",
                element.count
            ));
        }
        if element.count > 0 && element.properties.is_empty() {
            return Err(format!("element '{name}' has {} entries and no properties", element.count));
        }
        for entry in 0..element.count {
            let missing = || {
                format!(
                    "element '{name}': entry {entry} of {} is missing (the file ends early)",
                    element.count
                )
            };
            match binary {
                Some(little) => {
                    for (_, property) in &element.properties {
                        match &property.data_type {
                            PropertyType::Scalar(t) => at += scalar_size(t),
                            PropertyType::List(count_type, item) => {
                                let size = scalar_size(count_type);
                                let raw = payload.get(at..at + size).ok_or_else(missing)?;
                                let count = read_count(raw, count_type, little);
                                at += size
                                    + count
                                        .checked_mul(scalar_size(item) as u64)
                                        .map_or(usize::MAX / 2, |n| n.min(usize::MAX as u64 / 2) as usize);
                            }
                        }
                        if at > payload.len() {
                            return Err(missing());
                        }
                    }
                }
                None => {
                    let line =
                        lines.as_mut().and_then(|l| l.find(|l| !l.trim().is_empty())).ok_or_else(missing)?;
                    let mut tokens = line.split_whitespace();
                    for (_, property) in &element.properties {
                        let short = || format!("element '{name}': entry {entry} has too few values");
                        match &property.data_type {
                            PropertyType::Scalar(_) => {
                                tokens.next().ok_or_else(short)?;
                            }
                            PropertyType::List(..) => {
                                let count: u64 = tokens.next().ok_or_else(short)?.parse().map_err(|_| {
                                    format!("element '{name}': entry {entry}: a list length is not a whole number")
                                })?;
                                for _ in 0..count {
                                    tokens.next().ok_or_else(short)?;
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    Ok(())
}

/// A binary list length (a negative signed length reads as 0).
fn read_count(raw: &[u8], t: &ScalarType, little: bool) -> u64 {
    let bytes = |n: usize| {
        let mut b = [0u8; 8];
        b[..n].copy_from_slice(&raw[..n]);
        if !little {
            b[..n].reverse();
        }
        u64::from_le_bytes(b)
    };
    match t {
        ScalarType::Char => (raw[0] as i8).max(0) as u64,
        ScalarType::Short => (bytes(2) as u16 as i16).max(0) as u64,
        ScalarType::Int => (bytes(4) as u32 as i32).max(0) as u64,
        ScalarType::UChar | ScalarType::UShort | ScalarType::UInt => bytes(scalar_size(t)),
        // Floating-point list lengths are not valid PLY; ply-rs-bw refuses them.
        ScalarType::Float | ScalarType::Double => 0,
    }
}

/// The mesh from the vertex and face entries.
fn build(path: &Path, vertices: &[Entry], faces: &[Entry]) -> Result<Vec<Mesh>, SceneError> {
    let error = |message: String| SceneError::File { path: path.to_path_buf(), message };
    let mut positions = Vec::with_capacity(vertices.len());
    for (i, v) in vertices.iter().enumerate() {
        if let Some(why) = &v.bad {
            return Err(error(format!("vertex {i}: {why}")));
        }
        if v.has_position != 0b111 {
            return Err(error(format!("vertex {i}: needs x, y and z")));
        }
        positions.push(Vec3::new(v.position[0] as f32, v.position[1] as f32, v.position[2] as f32));
    }
    let normals = vertices
        .iter()
        .all(|v| v.has_normal == 0b111)
        .then(|| vertices.iter().map(|v| Vec3::from(v.normal)).collect::<Vec<_>>())
        .filter(|n| !n.is_empty());
    let colors: Vec<Vec3> = if !vertices.is_empty() && vertices.iter().all(|v| v.has_color == 0b111) {
        vertices.iter().map(|v| Vec3::from(v.color)).collect()
    } else {
        Vec::new()
    };
    let mut triangles = Vec::with_capacity(faces.len());
    for (f, face) in faces.iter().enumerate() {
        if let Some(why) = &face.bad {
            return Err(error(format!("face {f}: {why}")));
        }
        let Some(list) = &face.indices else {
            return Err(error(format!("face {f}: no 'vertex_indices' list")));
        };
        let mut index = Vec::with_capacity(list.len());
        for &i in list {
            match u32::try_from(i).ok().filter(|&i| (i as usize) < positions.len()) {
                Some(i) => index.push(i),
                None => {
                    return Err(error(format!(
                        "face {f}: vertex index {i} is outside 0..{} (the file's vertices)",
                        positions.len()
                    )))
                }
            }
        }
        // A polygon of n corners is a fan of n − 2 triangles; fewer than
        // three corners draw nothing.
        for k in 1..index.len().saturating_sub(1) {
            triangles.push([index[0], index[k], index[k + 1]]);
            if triangles.len() > MAX_TRIANGLES {
                SceneError::check_size(path, triangles.len(), positions.len())?;
            }
        }
    }
    if triangles.is_empty() {
        return Err(SceneError::NoTriangles { path: path.to_path_buf() });
    }
    let name = path.file_stem().map_or_else(|| "ply".to_string(), |s| s.to_string_lossy().into_owned());
    let mut mesh = Mesh::new(name.clone(), positions, normals, triangles, Material::default())
        .map_err(|source| SceneError::Mesh { path: path.to_path_buf(), mesh: name, source })?;
    mesh.colors = colors;
    Ok(vec![mesh])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Vec<Mesh>, SceneError> {
        parse_ply(Path::new("test.ply"), text.as_bytes())
    }

    const SQUARE: &str =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
        property uchar red\nproperty uchar green\nproperty uchar blue\n\
        element face 1\nproperty list uchar int vertex_indices\nend_header\n\
        0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 255 255 255\n4 0 1 2 3\n";

    #[test]
    fn an_ascii_quad_is_a_fan_of_two_coloured_triangles() {
        let meshes = parse(SQUARE).unwrap();
        let mesh = &meshes[0];
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(mesh.positions[2], Vec3::new(1.0, 1.0, 0.0));
        assert_eq!(mesh.colors, vec![Vec3::X, Vec3::Y, Vec3::Z, Vec3::ONE]);
        assert!(mesh.normals.iter().all(|n| (*n - Vec3::Z).length() < 1e-6), "{:?}", mesh.normals);
    }

    #[test]
    fn a_binary_file_reads_as_its_ascii_twin() {
        let mut bytes = b"ply\nformat binary_little_endian 1.0\ncomment made by hand\nelement vertex 3\n\
            property double x\nproperty double y\nproperty double z\nproperty float nx\nproperty float ny\nproperty float nz\n\
            element face 1\nproperty list uchar uint vertex_indices\nend_header\n"
            .to_vec();
        for p in [[0.0f64, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]] {
            p.iter().for_each(|c| bytes.extend(c.to_le_bytes()));
            [0.0f32, 0.0, 1.0].iter().for_each(|c| bytes.extend(c.to_le_bytes()));
        }
        bytes.push(3);
        [0u32, 1, 2].iter().for_each(|i| bytes.extend(i.to_le_bytes()));
        let mesh = &parse_ply(Path::new("b.ply"), &bytes).unwrap()[0];
        assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
        assert_eq!(mesh.positions[1], Vec3::new(2.0, 0.0, 0.0));
        assert_eq!(mesh.normals, vec![Vec3::Z; 3]);
        assert!(mesh.colors.is_empty());
    }

    fn message(text: &str) -> String {
        parse(text).err().map(|e| e.to_string()).unwrap_or_default()
    }

    /// A binary face whose list claims four billion indices is refused
    /// before the reader reserves room for them.
    #[test]
    fn a_binary_list_longer_than_the_file_is_refused() {
        let mut bytes =
            b"ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
            property float z\nelement face 1\nproperty list uint double vertex_indices\nend_header\n"
                .to_vec();
        bytes.extend([0u8; 36]);
        bytes.extend(4_000_000_000u32.to_be_bytes());
        bytes.extend([0u8; 24]);
        let m = parse_ply(Path::new("l.ply"), &bytes).err().map(|e| e.to_string()).unwrap_or_default();
        assert_eq!(m, "l.ply: element 'face': entry 0 of 1 is missing (the file ends early)");
        let m = message("ply\nformat ascii 1.0\nelement vertex 3\nelement face 0\nend_header\n");
        assert!(m.contains("element 'vertex' has 3 entries and no properties"), "{m}");
    }

    #[test]
    fn bad_files_name_the_file_and_the_problem() {
        let m =
            message("ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nend_header\n0\n");
        assert!(m.starts_with("test.ply: element 'vertex' claims 4000000000 entries"), "{m}");
        let m = message(&SQUARE.replace("4 0 1 2 3", "4 0 1 2 9"));
        assert!(m.contains("test.ply: face 0: vertex index 9 is outside 0..4"), "{m}");
        let m = message(&SQUARE.replace("4 0 1 2 3", "4 0 1 -2 3"));
        assert!(m.contains("vertex index -2"), "{m}");
        let m = message(&SQUARE.replace("1 1 0 0 0 255\n", ""));
        assert!(m.starts_with("test.ply: element"), "{m}");
        let m = message("ply\nformat ascii 1.0\nelement face 0\nend_header\n");
        assert_eq!(m, "test.ply: no 'vertex' element");
        let m = message("not a ply file\n");
        assert!(m.starts_with("test.ply: bad PLY header"), "{m}");
        let m = message(&SQUARE.replace("element face 1", "element face 0").replace("4 0 1 2 3\n", ""));
        assert_eq!(m, "test.ply: no triangles");
        let m = message(&SQUARE.replace("property float z\n", "").replace(" 0 2", " 2"));
        assert!(m.contains("needs x, y and z") || m.contains("element 'vertex'"), "{m}");
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]

        /// Any bytes changed anywhere in a valid file give a mesh or an
        /// error naming the file, never a panic or an abort.
        #[test]
        fn corrupted_files_never_panic(
            edits in proptest::collection::vec((0usize..400, proptest::prelude::any::<u8>()), 1..8),
            binary in proptest::prelude::any::<bool>(),
        ) {
            let mut bytes = if binary {
                let mut b = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n\
                    property float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
                    .to_vec();
                b.extend([0u8; 36]);
                for face in [[0i32, 1, 2], [2, 1, 0]] {
                    b.extend([3u8]);
                    face.iter().for_each(|i| b.extend(i.to_le_bytes()));
                }
                b
            } else {
                SQUARE.as_bytes().to_vec()
            };
            for (at, value) in edits {
                let n = bytes.len();
                bytes[at % n] = value;
            }
            if let Err(e) = parse_ply(Path::new("fuzz.ply"), &bytes) {
                proptest::prop_assert!(e.to_string().starts_with("fuzz.ply"), "{e}");
            }
        }
    }
}
