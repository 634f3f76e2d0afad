//! Reading an input by its name: a model (OBJ, glTF, GLB, STL, PLY, 3MF) or
//! a scene file, chosen by extension, or standard input — one dispatch for
//! every command of the CLI and for the Python module.

use std::path::Path;

use crate::io::LoadOptions;
use crate::scene::{RenderSettings, Scene};
use anyhow::{bail, Result};

/// A loaded input and what `zline info` says of it.
pub struct Loaded {
    /// The scene (a bare model framed and lit by zline's defaults).
    pub scene: Scene,
    /// The format's name.
    pub format: &'static str,
    /// Whether the file brought its own lights.
    pub own_lights: bool,
    /// Whether the file brought its own camera.
    pub own_camera: bool,
    /// The loader's warnings (a scene file prints its models' own as it
    /// loads).
    pub warnings: Vec<String>,
}

/// Loads `input` by its extension, or standard input for `-` (the format
/// told from the bytes; files it names are looked up in the current
/// folder).
pub fn load(input: &Path, options: LoadOptions) -> Result<Loaded> {
    use crate::io::{InputFormat, LoadedInput};
    let (format, (loaded, warnings)) = if input == Path::new("-") {
        let name = Path::new(crate::io::STDIN_NAME);
        let bytes = crate::io::read_stream(std::io::stdin().lock(), name)?;
        let Some(format) = InputFormat::sniff(&bytes) else {
            bail!(
                "{}: could not tell the format of the input; expected an OBJ, glTF, GLB, STL, PLY or 3MF model or a TOML scene file",
                name.display()
            );
        };
        (format, crate::io::load_bytes(format, name, bytes, options)?)
    } else {
        let Some(format) = InputFormat::from_extension(input) else {
            bail!(
                "{}: unsupported input; expected an .obj, .gltf, .glb, .stl, .ply or .3mf model, a .toml scene file, or - for standard input",
                input.display()
            );
        };
        (format, load_file(format, input, options)?)
    };
    let settings = RenderSettings::default();
    let name = format.name();
    Ok(match loaded {
        LoadedInput::Model(meshes) => Loaded {
            scene: crate::io::scene_for_model(meshes, settings),
            format: name,
            own_lights: false,
            own_camera: false,
            warnings,
        },
        LoadedInput::Gltf(gltf) => {
            let (own_lights, own_camera) = (!gltf.lights.is_empty(), gltf.camera.is_some());
            let scene = crate::io::scene_for_gltf(gltf, settings);
            Loaded { scene, format: name, own_lights, own_camera, warnings }
        }
        LoadedInput::Scene(scene) => {
            Loaded { scene: *scene, format: name, own_lights: true, own_camera: true, warnings }
        }
    })
}

/// The file `input` in `format`, with its loader's warnings.
fn load_file(
    format: crate::io::InputFormat,
    input: &Path,
    options: LoadOptions,
) -> Result<(crate::io::LoadedInput, Vec<String>)> {
    use crate::io::{InputFormat, LoadedInput};
    Ok(match format {
        InputFormat::Obj => {
            let (meshes, warnings) = crate::io::load_obj_with_options(input, options)?;
            (LoadedInput::Model(meshes), warnings)
        }
        InputFormat::Gltf | InputFormat::Glb => {
            let (gltf, warnings) = crate::io::load_gltf_with_options(input, options)?;
            (LoadedInput::Gltf(gltf), warnings)
        }
        InputFormat::Stl => (LoadedInput::Model(crate::io::load_stl(input)?), vec![]),
        InputFormat::Ply => (LoadedInput::Model(crate::io::load_ply(input)?), vec![]),
        InputFormat::ThreeMf => (LoadedInput::Model(crate::io::load_3mf(input)?), vec![]),
        InputFormat::Scene => {
            (LoadedInput::Scene(Box::new(crate::io::load_scene_with_options(input, options)?)), vec![])
        }
    })
}
