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

use glam::Vec3;
use zline_raster::{AttributePlanes, DepthPlane, EdgeTable, FixedPoint, PlaneBasis};
use zline_shading::{LitParts, PreparedLights, PreparedMaterial, ShadingMode};

use crate::adaptive::{Adaptive, GouraudChoice, PhongChoice};
use crate::bin::PrimitiveChunk;

use crate::clip::{clip_polygon, ClipVolume, MAX_CLIPPED};
use crate::vertex::ClipVertex;

/// Attributes of a Gouraud primitive: [1/w, r, g, b] (each over w when
/// perspective-correct; 1/w is then 1 in screen-linear mode).
pub type GouraudPlanes = AttributePlanes<4>;
/// Attributes of a Phong primitive: [1/w, normal xyz, eye position xyz].
pub type PhongPlanes = AttributePlanes<7>;
/// Attributes of a Phong primitive with vertex colours: [1/w, normal xyz,
/// eye position xyz, colour rgb] (each over w when perspective-correct).
pub type ColoredPhongAttributes = AttributePlanes<10>;

/// The planes and material of one untextured Phong primitive with vertex
/// colours, kept in the chunk's [`PrimitiveChunk::colored_phong`] so that
/// Phong primitives without colours stay at seven planes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ColoredPhongPlanes {
    /// The attributes.
    pub planes: ColoredPhongAttributes,
    /// Index into the frame's material table.
    pub material: u32,
}

/// How a primitive's samples get their colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shader {
    /// One colour for the whole triangle.
    Flat {
        /// The lit colour at the centroid.
        color: Vec3,
    },
    /// Interpolated vertex colours.
    Gouraud {
        /// Colour planes.
        planes: GouraudPlanes,
    },
    /// A textured primitive: its planes live in the chunk's
    /// [`PrimitiveChunk::textured`] (kept apart so untextured primitives
    /// stay small).
    Textured {
        /// Index into the chunk's textured planes.
        index: u32,
    },
    /// Lighting per sample.
    Phong {
        /// Normal and position planes.
        planes: PhongPlanes,
        /// Index into the frame's material table.
        material: u32,
    },
    /// Lighting per sample with interpolated vertex colours: its planes
    /// live in the chunk's [`PrimitiveChunk::colored_phong`].
    ColoredPhong {
        /// Index into the chunk's coloured Phong planes.
        index: u32,
    },
    /// A textured Phong primitive with vertex colours: its planes live in
    /// the chunk's [`PrimitiveChunk::textured_colored`] (textured flat and
    /// Gouraud primitives fold the colours into their lit parts in setup
    /// and use [`Shader::Textured`]).
    TexturedColored {
        /// Index into the chunk's textured and coloured planes.
        index: u32,
    },
}

/// A triangle ready for any tile: coverage, depth and shading.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Primitive {
    /// Coverage.
    pub edges: EdgeTable,
    /// Depth, as [`SetupContext::depth`] encodes it.
    pub depth: DepthPlane,
    /// Colour.
    pub shader: Shader,
    /// True when attribute planes hold a/w and 1/w.
    pub perspective: bool,
    /// Transparency kt = 1 − opacity (SPEC §9); 0 for opaque primitives.
    pub kt: f32,
    /// The mean NC depth of the vertices: the back-to-front sort key of the
    /// transparency pass.
    pub sort_depth: f32,
}

/// Attributes of a textured primitive: [1/w, s, t, then two triples] —
/// ambient+diffuse and specular parts (Gouraud) or normal and eye position
/// (Phong); each over w when perspective-correct.
pub type TexturedAttributes = AttributePlanes<9>;

/// Attributes of a textured Phong primitive with vertex colours: those of
/// [`TexturedAttributes`] (normal and eye position) followed by the colour
/// rgb, each over w when perspective-correct.
pub type TexturedColoredAttributes = AttributePlanes<12>;

/// How a textured primitive gets its lit parts (SPEC §7: the texel
/// modulates ka and kd, not ks: c = texel ⊙ (ambient+diffuse) + specular).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TexturedKind {
    /// Parts lit once at the centroid.
    Flat {
        /// Ambient + diffuse part.
        ambient_diffuse: Vec3,
        /// Specular part.
        specular: Vec3,
    },
    /// Parts lit at the vertices and interpolated separately.
    Gouraud,
    /// Parts lit per sample.
    Phong,
}

/// The planes and references of one textured primitive: nine planes
/// ([`TexturedAttributes`]), or twelve ([`TexturedColoredAttributes`],
/// always [`TexturedKind::Phong`]) for Phong with vertex colours.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexturedPlanes<const N: usize = 9> {
    /// How the lit parts come about.
    pub kind: TexturedKind,
    /// The attributes.
    pub planes: AttributePlanes<N>,
    /// Index into the frame's texture table.
    pub texture: u32,
    /// Index into the frame's material table.
    pub material: u32,
}

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
    /// The value stored for a vertex.
    #[inline]
    fn value(self, v: &ClipVertex, p: &Projected) -> f64 {
        match self {
            DepthEncoding::Normalized => p.z,
            DepthEncoding::Reversed { a, b, perspective } => {
                let z = f64::from(v.eye.z);
                let w = if perspective { -z } else { 1.0 };
                -(a * z + b) / (2.0 * w)
            }
        }
    }
}

/// Window size in pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Viewport {
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
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
    /// Perspective-correct (true) or screen-linear attributes.
    pub perspective: bool,
    /// Drop back faces.
    pub cull_back_faces: bool,
    /// The object's material and its index in the frame's table.
    pub material: (&'a PreparedMaterial, u32),
    /// The eye-space lighting model (flat shading evaluates it here).
    pub lighting: &'a PreparedLights,
    /// The adaptive mode's data when it is on ([`crate::adaptive`]).
    pub adaptive: Option<&'a Adaptive>,
    /// Index of the object's material without specular in the frame's
    /// table (used by the adaptive mode; equal to `material.1` when off).
    pub diffuse_only: (&'a PreparedMaterial, u32),
    /// The object's diffuse texture (index into the frame's table), when it
    /// has one and texture coordinates.
    pub texture: Option<u32>,
    /// True when the texture's alpha blends (the object is transparent even
    /// at opacity 1).
    pub blend_texture_alpha: bool,
    /// True for an orthographic projection (the viewer looks along −z
    /// everywhere), false for a perspective one (the viewer is at the origin).
    pub orthographic: bool,
    /// True when the mesh has vertex colours: [`ClipVertex::color`] holds
    /// them, a factor on ka and kd like a texel, applied by flat shading
    /// (their mean at the centroid), Gouraud shading (lit here in setup,
    /// per vertex) and Phong shading (interpolated like the normal and
    /// multiplied per sample: [`Shader::ColoredPhong`],
    /// [`Shader::TexturedColored`]).
    pub vertex_colors: bool,
}

/// Sets up one triangle (vertices in the mesh's order) and appends 0 or more
/// primitives to `out` (more than one only when clipping made a polygon).
pub fn setup_triangle(tri: [&ClipVertex; 3], ctx: &SetupContext<'_>, out: &mut PrimitiveChunk) {
    if tri[0].view_code & tri[1].view_code & tri[2].view_code != 0 {
        return; // entirely outside one plane of the view volume (NaN vertices included)
    }
    // Two-sided lighting: a triangle seen from behind (possible only when
    // culling is off) is lit with its normals turned towards the viewer, as
    // OpenGL's two-sided lighting model and glTF's doubleSided do; with
    // one-sided lighting the far side of an open mesh would be lit as if
    // the viewer stood behind it.
    let flipped: [ClipVertex; 3];
    let back = !ctx.cull_back_faces && seen_from_behind(&tri, ctx.orthographic);
    let tri = if back {
        flipped = tri.map(|v| turned(v, ctx));
        [&flipped[0], &flipped[1], &flipped[2]]
    } else {
        tri
    };
    // Gouraud lit here (textured, or with vertex colours) lights the
    // original vertices before clipping, so clipped vertices interpolate
    // the lit values in clip space like every attribute (SPEC §2, §6).
    let lit: [ClipVertex; 3];
    let tri = if ctx.shading == ShadingMode::Gouraud && (ctx.texture.is_some() || ctx.vertex_colors) {
        lit = tri.map(|v| lit_in_setup(v, ctx));
        [&lit[0], &lit[1], &lit[2]]
    } else {
        tri
    };
    let flat = match ctx.shading {
        ShadingMode::Flat => flat_parts(&tri, back, ctx),
        _ => LitParts::default(),
    };
    let code = tri[0].clip_code | tri[1].clip_code | tri[2].clip_code;
    if code == 0 {
        // The common case: projected once per vertex by the vertex stage.
        emit(tri, [tri[0].projected, tri[1].projected, tri[2].projected], flat, ctx, out);
        return;
    }
    if !tri.iter().all(|v| v.clip.is_finite()) {
        return;
    }
    let mut poly = [ClipVertex::default(); MAX_CLIPPED];
    let n = clip_polygon(&ctx.volume, tri.map(|v| *v), code, &mut poly);
    for i in 1..n.saturating_sub(1) {
        let t = [&poly[0], &poly[i], &poly[i + 1]];
        let p = t.map(|v| Projected::new(v.clip, ctx.viewport));
        if let [Some(a), Some(b), Some(c)] = p {
            emit(t, [a, b, c], flat, ctx, out);
        }
    }
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
    pub fn new(clip: glam::Vec4, viewport: Viewport) -> Option<Projected> {
        let cw = f64::from(clip.w);
        if cw.is_nan() || cw <= 0.0 {
            return None;
        }
        let (w, h) = (f64::from(viewport.width), f64::from(viewport.height));
        let (x, y) = (f64::from(clip.x) / cw, f64::from(clip.y) / cw);
        let fixed = FixedPoint::snap(((x + 1.0) * 0.5 * w) as f32, ((1.0 - y) * 0.5 * h) as f32)?;
        Some(Projected { fixed, z: f64::from(clip.z) / cw, inv_w: (1.0 / cw) as f32 })
    }
}

/// SPEC §6 flat shading: the lighting model at the centroid of the original
/// triangle with its face normal (computed in f64 so huge coordinates do not
/// overflow), turned towards the viewer when `back` (two-sided lighting).
fn flat_parts(tri: &[&ClipVertex; 3], back: bool, ctx: &SetupContext<'_>) -> LitParts {
    let p = tri.map(|v| v.eye.as_dvec3());
    let mut normal = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero().as_vec3();
    if back {
        normal = -normal;
    }
    let centroid = ((p[0] + p[1] + p[2]) / 3.0).as_vec3();
    let mut parts = ctx.lighting.shade_parts(ctx.material.0, centroid, normal, Vec3::ZERO);
    if ctx.vertex_colors {
        parts.ambient_diffuse *= (tri[0].color + tri[1].color + tri[2].color) / 3.0;
    }
    parts
}

/// The ambient+diffuse and specular parts at a vertex (Gouraud in setup),
/// the former multiplied by the vertex colour when the mesh has them.
#[inline]
fn vertex_parts(v: &ClipVertex, ctx: &SetupContext<'_>) -> LitParts {
    let mut parts = ctx.lighting.shade_parts(ctx.material.0, v.eye, v.normal, Vec3::ZERO);
    if ctx.vertex_colors {
        parts.ambient_diffuse *= v.color;
    }
    parts
}

/// A vertex of a Gouraud triangle lit in setup. Untextured: `color` becomes
/// the clamped lit colour, as the vertex stage makes it for meshes without
/// vertex colours. Textured: `color` and `normal` carry the unclamped
/// ambient+diffuse and specular parts (the normal is not needed once lit),
/// which the textured kernel combines with the texel and clamps.
fn lit_in_setup(v: &ClipVertex, ctx: &SetupContext<'_>) -> ClipVertex {
    let parts = vertex_parts(v, ctx);
    if ctx.texture.is_some() {
        ClipVertex { color: parts.ambient_diffuse, normal: parts.specular, ..*v }
    } else {
        ClipVertex { color: parts.color(), ..*v }
    }
}

/// True when the triangle's front (counter-clockwise) side faces away from
/// the viewer, decided in eye space on the original triangle.
fn seen_from_behind(tri: &[&ClipVertex; 3], orthographic: bool) -> bool {
    let p = tri.map(|v| v.eye.as_dvec3());
    let normal = (p[1] - p[0]).cross(p[2] - p[0]);
    let to_viewer = if orthographic { glam::DVec3::Z } else { -p[0] };
    normal.dot(to_viewer) < 0.0
}

/// A vertex with its normal turned around, and its Gouraud colour relit
/// with that normal (untextured Gouraud lights vertices in the vertex stage).
fn turned(v: &ClipVertex, ctx: &SetupContext<'_>) -> ClipVertex {
    let normal = -v.normal;
    let color = match (ctx.shading, ctx.texture) {
        (ShadingMode::Gouraud, None) if !ctx.vertex_colors => {
            ctx.lighting.shade(ctx.material.0, v.eye, normal, Vec3::ZERO)
        }
        _ => v.color,
    };
    ClipVertex { normal, color, ..*v }
}

/// Projects, snaps, culls and builds the planes of one clipped triangle.
#[inline]
fn emit(
    tri: [&ClipVertex; 3],
    p: [Projected; 3],
    flat: LitParts,
    ctx: &SetupContext<'_>,
    out: &mut PrimitiveChunk,
) {
    let fixed = p.map(|v| v.fixed);
    if ctx.cull_back_faces && !is_front_facing(&fixed) {
        return;
    }
    let (Some(edges), Some(basis)) = (EdgeTable::new(fixed), PlaneBasis::new(fixed)) else {
        return;
    };
    let depth = DepthPlane::new(&basis, std::array::from_fn(|k| ctx.depth.value(tri[k], &p[k])));
    let (mut perspective, mut material, mut flat_color) = (ctx.perspective, ctx.material.1, None);
    let mut lit_once = None;
    if let Some(adaptive) = ctx.adaptive {
        match (ctx.shading, ctx.texture) {
            (ShadingMode::Gouraud, None) => {
                match adaptive.gouraud(tri.map(|v| v.color), p.map(|v| v.inv_w), perspective) {
                    GouraudChoice::Flat(c) => flat_color = Some(c),
                    GouraudChoice::Linear => perspective = false,
                    GouraudChoice::Full => {}
                }
            }
            (ShadingMode::Phong, _) => {
                let m = &ctx.material.0.material;
                let (kd, ks, eye) = (m.kd.max_element(), m.ks.max_element(), tri.map(|v| v.eye));
                let normal = (!ctx.vertex_colors).then(|| tri.map(|v| v.normal));
                match adaptive.phong(kd, ks, normal, eye) {
                    PhongChoice::LitOnce => {
                        let normal = (tri[0].normal.normalize_or_zero()
                            + tri[1].normal.normalize_or_zero()
                            + tri[2].normal.normalize_or_zero())
                        .normalize_or_zero();
                        let centroid = (eye[0] + eye[1] + eye[2]) / 3.0;
                        let parts =
                            ctx.lighting.shade_parts(ctx.diffuse_only.0, centroid, normal, Vec3::ZERO);
                        lit_once = Some(parts);
                    }
                    PhongChoice::NoSpecular if ctx.material.0.specular => material = ctx.diffuse_only.1,
                    PhongChoice::NoSpecular | PhongChoice::Full => {}
                }
            }
            _ => {}
        }
    }
    let q = if perspective { p.map(|v| v.inv_w) } else { [1.0; 3] };
    let shader = match (ctx.texture, flat_color, lit_once) {
        (_, Some(color), _) => Shader::Flat { color },
        (None, None, Some(parts)) => Shader::Flat { color: parts.color() },
        (Some(texture), None, lit_once) => {
            textured(tri, q, (flat, lit_once), &basis, (texture, material), ctx, out)
        }
        (None, None, None) => untextured(tri, q, flat.color(), &basis, material, ctx, out),
    };
    let kt = 1.0 - ctx.material.0.material.opacity;
    let sort_depth = ((p[0].z + p[1].z + p[2].z) / 3.0) as f32;
    out.prims.push(Primitive { edges, depth, shader, perspective, kt, sort_depth });
}

/// The shader of an untextured primitive: only the attributes its mode
/// needs (coloured Phong's planes in the chunk's side table).
#[inline]
fn untextured(
    tri: [&ClipVertex; 3],
    q: [f32; 3],
    flat: Vec3,
    basis: &PlaneBasis,
    material: u32,
    ctx: &SetupContext<'_>,
    out: &mut PrimitiveChunk,
) -> Shader {
    match ctx.shading {
        ShadingMode::Flat => Shader::Flat { color: flat },
        ShadingMode::Gouraud => {
            let v = std::array::from_fn(|k| {
                let c = tri[k].color * q[k];
                [q[k], c.x, c.y, c.z]
            });
            Shader::Gouraud { planes: AttributePlanes::new(basis, v) }
        }
        ShadingMode::Phong if ctx.vertex_colors => {
            let v = std::array::from_fn(|k| {
                let (n, e, c) = (tri[k].normal * q[k], tri[k].eye * q[k], tri[k].color * q[k]);
                [q[k], n.x, n.y, n.z, e.x, e.y, e.z, c.x, c.y, c.z]
            });
            out.colored_phong.push(ColoredPhongPlanes { planes: AttributePlanes::new(basis, v), material });
            Shader::ColoredPhong { index: (out.colored_phong.len() - 1) as u32 }
        }
        ShadingMode::Phong => {
            let v = std::array::from_fn(|k| {
                let (n, e) = (tri[k].normal * q[k], tri[k].eye * q[k]);
                [q[k], n.x, n.y, n.z, e.x, e.y, e.z]
            });
            Shader::Phong { planes: AttributePlanes::new(basis, v), material }
        }
    }
}

/// The shader of a textured primitive: texture coordinates plus the parts
/// its mode interpolates (and, for Phong, the vertex colours when the mesh
/// has them), stored in the chunk's side tables.
fn textured(
    tri: [&ClipVertex; 3],
    q: [f32; 3],
    (flat, lit_once): (LitParts, Option<LitParts>),
    basis: &PlaneBasis,
    (texture, material): (u32, u32),
    ctx: &SetupContext<'_>,
    out: &mut PrimitiveChunk,
) -> Shader {
    // The adaptive mode's Phong lit once is drawn as textured flat.
    let (shading, flat) = match lit_once {
        Some(parts) => (ShadingMode::Flat, parts),
        None => (ctx.shading, flat),
    };
    if shading == ShadingMode::Phong && ctx.vertex_colors {
        let values = std::array::from_fn(|k| {
            let (uv, n, e, c) =
                (tri[k].uv * q[k], tri[k].normal * q[k], tri[k].eye * q[k], tri[k].color * q[k]);
            [q[k], uv.x, uv.y, n.x, n.y, n.z, e.x, e.y, e.z, c.x, c.y, c.z]
        });
        let planes = AttributePlanes::new(basis, values);
        out.textured_colored.push(TexturedPlanes { kind: TexturedKind::Phong, planes, texture, material });
        return Shader::TexturedColored { index: (out.textured_colored.len() - 1) as u32 };
    }
    let (kind, pairs): (TexturedKind, [[Vec3; 2]; 3]) = match shading {
        ShadingMode::Flat => (
            TexturedKind::Flat { ambient_diffuse: flat.ambient_diffuse, specular: flat.specular },
            [[Vec3::ZERO; 2]; 3],
        ),
        // Lit before clipping: see `lit_in_setup`.
        ShadingMode::Gouraud => (TexturedKind::Gouraud, tri.map(|v| [v.color, v.normal])),
        ShadingMode::Phong => (TexturedKind::Phong, tri.map(|v| [v.normal, v.eye])),
    };
    let values = std::array::from_fn(|k| {
        let (uv, a, b) = (tri[k].uv * q[k], pairs[k][0] * q[k], pairs[k][1] * q[k]);
        [q[k], uv.x, uv.y, a.x, a.y, a.z, b.x, b.y, b.z]
    });
    let planes = AttributePlanes::new(basis, values);
    out.textured.push(TexturedPlanes { kind, planes, texture, material });
    Shader::Textured { index: (out.textured.len() - 1) as u32 }
}

/// Front faces are counter-clockwise as seen by the viewer (SPEC §2). With
/// window y pointing down that is a negative cross product, decided exactly
/// on the snapped vertices.
#[inline]
pub fn is_front_facing(p: &[FixedPoint; 3]) -> bool {
    let [a, b, c] = p.map(|q| (i64::from(q.x), i64::from(q.y)));
    (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0) < 0
}
