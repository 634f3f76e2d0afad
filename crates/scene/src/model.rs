//! The scene model: meshes, objects, camera, lights and render settings.
//! Plain data, built by the loaders or by hand, consumed by the pipeline.

use std::sync::Arc;

use glam::{Mat4, Vec2, Vec3, Vec4};
use zline_shading::{Environment, Fog, Light, Material, Sampler, ShadingMode, Texture};

/// A texture and how to sample it. A diffuse map modulates ka and kd
/// (SPEC §7).
#[derive(Clone, Debug, PartialEq)]
pub struct TextureMap {
    /// The texels, shared between meshes.
    pub texture: Arc<Texture>,
    /// Filtering and wrapping.
    pub sampler: Sampler,
    /// True when the texel's alpha multiplies the material's opacity (glTF
    /// alpha mode BLEND); the mesh is then drawn in the transparency pass.
    pub alpha_blend: bool,
    /// glTF alpha mode MASK: samples whose texel alpha is below this cutoff
    /// are discarded (before the depth test writes anything).
    pub alpha_cutoff: Option<f32>,
}

/// A triangle mesh in object space with one material.
///
/// Invariants (upheld by the loaders and [`Mesh::new`]): `normals` has one
/// unit normal per position; every index is `< positions.len()`.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// A name for messages (OBJ object or group name, or the primitive).
    pub name: String,
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Unit vertex normals, one per position: from the file, or the
    /// normalized sum of the unit face normals around the vertex (SPEC §6).
    pub normals: Vec<Vec3>,
    /// Triangles as indices into `positions`, counter-clockwise for front
    /// faces.
    pub triangles: Vec<[u32; 3]>,
    /// The mesh's material.
    pub material: Material,
    /// Texture coordinates (s, t), one per position, or empty when the mesh
    /// has none (SPEC §7: t = 0 at the bottom of the image).
    pub uvs: Vec<Vec2>,
    /// Vertex colours (RGB), one per position, or empty when the mesh has
    /// none. Like a texel, a vertex colour multiplies ka and kd (glTF
    /// COLOR_0 multiplies the base colour), not ks or ke; it is applied
    /// with flat shading (the mean of the three corners, at the centroid)
    /// and Gouraud shading (at the vertices), and not yet with Phong shading.
    pub colors: Vec<Vec3>,
    /// The diffuse texture, if any; used only when `uvs` is not empty.
    pub diffuse_map: Option<TextureMap>,
    /// Tangents (xyz, w = ±1 the bitangent's handedness: B = w·(N × T)),
    /// one per position, or empty (`crate::normal_map`).
    pub tangents: Vec<Vec4>,
    /// A bump or normal map perturbing the normal per sample (Phong only);
    /// used only when `uvs` and `tangents` are not empty.
    pub normal_map: Option<NormalMap>,
    /// The maps of a Cook–Torrance material's other parameters (used only
    /// when `uvs` is not empty and `diffuse_map` is set).
    pub surface_maps: SurfaceMaps,
}

/// Textures of a Cook–Torrance material besides its base colour, read per
/// sample by Phong shading with the base colour texture's coordinates
/// (SPEC §5.2); flat and Gouraud shading use the factors alone.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SurfaceMaps {
    /// glTF's metallic–roughness texture: B multiplies the metallic
    /// factor, G the roughness factor.
    pub metallic_roughness: Option<TextureMap>,
    /// glTF's occlusion texture and its strength: the environment's light
    /// (the ambient term) times 1 + strength·(R − 1).
    pub occlusion: Option<(TextureMap, f32)>,
    /// glTF's emissive texture: its RGB multiplies ke.
    pub emission: Option<TextureMap>,
}

/// What a [`NormalMap`]'s texels hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum NormalEncoding {
    /// A height in the red channel (a bump map); the normal follows its
    /// gradient.
    Height,
    /// A tangent-space normal in r, g, b (a normal map).
    Tangent,
}

impl NormalEncoding {
    /// A lower-case name for messages.
    pub fn name(self) -> &'static str {
        match self {
            NormalEncoding::Height => "bump",
            NormalEncoding::Tangent => "normal",
        }
    }
}

/// A bump or normal map; `crate::normal_map`'s documentation states the
/// formulas.
#[derive(Clone, Debug, PartialEq)]
pub struct NormalMap {
    /// The texels and the sampler (its alpha settings are ignored).
    pub map: TextureMap,
    /// What the texels hold.
    pub encoding: NormalEncoding,
    /// k: the bump height of a white texel in texture-coordinate units
    /// ([`NormalEncoding::Height`]), or the factor on the x and y of a
    /// normal map ([`NormalEncoding::Tangent`]).
    pub scale: f32,
}

/// How values are interpolated across a triangle in window space (SPEC §6).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Interpolation {
    /// Interpolate a/w and 1/w linearly and divide per sample.
    #[default]
    PerspectiveCorrect,
    /// Interpolate values linearly in window space (the seed's formulas).
    ScreenLinear,
}

impl Interpolation {
    /// The name used by the CLI and scene files.
    pub fn name(self) -> &'static str {
        match self {
            Interpolation::PerspectiveCorrect => "perspective",
            Interpolation::ScreenLinear => "linear",
        }
    }
}

/// A mesh placed in the world.
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    /// The mesh, shared between instances.
    pub mesh: Arc<Mesh>,
    /// The model matrix.
    pub world_from_object: Mat4,
    /// Replaces the mesh's material when set.
    pub material: Option<Material>,
    /// Replaces the scene's shading mode for this object when set.
    pub shading: Option<ShadingMode>,
    /// Back-face culling: on for closed opaque meshes (SPEC §2).
    pub cull_back_faces: bool,
}

impl Object {
    /// The material the object is drawn with.
    pub fn material(&self) -> Material {
        self.material.unwrap_or(self.mesh.material)
    }
}

/// The camera's projection (SPEC §1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// `gluPerspective(fovy, aspect, near, far)`.
    Perspective {
        /// Vertical field of view in degrees.
        fovy_degrees: f32,
        /// Distance to the near plane (> 0).
        near: f32,
        /// Distance to the far plane (> near).
        far: f32,
    },
    /// `glOrtho` with a symmetric view volume of the given height.
    Orthographic {
        /// Height of the view volume in world units; width = height · aspect.
        height: f32,
        /// Distance to the near plane.
        near: f32,
        /// Distance to the far plane (> near).
        far: f32,
    },
    /// `glFrustum(left, right, bottom, top, near, far)`: a perspective view
    /// volume whose sides are given where they cut the near plane (eye
    /// space), not necessarily centred on the view axis: a camera's
    /// intrinsics (focal lengths and principal point), or an off-axis view.
    /// The frustum fixes its own aspect ratio; the image's is not used.
    Frustum {
        /// x of the left side at the near plane (< right).
        left: f32,
        /// x of the right side at the near plane.
        right: f32,
        /// y of the bottom side at the near plane (< top).
        bottom: f32,
        /// y of the top side at the near plane.
        top: f32,
        /// Distance to the near plane (> 0).
        near: f32,
        /// Distance to the far plane (> near).
        far: f32,
    },
}

impl Projection {
    /// True for the projections through a centre (perspective and
    /// frustum), false for the parallel one.
    pub fn is_perspective(&self) -> bool {
        !matches!(self, Projection::Orthographic { .. })
    }

    /// The distances to the near and far planes.
    pub fn near_far(&self) -> (f32, f32) {
        match *self {
            Projection::Perspective { near, far, .. }
            | Projection::Orthographic { near, far, .. }
            | Projection::Frustum { near, far, .. } => (near, far),
        }
    }
}

/// A look-at camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Eye position in world space.
    pub eye: Vec3,
    /// The point looked at.
    pub target: Vec3,
    /// The world's up direction.
    pub up: Vec3,
    /// The projection.
    pub projection: Projection,
}

impl Camera {
    /// The view matrix (right-handed, looking down −z, +y up).
    pub fn eye_from_world(&self) -> Mat4 {
        look_at_rh(self.eye, self.target, self.up)
    }

    /// The projection matrix for a viewport aspect ratio (width / height),
    /// with OpenGL's NC depth range [−1, 1].
    pub fn clip_from_eye(&self, aspect: f32) -> Mat4 {
        match self.projection {
            Projection::Perspective { fovy_degrees, near, far } => {
                perspective_rh_gl(fovy_degrees.to_radians(), aspect, near, far)
            }
            Projection::Orthographic { height, near, far } => {
                let (h, w) = (height / 2.0, height * aspect / 2.0);
                Mat4::orthographic_rh_gl(-w, w, -h, h, near, far)
            }
            Projection::Frustum { left, right, bottom, top, near, far } => {
                frustum_rh_gl(left, right, bottom, top, near, far)
            }
        }
    }
}

impl Camera {
    /// Coefficients (a, b) of w − z_clip = a·z_eye + b for this camera's
    /// projection, computed in f64 from near and far: the numerator of
    /// reversed depth (w − z_clip)/(2w), which [`DepthMode::ReversedFloat`]
    /// evaluates from eye-space depth instead of subtracting two nearly
    /// equal clip coordinates. Perspective: w = −z_eye, so a = 2n/(f − n),
    /// b = 2fn/(f − n); orthographic: w = 1, a = 2/(f − n), b = 2f/(f − n).
    pub fn reversed_depth_coefficients(&self) -> (f64, f64) {
        match self.projection {
            Projection::Perspective { near, far, .. } | Projection::Frustum { near, far, .. } => {
                let (n, f) = (f64::from(near), f64::from(far));
                (2.0 * n / (f - n), 2.0 * f * (n / (f - n)))
            }
            Projection::Orthographic { near, far, .. } => {
                let (n, f) = (f64::from(near), f64::from(far));
                (2.0 / (f - n), 2.0 * f / (f - n))
            }
        }
    }
}

/// `gluLookAt`, as glam's `Mat4::look_at_rh` but normalizing directions
/// after scaling them by their largest component: glam's `normalize`
/// squares the components and overflows f32 for eye–target distances
/// beyond ~1e19, which makes the whole view matrix NaN.
fn look_at_rh(eye: Vec3, target: Vec3, up: Vec3) -> Mat4 {
    use glam::Vec4;
    let unit = |v: Vec3| (v / v.abs().max_element()).normalize();
    let f = unit(target - eye);
    let s = unit(f.cross(up));
    let u = s.cross(f);
    Mat4::from_cols(
        Vec4::new(s.x, u.x, -f.x, 0.0),
        Vec4::new(s.y, u.y, -f.y, 0.0),
        Vec4::new(s.z, u.z, -f.z, 0.0),
        Vec4::new(-s.dot(eye), -u.dot(eye), f.dot(eye), 1.0),
    )
}

/// `gluPerspective` with OpenGL's NC depth range, as glam's
/// `Mat4::perspective_rh_gl` but with the depth term computed as
/// `2·near · (far / (near − far))`: glam's `2·near·far` overflows f32 once
/// near·far exceeds ~1.7e38, that is for scenes measured in units of 1e19
/// and beyond, which then project to infinities.
fn perspective_rh_gl(fovy_radians: f32, aspect: f32, near: f32, far: f32) -> Mat4 {
    use glam::Vec4;
    let inv_length = 1.0 / (near - far);
    let f = 1.0 / (0.5 * fovy_radians).tan();
    Mat4::from_cols(
        Vec4::new(f / aspect, 0.0, 0.0, 0.0),
        Vec4::new(0.0, f, 0.0, 0.0),
        Vec4::new(0.0, 0.0, (near + far) * inv_length, -1.0),
        Vec4::new(0.0, 0.0, (2.0 * near) * (far * inv_length), 0.0),
    )
}

/// `glFrustum` with OpenGL's NC depth range, its depth terms as in
/// [`perspective_rh_gl`] (the same bits for a centred frustum's depth).
fn frustum_rh_gl(left: f32, right: f32, bottom: f32, top: f32, near: f32, far: f32) -> Mat4 {
    use glam::Vec4;
    let inv_length = 1.0 / (near - far);
    let (w, h) = (right - left, top - bottom);
    Mat4::from_cols(
        Vec4::new(2.0 * near / w, 0.0, 0.0, 0.0),
        Vec4::new(0.0, 2.0 * near / h, 0.0, 0.0),
        Vec4::new((right + left) / w, (top + bottom) / h, (near + far) * inv_length, -1.0),
        Vec4::new(0.0, 0.0, (2.0 * near) * (far * inv_length), 0.0),
    )
}

/// Settings a scene file may give; the CLI may override them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Shading mode for objects that do not set their own.
    pub shading: ShadingMode,
    /// Interpolation of attributes.
    pub interpolation: Interpolation,
    /// Replaces every texture's filter when set (`--filter`).
    pub texture_filter: Option<zline_shading::Filter>,
    /// Supersampling: `n` gives an n×n ordered grid of samples per pixel,
    /// sample (a, b) of pixel (i, j) at (i + (a + ½)/n, j + (b + ½)/n),
    /// box-filtered (the mean of the n² lit, fogged, blended sample
    /// colours) before quantization. 1 samples pixel centres only.
    pub ssaa: u32,
    /// What the depth buffer stores.
    pub depth: DepthMode,
    /// The adaptive mode: when set, a tolerance in 8-bit units; per
    /// triangle the pipeline takes the cheapest evaluation whose error it
    /// can bound below this (see the pipeline's `adaptive` module).
    pub adaptive_tolerance: Option<f32>,
    /// Where untextured Gouraud shading clamps the lit colour (SPEC §11).
    pub gouraud_clamp: GouraudClamp,
    /// How triangles seen from behind are lit when not culled (SPEC §11).
    pub lighting_sides: LightingSides,
    /// The z-buffer or the painter's algorithm.
    pub visibility: crate::visibility::Visibility,
    /// Mesh edges drawn as lines.
    pub wireframe: crate::visibility::Wireframe,
    /// A transparent background: the frame's background is (0, 0, 0) with
    /// alpha 0, every pixel's alpha is its coverage (the share of its
    /// samples drawn, with transparent surfaces counting 1 − kt), and the
    /// image holds straight (not premultiplied) colour. Off: the scene's
    /// background, alpha 255 everywhere.
    pub transparent_background: bool,
    /// Exposure and tone mapping before quantization (SPEC §10); the
    /// default, no operator at exposure 1, is the plain clamp.
    pub tone_mapping: zline_shading::ToneMapping,
    /// Which renderer draws the image (`render`, `demo` and `view`;
    /// turntables and batches rasterize).
    pub renderer: crate::trace_options::Renderer,
    /// How the ray tracer traces, when it draws.
    pub trace: crate::trace_options::TraceOptions,
    /// How radiosity meshes and solves, when it draws.
    pub radiosity: crate::radiosity_options::RadiosityOptions,
}

/// Where untextured Gouraud shading clamps the lit colour to [0, 1] (SPEC
/// §5 clamps the lit colour, §6 interpolates colours lit at the vertices;
/// SPEC §11 states the choice). Textured Gouraud is not affected: it keeps
/// the two parts apart and clamps per sample after the texel (SPEC §7).
/// Vertex colours (which multiply ka and kd at each vertex) follow it. Flat
/// and Phong shading light where they clamp, so it does not concern them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum GouraudClamp {
    /// The lit colour is clamped at each vertex, then interpolated (as
    /// fixed-function OpenGL does).
    #[default]
    PerVertex,
    /// The unclamped lit colour (ambient + diffuse + specular) is
    /// interpolated and clamped at each sample: a highlight above 1 at one
    /// vertex spreads further over the triangle.
    PerSample,
}

impl GouraudClamp {
    /// The name used by the CLI and scene files.
    pub fn name(self) -> &'static str {
        match self {
            GouraudClamp::PerVertex => "vertex",
            GouraudClamp::PerSample => "sample",
        }
    }
}

/// How a triangle drawn without back-face culling and seen from behind is
/// lit (SPEC §11), in every shading mode. Which triangles are drawn does
/// not change.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum LightingSides {
    /// Two-sided lighting: its normals (vertex normals, and flat shading's
    /// face normal) are turned towards the viewer, as OpenGL's two-sided
    /// lighting model and glTF's doubleSided do.
    #[default]
    TwoSided,
    /// One-sided lighting: normals as given, so the far side of an open or
    /// transparent mesh is lit as if the viewer stood behind it (usually
    /// only ambient and emission).
    OneSided,
}

impl LightingSides {
    /// The name used by the CLI and scene files.
    pub fn name(self) -> &'static str {
        match self {
            LightingSides::TwoSided => "two-sided",
            LightingSides::OneSided => "one-sided",
        }
    }
}

/// The depth buffer's representation (SPEC §4 and its stated deviation).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum DepthMode {
    /// The seed's depth buffer: NC z in [−1, 1], cleared to 1, a fragment
    /// passes when z < stored.
    #[default]
    Normalized,
    /// Reversed-Z in floating point: stores (1 − z_win) = (w − z_clip)/(2w),
    /// computed from eye-space depth so that it keeps full relative
    /// precision far from the camera; cleared to 0, a fragment passes when
    /// its value is greater than the stored one. The same order as
    /// `Normalized` wherever both are exact.
    ReversedFloat,
}

impl DepthMode {
    /// The name used by the CLI and scene files.
    pub fn name(self) -> &'static str {
        match self {
            DepthMode::Normalized => "normalized",
            DepthMode::ReversedFloat => "reversed",
        }
    }
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            width: 800,
            height: 600,
            shading: ShadingMode::Phong,
            interpolation: Interpolation::PerspectiveCorrect,
            texture_filter: None,
            ssaa: 1,
            depth: DepthMode::Normalized,
            adaptive_tolerance: None,
            gouraud_clamp: GouraudClamp::PerVertex,
            lighting_sides: LightingSides::TwoSided,
            visibility: crate::visibility::Visibility::ZBuffer,
            wireframe: crate::visibility::Wireframe::default(),
            transparent_background: false,
            tone_mapping: zline_shading::ToneMapping::default(),
            renderer: crate::trace_options::Renderer::Raster,
            trace: crate::trace_options::TraceOptions::DEFAULT,
            radiosity: crate::radiosity_options::RadiosityOptions::DEFAULT,
        }
    }
}

/// Everything needed to render one image.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The camera.
    pub camera: Camera,
    /// Background colour (RGB in [0, 1]).
    pub background: Vec3,
    /// Ambient light Ia.
    pub ambient: Vec3,
    /// Light sources, in world space.
    pub lights: Vec<Light>,
    /// Light from an environment map, in world space (SPEC §5.3), and
    /// whether it is drawn as the background.
    pub environment: Option<Environment>,
    /// The objects.
    pub objects: Vec<Object>,
    /// Render settings.
    pub settings: RenderSettings,
    /// Fog (SPEC §8), if any.
    pub fog: Option<Fog>,
    /// Shadows: the method and the receiving planes.
    pub shadows: Shadows,
}

/// How shadows are computed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ShadowMode {
    /// No shadows: every surface is lit by every light (SPEC §5 alone).
    #[default]
    None,
    /// Planar projection shadows on the scene's [`ShadowPlane`]s.
    Planar,
    /// Shadow maps: every surface receives and every surface casts; a
    /// depth image from each light (six faces for a point light) decides
    /// per sample whether the light is seen.
    Map,
}

impl ShadowMode {
    /// Every mode, in the order the CLI lists them.
    pub const ALL: [ShadowMode; 3] = [ShadowMode::None, ShadowMode::Planar, ShadowMode::Map];

    /// The name the scene file and the CLI use: "none", "planar", "map".
    pub fn name(self) -> &'static str {
        match self {
            ShadowMode::None => "none",
            ShadowMode::Planar => "planar",
            ShadowMode::Map => "map",
        }
    }
}

/// A flat object that receives planar shadows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowPlane {
    /// The receiving object's index in `Scene::objects`. It casts no
    /// shadow itself.
    pub receiver: usize,
    /// The plane in world space, (a, b, c, d) with a·x + b·y + c·z + d = 0
    /// and (a, b, c) a unit normal.
    pub plane: Vec4,
}

/// Shadows of a scene: the method and the surfaces that receive them.
#[derive(Clone, Debug, PartialEq)]
pub struct Shadows {
    /// The method; [`ShadowMode::None`] ignores the planes.
    pub mode: ShadowMode,
    /// The receiving planes of [`ShadowMode::Planar`].
    pub planes: Vec<ShadowPlane>,
    /// The side of each shadow map (each face of a point light's cube) in
    /// texels, for [`ShadowMode::Map`].
    pub map_size: u32,
    /// Percentage-closer filtering for [`ShadowMode::Map`]: the light's
    /// share is the fraction of the 3 × 3 nearest texels that see it,
    /// instead of the one nearest texel's yes or no.
    pub pcf: bool,
    /// A scale on the shadow maps' slope-scaled depth bias (1 by default:
    /// 1.5 + 2·tan θ texels of depth). 0 shows the acne a map without bias
    /// has; large values detach shadows from their casters (peter-panning).
    pub bias: f32,
}

/// [`Shadows::map_size`] by default.
pub const DEFAULT_SHADOW_MAP_SIZE: u32 = 1024;

impl Default for Shadows {
    fn default() -> Shadows {
        Shadows {
            mode: ShadowMode::None,
            planes: Vec::new(),
            map_size: DEFAULT_SHADOW_MAP_SIZE,
            pcf: true,
            bias: 1.0,
        }
    }
}

impl Shadows {
    /// True when object `index` receives shadows in this mode: a planar
    /// mode's planes, every object with shadow maps.
    pub fn receives(&self, index: usize) -> bool {
        match self.mode {
            ShadowMode::None => false,
            ShadowMode::Planar => self.planes.iter().any(|p| p.receiver == index),
            ShadowMode::Map => true,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn look_at_matches_glam_and_survives_huge_distances() {
        let (eye, target) = (Vec3::new(1.0, 2.0, 5.0), Vec3::new(0.5, 0.0, -1.0));
        let ours = look_at_rh(eye, target, Vec3::Y);
        let glams = Mat4::look_at_rh(eye, target, Vec3::Y);
        assert!(ours.abs_diff_eq(glams, 1e-6), "{ours} vs {glams}");
        let huge = look_at_rh(Vec3::new(1e30, 2e30, 3e30), Vec3::ZERO, Vec3::Y);
        assert!(huge.is_finite(), "{huge}");
        let p = huge.transform_point3(Vec3::ZERO);
        // The target lies straight ahead (−z) at the eye's distance.
        let distance = 14f32.sqrt() * 1e30;
        assert!((p.z / -distance - 1.0).abs() < 1e-6 && p.x.abs().max(p.y.abs()) < 1e-6 * distance, "{p}");
    }

    #[test]
    fn perspective_matches_glam_and_survives_huge_planes() {
        let camera = |near, far| Camera {
            eye: Vec3::ZERO,
            target: Vec3::NEG_Z,
            up: Vec3::Y,
            projection: Projection::Perspective { fovy_degrees: 40.0, near, far },
        };
        let ours = camera(0.1, 100.0).clip_from_eye(1.5);
        let glams = Mat4::perspective_rh_gl(40f32.to_radians(), 1.5, 0.1, 100.0);
        assert!(ours.abs_diff_eq(glams, 1e-6), "{ours} vs {glams}");
        let huge = camera(1e30, 4e30).clip_from_eye(1.5);
        assert!(huge.is_finite(), "{huge}");
        let nc = huge.project_point3(Vec3::new(0.0, 0.0, -1e30));
        assert!((nc.z + 1.0).abs() < 1e-5, "near plane maps to z = -1, got {nc}");
    }

    #[test]
    fn a_frustum_is_glfrustum() {
        let camera = |projection| Camera { eye: Vec3::ZERO, target: Vec3::NEG_Z, up: Vec3::Y, projection };
        // Centred, it is gluPerspective's volume.
        let (near, far, fovy) = (0.5f32, 50.0, 40f32);
        let t = near * (fovy / 2.0).to_radians().tan();
        let centred = Projection::Frustum { left: -1.5 * t, right: 1.5 * t, bottom: -t, top: t, near, far };
        let perspective = Projection::Perspective { fovy_degrees: fovy, near, far };
        let (a, b) = (camera(centred).clip_from_eye(9.0), camera(perspective).clip_from_eye(1.5));
        assert!(a.abs_diff_eq(b, 1e-5), "{a} vs {b}");
        // Off axis: each side's corner at the near plane goes to the NC
        // cube's, and depth is as in the centred one.
        let (l, r, bo, to) = (-0.2f32, 0.6f32, -0.1f32, 0.3f32);
        let m = camera(Projection::Frustum { left: l, right: r, bottom: bo, top: to, near, far })
            .clip_from_eye(1.0);
        for (x, y, want) in [(l, bo, Vec3::new(-1.0, -1.0, -1.0)), (r, to, Vec3::new(1.0, 1.0, -1.0))] {
            let nc = m.project_point3(Vec3::new(x, y, -near));
            assert!(nc.abs_diff_eq(want, 1e-5), "{nc} vs {want}");
        }
        // A point on the far plane, along the left side's ray.
        let nc = m.project_point3(Vec3::new(l * far / near, 0.0, -far));
        assert!((nc.x + 1.0).abs() < 1e-5 && (nc.z - 1.0).abs() < 1e-4, "{nc}");
        assert!(Projection::Frustum { left: l, right: r, bottom: bo, top: to, near, far }.is_perspective());
    }
}
