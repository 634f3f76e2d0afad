//! Lines (`RenderSettings::wireframe`): a cube seen from near a corner,
//! orthographic, has 9 visible and 3 hidden edges; each edge is classified
//! by the pixels drawn along it in every mode.

use std::sync::Arc;

use glam::{DMat4, DVec2, DVec3, Mat4, Vec3};
use zline_pipeline::{render, Image, RenderOptions};
use zline_scene::{Camera, Object, Projection, Scene, Visibility, Wireframe, WireframeMode};
use zline_shading::{Light, Material, ShadingMode};

use crate::support::{draw, scene};

const SIZE: u32 = 160;

/// A cube of side 1.6 at the origin, flat-shaded light grey on white,
/// seen orthographically from (3, 2.5, 2): the faces +x, +y, +z face the
/// viewer, so the three edges at the corner (−0.8, −0.8, −0.8) are hidden.
fn cube_scene(mode: WireframeMode) -> Scene {
    let material = Material { ka: Vec3::splat(0.8), kd: Vec3::splat(0.5), ..Material::DEFAULT };
    let cube = Object {
        mesh: Arc::new(zline_scene::Mesh { material, ..zline_scene::cube(1.6) }),
        world_from_object: Mat4::IDENTITY,
        material: None,
        shading: Some(ShadingMode::Flat),
        cull_back_faces: true,
    };
    let light = Light::Directional { direction: Vec3::new(-0.3, -1.0, -0.6), color: Vec3::splat(0.4) };
    let mut s = scene(SIZE, Vec3::splat(0.5), vec![light], vec![cube]);
    s.background = Vec3::ONE;
    s.camera = Camera {
        eye: Vec3::new(3.0, 2.5, 2.0),
        target: Vec3::ZERO,
        up: Vec3::Y,
        projection: Projection::Orthographic { height: 3.2, near: 0.5, far: 20.0 },
    };
    s.settings.wireframe = Wireframe { mode, only: false, feature_angle: Some(30.0) };
    s
}

/// The 12 edges of the cube, and whether each is hidden (touches the
/// corner (−, −, −)).
fn edges() -> Vec<([DVec3; 2], bool)> {
    let h = 0.8;
    let corner = |i: u32| {
        DVec3::new(
            if i & 1 != 0 { h } else { -h },
            if i & 2 != 0 { h } else { -h },
            if i & 4 != 0 { h } else { -h },
        )
    };
    let mut out = Vec::new();
    for i in 0..8u32 {
        for bit in [1, 2, 4] {
            if i & bit == 0 {
                out.push(([corner(i), corner(i | bit)], i == 0));
            }
        }
    }
    out
}

fn window(s: &Scene, p: DVec3) -> DVec2 {
    let m: DMat4 = (s.camera.clip_from_eye(1.0) * s.camera.eye_from_world()).as_dmat4();
    let c = m * p.extend(1.0);
    let size = f64::from(SIZE);
    DVec2::new((c.x / c.w + 1.0) * 0.5 * size, (1.0 - c.y / c.w) * 0.5 * size)
}

fn distance_to_segment(q: DVec2, a: DVec2, b: DVec2) -> f64 {
    let t = ((q - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
    (a + t * (b - a) - q).length()
}

/// Per edge: along its major axis, one entry per column (row) at least
/// 4 pixels from its ends: whether the line's black is drawn at the
/// line's pixel or one beside it across (`None` within 4 pixels of
/// another edge).
fn drawn_along(s: &Scene, image: &Image) -> Vec<(Vec<Option<bool>>, bool)> {
    let all: Vec<_> =
        edges().into_iter().map(|(e, hidden)| ([window(s, e[0]), window(s, e[1])], hidden)).collect();
    let mut out = Vec::new();
    for (k, &([a, b], hidden)) in all.iter().enumerate() {
        let d = b - a;
        let major = if d.x.abs() >= d.y.abs() { 0 } else { 1 };
        let (from, to) = (a[major].min(b[major]), a[major].max(b[major]));
        let mut runs = Vec::new();
        let mut i = (from + 4.0).ceil() as i32;
        while f64::from(i) + 0.5 < to - 4.0 {
            let c = f64::from(i) + 0.5;
            let t = (c - a[major]) / d[major];
            let p = a + t * d;
            let near_other =
                all.iter().enumerate().any(|(j, e)| j != k && distance_to_segment(p, e.0[0], e.0[1]) < 4.0);
            let minor = p[1 - major].floor() as i32;
            let black = (minor - 1..=minor + 1).any(|m| {
                let (x, y) = if major == 0 { (i, m) } else { (m, i) };
                image.pixel(x as u32, y as u32) == [0, 0, 0]
            });
            runs.push((!near_other).then_some(black));
            i += 1;
        }
        let known = runs.iter().flatten().count();
        assert!(known > 20, "edge {k}: too short to classify ({known} columns)");
        out.push((runs, hidden));
    }
    out
}

/// The lengths of the runs of undrawn columns with drawn ones on both
/// sides (pieces cut by excluded columns are measured apart).
fn gaps(drawn: &[Option<bool>]) -> Vec<usize> {
    let mut out = Vec::new();
    for piece in drawn.split(Option::is_none) {
        let first = piece.iter().position(|&d| d == Some(true));
        let last = piece.iter().rposition(|&d| d == Some(true));
        if let (Some(a), Some(b)) = (first, last) {
            out.extend(piece[a..=b].split(|&d| d == Some(true)).map(<[_]>::len).filter(|&n| n > 0));
        }
    }
    out
}

/// True when every column not excluded has `value`.
fn every(drawn: &[Option<bool>], value: bool) -> bool {
    drawn.iter().all(|&d| d.is_none_or(|d| d == value))
}

#[test]
fn a_cube_from_a_corner_shows_nine_edges_solid_and_three_dashed_or_removed() {
    let dashed = cube_scene(WireframeMode::HiddenDashed);
    let image = draw(&dashed);
    let classified = drawn_along(&dashed, &image);
    assert_eq!(classified.iter().filter(|e| !e.1).count(), 9);
    for (k, (drawn, hidden)) in classified.iter().enumerate() {
        let known = drawn.iter().flatten();
        let share = known.clone().filter(|&&d| d).count() as f64 / known.count() as f64;
        if *hidden {
            // 6 columns on, 4 off along the major axis.
            let g = gaps(drawn);
            assert!(g.len() >= 2, "hidden edge {k}: not dashed: {drawn:?}");
            assert!(g.iter().all(|&n| n == 4), "hidden edge {k}: gaps {g:?}");
            assert!((0.5..=0.7).contains(&share), "hidden edge {k}: {share} drawn");
        } else {
            assert!(every(drawn, true), "visible edge {k}: not solid: {drawn:?}");
        }
    }
    let removed = cube_scene(WireframeMode::HiddenRemoved);
    for (k, (drawn, hidden)) in drawn_along(&removed, &draw(&removed)).iter().enumerate() {
        assert!(every(drawn, !*hidden), "edge {k} (hidden: {hidden}) in hidden-removed: {drawn:?}");
    }
    let all = cube_scene(WireframeMode::All);
    for (k, (drawn, _)) in drawn_along(&all, &draw(&all)).iter().enumerate() {
        assert!(every(drawn, true), "edge {k}: every edge solid in mode all: {drawn:?}");
    }
    // Lines alone: the same lines on the background, the faces not drawn.
    let mut only = cube_scene(WireframeMode::HiddenDashed);
    only.settings.wireframe.only = true;
    let alone = draw(&only);
    assert_eq!(drawn_along(&only, &alone), classified, "lines alone: the same classification");
    assert!(alone.to_rgb().chunks(3).all(|c| c == [0, 0, 0] || c == [255, 255, 255]));
    // The painter leaves no depth: a depth-only pass decides the lines.
    let mut painter = cube_scene(WireframeMode::HiddenDashed);
    painter.settings.visibility = Visibility::Painter;
    assert_eq!(drawn_along(&painter, &draw(&painter)), classified, "painter: the same lines");
}

#[test]
fn lines_are_the_same_for_any_tile_size_thread_count_and_with_supersampling() {
    for ssaa in [1, 3] {
        let mut s = cube_scene(WireframeMode::HiddenDashed);
        s.settings.ssaa = ssaa;
        s.settings.wireframe.feature_angle = None;
        let reference = render(&s, &RenderOptions { tile_size: 64 }).0;
        for tile_size in [1, 7, 33, 1000] {
            for threads in [1, 3] {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let image = pool.install(|| render(&s, &RenderOptions { tile_size }).0);
                assert!(image == reference, "ssaa {ssaa}: tile {tile_size}, {threads} threads differ");
            }
        }
        if ssaa == 3 {
            // Lines stay 1 pixel wide and solid black where visible.
            let classified = drawn_along(&s, &reference);
            assert!(classified.iter().filter(|e| !e.1).all(|e| every(&e.0, true)));
        }
    }
}

#[test]
fn edges_through_and_behind_the_camera_are_clipped_without_panic() {
    // A perspective camera inside a large cube: every edge ends behind the
    // camera or beside it; the near plane cuts them before any divide.
    let mut s = cube_scene(WireframeMode::All);
    s.camera = Camera {
        eye: Vec3::new(0.1, 0.2, 0.3),
        target: Vec3::new(0.0, 0.0, -1.0),
        up: Vec3::Y,
        projection: Projection::Perspective { fovy_degrees: 100.0, near: 0.01, far: 50.0 },
    };
    s.objects[0].cull_back_faces = false;
    for eye in [Vec3::new(0.1, 0.2, 0.3), Vec3::new(0.8, 0.8, 0.8), Vec3::new(0.0, 0.0, 0.79)] {
        s.camera.eye = eye;
        let image = draw(&s);
        assert!(image.to_rgb().chunks(3).any(|c| c == [0, 0, 0]), "eye {eye}: lines inside the cube drawn");
    }
}
