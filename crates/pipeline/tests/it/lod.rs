//! The adaptive mode's level of detail (`zline_pipeline::lod`): a dense
//! mesh far away is drawn from a simplified level whose image stays close
//! to the full mesh's; close up, the full mesh is drawn (the same bytes);
//! the image does not depend on the thread count or the tile size; and
//! meshes the simplifier cannot use are drawn in full without a panic.

use std::f32::consts::{PI, TAU};
use std::sync::Arc;

use glam::{Mat4, Vec3};
use zline_pipeline::lod::{pyramid, Pyramid, LEVELS, MIN_TRIANGLES};
use zline_pipeline::{Image, RenderOptions, RenderStats, Renderer};
use zline_scene::{Mesh, Scene};
use zline_shading::{Light, Material, ShadingMode};

use crate::support::{object, scene};

/// A bumpy sphere of radius ≈ 1: a uv sphere with a radial ripple (so the
/// simplifier has curvature of two scales to keep), vertex normals from
/// its faces, 2·segments·(rings − 1) triangles.
fn bumpy_sphere(rings: u32, segments: u32) -> Arc<Mesh> {
    let mut positions = vec![Vec3::Y];
    for i in 1..rings {
        let theta = PI * i as f32 / rings as f32;
        for j in 0..segments {
            let phi = TAU * j as f32 / segments as f32;
            let d = Vec3::new(theta.sin() * phi.sin(), theta.cos(), theta.sin() * phi.cos());
            positions.push(d * (1.0 + 0.05 * (9.0 * theta).sin() * (7.0 * phi).cos()));
        }
    }
    positions.push(Vec3::NEG_Y);
    let south = positions.len() as u32 - 1;
    let row = |i: u32, j: u32| 1 + (i - 1) * segments + j % segments;
    let mut triangles: Vec<[u32; 3]> = (0..segments).map(|j| [0, row(1, j), row(1, j + 1)]).collect();
    for i in 1..rings - 1 {
        for j in 0..segments {
            let (a, b, c, d) = (row(i, j), row(i + 1, j), row(i + 1, j + 1), row(i, j + 1));
            triangles.extend([[a, b, c], [a, c, d]]);
        }
    }
    triangles.extend((0..segments).map(|j| [south, row(rings - 1, j + 1), row(rings - 1, j)]));
    let material = Material::plastic(Vec3::new(0.8, 0.5, 0.3), 0.5, 24.0);
    Arc::new(Mesh::new("bumpy", positions, None, triangles, material).unwrap())
}

/// The sphere `distance` in front of the origin camera (90° field of
/// view), Phong, adaptive tolerance `tolerance`, 160×160.
fn sphere_scene(mesh: Arc<Mesh>, distance: f32, tolerance: Option<f32>) -> Scene {
    let lights = vec![Light::Directional { direction: Vec3::new(-0.4, -0.5, -1.0), color: Vec3::splat(0.9) }];
    let mut o = object(mesh, Some(ShadingMode::Phong));
    o.world_from_object = Mat4::from_translation(Vec3::new(0.0, 0.0, -distance));
    let mut s = scene(160, Vec3::splat(0.1), lights, vec![o]);
    s.camera.projection =
        zline_scene::Projection::Perspective { fovy_degrees: 90.0, near: 0.5, far: distance + 2.0 };
    s.settings.adaptive_tolerance = tolerance;
    s
}

/// The image, its stats and the levels drawn, with or without the levels.
fn draw(scene: &Scene, level_of_detail: bool) -> (Image, RenderStats, Vec<Option<usize>>) {
    let mut renderer = Renderer::default();
    renderer.set_level_of_detail(level_of_detail);
    let mut image = Image::empty();
    let stats = renderer.render_into(scene, &RenderOptions::default(), &mut image);
    (image, stats, renderer.levels_drawn().to_vec())
}

/// Share of pixels whose largest channel differs by more than `tolerance`,
/// and the RMSE over all channels, in 8-bit steps.
fn difference(a: &Image, b: &Image, tolerance: u8) -> (f64, f64) {
    let (a, b) = (a.to_rgb(), b.to_rgb());
    let (mut over, mut squares) = (0usize, 0.0f64);
    for (p, q) in a.chunks_exact(3).zip(b.chunks_exact(3)) {
        let d = p.iter().zip(q).map(|(x, y)| x.abs_diff(*y)).max().unwrap();
        over += usize::from(d > tolerance);
        squares += p.iter().zip(q).map(|(x, y)| (f64::from(*x) - f64::from(*y)).powi(2)).sum::<f64>();
    }
    let pixels = (a.len() / 3) as f64;
    (over as f64 / pixels, (squares / (3.0 * pixels)).sqrt())
}

/// The scene with its object moved `pixels` to the right at the object's
/// depth (90° field of view, 160 px: 2·d/160 units per pixel).
fn moved(scene: &Scene, distance: f32, pixels: f32) -> Scene {
    let mut s = scene.clone();
    let shift = Mat4::from_translation(Vec3::X * (2.0 * distance / 160.0) * pixels);
    s.objects[0].world_from_object = shift * s.objects[0].world_from_object;
    s
}

#[test]
fn a_far_dense_mesh_is_drawn_simplified_and_stays_close_to_the_full_mesh() {
    // 2·256·127 = 65 024 triangles; at distance 5 the sphere is ≈ 34 px
    // across, its mean triangle ≲ 0.1 px².
    let mesh = bumpy_sphere(128, 256);
    let distance = 5.0;
    for tolerance in [2u8, 8] {
        let s = sphere_scene(mesh.clone(), distance, Some(f32::from(tolerance)));
        let (full, full_stats, none) = draw(&s, false);
        let (lod, lod_stats, levels) = draw(&s, true);
        assert!(none.is_empty(), "levels reported with the level of detail off: {none:?}");
        assert_eq!((full_stats.simplified, lod_stats.simplified), (0, 1), "τ = {tolerance}");
        assert_eq!(full_stats.triangles_drawn, full_stats.triangles, "τ = {tolerance}");
        assert!(lod_stats.triangles_drawn * 4 < lod_stats.triangles, "τ = {tolerance}: {lod_stats:?}");
        assert!(matches!(levels[..], [Some(_)]), "τ = {tolerance}: no level drawn: {levels:?}");
        // Setup makes no primitive of a triangle whose bounds hold no
        // sample centre, so most of the full mesh's sub-pixel triangles
        // are gone before they count: the level saves setup work, not
        // primitives four to one.
        assert!(full_stats.primitives * 4 < full_stats.triangles_drawn, "τ = {tolerance}: {full_stats:?}");
        assert!(
            lod_stats.primitives < full_stats.primitives,
            "τ = {tolerance}: {} primitives of {}",
            lod_stats.primitives,
            full_stats.primitives
        );
        // The measure: pixels off by more than τ, and the RMSE, each no
        // more than the full mesh moved ¼ px changes them (its triangles
        // are far below a pixel, so such a move already resamples them).
        let (over, rmse) = difference(&lod, &full, tolerance);
        let shifted = draw(&moved(&s, distance, 0.25), false).0;
        let (over_moved, rmse_moved) = difference(&shifted, &full, tolerance);
        eprintln!(
            "τ = {tolerance}: level {levels:?}, {} of {} primitives; LOD {over:.4} over τ, RMSE {rmse:.3}; ¼ px move {over_moved:.4}, {rmse_moved:.3}",
            lod_stats.primitives, full_stats.primitives
        );
        assert!(
            over <= over_moved && rmse <= rmse_moved,
            "τ = {tolerance}: LOD {over:.4} over τ, RMSE {rmse:.3}; ¼ px move {over_moved:.4}, {rmse_moved:.3}"
        );
        // And in absolute terms: a thin rim of the 34-px disc at most.
        assert!(over <= 0.01, "τ = {tolerance}: {:.3} % of pixels over τ", 100.0 * over);
    }
}

#[test]
fn close_up_objects_keep_the_full_mesh() {
    let mesh = bumpy_sphere(64, 128);
    // Close: the sphere fills the view; its triangles cover many pixels.
    for distance in [2.5, 4.0] {
        let s = sphere_scene(mesh.clone(), distance, Some(8.0));
        let (full, _, _) = draw(&s, false);
        let (lod, _, levels) = draw(&s, true);
        assert_eq!(levels, [None], "distance {distance}");
        assert!(lod == full, "distance {distance}: the image changed");
    }
    // Without the adaptive mode there is no level of detail at all.
    let s = sphere_scene(mesh, 40.0, None);
    let (_, _, levels) = draw(&s, true);
    assert!(levels.is_empty());
}

#[test]
fn simplified_images_do_not_depend_on_threads_tiles_or_the_cache() {
    let s = sphere_scene(bumpy_sphere(64, 128), 10.0, Some(8.0));
    let (reference, _, levels) = draw(&s, true);
    assert!(matches!(levels[..], [Some(_)]), "{levels:?}");
    for (threads, tile_size) in [(1, 64), (2, 7), (3, 33)] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        let image = pool.install(|| {
            let mut r = Renderer::default();
            let mut image = Image::empty();
            r.render_into(&s, &RenderOptions { tile_size }, &mut image);
            image
        });
        assert!(image == reference, "{threads} threads, tile {tile_size}: a different image");
    }
    // A copy of the mesh (another Arc: its levels are built afresh) gives
    // the same bytes.
    let mut copy = s.clone();
    copy.objects[0].mesh = Arc::new((*s.objects[0].mesh).clone());
    assert!(draw(&copy, true).0 == reference, "rebuilt levels differ");
    // The cache hands the same pyramid for the same Arc.
    assert!(Arc::ptr_eq(&pyramid(&s.objects[0].mesh), &pyramid(&s.objects[0].mesh)));
}

fn raw(positions: Vec<Vec3>, triangles: Vec<[u32; 3]>) -> Mesh {
    Mesh {
        name: "raw".into(),
        normals: vec![Vec3::Z; positions.len()],
        positions,
        triangles,
        material: Material::default(),
        uvs: Vec::new(),
        colors: Vec::new(),
        diffuse_map: None,
        tangents: Vec::new(),
        normal_map: None,
        surface_maps: Default::default(),
    }
}

#[test]
fn meshes_the_simplifier_cannot_use_are_drawn_in_full_without_a_panic() {
    let n = MIN_TRIANGLES as u32 + 8;
    let line: Vec<Vec3> = (0..n + 2).map(|i| Vec3::new(i as f32 * 1e-3, 0.0, 0.0)).collect();
    let fan: Vec<[u32; 3]> = (0..n).map(|i| [i, i + 1, i + 2]).collect();
    let point = vec![Vec3::ONE; n as usize + 2];
    let mut nan = line.clone();
    nan[5] = Vec3::NAN;
    let cases = [
        ("empty", (true, raw(Vec::new(), Vec::new()))),
        ("one point", (true, raw(point, fan.clone()))),
        ("collinear", (true, raw(line.clone(), fan.clone()))),
        ("NaN position", (true, raw(nan, fan.clone()))),
        ("index out of range", (true, raw(line.clone(), [fan.clone(), vec![[0, 1, n + 100]]].concat()))),
        ("tiny", (true, raw(line[..3].to_vec(), vec![[0, 1, 2]]))),
        (
            "NaN normal",
            (true, Mesh { normals: vec![Vec3::NAN; line.len()], ..raw(line.clone(), fan.clone()) }),
        ),
        ("short uvs", (false, Mesh { uvs: vec![glam::Vec2::ZERO; 3], ..raw(line.clone(), fan.clone()) })),
        ("no normals", (false, Mesh { normals: Vec::new(), ..raw(line.clone(), fan.clone()) })),
    ];
    // (Meshes without one normal or one uv per vertex break the Mesh
    // invariant the vertex stage relies on: only the simplifier sees them,
    // and makes no level of them.)
    for (name, (render, mesh)) in cases {
        let p = Pyramid::new(&mesh);
        for k in 0..LEVELS + 1 {
            let level = p.level(&mesh, k);
            assert!(level.is_none() || render, "{name}: a level of a broken mesh");
        }
        if !render {
            continue;
        }
        let s = sphere_scene(Arc::new(mesh), 30.0, Some(8.0));
        let (_, _, levels) = draw(&s, true);
        assert_eq!(levels.len(), 1, "{name}");
    }
}
