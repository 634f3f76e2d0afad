//! Vertex colours (glTF COLOR_0): a per-vertex factor on ka and kd, like a
//! texel — applied by flat shading (the corners' mean) and Gouraud shading
//! (at the vertices), not yet by Phong shading.

use std::sync::Arc;

use glam::{Vec2, Vec3};
use zline_scene::{Mesh, TextureMap};
use zline_shading::{Filter, Light, Material, Sampler, ShadingMode, Texture, Wrap};

use crate::support::{draw, object, scene};

/// The square x, y ∈ [−1, 1] at z = −2 (window pixels 16..48 of 64) with
/// the given corner colours, counter-clockwise from bottom left.
fn tinted_square(colors: [Vec3; 4], material: Material) -> Mesh {
    let p = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| Vec3::new(x, y, -2.0));
    Mesh::new("tinted", p.to_vec(), Some(vec![Vec3::Z; 4]), vec![[0, 1, 2], [0, 2, 3]], material)
        .and_then(|m| m.with_colors(colors.to_vec()))
        .expect("valid mesh")
}

/// ka = kd = 1, ks = 0.25 with ns = 0 (so the specular term is 0.25 under
/// a head-on light wherever the eye is), ke = 0.
fn material() -> Material {
    Material { ka: Vec3::ONE, kd: Vec3::ONE, ks: Vec3::splat(0.25), ns: 0.0, ..Material::default() }
}

/// Ambient 0.25 and a head-on white light: ka·Ia + kd·Il·(N·L) = 1.25 and
/// specular 0.25 before the tint.
fn draw_one(mesh: Mesh, mode: ShadingMode) -> zline_pipeline::Image {
    let light = Light::Directional { direction: Vec3::NEG_Z, color: Vec3::ONE };
    draw(&scene(64, Vec3::splat(0.25), vec![light], vec![object(Arc::new(mesh), Some(mode))]))
}

#[test]
fn a_uniform_tint_multiplies_ambient_and_diffuse_but_not_specular() {
    // c = tint ⊙ 1.25 + 0.25 for tint (0.6, 0.2, 0) → (1.0, 0.5, 0.25):
    // (255, 128, 64) after floor(c·255 + 0.5).
    let tint = Vec3::new(0.6, 0.2, 0.0);
    for mode in [ShadingMode::Flat, ShadingMode::Gouraud] {
        let image = draw_one(tinted_square([tint; 4], material()), mode);
        assert_eq!(image.pixel(32, 30), [255, 128, 64], "{mode:?}");
    }
    // Phong does not apply vertex colours yet: 1.25 + 0.25 clamps to white.
    let image = draw_one(tinted_square([tint; 4], material()), ShadingMode::Phong);
    assert_eq!(image.pixel(32, 30), [255, 255, 255], "Phong: today's behaviour, tint not applied");
}

#[test]
fn gouraud_interpolates_tinted_vertex_colours_and_flat_averages_them() {
    // Left corners black, right corners red, ambient light only (ka = 1,
    // Ia = 1, kd = ks = 0): Gouraud gives red = the horizontal position,
    // 0 at the left edge to 1 at the right; flat gives each triangle the
    // mean of its corners: 2/3 for the lower-right one (two red corners),
    // 1/3 for the upper-left one.
    let unlit = Material { ka: Vec3::ONE, kd: Vec3::ZERO, ks: Vec3::ZERO, ..Material::default() };
    let colors = [Vec3::ZERO, Vec3::X, Vec3::X, Vec3::ZERO];
    let draw_unlit = |mode| {
        let mesh = Arc::new(tinted_square(colors, unlit));
        draw(&scene(64, Vec3::ONE, vec![], vec![object(mesh, Some(mode))]))
    };
    let gouraud = draw_unlit(ShadingMode::Gouraud);
    // Pixel 24's centre 24.5 is (24.5 − 16)/32 = 0.265625 of the way across
    // (perspective does not bend a face-on square): 0.265625·255 = 67.7 → 68;
    // pixel 40: 0.765625·255 = 195.2 → 195.
    assert_eq!(gouraud.pixel(24, 32), [68, 0, 0]);
    assert_eq!(gouraud.pixel(40, 32), [195, 0, 0]);
    let flat = draw_unlit(ShadingMode::Flat);
    assert_eq!(flat.pixel(40, 44), [170, 0, 0], "lower right: (0 + 1 + 1)/3 · 255 = 170");
    assert_eq!(flat.pixel(20, 20), [85, 0, 0], "upper left: (0 + 1 + 0)/3 · 255 = 85");
}

#[test]
fn a_texture_and_a_vertex_colour_multiply() {
    // Texel (0.8, 0.4, 1) ⊙ tint (0.5, 1, 0.25) under ambient 1, ka = 1:
    // (0.4, 0.4, 0.25) → (102, 102, 64).
    let unlit = Material { ka: Vec3::ONE, kd: Vec3::ZERO, ks: Vec3::ZERO, ..Material::default() };
    let texture = Texture::from_rgba8(1, 1, &[204, 102, 255, 255]).expect("valid");
    let uv = vec![Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y];
    let sampler = Sampler { filter: Filter::Nearest, wrap_s: Wrap::Repeat, wrap_t: Wrap::Repeat };
    let map = TextureMap { texture: Arc::new(texture), sampler, alpha_blend: false, alpha_cutoff: None };
    for mode in [ShadingMode::Flat, ShadingMode::Gouraud] {
        let mesh = tinted_square([Vec3::new(0.5, 1.0, 0.25); 4], unlit)
            .with_uvs(uv.clone())
            .expect("valid uvs")
            .with_diffuse_map(map.clone());
        let image = draw(&scene(64, Vec3::ONE, vec![], vec![object(Arc::new(mesh), Some(mode))]));
        assert_eq!(image.pixel(32, 30), [102, 102, 64], "{mode:?}");
    }
}
