//! Scene files: a TOML description of camera, lights, objects and render
//! settings → a [`Scene`].
//!
//! Contract: [`load_scene`] returns a scene whose every number is finite and
//! in range, or a [`SceneError`] naming the scene file, the line and column,
//! the key (`objects[2].scale`) and the offending value. Unknown keys are
//! errors (typos must not pass silently). Paths are relative to the scene
//! file and must lie in its folder (no absolute path, no `..` above it, no
//! symlink out of it) unless [`LoadOptions::allow_outside`]. Each distinct
//! model file is loaded once and its meshes shared.
//!
//! Limits: the scene file is at most
//! [`MAX_TEXT_FILE_BYTES`](zline_scene::MAX_TEXT_FILE_BYTES); its
//! primitives together make at most [`MAX_PRIMITIVE_TRIANGLES`] triangles,
//! counted before any is built; the whole scene (each object as often as
//! it is placed) has at most [`MAX_TRIANGLES`](zline_scene::MAX_TRIANGLES)
//! triangles and [`MAX_VERTICES`](zline_scene::MAX_VERTICES) vertices.
//!
//! The format is documented on [`load_scene`].

use std::path::{Path, PathBuf};

use glam::{EulerRot, Mat4, Quat, Vec3};
use serde::Deserialize;
use zline_scene::{
    cube, plane, torus, uv_sphere, Camera, Mesh, Object, Scene, ShadowPlane, MAX_PRIMITIVE_TRIANGLES,
};

use zline_shading::{Fog, Material, ShadingMode};

use crate::culling::default_culling;
use crate::error::{line_column, SceneError};
use crate::files::{read_text, resolve, FileKind, LoadOptions};
use crate::framing::{aspect, bounds_of, default_lights, model_camera, DEFAULT_AMBIENT, DEFAULT_BACKGROUND};

mod bump;
mod checks;
mod lights;
mod material;
mod models;
mod radiosity;
mod raytrace;
mod render;
mod view;
mod visibility;

use checks::{Checker, Result, S};
use lights::{LightDef, LightEntry};
use material::MaterialDef;
use models::{ModelCache, ModelPart};
use render::{settings, shadows, RenderDef, ShadingDef};
use view::{CameraDef, EnvironmentDef, FogDef};

/// Loads a TOML scene file. Warnings about model files (a missing MTL
/// file, say) are printed to stderr as `warning: ...` lines.
/// `examples/scene.toml` is a commented example of the whole format.
///
/// The format, every key optional unless marked required:
///
/// ```toml
/// background = [0.05, 0.05, 0.08]   # RGB in [0, 1]; default dark grey
/// ambient = [0.1, 0.1, 0.1]         # Ia, ≥ 0; default 0.15
///
/// [render]
/// width = 800                       # 1..=16384; default 800 × 600
/// height = 600
/// shading = "phong"                 # flat | gouraud | phong (default)
/// interpolation = "perspective"     # perspective (default) | linear
/// filter = "trilinear"              # nearest | bilinear | trilinear: replaces every texture's own
/// ssaa = 1                          # n×n supersampling, 1..=8; default 1 (off)
/// depth = "normalized"              # normalized (default) | reversed (reversed-Z float)
/// adaptive = 0.5                    # adaptive mode's tolerance in 8-bit units, in [0, 255]; default off
/// gouraud_clamp = "vertex"          # vertex (default) | sample: where untextured Gouraud clamps (SPEC §11)
/// lighting = "two-sided"            # two-sided (default) | one-sided: back faces drawn without culling
/// shadows = "planar"                # none (default) | planar: shadows cast on the shadow_plane objects |
///                                   #   map: shadow maps, every object casts and receives
/// shadow_map_size = 1024            # map: texels per side (per cube face for a point light), 16..=8192; default 1024
/// shadow_filter = "pcf"             # map: pcf (3×3 percentage-closer filtering, default) | nearest (one texel)
/// visibility = "zbuffer"           # zbuffer (default) | painter: sorted by farthest depth, no depth buffer
/// wireframe = "none"                # none (default) | all | hidden-removed | hidden-dashed: mesh edges as lines
/// wireframe_only = false            # true: the lines alone on the background
/// feature_angle = 30                # degrees in [0, 180]: only borders, silhouettes, sharper creases; default every edge
/// transparent_background = false    # true: RGBA output, alpha 0 where nothing is drawn, alpha = coverage
/// tonemap = "none"                  # none | khr-pbr-neutral | aces (SPEC §10; the last two end in sRGB)
/// exposure = 1.0                    # multiplies the colour before the tone mapping, ≥ 0
/// renderer = "raster"               # raster (default) | raytrace: Whitted ray tracing (SPEC §12) | radiosity (SPEC §13)
///
/// [raytrace]                        # the ray tracer's settings (used when it draws)
/// depth = 8                         # the ray tree's depth limit, 1..=64; default 8
/// min_weight = 0.002                # branches lighter than this are cut, in [0, 1]; default 1/512
/// shadow_rays = "filtered"          # filtered (default: kt of transparent surfaces passes) | opaque
/// accel = "bvh"                     # bvh (default) | kd | grid | none (brute force)
/// rays_per_axis = 1                 # n×n camera rays a pixel on a regular grid, 1..=16; default 1
/// adaptive = false                  # true: the course's adaptive supersampling instead
/// adaptive_depth = 3                # cuts of a pixel at most, 0..=4 (implies adaptive)
/// adaptive_threshold = 0.0625       # display-value difference that cuts a square, in [0, 1]
///
/// [radiosity]                       # radiosity's settings (used when it draws)
/// patch_size = 0.25                 # the longest patch edge in world units, > 0; default 1/16 of the scene
/// hemicube = 100                    # pixels along the hemicube's top face, 2..=2048; default 100
/// solver = "progressive"            # progressive (default) | jacobi | gauss-seidel
/// tolerance = 0.001                 # stop at this share of the source power left to move, in [0, 1]
/// analytic_near = false             # true: near patches' form factors by the contour integral, not the hemicube
/// subdivide = 0                    # times to cut patches where radiosity changes fast and solve again, 0..=4
/// lights = true                     # false: only emitting surfaces light the scene, not its lights
///
/// [camera]                          # omitted: the scene is framed
/// eye = [0, 1, 5]                   # required
/// target = [0, 0, 0]                # default the origin
/// up = [0, 1, 0]                    # default +Y
/// projection = "perspective"        # perspective (default) | orthographic
/// fovy = 45                         # degrees, in (0, 180); default 45
/// height = 4.0                      # orthographic: view height; default fits the scene
/// near = 0.1                        # default: fitted to the scene's bounding sphere
/// far = 100
///
/// [[lights]]                        # no [[lights]] at all: a default key and fill light;
/// type = "point"                    # `lights = []`: no lights
/// position = [2, 3, 4]              # required for point lights
/// color = [1, 0.9, 0.8]             # Il, ≥ 0; default white
/// attenuation = [1.0, 0.05, 0.0]    # a0 a1 a2 ≥ 0; default [1, 0, 0] (none)
/// range = 10                        # > 0: the light fades out by this distance (KHR_lights_punctual's
///                                   #   window, SPEC §5.1); default none. Point, spot and area lights
/// [[lights]]
/// type = "spot"                     # a point light shining into a cone (SPEC §5.1)
/// position = [0, 4, 0]              # required
/// direction = [0, -1, 0]            # required: the way the spot points
/// inner_angle = 20                  # degrees from the axis, full intensity within; default 0
/// outer_angle = 30                  # degrees, none past it, ≤ 90 and > inner_angle; default 45
/// [[lights]]
/// type = "directional"
/// direction = [-1, -1, -1]          # required: the way the light travels
/// color = [0.3, 0.3, 0.4]
/// [[lights]]                        # an area light (SPEC §5): k × k point lights at
/// type = "rect"                     #   the centres of a grid over it, each colour/k²
/// position = [0, 3, 0]              # required: the centre
/// u = [0.5, 0, 0]                   # required: half of one edge
/// v = [0, 0, 0.5]                   # required: half of the other
/// samples = 4                       # k, samples per side, 1..=16, or "auto"; default 4 (16 lights)
/// tolerance = 1.0                   # with "auto": the fewest k whose light differs from 16 × 16 by
///                                   #   at most this RMSE in 8-bit steps on the visible surfaces
///                                   #   (diffuse, white; shadows as the scene models them); default 1
/// color = [1, 1, 1]                 # the whole light's Il; attenuation as for points
/// [[lights]]
/// type = "disc"                     # a disc: position, normal, radius; samples as rect
/// position = [0, 3, 0]
/// normal = [0, -1, 0]
/// radius = 0.4
///
/// [fog]                             # optional (SPEC §8); no table, no fog
/// mode = "linear"                   # required: linear | exp | exp2
/// start = 10                        # linear: f = (end − z)/(end − start); default 0
/// end = 50                          # linear, ≥ start; default 1
/// # density = 0.05                  # exp: f = e^(−ρz), exp2: f = e^(−(ρz)²); default 1
/// color = [0.7, 0.75, 0.8]          # C_fog in [0, 1]; default 0.5 grey
/// coordinate = "eye-plane"          # eye-plane (−z_eye, default) | radial (|p_eye|)
///
/// [environment]                     # optional (SPEC §5.3): light from every direction
/// file = "studio.hdr"               # required: a Radiance HDR equirectangular panorama, or "sky"
///                                   #   (the built-in procedural sky)
/// intensity = 1.0                   # multiplies its radiance, ≥ 0; default 1
/// rotation = 0                      # degrees about +y, counter-clockwise from above; default 0
/// background = true                 # drawn where no surface is; default false
///
/// [[objects]]                       # at least one
/// model = "models/suzanne.obj"      # an OBJ, glTF, GLB, STL or PLY file (glTF: its nodes, not its camera or lights), or else:
/// # primitive = "sphere"            # rings (32), segments (64), radius (1)
/// # primitive = "plane"             # size (10), subdivisions (8)
/// # primitive = "cube"              # size (1)
/// # primitive = "torus"             # major_radius (1), minor_radius (0.25), rings (48), segments (24)
/// translate = [0, 0, 0]
/// rotate = [0, 30, 0]               # degrees about x, then y, then z
/// scale = 1.0                       # or [sx, sy, sz]; no zero factors
/// shading = "gouraud"               # overrides [render] shading
/// cull_back_faces = true            # default: true for closed, opaque meshes
/// shadow_plane = true               # receives planar shadows (casts none); must be flat; default false
/// bump = "textures/bumps.png"       # a height map (red channel) on every mesh with texture coordinates;
/// bump_scale = 1.0                  #   k, a white texel's height in texture units (default 1); Phong only
/// [objects.material]                # overrides, applied to every mesh of the model
/// color = [0.8, 0.2, 0.2]           # sets ka and kd together
/// ka = [0.8, 0.2, 0.2]              # in [0, 1]
/// kd = [0.8, 0.2, 0.2]
/// ks = [0.5, 0.5, 0.5]
/// ke = [0, 0, 0]                    # emission, added unlit
/// ns = 32                           # ≥ 0
/// opacity = 1.0                     # in [0, 1]
/// model = "cook-torrance"           # basic | cook-torrance (SPEC §5.2, kd the base colour); default
///                                   #   the mesh's own (glTF, and MTL with Pr/Pm, load as cook-torrance)
/// metallic = 0.0                    # in [0, 1]; a basic material switched takes 0
/// roughness = 0.5                   # in [0, 1]; switched: 0.5
/// distribution = "ggx"              # ggx | beckmann; switched: ggx. These three imply
///                                   #   model = "cook-torrance" and are errors with model = "basic"
/// ```
///
/// `shadow_plane = true` makes each mesh of the object a receiver of
/// [`ShadowMode::Planar`](zline_scene::ShadowMode) shadows, on the plane its
/// placed vertices lie on ([`ShadowPlane::of_object`]); a mesh that is not
/// flat, or has no triangle of positive area, is an error. The planes are
/// kept whatever `[render] shadows` says: the mode decides whether they are
/// used (the CLI's `--shadows` can turn them on).
///
/// Near and far, when not given, hug the bounding sphere of the scene seen
/// from the eye (near = max(d − 1.1·r, far·10⁻⁴)), as [`framing_camera`](crate::framing_camera)
/// does.
pub fn load_scene(path: &Path) -> Result<Scene, SceneError> {
    load_scene_with_options(path, LoadOptions::default())
}

/// [`load_scene`] with options (files outside the scene's folder).
pub fn load_scene_with_options(path: &Path, options: LoadOptions) -> Result<Scene, SceneError> {
    let text = read_text(path, FileKind::Text).map_err(|e| e.into_error(path))?;
    parse_scene(path, &text, options)
}

/// Loads scene-file text read from `path` (which names the file in
/// messages and locates the models it names).
pub(crate) fn parse_scene(path: &Path, text: &str, options: LoadOptions) -> Result<Scene, SceneError> {
    let file: SceneFile = toml::from_str(text).map_err(|e| toml_error(path, text, &e))?;
    let check = Checker { path, text };
    let (models, textures) = (ModelCache::default(), Default::default());
    Builder { check, models, options, primitive_triangles: 0, textures }.scene(file)
}

fn toml_error(path: &Path, text: &str, e: &toml::de::Error) -> SceneError {
    let message = e.message().trim().replace('\n', " ");
    match e.span() {
        Some(span) => SceneError::at_offset(path.to_path_buf(), text, span.start, message),
        None => SceneError::File { path: path.to_path_buf(), message },
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    background: Option<S<[f32; 3]>>,
    ambient: Option<S<[f32; 3]>>,
    render: Option<RenderDef>,
    raytrace: Option<raytrace::RayTraceDef>,
    radiosity: Option<radiosity::RadiosityDef>,
    camera: Option<S<CameraDef>>,
    lights: Option<Vec<S<LightDef>>>,
    fog: Option<S<FogDef>>,
    environment: Option<S<EnvironmentDef>>,
    #[serde(default)]
    objects: Vec<S<ObjectDef>>,
}

#[derive(Clone, Copy, Deserialize, PartialEq)]
#[serde(rename_all = "lowercase")]
enum PrimitiveKind {
    Sphere,
    Plane,
    Cube,
    Torus,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ObjectDef {
    model: Option<S<String>>,
    primitive: Option<S<PrimitiveKind>>,
    rings: Option<S<u32>>,
    segments: Option<S<u32>>,
    radius: Option<S<f32>>,
    size: Option<S<f32>>,
    subdivisions: Option<S<u32>>,
    major_radius: Option<S<f32>>,
    minor_radius: Option<S<f32>>,
    translate: Option<S<[f32; 3]>>,
    rotate: Option<S<[f32; 3]>>,
    scale: Option<S<ScaleDef>>,
    shading: Option<ShadingDef>,
    cull_back_faces: Option<bool>,
    shadow_plane: Option<S<bool>>,
    material: Option<MaterialDef>,
    bump: Option<S<String>>,
    bump_scale: Option<S<f32>>,
}

#[derive(Clone, Copy, Deserialize)]
#[serde(untagged, expecting = "a number or an array of 3 numbers [sx, sy, sz]")]
enum ScaleDef {
    Uniform(f32),
    PerAxis([f32; 3]),
}

/// Turns the parsed file into a scene, validating as it goes.
struct Builder<'a> {
    check: Checker<'a>,
    models: ModelCache,
    options: LoadOptions,
    /// The triangles of the primitives built so far.
    primitive_triangles: u64,
    /// Bump map images, each decoded once.
    textures: crate::texture_file::TextureCache,
}

impl Builder<'_> {
    fn scene(mut self, file: SceneFile) -> Result<Scene> {
        let mut shadows = shadows(&self.check, file.render.as_ref())?;
        let mut settings = settings(&self.check, file.render)?;
        settings.trace = raytrace::options(&self.check, file.raytrace)?;
        settings.radiosity = radiosity::options(&self.check, file.radiosity)?;
        let background = match &file.background {
            Some(c) => self.check.vec3_in(c, "background", 0.0, 1.0)?,
            None => DEFAULT_BACKGROUND,
        };
        let ambient = match &file.ambient {
            Some(c) => self.check.vec3_in(c, "ambient", 0.0, f32::INFINITY)?,
            None => DEFAULT_AMBIENT,
        };
        let entries = match &file.lights {
            Some(lights) => lights
                .iter()
                .enumerate()
                .map(|(i, l)| self.light(l, &format!("lights[{i}]")))
                .collect::<Result<Vec<_>>>()?,
            None => vec![LightEntry::Lights(default_lights())],
        };
        if file.objects.is_empty() {
            return Err(self.check.file_error("no [[objects]]: a scene needs at least one object"));
        }
        let mut objects: Vec<Object> = Vec::new();
        let mut planes = Vec::new();
        let (mut triangles, mut vertices) = (0, 0);
        for (i, def) in file.objects.iter().enumerate() {
            let placed = self.objects(def, &format!("objects[{i}]"))?;
            // Checked as the objects come, so that a scene naming many
            // large models stops at the first one too many.
            triangles += placed.iter().map(|o| o.mesh.triangles.len()).sum::<usize>();
            vertices += placed.iter().map(|o| o.mesh.positions.len()).sum::<usize>();
            SceneError::check_size(self.check.path, triangles, vertices)?;
            if let Some(flag) = def.get_ref().shadow_plane.as_ref().filter(|f| *f.get_ref()) {
                let key = format!("objects[{i}].shadow_plane");
                planes.extend(self.shadow_planes(flag, &key, &placed, objects.len())?);
            }
            objects.extend(placed);
        }
        let (min, max) = world_bounds(&objects);
        let camera = match &file.camera {
            Some(def) => self.camera(def, (min, max), aspect(&settings))?,
            None => model_camera(&objects, aspect(&settings)),
        };
        let fog = file.fog.as_ref().map(|f| self.fog(f)).transpose()?;
        let environment =
            file.environment.as_ref().map(|e| view::environment(&self.check, e, self.options)).transpose()?;
        shadows.planes = planes;
        let scene = Scene {
            shadows,
            camera,
            background,
            ambient,
            lights: Vec::new(),
            environment,
            objects,
            settings,
            fog,
        };
        Ok(lights::resolve(scene, entries, self.check.path))
    }

    /// The receiving planes of an entry with `shadow_plane = true`: one per
    /// placed mesh, `first` being the index the first will have in the
    /// scene; an error when one is not flat.
    fn shadow_planes(
        &self,
        flag: &S<bool>,
        key: &str,
        placed: &[Object],
        first: usize,
    ) -> Result<Vec<ShadowPlane>> {
        placed
            .iter()
            .enumerate()
            .map(|(j, object)| {
                ShadowPlane::of_object(first + j, object).ok_or_else(|| {
                    let why = if has_area(object) {
                        "its vertices are not on one plane"
                    } else {
                        "it has no triangle of positive area"
                    };
                    let message = match placed.len() {
                        1 => format!("needs a flat object: {why}"),
                        n => format!(
                            "needs a flat object: mesh {} of {n} ('{}') is not: {why}",
                            j + 1,
                            object.mesh.name
                        ),
                    };
                    self.check.error(flag.span(), key, message)
                })
            })
            .collect()
    }

    /// The `[camera]` table (see [`view::camera`]).
    fn camera(&self, def: &S<CameraDef>, bounds: (Vec3, Vec3), aspect: f32) -> Result<Camera> {
        view::camera(&self.check, def, bounds, aspect)
    }

    /// The `[fog]` table (see [`view::fog`]).
    fn fog(&self, def: &S<FogDef>) -> Result<Fog> {
        view::fog(&self.check, def)
    }

    /// One `[[lights]]` entry (see [`lights::light`]).
    fn light(&self, def: &S<LightDef>, key: &str) -> Result<LightEntry> {
        lights::light(&self.check, def, key)
    }

    /// The objects of one `[[objects]]` entry: one per mesh of its model.
    fn objects(&mut self, def: &S<ObjectDef>, key: &str) -> Result<Vec<Object>> {
        let o = def.get_ref();
        let parts = match (&o.model, &o.primitive) {
            (Some(model), None) => self.model(o, model, key)?,
            (None, Some(kind)) => vec![ModelPart::alone(self.primitive(o, kind, key)?)],
            (Some(_), Some(_)) => {
                return Err(self.check.error(def.span(), key, "give 'model' or 'primitive', not both"))
            }
            (None, None) => return Err(self.check.error(def.span(), key, "needs 'model' or 'primitive'")),
        };
        let bump_keys = bump::BumpKeys { file: o.bump.as_ref(), scale: &o.bump_scale };
        let parts = bump::apply(&self.check, (self.options, &mut self.textures), bump_keys, key, parts)?;
        let world_from_object = self.transform(o, key)?;
        let shading = o.shading.map(ShadingMode::from);
        let material_def = o.material.as_ref();
        let mut objects = Vec::with_capacity(parts.len());
        for ModelPart { mesh, model_from_mesh, cullable } in parts {
            let material = material_def.map(|m| self.material(m, mesh.material, key)).transpose()?;
            let opacity = material.unwrap_or(mesh.material).opacity;
            let cull_back_faces =
                o.cull_back_faces.unwrap_or_else(|| cullable && default_culling(&mesh, opacity));
            let world_from_object = world_from_object * model_from_mesh;
            objects.push(Object { mesh, world_from_object, material, shading, cull_back_faces });
        }
        Ok(objects)
    }

    fn model(&mut self, o: &ObjectDef, model: &S<String>, key: &str) -> Result<Vec<ModelPart>> {
        for (value, name) in
            [(&o.rings, "rings"), (&o.segments, "segments"), (&o.subdivisions, "subdivisions")]
        {
            self.check.not_allowed(value, key, name, "models")?;
        }
        for (value, name) in [
            (&o.radius, "radius"),
            (&o.size, "size"),
            (&o.major_radius, "major_radius"),
            (&o.minor_radius, "minor_radius"),
        ] {
            self.check.not_allowed(value, key, name, "models")?;
        }
        let model_path: PathBuf = resolve(self.check.path, Path::new(model.get_ref()), self.options)
            .map_err(|why| self.check.error(model.span(), &format!("{key}.model"), why))?;
        self.models.get(&model_path, self.options).map_err(|source| {
            let (line, column) = line_column(self.check.text, model.span().start);
            SceneError::Referenced {
                scene: self.check.path.to_path_buf(),
                line,
                column,
                key: format!("{key}.model"),
                source: Box::new(source),
            }
        })
    }

    fn primitive(&mut self, o: &ObjectDef, kind_def: &S<PrimitiveKind>, key: &str) -> Result<Mesh> {
        use PrimitiveKind::*;
        let kind = *kind_def.get_ref();
        let what = match kind {
            Sphere => "spheres",
            Plane => "planes",
            Cube => "cubes",
            Torus => "tori",
        };
        let count = |v: &Option<S<u32>>, name: &str, uses: &[PrimitiveKind], default: u32, min: u32| {
            if !uses.contains(&kind) {
                return self.check.not_allowed(v, key, name, what).map(|()| 0);
            }
            self.check.count(v, &format!("{key}.{name}"), default, min)
        };
        let length = |v: &Option<S<f32>>, name: &str, uses: &[PrimitiveKind], default: f32| {
            if !uses.contains(&kind) {
                return self.check.not_allowed(v, key, name, what).map(|()| 0.0);
            }
            self.check.positive(v, &format!("{key}.{name}"), default)
        };
        let (default_rings, min_rings) = if kind == Torus { (48, 3) } else { (32, 2) };
        let rings = count(&o.rings, "rings", &[Sphere, Torus], default_rings, min_rings)?;
        let segments =
            count(&o.segments, "segments", &[Sphere, Torus], if kind == Torus { 24 } else { 64 }, 3)?;
        let subdivisions = count(&o.subdivisions, "subdivisions", &[Plane], 8, 1)?;
        let radius = length(&o.radius, "radius", &[Sphere], 1.0)?;
        let size = length(&o.size, "size", &[Plane, Cube], if kind == Plane { 10.0 } else { 1.0 })?;
        let major = length(&o.major_radius, "major_radius", &[Torus], 1.0)?;
        let minor = length(&o.minor_radius, "minor_radius", &[Torus], 0.25)?;
        // Counted before building: the budget bounds the tessellation's
        // time and memory.
        let (r, s, n) = (u64::from(rings), u64::from(segments), u64::from(subdivisions));
        let triangles = match kind {
            Sphere => 2 * s * (r - 1),
            Plane => 2 * n * n,
            Cube => 12,
            Torus => 2 * r * s,
        };
        self.primitive_triangles += triangles;
        if self.primitive_triangles > MAX_PRIMITIVE_TRIANGLES {
            return Err(self.check.error(
                kind_def.span(),
                key,
                format!(
                    "this {} makes {triangles} triangles, which brings the scene's primitives to {}, more \
                     than the limit of {MAX_PRIMITIVE_TRIANGLES} (use fewer rings, segments or subdivisions)",
                    what.trim_end_matches('s').replace("tori", "torus"),
                    self.primitive_triangles
                ),
            ));
        }
        Ok(match kind {
            Sphere => uv_sphere(rings, segments, radius),
            Plane => plane(size, subdivisions),
            Cube => cube(size),
            Torus => torus(major, minor, rings, segments),
        })
    }

    fn transform(&self, o: &ObjectDef, key: &str) -> Result<Mat4> {
        let translate = o
            .translate
            .as_ref()
            .map_or(Ok(Vec3::ZERO), |t| self.check.vec3(t, &format!("{key}.translate")))?;
        let rotate =
            o.rotate.as_ref().map_or(Ok(Vec3::ZERO), |r| self.check.vec3(r, &format!("{key}.rotate")))?;
        let scale = match &o.scale {
            None => Vec3::ONE,
            Some(s) => {
                let v = match *s.get_ref() {
                    ScaleDef::Uniform(f) => Vec3::splat(f),
                    ScaleDef::PerAxis(a) => Vec3::from(a),
                };
                if !v.is_finite() || v.cmpeq(Vec3::ZERO).any() {
                    return Err(self.check.error(
                        s.span(),
                        &format!("{key}.scale"),
                        format!("must be finite and non-zero, got {v}"),
                    ));
                }
                v
            }
        };
        // Rotate about x first, then y, then z: R = Rz · Ry · Rx.
        let [rx, ry, rz] = rotate.to_array().map(f32::to_radians);
        let rotation = Quat::from_euler(EulerRot::ZYX, rz, ry, rx);
        Ok(Mat4::from_scale_rotation_translation(scale, rotation, translate))
    }

    /// An object's `[objects.material]` table (see [`material::material`]).
    fn material(&self, def: &MaterialDef, base: Material, key: &str) -> Result<Material> {
        material::material(&self.check, def, base, key)
    }
}

/// True when the object has a triangle of positive, finite area in world
/// space (what [`ShadowPlane::of_object`] needs besides flatness).
fn has_area(object: &Object) -> bool {
    let world =
        |i: u32| object.mesh.positions.get(i as usize).map(|&p| object.world_from_object.transform_point3(p));
    object.mesh.triangles.iter().any(|t| match (world(t[0]), world(t[1]), world(t[2])) {
        (Some(a), Some(b), Some(c)) => {
            let n = (b - a).cross(c - a);
            n.length_squared() > 0.0 && n.is_finite()
        }
        _ => false,
    })
}

/// The world-space bounding box of the objects (the transformed corners of
/// each mesh's box).
fn world_bounds(objects: &[Object]) -> (Vec3, Vec3) {
    let corners = objects.iter().flat_map(|o| {
        let (lo, hi) = o.mesh.bounds();
        (0..8).map(move |i| {
            let pick = glam::BVec3::new(i & 1 != 0, i & 2 != 0, i & 4 != 0);
            o.world_from_object.transform_point3(Vec3::select(pick, hi, lo))
        })
    });
    bounds_of(corners).unwrap_or((Vec3::ZERO, Vec3::ZERO))
}
