//! Whether subdivision pays (`cargo xtask radiosity-report`): the Cornell
//! box solved on uniform meshes and on meshes cut where radiosity changes
//! fast, each drawn at the reference's display scale and compared pixel
//! by pixel with a fine reference (patches of 25, Gauss–Seidel, hemicubes
//! of 200²): the error against the patches and the time.

use anyhow::Result;
use zline::radiosity::{solve, Method, Options, Solution};
use zline::scene::Scene;

/// The root mean square difference of two frames' RGB values, in 8-bit
/// levels.
fn rms(a: &zline::pipeline::Image, b: &zline::pipeline::Image) -> f64 {
    let (x, y) = (a.to_rgb(), b.to_rgb());
    let sum: f64 = x.iter().zip(&y).map(|(p, q)| (f64::from(*p) - f64::from(*q)).powi(2)).sum();
    (sum / x.len().max(1) as f64).sqrt()
}

pub(crate) fn run(scene: &Scene) -> Result<()> {
    println!("## Subdivision where radiosity changes fast: does it pay?\n");
    let draw = |s: &Solution, scale: f32| {
        zline::pipeline::render(&s.display_scene_scaled(scene, scale), &Default::default()).0
    };
    let reference = solve(
        scene,
        &Options {
            patch_size: Some(25.0),
            method: Method::GaussSeidel,
            resolution: 200,
            ..scene.settings.radiosity
        },
    )?;
    let scale = reference.display_scale();
    let truth = draw(&reference, scale);
    println!(
        "Reference: {} patches of 25, Gauss–Seidel, hemicubes of 200², {:.1} s. Error: RMS over the {}×{} frame's RGB, 8-bit levels, every image at the reference's display scale.\n",
        reference.patches.patches.len(),
        reference.took.as_secs_f64(),
        truth.width,
        truth.height
    );
    println!("| mesh | subdivision levels | patches | hemicube | time | RMS error |");
    println!("|---|---:|---:|---:|---:|---:|");
    for (size, subdivide, resolution) in [
        (50.0, 0, 100),
        (35.0, 0, 100),
        (25.0, 0, 100),
        (50.0, 1, 100),
        (50.0, 2, 100),
        (50.0, 1, 200),
        (35.0, 0, 200),
    ] {
        let options = Options { patch_size: Some(size), subdivide, resolution, ..scene.settings.radiosity };
        let solution = solve(scene, &options)?;
        let error = rms(&draw(&solution, scale), &truth);
        println!(
            "| uniform {size} | {subdivide} | {} | {resolution}² | {:.2} s | {error:.2} |",
            solution.patches.patches.len(),
            solution.took.as_secs_f64()
        );
    }
    println!();
    Ok(())
}
