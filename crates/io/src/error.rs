//! Loader errors: the one error type of the IO boundary.
//!
//! Contract: every message is one line that starts with the file it is
//! about, then says where (line, column, key, vertex) and what is wrong,
//! quoting the offending value where there is one:
//! `bunny.obj: line 12: vertex has non-finite coordinate 'nan'`.
//! Rendering itself cannot fail; only loading can.

use std::path::{Path, PathBuf};

use thiserror::Error;
use zline_scene::{MeshError, MAX_TRIANGLES, MAX_VERTICES};

/// An error while loading a model or scene file.
#[derive(Debug, Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("{}: cannot read file: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// A syntax or value error located at a line (1-based) of a text file.
    #[error("{}: line {line}: {message}", path.display())]
    Line {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong, quoting the line or value.
        message: String,
    },
    /// An error located at a line and column (1-based) of a text file.
    #[error("{}: line {line}, column {column}: {message}", path.display())]
    At {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// 1-based column, in characters.
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// An error in the file as a whole, or one without a known location.
    #[error("{}: {message}", path.display())]
    File {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// The model file holds no triangles.
    #[error("{}: no triangles", path.display())]
    NoTriangles {
        /// The file.
        path: PathBuf,
    },
    /// A mesh read from the file is invalid.
    #[error("{}: mesh '{mesh}': {source}", path.display())]
    Mesh {
        /// The file.
        path: PathBuf,
        /// The mesh's name.
        mesh: String,
        /// What is wrong with it.
        source: MeshError,
    },
    /// A texture that a material of a model uses failed to load.
    #[error("{}: material '{material}': texture {source}", model.display())]
    Texture {
        /// The model file (OBJ or glTF).
        model: PathBuf,
        /// The material that uses the texture.
        material: String,
        /// The texture's own error (which names the image file, or the
        /// embedded image).
        source: Box<SceneError>,
    },
    /// A file referenced by a scene file failed to load.
    #[error("{}: line {line}, column {column}: {key}: {source}", scene.display())]
    Referenced {
        /// The scene file.
        scene: PathBuf,
        /// 1-based line of the reference in the scene file.
        line: usize,
        /// 1-based column of the reference.
        column: usize,
        /// The key that names the file, e.g. `objects[2].model`.
        key: String,
        /// The referenced file's own error (which names that file).
        source: Box<SceneError>,
    },
}

impl SceneError {
    /// An error when a model or scene has more than [`MAX_TRIANGLES`]
    /// triangles or [`MAX_VERTICES`] vertices.
    pub(crate) fn check_size(path: &Path, triangles: usize, vertices: usize) -> Result<(), SceneError> {
        let over = |what: &str, n: usize, limit: usize| SceneError::File {
            path: path.to_path_buf(),
            message: format!("{n} {what}, more than the limit of {limit}"),
        };
        if triangles > MAX_TRIANGLES {
            return Err(over("triangles", triangles, MAX_TRIANGLES));
        }
        if vertices > MAX_VERTICES {
            return Err(over("vertices", vertices, MAX_VERTICES));
        }
        Ok(())
    }

    /// A located error in a text file, from a byte offset into its text.
    pub(crate) fn at_offset(path: PathBuf, text: &str, offset: usize, message: String) -> SceneError {
        let (line, column) = line_column(text, offset);
        SceneError::At { path, line, column, message }
    }
}

/// 1-based line and column (in characters) of a byte offset into `text`.
pub(crate) fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[line_start..].chars().count() + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_column_is_one_based() {
        let text = "ab\ncdé\nf";
        assert_eq!(line_column(text, 0), (1, 1));
        assert_eq!(line_column(text, 3), (2, 1));
        assert_eq!(line_column(text, 7), (2, 4));
        assert_eq!(line_column(text, 100), (3, 2));
    }

    #[test]
    fn triangles_and_vertices_over_the_limits_are_errors() {
        let path = Path::new("m.obj");
        assert!(SceneError::check_size(path, MAX_TRIANGLES, MAX_VERTICES).is_ok());
        let e = SceneError::check_size(path, MAX_TRIANGLES + 1, 3).unwrap_err().to_string();
        assert_eq!(
            e,
            format!("m.obj: {} triangles, more than the limit of {MAX_TRIANGLES}", MAX_TRIANGLES + 1)
        );
        let e = SceneError::check_size(path, 1, MAX_VERTICES + 1).unwrap_err().to_string();
        assert_eq!(e, format!("m.obj: {} vertices, more than the limit of {MAX_VERTICES}", MAX_VERTICES + 1));
    }

    #[test]
    fn messages_are_one_line_and_name_the_file() {
        let e = SceneError::Mesh {
            path: "a/model.obj".into(),
            mesh: "cube".into(),
            source: MeshError::NonFinitePosition { vertex: 3, x: f32::NAN, y: 0.0, z: 1.0 },
        };
        assert_eq!(e.to_string(), "a/model.obj: mesh 'cube': vertex 3 has non-finite position (NaN, 0, 1)");
        let e = SceneError::NoTriangles { path: "empty.obj".into() };
        assert_eq!(e.to_string(), "empty.obj: no triangles");
    }
}
