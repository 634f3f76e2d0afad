//! The adaptive mode (`RenderSettings::adaptive_tolerance`): every pixel
//! within the stated bound of the full evaluation of the same shading mode,
//! and shortcuts actually taken.

use std::sync::Arc;

use glam::{Mat4, Vec3};
use proptest::prelude::*;
use zline_scene::{uv_sphere, GouraudClamp, Interpolation, Object, Scene};
use zline_shading::{Attenuation, Light, Material, ShadingMode};

use crate::support::{colored, object, scene, wavy_grid};

/// The image with every mesh drawn in full: these tests hold the shading
/// shortcuts to their per-pixel bound; the simplified meshes the adaptive
/// mode also draws (`zline_pipeline::lod`) have their own measure
/// (`crate::lod`).
fn draw(scene: &Scene) -> zline_pipeline::Image {
    let mut renderer = zline_pipeline::Renderer::default();
    renderer.set_level_of_detail(false);
    let mut image = zline_pipeline::Image::empty();
    renderer.render_into(scene, &zline_pipeline::RenderOptions::default(), &mut image);
    image
}

/// Largest 8-bit difference between two images of the same size.
fn max_difference(a: &zline_pipeline::Image, b: &zline_pipeline::Image) -> u8 {
    let (a, b) = (a.to_rgb(), b.to_rgb());
    a.iter().zip(&b).map(|(x, y)| x.abs_diff(*y)).max().unwrap_or(0)
}

fn test_scene(mode: ShadingMode, light: Vec3, color: Vec3, a2: f32, distance: f32) -> Scene {
    shiny_scene(mode, light, color, a2, distance, 0.6)
}

/// `test_scene` with the sphere's ks.
fn shiny_scene(mode: ShadingMode, light: Vec3, color: Vec3, a2: f32, distance: f32, ks: f32) -> Scene {
    let mut sphere = uv_sphere(24, 48, 1.0);
    sphere.material = Material::plastic(Vec3::new(0.7, 0.4, 0.2), ks, 40.0);
    let sphere = Object {
        world_from_object: Mat4::from_translation(Vec3::new(0.8, 0.0, -distance)),
        ..object(Arc::new(sphere), Some(mode))
    };
    let lights = vec![
        Light::Point { position: light, color, attenuation: Attenuation::new(1.0, 0.0, a2) },
        Light::Directional { direction: Vec3::new(-0.2, -0.3, -1.0), color: Vec3::splat(0.1) },
    ];
    let mut s = scene(
        96,
        Vec3::splat(0.15),
        lights,
        vec![object(wavy_grid(20, -distance - 1.0), Some(mode)), sphere],
    );
    s.camera = crate::support::origin_camera(0.5, 100.0);
    s
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 32, ..ProptestConfig::default() })]

    /// The module's claim: the colour moves by at most τ/255, so the 8-bit
    /// value by at most ⌊τ⌋ + 1.
    #[test]
    fn every_pixel_stays_within_the_tolerance(
        phong in any::<bool>(),
        linear in any::<bool>(),
        light in (-5.0f32..5.0, -5.0f32..5.0, -4.0f32..4.0),
        color in (0.0f32..1.5, 0.0f32..1.5, 0.0f32..1.5),
        a2 in prop_oneof![Just(0.0f32), 0.0f32..2.0],
        distance in 2.5f32..12.0,
        tolerance in prop_oneof![Just(0.25f32), Just(0.5), Just(1.0), Just(2.0), Just(4.0), Just(8.0)],
        ks in prop_oneof![Just(0.0f32), Just(0.6)],
        per_sample in any::<bool>(),
    ) {
        let mode = if phong { ShadingMode::Phong } else { ShadingMode::Gouraud };
        let mut s = shiny_scene(mode, Vec3::from(light), Vec3::from(color), a2, distance, ks);
        if linear {
            s.settings.interpolation = Interpolation::ScreenLinear;
        }
        if per_sample {
            // Unclamped vertex colours (the light reaches 1.5): the
            // bounds hold for any values (see the module).
            s.settings.gouraud_clamp = GouraudClamp::PerSample;
        }
        let full = draw(&s);
        s.settings.adaptive_tolerance = Some(tolerance);
        let adaptive = draw(&s);
        let bound = tolerance.floor() as u8 + 1;
        let diff = max_difference(&full, &adaptive);
        prop_assert!(diff <= bound, "{mode:?}, τ = {tolerance}: difference {diff} > {bound}");
    }
}

#[test]
fn shortcuts_are_taken_and_a_zero_tolerance_keeps_gouraud_exact_where_colours_differ() {
    let s = test_scene(ShadingMode::Gouraud, Vec3::new(2.0, 3.0, 0.0), Vec3::ONE, 0.0, 4.0);
    let full = draw(&s);
    let mut adaptive = s.clone();
    adaptive.settings.adaptive_tolerance = Some(4.0);
    // At τ = 4 the shortcuts must change something (or they are never taken).
    assert!(draw(&adaptive) != full);
    // τ = 0 allows only triangles whose vertex colours are identical to go
    // flat, and screen-linear only where w is constant: the same colours.
    adaptive.settings.adaptive_tolerance = Some(0.0);
    assert!(max_difference(&draw(&adaptive), &full) <= 1);
}

#[test]
fn a_negligible_specular_is_dropped_and_a_visible_one_kept() {
    // A light 35 units away with f = 1/(1 + d²): specular ≤ 0.6/1000, a
    // sixth of an 8-bit step, dropped at τ = 1 on every triangle, so the
    // image is exactly the one without specular; a nearby light's highlight
    // stays.
    for (light, dropped) in [(Vec3::new(0.0, 0.0, 35.0), true), (Vec3::new(1.0, 1.0, 0.0), false)] {
        let mut s = test_scene(ShadingMode::Phong, light, Vec3::ONE, 1.0, 4.0);
        s.lights.truncate(1);
        let mut matte = s.clone();
        for o in &mut matte.objects {
            o.material = Some(Material { ks: Vec3::ZERO, ..o.mesh.material });
        }
        s.settings.adaptive_tolerance = Some(1.0);
        assert_eq!(draw(&s) == draw(&matte), dropped, "light at {light}");
    }
}

#[test]
fn phong_lit_once_on_a_fine_matte_sphere_stays_within_the_tolerance() {
    // 200 × 400 segments: neighbouring normals ~0.016 apart, so under a
    // white directional light the bound of shortcut 4 is ≈ 0.7·0.016 ≈ 3
    // steps: taken from τ ≈ 3 on, where it must change the image; below it
    // the image is the full one.
    let mut sphere = uv_sphere(200, 400, 1.0);
    sphere.material = Material::plastic(Vec3::new(0.7, 0.4, 0.2), 0.0, 1.0);
    let sphere = Object {
        world_from_object: Mat4::from_translation(Vec3::new(0.0, 0.0, -3.0)),
        ..object(Arc::new(sphere), Some(ShadingMode::Phong))
    };
    let sun = Light::Directional { direction: Vec3::new(-0.3, -0.5, -1.0), color: Vec3::ONE };
    let mut s = scene(96, Vec3::splat(0.1), vec![sun], vec![sphere]);
    let full = draw(&s);
    for tolerance in [0.5f32, 1.0, 2.0, 4.0, 8.0] {
        s.settings.adaptive_tolerance = Some(tolerance);
        let adaptive = draw(&s);
        let diff = max_difference(&full, &adaptive);
        assert!(diff <= tolerance.floor() as u8 + 1, "τ = {tolerance}: difference {diff}");
        if tolerance >= 4.0 {
            assert!(adaptive != full, "τ = {tolerance}: shortcut 4 not taken");
        }
    }
}

#[test]
fn a_negligible_specular_is_dropped_with_vertex_colours_too() {
    // As above, with vertex colours on both meshes (their Phong primitives
    // keep their planes in the chunks' side table) and once with a texture.
    let texture = zline_shading::Texture::from_rgba8(1, 1, &[230, 200, 250, 255]).expect("valid");
    let map = zline_scene::TextureMap {
        texture: Arc::new(texture),
        sampler: zline_shading::Sampler::default(),
        alpha_blend: false,
        alpha_cutoff: None,
    };
    for textured in [false, true] {
        for (light, dropped) in [(Vec3::new(0.0, 0.0, 35.0), true), (Vec3::new(1.0, 1.0, 0.0), false)] {
            let mut s = test_scene(ShadingMode::Phong, light, Vec3::ONE, 1.0, 4.0);
            s.lights.truncate(1);
            for o in &mut s.objects {
                let mut mesh = (*colored(&o.mesh)).clone();
                if textured {
                    let uv = mesh.positions.iter().map(|p| glam::Vec2::new(p.x, p.y)).collect();
                    mesh = mesh.with_uvs(uv).expect("one per vertex").with_diffuse_map(map.clone());
                }
                o.mesh = Arc::new(mesh);
            }
            let mut matte = s.clone();
            for o in &mut matte.objects {
                o.material = Some(Material { ks: Vec3::ZERO, ..o.mesh.material });
            }
            s.settings.adaptive_tolerance = Some(1.0);
            assert_eq!(draw(&s) == draw(&matte), dropped, "textured {textured}, light at {light}");
        }
    }
}
