//! Reading the input of `render`, `info` and friends: a model (OBJ, glTF,
//! GLB, STL, PLY) or a scene file, chosen by extension — one dispatch for
//! every command.

use std::path::Path;

use anyhow::{bail, Result};
use zline::io::LoadOptions;
use zline::scene::{RenderSettings, Scene};

/// A loaded input and what `zline info` says of it.
pub(crate) struct Loaded {
    /// The scene (a bare model framed and lit by zline's defaults).
    pub(crate) scene: Scene,
    /// The format's name.
    pub(crate) format: &'static str,
    /// Whether the file brought its own lights.
    pub(crate) own_lights: bool,
    /// Whether the file brought its own camera.
    pub(crate) own_camera: bool,
    /// The loader's warnings (a scene file prints its models' own as it
    /// loads).
    pub(crate) warnings: Vec<String>,
}

/// Loads `input` by its extension.
pub(crate) fn load(input: &Path, options: LoadOptions) -> Result<Loaded> {
    let ext = input.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let settings = RenderSettings::default();
    let model =
        |scene, format, warnings| Loaded { scene, format, own_lights: false, own_camera: false, warnings };
    Ok(match ext.as_deref() {
        Some("obj") => {
            let (meshes, warnings) = zline::io::load_obj_with_options(input, options)?;
            model(zline::io::scene_for_model(meshes, settings), "OBJ", warnings)
        }
        Some(e @ ("gltf" | "glb")) => {
            let (gltf, warnings) = zline::io::load_gltf_with_options(input, options)?;
            let (own_lights, own_camera) = (!gltf.lights.is_empty(), gltf.camera.is_some());
            let format = if e == "glb" { "GLB" } else { "glTF" };
            let scene = zline::io::scene_for_gltf(gltf, settings);
            Loaded { scene, format, own_lights, own_camera, warnings }
        }
        Some("stl") => {
            model(zline::io::scene_for_model(zline::io::load_stl(input)?, settings), "STL", vec![])
        }
        Some("ply") => {
            model(zline::io::scene_for_model(zline::io::load_ply(input)?, settings), "PLY", vec![])
        }
        Some("toml") => Loaded {
            scene: zline::io::load_scene_with_options(input, options)?,
            format: "scene file",
            own_lights: true,
            own_camera: true,
            warnings: vec![],
        },
        _ => bail!(
            "{}: unsupported input; expected an .obj, .gltf, .glb, .stl or .ply model or a .toml scene file",
            input.display()
        ),
    })
}

/// The scene of `input`, its warnings printed to stderr as `warning:` lines.
pub(crate) fn load_input(input: &Path, options: LoadOptions) -> Result<Scene> {
    let loaded = load(input, options)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    Ok(loaded.scene)
}

/// `zline info`: the input described on stdout, as text or JSON.
pub(crate) fn info(input: &Path, json: bool, options: LoadOptions) -> Result<()> {
    let Loaded { scene, format, own_lights, own_camera, warnings } = load(input, options)?;
    let name = input.display().to_string();
    let info = zline::info::ModelInfo::of_scene(&name, format, &scene, own_lights, own_camera, warnings);
    if json {
        println!("{}", serde_json::to_string_pretty(&info)?);
    } else {
        print!("{}", info.text());
    }
    Ok(())
}
