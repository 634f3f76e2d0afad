//! glTF loading: the shipped sample models (counts, transforms, materials,
//! textures, t = 1 − v) and small generated files for the hierarchy,
//! cameras, lights, warnings and errors.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{Mat4, Quat, Vec2, Vec3};
use zline_io::{load_gltf, load_gltf_with_warnings, scene_for_gltf, GltfScene, FRAMING_FOVY_DEGREES};
use zline_scene::{Attenuation, Cone, Light, Projection, RenderSettings};
use zline_shading::{Filter, Sampler, Wrap};

use crate::{check_message, repo};

#[track_caller]
fn check_close(a: Vec3, b: Vec3) {
    assert!((a - b).length() < 1e-5, "{a} is not {b}");
}

fn triangle_count(scene: &GltfScene) -> usize {
    scene.objects.iter().map(|o| o.mesh.triangle_count()).sum()
}

#[test]
fn box_glb_has_its_node_matrix_and_material() {
    let (scene, warnings) = load_gltf_with_warnings(&repo("assets/gltf/Box/glTF-Binary/Box.glb")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(scene.objects.len(), 1);
    let object = &scene.objects[0];
    assert_eq!((object.mesh.triangle_count(), object.mesh.vertex_count()), (12, 24));
    // The root node turns glTF's +Y up into +Z (a −90° turn about X): y → −z.
    check_close(object.world_from_object.transform_point3(Vec3::Y), Vec3::NEG_Z);
    check_close(object.world_from_object.transform_point3(Vec3::Z), Vec3::Y);
    let m = object.material();
    assert_eq!((m.kd, m.ka), (Vec3::new(0.8, 0.0, 0.0), Vec3::new(0.8, 0.0, 0.0)));
    assert_eq!((m.ks, m.ns, m.opacity), (Vec3::ZERO, 1.0, 1.0), "roughness 1: no highlight");
    assert!(object.cull_back_faces, "closed, opaque, single-sided");
    assert!(object.mesh.uvs.is_empty() && object.mesh.diffuse_map.is_none());
    assert_eq!((scene.camera, scene.lights.len()), (None, 0));
}

#[test]
fn box_textured_has_uvs_and_its_texture() {
    let scene = load_gltf(&repo("assets/gltf/BoxTextured/glTF/BoxTextured.gltf")).unwrap();
    assert_eq!((scene.objects.len(), triangle_count(&scene)), (1, 12));
    let mesh = &scene.objects[0].mesh;
    assert_eq!(mesh.uvs.len(), 24);
    let map = mesh.diffuse_map.as_ref().unwrap();
    assert_eq!((map.texture.width(), map.texture.height()), (256, 256));
    // minFilter NEAREST_MIPMAP_LINEAR, REPEAT both ways.
    assert_eq!(
        map.sampler,
        Sampler { filter: Filter::Trilinear, wrap_s: Wrap::Repeat, wrap_t: Wrap::Repeat }
    );
    assert_eq!(mesh.material.kd, Vec3::ONE, "no baseColorFactor: white, modulated by the texture");
}

#[test]
fn embedded_box_textured_matches_the_external_one() {
    let external = load_gltf(&repo("assets/gltf/BoxTextured/glTF/BoxTextured.gltf")).unwrap();
    let (embedded, warnings) =
        load_gltf_with_warnings(&repo("assets/gltf/BoxTextured/glTF-Embedded/BoxTextured.gltf")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(embedded, external, "same meshes, uvs, texels, sampler and placement");
}

#[test]
fn texture_coordinate_test_flips_v_into_t() {
    let scene =
        load_gltf(&repo("assets/gltf/TextureCoordinateTest/glTF/TextureCoordinateTest.gltf")).unwrap();
    assert_eq!((scene.objects.len(), triangle_count(&scene)), (5, 10));
    assert!(scene.objects.iter().all(|o| !o.cull_back_faces), "every material is double-sided");
    let top_left = scene.objects.iter().find(|o| o.mesh.name == "TopLeftMesh").unwrap();
    assert_eq!(top_left.mesh.diffuse_map.as_ref().unwrap().texture.width(), 512);
    // The file's v runs from 0 to 0.4 over the top-left part of the image,
    // so t runs from 0.6 to 1, and up with y like SPEC §7's t.
    let uvs = &top_left.mesh.uvs;
    let (lo, hi) = uvs.iter().fold((Vec2::MAX, Vec2::MIN), |(lo, hi), &t| (lo.min(t), hi.max(t)));
    assert!((lo.y - 0.6).abs() < 1e-6 && (hi.y - 1.0).abs() < 1e-6, "t from {} to {}", lo.y, hi.y);
    assert!(lo.x.abs() < 1e-6 && (hi.x - 0.4).abs() < 1e-6, "s from {} to {}", lo.x, hi.x);
    let positions = &top_left.mesh.positions;
    for i in 0..uvs.len() {
        for j in 0..uvs.len() {
            if positions[i].y > positions[j].y + 1e-3 {
                assert!(uvs[i].y > uvs[j].y, "t must grow with y: {i} {j}");
            }
        }
    }
    let back = scene.objects.iter().find(|o| o.mesh.name == "BackPlaneMesh").unwrap();
    assert!(back.mesh.uvs.is_empty() && back.mesh.diffuse_map.is_none());
}

#[test]
fn bare_gltf_gets_a_framing_camera_and_default_lights() {
    let scene = scene_for_gltf(
        load_gltf(&repo("assets/gltf/Box/glTF-Binary/Box.glb")).unwrap(),
        RenderSettings::default(),
    );
    assert_eq!(scene.lights, zline_io::default_lights());
    let Projection::Perspective { fovy_degrees, .. } = scene.camera.projection else { panic!() };
    assert_eq!(fovy_degrees, FRAMING_FOVY_DEGREES);
    // The tight framing looks along the framing direction at a point
    // inside the unit box (the middle of its projection, not its centre).
    let view = (scene.camera.eye - scene.camera.target).normalize();
    check_close(view, zline_io::VIEW_DIRECTION.normalize());
    assert!(scene.camera.target.abs().max_element() < 0.5, "{}", scene.camera.target);
}

// ---- generated files ------------------------------------------------------

/// A unit quad in z = 0: POSITION (accessor 0), TEXCOORD_0 (1), u16
/// indices (2), in `quad.bin`.
pub(crate) fn quad_bin() -> Vec<u8> {
    let mut bytes = Vec::new();
    for p in [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]] {
        p.iter().for_each(|c| bytes.extend(c.to_le_bytes()));
    }
    for t in [[0f32, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] {
        t.iter().for_each(|c| bytes.extend(c.to_le_bytes()));
    }
    for i in [0u16, 1, 2, 0, 2, 3] {
        bytes.extend(i.to_le_bytes());
    }
    bytes
}

/// Writes `name/quad.gltf` (with `quad.bin`) in a fresh temporary
/// directory: the quad mesh (material 0 when `members` has materials),
/// plus the given top-level JSON members (nodes, scenes, …).
pub(crate) fn quad_gltf(name: &str, members: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("zline-io-tests-{}", std::process::id())).join(name);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("quad.bin"), quad_bin()).unwrap();
    let material = if members.contains("\"materials\"") { r#", "material": 0"# } else { "" };
    let json = format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "buffers": [{{"uri": "quad.bin", "byteLength": 92}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 48}},
    {{"buffer": 0, "byteOffset": 48, "byteLength": 32}},
    {{"buffer": 0, "byteOffset": 80, "byteLength": 12}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"}},
    {{"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}}
  ],
  "meshes": [{{"name": "quad", "primitives": [{{"attributes": {{"POSITION": 0, "TEXCOORD_0": 1}}, "indices": 2{material}}}]}}],
  {members}
}}"#
    );
    let path = dir.join("quad.gltf");
    std::fs::write(&path, json).unwrap();
    path
}

/// Replaces `from` by `to` in a file.
pub(crate) fn edit(path: &Path, from: &str, to: &str) {
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.contains(from), "{from:?} not in {}", path.display());
    std::fs::write(path, text.replace(from, to)).unwrap();
}

#[test]
fn node_transforms_accumulate_and_meshes_are_shared() {
    let path = quad_gltf(
        "hierarchy",
        r#""nodes": [
            {"translation": [1, 2, 3], "children": [1]},
            {"scale": [2, 2, 2], "rotation": [0, 0.7071068, 0, 0.7071068], "mesh": 0},
            {"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 5,0,0,1], "mesh": 0}
        ],
        "scenes": [{"nodes": [0, 2]}], "scene": 0"#,
    );
    let (scene, warnings) = load_gltf_with_warnings(&path).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(scene.objects.len(), 2);
    let expected = Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0))
        * Mat4::from_scale_rotation_translation(
            Vec3::splat(2.0),
            Quat::from_rotation_y(90f32.to_radians()),
            Vec3::ZERO,
        );
    assert!(scene.objects[0].world_from_object.abs_diff_eq(expected, 1e-5));
    // x → −z after the turn, doubled, then moved.
    check_close(scene.objects[0].world_from_object.transform_point3(Vec3::X), Vec3::new(1.0, 2.0, 1.0));
    check_close(scene.objects[1].world_from_object.transform_point3(Vec3::ZERO), Vec3::new(5.0, 0.0, 0.0));
    assert!(Arc::ptr_eq(&scene.objects[0].mesh, &scene.objects[1].mesh));
    assert!(!scene.objects[0].cull_back_faces, "an open quad is never culled");
}

#[test]
fn mirroring_nodes_reverse_the_winding() {
    let path = quad_gltf(
        "mirror",
        r#""nodes": [{"mesh": 0}, {"mesh": 0, "scale": [-1, 1, 1]}], "scenes": [{"nodes": [0, 1]}]"#,
    );
    let scene = load_gltf(&path).unwrap();
    let (plain, mirrored) = (&scene.objects[0].mesh, &scene.objects[1].mesh);
    assert_eq!(plain.triangles, [[0, 1, 2], [0, 2, 3]]);
    assert_eq!(mirrored.triangles, [[0, 2, 1], [0, 3, 2]]);
    assert_eq!(plain.normals, mirrored.normals, "normals are the file's geometry, not the winding's");
}

#[test]
fn the_first_camera_is_taken_and_an_infinite_one_gets_a_fitted_far_plane() {
    let path = quad_gltf(
        "camera",
        r#""nodes": [
            {"mesh": 0},
            {"camera": 0, "translation": [0.5, 0.5, 4]},
            {"camera": 1}
        ],
        "cameras": [
            {"type": "perspective", "perspective": {"yfov": 0.6, "znear": 0.1}},
            {"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 2, "znear": 0, "zfar": 10}}
        ],
        "scenes": [{"nodes": [0, 1, 2]}]"#,
    );
    let scene = load_gltf(&path).unwrap();
    let camera = scene.camera.unwrap();
    check_close(camera.eye, Vec3::new(0.5, 0.5, 4.0));
    check_close(camera.target, Vec3::new(0.5, 0.5, 3.0));
    check_close(camera.up, Vec3::Y);
    let Projection::Perspective { fovy_degrees, near, far } = camera.projection else { panic!() };
    assert!((fovy_degrees - 0.6f32.to_degrees()).abs() < 1e-4);
    assert_eq!(near, 0.1);
    // The farthest quad corner is √(0.5² + 0.5² + 4²) away.
    assert!((far - 16.5f32.sqrt() * 1.05).abs() < 1e-4, "{far}");
    let framed = scene_for_gltf(load_gltf(&path).unwrap(), RenderSettings::default());
    assert_eq!(framed.camera, camera, "the file's camera is kept");

    edit(&path, r#""nodes": [0, 1, 2]"#, r#""nodes": [0, 2, 1]"#);
    let camera = load_gltf(&path).unwrap().camera.unwrap();
    assert_eq!(camera.projection, Projection::Orthographic { height: 4.0, near: 0.0, far: 10.0 });
}

#[test]
fn punctual_lights_become_point_spot_and_directional_lights() {
    let path = quad_gltf(
        "lights",
        r#""extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "color": [1, 0.5, 0], "intensity": 2},
            {"type": "directional", "intensity": 3},
            {"type": "spot", "range": 5, "spot": {"innerConeAngle": 0.25, "outerConeAngle": 0.5}},
            {"type": "spot", "spot": {"innerConeAngle": 0.8, "outerConeAngle": 0.5}}
        ]}},
        "nodes": [
            {"mesh": 0},
            {"translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}},
            {"rotation": [0, 0.7071068, 0, 0.7071068], "extensions": {"KHR_lights_punctual": {"light": 1}}},
            {"rotation": [0, 0.7071068, 0, 0.7071068], "extensions": {"KHR_lights_punctual": {"light": 2}}},
            {"extensions": {"KHR_lights_punctual": {"light": 3}}}
        ],
        "scenes": [{"nodes": [0, 1, 2, 3, 4]}]"#,
    );
    let (gltf, warnings) = load_gltf_with_warnings(&path).unwrap();
    let inverse_square = Attenuation::new(0.0, 0.0, 1.0);
    assert_eq!(gltf.lights.len(), 4);
    let Light::Point { position, color, attenuation } = gltf.lights[0] else { panic!() };
    check_close(position, Vec3::new(1.0, 2.0, 3.0));
    assert_eq!((color, attenuation), (Vec3::new(2.0, 1.0, 0.0), inverse_square));
    let Light::Directional { direction, color } = gltf.lights[1] else { panic!() };
    check_close(direction, Vec3::NEG_X); // −z turned 90° about y
    assert_eq!(color, Vec3::splat(3.0));
    let Light::Spot { direction, attenuation, cone, .. } = gltf.lights[2] else { panic!() };
    check_close(direction, Vec3::NEG_X);
    assert_eq!(attenuation, inverse_square.with_range(5.0));
    assert_eq!(cone, Cone { inner: 0.25, outer: 0.5 });
    // A cone the extension forbids is warned about and clamped into one.
    let Light::Spot { cone, .. } = gltf.lights[3] else { panic!() };
    assert!(cone.check().is_ok() && cone.outer == 0.5 && cone.inner < 0.5, "{cone:?}");
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    check_message(&warnings[0], &["quad.gltf", "light 3: cone angles must satisfy", "drawn with inner"]);
    let scene = scene_for_gltf(gltf, RenderSettings::default());
    assert_eq!(scene.lights.len(), 4, "the file's lights replace the default ones");
}

#[test]
fn unsupported_features_warn_and_still_load() {
    let path = quad_gltf(
        "unsupported",
        r#""extensionsUsed": ["KHR_texture_transform"],
        "materials": [{"name": "glow", "emissiveFactor": [1, 0, 0], "emissiveTexture": {"index": 0},
            "alphaMode": "MASK"}],
        "textures": [{"source": 0}], "images": [{"uri": "never-read.png"}],
        "nodes": [{"mesh": 0}, {"mesh": 1}],
        "scenes": [{"nodes": [0, 1]}]"#,
    );
    edit(
        &path,
        r#""meshes": ["#,
        r#""meshes": [{"name": "lines", "primitives": [{"attributes": {"POSITION": 0}, "mode": 1}]}, "#,
    );
    edit(&path, r#""mesh": 1}"#, r#""mesh": 1, "skin": 0}"#);
    edit(&path, r#""nodes": [{"mesh": 0},"#, r#""skins": [{"joints": [0]}], "nodes": [{"mesh": 0},"#);
    edit(&path, r#""TEXCOORD_0": 1}"#, r#""TEXCOORD_0": 1, "COLOR_0": 0}"#);
    let (scene, warnings) = load_gltf_with_warnings(&path).unwrap();
    assert_eq!(scene.objects.len(), 1, "the lines are skipped");
    assert_eq!(scene.objects[0].material().ke, Vec3::new(1.0, 0.0, 0.0), "the factor without the texture");
    assert!(warnings.iter().any(|w| w.contains("never-read.png: cannot read texture")), "{warnings:?}");
    assert!(scene.objects[0].mesh.surface_maps.emission.is_none(), "no image, no map");
    let corners = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
    assert_eq!(scene.objects[0].mesh.colors, corners, "COLOR_0 read from the POSITION accessor");
    let expected = [
        "extension 'KHR_texture_transform' is not supported",
        "mesh 'lines': primitive mode Lines is not supported; skipped",
        "skins are not supported",
        // The emissive texture is read (SPEC §5.2); its image is missing.
        "material 'glow': ",
    ];
    assert_eq!(warnings.len(), expected.len(), "{warnings:?}");
    for part in expected {
        assert!(
            warnings.iter().any(|w| w.starts_with(&path.display().to_string()) && w.contains(part)),
            "{part:?} not in {warnings:?}"
        );
    }
}

#[test]
fn mask_without_a_texture_applies_to_the_constant_alpha() {
    // Material 0: alpha 0.3 below the default cutoff 0.5 → the quad draws
    // nothing. Material 1: the same alpha over a cutoff of 0.25 → opaque.
    // Material 2: a base colour texture whose image is missing, alpha 0.3
    // → drawn untextured, so the constant alpha decides: nothing.
    let path = quad_gltf(
        "mask",
        r#""materials": [
            {"name": "hidden", "alphaMode": "MASK", "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 0.3]}},
            {"name": "shown", "alphaMode": "MASK", "alphaCutoff": 0.25,
             "pbrMetallicRoughness": {"baseColorFactor": [0, 1, 0, 0.3]}},
            {"name": "lost", "alphaMode": "MASK",
             "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 1, 0.3], "baseColorTexture": {"index": 0}}}
        ],
        "textures": [{"source": 0}], "images": [{"uri": "missing.png"}],
        "nodes": [{"mesh": 0}, {"mesh": 1}, {"mesh": 2}], "scenes": [{"nodes": [0, 1, 2]}]"#,
    );
    let quad_with = |m: u32| {
        format!(
            r#"{{"name": "q{m}", "primitives": [{{"attributes": {{"POSITION": 0, "TEXCOORD_0": 1}}, "indices": 2, "material": {m}}}]}}, "#
        )
    };
    edit(&path, r#""meshes": ["#, &format!(r#""meshes": [{}{}"#, quad_with(1), quad_with(2)));
    let (scene, warnings) = load_gltf_with_warnings(&path).unwrap();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    check_message(&warnings[0], &["missing.png"]);
    let names: Vec<&str> = scene.objects.iter().map(|o| o.mesh.name.as_str()).collect();
    assert_eq!(names, ["q1"], "only the material whose alpha reaches its cutoff is drawn");
    let m = scene.objects[0].material();
    assert_eq!((m.kd, m.opacity), (Vec3::new(0.0, 1.0, 0.0), 1.0), "drawn opaque");
    assert!(scene.objects[0].mesh.diffuse_map.is_none());
}

#[test]
fn vertex_color_test_reads_color_0_as_rgb() {
    let (scene, warnings) =
        load_gltf_with_warnings(&repo("assets/gltf/VertexColorTest/glTF-Binary/VertexColorTest.glb"))
            .unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    let test = scene.objects.iter().find(|o| o.mesh.name.starts_with("VertexColorTestMesh")).unwrap();
    let label = scene.objects.iter().find(|o| o.mesh.name.starts_with("LabelMesh")).unwrap();
    assert!(label.mesh.colors.is_empty(), "no COLOR_0, no colours");
    assert_eq!(test.mesh.colors.len(), test.mesh.vertex_count());
    // The test row is tinted pure red, green and blue, the reference row
    // white (the file's backing panel has greys near 0.5 and 1 too).
    for c in [Vec3::X, Vec3::Y, Vec3::Z, Vec3::ONE, Vec3::splat(0.501_960_8)] {
        assert!(test.mesh.colors.contains(&c), "{c} missing from {:?}", test.mesh.colors);
    }
    assert!(test.mesh.colors.iter().all(|c| c.cmpge(Vec3::ZERO).all() && c.cmple(Vec3::ONE).all()));
}

#[test]
fn emissive_factor_times_strength_becomes_ke() {
    let path = two_material_quads(
        "emissive",
        r#""extensionsUsed": ["KHR_materials_emissive_strength"],
        "materials": [
            {"emissiveFactor": [0.25, 0.5, 0.125],
             "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 3}}},
            {"emissiveFactor": [0.25, 0.5, 0.125]}
        ],"#,
    );
    let (scene, warnings) = load_gltf_with_warnings(&path).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    // × 3 gives (0.75, 1.5, 0.375); ke is clamped to [0, 1] like every coefficient.
    assert_eq!(scene.objects[0].material().ke, Vec3::new(0.75, 1.0, 0.375));
    assert_eq!(scene.objects[1].material().ke, Vec3::new(0.25, 0.5, 0.125), "no strength: the factor");
    let plain = load_gltf(&repo("assets/gltf/Box/glTF-Binary/Box.glb")).unwrap();
    assert_eq!(plain.objects[0].material().ke, Vec3::ZERO, "no emissiveFactor: no emission");
}

/// Two quads, the first object with `materials` (the JSON of
/// `extensionsUsed` and two materials, ending in a comma) material 0, the
/// second material 1.
fn two_material_quads(name: &str, materials: &str) -> PathBuf {
    let path = quad_gltf(
        name,
        &format!(r#"{materials} "nodes": [{{"mesh": 0}}, {{"mesh": 1}}], "scenes": [{{"nodes": [0, 1]}}]"#),
    );
    edit(
        &path,
        r#""meshes": ["#,
        r#""meshes": [{"name": "plain", "primitives": [{"attributes": {"POSITION": 0}, "indices": 2, "material": 1}]}, "#,
    );
    edit(&path, r#""nodes": [{"mesh": 0}, {"mesh": 1}]"#, r#""nodes": [{"mesh": 1}, {"mesh": 0}]"#);
    path
}

/// The quad with a base colour texture whose image is `uri`.
fn textured_quad(name: &str, uri: &str) -> PathBuf {
    quad_gltf(
        name,
        &format!(
            r#""materials": [{{"pbrMetallicRoughness": {{"baseColorTexture": {{"index": 0}}, "baseColorFactor": [0.2, 0.4, 0.6, 1]}}}}],
            "textures": [{{"source": 0, "sampler": 0}}],
            "samplers": [{{"minFilter": 9729, "wrapS": 33648}}],
            "images": [{{"uri": "{uri}"}}],
            "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}]"#
        ),
    )
}

#[test]
fn a_texture_next_to_the_file_is_read_with_its_sampler() {
    let path = textured_quad("texture", "my%20logo.png");
    std::fs::copy(
        repo("assets/gltf/BoxTextured/glTF/CesiumLogoFlat.png"),
        path.with_file_name("my logo.png"),
    )
    .unwrap();
    let (scene, warnings) = load_gltf_with_warnings(&path).unwrap();
    let map = scene.objects[0].mesh.diffuse_map.as_ref().unwrap();
    assert_eq!(map.sampler, Sampler { filter: Filter::Bilinear, wrap_s: Wrap::Repeat, wrap_t: Wrap::Repeat });
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    check_message(&warnings[0], &["quad.gltf", "MIRRORED_REPEAT is not supported; using REPEAT"]);
    // v = 0 at the bottom corners becomes t = 1.
    assert_eq!(scene.objects[0].mesh.uvs[0], Vec2::new(0.0, 1.0));
}

#[test]
fn mask_cutoffs_apply_to_the_factor_times_the_texel_alpha() {
    for (factor, cutoff, want) in
        [(1.0, 0.5, 0.5), (0.5, 0.25, 0.5), (0.8, 0.6, 0.75), (0.0, 0.5, f32::INFINITY)]
    {
        let name = format!("mask_{factor}_{cutoff}");
        let path = textured_quad(&name, "logo.png");
        std::fs::copy(
            repo("assets/gltf/BoxTextured/glTF/CesiumLogoFlat.png"),
            path.with_file_name("logo.png"),
        )
        .unwrap();
        edit(
            &path,
            r#""baseColorFactor": [0.2, 0.4, 0.6, 1]}"#,
            &format!(
                r#""baseColorFactor": [0.2, 0.4, 0.6, {factor}]}}, "alphaMode": "MASK", "alphaCutoff": {cutoff}"#
            ),
        );
        let scene = load_gltf(&path).unwrap();
        let map = scene.objects[0].mesh.diffuse_map.as_ref().unwrap();
        assert_eq!(map.alpha_cutoff, Some(want), "factor {factor}, cutoff {cutoff}");
    }
}

#[test]
fn a_missing_image_warns_and_draws_the_base_colour() {
    let (scene, warnings) = load_gltf_with_warnings(&textured_quad("no_image", "gone.png")).unwrap();
    let mesh = &scene.objects[0].mesh;
    assert!(mesh.diffuse_map.is_none());
    assert_eq!(mesh.material.kd, Vec3::new(0.2, 0.4, 0.6));
    assert!(
        warnings.iter().any(|w| w.contains("gone.png") && w.contains("cannot read texture")),
        "{warnings:?}"
    );
}

#[test]
fn a_corrupt_image_is_an_error_naming_it() {
    let path = textured_quad("bad_image", "bad.png");
    std::fs::write(path.with_file_name("bad.png"), b"\x89PNG\r\n\x1a\nbroken").unwrap();
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(&e, &["bad.png", "cannot decode image"]);
    let path = textured_quad("bad_embedded", "data:image/png;base64,aGVsbG8=");
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(&e, &["quad.gltf", "image 0 (embedded)", "not a PNG or JPEG"]);
}

#[test]
fn a_missing_buffer_is_an_error_naming_it() {
    let path = quad_gltf("no_buffer", r#""nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]"#);
    std::fs::remove_file(path.with_file_name("quad.bin")).unwrap();
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(&e, &["quad.gltf: buffer 0: cannot read", "quad.bin"]);
    std::fs::write(path.with_file_name("quad.bin"), [0u8; 10]).unwrap();
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(&e, &["quad.gltf: buffer 0: holds 10 bytes, byteLength says 92"]);
}

#[test]
fn broken_json_and_glb_are_errors_naming_the_file() {
    let path = quad_gltf("bad_json", r#""nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]"#);
    edit(&path, r#""asset""#, r#""asset" ]"#);
    check_message(&load_gltf(&path).unwrap_err().to_string(), &["quad.gltf: cannot read glTF"]);
    let glb = path.with_file_name("broken.glb");
    std::fs::write(&glb, b"glTF\x02\0\0\0\xff\xff\0\0").unwrap();
    check_message(
        &load_gltf(&glb).unwrap_err().to_string(),
        &["broken.glb: truncated GLB: expected 65535 bytes (the header's length), found 12"],
    );
    check_message(
        &load_gltf(&path.with_file_name("nowhere.glb")).unwrap_err().to_string(),
        &["nowhere.glb", "cannot read file"],
    );
}

#[test]
fn accessors_outside_their_buffer_are_errors() {
    let path = quad_gltf("bad_accessor", r#""nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]"#);
    edit(&path, r#""count": 6"#, r#""count": 600"#);
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(
        &e,
        &["quad.gltf: mesh 'quad': indices accessor 2: 600 elements do not fit in buffer view 2"],
    );
    let path = quad_gltf("bad_type", r#""nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]"#);
    edit(&path, r#""TEXCOORD_0": 1"#, r#""TEXCOORD_0": 0"#);
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(&e, &["mesh 'quad': TEXCOORD_0 accessor 0: type Vec3 of F32 is not allowed here"]);
}

#[test]
fn indices_beyond_the_vertices_are_mesh_errors() {
    let path = quad_gltf("bad_index", r#""nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]"#);
    let mut bin = quad_bin();
    bin[80..82].copy_from_slice(&9u16.to_le_bytes());
    std::fs::write(path.with_file_name("quad.bin"), bin).unwrap();
    let e = load_gltf(&path).unwrap_err().to_string();
    check_message(&e, &["quad.gltf: mesh 'quad': triangle 0 refers to vertex 9"]);
}

#[test]
fn the_other_material_maps_are_read_and_a_lone_map_gets_a_white_base_texture() {
    // Metallic–roughness, occlusion (with its strength) and emissive
    // textures, no base colour texture: each becomes a `SurfaceMaps` entry,
    // and the mesh a white base texture the maps' coordinates are read with.
    let path = quad_gltf(
        "surface_maps",
        r#""materials": [{"name": "maps", "emissiveFactor": [1, 1, 1],
            "pbrMetallicRoughness": {"metallicFactor": 0.5, "roughnessFactor": 0.25,
                "metallicRoughnessTexture": {"index": 0}},
            "occlusionTexture": {"index": 0, "strength": 0.75}, "emissiveTexture": {"index": 0}}],
        "textures": [{"source": 0}], "images": [{"uri": "logo.png"}],
        "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]"#,
    );
    std::fs::copy(repo("assets/gltf/BoxTextured/glTF/CesiumLogoFlat.png"), path.with_file_name("logo.png"))
        .unwrap();
    let (scene, warnings) = load_gltf_with_warnings(&path).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    let mesh = &scene.objects[0].mesh;
    let maps = &mesh.surface_maps;
    assert!(maps.metallic_roughness.is_some() && maps.emission.is_some());
    assert_eq!(maps.occlusion.as_ref().map(|(_, strength)| *strength), Some(0.75));
    let base = mesh.diffuse_map.as_ref().expect("a white base texture");
    assert_eq!((base.texture.width(), base.texture.height()), (1, 1));
    assert_eq!(base.texture.texel(0, 0, 0), glam::Vec4::ONE);
    match scene.objects[0].material().model {
        zline_shading::Model::CookTorrance(m) => assert_eq!((m.metallic, m.roughness), (0.5, 0.25)),
        other => panic!("glTF materials are Cook–Torrance, got {other:?}"),
    }
}

/// KHR_materials_ior and KHR_materials_transmission (SPEC §12): the index
/// of refraction (default 1.5), and kt = transmissionFactor as 1 − d.
#[test]
fn ior_and_transmission_reach_the_material() {
    let path = two_material_quads(
        "glass",
        r#""extensionsUsed": ["KHR_materials_ior", "KHR_materials_transmission"],
        "materials": [
            {"extensions": {"KHR_materials_ior": {"ior": 1.33},
                            "KHR_materials_transmission": {"transmissionFactor": 0.75}}},
            {"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.5]}, "alphaMode": "BLEND"}
        ],"#,
    );
    let (scene, warnings) = load_gltf_with_warnings(&path).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    let (glass, plain) = (scene.objects[0].material(), scene.objects[1].material());
    assert_eq!((glass.ior, glass.opacity), (1.33, 0.25));
    assert_eq!((plain.ior, plain.opacity), (1.5, 0.5), "the extension's default index; alpha blending alone");
}
