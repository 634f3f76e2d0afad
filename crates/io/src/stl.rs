//! STL (stereolithography: the triangle soup of CAD tools and 3D
//! printers), ASCII and binary, through the `stl_io` crate.
//!
//! STL stores each triangle with its own three corners. `stl_io` welds
//! corners with the same bits into shared vertices, so the mesh's vertex
//! normals are the normalized sums of the face normals around each corner
//! (SPEC §6), as for an OBJ without normals: a scanned model looks smooth
//! under Gouraud and Phong shading, and a CAD part's sharp edges are best
//! drawn with `--shading flat`. The facet normals of the file are not used
//! (many writers leave them zero). The mesh gets the default material.
//!
//! A binary file's triangle count must match its size (84 + 50 bytes per
//! triangle) before anything is read.

use std::io::Cursor;
use std::path::Path;

use glam::Vec3;
use zline_scene::{Material, Mesh};

use crate::error::SceneError;
use crate::files::{read_limited, FileKind};

/// Loads an STL file as one mesh.
pub fn load_stl(path: &Path) -> Result<Vec<Mesh>, SceneError> {
    let bytes = read_limited(path, FileKind::Model).map_err(|e| e.into_error(path))?;
    parse_stl(path, &bytes)
}

/// True when `bytes` start as ASCII STL does (`solid`, then a `facet` or
/// `endsolid` line). Binary files may also start with "solid" in their
/// 80-byte header, so the size rule decides those.
fn is_ascii(bytes: &[u8]) -> bool {
    let text = String::from_utf8_lossy(&bytes[..bytes.len().min(512)]);
    let mut words = text.split_whitespace();
    words.next() == Some("solid")
        && text.lines().nth(1).is_some_and(|l| {
            let l = l.trim_start();
            l.starts_with("facet") || l.starts_with("endsolid")
        })
}

/// True when `bytes` are ASCII STL or a binary STL whose size matches its
/// triangle count (what [`crate::InputFormat::sniff`] takes as STL).
pub(crate) fn looks_like_stl(bytes: &[u8]) -> bool {
    if is_ascii(bytes) {
        return true;
    }
    bytes.len() >= 84 && {
        let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
        84 + 50 * count == bytes.len() as u64
    }
}

/// Parses STL bytes read from `path` (which names the file in messages).
pub(crate) fn parse_stl(path: &Path, bytes: &[u8]) -> Result<Vec<Mesh>, SceneError> {
    let error = |message: String| SceneError::File { path: path.to_path_buf(), message };
    if !is_ascii(bytes) {
        if bytes.len() < 84 {
            return Err(error(format!(
                "{} bytes: too short for a binary STL (84 bytes of header)",
                bytes.len()
            )));
        }
        let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
        let expected = 84 + 50 * count;
        if expected != bytes.len() as u64 {
            return Err(error(format!(
                "binary STL of {count} triangles should be {expected} bytes, but the file has {}",
                bytes.len()
            )));
        }
        SceneError::check_size(path, count as usize, 0)?;
    }
    let mesh = stl_io::read_stl(&mut Cursor::new(bytes)).map_err(|e| error(format!("bad STL: {e}")))?;
    SceneError::check_size(path, mesh.faces.len(), mesh.vertices.len())?;
    let positions: Vec<Vec3> = mesh.vertices.iter().map(|v| Vec3::new(v[0], v[1], v[2])).collect();
    let triangles: Vec<[u32; 3]> = mesh
        .faces
        .iter()
        .map(|f| f.vertices.map(|i| i as u32))
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .collect();
    if triangles.is_empty() {
        return Err(SceneError::NoTriangles { path: path.to_path_buf() });
    }
    let name = path.file_stem().map_or_else(|| "stl".to_string(), |s| s.to_string_lossy().into_owned());
    let mesh = Mesh::new(name.clone(), positions, None, triangles, Material::default())
        .map_err(|source| SceneError::Mesh { path: path.to_path_buf(), mesh: name, source })?;
    Ok(vec![mesh])
}

#[cfg(test)]
mod tests {
    use super::*;

    const TETRA: &str = "solid t\n\
        facet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n\
        facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\n\
        facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\n\
        facet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\n\
        endsolid t\n";

    fn binary(triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
        let mut bytes = b"solid but binary".to_vec();
        bytes.resize(80, 0);
        bytes.extend((triangles.len() as u32).to_le_bytes());
        for t in triangles {
            bytes.extend([0u8; 12]);
            t.iter().flatten().for_each(|c| bytes.extend(c.to_le_bytes()));
            bytes.extend([0u8; 2]);
        }
        bytes
    }

    #[test]
    fn an_ascii_tetrahedron_shares_its_four_corners() {
        let mesh = &parse_stl(Path::new("t.stl"), TETRA.as_bytes()).unwrap()[0];
        assert_eq!(mesh.positions.len(), 4);
        assert_eq!(mesh.triangles.len(), 4);
        // The corner at the origin: the mean of three axis normals.
        let origin = mesh.positions.iter().position(|p| *p == Vec3::ZERO).unwrap();
        assert!((mesh.normals[origin] - Vec3::splat(-1.0 / 3f32.sqrt())).length() < 1e-6);
    }

    #[test]
    fn a_binary_file_with_solid_in_its_header_is_read_as_binary() {
        let t = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let mesh = &parse_stl(Path::new("b.stl"), &binary(&[t])).unwrap()[0];
        assert_eq!(mesh.triangles.len(), 1);
        assert_eq!(mesh.positions.len(), 3);
    }

    #[test]
    fn bad_files_name_the_file_and_the_problem() {
        let t = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let mut lying = binary(&[t]);
        lying[80..84].copy_from_slice(&4_000_000_000u32.to_le_bytes());
        let m = parse_stl(Path::new("b.stl"), &lying).unwrap_err().to_string();
        assert!(m.starts_with("b.stl: binary STL of 4000000000 triangles should be"), "{m}");
        let m = parse_stl(Path::new("s.stl"), b"tiny").unwrap_err().to_string();
        assert!(m.contains("too short"), "{m}");
        let degenerate = binary(&[[[1.0, 1.0, 1.0]; 3]]);
        let m = parse_stl(Path::new("d.stl"), &degenerate).unwrap_err().to_string();
        assert_eq!(m, "d.stl: no triangles");
        let m = parse_stl(
            Path::new("a.stl"),
            TETRA.replace("vertex 0 1 0\nvertex 1", "vertex 0 x 0\nvertex 1").as_bytes(),
        )
        .unwrap_err()
        .to_string();
        assert!(m.starts_with("a.stl: "), "{m}");
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]

        /// Any bytes changed anywhere in a valid file give a mesh or an
        /// error naming the file, never a panic.
        #[test]
        fn corrupted_files_never_panic(
            edits in proptest::collection::vec((0usize..600, proptest::prelude::any::<u8>()), 1..8),
            binary_file in proptest::prelude::any::<bool>(),
        ) {
            let t = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
            let mut bytes = if binary_file { binary(&[t, t]) } else { TETRA.as_bytes().to_vec() };
            for (at, value) in edits {
                let n = bytes.len();
                bytes[at % n] = value;
            }
            if let Err(e) = parse_stl(Path::new("fuzz.stl"), &bytes) {
                proptest::prop_assert!(e.to_string().starts_with("fuzz.stl"), "{e}");
            }
        }
    }
}
