//! Setup vectorized across triangles: the common case — an untextured
//! Gouraud or Phong triangle needing no clipping — eight triangles at a
//! time ([`SetupTriangles`], a job of [`zline_simd::vectorize`]).
//!
//! Per group of eight: a scalar pass reads each triangle's three vertex
//! records once and makes the per-triangle decisions of [`setup_triangle`]
//! (view volume, clipping needed, back face, seen from behind), putting
//! the window positions, depths and attribute values of the triangles it
//! keeps into lanes; [`SetupLanes`] then builds the edge tables and every
//! plane's gradients in lanes, with the scalar operations in their order;
//! last, a scalar pass appends the primitives in mesh order, calling
//! [`setup_triangle`] itself for a triangle that needs clipping. So the
//! primitives, their order and their bits are exactly the scalar path's
//! (the tests hold the two to it).

use zline_raster::lanes::{Lanes, SetupLanes, TriangleLanes, SETUP_LANES};
use zline_raster::{AttributePlanes, DepthPlane, EdgeTable};
use zline_scene::Interpolation;
use zline_shading::ShadingMode;
use zline_simd::lanes::Level;

use super::{
    gather, is_front_facing, seen_from_behind, setup_triangle, sort_keys, DepthEncoding, Faces, Gouraud,
    Kernel, KernelTables, Phong, Primitive, PrimitiveChunk, SetupContext, VertexColors,
};
use crate::vertex::{CompactVertices, Source, ValueLayout, VertexLighting};

/// The kernels the lanes path sets up.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LanesKind {
    /// Untextured Gouraud lit by the vertex stage: the colour.
    Gouraud,
    /// Untextured Phong without vertex colours: the normal and the eye
    /// position.
    Phong,
}

impl LanesKind {
    /// The lanes path for an object, or `None` where only the scalar path
    /// sets it up: flat shading (lit per triangle), textures, vertex
    /// colours, maps, the adaptive mode, the normals frame, and the pixel
    /// inspector's triangle sources.
    pub(crate) fn choose(ctx: &SetupContext<'_>, sources: bool) -> Option<LanesKind> {
        let plain = !sources
            && ctx.adaptive.is_none()
            && ctx.texture.is_none()
            && ctx.normal_map.is_none()
            && !ctx.normals
            && ctx.vertex_colors == VertexColors::Absent;
        match (ctx.shading, ctx.vertex_lighting) {
            (ShadingMode::Gouraud, VertexLighting::VertexStage) if plain => Some(LanesKind::Gouraud),
            (ShadingMode::Phong, VertexLighting::Unlit) if plain => Some(LanesKind::Phong),
            _ => None,
        }
    }

    /// What the lanes read of each vertex besides its
    /// [`ScreenVertex`](crate::vertex::ScreenVertex):
    /// Gouraud the lit colour, the turned one when back faces are turned,
    /// and the eye position when back faces are turned (to decide which
    /// side is seen) or depth is reversed (computed from eye z); Phong the
    /// normal and the eye position.
    pub(crate) fn layout(self, ctx: &SetupContext<'_>) -> ValueLayout {
        let reversed = matches!(ctx.depth, DepthEncoding::Reversed { .. });
        match self {
            LanesKind::Gouraud => {
                let turns = ctx.turns_back_faces();
                ValueLayout::new([true, turns, false, turns || reversed])
            }
            LanesKind::Phong => ValueLayout::new([false, false, true, true]),
        }
    }
}

/// Sets up `triangles` (indices into `vertices`) into `out` as
/// [`setup_triangle`] would, one at a time, but eight at a time in lanes.
pub(crate) struct SetupTriangles<'a> {
    /// The object's transformed vertices, in the layout of
    /// [`LanesKind::layout`].
    pub(crate) vertices: &'a CompactVertices,
    /// What whole records are rebuilt from, for triangles that need
    /// clipping.
    pub(crate) source: Source<'a>,
    /// The triangles, in mesh order.
    pub(crate) triangles: &'a [[u32; 3]],
    /// The object.
    pub(crate) ctx: &'a SetupContext<'a>,
    /// What the object's primitives are ([`LanesKind::choose`]).
    pub(crate) kind: LanesKind,
    /// Where the primitives go.
    pub(crate) out: &'a mut PrimitiveChunk,
}

impl zline_simd::Vectorized for SetupTriangles<'_> {
    type Output = ();

    #[inline(always)]
    fn run<L: Level>(self) {
        let SetupTriangles { vertices, source, triangles, ctx, kind, out } = self;
        for group in triangles.chunks(SETUP_LANES) {
            match kind {
                LanesKind::Gouraud => setup_group::<GouraudLanes, 4>((vertices, &source), group, ctx, out),
                LanesKind::Phong => setup_group::<PhongLanes, 7>((vertices, &source), group, ctx, out),
            }
        }
    }
}

/// One kernel's planes and primitive, for [`setup_group`]: `N` planes, the
/// first q (1/w or 1), then the vertex values [`Self::values`] gives, each
/// times q.
trait LaneKernel<const N: usize> {
    /// What the kernel's table holds beside the edges and depth.
    type Shader;
    /// Planes 1.. of vertex `i` (its normal turned when `back`), before q.
    fn values(v: &CompactVertices, i: usize, back: bool) -> [f32; N];
    /// The kernel and the shader data of a primitive with `planes`.
    fn shader(ctx: &SetupContext<'_>, planes: AttributePlanes<N>) -> (Kernel, Self::Shader);
    /// The kernel's table.
    fn table(tables: &mut KernelTables) -> &mut Vec<Primitive<Self::Shader>>;
}

/// [`LanesKind::Gouraud`].
struct GouraudLanes;

impl LaneKernel<4> for GouraudLanes {
    type Shader = Gouraud;

    #[inline(always)]
    fn values(v: &CompactVertices, i: usize, back: bool) -> [f32; 4] {
        // Seen from behind: the colour the vertex stage lit with the normal
        // turned (`super::turned`).
        let layout = &v.layout;
        let offset = if back { layout.turned } else { layout.color };
        let c = v.value(i, offset.unwrap_or_default());
        [0.0, c.x, c.y, c.z]
    }

    #[inline(always)]
    fn shader(ctx: &SetupContext<'_>, planes: AttributePlanes<4>) -> (Kernel, Gouraud) {
        (Kernel::Gouraud { interpolation: ctx.interpolation, clamp: ctx.gouraud_clamp }, Gouraud { planes })
    }

    #[inline(always)]
    fn table(tables: &mut KernelTables) -> &mut Vec<Primitive<Gouraud>> {
        &mut tables.gouraud
    }
}

/// [`LanesKind::Phong`].
struct PhongLanes;

impl LaneKernel<7> for PhongLanes {
    type Shader = Phong<7>;

    #[inline(always)]
    fn values(v: &CompactVertices, i: usize, back: bool) -> [f32; 7] {
        let (n, eye) =
            (v.value(i, v.layout.normal.unwrap_or_default()), v.value(i, v.layout.eye.unwrap_or_default()));
        let n = if back { -n } else { n };
        [0.0, n.x, n.y, n.z, eye.x, eye.y, eye.z]
    }

    #[inline(always)]
    fn shader(ctx: &SetupContext<'_>, planes: AttributePlanes<7>) -> (Kernel, Phong<7>) {
        (Kernel::Phong(ctx.interpolation), Phong { planes, material: ctx.material.1 })
    }

    #[inline(always)]
    fn table(tables: &mut KernelTables) -> &mut Vec<Primitive<Phong<7>>> {
        &mut tables.phong
    }
}

/// What the first pass decided for one triangle of a group.
#[derive(Clone, Copy, Debug)]
enum Lane {
    /// No primitive (outside the view volume, culled, bad index).
    Skip,
    /// Needs clipping: [`setup_triangle`] sets these vertices up, rebuilt
    /// whole ([`CompactVertices::full`]).
    Scalar([usize; 3]),
    /// In the lanes.
    Lanes,
}

/// Up to eight triangles (see the module doc).
#[inline(always)]
fn setup_group<K: LaneKernel<N>, const N: usize>(
    (vertices, source): (&CompactVertices, &Source<'_>),
    group: &[[u32; 3]],
    ctx: &SetupContext<'_>,
    out: &mut PrimitiveChunk,
) {
    let mut lane = [Lane::Skip; SETUP_LANES];
    let mut any_lanes = false;
    let mut points = TriangleLanes::default();
    // Depth values, NC depths (the sort keys) and planes [q, values·q],
    // per vertex j and lane k.
    let mut depth = [[0.0f64; SETUP_LANES]; 3];
    let mut nc = [[0.0f64; SETUP_LANES]; 3];
    let mut planes = [[[0.0f32; SETUP_LANES]; 3]; N];
    let eye = |i: usize| vertices.value(i, vertices.layout.eye.unwrap_or_default());
    for (k, t) in group.iter().enumerate() {
        let Some(tri) = gather(&vertices.screen, t) else {
            continue;
        };
        let index = [t[0] as usize, t[1] as usize, t[2] as usize];
        if tri[0].view_code & tri[1].view_code & tri[2].view_code != 0 {
            continue; // entirely outside one plane of the view volume (NaN vertices included)
        }
        if tri[0].clip_code | tri[1].clip_code | tri[2].clip_code != 0 {
            lane[k] = Lane::Scalar(index);
            continue;
        }
        let fixed = [tri[0].fixed, tri[1].fixed, tri[2].fixed];
        if ctx.faces == Faces::Front && !is_front_facing(&fixed) {
            continue; // culled (SPEC §2)
        }
        let back = ctx.turns_back_faces()
            && seen_from_behind([eye(index[0]), eye(index[1]), eye(index[2])], ctx.viewer);
        (lane[k], any_lanes) = (Lane::Lanes, true);
        points.set(k, fixed);
        for (j, (v, &i)) in tri.iter().zip(&index).enumerate() {
            let eye_z = if vertices.layout.eye.is_some() { eye(i).z } else { 0.0 };
            depth[j][k] = ctx.depth.value(eye_z, v.z);
            nc[j][k] = v.z;
            let q = match ctx.interpolation {
                Interpolation::PerspectiveCorrect => v.inv_w,
                Interpolation::ScreenLinear => 1.0,
            };
            let values = K::values(vertices, i, back);
            planes[0][j][k] = q;
            for i in 1..N {
                planes[i][j][k] = values[i] * q;
            }
        }
    }
    let clipped = |index: [usize; 3], out: &mut PrimitiveChunk| {
        let tri = index.map(|i| vertices.full(i, source));
        setup_triangle([&tri[0], &tri[1], &tri[2]], ctx, out);
    };
    if !any_lanes {
        for l in lane {
            if let Lane::Scalar(index) = l {
                clipped(index, out);
            }
        }
        return;
    }
    let setup = SetupLanes::new(&points);
    let (dzdx, dzdy) = setup.gradients(&depth);
    let mut dx = [[0.0f32; SETUP_LANES]; N];
    let mut dy = [[0.0f32; SETUP_LANES]; N];
    for i in 0..N {
        (dx[i], dy[i]) = setup.attribute_gradients(&planes[i]);
    }
    let (sort, far) = sort_keys_x8(&nc);
    for (k, l) in lane.into_iter().enumerate() {
        match l {
            Lane::Skip => {}
            Lane::Scalar(index) => clipped(index, out),
            Lane::Lanes if setup.drawn(k) => {
                let edges: EdgeTable = setup.edge_table(k);
                let depth: DepthPlane = setup.depth_plane(k, depth[0][k], (dzdx[k], dzdy[k]));
                // Loops, not `from_fn`s (which a build may leave out of line).
                let (mut v0, mut d) = ([0.0; N], ([0.0; N], [0.0; N]));
                for i in 0..N {
                    (v0[i], d.0[i], d.1[i]) = (planes[i][0][k], dx[i][k], dy[i][k]);
                }
                let (kernel, shader) = K::shader(ctx, setup.attribute_planes(k, v0, d));
                let PrimitiveChunk { draws, bounds, tables, .. } = &mut *out;
                let primitive = Primitive { edges, depth, shader };
                PrimitiveChunk::push((draws, bounds), K::table(tables), kernel, primitive, (sort[k], far[k]));
            }
            Lane::Lanes => {}
        }
    }
}

/// Every lane's [`sort_keys`].
#[inline(always)]
fn sort_keys_x8(z: &[Lanes<f64>; 3]) -> (Lanes<f32>, Lanes<f32>) {
    let mut keys = ([0.0; SETUP_LANES], [0.0; SETUP_LANES]);
    for (k, ((&a, &b), &c)) in z[0].iter().zip(&z[1]).zip(&z[2]).enumerate() {
        (keys.0[k], keys.1[k]) = sort_keys([a, b, c]);
    }
    keys
}

#[cfg(test)]
mod tests {
    use glam::{Mat4, Vec3};
    use proptest::prelude::*;
    use zline_scene::{GouraudClamp, LightingSides, Material, Mesh};
    use zline_shading::{Attenuation, Light, LightingModel, PreparedLights, PreparedMaterial};

    use super::*;
    use crate::setup::{DepthEncoding, Viewer};
    use crate::vertex::{
        transform_compact, transform_mesh, ObjectTransforms, Screen, VertexLights, Viewport,
    };
    use crate::volume::ClipVolume;

    /// A chunk's primitives, bit for bit (`{:?}` prints every float's
    /// sign and NaN).
    fn bits(chunk: &PrimitiveChunk) -> String {
        let t = &chunk.tables;
        format!("{:?}\n{:?}\n{:?}\n{:?}", chunk.draws, chunk.bounds, t.gouraud, t.phong)
    }

    fn vec3(r: f32) -> impl Strategy<Value = Vec3> {
        (-r..r, -r..r, -r..r).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// Random meshes seen from random places — triangles in front,
        /// behind, across the near plane and the guard band, sub-pixel
        /// and degenerate, indices out of range — set up by the lanes and
        /// one at a time by `setup_triangle` give the same primitives.
        #[test]
        fn lanes_equal_setup_triangle(
            positions in prop::collection::vec(vec3(2.0), 3..40),
            normals in prop::collection::vec(vec3(1.0), 40),
            indices in prop::collection::vec(prop::array::uniform3(0u32..42), 1..60),
            eye in vec3(4.0),
            (phong, front_only, two_sided, linear, reversed, clamp) in
                (any::<bool>(), any::<bool>(), any::<bool>(), any::<bool>(), any::<bool>(), any::<bool>()),
            (width, height) in (1u32..400, 1u32..300),
        ) {
            let n = positions.len();
            let normals = Some(normals[..n].to_vec());
            let mut mesh = Mesh::new("random", positions, normals, vec![], Material::default()).unwrap();
            // Texture coordinates the kernels do not read, but clipping
            // carries: the rebuilt records must hold them too.
            mesh.uvs = mesh.normals.iter().map(|v| v.truncate()).collect();
            // Unchecked, as a hand-built mesh may be: some out of range.
            mesh.triangles = indices;
            let eye_from_world = Mat4::look_at_rh(eye, Vec3::ZERO, Vec3::Y);
            let clip_from_eye = Mat4::perspective_rh_gl(1.0, width as f32 / height as f32, 0.5, 20.0);
            let t = ObjectTransforms::new(clip_from_eye, eye_from_world, Mat4::IDENTITY);
            let model = LightingModel {
                ambient: Vec3::splat(0.1),
                lights: vec![Light::Point {
                    position: Vec3::new(3.0, 4.0, 5.0),
                    color: Vec3::ONE,
                    attenuation: Attenuation::new(1.0, 0.01, 0.0),
                }],
                environment: None,
            };
            let lights = PreparedLights::new(&model, &eye_from_world);
            let material = PreparedMaterial::new(Material::default());
            let faces = if front_only { Faces::Front } else { Faces::Both };
            let sides = if two_sided { LightingSides::TwoSided } else { LightingSides::OneSided };
            let viewport = Viewport { width, height };
            let volume = ClipVolume::new(width, height);
            let ctx = SetupContext {
                viewport,
                volume,
                depth: if reversed {
                    DepthEncoding::Reversed { a: 1.05, b: 1.1, perspective: true }
                } else {
                    DepthEncoding::Normalized
                },
                shading: if phong { ShadingMode::Phong } else { ShadingMode::Gouraud },
                vertex_lighting: if phong { VertexLighting::Unlit } else { VertexLighting::VertexStage },
                interpolation: if linear { Interpolation::ScreenLinear } else { Interpolation::PerspectiveCorrect },
                faces,
                sides,
                gouraud_clamp: if clamp { GouraudClamp::PerVertex } else { GouraudClamp::PerSample },
                viewer: Viewer::AtOrigin,
                material: (&material, 3),
                lighting: &lights,
                adaptive: None,
                diffuse_only: (&material, 3),
                texture: None,
                vertex_colors: VertexColors::Absent,
                normal_map: None,
                normals: false,
            };
            let lit = (!phong).then_some(VertexLights {
                lights: &lights,
                material: &material,
                clamp: ctx.gouraud_clamp,
                turned: ctx.turns_back_faces(),
            });
            let mut vertices = Vec::new();
            transform_mesh(&mesh, &t, lit, &Screen { viewport, volume }, &mut vertices);
            let kind = LanesKind::choose(&ctx, false);
            prop_assert_eq!(kind, Some(if phong { LanesKind::Phong } else { LanesKind::Gouraud }));
            prop_assert_eq!(LanesKind::choose(&ctx, true), None);

            let mut scalar = PrimitiveChunk::default();
            for tri in &mesh.triangles {
                if let Some(tri) = gather(&vertices, tri) {
                    setup_triangle(tri, &ctx, &mut scalar);
                }
            }
            // The lanes read compact records (whole ones rebuilt for clipping).
            let (kind, screen) = (kind.unwrap(), Screen { viewport, volume });
            let mut compact = CompactVertices::default();
            transform_compact(&mesh, &t, lit, &screen, kind.layout(&ctx), &mut compact);
            let source = Source { mesh: &mesh, t: &t, screen: &screen };
            for (i, whole) in vertices.iter().enumerate() {
                prop_assert_eq!(format!("{:?}", compact.full(i, &source)), format!("{whole:?}"));
            }
            let mut lanes = PrimitiveChunk::default();
            let (vertices, triangles) = (&compact, &mesh.triangles[..]);
            zline_simd::vectorize(SetupTriangles { vertices, source, triangles, ctx: &ctx, kind, out: &mut lanes });
            prop_assert_eq!(bits(&lanes), bits(&scalar));
        }
    }
}
