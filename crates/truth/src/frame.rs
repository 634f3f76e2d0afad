//! One frame's geometry: every object's vertices in eye, clip and sample
//! space, and every drawn triangle as a [`Prim`] in draw order (objects in
//! scene order, triangles in mesh order, clipped pieces in fan order).
//!
//! Per triangle (SPEC §1–2): non-finite input is dropped; a triangle with a
//! vertex outside the near or far plane is clipped ([`crate::clip`]); each
//! piece with zero or non-finite area in sample space is dropped; with
//! back-face culling on, a piece that is not counter-clockwise as seen by
//! the viewer (negative doubled area, window y down) is dropped. Nothing
//! else is special about mirrored (negative-determinant) model matrices,
//! as in the fast renderer: the window winding alone decides. Without
//! culling and with two-sided lighting (`LightingSides::TwoSided`, the
//! default), a triangle whose front faces away from the viewer — decided
//! in eye space on the original triangle, against −p for a perspective
//! camera and +z for an orthographic one — is lit with its normals turned
//! around, as the fast renderer's setup does; one-sided lighting keeps the
//! normals as given.
//!
//! With `ShadowMode::Planar` or `ShadowMode::Map`, the frame also holds
//! every caster triangle in eye space as [`Occluders`] (Planar: the
//! objects that do not receive shadows; Map: every object), and shadow
//! receivers are shaded as Phong whatever their mode ([`crate::shadow`]).

use std::sync::Arc;

use glam::{DMat4, DVec2, DVec3, DVec4};
use rayon::prelude::*;
use zline_scene::{
    Interpolation, LightingSides, Mesh, Projection, Scene, ShadowMode, SurfaceMaps, TextureMap,
};
use zline_shading::ShadingMode;

use crate::camera::{self, Corner, ObjectTransforms, SampleSpace, Vertex};
use crate::clip::clip_triangle;
use crate::coverage::signed_area2;
use crate::environment::EnvironmentF64;
use crate::lighting::{EyeLights, MaterialF64, ModelF64};
use crate::shadow::{Occluders, TriangleId};
use crate::split_sum::SplitSum;

/// Triangles per rayon task in setup.
const TRIANGLE_CHUNK: usize = 4096;

/// An object with its per-frame data.
#[derive(Debug)]
pub(crate) struct ObjectFrame {
    /// The mesh.
    pub(crate) mesh: Arc<Mesh>,
    /// Transformed vertices, one per mesh position.
    pub(crate) vertices: Vec<Vertex>,
    /// The object's material, sanitized.
    pub(crate) material: MaterialF64,
    /// Its shading mode (the object's, else the scene's; Phong for a
    /// shadow receiver).
    pub(crate) mode: ShadingMode,
    /// Receives shadows: lit without the lights the frame's occluders hide.
    pub(crate) receives_shadows: bool,
    /// The diffuse texture with the scene's filter override, when the mesh
    /// has one and texture coordinates.
    pub(crate) texture: Option<TextureMap>,
    /// Drawn in the transparency pass: opacity < 1, or texture alpha blends.
    pub(crate) transparent: bool,
    /// A Cook–Torrance material's metallic–roughness, occlusion and
    /// emissive maps, each with the scene's filter override: only beside
    /// the diffuse texture (read with its coordinates), else none.
    pub(crate) surface_maps: SurfaceMaps,
    /// The bump or normal map, when it is drawn.
    pub(crate) normal_map: Option<crate::normal_map::FrameNormalMap>,
}

/// A corner of a clipped piece: its projection and its weights with
/// respect to the original triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ClippedCorner {
    pub(crate) corner: Corner,
    pub(crate) beta: DVec3,
}

/// A triangle (or a piece of a clipped one) to draw.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Prim {
    /// Index of the object.
    pub(crate) object: u32,
    /// Index of the triangle in the object's mesh.
    pub(crate) triangle: u32,
    /// Seen from behind without culling, with two-sided lighting: normals
    /// are turned around.
    pub(crate) back: bool,
    /// The piece's corners when the triangle was clipped (rare, so boxed).
    pub(crate) clipped: Option<Box<[ClippedCorner; 3]>>,
}

/// A prim's corners in sample space and their weights with respect to the
/// original triangle's vertices.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PrimGeometry {
    pub(crate) corners: [Corner; 3],
    pub(crate) beta: [DVec3; 3],
}

/// Everything the tiles read.
#[derive(Debug)]
pub(crate) struct Frame<'a> {
    /// The scene.
    pub(crate) scene: &'a Scene,
    /// Supersampling factor n (samples per pixel along each axis).
    pub(crate) n: u32,
    /// Image size in pixels.
    pub(crate) size: (u32, u32),
    /// Sample grid size: (n·W, n·H).
    pub(crate) limit: (i64, i64),
    /// Perspective-correct attribute interpolation (else screen-linear).
    pub(crate) perspective: bool,
    /// Lights in eye space.
    pub(crate) lights: EyeLights,
    /// The objects.
    pub(crate) objects: Vec<ObjectFrame>,
    /// The shadow casters' triangles, when some object receives shadows
    /// and some caster triangle is not degenerate.
    pub(crate) occluders: Option<Occluders>,
    /// Triangles to draw, in draw order.
    pub(crate) prims: Vec<Prim>,
    /// The caller's shading function, replacing the lighting model of
    /// Phong-shaded samples ([`crate::render_truth_shaded`]).
    pub(crate) shader: Option<Shader<'a>>,
    /// Where undrawn samples show the environment (SPEC §5.3), the
    /// mapping from sample space back to eye-space rays.
    pub(crate) sky: Option<Sky>,
}

/// The rays behind the samples, for an environment drawn as the
/// background: through the sample's centre from the eye (perspective), or
/// along −z (orthographic).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Sky {
    /// The inverse of clip_from_eye.
    eye_from_clip: DMat4,
    orthographic: bool,
}

/// A caller-supplied shading function ([`crate::render_truth_shaded`]).
#[derive(Clone, Copy)]
pub(crate) struct Shader<'a>(pub(crate) &'a (dyn Fn(&crate::sample::SampleShading) -> DVec3 + Sync));

impl std::fmt::Debug for Shader<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Shader(..)")
    }
}

impl<'a> Frame<'a> {
    /// Transforms and sets up every object of `scene`, Cook–Torrance's
    /// environment term taking its split sum from `split_sum`.
    pub(crate) fn new(scene: &'a Scene, split_sum: SplitSum) -> Frame<'a> {
        let s = &scene.settings;
        let (width, height) = (s.width.max(1), s.height.max(1));
        let n = s.ssaa.max(1);
        let space = SampleSpace { width: f64::from(width * n), height: f64::from(height * n) };
        let eye_from_world = camera::eye_from_world(&scene.camera);
        let clip_from_eye = camera::clip_from_eye(&scene.camera, f64::from(width) / f64::from(height));
        let orthographic = matches!(scene.camera.projection, Projection::Orthographic { .. });
        let mut objects = Vec::with_capacity(scene.objects.len());
        let mut prims = Vec::new();
        for (index, object) in scene.objects.iter().enumerate() {
            let world_from_object = object.world_from_object.as_dmat4();
            let t = ObjectTransforms::new(clip_from_eye, eye_from_world, world_from_object);
            let frame_object = object_frame(scene, index, &t, &space);
            let ctx = SetupContext {
                object: index as u32,
                cull: object.cull_back_faces,
                sides: s.lighting_sides,
                orthographic,
                space,
            };
            prims.extend(setup_object(&frame_object, &ctx));
            objects.push(frame_object);
        }
        let occluders = shadow_casters(scene.shadows.mode, &objects);
        let environment = scene.environment.as_ref().map(|e| EnvironmentF64::new(e, &eye_from_world));
        // SPEC §5.3: with a transparent background the environment is not drawn.
        let sky = environment
            .as_ref()
            .filter(|e| e.background && !s.transparent_background)
            .map(|_| Sky { eye_from_clip: clip_from_eye.inverse(), orthographic });
        Frame {
            scene,
            n,
            size: (width, height),
            limit: (i64::from(width * n), i64::from(height * n)),
            perspective: s.interpolation == Interpolation::PerspectiveCorrect,
            lights: EyeLights::new(scene.ambient, &scene.lights, &eye_from_world, split_sum)
                .with_environment(environment),
            objects,
            occluders,
            prims,
            shader: None,
            sky,
        }
    }

    /// What an undrawn sample at sample-space position `p` shows: k·L along
    /// its ray when the environment is drawn (SPEC §5.3), clamped to
    /// [0, 1] per sample like a lit colour (the truth has no tone mapping),
    /// else the background colour.
    pub(crate) fn background(&self, p: DVec2) -> DVec3 {
        let (Some(sky), Some(environment)) = (&self.sky, self.lights.environment()) else {
            return self.scene.background.as_dvec3();
        };
        let ray = if sky.orthographic {
            DVec3::NEG_Z
        } else {
            let ndc_x = p.x / self.limit.0 as f64 * 2.0 - 1.0;
            let ndc_y = 1.0 - p.y / self.limit.1 as f64 * 2.0;
            let q = sky.eye_from_clip * DVec4::new(ndc_x, ndc_y, 0.0, 1.0);
            // A point of the ray (the eye is the origin), in front of it.
            let d = (q.truncate() / q.w).normalize_or_zero();
            if d.z > 0.0 {
                -d
            } else {
                d
            }
        };
        environment.radiance(ray).clamp(DVec3::ZERO, DVec3::ONE)
    }

    /// A prim's corners and weights.
    pub(crate) fn geometry(&self, prim: &Prim) -> PrimGeometry {
        match &prim.clipped {
            Some(c) => PrimGeometry { corners: c.map(|k| k.corner), beta: c.map(|k| k.beta) },
            None => {
                let object = &self.objects[prim.object as usize];
                let tri = object.mesh.triangles[prim.triangle as usize];
                PrimGeometry {
                    corners: tri.map(|i| object.vertices[i as usize].corner.unwrap_or_default()),
                    beta: DVec3::AXES,
                }
            }
        }
    }
}

/// The per-frame data of object `index`.
fn object_frame(scene: &Scene, index: usize, t: &ObjectTransforms, space: &SampleSpace) -> ObjectFrame {
    let object = &scene.objects[index];
    let mesh = Arc::clone(&object.mesh);
    let vertices = mesh
        .positions
        .par_iter()
        .enumerate()
        .map(|(i, p)| {
            let normal = mesh.normals.get(i).map_or(DVec3::ZERO, |n| n.as_dvec3());
            t.vertex(p.as_dvec3(), normal, space)
        })
        .collect();
    let filtered = |map: &TextureMap| {
        let mut map = map.clone();
        if let Some(filter) = scene.settings.texture_filter {
            map.sampler.filter = filter;
        }
        map
    };
    let texture = match (&mesh.diffuse_map, mesh.uvs.is_empty()) {
        (Some(map), false) => Some(filtered(map)),
        _ => None,
    };
    let material = MaterialF64::new(&object.material());
    let maps = &mesh.surface_maps;
    let surface_maps = match material.model {
        ModelF64::CookTorrance(_) if texture.is_some() => SurfaceMaps {
            metallic_roughness: maps.metallic_roughness.as_ref().map(filtered),
            occlusion: maps.occlusion.as_ref().map(|(map, strength)| (filtered(map), *strength)),
            emission: maps.emission.as_ref().map(filtered),
        },
        _ => SurfaceMaps::default(),
    };
    let transparent = material.opacity < 1.0 || texture.as_ref().is_some_and(|m| m.alpha_blend);
    let receives_shadows = scene.shadows.receives(index);
    let mode =
        if receives_shadows { ShadingMode::Phong } else { object.shading.unwrap_or(scene.settings.shading) };
    ObjectFrame {
        normal_map: crate::normal_map::FrameNormalMap::new(&mesh, mode, t),
        mode,
        receives_shadows,
        mesh,
        vertices,
        material,
        texture,
        transparent,
        surface_maps,
    }
}

/// The caster triangles in eye space, with their identities: in Map mode
/// every object's, else (Planar) those of every object that does not
/// receive shadows; `None` when no object receives shadows or nothing
/// casts them.
fn shadow_casters(mode: ShadowMode, objects: &[ObjectFrame]) -> Option<Occluders> {
    if !objects.iter().any(|o| o.receives_shadows) {
        return None;
    }
    let casts = |o: &ObjectFrame| mode == ShadowMode::Map || !o.receives_shadows;
    let triangles = objects.iter().enumerate().filter(|(_, o)| casts(o)).flat_map(|(object, o)| {
        o.mesh.triangles.iter().enumerate().filter_map(move |(triangle, t)| {
            let [a, b, c] = gather(&o.vertices, *t)?;
            let id = TriangleId { object: object as u32, triangle: triangle as u32 };
            Some((id, [a.eye, b.eye, c.eye]))
        })
    });
    let occluders = Occluders::new(triangles);
    (!occluders.is_empty()).then_some(occluders)
}

/// What setup needs to know about the object.
#[derive(Clone, Copy, Debug)]
struct SetupContext {
    object: u32,
    cull: bool,
    /// How back faces that are drawn are lit.
    sides: LightingSides,
    orthographic: bool,
    space: SampleSpace,
}

/// The prims of one object, in mesh order.
fn setup_object(object: &ObjectFrame, ctx: &SetupContext) -> Vec<Prim> {
    let chunks: Vec<Vec<Prim>> = object
        .mesh
        .triangles
        .par_chunks(TRIANGLE_CHUNK)
        .enumerate()
        .map(|(chunk, tris)| {
            let mut out = Vec::with_capacity(tris.len());
            for (k, tri) in tris.iter().enumerate() {
                let index = (chunk * TRIANGLE_CHUNK + k) as u32;
                setup_triangle(&object.vertices, *tri, index, ctx, &mut out);
            }
            out
        })
        .collect();
    chunks.concat()
}

/// Appends the drawn pieces of one triangle to `out`.
fn setup_triangle(vertices: &[Vertex], tri: [u32; 3], index: u32, ctx: &SetupContext, out: &mut Vec<Prim>) {
    let Some(v) = gather(vertices, tri) else { return };
    if !v.iter().all(|v| v.eye.is_finite() && v.clip.is_finite()) {
        return;
    }
    let back = !ctx.cull && ctx.sides == LightingSides::TwoSided && seen_from_behind(&v, ctx.orthographic);
    let prim = |clipped| Prim { object: ctx.object, triangle: index, back, clipped };
    if let [Some(a), Some(b), Some(c)] = v.map(|v| v.corner) {
        if drawn([a, b, c], ctx.cull) {
            out.push(prim(None));
        }
        return;
    }
    let (poly, n) = clip_triangle(v.map(|v| v.clip));
    for i in 1..n.saturating_sub(1) {
        let piece = [poly[0], poly[i], poly[i + 1]];
        let corners = piece.map(|p| ctx.space.project(p.clip));
        if let [Some(a), Some(b), Some(c)] = corners {
            if drawn([a, b, c], ctx.cull) {
                let k = |j: usize, corner| ClippedCorner { corner, beta: piece[j].beta };
                out.push(prim(Some(Box::new([k(0, a), k(1, b), k(2, c)]))));
            }
        }
    }
}

/// The three vertices of a triangle; `None` when an index is out of range.
fn gather(vertices: &[Vertex], t: [u32; 3]) -> Option<[&Vertex; 3]> {
    Some([vertices.get(t[0] as usize)?, vertices.get(t[1] as usize)?, vertices.get(t[2] as usize)?])
}

/// False for zero or non-finite area, and for back faces when culling.
fn drawn(c: [Corner; 3], cull: bool) -> bool {
    let cross = signed_area2(c[0].pos, c[1].pos, c[2].pos);
    cross.is_finite() && cross != 0.0 && !(cull && cross > 0.0)
}

/// True when the triangle's counter-clockwise side faces away from the
/// viewer, decided in eye space.
fn seen_from_behind(v: &[&Vertex; 3], orthographic: bool) -> bool {
    let normal = face_cross(v);
    let to_viewer = if orthographic { DVec3::Z } else { -v[0].eye };
    normal.dot(to_viewer) < 0.0
}

/// (p1 − p0) × (p2 − p0) in eye space: the unnormalized face normal.
pub(crate) fn face_cross(v: &[&Vertex; 3]) -> DVec3 {
    (v[1].eye - v[0].eye).cross(v[2].eye - v[0].eye)
}
