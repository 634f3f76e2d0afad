//! The vertex stage: object space → eye and clip space (SPEC §1, §6).
//!
//! Positions go to eye space (for lighting and fog) and clip space (for
//! clipping and the divide); normals go through the inverse transpose of
//! eye_from_object and are normalized here, before any interpolation. For
//! Gouraud objects without texture or vertex colours the lighting model is
//! evaluated at every vertex now (clamped or not, as the scene's
//! [`GouraudClamp`] says) ([`VertexLighting`] says where each
//! object is lit). Output: [`ClipVertex`]es with their outcodes and, when
//! they need no clipping, their [`Projected`] window positions; or, for an
//! object that setup builds in lanes, the compact records of [`compact`].

use glam::{Mat3, Mat4, Vec3, Vec4};
use rayon::prelude::*;
use zline_raster::FixedPoint;
use zline_scene::{GouraudClamp, Mesh};
use zline_shading::{PreparedLights, PreparedMaterial, ShadingMode, Vec3x8};
use zline_simd::lanes::{f32x8, i32x8, Level};

use crate::volume::{view_code, view_codes_x8, ClipVolume};

pub mod compact;

pub use compact::{CompactVertices, ScreenVertex, ValueLayout};

/// The most vertices per rayon task: big enough that scheduling costs
/// nothing.
const VERTEX_CHUNK: usize = 4096;

/// The fewest vertices per rayon task a big pool cuts a mesh into.
const MIN_VERTEX_CHUNK: usize = 512;

/// Vertices per rayon task for a mesh of `n` vertices ([`crate::tasks::task_len`]:
/// fewer than [`VERTEX_CHUNK`] when that would leave threads idle; the
/// 35k-vertex bunny was 9 tasks for 16 threads), a multiple of 8 so that
/// only the mesh's last group of eight lanes is partial. A vertex's record
/// does not depend on the chunks.
fn vertex_chunk(n: usize) -> usize {
    crate::tasks::task_len(n, (MIN_VERTEX_CHUNK, VERTEX_CHUNK)).next_multiple_of(8)
}

/// Window size in pixels (samples when supersampling).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Viewport {
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
}

/// A vertex after the divide and the window mapping (SPEC §1).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Projected {
    /// Window position snapped to the 1/256 grid.
    pub fixed: FixedPoint,
    /// NC depth z/w.
    pub z: f64,
    /// 1/w.
    pub inv_w: f32,
}

impl Projected {
    /// Divides by w and maps to the window. `None` when w ≤ 0 or NaN (never
    /// divided) or the position cannot be snapped.
    #[inline]
    pub fn new(clip: Vec4, viewport: Viewport) -> Option<Projected> {
        let cw = f64::from(clip.w);
        if cw.is_nan() || cw <= 0.0 {
            return None;
        }
        let q = [f64::from(clip.x) / cw, f64::from(clip.y) / cw, f64::from(clip.z) / cw, 1.0 / cw];
        Projected::from_quotients(q, viewport)
    }

    /// The window mapping of x/w, y/w, z/w and 1/w (in f64, w > 0).
    #[inline(always)]
    fn from_quotients(q @ [_, _, z, inv_w]: [f64; 4], viewport: Viewport) -> Option<Projected> {
        let (x, y) = window(q, viewport);
        Some(Projected { fixed: FixedPoint::snap(x, y)?, z, inv_w: inv_w as f32 })
    }
}

/// The window position (in pixels, y down) of quotients x/w, y/w: the
/// viewport map in f64, rounded to f32 for the snap.
#[inline(always)]
fn window([x, y, ..]: [f64; 4], viewport: Viewport) -> (f32, f32) {
    let (w, h) = (f64::from(viewport.width), f64::from(viewport.height));
    (((x + 1.0) * 0.5 * w) as f32, ((1.0 - y) * 0.5 * h) as f32)
}

/// Where an object's vertices are lit — the one place that decides it
/// ([`VertexLighting::choose`]); the vertex stage and setup both follow
/// the choice, and it says what [`ClipVertex::color`] holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VertexLighting {
    /// Not lit per vertex (flat and Phong shading light later): `color` is
    /// the mesh's vertex colour, or zero for meshes without colours.
    Unlit,
    /// Gouraud without texture or vertex colours, lit by the vertex stage,
    /// eight vertices at a time: `color` is the lit colour, clamped to
    /// [0, 1] per vertex ([`GouraudClamp::PerVertex`], the reading of
    /// fixed-function GL), or the unclamped sum ambient + diffuse +
    /// specular that the kernel clamps per sample
    /// ([`GouraudClamp::PerSample`]).
    VertexStage,
    /// Gouraud with a texture or vertex colours, lit by setup on the
    /// original vertices before clipping (so clipped vertices interpolate
    /// lit values, SPEC §2). Until then `color` is the vertex colour; after,
    /// untextured: `color` is the lit colour, clamped or not as for
    /// `VertexStage`; textured (whatever the [`GouraudClamp`]): `color` is
    /// the unclamped ambient+diffuse part and `normal` the specular part,
    /// which the textured kernel combines with the texel and clamps.
    Setup,
}

impl VertexLighting {
    /// The choice for an object drawn with `shading`, with or without a
    /// texture and vertex colours.
    pub fn choose(shading: ShadingMode, textured: bool, vertex_colors: bool) -> VertexLighting {
        match shading {
            ShadingMode::Gouraud if textured || vertex_colors => VertexLighting::Setup,
            ShadingMode::Gouraud => VertexLighting::VertexStage,
            ShadingMode::Flat | ShadingMode::Phong => VertexLighting::Unlit,
        }
    }
}

/// One transformed vertex; what `color` holds is stated by the object's
/// [`VertexLighting`]. The vertex stage also classifies it against the view
/// volume and the clipping planes and, when it needs no clipping, divides
/// and snaps it once here instead of once per triangle that uses it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ClipVertex {
    /// Clip-space position.
    pub clip: Vec4,
    /// Eye-space position.
    pub eye: Vec3,
    /// Unit eye-space normal (zero when the normal matrix is singular).
    pub normal: Vec3,
    /// The colour attribute: see [`VertexLighting`].
    pub color: Vec3,
    /// Texture coordinates (zero for meshes without them).
    pub uv: glam::Vec2,
    /// Eye-space tangent (xyz, not normalized) and handedness w = ±1, for
    /// meshes with a normal map (`zline_scene::NormalMap`, Phong only).
    /// On a Gouraud object lit by the vertex stage that draws both sides
    /// with two-sided lighting ([`VertexLights::turned`]), xyz is instead
    /// the colour lit with the normal turned, which setup gives a triangle
    /// seen from behind. Zero otherwise.
    pub tangent: Vec4,
    /// Window position, NC depth and 1/w; meaningful when `clip_code` is 0.
    pub projected: Projected,
    /// Outcode against the view volume (see [`view_code`]).
    pub view_code: u8,
    /// Outcode against the clipping planes ([`ClipVolume::clip_code`]),
    /// with [`NEEDS_SETUP`] when the vertex must be projected in setup.
    pub clip_code: u8,
}

/// A `clip_code` bit meaning "not projected by the vertex stage" (set on
/// vertices made by clipping).
pub const NEEDS_SETUP: u8 = 1 << 7;

impl ClipVertex {
    /// Linear interpolation of every field: a + t·(b − a) (SPEC §2: new
    /// vertices interpolate in clip space).
    #[inline]
    pub fn lerp(&self, other: &ClipVertex, t: f32) -> ClipVertex {
        ClipVertex {
            clip: self.clip.lerp(other.clip, t),
            eye: self.eye.lerp(other.eye, t),
            normal: self.normal.lerp(other.normal, t),
            color: self.color.lerp(other.color, t),
            uv: self.uv.lerp(other.uv, t),
            tangent: self.tangent.lerp(other.tangent, t),
            projected: Projected::default(),
            view_code: 0,
            clip_code: NEEDS_SETUP,
        }
    }
}

/// The matrices of one object for one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObjectTransforms {
    /// Projection · view · model.
    pub clip_from_object: Mat4,
    /// View · model.
    pub eye_from_object: Mat4,
    /// Inverse transpose of eye_from_object's linear part.
    pub normal_eye_from_object: Mat3,
}

impl ObjectTransforms {
    /// The matrices for a model matrix under a camera.
    pub fn new(clip_from_eye: Mat4, eye_from_world: Mat4, world_from_object: Mat4) -> ObjectTransforms {
        let eye_from_object = eye_from_world * world_from_object;
        ObjectTransforms {
            clip_from_object: clip_from_eye * eye_from_object,
            eye_from_object,
            normal_eye_from_object: Mat3::from_mat4(eye_from_object).inverse().transpose(),
        }
    }
}

/// Where the vertex stage puts vertices on the screen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Screen {
    /// The window.
    pub viewport: Viewport,
    /// The clipping planes.
    pub volume: ClipVolume,
}

/// The lights and material of an object whose vertices the vertex stage
/// lights ([`VertexLighting::VertexStage`]).
#[derive(Clone, Copy, Debug)]
pub struct VertexLights<'a> {
    /// The lighting model in eye space.
    pub lights: &'a PreparedLights,
    /// The object's material.
    pub material: &'a PreparedMaterial,
    /// Whether the lit colour is clamped here or per sample.
    pub clamp: GouraudClamp,
    /// Also light each vertex with its normal turned, into
    /// [`ClipVertex::tangent`]: for an object drawing both sides with
    /// two-sided lighting, whose triangles seen from behind would otherwise
    /// relight their vertices one triangle at a time in setup.
    pub turned: bool,
}

/// Transforms every vertex of `mesh` into `out` (resized), in parallel, and
/// lights them when `lighting` is given; the result is in vertex order
/// whatever the thread count.
pub fn transform_mesh(
    mesh: &Mesh,
    t: &ObjectTransforms,
    lighting: Option<VertexLights<'_>>,
    screen: &Screen,
    out: &mut Vec<ClipVertex>,
) {
    out.resize(mesh.positions.len(), ClipVertex::default());
    let size = vertex_chunk(out.len());
    out.par_chunks_mut(size).enumerate().for_each(|(chunk, out)| {
        let start = chunk * size;
        let positions = &mesh.positions[start..start + out.len()];
        let normals = &mesh.normals[start..start + out.len()];
        let records = Records::Full(&mut *out);
        zline_simd::vectorize(TransformVertices { out: records, positions, normals, t, screen, lighting });
        complete(out, start, (mesh, t), lighting.is_some());
    });
}

/// The mesh's own attributes of the records `out` (vertices `start..`),
/// after the transform: texture coordinates, eye-space tangents (unlit
/// objects with a normal map) and vertex colours.
fn complete(out: &mut [ClipVertex], start: usize, (mesh, t): (&Mesh, &ObjectTransforms), lit: bool) {
    let range = start..start + out.len();
    if let Some(uvs) = mesh.uvs.get(range.clone()) {
        for (v, &uv) in out.iter_mut().zip(uvs) {
            v.uv = uv;
        }
    }
    // Tangents are read only by Phong's perturbed kernel; on a Gouraud
    // object lit here `tangent` holds the turned colour instead.
    let tangents = mesh.normal_map.as_ref().and(mesh.tangents.get(range.clone()));
    if let (Some(tangents), false) = (tangents, lit) {
        transform_tangents(out, tangents, t);
    }
    // Lit vertices have no vertex colours (`VertexLighting::choose`).
    debug_assert!(!lit || mesh.colors.is_empty());
    if let Some(colors) = mesh.colors.get(range) {
        for (v, &c) in out.iter_mut().zip(colors) {
            v.color = c;
        }
    }
}

/// Tangents go to eye space by eye_from_object's linear part (they are
/// directions in the surface, not normals); a mirroring transform
/// (negative determinant) flips the handedness, so that B = w·(N × T) keeps
/// pointing along +t with the normals of the inverse transpose.
fn transform_tangents(out: &mut [ClipVertex], tangents: &[Vec4], t: &ObjectTransforms) {
    let linear = Mat3::from_mat4(t.eye_from_object);
    let mirror = if linear.determinant() < 0.0 { -1.0 } else { 1.0 };
    for (v, &tangent) in out.iter_mut().zip(tangents) {
        v.tangent = (linear * tangent.truncate()).extend(tangent.w * mirror);
    }
}

/// The vertex transform eight vertices at a time, a job of
/// [`zline_simd::vectorize`]: the three matrix products, the normal's
/// normalization and both outcodes in lanes, with glam's operations in
/// glam's order (no fused multiply-add), so that every vertex gets the bits
/// of its scalar twin [`transform_vertex`]; the divides by w in f64, all
/// eight lanes packed, and the snap of each vertex that needs no clipping.
/// Gouraud vertices lit here are lit from the same lanes ([`lit_x8`], see
/// `zline_shading::Vec3x8`), also with the normal turned when
/// [`VertexLights::turned`] asks.
struct TransformVertices<'a> {
    out: Records<'a>,
    positions: &'a [Vec3],
    normals: &'a [Vec3],
    t: &'a ObjectTransforms,
    screen: &'a Screen,
    lighting: Option<VertexLights<'a>>,
}

/// Where [`TransformVertices`] stores its vertices: whole records, or the
/// compact ones of an object set up in lanes ([`compact`]) — a run-time
/// choice made once per group of eight, not a second job.
enum Records<'a> {
    /// [`ClipVertex`]es.
    Full(&'a mut [ClipVertex]),
    /// [`ScreenVertex`]es and the values the layout names.
    Compact(&'a mut [ScreenVertex], &'a mut [f32], ValueLayout),
}

impl zline_simd::Vectorized for TransformVertices<'_> {
    type Output = ();

    #[inline(always)]
    fn run<S: Level>(self) {
        let TransformVertices { mut out, positions, normals, t, screen, lighting } = self;
        for (g, (p, n)) in positions.chunks(8).zip(normals.chunks(8)).enumerate() {
            let lanes = transform_group::<S>(p, n, (t, lighting.as_ref()), screen);
            let range = g * 8..g * 8 + p.len();
            match &mut out {
                Records::Full(out) => store_full(&lanes, &mut out[range]),
                Records::Compact(screen, values, layout) => {
                    let values = &mut values[range.start * layout.stride..range.end * layout.stride];
                    store_compact(&lanes, &mut screen[range], values, &*layout);
                }
            }
        }
    }
}

/// Eight vertices of [`TransformVertices`] in lanes, transposed: each
/// array's lane k is vertex k of the group.
struct GroupLanes {
    clip: [[f32; 8]; 4],
    eye: [[f32; 8]; 3],
    normal: [[f32; 8]; 3],
    color: [[f32; 8]; 3],
    turned: [[f32; 8]; 3],
    /// x/w, y/w, z/w, 1/w.
    quotients: [[f64; 4]; 8],
    fixed: ([i32; 8], [i32; 8]),
    /// Whether the lane could be snapped.
    snapped: [bool; 8],
    clip_codes: [u8; 8],
    view_codes: [u8; 8],
}

impl GroupLanes {
    /// Vertex k's window position, depth and outcodes, with
    /// [`NEEDS_SETUP`] when it must be projected in setup.
    #[inline(always)]
    fn screen(&self, k: usize) -> (Projected, u8, u8) {
        let projected = (self.clip_codes[k] == 0 && self.snapped[k]).then(|| Projected {
            fixed: FixedPoint { x: self.fixed.0[k], y: self.fixed.1[k] },
            z: self.quotients[k][2],
            inv_w: self.quotients[k][3] as f32,
        });
        let needs_setup = if projected.is_none() { NEEDS_SETUP } else { 0 };
        (projected.unwrap_or_default(), self.view_codes[k], self.clip_codes[k] | needs_setup)
    }
}

/// Lane k of three arrays as a vector.
#[inline(always)]
fn lane3(v: &[[f32; 8]; 3], k: usize) -> Vec3 {
    Vec3::new(v[0][k], v[1][k], v[2][k])
}

/// Stores a group as whole records.
#[inline(always)]
fn store_full(g: &GroupLanes, out: &mut [ClipVertex]) {
    for (k, v) in out.iter_mut().enumerate() {
        let (projected, view_code, clip_code) = g.screen(k);
        *v = ClipVertex {
            clip: Vec4::new(g.clip[0][k], g.clip[1][k], g.clip[2][k], g.clip[3][k]),
            eye: lane3(&g.eye, k),
            normal: lane3(&g.normal, k),
            color: lane3(&g.color, k),
            uv: glam::Vec2::ZERO,
            tangent: lane3(&g.turned, k).extend(0.0),
            projected,
            view_code,
            clip_code,
        };
    }
}

/// Up to eight vertices of [`TransformVertices`] (lanes past the end repeat
/// the last vertex and are not stored). Helpers are functions, not
/// closures: a closure left out of line would reach each lane operation
/// through a call.
#[inline(always)]
fn transform_group<S: Level>(
    p: &[Vec3],
    n: &[Vec3],
    (t, lighting): (&ObjectTransforms, Option<&VertexLights<'_>>),
    s: &Screen,
) -> GroupLanes {
    let p = [gather::<S>(p, 0), gather(p, 1), gather(p, 2)];
    let e = t.eye_from_object.to_cols_array_2d();
    let eye = [affine(&e, 0, &p), affine(&e, 1, &p), affine(&e, 2, &p)];
    let c = t.clip_from_object.to_cols_array_2d();
    let clip = [affine(&c, 0, &p), affine(&c, 1, &p), affine(&c, 2, &p), affine(&c, 3, &p)];
    // glam's Mat3 · n, then normalize_or_zero: n·(1/√((x² + y²) + z²)) when
    // that factor is finite and positive, else zero.
    let n = [gather::<S>(n, 0), gather(n, 1), gather(n, 2)];
    let m = t.normal_eye_from_object.to_cols_array_2d();
    let [mx, my, mz] = [linear(&m, 0, &n), linear(&m, 1, &n), linear(&m, 2, &n)];
    let rcp = f32x8::splat(1.0) / ((mx * mx + my * my) + mz * mz).sqrt();
    let unit = rcp.is_finite() & rcp.cmp_gt(f32x8::splat(0.0));
    let zero = f32x8::splat(0.0);
    let normal = [unit.blend(mx * rcp, zero), unit.blend(my * rcp, zero), unit.blend(mz * rcp, zero)];
    let (color, turned) = match lighting {
        None => ([zero; 3], [zero; 3]),
        Some(l) => {
            let eye = Vec3x8 { x: eye[0], y: eye[1], z: eye[2] };
            let n = Vec3x8 { x: normal[0], y: normal[1], z: normal[2] };
            // One lighting call in a loop over one or two normals, not two
            // inlined copies of the lighting model per level.
            let normals = [n, Vec3x8 { x: -n.x, y: -n.y, z: -n.z }];
            let mut lit = [Vec3x8::splat(Vec3::ZERO); 2];
            for (out, normal) in lit.iter_mut().zip(normals).take(1 + usize::from(l.turned)) {
                *out = lit_x8(l, eye, normal);
            }
            let [c, t] = lit;
            ([c.x, c.y, c.z], [t.x, t.y, t.z])
        }
    };
    let clip_codes = s.volume.clip_codes_x8(clip);
    let view_codes = view_codes_x8(clip);
    let clip = [clip[0].to_array(), clip[1].to_array(), clip[2].to_array(), clip[3].to_array()];
    // The divides of all eight lanes, branch-free so that they run packed
    // (each lane is IEEE division, the bits of `Projected::new`); only the
    // lanes that need no clipping are used.
    let quotients = divide_by_w(&clip);
    let (fixed_x, fixed_y, snapped) = snap_x8::<S>(&quotients, s.viewport);
    GroupLanes {
        clip,
        eye: [eye[0].to_array(), eye[1].to_array(), eye[2].to_array()],
        normal: [normal[0].to_array(), normal[1].to_array(), normal[2].to_array()],
        color: [color[0].to_array(), color[1].to_array(), color[2].to_array()],
        turned: [turned[0].to_array(), turned[1].to_array(), turned[2].to_array()],
        quotients,
        fixed: (fixed_x, fixed_y),
        snapped,
        clip_codes,
        view_codes,
    }
}

/// What [`CompactVertices::full`] rebuilds a record from.
#[derive(Clone, Copy, Debug)]
pub struct Source<'a> {
    /// The object's mesh.
    pub mesh: &'a Mesh,
    /// Its transforms.
    pub t: &'a ObjectTransforms,
    /// The screen.
    pub screen: &'a Screen,
}

impl CompactVertices {
    /// Vertex `i` (in range) as [`transform_mesh`] would have
    /// stored it, bit for bit.
    pub fn full(&self, i: usize, source: &Source<'_>) -> ClipVertex {
        let Source { mesh, t, screen } = *source;
        let mut v = transform_vertex(mesh.positions[i], mesh.normals[i], t, screen);
        // What the lanes stored (`store_full`), then what the mesh adds.
        if let Some(offset) = self.layout.color {
            v.color = self.value(i, offset);
        }
        if let Some(offset) = self.layout.turned {
            v.tangent = self.value(i, offset).extend(0.0);
        }
        complete(std::slice::from_mut(&mut v), i, (mesh, t), self.lit);
        v
    }
}

/// [`transform_mesh`] into compact records holding `layout`'s values
/// (a layout with a turned colour needs `lighting` with
/// [`VertexLights::turned`]).
pub fn transform_compact(
    mesh: &Mesh,
    t: &ObjectTransforms,
    lighting: Option<VertexLights<'_>>,
    screen: &Screen,
    layout: ValueLayout,
    out: &mut CompactVertices,
) {
    let n = mesh.positions.len();
    (out.layout, out.lit) = (layout, lighting.is_some());
    out.screen.resize(n, ScreenVertex::default());
    // As many value chunks as vertex chunks: with no values stored, one
    // unused float each.
    let size = vertex_chunk(n);
    let (len, chunk) = match layout.stride {
        0 => (n.div_ceil(size), 1),
        stride => (n * stride, size * stride),
    };
    out.values.resize(len, 0.0);
    let values = out.values.par_chunks_mut(chunk);
    out.screen.par_chunks_mut(size).zip(values).enumerate().for_each(|(chunk, (out, values))| {
        let start = chunk * size;
        let positions = &mesh.positions[start..start + out.len()];
        let normals = &mesh.normals[start..start + out.len()];
        let out = Records::Compact(out, values, layout);
        zline_simd::vectorize(TransformVertices { out, positions, normals, t, screen, lighting });
    });
}

/// Stores a group in compact records.
#[inline(always)]
fn store_compact(g: &GroupLanes, screen: &mut [ScreenVertex], values: &mut [f32], layout: &ValueLayout) {
    let stored = [
        (layout.color, &g.color),
        (layout.turned, &g.turned),
        (layout.normal, &g.normal),
        (layout.eye, &g.eye),
    ];
    for (k, s) in screen.iter_mut().enumerate() {
        let (p, view_code, clip_code) = g.screen(k);
        *s = ScreenVertex { fixed: p.fixed, z: p.z, inv_w: p.inv_w, view_code, clip_code };
        let v = &mut values[k * layout.stride..];
        for (offset, lanes) in stored {
            if let Some(o) = offset {
                v[o..o + 3].copy_from_slice(&[lanes[0][k], lanes[1][k], lanes[2][k]]);
            }
        }
    }
}

/// Eight vertices lit by the lighting model: exactly what
/// [`PreparedLights::shade`] gives, or the sum of
/// [`PreparedLights::shade_parts`] unclamped.
#[inline(always)]
fn lit_x8<S: Level>(l: &VertexLights<'_>, eye: Vec3x8<S>, normal: Vec3x8<S>) -> Vec3x8<S> {
    match l.clamp {
        GouraudClamp::PerVertex => l.lights.shade_x8(l.material, eye, normal),
        GouraudClamp::PerSample => {
            let (ambient_diffuse, specular) = l.lights.shade_parts_x8(l.material, eye, normal);
            ambient_diffuse + specular
        }
    }
}

/// The window positions of eight vertices from their quotients, snapped as
/// [`Projected::from_quotients`] snaps them ([`window`], then
/// `FixedPoint::snap`'s range test and ×256 rounded to nearest, halves
/// away from zero, by truncation and the fraction's side),
/// in lanes: fixed x, fixed y, and whether the lane could be snapped. The
/// scalar snap cost about 50 instructions a vertex, mostly `as i32`'s
/// saturating checks.
#[inline(always)]
fn snap_x8<S: Level>(q: &[[f64; 4]; 8], viewport: Viewport) -> ([i32; 8], [i32; 8], [bool; 8]) {
    let (mut wx, mut wy) = ([0.0f32; 8], [0.0f32; 8]);
    for k in 0..8 {
        (wx[k], wy[k]) = window(q[k], viewport);
    }
    let (x, y) = (f32x8::<S>::from(wx), f32x8::<S>::from(wy));
    let limit = f32x8::splat(zline_raster::MAX_WINDOW_COORD);
    // False for NaN, as `FixedPoint::snap`'s test.
    let ok = x.abs().cmp_le(limit) & y.abs().cmp_le(limit);
    let one = f32x8::splat(zline_raster::SUBPIXEL_ONE as f32);
    let (fx, fy) = (round_x8(x * one).to_array(), round_x8(y * one).to_array());
    let ok = as_int(ok).to_array().map(|m| m != 0);
    (fx, fy, ok)
}

/// A mask's lanes as integers (−1 where it holds, 0 elsewhere).
#[inline(always)]
fn as_int<S: Level>(mask: f32x8<S>) -> i32x8<S> {
    bytemuck::cast(mask)
}

/// `round_to_i32` of `FixedPoint::snap` in lanes: truncation, then one
/// step away from zero where the fraction is at least one half. Exact for
/// |v| ≤ 2^29 (the truncation cannot saturate, and v − t is exact).
#[inline(always)]
fn round_x8<S: Level>(v: f32x8<S>) -> i32x8<S> {
    let t = v.fast_trunc_int();
    let frac = v - f32x8::from_i32x8(t);
    let half = f32x8::splat(0.5);
    t - as_int(frac.cmp_ge(half)) + as_int(frac.cmp_le(-half))
}

/// x/w, y/w, z/w and 1/w of eight clip positions, in f64.
#[inline(always)]
fn divide_by_w(clip: &[[f32; 8]; 4]) -> [[f64; 4]; 8] {
    let w: [f64; 8] = clip[3].map(f64::from);
    let over_w = |c: usize| -> [f64; 8] { std::array::from_fn(|k| f64::from(clip[c][k]) / w[k]) };
    let (x, y, z) = (over_w(0), over_w(1), over_w(2));
    let inv: [f64; 8] = std::array::from_fn(|k| 1.0 / w[k]);
    std::array::from_fn(|k| [x[k], y[k], z[k], inv[k]])
}

/// Component `c` of up to eight vectors in lanes (the last repeated).
#[inline(always)]
fn gather<S: Level>(v: &[Vec3], c: usize) -> f32x8<S> {
    let last = v.len() - 1;
    let mut lanes = [0.0; 8];
    for (k, lane) in lanes.iter_mut().enumerate() {
        *lane = v[k.min(last)][c];
    }
    f32x8::from(lanes)
}

/// Row `row` of glam's Mat4 · point (the same as Mat4 · (p, 1)), columns
/// `m`: ((m0·x + m1·y) + m2·z) + m3.
#[inline(always)]
fn affine<S: Level>(m: &[[f32; 4]; 4], row: usize, [x, y, z]: &[f32x8<S>; 3]) -> f32x8<S> {
    let splat = |col: usize| f32x8::<S>::splat(m[col][row]);
    ((splat(0) * *x + splat(1) * *y) + splat(2) * *z) + splat(3)
}

/// Row `row` of glam's Mat3 · v, columns `m`: (m0·x + m1·y) + m2·z.
#[inline(always)]
fn linear<S: Level>(m: &[[f32; 3]; 3], row: usize, [x, y, z]: &[f32x8<S>; 3]) -> f32x8<S> {
    let splat = |col: usize| f32x8::<S>::splat(m[col][row]);
    (splat(0) * *x + splat(1) * *y) + splat(2) * *z
}

/// One vertex: the scalar twin of [`TransformVertices`], which the tests
/// hold it to bit for bit.
fn transform_vertex(p: Vec3, n: Vec3, t: &ObjectTransforms, s: &Screen) -> ClipVertex {
    let eye = t.eye_from_object.transform_point3(p);
    let normal = (t.normal_eye_from_object * n).normalize_or_zero();
    let clip = t.clip_from_object * p.extend(1.0);
    let mut clip_code = s.volume.clip_code(clip);
    let projected = if clip_code == 0 { Projected::new(clip, s.viewport) } else { None };
    if projected.is_none() {
        clip_code |= NEEDS_SETUP;
    }
    ClipVertex {
        clip,
        eye,
        normal,
        color: Vec3::ZERO,
        uv: glam::Vec2::ZERO,
        tangent: Vec4::ZERO,
        projected: projected.unwrap_or_default(),
        view_code: view_code(clip),
        clip_code,
    }
}

#[cfg(test)]
mod tests;
