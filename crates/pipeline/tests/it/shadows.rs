//! Planar shadows against pixels predicted by hand.
//!
//! Set-up: the origin camera (fovy 90°) and a 64×64 image; a receiving
//! square of half-size 4 at z = −4 facing +z (it fills the view); a small
//! occluder square at z = −2 spanning x ∈ [−1.5, −0.5], y ∈ [−0.5, 0.5];
//! a directional light travelling along (0.5, 0, −1). A point of the
//! occluder moves by +1 in x on its way down the 2 units to the receiver,
//! so the shadow is the square x, y ∈ [−0.5, 0.5] at z = −4: NC ±0.125,
//! pixel columns and rows 28..36 (pixel centres 28.5 … 35.5 inside, the
//! edges 28 and 36 on no centre). The occluder itself projects to columns
//! 8..24, away from the shadow.

use glam::{DVec3, Vec3};
use zline_scene::{ShadowMode, ShadowPlane, Shadows};
use zline_shading::{Light, Material, ShadingMode};

use crate::support::{draw, object, quantize_robust, scene, square};

const SIZE: u32 = 64;

fn receiver_material() -> Material {
    Material {
        ke: Vec3::ZERO,
        ka: Vec3::splat(0.6),
        kd: Vec3::new(0.85, 0.65, 0.5),
        ks: Vec3::ZERO,
        ns: 1.0,
        opacity: 1.0,
        model: Default::default(),
        ..Material::DEFAULT
    }
}

fn shadow_scene(lights: Vec<Light>, receiver_shading: ShadingMode) -> zline_scene::Scene {
    let floor = object(square(0.0, 0.0, 4.0, -4.0, receiver_material()), Some(receiver_shading));
    let occluder =
        object(square(-1.0, 0.0, 0.5, -2.0, Material::plastic(Vec3::new(0.2, 0.9, 0.2), 0.0, 1.0)), None);
    let mut s = scene(SIZE, Vec3::new(0.25, 0.45, 0.7), lights, vec![floor, occluder]);
    s.shadows = Shadows {
        mode: ShadowMode::Planar,
        planes: vec![ShadowPlane::of_object(0, &s.objects[0]).expect("the floor is flat")],
        ..Shadows::default()
    };
    s
}

fn sun(color: Vec3) -> Light {
    Light::Directional { direction: Vec3::new(0.5, 0.0, -1.0), color }
}

/// The floor's colour lit by directional lights of these colours
/// travelling along (0.5, 0, −1): SPEC §5 in f64 (N = +z, so N·L = 1/√1.25).
fn floor_color(lights: &[Vec3]) -> [u8; 3] {
    let m = receiver_material();
    let n_dot_l = 1.0 / 1.25f64.sqrt();
    let mut c = m.ka.as_dvec3() * DVec3::new(0.25, 0.45, 0.7);
    for l in lights {
        c += m.kd.as_dvec3() * l.as_dvec3() * n_dot_l;
    }
    quantize_robust(c)
}

fn in_shadow(x: u32, y: u32) -> bool {
    (28..36).contains(&x) && (28..36).contains(&y)
}

fn on_occluder(x: u32, y: u32) -> bool {
    (8..24).contains(&x) && (24..40).contains(&y)
}

#[test]
fn a_square_casts_the_predicted_square_of_pixels() {
    let white = Vec3::ONE;
    for shading in [ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong] {
        let image = draw(&shadow_scene(vec![sun(white)], shading));
        let (lit, dark) = (floor_color(&[white]), floor_color(&[]));
        for y in 0..SIZE {
            for x in 0..SIZE {
                if on_occluder(x, y) {
                    continue;
                }
                let want = if in_shadow(x, y) { dark } else { lit };
                assert_eq!(image.pixel(x, y), want, "{shading:?}: pixel ({x}, {y})");
            }
        }
    }
}

#[test]
fn without_shadows_the_floor_is_lit_everywhere() {
    let mut s = shadow_scene(vec![sun(Vec3::ONE)], ShadingMode::Phong);
    s.shadows.mode = ShadowMode::None;
    let image = draw(&s);
    assert_eq!(image.pixel(31, 31), floor_color(&[Vec3::ONE]));
}

#[test]
fn a_hidden_coloured_light_leaves_the_other_lights() {
    // Two suns along the same direction, red and blue: in the shadow both
    // are hidden; a third light from straight ahead (travelling −z) sees
    // the shadow region past the occluder and keeps lighting it.
    let (red, blue) = (Vec3::new(0.5, 0.0, 0.0), Vec3::new(0.0, 0.0, 0.4));
    let head_on = Light::Directional { direction: Vec3::NEG_Z, color: Vec3::new(0.0, 0.3, 0.0) };
    let image = draw(&shadow_scene(vec![sun(red), sun(blue), head_on], ShadingMode::Phong));
    let m = receiver_material();
    let base = m.ka.as_dvec3() * DVec3::new(0.25, 0.45, 0.7) + m.kd.as_dvec3() * DVec3::new(0.0, 0.3, 0.0);
    let n_dot_l = 1.0 / 1.25f64.sqrt();
    let lit = base + m.kd.as_dvec3() * (red + blue).as_dvec3() * n_dot_l;
    assert_eq!(image.pixel(31, 31), quantize_robust(base), "in the shadow: green light only");
    assert_eq!(image.pixel(50, 31), quantize_robust(lit), "outside: all three");
    // The head-on light's own shadow is the occluder's outline on the
    // floor at twice its size, behind the occluder: hidden from the camera.
}

#[test]
fn a_receiver_does_not_shadow_other_planes_through_its_mask() {
    // Two receivers: the floor and the occluder itself marked as a plane.
    // The occluder now casts nothing (receivers do not cast), so the floor
    // is lit everywhere.
    let mut s = shadow_scene(vec![sun(Vec3::ONE)], ShadingMode::Phong);
    s.shadows.planes.push(ShadowPlane::of_object(1, &s.objects[1]).expect("flat"));
    let image = draw(&s);
    assert_eq!(image.pixel(31, 31), floor_color(&[Vec3::ONE]));
}

#[test]
fn shadows_are_the_same_for_any_tile_size_and_thread_count() {
    for mode in [ShadowMode::Planar, ShadowMode::Map] {
        let mut s = shadow_scene(
            vec![
                sun(Vec3::ONE),
                Light::Point {
                    position: Vec3::new(1.0, 2.0, -1.0),
                    color: Vec3::splat(0.5),
                    attenuation: zline_shading::Attenuation::NONE,
                },
            ],
            ShadingMode::Phong,
        );
        s.shadows.mode = mode;
        let reference = draw(&s);
        for tile_size in [1, 7, 16, 1000] {
            let image = zline_pipeline::render(&s, &zline_pipeline::RenderOptions { tile_size }).0;
            assert!(image == reference, "{mode:?}: tile {tile_size}");
        }
        let pool = rayon::ThreadPoolBuilder::new().num_threads(3).build().expect("pool");
        assert!(pool.install(|| draw(&s)) == reference, "{mode:?}: 3 threads");
    }
}

#[test]
fn hostile_shadow_geometry_draws_a_defined_image() {
    use zline_shading::Attenuation;
    let point = |position: Vec3| Light::Point { position, color: Vec3::ONE, attenuation: Attenuation::NONE };
    let cases: Vec<(&str, Vec<Light>, f32)> = vec![
        ("light on the plane", vec![point(Vec3::new(0.0, 0.0, -4.0))], 1.0),
        ("light inside the occluder's plane", vec![point(Vec3::new(-1.0, 0.0, -2.0))], 1.0),
        ("light a hair above the plane", vec![point(Vec3::new(0.0, 0.0, -4.0 + 1e-6))], 1.0),
        ("light at 1e30", vec![point(Vec3::splat(1e30))], 1.0),
        (
            "directional along the plane",
            vec![Light::Directional { direction: Vec3::X, color: Vec3::ONE }],
            1.0,
        ),
        ("huge occluder", vec![sun(Vec3::ONE)], 1e30),
        ("40 lights", (0..40).map(|k| point(Vec3::new(k as f32 * 0.1 - 2.0, 1.0, -1.0))).collect(), 1.0),
    ];
    for (name, lights, scale) in cases {
        for mode in [ShadowMode::Planar, ShadowMode::Map] {
            let mut s = shadow_scene(lights.clone(), ShadingMode::Phong);
            s.shadows.mode = mode;
            s.shadows.map_size = 64;
            s.objects[1].world_from_object = glam::Mat4::from_scale(Vec3::splat(scale));
            let a = draw(&s);
            let b = zline_pipeline::render(&s, &zline_pipeline::RenderOptions { tile_size: 16 }).0;
            assert!(a == b, "{name}, {mode:?}: the image depends on the tile size");
        }
    }
}

#[test]
fn a_shadow_map_darkens_the_same_square_of_pixels() {
    // The planar scene's square under the same sun, with shadow maps: the
    // map's texels (≈ 0.06 px on the floor at 1024²) and its 3 × 3 filter
    // stay far from the pixel centres, which lie ≥ ½ px from the shadow's
    // edges, so the prediction is the same.
    for pcf in [true, false] {
        let mut s = shadow_scene(vec![sun(Vec3::ONE)], ShadingMode::Phong);
        s.shadows = Shadows { mode: ShadowMode::Map, pcf, ..Shadows::default() };
        let image = draw(&s);
        let (lit, dark) = (floor_color(&[Vec3::ONE]), floor_color(&[]));
        for y in 0..SIZE {
            for x in 0..SIZE {
                if on_occluder(x, y) {
                    continue;
                }
                let want = if in_shadow(x, y) { dark } else { lit };
                assert_eq!(image.pixel(x, y), want, "pcf {pcf}: pixel ({x}, {y})");
            }
        }
    }
}

#[test]
fn a_point_light_s_cube_map_shadows_the_floor_under_the_square() {
    // A point light at (−1, 0, 0) right above the occluder's centre line
    // (at z = 0, 2 in front of it): the shadow on the floor at z = −4 is the
    // square scaled by 4/2 about the light's foot: x ∈ [−2, 0], y ∈ [−1, 1],
    // which is NC [−0.5, 0] × [−0.25, 0.25]: columns 16..32, rows 24..40.
    let light = Light::Point {
        position: Vec3::new(-1.0, 0.0, 0.0),
        color: Vec3::ONE,
        attenuation: Default::default(),
    };
    let mut s = shadow_scene(vec![light], ShadingMode::Phong);
    s.shadows = Shadows { mode: ShadowMode::Map, ..Shadows::default() };
    let image = draw(&s);
    // Behind the occluder (columns 8..24) the floor is hidden; check the
    // visible part of the shadow and the lit floor beside it.
    let centre = image.pixel(28, 31);
    let beside = image.pixel(40, 31);
    assert!(centre.iter().zip(&beside).all(|(c, b)| c < b), "shadowed {centre:?} vs lit {beside:?}");
    let ambient = floor_color(&[]);
    assert_eq!(centre, ambient, "in the shadow only the ambient term is left");
    assert_ne!(image.pixel(33, 31), ambient, "column 33 lies outside the shadow");
}
