//! The vertex stage: object space → eye and clip space (SPEC §1, §6).
//!
//! Positions go to eye space (for lighting and fog) and clip space (for
//! clipping and the divide); normals go through the inverse transpose of
//! eye_from_object and are normalized here, before any interpolation. For
//! Gouraud objects without texture or vertex colours the lighting model is
//! evaluated at every vertex now (clamped or not, as the scene's
//! [`GouraudClamp`] says) ([`VertexLighting`] says where each
//! object is lit). Output: [`ClipVertex`]es with their outcodes and, when
//! they need no clipping, their [`Projected`] window positions.

use glam::{Mat3, Mat4, Vec3, Vec4};
use rayon::prelude::*;
use zline_raster::FixedPoint;
use zline_scene::{GouraudClamp, Mesh};
use zline_shading::{PreparedLights, PreparedMaterial, ShadingMode, Vec3x8};
use zline_simd::lanes::{f32x8, i32x8, Level};

#[cfg(test)]
use crate::volume::view_code;
use crate::volume::{view_codes_x8, ClipVolume};

/// Vertices per rayon task: big enough that scheduling costs nothing.
const VERTEX_CHUNK: usize = 4096;

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
    out.par_chunks_mut(VERTEX_CHUNK).enumerate().for_each(|(chunk, out)| {
        let start = chunk * VERTEX_CHUNK;
        let positions = &mesh.positions[start..start + out.len()];
        let normals = &mesh.normals[start..start + out.len()];
        zline_simd::vectorize(TransformVertices { out: &mut *out, positions, normals, t, screen, lighting });
        if let Some(uvs) = mesh.uvs.get(start..start + out.len()) {
            for (v, &uv) in out.iter_mut().zip(uvs) {
                v.uv = uv;
            }
        }
        // Tangents are read only by Phong's perturbed kernel; on a Gouraud
        // object lit here `tangent` holds the turned colour instead.
        let tangents = mesh.normal_map.as_ref().and(mesh.tangents.get(start..start + out.len()));
        if let (Some(tangents), None) = (tangents, lighting) {
            transform_tangents(out, tangents, t);
        }
        // Lit vertices have no vertex colours (`VertexLighting::choose`).
        debug_assert!(lighting.is_none() || mesh.colors.is_empty());
        if let Some(colors) = mesh.colors.get(start..start + out.len()) {
            for (v, &c) in out.iter_mut().zip(colors) {
                v.color = c;
            }
        }
    });
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
    out: &'a mut [ClipVertex],
    positions: &'a [Vec3],
    normals: &'a [Vec3],
    t: &'a ObjectTransforms,
    screen: &'a Screen,
    lighting: Option<VertexLights<'a>>,
}

impl zline_simd::Vectorized for TransformVertices<'_> {
    type Output = ();

    #[inline(always)]
    fn run<S: Level>(self) {
        let TransformVertices { out, positions, normals, t, screen, lighting } = self;
        let groups = out.chunks_mut(8).zip(positions.chunks(8).zip(normals.chunks(8)));
        for (out, (p, n)) in groups {
            transform_group::<S>(out, p, n, (t, lighting.as_ref()), screen);
        }
    }
}

/// Up to eight vertices of [`TransformVertices`] (lanes past the end repeat
/// the last vertex and are not stored). Helpers are functions, not
/// closures: a closure left out of line would reach each lane operation
/// through a call.
#[inline(always)]
fn transform_group<S: Level>(
    out: &mut [ClipVertex],
    p: &[Vec3],
    n: &[Vec3],
    (t, lighting): (&ObjectTransforms, Option<&VertexLights<'_>>),
    s: &Screen,
) {
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
    let eye = [eye[0].to_array(), eye[1].to_array(), eye[2].to_array()];
    let normal = [normal[0].to_array(), normal[1].to_array(), normal[2].to_array()];
    let clip = [clip[0].to_array(), clip[1].to_array(), clip[2].to_array(), clip[3].to_array()];
    let color = [color[0].to_array(), color[1].to_array(), color[2].to_array()];
    let turned = [turned[0].to_array(), turned[1].to_array(), turned[2].to_array()];
    // The divides of all eight lanes, branch-free so that they run packed
    // (each lane is IEEE division, the bits of `Projected::new`); only the
    // lanes that need no clipping are used.
    let quotients = divide_by_w(&clip);
    let (fixed_x, fixed_y, snapped) = snap_x8::<S>(&quotients, s.viewport);
    for (k, v) in out.iter_mut().enumerate() {
        let clip = Vec4::new(clip[0][k], clip[1][k], clip[2][k], clip[3][k]);
        let mut clip_code = clip_codes[k];
        // `Projected::from_quotients`, its snap done in lanes.
        let projected = (clip_code == 0 && snapped[k]).then(|| Projected {
            fixed: FixedPoint { x: fixed_x[k], y: fixed_y[k] },
            z: quotients[k][2],
            inv_w: quotients[k][3] as f32,
        });
        if projected.is_none() {
            clip_code |= NEEDS_SETUP;
        }
        *v = ClipVertex {
            clip,
            eye: Vec3::new(eye[0][k], eye[1][k], eye[2][k]),
            normal: Vec3::new(normal[0][k], normal[1][k], normal[2][k]),
            color: Vec3::new(color[0][k], color[1][k], color[2][k]),
            uv: glam::Vec2::ZERO,
            tangent: Vec4::new(turned[0][k], turned[1][k], turned[2][k], 0.0),
            projected: projected.unwrap_or_default(),
            view_code: view_codes[k],
            clip_code,
        };
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
#[cfg(test)]
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
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn vec3() -> impl Strategy<Value = Vec3> {
        let c = prop_oneof![
            8 => -50.0f32..50.0,
            1 => Just(0.0f32),
            1 => -1e30f32..1e30,
            1 => prop_oneof![Just(f32::NAN), Just(f32::INFINITY), Just(-0.0f32), Just(1e-30f32)],
        ];
        (c.clone(), c.clone(), c).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    fn bits(v: &ClipVertex) -> Vec<u32> {
        let floats = [v.clip.to_array().as_slice(), &v.eye.to_array(), &v.normal.to_array()].concat();
        let p = v.projected;
        // A NaN's sign and payload are not specified by Rust or LLVM (which
        // may swap an addition's operands): every NaN compares as one.
        let mut out: Vec<u32> =
            floats.iter().map(|f| if f.is_nan() { u32::MAX } else { f.to_bits() }).collect();
        out.extend([
            p.fixed.x as u32,
            p.fixed.y as u32,
            p.inv_w.to_bits(),
            u32::from(v.view_code),
            u32::from(v.clip_code),
        ]);
        out.extend([p.z.to_bits() as u32, (p.z.to_bits() >> 32) as u32]);
        out
    }

    /// [`snap_x8`] at a level, as a job.
    struct Snap([[f64; 4]; 8], Viewport);

    impl zline_simd::Vectorized for Snap {
        type Output = ([i32; 8], [i32; 8], [bool; 8]);
        fn run<S: Level>(self) -> Self::Output {
            snap_x8::<S>(&self.0, self.1)
        }
    }

    /// The lanes' snap equals `Projected::from_quotients`' where rounding is decided
    /// by a half (±0.5 and ±1.5 fixed-point units, each side of zero),
    /// at the largest accepted coordinate and past it, and for NaN and
    /// infinities, at the CPU's level and at the baseline.
    #[test]
    fn the_lanes_snap_as_fixed_point_does() {
        let s = 1.0 / 256.0;
        let max = f64::from(zline_raster::MAX_WINDOW_COORD);
        let values = [
            0.0,
            0.5 * s,
            -0.5 * s,
            1.5 * s,
            -1.5 * s,
            2.5 * s,
            -2.5 * s,
            0.49 * s,
            -0.51 * s,
            1234.5 * s,
            -1234.5 * s,
            100.25,
            -77.75,
            max,
            -max,
            max + 1.0,
            -max - 1.0,
            max * 0.75 + 0.5 * s,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1.0e300,
        ];
        // With a 2 × 2 viewport the window map is x + 1 and 1 − y, so the
        // quotients v − 1 and 1 − v land on window coordinate v.
        let viewport = Viewport { width: 2, height: 2 };
        for (i, &vx) in values.iter().enumerate() {
            let mut q = [[0.0; 4]; 8];
            for (k, lane) in q.iter_mut().enumerate() {
                let vy = values[(i + 3 * k + 1) % values.len()];
                let vx = if k == 0 { vx } else { values[(i + k) % values.len()] };
                *lane = [vx - 1.0, 1.0 - vy, 0.5, 1.0];
            }
            let expected: Vec<Option<FixedPoint>> =
                q.iter().map(|&q| Projected::from_quotients(q, viewport).map(|p| p.fixed)).collect();
            for (fx, fy, ok) in [
                zline_simd::vectorize(Snap(q, viewport)),
                snap_x8::<zline_simd::lanes::Baseline>(&q, viewport),
            ] {
                let got: Vec<Option<FixedPoint>> =
                    (0..8).map(|k| ok[k].then_some(FixedPoint { x: fx[k], y: fy[k] })).collect();
                assert_eq!(got, expected, "quotients {q:?}");
            }
        }
    }

    proptest! {
        /// Every lane of the vectorized transform, at the level the CPU
        /// runs and at the baseline, equals the scalar twin bit for bit:
        /// inside, outside, behind the eye, degenerate and non-finite.
        #[test]
        fn the_lanes_equal_the_scalar_twin(
            vertices in proptest::collection::vec((vec3(), vec3()), 1..30),
            eye in vec3(),
            perspective in any::<bool>(),
        ) {
            let camera = zline_scene::Camera {
                eye: eye.clamp(Vec3::splat(-5.0), Vec3::splat(5.0)).map(|c| if c.is_nan() { 0.0 } else { c }),
                target: Vec3::new(0.1, 0.2, -1.0),
                up: Vec3::Y,
                projection: if perspective {
                    zline_scene::Projection::Perspective { fovy_degrees: 60.0, near: 0.5, far: 80.0 }
                } else {
                    zline_scene::Projection::Orthographic { height: 40.0, near: 0.5, far: 80.0 }
                },
            };
            let model = Mat4::from_scale_rotation_translation(
                Vec3::new(1.5, -0.75, 2.0),
                glam::Quat::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 0.7),
                Vec3::new(0.25, -3.0, 1.0),
            );
            let t = ObjectTransforms::new(camera.clip_from_eye(4.0 / 3.0), camera.eye_from_world(), model);
            let screen = Screen { viewport: Viewport { width: 320, height: 240 }, volume: ClipVolume::new(320, 240) };
            let (positions, normals): (Vec<Vec3>, Vec<Vec3>) = vertices.into_iter().unzip();
            let twin: Vec<Vec<u32>> =
                positions.iter().zip(&normals).map(|(&p, &n)| bits(&transform_vertex(p, n, &t, &screen))).collect();
            for baseline in [false, true] {
                let mut out = vec![ClipVertex::default(); positions.len()];
                let (positions, normals, screen) = (&positions, &normals, &screen);
                let job = TransformVertices { out: &mut out, positions, normals, t: &t, screen, lighting: None };
                if baseline {
                    zline_simd::vectorize_at::<zline_simd::lanes::Baseline, _>(job);
                } else {
                    zline_simd::vectorize(job);
                }
                let lanes: Vec<Vec<u32>> = out.iter().map(bits).collect();
                prop_assert_eq!(&lanes, &twin, "baseline: {}", baseline);
            }
            // Lit from the lanes: each colour is the scalar lighting model
            // at the vertex's own eye position and normal, clamped per
            // vertex or the unclamped sum.
            let model = zline_shading::LightingModel {
                ambient: Vec3::splat(0.1),
                lights: vec![
                    zline_shading::Light::Point {
                        position: Vec3::new(4.0, 4.0, 5.0),
                        color: Vec3::ONE,
                        attenuation: zline_shading::Attenuation::new(1.0, 0.01, 0.005),
                    },
                    zline_shading::Light::Directional { direction: Vec3::new(1.0, -0.5, -1.0), color: Vec3::new(0.25, 0.3, 0.6) },
                ],
                environment: None,
            };
            let lights = PreparedLights::new(&model, &Mat4::IDENTITY);
            let material = PreparedMaterial::new(zline_shading::Material { ks: Vec3::splat(0.6), ns: 40.0, ..Default::default() });
            for clamp in [GouraudClamp::PerVertex, GouraudClamp::PerSample] {
                let mut out = vec![ClipVertex::default(); positions.len()];
                let lighting = Some(VertexLights { lights: &lights, material: &material, clamp, turned: true });
                let (positions, normals, screen) = (&positions, &normals, &screen);
                zline_simd::vectorize(TransformVertices { out: &mut out, positions, normals, t: &t, screen, lighting });
                // A vertex at a non-finite position is outside every view
                // volume plane and never drawn; the scalar model returns
                // black there, the lanes a colour.
                // The turned colour (two-sided lighting) is the same model
                // with the normal negated.
                for v in out.iter().filter(|v| v.eye.is_finite()) {
                    let lit = |normal: Vec3| match clamp {
                        GouraudClamp::PerVertex => lights.shade(&material, v.eye, normal, Vec3::ZERO),
                        GouraudClamp::PerSample => {
                            let parts = lights.shade_parts(&material, v.eye, normal, Vec3::ZERO);
                            parts.ambient_diffuse + parts.specular
                        }
                    };
                    let canon = |c: Vec3| c.to_array().map(|f| if f.is_nan() { u32::MAX } else { f.to_bits() });
                    prop_assert_eq!(canon(v.color), canon(lit(v.normal)), "{:?} at {:?}, {:?}", clamp, v.eye, v.normal);
                    let turned = v.tangent.truncate();
                    prop_assert_eq!(canon(turned), canon(lit(-v.normal)), "turned {:?} at {:?}", clamp, v.eye);
                }
            }
        }
    }
}
