//! Texture mapping in the pipeline (SPEC §7): texels land where their
//! coordinates say, modulate ambient and diffuse but not specular, and the
//! perspective-correct and affine mappings put a receding boundary where the
//! formulas put it.

use std::sync::Arc;

use glam::{Vec2, Vec3};
use zline_scene::{Interpolation, Mesh, TextureMap};
use zline_shading::{Filter, Light, Material, Sampler, ShadingMode, Texture, Wrap};

use crate::support::{draw, object, scene};

/// A mesh with texture coordinates and a texture.
fn textured(positions: Vec<Vec3>, uvs: Vec<Vec2>, texture: Texture, material: Material) -> Arc<Mesh> {
    let n = positions.len();
    let triangles = vec![[0, 1, 2], [0, 2, 3]];
    let sampler = Sampler { filter: Filter::Nearest, wrap_s: Wrap::ClampToEdge, wrap_t: Wrap::ClampToEdge };
    let mesh = Mesh::new("textured", positions, Some(vec![Vec3::Z; n]), triangles, material)
        .and_then(|m| m.with_uvs(uvs))
        .expect("valid mesh")
        .with_diffuse_map(TextureMap {
            texture: Arc::new(texture),
            sampler,
            alpha_blend: false,
            alpha_cutoff: None,
        });
    Arc::new(mesh)
}

/// The unit square's corners at depth z, with (s, t) = (0, 0) bottom left.
fn square(half: f32, z: f32) -> (Vec<Vec3>, Vec<Vec2>) {
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    let p = corners.map(|(x, y)| Vec3::new(x * half, y * half, z)).to_vec();
    let uv = corners.map(|(x, y)| Vec2::new((x + 1.0) / 2.0, (y + 1.0) / 2.0)).to_vec();
    (p, uv)
}

fn unlit() -> Material {
    Material { ka: Vec3::ONE, kd: Vec3::ZERO, ks: Vec3::ZERO, ns: 1.0, opacity: 1.0, ..Material::default() }
}

/// Rows top to bottom: red, green / blue, white.
fn checker() -> Texture {
    let px = [[255, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255], [255, 255, 255, 255]];
    Texture::from_rgba8(2, 2, &px.concat()).expect("valid texture")
}

#[test]
fn texels_land_in_their_quadrants_in_every_shading_mode() {
    for mode in ShadingMode::ALL {
        let (p, uv) = square(1.0, -2.0);
        let mut s =
            scene(64, Vec3::ONE, vec![], vec![object(textured(p, uv, checker(), unlit()), Some(mode))]);
        s.background = Vec3::ZERO;
        let image = draw(&s);
        // The square spans window pixels 16..48; quadrant centres at 24 and 40.
        assert_eq!(image.pixel(24, 24), [255, 0, 0], "{mode:?}: top left is the image's top-left texel");
        assert_eq!(image.pixel(40, 24), [0, 255, 0], "{mode:?}: top right");
        assert_eq!(image.pixel(24, 40), [0, 0, 255], "{mode:?}: bottom left");
        assert_eq!(image.pixel(40, 40), [255, 255, 255], "{mode:?}: bottom right");
        assert_eq!(image.pixel(4, 4), [0, 0, 0], "{mode:?}: background");
    }
}

#[test]
fn the_texel_modulates_ambient_and_diffuse_but_not_specular() {
    // Flat: a directional light head-on, N·L = 1, and shininess 0 so the
    // specular term is ks·Il·(N·H)^0 = 0.25 wherever the eye is:
    // ad = ka·Ia + kd·Il = 0.1 + 0.5, spec = 0.25.
    // c = texel ⊙ 0.6 + 0.25 for texel (0.2, 0.4, 0.8) → (0.37, 0.49, 0.73).
    let texel = [51, 102, 204, 255]; // 0.2, 0.4, 0.8
    let texture = Texture::from_rgba8(1, 1, &texel).expect("valid");
    let m = Material {
        ka: Vec3::ONE,
        kd: Vec3::splat(0.5),
        ks: Vec3::splat(0.25),
        ns: 0.0,
        opacity: 1.0,
        ..Material::default()
    };
    let (p, uv) = square(1.0, -2.0);
    let light = Light::Directional { direction: Vec3::NEG_Z, color: Vec3::ONE };
    let s = scene(
        64,
        Vec3::splat(0.1),
        vec![light],
        vec![object(textured(p, uv, texture, m), Some(ShadingMode::Flat))],
    );
    // floor(0.37·255 + 0.5) = 94, floor(0.49·255 + 0.5) = 125, floor(0.73·255 + 0.5) = 186.
    assert_eq!(draw(&s).pixel(32, 30), [94, 125, 186]);
}

#[test]
fn emission_is_added_before_the_clamp_and_not_modulated_by_the_texture() {
    // ke = (0.2, 0.4, 0.6) alone, under a head-on light and ambient that a
    // zero ka, kd and ks ignore: I = ke → floor(ke·255 + 0.5) = (51, 102, 153).
    // With ka = 0.5 and ambient 1 the red channel is 0.2 + 0.5 = 0.7 → 179.
    // Textured with a black texel, ka and kd vanish but ke stays.
    let ke = Vec3::new(0.2, 0.4, 0.6);
    let dark = Material { ke, ka: Vec3::ZERO, kd: Vec3::ZERO, ks: Vec3::ZERO, ..Material::default() };
    let light = Light::Directional { direction: Vec3::NEG_Z, color: Vec3::ONE };
    let black = || Texture::from_rgba8(1, 1, &[0, 0, 0, 255]).expect("valid");
    for mode in ShadingMode::ALL {
        let (p, uv) = square(1.0, -2.0);
        let plain = Mesh::new("plain", p.clone(), Some(vec![Vec3::Z; 4]), vec![[0, 1, 2], [0, 2, 3]], dark);
        let s = scene(64, Vec3::ONE, vec![light], vec![object(Arc::new(plain.expect("valid")), Some(mode))]);
        assert_eq!(draw(&s).pixel(32, 30), [51, 102, 153], "{mode:?}: emission only");
        let red_ambient = Material { ka: Vec3::new(0.5, 0.0, 0.0), ..dark };
        let plain =
            Mesh::new("plain", p.clone(), Some(vec![Vec3::Z; 4]), vec![[0, 1, 2], [0, 2, 3]], red_ambient);
        let s = scene(64, Vec3::ONE, vec![light], vec![object(Arc::new(plain.expect("valid")), Some(mode))]);
        assert_eq!(draw(&s).pixel(32, 30), [179, 102, 153], "{mode:?}: ke + ka·Ia");
        let lit = Material { ka: Vec3::ONE, kd: Vec3::ONE, ..dark };
        let s = scene(64, Vec3::ONE, vec![light], vec![object(textured(p, uv, black(), lit), Some(mode))]);
        assert_eq!(draw(&s).pixel(32, 30), [51, 102, 153], "{mode:?}: a black texel keeps ke");
    }
}

/// The first row (from the top, in column 32) whose colour is the texture's
/// upper (white) half, on a floor receding from z = −1 to z = −5.
fn boundary_row(interpolation: Interpolation) -> u32 {
    let px = [[255, 255, 255, 255], [0, 0, 0, 255]]; // top row white, bottom row black
    let texture = Texture::from_rgba8(1, 2, &px.concat()).expect("valid");
    let p = vec![
        Vec3::new(-1.0, -1.0, -1.0),
        Vec3::new(1.0, -1.0, -1.0),
        Vec3::new(1.0, -1.0, -5.0),
        Vec3::new(-1.0, -1.0, -5.0),
    ];
    let uv = vec![Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), Vec2::new(1.0, 1.0), Vec2::new(0.0, 1.0)];
    let mut o = object(textured(p, uv, texture, unlit()), Some(ShadingMode::Flat));
    o.cull_back_faces = false;
    let mut s = scene(101, Vec3::ONE, vec![], vec![o]);
    s.settings.interpolation = interpolation;
    let image = draw(&s);
    (0..101)
        .find(|&y| image.pixel(50, y) == [255, 255, 255])
        .map_or(0, |top| (top..101).find(|&y| image.pixel(50, y) == [0, 0, 0]).unwrap_or(0))
}

#[test]
fn perspective_correct_and_affine_boundaries_fall_where_the_formulas_say() {
    // The floor y = −1 from z = −1 to −5; t = 0.5 is at z = −3 in eye space,
    // which projects to y_nc = −1/3: window y (1 + 1/3)/2 · 101 = 67.33, so
    // the first black row is 67 (sample centre 67.5 lies below it). Affine
    // mapping puts t = 0.5 halfway between the projected ends y_nc = −1 and
    // −0.2, at y_nc = −0.6: y = (1 + 0.6)/2 · 101 = 80.8, first black row 81
    // (row 80's centre 80.5 is above it).
    assert_eq!(boundary_row(Interpolation::PerspectiveCorrect), 67);
    assert_eq!(boundary_row(Interpolation::ScreenLinear), 81);
}

#[test]
fn a_mesh_without_texture_coordinates_is_drawn_untextured() {
    let (p, _) = square(1.0, -2.0);
    let mesh = Mesh::new("plain", p, None, vec![[0, 1, 2], [0, 2, 3]], unlit()).expect("valid");
    let mesh = mesh.with_diffuse_map(TextureMap {
        texture: Arc::new(checker()),
        sampler: Sampler::default(),
        alpha_blend: false,
        alpha_cutoff: None,
    });
    let s = scene(64, Vec3::ONE, vec![], vec![object(Arc::new(mesh), None)]);
    assert_eq!(draw(&s).pixel(32, 32), [255, 255, 255]);
}

#[test]
fn texel_alpha_blends_when_the_map_says_so() {
    // A white texel at alpha 102/255 = 0.4 over an opaque red square (unlit):
    // C = 0.4·white + 0.6·red = (1, 0.4, 0.4) → (255, 102, 102). Without
    // alpha blending the texel is opaque white.
    let texel = [255, 255, 255, 102];
    let red = Material { ka: Vec3::new(1.0, 0.0, 0.0), ..unlit() };
    for (alpha_blend, want) in [(true, [255, 102, 102]), (false, [255, 255, 255])] {
        let (p, uv) = square(1.0, -2.0);
        let mut mesh = (*textured(p, uv, Texture::from_rgba8(1, 1, &texel).expect("valid"), unlit())).clone();
        if let Some(map) = &mut mesh.diffuse_map {
            map.alpha_blend = alpha_blend;
        }
        let (q, _) = square(1.5, -3.0);
        let under = Mesh::new("under", q, None, vec![[0, 1, 2], [0, 2, 3]], red).expect("valid");
        let mut top = object(Arc::new(mesh), Some(ShadingMode::Flat));
        top.cull_back_faces = false;
        let s = scene(64, Vec3::ONE, vec![], vec![top, object(Arc::new(under), None)]);
        assert_eq!(draw(&s).pixel(32, 32), want, "alpha_blend {alpha_blend}");
    }
}

#[test]
fn alpha_mask_discards_samples_below_the_cutoff_before_depth() {
    // A white square in front of a red one; its texel alpha against a 0.5
    // cutoff decides whether the front square exists at all.
    let red = Material { ka: Vec3::new(1.0, 0.0, 0.0), ..unlit() };
    for (alpha, want) in [(76u8, [255, 0, 0]), (179, [255, 255, 255])] {
        let (p, uv) = square(1.0, -2.0);
        let texel = [255, 255, 255, alpha];
        let mut mesh = (*textured(p, uv, Texture::from_rgba8(1, 1, &texel).expect("valid"), unlit())).clone();
        if let Some(map) = &mut mesh.diffuse_map {
            map.alpha_cutoff = Some(0.5);
        }
        let (q, _) = square(1.5, -3.0);
        let under = Mesh::new("under", q, None, vec![[0, 1, 2], [0, 2, 3]], red).expect("valid");
        // The masked square is drawn first: a discarded sample must not
        // have written depth that would hide the red square behind it.
        let s =
            scene(64, Vec3::ONE, vec![], vec![object(Arc::new(mesh), None), object(Arc::new(under), None)]);
        assert_eq!(draw(&s).pixel(32, 32), want, "texel alpha {alpha}/255");
    }
}

#[test]
fn a_white_texture_leaves_a_clipped_gouraud_triangle_unchanged() {
    // A triangle reaching behind the eye, lit by a near point light with a
    // highlight: clipping must interpolate the lit parts of the original
    // vertices (SPEC §2), not light the new vertices, with or without a
    // texture. Found by the f64 truth's property test: relighting the
    // clipped vertices put pixel (24, 40) at 30 instead of 89.
    let positions = vec![Vec3::new(-2.0, -1.0, -3.0), Vec3::new(2.0, -1.0, -3.0), Vec3::new(0.0, -1.0, 2.0)];
    let normals = vec![Vec3::new(-0.8, 0.6, 0.0), Vec3::new(0.8, 0.6, 0.0), Vec3::new(0.0, 0.6, 0.8)];
    let material = Material {
        ka: Vec3::ZERO,
        kd: Vec3::splat(0.8),
        ks: Vec3::splat(0.5),
        ns: 8.0,
        ..Material::default()
    };
    let plain =
        Mesh::new("clipped", positions, Some(normals), vec![[0, 1, 2]], material).expect("valid mesh");
    let white =
        plain.clone().with_uvs(vec![Vec2::ZERO; 3]).expect("valid uvs").with_diffuse_map(TextureMap {
            texture: Arc::new(Texture::solid(glam::Vec4::ONE)),
            sampler: Sampler::default(),
            alpha_blend: false,
            alpha_cutoff: None,
        });
    let light = Light::Point {
        position: Vec3::new(0.0, 0.0, -1.0),
        color: Vec3::ONE,
        attenuation: Default::default(),
    };
    let draw_mesh = |mesh: Mesh| {
        let mut o = object(Arc::new(mesh), Some(ShadingMode::Gouraud));
        o.cull_back_faces = false;
        let mut s = scene(48, Vec3::ZERO, vec![light], vec![o]);
        s.camera.target = Vec3::new(0.0, -0.5, -1.0);
        s.camera.projection =
            zline_scene::Projection::Perspective { fovy_degrees: 60.0, near: 0.5, far: 20.0 };
        draw(&s)
    };
    let (plain, white) = (draw_mesh(plain), draw_mesh(white));
    assert!(plain.pixel(24, 40)[0] > 60, "the test scene lights pixel (24, 40): {:?}", plain.pixel(24, 40));
    let worst = plain.to_rgb().iter().zip(white.to_rgb()).map(|(a, b)| a.abs_diff(b)).max();
    // Textured and untextured Gouraud interpolate different quantities (the
    // parts before the clamp vs the clamped colour), equal here since no
    // channel exceeds 1; f32 rounding may still differ by one step.
    assert!(worst <= Some(1), "textured and untextured differ by {worst:?}");
}
