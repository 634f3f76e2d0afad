//! Triangle setup: clip-space triangles → [`Primitive`]s ready to scan
//! (SPEC §1–4, §6).
//!
//! Per triangle: drop non-finite input and triangles outside the view volume,
//! clip when needed, divide by w, map to the window (row 0 on top), snap to
//! the 1/256 grid, cull back faces by the exact sign of the snapped area,
//! and build the edge table and plane equations. Attribute planes hold a/w
//! and 1/w for perspective-correct interpolation or a itself for
//! screen-linear interpolation; the shading mode decides which attributes
//! exist at all, so a flat triangle carries none.

pub(crate) mod lanes;
mod primitive;

pub use primitive::{
    layout, AlphaUse, Draw, Flat, Gouraud, Kernel, KernelTables, LevelOfDetail, PassKind, Perturbed, Phong,
    Primitive, PrimitiveChunk, TexturedFlat, TexturedGouraud, TexturedLighting, TexturedPhong,
};

use glam::Vec3;
use zline_raster::{AttributePlanes, DepthPlane, EdgeTable, FixedPoint, PlaneBasis};
use zline_scene::{GouraudClamp, Interpolation, LightingSides};
use zline_shading::{LitParts, PreparedLights, PreparedMaterial, ShadingMode};

use crate::adaptive::{Adaptive, GouraudChoice, PhongChoice};
use crate::clip::{clip_polygon, MAX_CLIPPED};
use crate::vertex::{ClipVertex, Projected, VertexLighting, Viewport};
use crate::volume::ClipVolume;

/// What a primitive's depth plane holds (the scene's
/// [`zline_scene::DepthMode`]). Either way a smaller value is nearer and
/// the far plane maps to the buffer's clear value, so the tile compares
/// with one strict `<` in both modes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum DepthEncoding {
    /// NC depth z_nc = z_clip/w ∈ [−1, 1] (SPEC §4), cleared to 1.
    #[default]
    Normalized,
    /// Negated reversed depth d = −(w − z_clip)/(2w) = (z_nc − 1)/2 ∈
    /// [−1, 0], cleared to 0, computed in f64 from the eye-space depth
    /// alone: −(a·z_eye + b)/(2w) with the camera's (a, b)
    /// (`Camera::reversed_depth_coefficients`) and w = −z_eye (perspective)
    /// or 1 (orthographic). Far from the camera its magnitude is small,
    /// where floats are dense, so it keeps the relative precision of z_eye
    /// that NC depth (crowded near 1) loses; the negation only keeps the
    /// comparison the same.
    Reversed {
        /// a in w − z_clip = a·z_eye + b.
        a: f64,
        /// b in w − z_clip = a·z_eye + b.
        b: f64,
        /// w = −z_eye (true) or 1.
        perspective: bool,
    },
}

impl DepthEncoding {
    /// The value stored for a vertex at eye-space depth `eye_z` and NC
    /// depth `z`.
    #[inline]
    fn value(self, eye_z: f32, z: f64) -> f64 {
        match self {
            DepthEncoding::Normalized => z,
            DepthEncoding::Reversed { a, b, perspective } => {
                let z = f64::from(eye_z);
                let w = if perspective { -z } else { 1.0 };
                -(a * z + b) / (2.0 * w)
            }
        }
    }
}

/// Which faces an object draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Faces {
    /// Front faces only: back faces are culled.
    Front,
    /// Both sides; how a triangle seen from behind is lit is the frame's
    /// [`LightingSides`].
    Both,
}

/// Where the viewer is, for deciding which side of a triangle it sees.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Viewer {
    /// At the eye-space origin (perspective projection).
    AtOrigin,
    /// At infinity, looking along −z (orthographic projection).
    AlongMinusZ,
}

/// Whether a mesh has vertex colours: a factor on ka and kd like a texel,
/// applied by flat shading (their mean at the centroid), Gouraud shading
/// (lit in setup, per vertex) and Phong shading (interpolated like the
/// normal and multiplied per sample: [`Kernel::ColoredPhong`],
/// [`TexturedLighting::ColoredPhong`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VertexColors {
    /// No vertex colours.
    Absent,
    /// [`ClipVertex::color`] holds them until lighting.
    Present,
}

/// An object's texture as its kernels use it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TextureUse {
    /// Index into the frame's texture table.
    pub index: u32,
    /// How the level of detail is found (from the filter).
    pub lod: LevelOfDetail,
    /// What the texel's alpha does (from the alpha mode).
    pub alpha: AlphaUse,
}

/// An object's bump or normal map as its kernel uses it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalMapUse {
    /// Index into the frame's texture table.
    pub index: u32,
    /// What the map holds.
    pub encoding: zline_scene::NormalEncoding,
    /// Its scale k.
    pub scale: f32,
}

/// Everything setup needs to know about the object a triangle belongs to.
#[derive(Clone, Copy, Debug)]
pub struct SetupContext<'a> {
    /// The window.
    pub viewport: Viewport,
    /// The clipping planes.
    pub volume: ClipVolume,
    /// What depth planes hold.
    pub depth: DepthEncoding,
    /// The object's shading mode.
    pub shading: ShadingMode,
    /// Where the object's vertices are lit (Gouraud).
    pub vertex_lighting: VertexLighting,
    /// How attributes are interpolated.
    pub interpolation: Interpolation,
    /// Which faces are drawn.
    pub faces: Faces,
    /// How a triangle seen from behind is lit (when `faces` draws it).
    pub sides: LightingSides,
    /// Where untextured Gouraud clamps the lit colour: what
    /// [`ClipVertex::color`] holds once lit, and which kernel draws it.
    pub gouraud_clamp: GouraudClamp,
    /// Where the viewer is.
    pub viewer: Viewer,
    /// The object's material and its index in the frame's table.
    pub material: (&'a PreparedMaterial, u32),
    /// The eye-space lighting model (flat shading evaluates it here).
    pub lighting: &'a PreparedLights,
    /// The adaptive mode's data when it is on ([`crate::adaptive`]).
    pub adaptive: Option<&'a Adaptive>,
    /// The object's material without specular and its index in the
    /// frame's table (used by the adaptive mode; equal to `material` when
    /// off).
    pub diffuse_only: (&'a PreparedMaterial, u32),
    /// The object's diffuse texture, when it has one and texture
    /// coordinates.
    pub texture: Option<TextureUse>,
    /// Whether the mesh has vertex colours.
    pub vertex_colors: VertexColors,
    /// The object's bump or normal map, when it is drawn: Phong shading,
    /// texture coordinates and tangents, no vertex colours.
    pub normal_map: Option<NormalMapUse>,
    /// The normals frame: flat shading's colour is the encoded face
    /// normal (n + 1)/2, facing the viewer, instead of the lit colour.
    pub normals: bool,
}

impl SetupContext<'_> {
    /// Whether a triangle seen from behind is lit with its normals turned
    /// towards the viewer: back faces drawn, two-sided lighting.
    #[inline]
    pub fn turns_back_faces(&self) -> bool {
        self.faces == Faces::Both && self.sides == LightingSides::TwoSided
    }
}

/// Sets up one triangle (vertices in the mesh's order) and appends 0 or more
/// primitives to `out` (more than one only when clipping made a polygon).
///
/// The two tests that drop most triangles of a closed mesh run here,
/// inlined into the caller's loop: entirely outside one plane of the view
/// volume, and (culling, no clipping needed) a back face. The rest is
/// `setup_drawn`, out of line.
#[inline(always)]
pub fn setup_triangle(tri: [&ClipVertex; 3], ctx: &SetupContext<'_>, out: &mut PrimitiveChunk) {
    if tri[0].view_code & tri[1].view_code & tri[2].view_code != 0 {
        return; // entirely outside one plane of the view volume (NaN vertices included)
    }
    let projected = tri[0].clip_code | tri[1].clip_code | tri[2].clip_code == 0;
    if ctx.faces == Faces::Front && projected {
        let p = [tri[0].projected.fixed, tri[1].projected.fixed, tri[2].projected.fixed];
        if !is_front_facing(&p) {
            return; // culled before it is lit (SPEC §2)
        }
    }
    setup_drawn(tri, ctx, out);
}

/// [`setup_triangle`] past its first tests.
#[inline(never)]
fn setup_drawn(tri: [&ClipVertex; 3], ctx: &SetupContext<'_>, out: &mut PrimitiveChunk) {
    // Two-sided lighting (the default): a triangle seen from behind
    // (possible only when culling is off) is lit with its normals turned
    // towards the viewer, as OpenGL's two-sided lighting model and glTF's
    // doubleSided do. One-sided lighting keeps the normals as given, so the
    // far side of an open mesh is lit as if the viewer stood behind it.
    let flipped: [ClipVertex; 3];
    let back = ctx.turns_back_faces() && seen_from_behind([tri[0].eye, tri[1].eye, tri[2].eye], ctx.viewer);
    let tri = if back {
        flipped = tri.map(|v| turned(v, ctx));
        [&flipped[0], &flipped[1], &flipped[2]]
    } else {
        tri
    };
    // Gouraud lit here lights the original vertices before clipping, so
    // clipped vertices interpolate the lit values in clip space like every
    // attribute (SPEC §2, §6).
    let lit: [ClipVertex; 3];
    let tri = if ctx.vertex_lighting == VertexLighting::Setup {
        lit = tri.map(|v| lit_in_setup(v, ctx));
        [&lit[0], &lit[1], &lit[2]]
    } else {
        tri
    };
    // Flat shading lights the original triangle once, also when clipping
    // makes a fan of it.
    let flat = || match ctx.shading {
        ShadingMode::Flat => flat_parts(&tri, back, ctx),
        _ => LitParts::default(),
    };
    let code = tri[0].clip_code | tri[1].clip_code | tri[2].clip_code;
    if code == 0 {
        // The common case: projected once per vertex by the vertex stage.
        // Back faces are culled here already, before lighting and the call
        // (about half of a closed mesh's triangles).
        let p = [tri[0].projected, tri[1].projected, tri[2].projected];
        if drawn_side(&p, ctx) {
            emit(tri, p, flat(), ctx, out);
        }
        return;
    }
    let flat = flat();
    if !tri.iter().all(|v| v.clip.is_finite()) {
        return;
    }
    let mut poly = [ClipVertex::default(); MAX_CLIPPED];
    let n = clip_polygon(&ctx.volume, tri.map(|v| *v), code, &mut poly);
    for i in 1..n.saturating_sub(1) {
        let t = [&poly[0], &poly[i], &poly[i + 1]];
        let p = t.map(|v| Projected::new(v.clip, ctx.viewport));
        if let [Some(a), Some(b), Some(c)] = p {
            let p = [a, b, c];
            if drawn_side(&p, ctx) {
                emit(t, p, flat, ctx, out);
            }
        }
    }
}

/// SPEC §6 flat shading: the lighting model at the centroid of the original
/// triangle with its face normal (computed in f64 so huge coordinates do not
/// overflow), turned towards the viewer when `back` (two-sided lighting of
/// a triangle seen from behind).
fn flat_parts(tri: &[&ClipVertex; 3], back: bool, ctx: &SetupContext<'_>) -> LitParts {
    let p = tri.map(|v| v.eye.as_dvec3());
    let mut normal = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero().as_vec3();
    if back {
        normal = -normal;
    }
    if ctx.normals {
        let encoded = (normal + Vec3::ONE) * 0.5;
        return LitParts { ambient_diffuse: encoded, specular: Vec3::ZERO };
    }
    let centroid = ((p[0] + p[1] + p[2]) / 3.0).as_vec3();
    let mut parts = ctx.lighting.shade_parts(ctx.material.0, centroid, normal, Vec3::ZERO);
    if ctx.vertex_colors == VertexColors::Present {
        parts.ambient_diffuse *= (tri[0].color + tri[1].color + tri[2].color) / 3.0;
    }
    parts
}

/// A vertex of a Gouraud triangle lit in setup ([`VertexLighting::Setup`]):
/// the ambient+diffuse part multiplied by the vertex colour when the mesh
/// has them; untextured, `color` becomes the lit colour ([`lit_color`]:
/// clamped or not); textured, `color` and `normal` carry the unclamped
/// ambient+diffuse and specular parts (the normal is not needed once lit).
fn lit_in_setup(v: &ClipVertex, ctx: &SetupContext<'_>) -> ClipVertex {
    let mut parts = ctx.lighting.shade_parts(ctx.material.0, v.eye, v.normal, Vec3::ZERO);
    if ctx.vertex_colors == VertexColors::Present {
        parts.ambient_diffuse *= v.color;
    }
    if ctx.texture.is_some() {
        ClipVertex { color: parts.ambient_diffuse, normal: parts.specular, ..*v }
    } else {
        ClipVertex { color: lit_color(parts, ctx.gouraud_clamp, ctx.lighting.ceiling()), ..*v }
    }
}

/// An untextured Gouraud vertex's colour attribute: the lit colour clamped
/// to [0, 1] ([`GouraudClamp::PerVertex`]), or the unclamped sum that the
/// kernel clamps per sample ([`GouraudClamp::PerSample`]).
#[inline]
fn lit_color(parts: LitParts, clamp: GouraudClamp, ceiling: f32) -> Vec3 {
    match clamp {
        GouraudClamp::PerVertex => parts.color_below(ceiling),
        GouraudClamp::PerSample => parts.ambient_diffuse + parts.specular,
    }
}

/// True when the triangle's front (counter-clockwise) side faces away from
/// the viewer, decided in eye space on the original triangle.
#[inline]
fn seen_from_behind(eye: [Vec3; 3], viewer: Viewer) -> bool {
    // Not `eye.map`: some builds left that out of line in setup's lanes.
    let p = [eye[0].as_dvec3(), eye[1].as_dvec3(), eye[2].as_dvec3()];
    let normal = (p[1] - p[0]).cross(p[2] - p[0]);
    let to_viewer = match viewer {
        Viewer::AlongMinusZ => glam::DVec3::Z,
        Viewer::AtOrigin => -p[0],
    };
    normal.dot(to_viewer) < 0.0
}

/// A vertex with its normal turned around, and the colour the vertex stage
/// lit with that normal when it lit the vertex ([`ClipVertex::tangent`]).
#[inline]
fn turned(v: &ClipVertex, ctx: &SetupContext<'_>) -> ClipVertex {
    let normal = -v.normal;
    // The whole tangent frame turns: T and w negated keep B = w·(N × T)
    // negated too, so the perturbed normal is the front one negated.
    let tangent = -v.tangent;
    let color = match ctx.vertex_lighting {
        VertexLighting::VertexStage => v.tangent.truncate(),
        VertexLighting::Unlit | VertexLighting::Setup => v.color,
    };
    ClipVertex { normal, color, tangent, ..*v }
}

/// What the adaptive mode ([`crate::adaptive`]) decided for one triangle.
#[derive(Clone, Copy, Debug)]
struct Shortcuts {
    interpolation: Interpolation,
    /// The material drawn (its index in the frame's table).
    material: u32,
    lighting: Shortcut,
}

/// The adaptive mode's lighting shortcut for one triangle.
#[derive(Clone, Copy, Debug)]
enum Shortcut {
    /// The full evaluation.
    None,
    /// Gouraud drawn flat with this colour.
    Flat(Vec3),
    /// Phong lit once at the centroid with these parts.
    LitOnce(LitParts),
}

/// The adaptive mode's choice for one triangle ([`crate::adaptive`]).
#[inline(never)]
fn adaptive_shortcuts(
    adaptive: &Adaptive,
    tri: [&ClipVertex; 3],
    p: &[Projected; 3],
    ctx: &SetupContext<'_>,
) -> Shortcuts {
    let mut s =
        Shortcuts { interpolation: ctx.interpolation, material: ctx.material.1, lighting: Shortcut::None };
    match (ctx.shading, ctx.texture) {
        (ShadingMode::Gouraud, None) => {
            let perspective = ctx.interpolation == Interpolation::PerspectiveCorrect;
            match adaptive.gouraud(tri.map(|v| v.color), p.map(|v| v.inv_w), perspective) {
                // With GouraudClamp::PerSample the vertex colours, and so
                // their midpoint, are unclamped, and the flat kernel does
                // not clamp (a no-op for colours clamped at the vertices).
                GouraudChoice::Flat(c) => s.lighting = Shortcut::Flat(c.clamp(Vec3::ZERO, Vec3::ONE)),
                GouraudChoice::Linear => s.interpolation = Interpolation::ScreenLinear,
                GouraudChoice::Full => {}
            }
        }
        // The Phong shortcuts' bounds are the basic model's (SPEC §5.1):
        // Cook–Torrance surfaces keep the full evaluation.
        (ShadingMode::Phong, _) if ctx.material.0.microfacet.is_none() => {
            let m = &ctx.material.0.material;
            let (kd, ks, eye) = (m.kd.max_element(), m.ks.max_element(), tri.map(|v| v.eye));
            let normal = (ctx.vertex_colors == VertexColors::Absent).then(|| tri.map(|v| v.normal));
            match adaptive.phong(kd, ks, normal, eye) {
                PhongChoice::LitOnce => {
                    let normal = (tri[0].normal.normalize_or_zero()
                        + tri[1].normal.normalize_or_zero()
                        + tri[2].normal.normalize_or_zero())
                    .normalize_or_zero();
                    let centroid = (eye[0] + eye[1] + eye[2]) / 3.0;
                    let parts = ctx.lighting.shade_parts(ctx.diffuse_only.0, centroid, normal, Vec3::ZERO);
                    s.lighting = Shortcut::LitOnce(parts);
                }
                PhongChoice::NoSpecular if ctx.material.0.specular => s.material = ctx.diffuse_only.1,
                PhongChoice::NoSpecular | PhongChoice::Full => {}
            }
        }
        _ => {}
    }
    s
}

/// False for a back face of an object that culls them (SPEC §2): decided
/// before a triangle is lit or its planes are built.
#[inline]
fn drawn_side(p: &[Projected; 3], ctx: &SetupContext<'_>) -> bool {
    ctx.faces == Faces::Both || is_front_facing(&p.map(|v| v.fixed))
}

/// Builds the edge table and planes of one projected triangle that
/// survived culling, and appends it to the table of the kernel that will
/// draw it: a perturbed, untextured or textured kernel (`emit_perturbed`,
/// `emit_untextured`, `emit_textured`).
#[inline]
fn emit(
    tri: [&ClipVertex; 3],
    p: [Projected; 3],
    flat: LitParts,
    ctx: &SetupContext<'_>,
    out: &mut PrimitiveChunk,
) {
    let fixed = p.map(|v| v.fixed);
    let Some(edges) = EdgeTable::new(fixed) else {
        return;
    };
    // A triangle whose bounds hold no sample centre covers no sample (the
    // spans lie inside the bounds): no planes, no primitive. On a mesh of
    // triangles smaller than a pixel this is most of them.
    if edges.bounds().is_empty() {
        return;
    }
    let Some(basis) = PlaneBasis::new(fixed) else {
        return;
    };
    let depth = DepthPlane::new(&basis, std::array::from_fn(|k| ctx.depth.value(tri[k].eye.z, p[k].z)));
    let sc = match ctx.adaptive {
        None => {
            Shortcuts { interpolation: ctx.interpolation, material: ctx.material.1, lighting: Shortcut::None }
        }
        Some(adaptive) => adaptive_shortcuts(adaptive, tri, &p, ctx),
    };
    let q = match sc.interpolation {
        Interpolation::PerspectiveCorrect => p.map(|v| v.inv_w),
        Interpolation::ScreenLinear => [1.0; 3],
    };
    let (sort_depth, far_depth) = sort_keys([p[0].z, p[1].z, p[2].z]);
    let planes = Planes { tri, q, basis: &basis };
    let PrimitiveChunk { draws, bounds, tables, .. } = out;
    let mut push = Push { draws, bounds, edges, depth, depths: (sort_depth, far_depth) };
    match (ctx.normal_map, sc.lighting, ctx.texture) {
        (Some(map), Shortcut::None, _) => emit_perturbed(&planes, map, &sc, ctx, (tables, &mut push)),
        (_, _, None) => emit_untextured(&planes, flat, &sc, ctx, (tables, &mut push)),
        (_, _, Some(texture)) => emit_textured(&planes, (flat, texture), &sc, ctx, (tables, &mut push)),
    }
}

/// A draw's sort keys from its vertices' NC depths: the mean (the
/// transparency pass's back to front) and the largest (the painter's), in
/// f32.
#[inline(always)]
pub(crate) fn sort_keys(z: [f64; 3]) -> (f32, f32) {
    (((z[0] + z[1] + z[2]) / 3.0) as f32, z[0].max(z[1]).max(z[2]) as f32)
}

/// The three vertices (whole records, or compact ones) of a triangle;
/// `None` when an index is out of range (meshes are validated on load, but
/// a hand-built one may not be).
#[inline(always)]
pub(crate) fn gather<'a, V>(vertices: &'a [V], t: &[u32; 3]) -> Option<[&'a V; 3]> {
    Some([vertices.get(t[0] as usize)?, vertices.get(t[1] as usize)?, vertices.get(t[2] as usize)?])
}

/// What every primitive of one triangle shares, and the chunk's draw list
/// and bounds it is appended to.
struct Push<'a> {
    draws: &'a mut Vec<Draw>,
    bounds: &'a mut Vec<zline_raster::Rect>,
    edges: EdgeTable,
    depth: DepthPlane,
    depths: (f32, f32),
}

impl Push<'_> {
    /// Appends the triangle to `table` with `kernel` and `shader`.
    #[inline(always)]
    fn push<S>(&mut self, table: &mut Vec<Primitive<S>>, kernel: Kernel, shader: S) {
        let primitive = Primitive { edges: self.edges, depth: self.depth, shader };
        PrimitiveChunk::push((self.draws, self.bounds), table, kernel, primitive, self.depths);
    }
}

/// A bump- or normal-mapped triangle: Phong with the tangent frame.
#[inline(always)]
fn emit_perturbed(
    planes: &Planes<'_>,
    map: NormalMapUse,
    sc: &Shortcuts,
    ctx: &SetupContext<'_>,
    (t, push): (&mut KernelTables, &mut Push<'_>),
) {
    let planes = planes.textured(|v| {
        let tangent = v.tangent.truncate();
        [v.normal, v.eye, tangent, v.normal.cross(tangent) * v.tangent.w]
    });
    let kernel = Kernel::Perturbed {
        encoding: map.encoding,
        interpolation: sc.interpolation,
        texture: ctx.texture.map(|t| (t.lod, t.alpha)),
    };
    let texture = ctx.texture.map_or(0, |t| t.index);
    let shader = Perturbed { planes, material: sc.material, map: map.index, scale: map.scale, texture };
    push.push(&mut t.perturbed, kernel, shader);
}

/// An untextured triangle: only the attributes the shading mode needs.
#[inline(always)]
fn emit_untextured(
    planes: &Planes<'_>,
    flat: LitParts,
    sc: &Shortcuts,
    ctx: &SetupContext<'_>,
    (t, push): (&mut KernelTables, &mut Push<'_>),
) {
    let interpolation = sc.interpolation;
    match (ctx.shading, sc.lighting) {
        (_, Shortcut::Flat(color)) => push.push(&mut t.flat, Kernel::Flat, Flat { color }),
        (_, Shortcut::LitOnce(parts)) => {
            push.push(&mut t.flat, Kernel::Flat, Flat { color: parts.color_below(ctx.lighting.ceiling()) })
        }
        (ShadingMode::Flat, Shortcut::None) => {
            push.push(&mut t.flat, Kernel::Flat, Flat { color: flat.color_below(ctx.lighting.ceiling()) })
        }
        (ShadingMode::Gouraud, Shortcut::None) => {
            let planes = planes.build(|v| [v.color]);
            let kernel = Kernel::Gouraud { interpolation, clamp: ctx.gouraud_clamp };
            push.push(&mut t.gouraud, kernel, Gouraud { planes })
        }
        (ShadingMode::Phong, Shortcut::None) => match ctx.vertex_colors {
            VertexColors::Absent => {
                let planes = planes.build(|v| [v.normal, v.eye]);
                let shader = Phong { planes, material: sc.material };
                push.push(&mut t.phong, Kernel::Phong(interpolation), shader)
            }
            VertexColors::Present => {
                let planes = planes.build(|v| [v.normal, v.eye, v.color]);
                let shader = Phong { planes, material: sc.material };
                push.push(&mut t.colored_phong, Kernel::ColoredPhong(interpolation), shader)
            }
        },
    }
}

/// A textured triangle: texture coordinates plus what the lighting
/// interpolates. The adaptive mode's Phong lit once is drawn as textured
/// flat.
#[inline(always)]
fn emit_textured(
    planes: &Planes<'_>,
    (flat, texture): (LitParts, TextureUse),
    sc: &Shortcuts,
    ctx: &SetupContext<'_>,
    (t, push): (&mut KernelTables, &mut Push<'_>),
) {
    let (shading, flat) = match sc.lighting {
        Shortcut::LitOnce(parts) => (ShadingMode::Flat, parts),
        Shortcut::None | Shortcut::Flat(_) => (ctx.shading, flat),
    };
    let lighting = match (shading, ctx.vertex_colors) {
        (ShadingMode::Flat, _) => TexturedLighting::Flat,
        (ShadingMode::Gouraud, _) => TexturedLighting::Gouraud,
        (ShadingMode::Phong, VertexColors::Absent) => TexturedLighting::Phong,
        (ShadingMode::Phong, VertexColors::Present) => TexturedLighting::ColoredPhong,
    };
    let interpolation = sc.interpolation;
    let kernel = Kernel::Textured { lighting, interpolation, lod: texture.lod, alpha: texture.alpha };
    let (index, material) = (texture.index, sc.material);
    match lighting {
        TexturedLighting::Flat => {
            let planes = planes.textured(|_| []);
            let (ambient_diffuse, specular) = (flat.ambient_diffuse, flat.specular);
            let shader = TexturedFlat { planes, ambient_diffuse, specular, texture: index };
            push.push(&mut t.textured_flat, kernel, shader)
        }
        TexturedLighting::Gouraud => {
            // Lit before clipping: see `lit_in_setup`.
            let planes = planes.textured(|v| [v.color, v.normal]);
            push.push(&mut t.textured_gouraud, kernel, TexturedGouraud { planes, texture: index })
        }
        TexturedLighting::Phong => {
            let planes = planes.textured(|v| [v.normal, v.eye]);
            push.push(&mut t.textured_phong, kernel, TexturedPhong { planes, texture: index, material })
        }
        TexturedLighting::ColoredPhong => {
            let planes = planes.textured(|v| [v.normal, v.eye, v.color]);
            push.push(
                &mut t.textured_colored_phong,
                kernel,
                TexturedPhong { planes, texture: index, material },
            )
        }
    }
}

/// Builds attribute planes over one triangle: plane [`layout`]`::*::Q` is
/// q (1/w or 1), then each attribute times q.
struct Planes<'a> {
    tri: [&'a ClipVertex; 3],
    q: [f32; 3],
    basis: &'a PlaneBasis,
}

impl Planes<'_> {
    /// [q, then the triples `f` gives, each times q].
    #[inline(always)]
    fn build<const K: usize, const N: usize>(
        &self,
        f: impl Fn(&ClipVertex) -> [Vec3; K],
    ) -> AttributePlanes<N> {
        debug_assert_eq!(N, 1 + 3 * K);
        // Loops, not nested `from_fn`s: those stayed out of line, a call
        // per drawn triangle.
        let mut values = [[0.0; N]; 3];
        for (k, row) in values.iter_mut().enumerate() {
            let q = self.q[k];
            row[0] = q;
            for (j, triple) in f(self.tri[k]).iter().enumerate() {
                for c in 0..3 {
                    row[1 + 3 * j + c] = triple[c] * q;
                }
            }
        }
        AttributePlanes::new(self.basis, values)
    }

    /// [q, s·q, t·q, then the triples `f` gives, each times q].
    #[inline(always)]
    fn textured<const K: usize, const N: usize>(
        &self,
        f: impl Fn(&ClipVertex) -> [Vec3; K],
    ) -> AttributePlanes<N> {
        debug_assert_eq!(N, 3 + 3 * K);
        let mut values = [[0.0; N]; 3];
        for (k, row) in values.iter_mut().enumerate() {
            let q = self.q[k];
            let uv = self.tri[k].uv * q;
            (row[0], row[1], row[2]) = (q, uv.x, uv.y);
            for (j, triple) in f(self.tri[k]).iter().enumerate() {
                for c in 0..3 {
                    row[3 + 3 * j + c] = triple[c] * q;
                }
            }
        }
        AttributePlanes::new(self.basis, values)
    }
}

/// Front faces are counter-clockwise as seen by the viewer (SPEC §2). With
/// window y pointing down that is a negative cross product, decided exactly
/// on the snapped vertices.
#[inline]
pub fn is_front_facing(p: &[FixedPoint; 3]) -> bool {
    let xy = |q: FixedPoint| (i64::from(q.x), i64::from(q.y));
    let [a, b, c] = [xy(p[0]), xy(p[1]), xy(p[2])];
    (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0) < 0
}
