//! Vertex colours (glTF COLOR_0): a per-vertex factor on ka and kd, like a
//! texel — applied by flat shading (the corners' mean), Gouraud shading (at
//! the vertices) and Phong shading (interpolated, per sample).

use std::sync::Arc;

use glam::{Vec2, Vec3};
use zline_scene::{Interpolation, Mesh, TextureMap};
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
    for mode in ShadingMode::ALL {
        let image = draw_one(tinted_square([tint; 4], material()), mode);
        assert_eq!(image.pixel(32, 30), [255, 128, 64], "{mode:?}");
    }
    // Without colours the same material gives 1.25 + 0.25, white.
    let plain = tinted_square([tint; 4], material());
    let plain = Mesh { colors: Vec::new(), ..plain };
    assert_eq!(draw_one(plain, ShadingMode::Phong).pixel(32, 30), [255, 255, 255]);
}

#[test]
fn a_uniform_tint_in_phong_equals_the_material_with_ka_and_kd_multiplied() {
    // A lit, curved surface (normals spread over the square) under a point
    // light: Phong with a uniform tint gives the image of the uncoloured
    // mesh whose ka and kd are multiplied by the tint. With powers of two
    // as the tint's channels every product and plane value only changes
    // its exponent, so the two are equal to the last bit, not just close.
    let tint = Vec3::new(0.5, 0.25, 1.0);
    let base = Material { ka: Vec3::new(0.4, 0.8, 0.6), kd: Vec3::new(0.8, 0.6, 0.4), ..material() };
    let base = Material { ks: Vec3::splat(0.3), ns: 12.0, ke: Vec3::new(0.0, 0.05, 0.0), ..base };
    let normals = [(-0.4, -0.3), (0.4, -0.3), (0.4, 0.3), (-0.4, 0.3)]
        .map(|(x, y)| Vec3::new(x, y, 1.0).normalize())
        .to_vec();
    let light = Light::Point {
        position: Vec3::new(0.5, 0.8, 0.0),
        color: Vec3::ONE,
        attenuation: zline_shading::Attenuation::NONE,
    };
    let image = |mesh: Mesh| {
        let s =
            scene(64, Vec3::splat(0.2), vec![light], vec![object(Arc::new(mesh), Some(ShadingMode::Phong))]);
        draw(&s).to_rgb()
    };
    let tinted = Mesh { normals: normals.clone(), ..tinted_square([tint; 4], base) };
    let multiplied = Material { ka: base.ka * tint, kd: base.kd * tint, ..base };
    let plain = Mesh { normals, colors: Vec::new(), ..tinted_square([tint; 4], multiplied) };
    let (a, b) = (image(tinted), image(plain));
    assert!(a.iter().any(|&c| c > 60), "nothing drawn");
    assert!(a == b, "tinted Phong differs from the material with ka and kd multiplied");
}

/// The square x ∈ [−1, 1], y ∈ [−1, 1] tilted in depth: z = −2 − x (the
/// left edge at z = −1, the right edge at z = −3), counter-clockwise from
/// bottom left, with the given corner colours.
fn tilted_square(colors: [Vec3; 4], material: Material) -> Mesh {
    let p = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| Vec3::new(x, y, -2.0 - x));
    let n = Vec3::new(1.0, 0.0, 1.0).normalize();
    Mesh::new("tilted", p.to_vec(), Some(vec![n; 4]), vec![[0, 1, 2], [0, 2, 3]], material)
        .and_then(|m| m.with_colors(colors.to_vec()))
        .expect("valid mesh")
}

#[test]
fn phong_interpolates_vertex_colours_perspective_correct_or_screen_linear() {
    // Ambient light only (ka = 1, Ia = 1): the colour is the interpolated
    // vertex colour. Left corners (0, 1, 0.2), right corners (1, 0, 0.2):
    // red = (x + 1)/2 and green = 1 − red on the square (affine in x, so
    // both triangles agree).
    let unlit = Material { ka: Vec3::ONE, kd: Vec3::ZERO, ks: Vec3::ZERO, ..Material::default() };
    let (left, right) = (Vec3::new(0.0, 1.0, 0.2), Vec3::new(1.0, 0.0, 0.2));
    let mesh = Arc::new(tilted_square([left, right, right, left], unlit));
    let mut s = scene(64, Vec3::ONE, vec![], vec![object(mesh, Some(ShadingMode::Phong))]);
    // Perspective-correct, pixel (16, 32): x_nc = 16.5/32 − 1 = −31/64,
    // y_nc = −1/64. The ray t·(x_nc, y_nc, −1) meets x + z = −2 at
    // t = 2/(1 − x_nc) = 128/95, so x = −62/95: red = 33/190 = 0.17368
    // → 44.29 → 44; green = 157/190 → 210.71 → 211; blue 0.2 → 51.
    assert_eq!(draw(&s).pixel(16, 32), [44, 211, 51]);
    // Screen-linear: the window corners are (0, 64), (42.67, 42.67),
    // (42.67, 21.33), (0, 0) — 42.67 snapped to 10923/256 = 42.66797. The
    // sample (16.5, 32.5) lies above the diagonal y = 64 − x, in the upper
    // triangle (corners 0, 2, 3), where only corner 2 is on the right:
    // its weight is 16.5/42.66797 = 0.38671. Red 0.38671·255 = 98.61 → 99,
    // green 0.61329·255 = 156.39 → 156.
    s.settings.interpolation = Interpolation::ScreenLinear;
    assert_eq!(draw(&s).pixel(16, 32), [99, 156, 51]);
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
    for mode in ShadingMode::ALL {
        let mesh = tinted_square([Vec3::new(0.5, 1.0, 0.25); 4], unlit)
            .with_uvs(uv.clone())
            .expect("valid uvs")
            .with_diffuse_map(map.clone());
        let image = draw(&scene(64, Vec3::ONE, vec![], vec![object(Arc::new(mesh), Some(mode))]));
        assert_eq!(image.pixel(32, 30), [102, 102, 64], "{mode:?}");
    }
}

#[test]
fn texel_and_vertex_colour_multiply_ambient_and_diffuse_but_not_specular() {
    // Texel (0.8, 0.4, 1) ⊙ tint (0.5, 1, 0.25) ⊙ 1.25 + 0.25 (see
    // `draw_one`) = (0.75, 0.75, 0.5625) → (191.25, 191.25, 143.44) →
    // (191, 191, 143) in every mode (flat and Gouraud fold the tint into
    // their lit parts in setup, Phong interpolates it per sample).
    let texture = Texture::from_rgba8(1, 1, &[204, 102, 255, 255]).expect("valid");
    let uv = vec![Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y];
    let sampler = Sampler { filter: Filter::Nearest, wrap_s: Wrap::Repeat, wrap_t: Wrap::Repeat };
    let map = TextureMap { texture: Arc::new(texture), sampler, alpha_blend: false, alpha_cutoff: None };
    for mode in ShadingMode::ALL {
        let mesh = tinted_square([Vec3::new(0.5, 1.0, 0.25); 4], material())
            .with_uvs(uv.clone())
            .expect("valid uvs")
            .with_diffuse_map(map.clone());
        assert_eq!(draw_one(mesh, mode).pixel(32, 30), [191, 191, 143], "{mode:?}");
    }
}

#[test]
fn textured_phong_interpolates_vertex_colours_perspective_correct() {
    // The tilted square of the interpolation test under a white 1×1
    // texture: the same bytes as without the texture.
    let unlit = Material { ka: Vec3::ONE, kd: Vec3::ZERO, ks: Vec3::ZERO, ..Material::default() };
    let (left, right) = (Vec3::new(0.0, 1.0, 0.2), Vec3::new(1.0, 0.0, 0.2));
    let texture = Texture::from_rgba8(1, 1, &[255, 255, 255, 255]).expect("valid");
    let sampler = Sampler { filter: Filter::Nearest, wrap_s: Wrap::Repeat, wrap_t: Wrap::Repeat };
    let map = TextureMap { texture: Arc::new(texture), sampler, alpha_blend: false, alpha_cutoff: None };
    let mesh = tilted_square([left, right, right, left], unlit)
        .with_uvs(vec![Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y])
        .expect("valid uvs")
        .with_diffuse_map(map);
    let s = scene(64, Vec3::ONE, vec![], vec![object(Arc::new(mesh), Some(ShadingMode::Phong))]);
    assert_eq!(draw(&s).pixel(16, 32), [44, 211, 51]);
}
