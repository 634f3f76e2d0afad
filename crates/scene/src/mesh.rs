//! Mesh construction: validation of indices and coordinates, and vertex
//! normals (SPEC §6).
//!
//! Contract: [`Mesh::new`] takes positions, optional normals and triangles,
//! and returns a mesh that upholds [`Mesh`]'s invariants — every index in
//! range, every position finite, one finite unit normal per vertex — or a
//! [`MeshError`] naming the first offending triangle or vertex.
//!
//! Vertex normals, when the caller has none, are the normalized sum of the
//! unit normals of the faces around the vertex. Face normals are computed in
//! f64, so coordinates up to f32::MAX neither overflow nor underflow.
//! Vertices at the same position are treated as one vertex for this sum:
//! OBJ loaders split a vertex wherever its texture coordinates or normals
//! differ, and summing per split vertex would show those seams as creases.
//! Degenerate faces (zero area) contribute nothing. A vertex whose sum is
//! zero takes the normal of its first non-degenerate face, and a vertex
//! with no such face takes [`FALLBACK_NORMAL`] (+Z).
//!
//! Supplied normals are re-normalized; a zero or non-finite supplied normal
//! is replaced by the computed one.

use std::collections::HashMap;

use glam::{DVec3, Vec3};
use zline_shading::Material;

use crate::error::MeshError;
use crate::model::{Mesh, TextureMap};

/// The normal of a vertex that belongs to no non-degenerate face.
pub const FALLBACK_NORMAL: Vec3 = Vec3::Z;

impl Mesh {
    /// Builds a validated mesh. `normals`, when given, must have one entry
    /// per position; missing or unusable normals are computed (see the
    /// module documentation).
    pub fn new(
        name: impl Into<String>,
        positions: Vec<Vec3>,
        normals: Option<Vec<Vec3>>,
        triangles: Vec<[u32; 3]>,
        material: Material,
    ) -> Result<Mesh, MeshError> {
        check_positions(&positions)?;
        check_indices(&triangles, positions.len())?;
        let normals = match normals {
            Some(given) if given.len() != positions.len() => {
                return Err(MeshError::NormalCount { normals: given.len(), positions: positions.len() })
            }
            Some(given) => repair_normals(given, &positions, &triangles),
            None => vertex_normals(&positions, &triangles),
        };
        Ok(Mesh {
            name: name.into(),
            positions,
            normals,
            triangles,
            material,
            uvs: Vec::new(),
            colors: Vec::new(),
            diffuse_map: None,
            tangents: Vec::new(),
            normal_map: None,
            surface_maps: Default::default(),
        })
    }

    /// The same mesh with texture coordinates, one per position. Errors
    /// when the count differs or a coordinate is not finite.
    pub fn with_uvs(mut self, uvs: Vec<glam::Vec2>) -> Result<Mesh, MeshError> {
        if uvs.len() != self.positions.len() {
            return Err(MeshError::UvCount { uvs: uvs.len(), positions: self.positions.len() });
        }
        if let Some(vertex) = uvs.iter().position(|t| !t.is_finite()) {
            let t = uvs[vertex];
            return Err(MeshError::NonFiniteUv { vertex, s: t.x, t: t.y });
        }
        self.uvs = uvs;
        Ok(self)
    }

    /// The same mesh with vertex colours, one per position, each a factor
    /// on ka and kd (see [`Mesh::colors`]). Errors when the count differs or
    /// a colour is not finite.
    pub fn with_colors(mut self, colors: Vec<Vec3>) -> Result<Mesh, MeshError> {
        if colors.len() != self.positions.len() {
            return Err(MeshError::ColorCount { colors: colors.len(), positions: self.positions.len() });
        }
        if let Some(vertex) = colors.iter().position(|c| !c.is_finite()) {
            return Err(MeshError::NonFiniteColor { vertex, color: colors[vertex] });
        }
        self.colors = colors;
        Ok(self)
    }

    /// The same mesh with a diffuse texture.
    pub fn with_diffuse_map(mut self, map: TextureMap) -> Mesh {
        self.diffuse_map = Some(map);
        self
    }

    /// The axis-aligned bounding box (min, max) of the positions;
    /// `(Vec3::ZERO, Vec3::ZERO)` for a mesh without vertices.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        bounds_of(self.positions.iter().copied()).unwrap_or((Vec3::ZERO, Vec3::ZERO))
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// True when the mesh is closed and consistently oriented: every edge
    /// (between vertex positions, so split vertices count as one) is used
    /// once in each direction, by exactly two triangles. Such a mesh, when
    /// opaque, can have its back faces culled (SPEC §2).
    ///
    /// Positions are compared on a grid of [`CLOSURE_TOLERANCE`] times the
    /// mesh's largest extent: corners that a generator meant to be one
    /// point but computed apart (a UV sphere's pole at sin π ≈ 1.2e-16
    /// instead of 0) count as one, so a surface is closed when its gaps,
    /// if any, are narrower than a grid step. Two positions in one cell
    /// are at most √3 steps apart; two that close but in neighbouring cells
    /// stay apart, which can only leave a mesh open (culling off).
    pub fn is_closed(&self) -> bool {
        // Sorting, not hashing (hashing 3 edges per triangle measured ~10 %
        // of a whole-process bunny thumbnail). Each edge between position
        // classes p ≠ q becomes one key: the pair (min, max) and one bit for
        // its direction. Sorted, a closed mesh's keys come in pairs — the
        // same pair, once each way — and no pair a third time.
        if self.positions.len() > 1 << 31 {
            // The key holds two 31-bit classes; a mesh this large is taken
            // as open, which only costs culling.
            return false;
        }
        let class = position_classes(&self.positions, closure_grid(&self.positions));
        let mut keys: Vec<u64> = Vec::with_capacity(self.triangles.len() * 3);
        for tri in &self.triangles {
            let [a, b, c] = tri.map(|i| u64::from(class[i as usize]));
            for (p, q) in [(a, b), (b, c), (c, a)] {
                if p != q {
                    keys.push(p.min(q) << 33 | p.max(q) << 1 | u64::from(p < q));
                }
            }
        }
        keys.sort_unstable();
        let edge = |k: u64| k >> 1;
        !keys.is_empty()
            && keys.len().is_multiple_of(2)
            && keys.chunks_exact(2).all(|pair| pair[0] & 1 == 0 && pair[1] == pair[0] | 1)
            && keys.chunks_exact(2).zip(keys.chunks_exact(2).skip(1)).all(|(a, b)| edge(a[0]) != edge(b[0]))
    }

    /// The corner positions of triangle `t`.
    pub fn triangle(&self, t: usize) -> [Vec3; 3] {
        self.triangles[t].map(|i| self.positions[i as usize])
    }
}

/// The bounding box of some points, `None` when there are none.
pub(crate) fn bounds_of(points: impl IntoIterator<Item = Vec3>) -> Option<(Vec3, Vec3)> {
    points.into_iter().fold(None, |acc, p| match acc {
        None => Some((p, p)),
        Some((lo, hi)) => Some((lo.min(p), hi.max(p))),
    })
}

fn check_positions(positions: &[Vec3]) -> Result<(), MeshError> {
    match positions.iter().position(|p| !p.is_finite()) {
        Some(vertex) => {
            let p = positions[vertex];
            Err(MeshError::NonFinitePosition { vertex, x: p.x, y: p.y, z: p.z })
        }
        None => Ok(()),
    }
}

fn check_indices(triangles: &[[u32; 3]], vertex_count: usize) -> Result<(), MeshError> {
    for (triangle, tri) in triangles.iter().enumerate() {
        if let Some(&index) = tri.iter().find(|&&i| i as usize >= vertex_count) {
            return Err(MeshError::IndexOutOfRange { triangle, index, vertex_count });
        }
    }
    Ok(())
}

/// The unit normal of the triangle (a, b, c), counter-clockwise front, or
/// `None` when it has no area (or its coordinates are not finite).
pub fn face_normal(a: Vec3, b: Vec3, c: Vec3) -> Option<Vec3> {
    let (a, b, c) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
    unit_f64((b - a).cross(c - a))
}

/// `v / |v|` computed in f64, `None` for a zero or non-finite vector.
fn unit_f64(v: DVec3) -> Option<Vec3> {
    let len = v.length();
    (len > 0.0 && len.is_finite()).then(|| (v / len).as_vec3())
}

/// One normal per vertex from the faces around it (see the module doc).
pub(crate) fn vertex_normals(positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<Vec3> {
    let (group_of, groups) = weld_by_position(positions);
    let mut sum = vec![DVec3::ZERO; groups];
    let mut first = vec![None; groups];
    for tri in triangles {
        let [a, b, c] = tri.map(|i| positions[i as usize]);
        let Some(n) = face_normal(a, b, c) else { continue };
        for &i in tri {
            let g = group_of[i as usize];
            sum[g] += n.as_dvec3();
            first[g].get_or_insert(n);
        }
    }
    let per_group: Vec<Vec3> =
        sum.iter().zip(&first).map(|(&s, &f)| unit_f64(s).or(f).unwrap_or(FALLBACK_NORMAL)).collect();
    group_of.iter().map(|&g| per_group[g]).collect()
}

/// Assigns every vertex the id of the first vertex at the same position.
/// Returns the group of each vertex and the number of groups.
pub(crate) fn weld_by_position(positions: &[Vec3]) -> (Vec<usize>, usize) {
    let mut ids = HashMap::with_capacity(positions.len());
    let group_of = positions
        .iter()
        .map(|&p| {
            let next = ids.len();
            *ids.entry(position_key(p)).or_insert(next)
        })
        .collect();
    (group_of, ids.len())
}

/// A position's bits as a key; adding 0.0 turns −0.0 into +0.0, so both
/// spell the same key.
fn position_key(p: Vec3) -> [u32; 3] {
    (p + Vec3::ZERO).to_array().map(f32::to_bits)
}

/// The largest gap, relative to a mesh's largest extent, that
/// [`Mesh::is_closed`] takes for no gap: 2⁻²⁰. A gap of that size shows
/// only when the mesh spans more than about 2,400 pixels (√3 · 2²⁰ / 256: a
/// fixed-point step of 1/256 pixel, SPEC §3), and a mesh's own corners
/// computed apart by float rounding differ by far less (a few units in the
/// last place of an f32, 2⁻²³ of the coordinate).
pub const CLOSURE_TOLERANCE: f64 = 1.0 / (1u64 << 20) as f64;

/// The grid [`Mesh::is_closed`] compares positions on: its origin (the
/// bounds' low corner) and step ([`CLOSURE_TOLERANCE`] times the largest
/// extent; 1 for a mesh of one point, whose positions all fall in one cell
/// anyway).
fn closure_grid(positions: &[Vec3]) -> (DVec3, f64) {
    let Some((lo, hi)) = bounds_of(positions.iter().copied()) else {
        return (DVec3::ZERO, 1.0);
    };
    let extent = (hi.as_dvec3() - lo.as_dvec3()).max_element();
    (lo.as_dvec3(), if extent > 0.0 { extent * CLOSURE_TOLERANCE } else { 1.0 })
}

/// A position's cell on the grid `(origin, step)`: at most 2²⁰ + 1 cells
/// an axis, each coordinate rounded to the nearest (equal positions, −0.0
/// and +0.0 among them, always share a cell).
fn grid_key(p: Vec3, (origin, step): (DVec3, f64)) -> [u32; 3] {
    ((p.as_dvec3() - origin) / step).round().to_array().map(|c| c as u32)
}

/// For each vertex, one vertex in the same cell of `grid` (the same for
/// all of them), found by sorting.
fn position_classes(positions: &[Vec3], grid: (DVec3, f64)) -> Vec<u32> {
    let mut order: Vec<([u32; 3], u32)> =
        positions.iter().enumerate().map(|(i, &p)| (grid_key(p, grid), i as u32)).collect();
    order.sort_unstable();
    let mut class = vec![0; positions.len()];
    let mut first = 0;
    for (k, &(key, i)) in order.iter().enumerate() {
        if k == 0 || key != order[k - 1].0 {
            first = i;
        }
        class[i as usize] = first;
    }
    class
}

/// Re-normalizes supplied normals, replacing unusable ones by computed ones.
fn repair_normals(mut given: Vec<Vec3>, positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<Vec3> {
    let mut computed: Option<Vec<Vec3>> = None;
    for (i, n) in given.iter_mut().enumerate() {
        *n = match unit_f64(n.as_dvec3()) {
            Some(unit) => unit,
            None => computed.get_or_insert_with(|| vertex_normals(positions, triangles))[i],
        };
    }
    given
}

#[cfg(test)]
mod tests {
    use super::*;

    #[track_caller]
    fn check_unit(n: Vec3) {
        assert!(n.is_finite() && (n.length() - 1.0).abs() < 1e-5, "not a unit normal: {n}");
    }

    fn quad_positions(scale: f32) -> Vec<Vec3> {
        vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ]
        .into_iter()
        .map(|p| p * scale)
        .collect()
    }

    #[test]
    fn computed_normals_of_a_ccw_quad_point_to_plus_z() {
        let mesh =
            Mesh::new("quad", quad_positions(1.0), None, vec![[0, 1, 2], [0, 2, 3]], Material::DEFAULT)
                .unwrap();
        for n in &mesh.normals {
            assert!((*n - Vec3::Z).length() < 1e-6, "{n}");
        }
    }

    #[test]
    fn huge_and_tiny_coordinates_give_unit_normals() {
        for scale in [1e30, 3e38, 1e-30, 1e-40] {
            let mesh =
                Mesh::new("q", quad_positions(scale), None, vec![[0, 1, 2], [0, 2, 3]], Material::DEFAULT)
                    .unwrap();
            for &n in &mesh.normals {
                check_unit(n);
            }
        }
    }

    #[test]
    fn normal_is_the_normalized_sum_of_unit_face_normals() {
        // A vertex shared by a big face (+Z) and a small face (+X): the sum of
        // unit normals is not weighted by area, so the result is the diagonal.
        let p = vec![
            Vec3::ZERO,
            Vec3::new(100.0, 0.0, 0.0),
            Vec3::new(0.0, 100.0, 0.0),
            Vec3::new(0.0, 0.0, -0.01),
            Vec3::new(0.0, 0.01, 0.0),
        ];
        let mesh = Mesh::new("v", p, None, vec![[0, 1, 2], [0, 3, 4]], Material::DEFAULT).unwrap();
        let expected = Vec3::new(1.0, 0.0, 1.0).normalize();
        assert!((mesh.normals[0] - expected).length() < 1e-6, "{}", mesh.normals[0]);
    }

    #[test]
    fn split_vertices_at_one_position_share_a_normal() {
        // Two triangles folded along the x axis (normals +Z and +Y), the
        // vertices on the fold duplicated as an OBJ loader would.
        let p = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::ZERO, Vec3::Z, Vec3::X];
        let mesh = Mesh::new("fold", p, None, vec![[0, 1, 2], [3, 4, 5]], Material::DEFAULT).unwrap();
        assert_eq!(mesh.normals[0], mesh.normals[3]);
        assert_eq!(mesh.normals[1], mesh.normals[5]);
        assert!((mesh.normals[0] - Vec3::new(0.0, 1.0, 1.0).normalize()).length() < 1e-6);
        assert_eq!(mesh.normals[2], Vec3::Z);
    }

    #[test]
    fn vertices_without_faces_and_degenerate_faces_get_the_fallback() {
        let p = vec![Vec3::ZERO, Vec3::X, Vec3::X * 2.0, Vec3::Y];
        let mesh = Mesh::new("line", p, None, vec![[0, 1, 2]], Material::DEFAULT).unwrap();
        assert!(mesh.normals.iter().all(|&n| n == FALLBACK_NORMAL));
    }

    #[test]
    fn supplied_normals_are_renormalized_and_bad_ones_replaced() {
        let normals = vec![Vec3::Z * 5.0, Vec3::ZERO, Vec3::NAN, Vec3::new(0.0, 0.0, 1e-30)];
        let mesh =
            Mesh::new("q", quad_positions(1.0), Some(normals), vec![[0, 1, 2], [0, 2, 3]], Material::DEFAULT)
                .unwrap();
        for &n in &mesh.normals {
            assert!((n - Vec3::Z).length() < 1e-6, "{n}");
        }
    }

    #[test]
    fn bad_input_is_reported() {
        let m = Material::DEFAULT;
        let e = Mesh::new("q", quad_positions(1.0), None, vec![[0, 1, 4]], m).unwrap_err();
        assert_eq!(e.to_string(), "triangle 0 refers to vertex 4, but there are only 4 vertices");
        let mut p = quad_positions(1.0);
        p[2].y = f32::INFINITY;
        let e = Mesh::new("q", p, None, vec![[0, 1, 2]], m).unwrap_err();
        assert_eq!(e.to_string(), "vertex 2 has non-finite position (1, inf, 0)");
        let e = Mesh::new("q", quad_positions(1.0), Some(vec![Vec3::Z]), vec![], m).unwrap_err();
        assert_eq!(e.to_string(), "1 normals given for 4 vertices");
    }

    #[test]
    fn bounds_cover_all_positions() {
        let mesh = Mesh::new("q", quad_positions(2.0), None, vec![[0, 1, 2]], Material::DEFAULT).unwrap();
        assert_eq!(mesh.bounds(), (Vec3::ZERO, Vec3::new(2.0, 2.0, 0.0)));
        assert_eq!(mesh.triangle_count(), 1);
        assert_eq!(mesh.vertex_count(), 4);
    }

    /// The definition, by hashing: every directed edge between position
    /// classes used once, and its reverse too.
    fn closed_by_hashing(mesh: &Mesh) -> bool {
        use std::collections::HashMap;
        let grid = closure_grid(&mesh.positions);
        let mut directed = HashMap::new();
        for tri in &mesh.triangles {
            let [a, b, c] = tri.map(|i| grid_key(mesh.positions[i as usize], grid));
            for edge in [(a, b), (b, c), (c, a)].into_iter().filter(|(p, q)| p != q) {
                *directed.entry(edge).or_insert(0u32) += 1;
            }
        }
        !directed.is_empty()
            && directed.iter().all(|(&(p, q), &n)| n == 1 && directed.get(&(q, p)) == Some(&1))
    }

    /// A UV sphere as generators write it: the seam's column and each
    /// pole's fan of corners duplicated, every corner computed from its
    /// angles (so the south pole's corners lie about 1.2e-16 apart, sin π
    /// not being 0), plus `offset` added to the first south-pole corner.
    fn generated_sphere(offset: Vec3) -> Mesh {
        let (stacks, slices) = (6u32, 12u32);
        let cols = slices + 1;
        let mut positions = Vec::new();
        for i in 0..=stacks {
            let phi = std::f64::consts::PI * f64::from(i) / f64::from(stacks);
            for j in 0..=slices {
                let theta = std::f64::consts::TAU * f64::from(j % slices) / f64::from(slices);
                let p = glam::DVec3::new(phi.sin() * theta.cos(), phi.cos(), -phi.sin() * theta.sin());
                positions.push(p.as_vec3());
            }
        }
        positions[(stacks * cols) as usize] += offset;
        let mut triangles = Vec::new();
        for i in 0..stacks {
            for j in 0..slices {
                let (a, d) = (i * cols + j, i * cols + j + 1);
                let (b, c) = (a + cols, d + cols);
                if i != 0 {
                    triangles.push([a, b, d]);
                }
                if i != stacks - 1 {
                    triangles.push([b, c, d]);
                }
            }
        }
        Mesh::new("generated", positions, None, triangles, Material::default()).unwrap()
    }

    #[test]
    fn corners_apart_by_rounding_close_a_mesh_and_a_real_gap_does_not() {
        let sphere = generated_sphere(Vec3::ZERO);
        let south: Vec<Vec3> = sphere.positions[sphere.positions.len() - 13..].to_vec();
        assert!(south.iter().any(|&p| p != south[0]), "the fan's corners differ: {south:?}");
        assert!(sphere.is_closed(), "corners 1e-16 apart are one point");
        assert!(closed_by_hashing(&sphere));
        // Beyond the tolerance (2 × 2⁻²⁰ of the extent 2), the gap is real.
        let step = (2.0 * CLOSURE_TOLERANCE) as f32;
        assert!(!generated_sphere(Vec3::new(4.0 * step, 0.0, 0.0)).is_closed());
        assert!(generated_sphere(Vec3::new(0.25 * step, 0.0, 0.0)).is_closed());
        // Far from the origin, the grid follows the bounds, not the origin.
        let mut far = generated_sphere(Vec3::ZERO);
        far.positions.iter_mut().for_each(|p| *p += Vec3::splat(1.0e4));
        assert!(far.is_closed(), "only positions equal once moved: still closed");
    }

    /// The grid follows the mesh's size: a closed tetrahedron is closed at
    /// 1e-30 and at 1e30 (where the step is far above 1, and far below),
    /// and without one face it is open at every scale; a mesh of one point
    /// has no edge and is not closed.
    #[test]
    fn closedness_holds_at_every_scale() {
        let corners = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
        let faces = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        for scale in [1.0e-30f32, 1.0e-3, 1.0, 1.0e3, 1.0e30] {
            let positions: Vec<Vec3> = corners.iter().map(|&c| c * scale).collect();
            let closed = Mesh::new("t", positions.clone(), None, faces.clone(), Material::default()).unwrap();
            assert!(closed.is_closed(), "scale {scale}");
            let open = Mesh::new("t", positions, None, faces[..3].to_vec(), Material::default()).unwrap();
            assert!(!open.is_closed(), "scale {scale}");
        }
        let point = Mesh::new("p", vec![Vec3::ONE; 3], None, vec![[0, 1, 2]], Material::default()).unwrap();
        assert!(!point.is_closed());
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]
        /// Random triangle lists over a few positions (some repeated, −0.0
        /// among them), made mostly of a tetrahedron's faces so that closed
        /// meshes occur: sorting agrees with hashing.
        #[test]
        fn closedness_matches_hashing(
            picks in proptest::collection::vec(0usize..6, 0..8),
            extra in proptest::collection::vec([0u32..7, 0u32..7, 0u32..7], 0..3),
        ) {
            let positions = vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(0.0, 1.0, 0.0),
                Vec3::new(0.0, 0.0, 1.0),
                Vec3::new(-0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(0.0, 0.0, 1.0),
            ];
            let faces = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3], [4, 5, 6], [4, 2, 5]];
            let mut triangles: Vec<[u32; 3]> = picks.iter().map(|&k| faces[k]).collect();
            triangles.extend(extra);
            let mesh = Mesh::new("t", positions, None, triangles, Material::default()).unwrap();
            proptest::prop_assert_eq!(mesh.is_closed(), closed_by_hashing(&mesh));
        }
    }
}
