//! `zline inspect` and `render --inspect`: the reported pixel is the PNG's
//! pixel, byte for byte, on several pixels of a model and of a scene with
//! transparency and supersampling; and the usage errors.

use crate::{check_clean_error, repo, zline};

fn json_of(out: &std::process::Output) -> serde_json::Value {
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("one JSON object on stdout")
}

#[test]
fn the_reported_pixel_is_the_written_pngs_pixel() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("out.png");
    let bunny = repo().join("assets/ply/bunny_lowres.ply");
    let scene = repo().join("tests/scenes/transparency.toml");
    let cases: [(&std::path::Path, &[&str]); 3] = [
        (&bunny, &["--size", "120x90"]),
        (&scene, &["--size", "120x90", "--ssaa", "2"]),
        (&scene, &["--size", "120x90", "--transparent", "--fog", "exp:0.2"]),
    ];
    let mut fragments = 0;
    for (input, flags) in cases {
        for (x, y) in [(60, 45), (10, 80), (33, 52), (95, 20)] {
            let pixel = format!("{x},{y}");
            let mut args = vec!["render", input.to_str().unwrap(), "-o", png.to_str().unwrap()];
            args.extend_from_slice(flags);
            args.extend(["--inspect", &pixel, "--inspect-json"]);
            let report = json_of(&zline(&args));
            let written = image::open(&png).unwrap().to_rgba8();
            let want = written.get_pixel(x, y).0;
            let got: Vec<u8> =
                report["resolved"].as_array().unwrap().iter().map(|v| v.as_u64().unwrap() as u8).collect();
            assert_eq!(got, want, "{input:?} {flags:?} at {pixel}");
            assert_eq!(report["matches"], true);
            fragments += report["samples"]
                .as_array()
                .unwrap()
                .iter()
                .map(|s| s["fragments"].as_array().unwrap().len())
                .sum::<usize>();
        }
    }
    assert!(fragments > 10, "{fragments}");
}

#[test]
fn inspect_prints_each_fragment_and_the_check() {
    let scene = repo().join("tests/scenes/transparency.toml");
    // A pixel where the glass covers an opaque surface (found by search
    // below, so the test does not hang on a camera change).
    let mut found = false;
    for (x, y) in [(100, 75), (80, 60), (120, 90), (60, 50), (140, 70)] {
        let out = zline(&[
            "inspect",
            scene.to_str().unwrap(),
            "--pixel",
            &format!("{x},{y}"),
            "--",
            "--size",
            "200x150",
        ]);
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        assert!(text.contains("the rendered image's pixel is the same"), "{text}");
        if text.contains("transparent pass") && text.contains("opaque pass") {
            assert!(text.contains("blended") && text.contains("edge table: sample row"), "{text}");
            found = true;
            break;
        }
    }
    assert!(found, "no pixel with both an opaque and a transparent fragment");
}

#[test]
fn inspect_usage_errors_are_clean() {
    let bunny = repo().join("assets/ply/bunny_lowres.ply");
    let bunny = bunny.to_str().unwrap();
    let out = zline(&["inspect", bunny, "--pixel", "900,10", "--", "--size", "64x48"]);
    check_clean_error(&out, &["900", "outside the 64x48 image"]);
    let out = zline(&["render", bunny, "-o", "-", "--inspect", "1,1"]);
    check_clean_error(&out, &["--inspect", "standard output"]);
    let out = zline(&["inspect", bunny, "--pixel", "ten,3"]);
    assert_ne!(out.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&out.stderr).contains("X,Y"), "{}", String::from_utf8_lossy(&out.stderr));
}

/// The reported lighting terms add up to the colour the kernel wrote: on an
/// untextured, unshadowed Phong model without fog, every written
/// fragment's colour is clamp(ke + ka·Ia + Σ diffuse + specular) within
/// f32 rounding (the kernels evaluate the same formulas eight lanes at a
/// time, in another order).
#[test]
fn the_lighting_terms_add_up_to_the_written_colour() {
    let mut scene =
        zline::load::load(&repo().join("assets/ply/bunny_lowres.ply"), Default::default()).unwrap().scene;
    (scene.settings.width, scene.settings.height) = (96, 72);
    scene.settings.shading = zline::shading::ShadingMode::Phong;
    scene.camera = zline::io::model_camera(&scene.objects, 96.0 / 72.0);
    let mut checked = 0;
    for ((x, y), f) in written_on_grid(&scene, (2..96).step_by(4), (2..72).step_by(4)) {
        let want = terms_sum(&scene, &f).unwrap();
        assert!(
            (f.after.1 - want).abs().max_element() < 2e-5,
            "({x}, {y}): kernel {} vs terms {want}",
            f.after.1
        );
        checked += 1;
    }
    assert!(checked > 100, "{checked}");
}

/// On the demo's textured floor, the texel the inspector reads and its
/// lighting terms give the written colour: texel ⊙ (ka·Ia + Σ diffuse) +
/// ke + Σ specular (SPEC §7), within 5·10⁻⁴ — the inspector's level of
/// detail is the kernels' formula in scalar f32 with libm's log2, the
/// kernels' a vector log2, so the trilinear weight may differ in its last
/// bits.
#[test]
fn the_texel_read_and_the_terms_give_the_textured_colour() {
    let mut scene = zline::scenes::demo_scene();
    (scene.settings.width, scene.settings.height) = (160, 120);
    let mut checked = 0;
    let written = written_on_grid(&scene, (0..160).step_by(7), (60..120).step_by(6));
    for ((x, y), f) in
        written.iter().filter(|(_, f)| f.attributes.texture.is_some() && f.attributes.normal.is_some())
    {
        let texel = f.attributes.texture.unwrap().texel.truncate();
        let m = scene.objects[f.object as usize].material().sanitized();
        let (_, terms) =
            zline::inspect::lighting_terms(&scene, f.object, &f.attributes, &f.light_shares).unwrap();
        let diffuse: glam::Vec3 = terms.iter().map(|t| glam::Vec3::from(t.diffuse)).sum();
        let specular: glam::Vec3 = terms.iter().map(|t| glam::Vec3::from(t.specular)).sum();
        let want = (texel * (m.ka * scene.ambient + diffuse) + m.ke + specular)
            .clamp(glam::Vec3::ZERO, glam::Vec3::ONE);
        assert!((f.after.1 - want).abs().max_element() < 5e-4, "({x}, {y}): kernel {} vs {want}", f.after.1);
        checked += 1;
    }
    assert!(checked > 30, "{checked}");
}

/// Under shadow maps and planar shadows the terms, each light times the
/// share the kernels' own lookup gives, still add up to the written
/// colour of the room's untextured surfaces; some samples are in shadow.
#[test]
fn shadowed_terms_add_up_with_the_lights_share() {
    for mode in [zline::scene::ShadowMode::Map, zline::scene::ShadowMode::Planar] {
        let mut scene = zline::scenes::room_scene();
        (scene.settings.width, scene.settings.height) = (96, 72);
        scene.shadows.mode = mode;
        let (mut checked, mut shadowed) = (0, 0);
        for ((x, y), f) in written_on_grid(&scene, (1..96).step_by(5), (1..72).step_by(5)) {
            assert!(f.light_shares.iter().all(|s| (0.0..=1.0).contains(s)), "{:?}", f.light_shares);
            shadowed += usize::from(f.light_shares.iter().any(|&s| s < 1.0));
            if f.attributes.texture.is_some() || f.attributes.vertex_color.is_some() {
                continue;
            }
            let Some(want) = terms_sum(&scene, &f) else { continue };
            assert!(
                (f.after.1 - want).abs().max_element() < 1e-4,
                "{mode:?} ({x}, {y}): kernel {} vs terms {want}",
                f.after.1
            );
            checked += 1;
        }
        assert!(checked > 30 && shadowed > 5, "{mode:?}: {checked} checked, {shadowed} in shadow");
    }
}

/// The vertices the inspector lists in NC space map to the window
/// vertices setup snapped (the same three points, within the 1/256-pixel
/// grid), for the bunny's unclipped triangles.
#[test]
fn the_vertices_in_each_space_lead_to_the_snapped_window_vertices() {
    use zline::pipeline::{RenderOptions, Renderer};
    let mut scene =
        zline::load::load(&repo().join("assets/ply/bunny_lowres.ply"), Default::default()).unwrap().scene;
    (scene.settings.width, scene.settings.height) = (96, 72);
    scene.camera = zline::io::model_camera(&scene.objects, 96.0 / 72.0);
    let mut renderer = Renderer::default();
    let mut checked = 0;
    for (x, y) in (8..64).step_by(8).flat_map(|y| (8..88).step_by(8).map(move |x| (x, y))) {
        let mut image = zline::pipeline::Image::empty();
        let trace = renderer.inspect(&scene, &RenderOptions::default(), (x, y), &mut image).unwrap();
        for f in trace.samples.iter().flat_map(|s| &s.fragments) {
            let spaces = zline::inspect::vertex_spaces(&scene, f.object, f.triangle.unwrap()).unwrap();
            let mut window: Vec<(f64, f64)> = spaces[4]
                .iter()
                .map(|v| ((f64::from(v.x) + 1.0) / 2.0 * 96.0, (1.0 - f64::from(v.y)) / 2.0 * 72.0))
                .collect();
            let mut snapped = f.vertices.to_vec();
            let key = |p: &(f64, f64)| (p.1, p.0);
            window.sort_by(|a, b| key(a).partial_cmp(&key(b)).unwrap());
            snapped.sort_by(|a, b| key(a).partial_cmp(&key(b)).unwrap());
            for (w, s) in window.iter().zip(&snapped) {
                assert!(
                    (w.0 - s.0).abs() < 0.01 && (w.1 - s.1).abs() < 0.01,
                    "({x}, {y}): {window:?} vs {snapped:?}"
                );
            }
            checked += 1;
        }
    }
    assert!(checked >= 10, "{checked}");
}

/// The written fragments (the opaque pass's) of every pixel of the grid
/// `xs` × `ys`, each with its pixel, as the inspector reports them.
fn written_on_grid(
    scene: &zline::scene::Scene,
    xs: std::iter::StepBy<std::ops::Range<u32>>,
    ys: std::iter::StepBy<std::ops::Range<u32>>,
) -> Vec<((u32, u32), zline::pipeline::FragmentTrace)> {
    use zline::pipeline::{Outcome, RenderOptions, Renderer};
    let mut renderer = Renderer::default();
    let pixels: Vec<(u32, u32)> = ys.flat_map(|y| xs.clone().map(move |x| (x, y))).collect();
    let mut out = Vec::new();
    for pixel in pixels {
        let mut image = zline::pipeline::Image::empty();
        let trace = renderer.inspect(scene, &RenderOptions::default(), pixel, &mut image).unwrap();
        let written =
            trace.samples.into_iter().flat_map(|s| s.fragments).filter(|f| f.outcome == Outcome::Written);
        out.extend(written.map(|f| (pixel, f)));
    }
    out
}

/// clamp(ke + ka·Ia + Σ (diffuse + specular)) from the reported terms;
/// `None` for a kernel without a per-sample normal.
fn terms_sum(scene: &zline::scene::Scene, f: &zline::pipeline::FragmentTrace) -> Option<glam::Vec3> {
    let (base, terms) = zline::inspect::lighting_terms(scene, f.object, &f.attributes, &f.light_shares)?;
    let sum = terms.iter().fold(base, |c, t| c + glam::Vec3::from(t.diffuse) + glam::Vec3::from(t.specular));
    Some(sum.clamp(glam::Vec3::ZERO, glam::Vec3::ONE))
}
