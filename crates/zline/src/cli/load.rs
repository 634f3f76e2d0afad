//! Reading the input of `render`, `info` and friends: a model (OBJ, glTF,
//! GLB, STL, PLY, 3MF) or a scene file, chosen by extension — one dispatch for
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

/// Loads `input` by its extension, or standard input for `-` (the format
/// told from the bytes; files it names are looked up in the current
/// folder).
pub(crate) fn load(input: &Path, options: LoadOptions) -> Result<Loaded> {
    use zline::io::{InputFormat, LoadedInput};
    let (format, (loaded, warnings)) = if input == Path::new("-") {
        let name = Path::new(zline::io::STDIN_NAME);
        let bytes = zline::io::read_stream(std::io::stdin().lock(), name)?;
        let Some(format) = InputFormat::sniff(&bytes) else {
            bail!(
                "{}: could not tell the format of the input; expected an OBJ, glTF, GLB, STL, PLY or 3MF model or a TOML scene file",
                name.display()
            );
        };
        (format, zline::io::load_bytes(format, name, bytes, options)?)
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
            scene: zline::io::scene_for_model(meshes, settings),
            format: name,
            own_lights: false,
            own_camera: false,
            warnings,
        },
        LoadedInput::Gltf(gltf) => {
            let (own_lights, own_camera) = (!gltf.lights.is_empty(), gltf.camera.is_some());
            let scene = zline::io::scene_for_gltf(gltf, settings);
            Loaded { scene, format: name, own_lights, own_camera, warnings }
        }
        LoadedInput::Scene(scene) => {
            Loaded { scene: *scene, format: name, own_lights: true, own_camera: true, warnings }
        }
    })
}

/// The file `input` in `format`, with its loader's warnings.
fn load_file(
    format: zline::io::InputFormat,
    input: &Path,
    options: LoadOptions,
) -> Result<(zline::io::LoadedInput, Vec<String>)> {
    use zline::io::{InputFormat, LoadedInput};
    Ok(match format {
        InputFormat::Obj => {
            let (meshes, warnings) = zline::io::load_obj_with_options(input, options)?;
            (LoadedInput::Model(meshes), warnings)
        }
        InputFormat::Gltf | InputFormat::Glb => {
            let (gltf, warnings) = zline::io::load_gltf_with_options(input, options)?;
            (LoadedInput::Gltf(gltf), warnings)
        }
        InputFormat::Stl => (LoadedInput::Model(zline::io::load_stl(input)?), vec![]),
        InputFormat::Ply => (LoadedInput::Model(zline::io::load_ply(input)?), vec![]),
        InputFormat::ThreeMf => (LoadedInput::Model(zline::io::load_3mf(input)?), vec![]),
        InputFormat::Scene => {
            (LoadedInput::Scene(Box::new(zline::io::load_scene_with_options(input, options)?)), vec![])
        }
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
    let name =
        if input == Path::new("-") { zline::io::STDIN_NAME.to_owned() } else { input.display().to_string() };
    let info = zline::info::ModelInfo::of_scene(&name, format, &scene, own_lights, own_camera, warnings);
    if json {
        println!("{}", serde_json::to_string_pretty(&info)?);
    } else {
        print!("{}", info.text());
    }
    Ok(())
}
