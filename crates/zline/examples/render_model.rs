//! zline as a library: load a model, frame it, render it, save a PNG.
//!
//! ```sh
//! cargo run --release -p zline --example render_model -- assets/obj/spot/spot.obj spot.png
//! ```
//!
//! Without arguments it renders `assets/obj/suzanne/suzanne.obj` to
//! `suzanne.png`.

use std::path::PathBuf;

use zline::pipeline::{render, RenderOptions};
use zline::scene::{RenderSettings, ShadingMode};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args_os().skip(1).map(PathBuf::from);
    let model = args.next().unwrap_or_else(|| "assets/obj/suzanne/suzanne.obj".into());
    let output = args.next().unwrap_or_else(|| "suzanne.png".into());

    // Load the meshes (OBJ here; zline::io also reads glTF, STL, PLY and
    // scene files) and print what the loader could not use.
    let (meshes, warnings) = zline::io::load_obj_with_warnings(&model)?;
    for w in &warnings {
        eprintln!("warning: {w}");
    }

    // A scene around them: the tight framing camera, a key and a fill
    // light, and the settings of the image.
    let settings =
        RenderSettings { width: 640, height: 480, shading: ShadingMode::Phong, ..RenderSettings::default() };
    let scene = zline::io::scene_for_model(meshes, settings);

    // Render on every core and save.
    let (image, stats) = render(&scene, &RenderOptions::default());
    zline::save_png(&image, &output)?;
    println!(
        "{}: {} triangles, {} samples shaded, {:.2} ms -> {}",
        model.display(),
        stats.triangles,
        stats.fragments,
        stats.geometry.as_secs_f64() * 1e3
            + stats.binning.as_secs_f64() * 1e3
            + stats.raster.as_secs_f64() * 1e3,
        output.display()
    );
    Ok(())
}
