//! Bump and normal maps: a texture that perturbs the shading normal per
//! sample in the tangent frame of the surface, and the tangents that span
//! that frame.
//!
//! Contract: a mesh draws its [`NormalMap`](crate::NormalMap) when it has texture
//! coordinates and tangents ([`Mesh::with_tangents`] from a file, or
//! [`Mesh::with_generated_tangents`], MikkTSpace), and only with Phong
//! shading. Flat and Gouraud shading ignore it: the perturbation is a
//! property of each sample, and lighting once per triangle or at the
//! vertices would alias the map away (a vertex samples the map at one
//! point and the colours in between only blend those few values).
//!
//! The tangent frame of a sample (eye space): N the interpolated normal,
//! normalized; T and B = w·(N × T) (B formed per vertex from the vertex's
//! normal and tangent) interpolated and not normalized — the MikkTSpace
//! convention, which the maps baked against it expect. The map gives a
//! tangent-space normal m and the shading normal is
//!
//! n′ = normalize(m.x·T + m.y·B + m.z·N)
//!
//! (zero when that sum is zero, like an interpolated normal). The map's
//! texels are read at level 0 with its sampler's filter (trilinear reads
//! level 0 bilinearly: a level of detail for a derivative is not defined
//! here, so a minified map aliases).
//!
//! - [`NormalEncoding::Height`](crate::NormalEncoding::Height) (OBJ `bump`/`map_bump`, scene files'
//!   `bump`): the red channel is a height h ∈ [0, 1]; its gradient by
//!   central differences one texel apart,
//!   ∂h/∂s ≈ (h(s + 1/W, t) − h(s − 1/W, t))·W/2 and
//!   ∂h/∂t ≈ (h(s, t + 1/H) − h(s, t − 1/H))·H/2 for a W × H map, gives
//!   m = (−k·∂h/∂s, −k·∂h/∂t, 1) with k the map's scale. That is Blinn's
//!   (1978) N′ = N + (B_u (N × P_v) − B_v (N × P_u))/|N| with height k·h,
//!   P_u = T, P_v = B and a unit N: the surface is taken as if a step of 1
//!   in s moved one unit along T. So k is the height of a white texel over
//!   a black one in texture-coordinate units: a ramp from 0 to 1 across
//!   the whole texture along s tilts the normal by atan(k) towards −T.
//! - [`NormalEncoding::Tangent`](crate::NormalEncoding::Tangent) (glTF `normalTexture`): the texel's
//!   r, g, b ∈ [0, 1] (byte/255) decode as m = ((2r − 1)·k, (2g − 1)·k,
//!   2b − 1), glTF's rule with k its `scale`; +y is up in the image
//!   (towards +t), the OpenGL convention glTF uses. A byte of 128 is
//!   2·128/255 − 1 = 1/255, not 0: the "flat" texel (128, 128, 255) tilts
//!   the normal by atan(√2/255) ≈ 0.32° towards T + B.

use std::collections::HashMap;

use glam::Vec4;

use crate::error::MeshError;
use crate::model::Mesh;

impl Mesh {
    /// The same mesh with tangents from a file, one per position (xyz and
    /// the handedness w, taken as its sign: −1 when negative, else +1).
    /// Errors when the count differs or a tangent is not finite.
    pub fn with_tangents(mut self, tangents: Vec<Vec4>) -> Result<Mesh, MeshError> {
        if tangents.len() != self.positions.len() {
            return Err(MeshError::TangentCount {
                tangents: tangents.len(),
                positions: self.positions.len(),
            });
        }
        if let Some(vertex) = tangents.iter().position(|t| !t.is_finite()) {
            return Err(MeshError::NonFiniteTangent { vertex, tangent: tangents[vertex] });
        }
        self.tangents = tangents.into_iter().map(|t| t.truncate().extend(handedness(t.w))).collect();
        Ok(self)
    }

    /// The same mesh with a bump or normal map.
    pub fn with_normal_map(mut self, map: crate::model::NormalMap) -> Mesh {
        self.normal_map = Some(map);
        self
    }

    /// The same mesh with MikkTSpace tangents from its positions, normals
    /// and texture coordinates (the `mikktspace` crate), the tangents glTF
    /// prescribes when a file has none. MikkTSpace gives a tangent per
    /// triangle corner; a vertex whose corners disagree is split into one
    /// vertex per tangent (the copies keep its position, normal, texture
    /// coordinates and colour), so shared vertices stay shared where the
    /// tangent frame is continuous. A mesh without texture coordinates, or
    /// one MikkTSpace rejects, is returned unchanged (without tangents, so
    /// its map is not drawn).
    pub fn with_generated_tangents(self) -> Mesh {
        if self.uvs.len() != self.positions.len() || self.triangles.is_empty() {
            return self;
        }
        let mut geometry = Corners { mesh: &self, tangents: vec![Vec4::ZERO; self.triangles.len() * 3] };
        if !mikktspace::generate_tangents(&mut geometry) {
            return self;
        }
        let corners = geometry.tangents;
        split_by_tangent(self, &corners)
    }
}

/// −1 for a negative handedness, +1 otherwise.
fn handedness(w: f32) -> f32 {
    if w < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// The mesh as MikkTSpace reads it, with a tangent slot per corner.
struct Corners<'a> {
    mesh: &'a Mesh,
    tangents: Vec<Vec4>,
}

impl Corners<'_> {
    fn vertex(&self, face: usize, vert: usize) -> usize {
        self.mesh.triangles[face][vert] as usize
    }
}

impl mikktspace::Geometry for Corners<'_> {
    fn num_faces(&self) -> usize {
        self.mesh.triangles.len()
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.positions[self.vertex(face, vert)].to_array()
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.normals[self.vertex(face, vert)].to_array()
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        self.mesh.uvs[self.vertex(face, vert)].to_array()
    }

    fn set_tangent_encoded(&mut self, tangent: [f32; 4], face: usize, vert: usize) {
        let t = Vec4::from_array(tangent);
        // A degenerate corner can come back non-finite: no tangent there.
        self.tangents[face * 3 + vert] =
            if t.is_finite() { t.truncate().extend(handedness(t.w)) } else { Vec4::ZERO };
    }
}

/// Assigns each vertex its corners' tangent, splitting vertices whose
/// corners disagree (see [`Mesh::with_generated_tangents`]).
fn split_by_tangent(mut mesh: Mesh, corners: &[Vec4]) -> Mesh {
    let n = mesh.positions.len();
    let mut tangents: Vec<Option<Vec4>> = vec![None; n];
    let mut copies: HashMap<(u32, [u32; 4]), u32> = HashMap::new();
    let key = |t: Vec4| t.to_array().map(f32::to_bits);
    for (k, &t) in corners.iter().enumerate() {
        let (face, vert) = (k / 3, k % 3);
        let v = mesh.triangles[face][vert];
        match tangents[v as usize] {
            None => tangents[v as usize] = Some(t),
            Some(first) if key(first) == key(t) => {}
            Some(_) => {
                let index = *copies.entry((v, key(t))).or_insert_with(|| {
                    let i = v as usize;
                    mesh.positions.push(mesh.positions[i]);
                    mesh.normals.push(mesh.normals[i]);
                    mesh.uvs.push(mesh.uvs[i]);
                    if !mesh.colors.is_empty() {
                        mesh.colors.push(mesh.colors[i]);
                    }
                    tangents.push(Some(t));
                    (tangents.len() - 1) as u32
                });
                mesh.triangles[face][vert] = index;
            }
        }
    }
    mesh.tangents = tangents.into_iter().map(|t| t.unwrap_or(Vec4::ZERO)).collect();
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Vec2, Vec3};
    use zline_shading::Material;

    fn quad(uvs: Vec<Vec2>) -> Mesh {
        let positions = vec![Vec3::new(0.0, 0.0, 0.0), Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
        Mesh::new("quad", positions, None, vec![[0, 1, 2], [0, 2, 3]], Material::DEFAULT)
            .unwrap()
            .with_uvs(uvs)
            .unwrap()
    }

    #[test]
    fn generated_tangents_follow_s_and_t() {
        // s along +x, t along +y: T = +x, and B = w·(N × T) = w·(z × x) =
        // w·y must point along +t, so w = +1.
        let mesh = quad(vec![Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y]).with_generated_tangents();
        assert_eq!(mesh.tangents.len(), 4);
        for t in &mesh.tangents {
            assert!((t.truncate() - Vec3::X).length() < 1e-6, "{t}");
            assert_eq!(t.w, 1.0);
        }
        // Mirrored in s: T = −x, and B must still point along +t = +y,
        // so w = −1 (N × T = z × −x = −y).
        let mesh = quad(vec![Vec2::X, Vec2::ZERO, Vec2::Y, Vec2::ONE]).with_generated_tangents();
        for t in &mesh.tangents {
            assert!((t.truncate() + Vec3::X).length() < 1e-6, "{t}");
            assert_eq!(t.w, -1.0);
        }
    }

    #[test]
    fn a_seam_splits_the_vertices_it_runs_through() {
        // Two triangles sharing vertices 0 and 2 whose texture coordinates
        // turn a quarter between them: the shared vertices get two
        // tangents each, so they are split; the result is still valid.
        let positions = vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
        let mesh = Mesh::new("seam", positions, None, vec![[0, 1, 2], [0, 2, 3]], Material::DEFAULT).unwrap();
        let corners = [
            Vec4::new(1.0, 0.0, 0.0, 1.0),
            Vec4::new(1.0, 0.0, 0.0, 1.0),
            Vec4::new(1.0, 0.0, 0.0, 1.0),
            Vec4::new(0.0, 1.0, 0.0, 1.0),
            Vec4::new(0.0, 1.0, 0.0, 1.0),
            Vec4::new(0.0, 1.0, 0.0, 1.0),
        ];
        let mesh = mesh.with_uvs(vec![Vec2::ZERO; 4]).unwrap();
        let split = split_by_tangent(mesh, &corners);
        assert_eq!(split.positions.len(), 6);
        assert_eq!(split.triangles, vec![[0, 1, 2], [4, 5, 3]]);
        assert_eq!(split.tangents[3], Vec4::new(0.0, 1.0, 0.0, 1.0));
        assert_eq!(split.tangents[4], split.tangents[3]);
        assert_eq!(split.positions[4], split.positions[0]);
        assert_eq!(split.tangents.len(), split.positions.len());
        assert_eq!(split.normals.len(), split.positions.len());
    }

    #[test]
    fn file_tangents_are_checked() {
        let mesh = quad(vec![Vec2::ZERO; 4]);
        assert!(matches!(
            mesh.clone().with_tangents(vec![Vec4::X; 3]),
            Err(MeshError::TangentCount { tangents: 3, positions: 4 })
        ));
        let bad = vec![Vec4::X, Vec4::X, Vec4::new(f32::NAN, 0.0, 0.0, 1.0), Vec4::X];
        assert!(matches!(
            mesh.clone().with_tangents(bad),
            Err(MeshError::NonFiniteTangent { vertex: 2, .. })
        ));
        let ok = mesh.with_tangents(vec![Vec4::new(1.0, 0.0, 0.0, -0.5); 4]).unwrap();
        assert_eq!(ok.tangents[0].w, -1.0);
    }
}
