//! The CLI's side of reading an input (`zline::load`): the loader's
//! warnings on stderr, and `zline info`.

use std::path::Path;

use anyhow::Result;
use zline::io::LoadOptions;
use zline::load::{load, Loaded};
use zline::scene::Scene;

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
