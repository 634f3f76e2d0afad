//! What a model or scene file holds, for `zline info`: triangles,
//! vertices, bounds, materials, textures, lights, camera and the loader's
//! warnings — as text for people or JSON for scripts.

use std::fmt::Write as _;

use glam::Vec3;
use serde::Serialize;
use zline_scene::Scene;
use zline_shading::{Light, Material, Model};

/// A loaded file described.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ModelInfo {
    /// The file as given.
    pub file: String,
    /// Its format: OBJ, glTF, GLB, STL, PLY or scene file.
    pub format: String,
    /// Triangles over all objects (each placement counted).
    pub triangles: usize,
    /// Vertices over all objects (each placement counted).
    pub vertices: usize,
    /// Objects (mesh placements).
    pub objects: usize,
    /// World-space bounds of every finite vertex, or `None` without any.
    pub bounds: Option<Bounds>,
    /// The distinct materials, in first-use order.
    pub materials: Vec<MaterialInfo>,
    /// The distinct diffuse textures, in first-use order.
    pub textures: Vec<TextureInfo>,
    /// The file's lights (`None`: it has none, and zline adds its key and
    /// fill lights).
    pub lights: Option<Vec<LightInfo>>,
    /// The file's camera (`None`: it has none, and zline frames the model).
    pub camera: Option<CameraInfo>,
    /// The loader's warnings.
    pub warnings: Vec<String>,
}

/// An axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Bounds {
    /// The least corner.
    pub min: [f32; 3],
    /// The greatest corner.
    pub max: [f32; 3],
}

/// A material's coefficients and the meshes using it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MaterialInfo {
    /// The first mesh using it (OBJ group, glTF mesh or file name).
    pub first_mesh: String,
    /// How many objects use it.
    pub objects: usize,
    /// Diffuse colour kd.
    pub kd: [f32; 3],
    /// Specular colour ks.
    pub ks: [f32; 3],
    /// Shininess ns.
    pub ns: f32,
    /// Opacity (1 opaque).
    pub opacity: f32,
    /// Whether it emits (ke ≠ 0).
    pub emissive: bool,
    /// The reflection model: `basic` or `cook-torrance` ([`Model::name`]).
    pub model: &'static str,
    /// The Cook–Torrance parameters (`None` with the basic model, whose
    /// coefficients are kd, ks and ns; Cook–Torrance uses kd as its base
    /// colour and neither ks nor ns).
    pub microfacet: Option<MicrofacetInfo>,
}

/// A Cook–Torrance material's parameters besides its base colour.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MicrofacetInfo {
    /// The distribution: `ggx` or `beckmann`.
    pub distribution: &'static str,
    /// Metallic, in [0, 1].
    pub metallic: f32,
    /// Perceptual roughness, in [0, 1].
    pub roughness: f32,
}

/// A texture's size.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TextureInfo {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Mip levels built.
    pub levels: usize,
    /// How many objects use it.
    pub objects: usize,
}

/// A light.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LightInfo {
    /// `point` or `directional`.
    pub kind: &'static str,
    /// The position (point) or direction of travel (directional).
    pub vector: [f32; 3],
    /// Its colour Il.
    pub color: [f32; 3],
}

/// A camera.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CameraInfo {
    /// The eye.
    pub eye: [f32; 3],
    /// The point looked at.
    pub target: [f32; 3],
    /// `perspective` or `orthographic`.
    pub projection: &'static str,
}

impl ModelInfo {
    /// Describes `scene`, loaded from `file` (of `format`). `own_lights`
    /// and `own_camera` say whether the file brought them (else the scene
    /// holds zline's defaults, which are not listed).
    pub fn of_scene(
        file: &str,
        format: &str,
        scene: &Scene,
        own_lights: bool,
        own_camera: bool,
        warnings: Vec<String>,
    ) -> ModelInfo {
        let mut min = Vec3::splat(f32::INFINITY);
        let mut max = Vec3::splat(f32::NEG_INFINITY);
        let (mut triangles, mut vertices) = (0, 0);
        let mut materials: Vec<(Material, MaterialInfo)> = Vec::new();
        let mut textures: Vec<(*const zline_shading::Texture, TextureInfo)> = Vec::new();
        for object in &scene.objects {
            let mesh = &object.mesh;
            triangles += mesh.triangles.len();
            vertices += mesh.positions.len();
            for p in &mesh.positions {
                let w = object.world_from_object.transform_point3(*p);
                if w.is_finite() {
                    (min, max) = (min.min(w), max.max(w));
                }
            }
            let material = object.material();
            match materials.iter_mut().find(|(m, _)| *m == material) {
                Some((_, info)) => info.objects += 1,
                None => materials.push((
                    material,
                    MaterialInfo {
                        first_mesh: mesh.name.clone(),
                        objects: 1,
                        kd: material.kd.to_array(),
                        ks: material.ks.to_array(),
                        ns: material.ns,
                        opacity: material.opacity,
                        emissive: material.ke != Vec3::ZERO,
                        model: material.model.name(),
                        microfacet: match material.model {
                            Model::Basic => None,
                            Model::CookTorrance(m) => Some(MicrofacetInfo {
                                distribution: m.distribution.name(),
                                metallic: m.metallic,
                                roughness: m.roughness,
                            }),
                        },
                    },
                )),
            }
            if let Some(map) = mesh.diffuse_map.as_ref().filter(|_| !mesh.uvs.is_empty()) {
                let key = std::sync::Arc::as_ptr(&map.texture);
                match textures.iter_mut().find(|(k, _)| *k == key) {
                    Some((_, info)) => info.objects += 1,
                    None => textures.push((
                        key,
                        TextureInfo {
                            width: map.texture.width(),
                            height: map.texture.height(),
                            levels: map.texture.levels(),
                            objects: 1,
                        },
                    )),
                }
            }
        }
        let lights = own_lights.then(|| scene.lights.iter().map(light_info).collect());
        let camera = own_camera.then(|| CameraInfo {
            eye: scene.camera.eye.to_array(),
            target: scene.camera.target.to_array(),
            projection: match scene.camera.projection {
                zline_scene::Projection::Perspective { .. } => "perspective",
                zline_scene::Projection::Orthographic { .. } => "orthographic",
                zline_scene::Projection::Frustum { .. } => "frustum",
            },
        });
        ModelInfo {
            file: file.to_string(),
            format: format.to_string(),
            triangles,
            vertices,
            objects: scene.objects.len(),
            bounds: min.cmple(max).all().then(|| Bounds { min: min.to_array(), max: max.to_array() }),
            materials: materials.into_iter().map(|(_, i)| i).collect(),
            textures: textures.into_iter().map(|(_, i)| i).collect(),
            lights,
            camera,
            warnings,
        }
    }

    /// The description for people, one fact per line.
    pub fn text(&self) -> String {
        let mut s = String::new();
        let v = |a: [f32; 3]| format!("({}, {}, {})", short(a[0]), short(a[1]), short(a[2]));
        let _ = writeln!(s, "{} ({})", self.file, self.format);
        let _ = writeln!(s, "  triangles  {}", self.triangles);
        let _ = writeln!(s, "  vertices   {}", self.vertices);
        let _ = writeln!(s, "  objects    {}", self.objects);
        match &self.bounds {
            Some(b) => {
                let size = Vec3::from(b.max) - Vec3::from(b.min);
                let _ = writeln!(
                    s,
                    "  bounds     {} .. {}, size {} × {} × {}",
                    v(b.min),
                    v(b.max),
                    short(size.x),
                    short(size.y),
                    short(size.z)
                );
            }
            None => {
                let _ = writeln!(s, "  bounds     none (no finite vertex)");
            }
        }
        let _ = writeln!(s, "  materials  {}", self.materials.len());
        for m in &self.materials {
            // The coefficients the model uses: kd, ks and ns for the basic
            // one, the parameters and the base colour kd for Cook–Torrance.
            let coefficients = match &m.microfacet {
                None => format!("kd {}, ks {}, ns {}", v(m.kd), v(m.ks), short(m.ns)),
                Some(f) => format!(
                    "{} ({}, metallic {}, roughness {}), kd {}",
                    m.model,
                    f.distribution,
                    short(f.metallic),
                    short(f.roughness),
                    v(m.kd)
                ),
            };
            let _ = writeln!(
                s,
                "    '{}' ({}): {coefficients}{}{}",
                m.first_mesh,
                count(m.objects, "object"),
                if m.opacity < 1.0 { format!(", opacity {}", short(m.opacity)) } else { String::new() },
                if m.emissive { ", emissive" } else { "" }
            );
        }
        let _ = writeln!(s, "  textures   {}", self.textures.len());
        for t in &self.textures {
            let _ = writeln!(
                s,
                "    {} × {} ({}, {})",
                t.width,
                t.height,
                count(t.levels, "mip level"),
                count(t.objects, "object")
            );
        }
        match &self.lights {
            Some(lights) => {
                let _ = writeln!(s, "  lights     {}", lights.len());
                for l in lights {
                    let _ = writeln!(s, "    {} {}, colour {}", l.kind, v(l.vector), v(l.color));
                }
            }
            None => {
                let _ = writeln!(s, "  lights     none in the file (zline adds a key and a fill light)");
            }
        }
        match &self.camera {
            Some(c) => {
                let _ = writeln!(s, "  camera     {} from {} to {}", c.projection, v(c.eye), v(c.target));
            }
            None => {
                let _ = writeln!(s, "  camera     none in the file (zline frames the model)");
            }
        }
        let _ = writeln!(s, "  warnings   {}", self.warnings.len());
        for w in &self.warnings {
            let _ = writeln!(s, "    {w}");
        }
        s
    }
}

/// "1 object", "2 objects".
fn count(n: usize, what: &str) -> String {
    format!("{n} {what}{}", if n == 1 { "" } else { "s" })
}

fn light_info(light: &Light) -> LightInfo {
    match *light {
        Light::Point { position, color, .. } => {
            LightInfo { kind: "point", vector: position.to_array(), color: color.to_array() }
        }
        Light::Spot { position, color, .. } => {
            LightInfo { kind: "spot", vector: position.to_array(), color: color.to_array() }
        }
        Light::Directional { direction, color } => {
            LightInfo { kind: "directional", vector: direction.to_array(), color: color.to_array() }
        }
    }
}

/// A number for people: four significant digits, scientific when huge or
/// tiny.
fn short(x: f32) -> String {
    if x == 0.0 {
        "0".to_string()
    } else if (1e-3..1e6).contains(&x.abs()) {
        let digits = (3 - x.abs().log10().floor() as i32).clamp(0, 6) as usize;
        let s = format!("{x:.digits$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        format!("{x:.3e}")
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::Mat4;
    use zline_scene::{cube, Object, RenderSettings};

    use super::*;

    #[test]
    fn two_placed_cubes_are_counted_twice_and_bounded_together() {
        let object = |x: f32| Object {
            mesh: Arc::new(cube(2.0)),
            world_from_object: Mat4::from_translation(Vec3::new(x, 0.0, 0.0)),
            material: None,
            shading: None,
            cull_back_faces: true,
        };
        let scene = zline_io::scene_for_model(Vec::new(), RenderSettings::default());
        let scene = Scene { objects: vec![object(0.0), object(5.0)], ..scene };
        let info = ModelInfo::of_scene("two.toml", "scene file", &scene, false, false, vec!["w".into()]);
        assert_eq!((info.triangles, info.vertices, info.objects), (24, 48, 2));
        assert_eq!(info.bounds, Some(Bounds { min: [-1.0, -1.0, -1.0], max: [6.0, 1.0, 1.0] }));
        assert_eq!(info.materials.len(), 1);
        assert_eq!(info.materials[0].objects, 2);
        assert!(
            info.text().contains("bounds     (-1, -1, -1) .. (6, 1, 1), size 7 × 2 × 2"),
            "{}",
            info.text()
        );
        assert!(info.text().contains("lights     none in the file"));
    }

    #[test]
    fn each_material_says_its_model() {
        use zline_shading::{Distribution, Microfacet};
        let metal = Microfacet { metallic: 0.98, roughness: 0.3, distribution: Distribution::Ggx };
        let object = |material: Material| Object {
            mesh: Arc::new(cube(1.0)),
            world_from_object: Mat4::IDENTITY,
            material: Some(material),
            shading: None,
            cull_back_faces: true,
        };
        let basic = Material::plastic(Vec3::new(1.0, 0.5, 0.25), 0.5, 16.0);
        let gold = Material { model: Model::CookTorrance(metal), ..basic };
        let scene = zline_io::scene_for_model(Vec::new(), RenderSettings::default());
        let scene = Scene { objects: vec![object(basic), object(gold)], ..scene };
        let info = ModelInfo::of_scene("m.toml", "scene file", &scene, false, false, Vec::new());
        let text = info.text();
        assert!(
            text.contains("    'cube' (1 object): kd (1, 0.5, 0.25), ks (0.5, 0.5, 0.5), ns 16\n"),
            "{text}"
        );
        assert!(
            text.contains("    'cube' (1 object): cook-torrance (ggx, metallic 0.98, roughness 0.3), kd (1, 0.5, 0.25)\n"),
            "{text}"
        );
        let json = serde_json::to_value(&info).unwrap();
        let (a, b) = (&json["materials"][0], &json["materials"][1]);
        assert_eq!((a["model"].as_str(), a["microfacet"].is_null()), (Some("basic"), true));
        assert_eq!(b["model"], "cook-torrance");
        assert_eq!(b["microfacet"]["distribution"], "ggx");
        assert_eq!(b["microfacet"]["roughness"].as_f64(), Some(0.3f32 as f64));
    }

    #[test]
    fn numbers_read_well() {
        assert_eq!(short(0.0), "0");
        assert_eq!(short(1.5), "1.5");
        assert_eq!(short(0.123456), "0.1235");
        assert_eq!(short(1234.25), "1234");
        assert_eq!(short(1e30), "1.000e30");
    }
}
