//! `zline view`: the viewer's state machine driven headless, its first
//! frame against `zline render`, and a real window under Xvfb (skipped
//! with a message where Xvfb is not installed).

use std::time::Duration;

use glam::Vec3;
use zline::scene::{Camera, RenderSettings, Scene, ShadingMode, ShadowMode, WireframeMode};
use zline::viewer::state::{
    magnification, Action, Button, Event, FrameRequest, Toggles, ViewerState, MAX_ZOOM, REFINE_AFTER,
};

use crate::{repo, zline};

fn cube_scene() -> Scene {
    zline::io::scene_for_model(vec![zline::scene::cube(1.0)], RenderSettings::default())
}

fn drag(button: Button, dx: f32, dy: f32) -> Event {
    Event::Drag { button, dx, dy, shift: false }
}

#[track_caller]
fn check_close(a: Vec3, b: Vec3, tolerance: f32) {
    assert!((a - b).length() <= tolerance, "{a} != {b} (tolerance {tolerance})");
}

#[track_caller]
fn check_same_camera(a: Camera, b: Camera, tolerance: f32) {
    check_close(a.eye, b.eye, tolerance);
    check_close(a.target, b.target, tolerance);
}

/// Renders the state's due frame "in" `took` and gives its request.
fn draw(state: &mut ViewerState, took: Duration) -> FrameRequest {
    let request = state.frame_to_render().expect("a frame is due");
    state.handle(Event::FrameRendered(request, took));
    request
}

#[test]
fn orbiting_a_full_turn_returns_to_the_start() {
    let mut state = ViewerState::new(cube_scene());
    let start = state.camera();
    let d = (start.eye - start.target).length();
    // 0.4° a pixel: 900 px are a full turn about up.
    for _ in 0..90 {
        state.handle(drag(Button::Left, 10.0, 0.0));
    }
    check_same_camera(state.camera(), start, 1e-4 * d);
    // Half way it is behind the model: x and z of the view flipped.
    for _ in 0..45 {
        state.handle(drag(Button::Left, 10.0, 0.0));
    }
    let (back, front) = (state.camera().eye - start.target, start.eye - start.target);
    check_close(back, Vec3::new(-front.x, front.y, -front.z), 1e-4 * d);
    // Up and down again, within the poles: back where it was.
    let before = state.camera();
    state.handle(drag(Button::Left, 0.0, 50.0));
    assert!(state.camera().eye.y > before.eye.y, "dragging down raises the camera");
    state.handle(drag(Button::Left, 0.0, -50.0));
    check_same_camera(state.camera(), before, 1e-4 * d);
}

#[test]
fn the_wheel_zooms_by_notches_and_stops_at_the_limit() {
    let mut state = ViewerState::new(cube_scene());
    let home = state.home_camera();
    state.handle(Event::Wheel(1.0));
    assert!((magnification(&state.camera(), &home) - 1.1).abs() < 1e-5);
    state.handle(Event::Wheel(-2.0));
    assert!((magnification(&state.camera(), &home) - 1.0 / 1.1).abs() < 1e-5);
    state.handle(Event::Wheel(1000.0));
    assert!((magnification(&state.camera(), &home) - MAX_ZOOM).abs() < 1e-3 * MAX_ZOOM);
    state.handle(Event::Wheel(-5000.0));
    assert!((magnification(&state.camera(), &home) - 1.0 / MAX_ZOOM).abs() < 1e-3 / MAX_ZOOM);
    // The target stays; near and far still hold the cube (radius √3/2·…).
    check_close(state.camera().target, home.target, 1e-5);
    let zline::scene::Projection::Perspective { near, far, .. } = state.camera().projection else { panic!() };
    let to_center = state.camera().eye.length();
    assert!(near < to_center - 0.87 && far > to_center + 0.87, "{near} {far} {to_center}");
}

#[test]
fn a_pan_moves_eye_and_target_across_the_view() {
    let mut state = ViewerState::new(cube_scene());
    let home = state.home_camera();
    let d = (home.eye - home.target).length();
    let zline::scene::Projection::Perspective { fovy_degrees, .. } = home.projection else { panic!() };
    // 600 px high: one pixel is 2·d·tan(fovy/2)/600 at the target.
    let per_pixel = 2.0 * d * (fovy_degrees.to_radians() / 2.0).tan() / 600.0;
    state.handle(Event::Drag { button: Button::Left, dx: 30.0, dy: 0.0, shift: true });
    let moved = state.camera();
    let right = (home.target - home.eye).cross(home.up).normalize();
    check_close(moved.target - home.target, -right * 30.0 * per_pixel, 1e-4 * d);
    check_close(moved.eye - home.eye, -right * 30.0 * per_pixel, 1e-4 * d);
    // A right drag pans too.
    state.handle(drag(Button::Right, -30.0, 0.0));
    check_same_camera(state.camera(), home, 1e-4 * d);
}

#[test]
fn previews_keep_to_the_budget_and_the_full_frame_follows_when_still() {
    let mut state = ViewerState::new(cube_scene());
    let first = draw(&mut state, Duration::from_millis(100));
    assert_eq!((first.block, first.width, first.height, first.full), (1, 800, 600, true));
    assert_eq!(state.frame_to_render(), None, "nothing changed");
    state.handle(Event::Tick(Duration::from_secs(1)));
    assert_eq!(state.frame_to_render(), None, "time alone changes nothing");
    // A slow full frame (100 ms): moving, frames of 1/2 the resolution
    // (a quarter of the samples: 25 ms, under 33).
    state.handle(drag(Button::Left, 5.0, 0.0));
    let preview = draw(&mut state, Duration::from_millis(25));
    assert_eq!((preview.block, preview.width, preview.height, preview.ssaa), (2, 400, 300, 1));
    assert!(!preview.full);
    assert_eq!(state.frame_to_render(), None, "the preview is up to date");
    state.handle(Event::Tick(Duration::from_secs(1) + REFINE_AFTER - Duration::from_millis(1)));
    assert_eq!(state.frame_to_render(), None, "still moving");
    state.handle(Event::Tick(Duration::from_secs(1) + REFINE_AFTER));
    let full = draw(&mut state, Duration::from_millis(10));
    assert_eq!((full.block, full.width, full.height, full.full), (1, 800, 600, true));
    assert_eq!(state.frame_to_render(), None);
    // Fast frames: previews at full resolution. The history holds the
    // slowest of the last four frames: three more fast frames clear it.
    for _ in 0..3 {
        state.handle(Event::Key(Action::CycleWireframe));
        draw(&mut state, Duration::from_millis(10));
    }
    state.handle(drag(Button::Left, 5.0, 0.0));
    assert_eq!(state.frame_to_render().map(|r| (r.block, r.full)), Some((1, false)));
    // A very slow frame: the coarsest preview.
    state.handle(Event::FrameRendered(state.full_request(), Duration::from_secs(100)));
    state.handle(drag(Button::Left, 5.0, 0.0));
    assert_eq!(state.frame_to_render().map(|r| r.block), Some(zline::viewer::state::MAX_BLOCK));
}

#[test]
fn each_key_changes_its_setting_and_nothing_else() {
    let state = ViewerState::new(cube_scene());
    let base = state.toggles();
    let check = |action: Action, expected: Toggles| {
        let mut s = state.clone();
        s.handle(Event::Key(action));
        assert_eq!(s.toggles(), expected, "{action:?}");
        check_same_camera(s.camera(), state.camera(), 0.0);
        assert!(s.frame_to_render().is_some(), "{action:?} draws a frame");
    };
    check(Action::Shading(ShadingMode::Flat), Toggles { shading: ShadingMode::Flat, ..base });
    check(Action::Shading(ShadingMode::Gouraud), Toggles { shading: ShadingMode::Gouraud, ..base });
    check(Action::ToggleTextures, Toggles { textures: false, ..base });
    check(Action::ToggleFog, Toggles { fog: true, ..base });
    check(Action::CycleWireframe, Toggles { wireframe: WireframeMode::All, ..base });
    // A model has no shadow planes: none → map.
    check(Action::CycleShadows, Toggles { shadows: ShadowMode::Map, ..base });
    check(Action::MoreSamples, Toggles { ssaa: 2, ..base });
    check(Action::ToggleVisibility, Toggles { visibility: zline::scene::Visibility::Painter, ..base });
    check(Action::ToggleCulling, Toggles { culling: false, ..base });
    let affine = zline::scene::Interpolation::ScreenLinear;
    check(Action::ToggleInterpolation, Toggles { interpolation: affine, ..base });
    // The cycles come round; − stops at 1.
    let mut s = state.clone();
    for _ in 0..4 {
        s.handle(Event::Key(Action::CycleWireframe));
    }
    assert_eq!(s.toggles(), base);
    s.handle(Event::Key(Action::FewerSamples));
    assert_eq!(s.toggles(), base);
    // The overlay, screenshot and quit keys change no setting.
    for action in [Action::ToggleOverlay, Action::Screenshot, Action::Quit] {
        s.handle(Event::Key(action));
        assert_eq!(s.toggles(), base, "{action:?}");
    }
    assert!(!s.overlay() && s.take_screenshot() && !s.take_screenshot() && s.quit());
}

#[test]
fn the_keys_reach_the_scene_rendered() {
    let mut room = zline::scenes::room_scene();
    room.shadows.mode = ShadowMode::None;
    let mut room = ViewerState::new(room);
    room.handle(Event::Key(Action::CycleShadows));
    assert_eq!(room.toggles().shadows, ShadowMode::Planar, "the room has shadow planes");
    let spot = repo().join("assets/obj/spot/spot.obj");
    let meshes = zline::io::load_obj(&spot).unwrap();
    let mut state = ViewerState::new(zline::io::scene_for_model(meshes, RenderSettings::default()));
    let textured =
        |s: &ViewerState| s.scene(&s.full_request()).objects.iter().any(|o| o.mesh.diffuse_map.is_some());
    assert!(textured(&state));
    for action in [
        Action::ToggleTextures,
        Action::ToggleFog,
        Action::Shading(ShadingMode::Gouraud),
        Action::MoreSamples,
    ] {
        state.handle(Event::Key(action));
    }
    let scene = state.scene(&state.full_request());
    assert!(!textured(&state));
    assert!(
        scene.fog.is_some() && scene.settings.shading == ShadingMode::Gouraud && scene.settings.ssaa == 2
    );
    state.handle(Event::Key(Action::ToggleTextures));
    assert!(textured(&state));
    // The classroom's switches, each with its line on what to see; twice
    // brings the scene back.
    assert_eq!(state.hint(), None);
    for (action, says) in [
        (Action::ToggleVisibility, "painter"),
        (Action::ToggleCulling, "culling off"),
        (Action::ToggleInterpolation, "affine"),
    ] {
        let before = state.scene(&state.full_request());
        state.handle(Event::Key(action));
        assert!(state.hint().is_some_and(|h| h.contains(says)), "{action:?}: {:?}", state.hint());
        let scene = state.scene(&state.full_request());
        assert_ne!(
            (
                scene.settings.visibility,
                scene.settings.interpolation,
                scene.objects.iter().any(|o| o.cull_back_faces)
            ),
            (
                before.settings.visibility,
                before.settings.interpolation,
                before.objects.iter().any(|o| o.cull_back_faces)
            ),
            "{action:?} reaches the scene"
        );
        state.handle(Event::Key(action));
        assert_eq!(state.hint(), None, "{action:?} twice");
    } // Step mode: the first triangles only, in draw order.
    let count = |s: &ViewerState| {
        s.scene(&s.full_request()).objects.iter().map(|o| o.mesh.triangles.len()).sum::<usize>()
    };
    let all = count(&state);
    state.handle(Event::Key(Action::ToggleStepMode));
    assert_eq!(count(&state), 1);
    for _ in 0..4 {
        state.handle(Event::Key(Action::StepForward));
    }
    state.handle(Event::Key(Action::StepBack));
    assert_eq!(count(&state), 4);
    assert!(
        state.hint().is_some_and(|h| h.contains(&format!("first 4 of {all} triangles"))),
        "{:?}",
        state.hint()
    );
    state.handle(Event::Key(Action::ScanlineForward));
    assert!(state.toggles().scanline.is_some());
    assert!(state.hint().is_some_and(|h| h.contains("scanline")), "{:?}", state.hint());
    state.handle(Event::Key(Action::StepForward));
    assert_eq!(state.toggles().scanline, None, "a new triangle starts whole");
    state.handle(Event::Key(Action::ToggleStepMode));
    assert_eq!((count(&state), state.hint()), (all, None));
    // O: the overdraw heat map under each tie rule, then the image again.
    use zline::raster::TieRule;
    for (rule, says) in
        [(TieRule::TopLeft, "overdraw (O)"), (TieRule::Closed, "twice"), (TieRule::Open, "neither")]
    {
        state.handle(Event::Key(Action::CycleOverdraw));
        assert_eq!(state.toggles().overdraw, Some(rule));
        assert!(state.hint().is_some_and(|h| h.contains(says)), "{rule:?}: {:?}", state.hint());
    }
    state.handle(Event::Key(Action::CycleOverdraw));
    assert_eq!((state.toggles().overdraw, state.hint()), (None, None));
    // D: the depth buffer's picture; X: a shuffled order of the same
    // triangles.
    state.handle(Event::Key(Action::ToggleDepthView));
    assert!(state.hint().is_some_and(|h| h.contains("depth buffer")), "{:?}", state.hint());
    state.handle(Event::Key(Action::ToggleDepthView));
    let order = |s: &ViewerState| s.scene(&s.full_request()).objects[0].mesh.triangles.clone();
    let plain = order(&state);
    state.handle(Event::Key(Action::ToggleShuffle));
    assert!(state.hint().is_some_and(|h| h.contains("shuffled")), "{:?}", state.hint());
    let (mut shuffled, mut sorted) = (order(&state), plain.clone());
    assert_ne!(shuffled, plain);
    shuffled.sort_unstable();
    sorted.sort_unstable();
    assert_eq!(shuffled, sorted);
    state.handle(Event::Key(Action::ToggleShuffle));
    assert_eq!((order(&state), state.hint()), (plain, None));
    // A click asks for the inspector once, at a pixel inside the window,
    // and draws the frame again (with the inspector's line).
    let before = state.frame_to_render();
    state.handle(Event::Click(5000, 7));
    let (w, _) = state.window();
    assert_eq!(state.take_inspection(), Some((w - 1, 7)));
    assert_eq!(state.take_inspection(), None);
    assert!(state.frame_to_render().is_some() || before.is_some());
}

#[test]
fn reset_brings_back_the_framed_camera() {
    let mut state = ViewerState::new(cube_scene());
    let home = state.camera();
    state.handle(drag(Button::Left, 123.0, -45.0));
    state.handle(drag(Button::Middle, 17.0, 9.0));
    state.handle(Event::Wheel(3.0));
    assert!((state.camera().eye - home.eye).length() > 0.1);
    state.handle(Event::Key(Action::ResetCamera));
    assert_eq!(state.camera(), home);
    assert_eq!(home, cube_scene().camera, "the home camera is the model's framing");
}

#[test]
fn a_resized_window_draws_at_its_new_size() {
    let mut state = ViewerState::new(cube_scene());
    draw(&mut state, Duration::from_millis(5));
    state.handle(Event::Resize(300, 200));
    let r = draw(&mut state, Duration::from_millis(5));
    assert_eq!((r.width, r.height, r.full), (300, 200, true));
    let scene = state.scene(&r);
    assert_eq!((scene.settings.width, scene.settings.height), (300, 200));
}

/// The ray tracer's viewer refines progressively: when still, the block
/// halves frame by frame down to the full frame; a move starts again from
/// the preview.
#[test]
fn progressive_refinement_halves_the_block_down_to_the_full_frame() {
    let mut state = ViewerState::new(cube_scene());
    state.refine_progressively();
    let steps: Vec<(u32, bool)> =
        (0..4).map(|_| draw(&mut state, Duration::from_millis(5))).map(|r| (r.block, r.full)).collect();
    assert_eq!(steps, [(8, false), (4, false), (2, false), (1, true)]);
    assert_eq!(state.frame_to_render(), None, "the full frame is shown");
    // Slow frames: a move gives a coarse preview, then the refinement
    // continues from it once the input is still.
    state.handle(Event::FrameRendered(state.full_request(), Duration::from_secs(10)));
    state.handle(drag(Button::Left, 5.0, 0.0));
    let preview = draw(&mut state, Duration::from_millis(30));
    assert_eq!((preview.block, preview.full), (8, false));
    state.handle(Event::Tick(REFINE_AFTER));
    let rest: Vec<u32> = (0..3).map(|_| draw(&mut state, Duration::from_millis(30)).block).collect();
    assert_eq!(rest, [4, 2, 1]);
    assert_eq!(state.frame_to_render(), None);
}

/// `zline view --save-first-frame` against `zline render`, same flags.
#[test]
fn the_first_frame_is_the_image_render_draws() {
    let dir = tempfile::tempdir().unwrap();
    let spot = repo().join("assets/obj/spot/spot.obj");
    let flag_sets: [&[&str]; 2] = [
        &["--size", "160x120"],
        &[
            "--size",
            "200x150",
            "--shading",
            "gouraud",
            "--azimuth",
            "30",
            "--elevation",
            "-10",
            "--background",
            "0.1,0.2,0.3",
            "--ssaa",
            "2",
        ],
    ];
    for flags in flag_sets {
        let (rendered, viewed) = (dir.path().join("render.png"), dir.path().join("view.png"));
        let mut render = vec!["render", spot.to_str().unwrap(), "-o", rendered.to_str().unwrap()];
        render.extend_from_slice(flags);
        let mut view = vec!["view", spot.to_str().unwrap(), "--save-first-frame", viewed.to_str().unwrap()];
        view.extend_from_slice(flags);
        for args in [&render, &view] {
            let out = zline(args);
            assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        }
        assert_eq!(std::fs::read(&rendered).unwrap(), std::fs::read(&viewed).unwrap(), "{flags:?}");
    }
}

/// The same with the ray tracer, chosen by the flag or by a scene file.
#[test]
fn the_first_traced_frame_is_the_image_render_draws() {
    let dir = tempfile::tempdir().unwrap();
    let spot = repo().join("assets/obj/spot/spot.obj");
    let scene = dir.path().join("traced.toml");
    let text = format!(
        "[render]\nrenderer = \"raytrace\"\n[raytrace]\ndepth = 2\n[[objects]]\nmodel = {:?}\n",
        spot.to_str().unwrap()
    );
    std::fs::write(&scene, text).unwrap();
    let cases: [(&std::path::Path, &[&str]); 2] =
        [(&spot, &["--renderer", "raytrace", "--size", "96x72"]), (&scene, &["--size", "80x60"])];
    for (input, flags) in cases {
        let (rendered, viewed) = (dir.path().join("render.png"), dir.path().join("view.png"));
        let input = input.to_str().unwrap();
        let mut render = vec!["render", input, "-o", rendered.to_str().unwrap(), "--allow-paths-outside"];
        render.extend_from_slice(flags);
        let mut view =
            vec!["view", input, "--save-first-frame", viewed.to_str().unwrap(), "--allow-paths-outside"];
        view.extend_from_slice(flags);
        for args in [&render, &view] {
            let out = zline(args);
            assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        }
        let said = String::from_utf8_lossy(&zline(&render).stderr).into_owned();
        assert!(said.contains("ray traced"), "{said}");
        assert_eq!(std::fs::read(&rendered).unwrap(), std::fs::read(&viewed).unwrap(), "{flags:?}");
    }
}

#[test]
fn without_a_display_view_says_so() {
    let spot = repo().join("assets/obj/spot/spot.obj");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_zline"))
        .args(["view", spot.to_str().unwrap(), "--size", "64x48"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    crate::check_clean_error(&out, &["cannot open a window", "X server"]);
}

/// The window on a private Xvfb, read back from the X server's framebuffer:
/// the screen shows zline's frame (all but the frame-time text).
#[test]
fn under_xvfb_the_window_shows_the_frame() {
    let Some(xvfb) = zline::viewer::capture::find_xvfb() else {
        eprintln!("skipped: Xvfb not found (apt-get install xvfb)");
        return;
    };
    let spot = repo().join("assets/obj/spot/spot.obj");
    // Rasterized, and ray-traced (refined to the full frame in 4 frames).
    for extra in [&[][..], &["--renderer", "raytrace"][..]] {
        let mut args: Vec<std::ffi::OsString> = vec![spot.clone().into(), "--size".into(), "320x240".into()];
        args.extend(extra.iter().map(Into::into));
        let capture = zline::viewer::capture::under_xvfb(
            &xvfb,
            std::path::Path::new(env!("CARGO_BIN_EXE_zline")),
            &args,
            (320, 240),
            40,
        )
        .unwrap();
        assert_eq!((capture.screen.width, capture.screen.height), (320, 240));
        let distinct: std::collections::HashSet<u32> = capture.screen.pixels.iter().copied().collect();
        assert!(distinct.len() > 100, "{extra:?}: the screen is blank or flat: {} colours", distinct.len());
        // The text band over 320x240 is 2·4 + 2·10 rows of the width (12 %);
        // the rest is the frame exactly.
        let share = 100.0 * capture.matching;
        assert!(capture.matching > 0.8, "{extra:?}: only {share:.1} % of the screen is the frame");
    }
}

#[test]
fn keys_given_on_the_command_line_reach_the_first_frame() {
    let dir = tempfile::tempdir().unwrap();
    let spot = repo().join("assets/obj/spot/spot.obj");
    let spot = spot.to_str().unwrap();
    let path = |name: &str| dir.path().join(name).to_str().unwrap().to_owned();
    let run = |args: &[&str]| {
        let out = zline(args);
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        image::open(args.last().unwrap()).unwrap().to_rgb8()
    };
    let size = ["--size", "160x120"];
    // The overdraw map of closed triangles (O twice) is render's --overdraw
    // --tie-rule closed.
    let (viewed, drawn) = (path("view.png"), path("heat.png"));
    let shown = run(&["view", spot, size[0], size[1], "--keys", "O O", "--save-first-frame", &viewed]);
    let out = zline(&[
        "render",
        spot,
        size[0],
        size[1],
        "-o",
        &path("x.png"),
        "--tie-rule",
        "closed",
        "--overdraw",
        &drawn,
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(shown, image::open(&drawn).unwrap().to_rgb8());
    // Step mode at the 300th triangle: more drawn than at the 3rd, less
    // than the whole model.
    let drawn_pixels = |keys: &str| {
        let img = run(&["view", spot, size[0], size[1], "--keys", keys, "--save-first-frame", &viewed]);
        let background = *img.get_pixel(0, 0);
        img.pixels().filter(|p| **p != background).count()
    };
    let (few, some, all) = (drawn_pixels("P 2*."), drawn_pixels("P 299*."), drawn_pixels("1"));
    assert!(few < some && some < all, "{few} {some} {all}");
    // Scanline steps: the 300th triangle drawn down to a row is the frame
    // with 300 triangles above and on the row, with 299 below it.
    let with = run(&["view", spot, size[0], size[1], "--keys", "P 299*.", "--save-first-frame", &viewed]);
    let without = run(&["view", spot, size[0], size[1], "--keys", "P 298*.", "--save-first-frame", &viewed]);
    let rows = |img: &image::RgbImage, r: std::ops::Range<u32>| {
        r.flat_map(|y| (0..img.width()).map(move |x| img.get_pixel(x, y).0)).collect::<Vec<_>>()
    };
    let mut partly = 0;
    for step in [1u32, 3, 6, 12, 40] {
        let keys = format!("P 299*. {step}*]");
        let partial = run(&["view", spot, size[0], size[1], "--keys", &keys, "--save-first-frame", &viewed]);
        let split = (0..=120).find(|&r| {
            rows(&partial, 0..r) == rows(&with, 0..r) && rows(&partial, r..120) == rows(&without, r..120)
        });
        assert!(split.is_some(), "{keys}: not the full frame above a row and the previous one below");
        partly += usize::from(partial != with && partial != without);
    }
    assert!(partly > 0, "no step showed the 300th triangle partly drawn");
    // D: the depth image's picture, as --depth-image's 16-bit PNG rounded
    // to 8 bits.
    let depth16 = path("depth.png");
    let out = zline(&["render", spot, size[0], size[1], "-o", &path("x.png"), "--depth-image", &depth16]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let shown = run(&["view", spot, size[0], size[1], "--keys", "D", "--save-first-frame", &viewed]);
    let want = image::open(&depth16).unwrap().to_luma16();
    for (p, q) in shown.pixels().zip(want.pixels()) {
        let g = ((u32::from(q.0[0]) * 255 + 32767) / 65535) as u8;
        assert_eq!(p.0, [g, g, g]);
    }
    // --click: the inspector's report, checked against the frame.
    let out = zline(&["view", spot, size[0], size[1], "--click", "80,60", "--save-first-frame", &viewed]);
    let report = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success() && report.contains("pixel (80, 60) of 160x120"), "{report}");
    assert!(report.contains("the rendered image's pixel is the same"), "{report}");
    let out = zline(&["view", spot, "--click", "80;60", "--save-first-frame", &viewed]);
    crate::check_clean_error(&out, &["--click", "X,Y"]);
    for (keys, says) in [("Q", "not a key"), ("0*.", "count before *"), ("P 100001*.", "count before *")] {
        let out = zline(&["view", spot, "--keys", keys, "--save-first-frame", &viewed]);
        crate::check_clean_error(&out, &["--keys", says]);
    }
}

#[test]
fn bad_view_arguments_are_clean_errors() {
    let spot = repo().join("assets/obj/spot/spot.obj");
    let spot = spot.to_str().unwrap();
    let out = zline(&["view", spot, "-o", "shots.gif"]);
    crate::check_clean_error(&out, &["shots.gif", ".png"]);
    let out = zline(&["view", spot, "--save-first-frame", "/nonexistent-folder/x.png"]);
    crate::check_clean_error(&out, &["/nonexistent-folder/x.png", "does not exist"]);
    let out = zline(&["view", "model.xyz", "--save-first-frame", "/tmp/x.png"]);
    crate::check_clean_error(&out, &["model.xyz", "unsupported input"]);
    let out = zline(&["view", spot, "--exit-after-frames", "0"]);
    assert_eq!(out.status.code(), Some(2), "clap refuses 0 frames");
}
