//! The Cornell box solved: colour bleeds from the red and green walls.

use std::path::Path;

use zline_radiosity::{solve, Method, Options};

#[test]
fn the_cornell_box_bleeds_red_and_green_onto_the_white_walls() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/cornell/cornell_box.toml");
    let scene = zline_io::load_scene(&path).expect("the shipped Cornell box loads");
    let options =
        Options { method: Method::Progressive, patch_size: Some(100.0), ..scene.settings.radiosity };
    let solution = solve(&scene, &options).unwrap();
    let n = solution.patches.patches.len();
    let residual = solution.convergence.residuals.last().copied().unwrap_or(1.0);
    eprintln!(
        "{n} patches, {} shots, residual {residual:.2e}, {:.2?}",
        solution.convergence.residuals.len(),
        solution.took
    );
    assert!(residual <= 1e-3);
    // White patches of the floor (y ≈ 0, facing up) near the red wall
    // (x ≈ 550) and near the green one (x ≈ 0).
    let mut near_red = glam::Vec3::ZERO;
    let mut near_green = glam::Vec3::ZERO;
    for (p, b) in solution.patches.patches.iter().zip(&solution.radiosity) {
        let white = (p.reflectance.x - p.reflectance.y).abs() < 0.05;
        if white && p.normal.y > 0.9 && p.centre.y < 1.0 {
            if p.centre.x > 450.0 {
                near_red += *b;
            } else if p.centre.x < 100.0 {
                near_green += *b;
            }
        }
    }
    let (red, green) = (near_red.x / near_red.y, near_green.x / near_green.y);
    assert!(
        red > 1.05 * green,
        "red/green on the floor by the red wall {red:.3}, by the green wall {green:.3}"
    );
}

#[test]
fn bad_input_is_refused_or_clamped_with_a_message() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/cornell/cornell_box.toml");
    let scene = zline_io::load_scene(&path).unwrap();
    // A patch size that would give billions of patches: refused at once.
    let tiny = Options { patch_size: Some(1e-4), ..scene.settings.radiosity };
    let started = std::time::Instant::now();
    let error = solve(&scene, &tiny).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(error.contains("patches") && error.contains("--patch-size"), "{error}");
    assert!(started.elapsed().as_secs_f32() < 1.0);
    for size in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        let error = solve(&scene, &Options { patch_size: Some(size), ..scene.settings.radiosity })
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(error.contains("not a positive length"), "{size}: {error}");
    }
    // The sweeps' matrix beyond its bound: refused before it is made.
    let big = Options { patch_size: Some(12.0), method: Method::Jacobi, ..scene.settings.radiosity };
    let error = solve(&scene, &big).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(error.contains("matrix") && error.contains("--solver progressive"), "{error}");
    // A reflectance at or above 1: clamped, with a warning.
    let mut bright = scene.clone();
    for object in &mut bright.objects {
        let mut m = object.material();
        m.kd = glam::Vec3::splat(1.5);
        object.material = Some(m);
    }
    let coarse = Options { patch_size: Some(200.0), max_steps: 50, ..scene.settings.radiosity };
    let solution = solve(&bright, &coarse).unwrap();
    assert!(
        solution.patches.warnings.iter().any(|w| w.contains("clamped")),
        "{:?}",
        solution.patches.warnings
    );
    assert!(solution.patches.patches.iter().all(|p| p.reflectance.max_element() <= 0.99));
    // NaN emission: the scene's material sanitizing takes it as 0 (what
    // the rasterizer and the ray tracer draw), so every radiosity stays
    // finite.
    let mut nan = scene.clone();
    let mut m = nan.objects[0].material();
    m.ke = glam::Vec3::NAN;
    nan.objects[0].material = Some(m);
    let solution = solve(&nan, &coarse).expect("a sanitized emission");
    assert!(solution.radiosity.iter().all(|b| b.is_finite()));
}
