//! The transparency pass (SPEC §9): blended colours computed by hand, back
//! to front whatever the draw order, depth-tested against opaque surfaces
//! without writing depth, and the same bytes for any tiling.

use glam::{DVec3, Vec3};
use zline_pipeline::{render, RenderOptions};
use zline_scene::{Fog, FogCoordinate, FogMode, Scene};
use zline_shading::Material;

use crate::support::{draw, object, quantize_robust, scene, square};

const SIZE: u32 = 33;
const CENTRE: (u32, u32) = (16, 16);

/// An unlit material showing `color` (ka = color under white ambient light).
fn unlit(color: [f64; 3], opacity: f32) -> Material {
    let c = Vec3::from_array(color.map(|v| v as f32));
    Material { ka: c, kd: Vec3::ZERO, ks: Vec3::ZERO, ns: 1.0, opacity, ..Material::default() }
}

/// Squares of half-size 0.6 at the given depths and materials, in this
/// draw order, over a grey background.
fn squares(layers: &[(f32, Material)]) -> Scene {
    let objects = layers
        .iter()
        .map(|&(z, m)| {
            let mut o = object(square(0.0, 0.0, 0.6 * -z, z, m), None);
            o.cull_back_faces = m.opacity >= 1.0;
            o
        })
        .collect();
    let mut s = scene(SIZE, Vec3::ONE, vec![], objects);
    s.background = Vec3::new(0.3, 0.35, 0.4);
    s
}

const RED: [f64; 3] = [0.83, 0.17, 0.11];
const BLUE: [f64; 3] = [0.13, 0.29, 0.91];
const GREEN: [f64; 3] = [0.21, 0.77, 0.33];

fn v(c: [f64; 3]) -> DVec3 {
    DVec3::from_array(c)
}

#[test]
fn transparent_square_over_an_opaque_one() {
    // Opacity d = 0.25 → kt = 0.75: C = 0.25·blue + 0.75·red.
    let s = squares(&[(-2.0, unlit(BLUE, 0.25)), (-3.0, unlit(RED, 1.0))]);
    let want = v(BLUE) * 0.25 + v(RED) * 0.75;
    assert_eq!(draw(&s).pixel(CENTRE.0, CENTRE.1), quantize_robust(want));
}

#[test]
fn transparent_square_over_the_background() {
    let s = squares(&[(-2.0, unlit(BLUE, 0.62))]);
    let want = v(BLUE) * 0.62 + DVec3::new(0.3, 0.35, 0.4) * 0.38;
    assert_eq!(draw(&s).pixel(CENTRE.0, CENTRE.1), quantize_robust(want));
}

#[test]
fn layers_blend_back_to_front_whatever_the_draw_order() {
    // Green (far, d = 0.5) over red, then blue (near, d = 0.3) over that.
    let behind = v(GREEN) * 0.5 + v(RED) * 0.5;
    let want = v(BLUE) * 0.3 + behind * 0.7;
    let (red, green, blue) = ((-4.0, unlit(RED, 1.0)), (-3.0, unlit(GREEN, 0.5)), (-2.0, unlit(BLUE, 0.3)));
    let a = draw(&squares(&[red, green, blue]));
    let b = draw(&squares(&[blue, green, red]));
    assert_eq!(a.pixel(CENTRE.0, CENTRE.1), quantize_robust(want));
    assert!(a == b, "draw order changed the image");
}

#[test]
fn transparent_surfaces_behind_opaque_ones_are_hidden_and_write_no_depth() {
    // Blue (transparent) is behind red: hidden. Green (transparent) in front
    // of both: blended over red only, as blue wrote no depth that could hide
    // anything and contributed nothing.
    let s = squares(&[(-5.0, unlit(BLUE, 0.5)), (-3.0, unlit(RED, 1.0)), (-2.0, unlit(GREEN, 0.43))]);
    let want = v(GREEN) * 0.43 + v(RED) * 0.57;
    assert_eq!(draw(&s).pixel(CENTRE.0, CENTRE.1), quantize_robust(want));
}

#[test]
fn transparent_fragments_are_fogged_before_blending() {
    // Linear fog from 1 to 3: f = 0.5 at the transparent square (z = 2),
    // f = 0 at the opaque one (z = 3).
    let mut s = squares(&[(-2.0, unlit(BLUE, 0.25)), (-3.0, unlit(RED, 1.0))]);
    let fog = [0.5, 0.6, 0.7];
    s.fog = Some(Fog {
        mode: FogMode::Linear { start: 1.0, end: 3.0 },
        color: Vec3::from_array(fog.map(|c: f64| c as f32)),
        coordinate: FogCoordinate::EyePlane,
    });
    let red = v(fog);
    let blue = v(BLUE) * 0.5 + v(fog) * 0.5;
    let want = blue * 0.25 + red * 0.75;
    assert_eq!(draw(&s).pixel(CENTRE.0, CENTRE.1), quantize_robust(want));
}

#[test]
fn transparency_is_the_same_for_any_tiling_and_thread_count() {
    let s = squares(&[(-2.0, unlit(BLUE, 0.3)), (-2.5, unlit(GREEN, 0.6)), (-3.0, unlit(RED, 1.0))]);
    let reference = render(&s, &RenderOptions { tile_size: 64 }).0;
    for tile_size in [1, 5, 16] {
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let image = pool.install(|| render(&s, &RenderOptions { tile_size }).0);
            assert!(image == reference, "tile {tile_size}, {threads} threads differ");
        }
    }
}
