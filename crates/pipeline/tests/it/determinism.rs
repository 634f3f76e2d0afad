//! The same scene gives the same bytes for any tile size and thread count
//! (SPEC §10).

use glam::Vec3;
use zline_pipeline::{render, RenderOptions};
use zline_scene::Interpolation;
use zline_shading::{Attenuation, Light, ShadingMode};

use crate::support::{colored, object, scene, wavy_grid};

fn test_scene(mode: ShadingMode, interpolation: Interpolation) -> zline_scene::Scene {
    let lights = vec![
        Light::Point {
            position: Vec3::new(1.0, 2.0, 0.0),
            color: Vec3::new(1.0, 0.8, 0.6),
            attenuation: Attenuation::new(1.0, 0.1, 0.05),
        },
        Light::Directional { direction: Vec3::new(-0.3, -0.2, -1.0), color: Vec3::new(0.2, 0.3, 0.5) },
    ];
    let mut s = scene(173, Vec3::splat(0.1), lights, vec![object(wavy_grid(60, -3.0), Some(mode))]);
    s.settings.interpolation = interpolation;
    s.settings.width = 211;
    s
}

#[test]
fn tile_size_and_thread_count_do_not_change_a_single_byte() {
    for mode in ShadingMode::ALL {
        for interp in [Interpolation::PerspectiveCorrect, Interpolation::ScreenLinear] {
            let s = test_scene(mode, interp);
            let reference = render(&s, &RenderOptions { tile_size: 64 }).0;
            assert!(reference.to_rgb().iter().any(|&c| c > 40), "{mode:?}: nothing drawn");
            for tile_size in [1, 7, 16, 33, 1000] {
                for threads in [1, 2, 3] {
                    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                    let image = pool.install(|| render(&s, &RenderOptions { tile_size }).0);
                    assert!(
                        image == reference,
                        "{mode:?} {interp:?}: tile {tile_size}, {threads} threads differ"
                    );
                }
            }
        }
    }
}

#[test]
fn vertex_colours_do_not_change_a_byte_with_tile_size_or_thread_count() {
    // Coloured meshes (Phong keeps their planes in side tables), untextured
    // and textured.
    let texture =
        zline_shading::Texture::from_rgba8(2, 1, &[250, 200, 120, 255, 90, 160, 240, 255]).expect("valid");
    let map = zline_scene::TextureMap {
        texture: std::sync::Arc::new(texture),
        sampler: zline_shading::Sampler::default(),
        alpha_blend: false,
        alpha_cutoff: None,
    };
    for mode in ShadingMode::ALL {
        for textured in [false, true] {
            for interp in [Interpolation::PerspectiveCorrect, Interpolation::ScreenLinear] {
                let mut s = test_scene(mode, interp);
                let mut mesh = (*colored(&s.objects[0].mesh)).clone();
                if textured {
                    let uv = mesh.positions.iter().map(|p| glam::Vec2::new(p.x * 0.7, p.y * 0.4)).collect();
                    mesh = mesh.with_uvs(uv).expect("one per vertex").with_diffuse_map(map.clone());
                }
                s.objects[0].mesh = std::sync::Arc::new(mesh);
                let reference = render(&s, &RenderOptions { tile_size: 64 }).0;
                assert!(reference != render(&test_scene(mode, interp), &RenderOptions { tile_size: 64 }).0);
                for tile_size in [1, 7, 33] {
                    for threads in [1, 2] {
                        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                        let image = pool.install(|| render(&s, &RenderOptions { tile_size }).0);
                        assert!(
                            image == reference,
                            "{mode:?} {interp:?} textured {textured}: tile {tile_size}, {threads} threads differ"
                        );
                    }
                }
            }
        }
    }
}

// Out-of-range tile sizes and image settings (moved from the crate's unit
// tests, so that its unit-test build does not compile the kernels again).

#[test]
fn any_tile_size_even_out_of_range_renders_the_same_image() {
    let mut scene = zline_scenes::demo_scene();
    (scene.settings.width, scene.settings.height) = (96, 40);
    let reference = render(&scene, &RenderOptions::default()).0;
    for tile_size in [0, 1, zline_scene::MAX_TILE_SIZE + 1, 1 << 31, u32::MAX] {
        let image = render(&scene, &RenderOptions { tile_size }).0;
        assert!(image == reference, "tile {tile_size}: a different image");
    }
    scene.settings.ssaa = 3;
    let reference = render(&scene, &RenderOptions::default()).0;
    assert!(render(&scene, &RenderOptions { tile_size: u32::MAX }).0 == reference, "ssaa 3");
}

#[test]
fn oversized_settings_are_taken_as_the_largest() {
    let mut scene = zline_scenes::demo_scene();
    (scene.settings.width, scene.settings.height) = (u32::MAX, 0);
    scene.settings.ssaa = u32::MAX;
    let image = render(&scene, &RenderOptions { tile_size: u32::MAX }).0;
    assert_eq!((image.width, image.height), (zline_scene::MAX_IMAGE_SIDE, 1));
}

#[test]
fn lines_do_not_change_a_byte_with_tile_size_or_thread_count() {
    // The edges are extracted, sorted and clipped in parallel: every edge
    // and every feature edge, hidden ones dashed.
    use zline_scene::{Wireframe, WireframeMode};
    for (mode, feature_angle) in [(WireframeMode::HiddenDashed, None), (WireframeMode::All, Some(20.0))] {
        let mut s = test_scene(ShadingMode::Phong, Interpolation::PerspectiveCorrect);
        s.settings.wireframe = Wireframe { mode, only: false, feature_angle };
        let reference = render(&s, &RenderOptions { tile_size: 64 }).0;
        let plain = render(
            &test_scene(ShadingMode::Phong, Interpolation::PerspectiveCorrect),
            &RenderOptions::default(),
        )
        .0;
        assert!(reference != plain, "{mode:?}: no line drawn");
        for tile_size in [7, 64] {
            for threads in [1, 2, 3, 8] {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let image = pool.install(|| render(&s, &RenderOptions { tile_size }).0);
                assert!(image == reference, "{mode:?}: tile {tile_size}, {threads} threads differ");
            }
        }
    }
}

#[test]
fn planar_shadows_do_not_change_a_byte_with_tile_size_or_thread_count() {
    // The casters' triangles are clipped and projected in parallel: the
    // wavy grid's 7,200 triangles onto a wall behind it.
    use zline_scene::{ShadowMode, ShadowPlane, Shadows};
    let mut s = test_scene(ShadingMode::Gouraud, Interpolation::PerspectiveCorrect);
    let wall = crate::support::square(0.0, 0.0, 6.0, -5.0, zline_shading::Material::default());
    s.objects.insert(0, object(wall, Some(ShadingMode::Phong)));
    s.shadows = Shadows {
        mode: ShadowMode::Planar,
        planes: vec![ShadowPlane::of_object(0, &s.objects[0]).expect("the wall is flat")],
        ..Shadows::default()
    };
    let reference = render(&s, &RenderOptions { tile_size: 64 }).0;
    let mut unshadowed = s.clone();
    unshadowed.shadows.mode = ShadowMode::None;
    assert!(reference != render(&unshadowed, &RenderOptions::default()).0, "no shadow drawn");
    for tile_size in [7, 64] {
        for threads in [1, 2, 3, 8] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let image = pool.install(|| render(&s, &RenderOptions { tile_size }).0);
            assert!(image == reference, "tile {tile_size}, {threads} threads differ");
        }
    }
}

#[test]
fn bands_cut_into_pieces_give_the_same_bytes_and_one_time_per_piece() {
    // Phong over a wavy grid; plain, with alpha coverage and supersampled,
    // the colour and the depth image; 211×173 in 16-pixel tiles: 11 bands
    // of 14 tiles, the last column and row of tiles partial.
    for (coverage, ssaa) in [(false, 1), (true, 1), (false, 2), (true, 2)] {
        let mut s = test_scene(ShadingMode::Phong, Interpolation::PerspectiveCorrect);
        (s.settings.transparent_background, s.settings.ssaa) = (coverage, ssaa);
        let options = RenderOptions { tile_size: 16 };
        let mut renderer = zline_pipeline::Renderer::default();
        assert_eq!(renderer.unit_times().count(), 0, "no frame drawn yet");
        let (mut reference, mut reference_depth) = (zline_pipeline::Image::empty(), Default::default());
        renderer.set_band_pieces(Some(1));
        renderer.render_with_depth(&s, &options, &mut reference, &mut reference_depth);
        assert_eq!(renderer.unit_times().count(), 11);
        assert!(reference.to_rgb().iter().any(|&c| c > 40), "nothing drawn");
        for (pieces, units) in [(2, 22), (3, 33), (7, 77), (14, 154), (100, 154)] {
            for threads in [1, 3] {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let (mut image, mut depth) = (zline_pipeline::Image::empty(), Default::default());
                renderer.set_band_pieces(Some(pieces));
                let what = format!("coverage {coverage}, ssaa {ssaa}: {pieces} pieces, {threads} threads");
                pool.install(|| renderer.render_with_depth(&s, &options, &mut image, &mut depth));
                assert!(image == reference, "{what}: the image differs");
                let same = |a: &zline_pipeline::DepthImage, b: &zline_pipeline::DepthImage| {
                    a.depth.iter().zip(&b.depth).all(|(x, y)| x.to_bits() == y.to_bits())
                };
                assert!(same(&depth, &reference_depth), "{what}: the depth differs");
                assert_eq!(renderer.unit_times().count(), units, "{what}");
                // Without the depth image too.
                pool.install(|| renderer.render_into(&s, &options, &mut image));
                assert!(image == reference, "{what}: the image without depth differs");
            }
        }
    }
}

#[test]
fn the_cut_follows_the_thread_count_and_leaves_tall_bands_whole() {
    use zline_pipeline::{pieces_per_band, MAX_PIECES};
    // 1920×1080 in 64-pixel tiles: 17 bands of 30 tiles.
    assert_eq!(pieces_per_band(1, 17, 30), 1);
    assert_eq!(pieces_per_band(2, 17, 30), 1);
    assert_eq!(pieces_per_band(8, 17, 30), 2);
    assert_eq!(pieces_per_band(16, 17, 30), 4);
    assert_eq!(pieces_per_band(64, 17, 30), MAX_PIECES);
    // At most one piece a tile.
    assert_eq!(pieces_per_band(64, 1, 3), 3);
    assert_eq!(pieces_per_band(4, 0, 0), 1);
    // Tiles above 64 pixels: the bands stay whole whatever is asked.
    let s = test_scene(ShadingMode::Gouraud, Interpolation::PerspectiveCorrect);
    let mut renderer = zline_pipeline::Renderer::default();
    renderer.set_band_pieces(Some(4));
    let mut image = zline_pipeline::Image::empty();
    renderer.render_into(&s, &RenderOptions { tile_size: 65 }, &mut image);
    assert_eq!(renderer.unit_times().count(), 3, "173 rows in 65-pixel bands, whole");
    renderer.render_into(&s, &RenderOptions { tile_size: 64 }, &mut image);
    assert_eq!(renderer.unit_times().count(), 3 * 4);
}

#[test]
fn unit_times_lie_within_the_raster_stage() {
    let s = test_scene(ShadingMode::Phong, Interpolation::PerspectiveCorrect);
    let mut renderer = zline_pipeline::Renderer::default();
    let mut image = zline_pipeline::Image::empty();
    // One thread, so the units run one after the other within the stage.
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let stats = pool.install(|| renderer.render_into(&s, &RenderOptions { tile_size: 16 }, &mut image));
    let units: std::time::Duration = renderer.unit_times().sum();
    assert!(units <= stats.raster, "{units:?} > {:?}", stats.raster);
    // An overdraw frame draws no tile: none, not the last frame's.
    assert!(renderer.unit_times().count() > 0);
    let mut overdraw = zline_pipeline::Overdraw::default();
    let options = RenderOptions { tile_size: 16 };
    renderer.render_overdraw_into(&s, &options, zline_raster::TieRule::TopLeft, &mut overdraw);
    assert_eq!(renderer.unit_times().count(), 0);
}
