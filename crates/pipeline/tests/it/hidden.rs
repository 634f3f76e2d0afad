//! Hidden work skipped (`tile::coarse`): a tile whose every sample is drawn
//! skips whole the primitives its coarse depth hides. Drawn after the wall
//! that hides them, a mesh's triangles are skipped; drawn before it, none
//! can be. The images must be the same bytes.

use glam::Vec3;
use zline_scene::{DepthMode, Scene};
use zline_shading::{Material, ShadingMode};

use crate::support::{draw, object, scene, square, wavy_grid};

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
