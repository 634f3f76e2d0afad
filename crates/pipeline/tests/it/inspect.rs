//! The pixel inspector (`Renderer::inspect`): on random pixels of the
//! built-in scenes under many settings, the inspector's resolve of the
//! pixel is the rendered image's, byte for byte, and the fragments it lists
//! agree with the depth test and the buffers.

use zline_pipeline::{render, Outcome, Pass, PixelTrace, RenderOptions, Renderer};
use zline_scene::{Scene, ShadowMode, Visibility};

/// Deterministic pseudo-random numbers (a 64-bit LCG).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self, n: u32) -> u32 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((self.0 >> 33) % u64::from(n)) as u32
    }
}

fn scenes() -> Vec<(&'static str, Scene)> {
    let small = |mut s: Scene, w, h| {
        (s.settings.width, s.settings.height) = (w, h);
        s
    };
    let demo = small(zline_scenes::demo_scene(), 96, 72);
    let mut supersampled = demo.clone();
    supersampled.settings.ssaa = 3;
    let mut painter = demo.clone();
    painter.settings.visibility = Visibility::Painter;
    let mut clear = demo.clone();
    clear.settings.transparent_background = true;
    let room = small(zline_scenes::room_scene(), 80, 60);
    let mut maps = room.clone();
    maps.shadows.mode = ShadowMode::Map;
    let mut lines = room.clone();
    lines.settings.wireframe.mode = zline_scene::WireframeMode::HiddenDashed;
    vec![
        ("demo", demo),
        ("demo ssaa 3", supersampled),
        ("demo painter", painter),
        ("demo transparent background", clear),
        ("room", room),
        ("room shadow maps", maps),
        ("room hidden-dashed lines", lines),
        ("whitted", small(zline_scenes::whitted_scene(), 64, 48)),
    ]
}

fn check(name: &str, trace: &PixelTrace) {
    assert!(
        trace.matches(),
        "{name} {:?}: inspector {:?}, image {:?}",
        trace.pixel,
        trace.resolved,
        trace.image
    );
    assert_eq!(trace.samples.len(), (trace.n * trace.n) as usize);
    for s in &trace.samples {
        for f in &s.fragments {
            match f.outcome {
                Outcome::Written => assert_eq!(f.after.0, f.z, "{name}: a written fragment stores its depth"),
                Outcome::Hidden => assert!(f.z >= f.before.0 && f.after == f.before, "{name}: {f:?}"),
                Outcome::Discarded => assert_eq!(f.after, f.before, "{name}"),
                Outcome::Blended => assert!(f.pass != Pass::Opaque, "{name}"),
            }
            // The span the edge table gives contains the sample.
            let column = (s.position.0 * f64::from(trace.n)).floor() as i32;
            assert!((f.span.x0..f.span.x1).contains(&column), "{name}: {f:?}");
        }
        // The opaque pass leaves the nearest written depth.
        let written = s.fragments.iter().filter(|f| f.outcome == Outcome::Written).map(|f| f.z);
        if let Some(nearest) = written.reduce(f32::min) {
            assert_eq!(s.after_opaque.0, nearest, "{name}");
        }
    }
}

#[test]
fn the_inspected_pixel_is_the_rendered_pixel_bit_for_bit() {
    let mut rng = Lcg(11);
    let mut fragments = 0;
    for (name, scene) in scenes() {
        let options = RenderOptions::default();
        let (want, _) = render(&scene, &options);
        let mut renderer = Renderer::default();
        for _ in 0..25 {
            let pixel = (rng.next(scene.settings.width), rng.next(scene.settings.height));
            let mut image = zline_pipeline::Image::empty();
            let trace = renderer.inspect(&scene, &options, pixel, &mut image).unwrap();
            assert_eq!(image, want, "{name}: inspecting changes nothing in the image");
            check(name, &trace);
            fragments += trace.samples.iter().map(|s| s.fragments.len()).sum::<usize>();
        }
    }
    assert!(fragments > 200, "too few fragments followed: {fragments}");
}

#[test]
fn hidden_and_transparent_fragments_are_reported_in_draw_order() {
    // The demo's glass sphere stands in front of an opaque one: find a
    // pixel with a hidden fragment and one with a blended fragment.
    let mut scene = zline_scenes::demo_scene();
    (scene.settings.width, scene.settings.height) = (96, 72);
    let options = RenderOptions::default();
    let mut renderer = Renderer::default();
    let (mut hidden, mut blended) = (false, false);
    for y in (0..72).step_by(3) {
        for x in (0..96).step_by(3) {
            let mut image = zline_pipeline::Image::empty();
            let trace = renderer.inspect(&scene, &options, (x, y), &mut image).unwrap();
            let f = &trace.samples[0].fragments;
            hidden |= f.iter().any(|f| f.outcome == Outcome::Hidden);
            blended |= f.iter().any(|f| f.outcome == Outcome::Blended && f.pass == Pass::Transparent);
            // Opaque fragments come before transparent ones.
            let first_transparent = f.iter().position(|f| f.pass == Pass::Transparent).unwrap_or(f.len());
            assert!(f[first_transparent..].iter().all(|f| f.pass == Pass::Transparent));
        }
    }
    assert!(hidden && blended, "hidden {hidden}, blended {blended}");
    let err = renderer.inspect(&scene, &options, (96, 0), &mut zline_pipeline::Image::empty()).unwrap_err();
    assert!(err.to_string().contains("outside the 96x72 image"), "{err}");
}
