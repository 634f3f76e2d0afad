//! Mesh errors: why arrays do not make a valid [`Mesh`](crate::Mesh).
//!
//! Contract: every message is one line naming the first offending triangle
//! or vertex and quoting its values. A mesh error knows no file; the
//! loaders (zline-io) wrap it in an error that names the file and mesh.

use thiserror::Error;

/// Why a [`Mesh`](crate::Mesh) could not be built from its arrays. It knows
/// no file; loaders wrap it in an error naming the file and the mesh.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum MeshError {
    /// A triangle refers to a vertex that does not exist.
    #[error("triangle {triangle} refers to vertex {index}, but there are only {vertex_count} vertices")]
    IndexOutOfRange {
        /// Index of the triangle.
        triangle: usize,
        /// The offending vertex index.
        index: u32,
        /// Number of vertices.
        vertex_count: usize,
    },
    /// A vertex position has a NaN or infinite coordinate.
    #[error("vertex {vertex} has non-finite position ({x}, {y}, {z})")]
    NonFinitePosition {
        /// Index of the vertex.
        vertex: usize,
        /// The coordinates.
        x: f32,
        /// The coordinates.
        y: f32,
        /// The coordinates.
        z: f32,
    },
    /// The normal array does not have one normal per vertex.
    #[error("{normals} normals given for {positions} vertices")]
    NormalCount {
        /// Number of normals.
        normals: usize,
        /// Number of positions.
        positions: usize,
    },
    /// The texture coordinate array does not have one entry per vertex.
    #[error("{uvs} texture coordinates given for {positions} vertices")]
    UvCount {
        /// Number of texture coordinates.
        uvs: usize,
        /// Number of positions.
        positions: usize,
    },
    /// A texture coordinate is NaN or infinite.
    #[error("vertex {vertex} has non-finite texture coordinate ({s}, {t})")]
    NonFiniteUv {
        /// Index of the vertex.
        vertex: usize,
        /// s.
        s: f32,
        /// t.
        t: f32,
    },
    /// The vertex colour array does not have one entry per vertex.
    #[error("{colors} vertex colours given for {positions} vertices")]
    ColorCount {
        /// Number of colours.
        colors: usize,
        /// Number of positions.
        positions: usize,
    },
    /// The tangent array does not have one tangent per vertex.
    #[error("{tangents} tangents given for {positions} vertices")]
    TangentCount {
        /// Number of tangents.
        tangents: usize,
        /// Number of positions.
        positions: usize,
    },
    /// A tangent is NaN or infinite.
    #[error("vertex {vertex} has non-finite tangent {tangent}")]
    NonFiniteTangent {
        /// Index of the vertex.
        vertex: usize,
        /// The tangent (xyz, handedness).
        tangent: glam::Vec4,
    },
    /// A vertex colour is NaN or infinite.
    #[error("vertex {vertex} has non-finite colour {color}")]
    NonFiniteColor {
        /// Index of the vertex.
        vertex: usize,
        /// The colour.
        color: glam::Vec3,
    },
}
