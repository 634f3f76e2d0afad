//! glTF vertex attributes and indices: POSITION, NORMAL, TANGENT, COLOR_0,
//! TEXCOORD_n and the triangle indices, each accessor checked for its type,
//! its range in the buffer and its count (see the parent module).

use std::path::Path;

use glam::{Vec2, Vec3};
use gltf::accessor::{DataType, Dimensions};

use crate::error::SceneError;

/// The vertex data of one glTF file: its buffers, and the file for
/// messages.
pub(super) struct Attributes<'a> {
    /// The glTF file.
    pub(super) path: &'a Path,
    /// Its buffers, in order.
    pub(super) buffers: &'a [Vec<u8>],
}

impl Attributes<'_> {
    pub(super) fn read_positions(
        &self,
        primitive: &gltf::Primitive,
        name: &str,
    ) -> Result<Option<Vec<Vec3>>, SceneError> {
        let Some(accessor) = primitive.get(&gltf::Semantic::Positions) else { return Ok(None) };
        self.check_accessor(&accessor, name, "POSITION", &[(Dimensions::Vec3, DataType::F32)])?;
        let read = primitive.reader(|b| self.buffers.get(b.index()).map(Vec::as_slice)).read_positions();
        let positions: Vec<Vec3> = read.map(|it| it.map(Vec3::from).collect()).unwrap_or_default();
        self.check_count(&accessor, name, "POSITION", positions.len())?;
        Ok(Some(positions))
    }

    /// The normals, when the primitive has one per vertex.
    pub(super) fn read_normals(
        &self,
        primitive: &gltf::Primitive,
        name: &str,
        vertices: usize,
    ) -> Result<Option<Vec<Vec3>>, SceneError> {
        let Some(accessor) = primitive.get(&gltf::Semantic::Normals) else { return Ok(None) };
        self.check_accessor(&accessor, name, "NORMAL", &[(Dimensions::Vec3, DataType::F32)])?;
        let read = primitive.reader(|b| self.buffers.get(b.index()).map(Vec::as_slice)).read_normals();
        let normals: Vec<Vec3> = read.map(|it| it.map(Vec3::from).collect()).unwrap_or_default();
        self.check_count(&accessor, name, "NORMAL", normals.len())?;
        Ok((normals.len() == vertices).then_some(normals))
    }

    /// TANGENT (xyz, w the handedness), when the primitive has one per
    /// vertex. glTF's bitangent w·(N × T) points up the image, along
    /// t = 1 − v, as zline's does.
    pub(super) fn read_tangents(
        &self,
        primitive: &gltf::Primitive,
        name: &str,
        vertices: usize,
    ) -> Result<Option<Vec<glam::Vec4>>, SceneError> {
        let Some(accessor) = primitive.get(&gltf::Semantic::Tangents) else { return Ok(None) };
        self.check_accessor(&accessor, name, "TANGENT", &[(Dimensions::Vec4, DataType::F32)])?;
        let read = primitive.reader(|b| self.buffers.get(b.index()).map(Vec::as_slice)).read_tangents();
        let tangents: Vec<glam::Vec4> = read.map(|it| it.map(glam::Vec4::from).collect()).unwrap_or_default();
        self.check_count(&accessor, name, "TANGENT", tangents.len())?;
        Ok((tangents.len() == vertices).then_some(tangents))
    }

    /// COLOR_0 as RGB, and whether some alpha is below 1 (not used; the
    /// caller warns).
    pub(super) fn read_colors(
        &self,
        primitive: &gltf::Primitive,
        name: &str,
    ) -> Result<Option<(Vec<Vec3>, bool)>, SceneError> {
        let Some(accessor) = primitive.get(&gltf::Semantic::Colors(0)) else { return Ok(None) };
        let types = [Dimensions::Vec3, Dimensions::Vec4]
            .into_iter()
            .flat_map(|d| [DataType::F32, DataType::U8, DataType::U16].map(|t| (d, t)));
        self.check_accessor(&accessor, name, "COLOR_0", &types.collect::<Vec<_>>())?;
        let read = primitive.reader(|b| self.buffers.get(b.index()).map(Vec::as_slice)).read_colors(0);
        let rgba: Vec<[f32; 4]> = read.map(|r| r.into_rgba_f32().collect()).unwrap_or_default();
        self.check_count(&accessor, name, "COLOR_0", rgba.len())?;
        let alpha_ignored = rgba.iter().any(|c| c[3] < 1.0);
        Ok(Some((rgba.iter().map(|&[r, g, b, _]| Vec3::new(r, g, b)).collect(), alpha_ignored)))
    }

    /// Texture coordinates of a set, flipped to t = 1 − v.
    pub(super) fn read_uvs(
        &self,
        primitive: &gltf::Primitive,
        name: &str,
        set: u32,
    ) -> Result<Option<Vec<Vec2>>, SceneError> {
        let Some(accessor) = primitive.get(&gltf::Semantic::TexCoords(set)) else { return Ok(None) };
        let what = format!("TEXCOORD_{set}");
        let types = [DataType::F32, DataType::U8, DataType::U16].map(|t| (Dimensions::Vec2, t));
        self.check_accessor(&accessor, name, &what, &types)?;
        let read = primitive.reader(|b| self.buffers.get(b.index()).map(Vec::as_slice)).read_tex_coords(set);
        let uvs: Vec<Vec2> =
            read.map(|r| r.into_f32().map(|[s, v]| Vec2::new(s, 1.0 - v)).collect()).unwrap_or_default();
        self.check_count(&accessor, name, &what, uvs.len())?;
        Ok(Some(uvs))
    }

    /// Triangles from the indices, or from consecutive vertices for a
    /// non-indexed primitive; a trailing incomplete triangle is dropped.
    pub(super) fn read_triangles(
        &self,
        primitive: &gltf::Primitive,
        name: &str,
        vertices: usize,
    ) -> Result<Vec<[u32; 3]>, SceneError> {
        let indices: Vec<u32> = match primitive.indices() {
            Some(accessor) => {
                let types = [DataType::U8, DataType::U16, DataType::U32].map(|t| (Dimensions::Scalar, t));
                self.check_accessor(&accessor, name, "indices", &types)?;
                let reader = primitive.reader(|b| self.buffers.get(b.index()).map(Vec::as_slice));
                let indices: Vec<u32> =
                    reader.read_indices().map(|r| r.into_u32().collect()).unwrap_or_default();
                self.check_count(&accessor, name, "indices", indices.len())?;
                indices
            }
            None => {
                let count = u32::try_from(vertices)
                    .map_err(|_| self.error(format!("mesh '{name}': {vertices} vertices are too many")))?;
                (0..count).collect()
            }
        };
        Ok(indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect())
    }

    /// Checks an accessor's type and that its data lies inside its buffer,
    /// so that reading it cannot fail or panic.
    pub(super) fn check_accessor(
        &self,
        accessor: &gltf::Accessor,
        mesh: &str,
        what: &str,
        types: &[(Dimensions, DataType)],
    ) -> Result<(), SceneError> {
        let fail =
            |why: String| self.error(format!("mesh '{mesh}': {what} accessor {}: {why}", accessor.index()));
        let kind = (accessor.dimensions(), accessor.data_type());
        if !types.contains(&kind) {
            return Err(fail(format!("type {:?} of {:?} is not allowed here", kind.0, kind.1)));
        }
        if accessor.count() == 0 {
            return Err(fail("count is 0".into()));
        }
        let size = accessor.size();
        if let Some(view) = accessor.view() {
            self.check_range(&view, accessor.offset(), accessor.count(), size).map_err(&fail)?;
        }
        if let Some(sparse) = accessor.sparse() {
            if sparse.count() == 0 {
                return Err(fail("sparse count is 0".into()));
            }
            let (indices, values) = (sparse.indices(), sparse.values());
            let index_size = indices.index_type().size();
            self.check_range(&indices.view(), indices.offset(), sparse.count(), index_size).map_err(&fail)?;
            self.check_range(&values.view(), values.offset(), sparse.count(), size).map_err(&fail)?;
        }
        Ok(())
    }

    /// `count` elements of `size` bytes from `offset` fit in the view, and
    /// the view in its buffer.
    pub(super) fn check_range(
        &self,
        view: &gltf::buffer::View,
        offset: usize,
        count: usize,
        size: usize,
    ) -> Result<(), String> {
        let stride = view.stride().unwrap_or(size);
        if stride < size {
            return Err(format!("byteStride {stride} is smaller than an element ({size} bytes)"));
        }
        let end = (count - 1)
            .checked_mul(stride)
            .and_then(|n| n.checked_add(offset))
            .and_then(|n| n.checked_add(size));
        if end.is_none_or(|end| end > view.length()) {
            return Err(format!("{count} elements do not fit in buffer view {}", view.index()));
        }
        let buffer_len = self.buffers.get(view.buffer().index()).map_or(0, Vec::len);
        if view.offset().checked_add(view.length()).is_none_or(|end| end > buffer_len) {
            return Err(format!("buffer view {} reaches beyond its buffer", view.index()));
        }
        Ok(())
    }

    pub(super) fn check_count(
        &self,
        accessor: &gltf::Accessor,
        mesh: &str,
        what: &str,
        read: usize,
    ) -> Result<(), SceneError> {
        if read == accessor.count() {
            return Ok(());
        }
        let index = accessor.index();
        Err(self.error(format!(
            "mesh '{mesh}': {what} accessor {index}: read {read} of {} elements",
            accessor.count()
        )))
    }

    fn error(&self, message: String) -> SceneError {
        SceneError::File { path: self.path.to_path_buf(), message }
    }
}
