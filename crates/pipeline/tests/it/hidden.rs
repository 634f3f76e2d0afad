//! Hidden work skipped (`tile::coarse`): a tile whose every sample is drawn
//! skips whole the primitives its coarse depth hides. Drawn after the wall
//! that hides them, a mesh's triangles are skipped; drawn before it, none
//! can be. The images must be the same bytes.

use glam::Vec3;
use zline_scene::{DepthMode, Scene};
use zline_shading::{Material, ShadingMode};

use crate::support::{draw, mesh, object, scene, square, wavy_grid};

/// A wavy grid (crests ±0.3) around depth `z` and a wall at z = −2 over the
/// left half of the view, whole 64-pixel tiles of it, the wall first or
/// last.
fn behind_a_wall(z: f32, wall_first: bool, mode: ShadingMode) -> Scene {
    let lights =
        vec![zline_shading::Light::Directional { direction: Vec3::new(0.3, -0.2, -1.0), color: Vec3::ONE }];
    let wall = object(
        square(-2.5, 0.0, 2.5, -2.0, Material::plastic(Vec3::new(0.4, 0.6, 0.7), 0.3, 8.0)),
        Some(ShadingMode::Flat),
    );
    let mut objects = vec![object(wavy_grid(48, z), Some(mode))];
    if wall_first {
        objects.insert(0, wall);
    } else {
        objects.push(wall);
    }
    scene(128, Vec3::splat(0.2), lights, objects)
}

#[test]
fn a_mesh_behind_a_wall_draws_the_same_image_whichever_comes_first() {
    // Far behind the wall; just behind it (the crests 0.04 from the wall);
    // and through it (crests 0.1 in front, beside triangles just behind).
    for z in [-3.0, -2.34, -2.2] {
        for depth in [DepthMode::Normalized, DepthMode::ReversedFloat] {
            for ssaa in [1, 2] {
                for mode in ShadingMode::ALL {
                    let with = |wall_first| {
                        let mut s = behind_a_wall(z, wall_first, mode);
                        (s.settings.depth, s.settings.ssaa) = (depth, ssaa);
                        draw(&s)
                    };
                    let (first, last) = (with(true), with(false));
                    assert!(first == last, "grid at {z}, {depth:?}, ssaa {ssaa}, {mode:?}");
                }
            }
        }
    }
}

/// What the coarse depth skipped (`RenderStats::hidden`) with the wavy
/// grid behind a wall over the whole view: drawn after the wall, each of
/// the grid's primitives is skipped in every tile it was binned to, so at
/// least once, and no sample of it is shaded; drawn before the wall,
/// nothing is skipped (the wall is nearer than all of it). The count is a
/// frame's, the same for a renderer's second frame, at any thread count
/// and whatever the cut of the bands.
#[test]
fn what_the_coarse_depth_skips_is_counted_the_same_at_any_thread_count() {
    use zline_pipeline::{Image, RenderOptions, Renderer};
    let lights = vec![zline_shading::Light::Directional { direction: Vec3::NEG_Z, color: Vec3::ONE }];
    // One triangle over the whole view, so that each tile is whole after
    // the wall's one primitive (a second one, tested against a tile the
    // first completed, would fail and leave the next untested).
    let wall = || {
        let p = [(-6.0, -6.0), (12.0, -6.0), (-6.0, 12.0)].map(|(x, y)| Vec3::new(x, y, -2.0)).to_vec();
        let material = Material::plastic(Vec3::new(0.4, 0.6, 0.7), 0.3, 8.0);
        object(mesh(p, vec![Vec3::Z; 3], vec![[0, 1, 2]], material), Some(ShadingMode::Flat))
    };
    let grid = || object(wavy_grid(24, -3.0), Some(ShadingMode::Phong));
    let frames = |objects, threads, pieces| {
        let s = scene(128, Vec3::splat(0.2), lights.clone(), objects);
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        let mut renderer = Renderer::default();
        renderer.set_band_pieces(pieces);
        let mut image = Image::empty();
        let mut frame = || pool.install(|| renderer.render_into(&s, &RenderOptions::default(), &mut image));
        let (first, second) = (frame(), frame());
        assert_eq!(
            first.hidden, second.hidden,
            "{threads} threads, pieces {pieces:?}: the second frame's count"
        );
        first
    };
    let stats = frames(vec![wall(), grid()], 1, None);
    let grid_primitives = stats.primitives - 1;
    assert!(grid_primitives > 1000, "{} primitives", stats.primitives);
    assert!(stats.hidden >= grid_primitives, "{} skipped of {grid_primitives}", stats.hidden);
    assert_eq!(stats.fragments, 128 * 128, "only the wall is shaded");
    for (threads, pieces) in [(3, None), (3, Some(2)), (2, Some(4)), (1, Some(3))] {
        assert_eq!(
            frames(vec![wall(), grid()], threads, pieces).hidden,
            stats.hidden,
            "{threads} threads, {pieces:?}"
        );
    }
    assert_eq!(frames(vec![grid(), wall()], 2, None).hidden, 0, "the wall last");
}
