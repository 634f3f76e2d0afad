//! Bump and normal maps (`zline_scene::NormalMap`): the perturbed normal
//! of hand-made maps against the lighting model evaluated by hand with the
//! normal the formulas predict.
//!
//! The square faces +z at z = −2 with (s, t) = (x, y) mapped to [0, 1]²,
//! so MikkTSpace gives T = +x, w = +1 and B = w·(N × T) = +y; the lights
//! are directional and the material diffuse only (kd = 1, no ambient, no
//! specular), so a pixel is floor(255·max(n′·L, 0) + ½).

use std::sync::Arc;

use glam::{DVec3, Vec2, Vec3};
use zline_scene::{Mesh, NormalEncoding, NormalMap, Scene, TextureMap};
use zline_shading::{Filter, Light, Material, Sampler, ShadingMode, Texture, Wrap};

use crate::support::{draw, object, scene};

fn diffuse() -> Material {
    Material { ka: Vec3::ZERO, kd: Vec3::ONE, ks: Vec3::ZERO, ..Material::default() }
}

/// The square with texture coordinates and generated tangents, and `map`
/// when given.
fn square(map: Option<(Texture, NormalEncoding, f32)>) -> Arc<Mesh> {
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    let p = corners.map(|(x, y)| Vec3::new(x, y, -2.0)).to_vec();
    let uv = corners.map(|(x, y)| Vec2::new((x + 1.0) / 2.0, (y + 1.0) / 2.0)).to_vec();
    let mesh = Mesh::new("square", p, Some(vec![Vec3::Z; 4]), vec![[0, 1, 2], [0, 2, 3]], diffuse())
        .and_then(|m| m.with_uvs(uv))
        .expect("valid mesh")
        .with_generated_tangents();
    assert_eq!(mesh.tangents, vec![glam::Vec4::new(1.0, 0.0, 0.0, 1.0); 4], "T = +x, w = +1");
    let Some((texture, encoding, scale)) = map else {
        return Arc::new(mesh);
    };
    let sampler = Sampler { filter: Filter::Bilinear, wrap_s: Wrap::ClampToEdge, wrap_t: Wrap::ClampToEdge };
    let map = TextureMap { texture: Arc::new(texture), sampler, alpha_blend: false, alpha_cutoff: None };
    Arc::new(mesh.with_normal_map(NormalMap { map, encoding, scale }))
}

fn lit(mesh: Arc<Mesh>, mode: ShadingMode, towards_light: DVec3) -> Scene {
    let light = Light::Directional { direction: -towards_light.as_vec3(), color: Vec3::ONE };
    scene(64, Vec3::ZERO, vec![light], vec![object(mesh, Some(mode))])
}

/// floor(255·max(n·L, 0) + ½) with both normalized, in f64.
fn expected(n: DVec3, l: DVec3) -> u8 {
    let c = n.normalize().dot(l.normalize()).max(0.0) * 255.0;
    let frac = (c + 0.5).fract();
    assert!(frac > 0.02 && frac < 0.98, "{c}: too near a rounding boundary for an exact test");
    (c + 0.5).floor() as u8
}

/// A 52 × 1 ramp in red: texel x holds 5x/255, so bilinear filtering
/// gives a height rising by 5/255 per texel, ∂h/∂s = 5·52/255 = 260/255
/// everywhere between the first and last texel centres, and central
/// differences return it exactly (up to f32 rounding).
fn ramp() -> Texture {
    let px: Vec<u8> = (0..52u8).flat_map(|x| [5 * x, 0, 0, 255]).collect();
    Texture::from_rgba8(52, 1, &px).expect("valid texture")
}

#[test]
fn a_linear_ramp_tilts_the_normal_by_the_predicted_angle() {
    // m = (−k·∂h/∂s, −k·∂h/∂t, 1) = (−k·260/255, 0, 1) in (T, B, N) =
    // (x, y, z): the normal leans towards −x by atan(k·260/255) — 45.56°
    // for k = 1, 27.0° for k = ½.
    for k in [1.0f32, 0.5] {
        let tilted = DVec3::new(-f64::from(k) * 260.0 / 255.0, 0.0, 1.0);
        let angle = (f64::from(k) * 260.0 / 255.0).atan().to_degrees();
        assert!((tilted.normalize().dot(DVec3::Z).acos().to_degrees() - angle).abs() < 1e-9);
        for l in [DVec3::Z, DVec3::new(-1.0, 0.0, 1.0), DVec3::new(1.0, 0.5, 2.0), DVec3::new(0.3, -1.0, 1.0)]
        {
            let image = draw(&lit(square(Some((ramp(), NormalEncoding::Height, k))), ShadingMode::Phong, l));
            let want = expected(tilted, l);
            for (x, y) in [(32, 30), (24, 40), (40, 22)] {
                assert_eq!(image.pixel(x, y), [want; 3], "k = {k}, L = {l}, pixel ({x}, {y})");
            }
            // Without the map the normal is +z.
            let plain = draw(&lit(square(None), ShadingMode::Phong, l));
            assert_eq!(plain.pixel(32, 30), [expected(DVec3::Z, l); 3]);
        }
    }
}

#[test]
fn a_flat_normal_map_tilts_only_by_the_byte_rounding() {
    // (128, 128, 255) decodes as m = (2·128/255 − 1, 2·128/255 − 1,
    // 2·255/255 − 1) = (1/255, 1/255, 1): glTF's rule leaves a tilt of
    // atan(√2/255) ≈ 0.32° towards T + B, so a lit channel moves by at
    // most 255·sin(0.32°) ≈ 1.4 of a step: never more than 2 after
    // rounding. Head-on the tilt is invisible; from (1, 1, 1) it moves
    // n·L from 1/√3 (147.22 → 147) to 148.38 → 148: the pixel changes by
    // one step, exactly as the decoded normal predicts.
    let flat = || Texture::from_rgba8(1, 1, &[128, 128, 255, 255]).expect("valid");
    let decoded = DVec3::new(1.0 / 255.0, 1.0 / 255.0, 1.0);
    assert!((2.0 * f64::from(128u8) / 255.0 - 1.0 - 1.0 / 255.0).abs() < 1e-15);
    for l in [DVec3::Z, DVec3::ONE, DVec3::new(-1.0, 0.2, 1.0)] {
        let mapped = draw(&lit(square(Some((flat(), NormalEncoding::Tangent, 1.0))), ShadingMode::Phong, l));
        let plain = draw(&lit(square(None), ShadingMode::Phong, l));
        assert_eq!(mapped.pixel(32, 30), [expected(decoded, l); 3], "L = {l}");
        assert_eq!(plain.pixel(32, 30), [expected(DVec3::Z, l); 3], "L = {l}");
        if l == DVec3::ONE {
            assert_eq!((mapped.pixel(32, 30)[0], plain.pixel(32, 30)[0]), (148, 147));
        }
        let pixels = (0..64).flat_map(|y| (0..64).map(move |x| (x, y)));
        let most = pixels
            .flat_map(|(x, y)| (0..3).map(move |c| (x, y, c)))
            .map(|(x, y, c)| mapped.pixel(x, y)[c].abs_diff(plain.pixel(x, y)[c]))
            .max();
        assert!(most <= Some(2), "L = {l}: {most:?}");
    }
    // With the scale, only x and y grow: k = 0 gives exactly +z back.
    let l = DVec3::ONE;
    let zero = draw(&lit(square(Some((flat(), NormalEncoding::Tangent, 0.0))), ShadingMode::Phong, l));
    assert_eq!(zero.pixels, draw(&lit(square(None), ShadingMode::Phong, l)).pixels);
}

/// The square rotated 180° about y around its centre, culling off: seen
/// from behind.
fn turn_away(s: &mut Scene) {
    s.objects[0].world_from_object = glam::Mat4::from_translation(Vec3::new(0.0, 0.0, -2.0))
        * glam::Mat4::from_rotation_y(std::f32::consts::PI)
        * glam::Mat4::from_translation(Vec3::new(0.0, 0.0, 2.0));
    s.objects[0].cull_back_faces = false;
}

#[test]
fn flat_and_gouraud_shading_ignore_the_maps() {
    // Also seen from behind: two-sided Gouraud lighting reads the colour
    // the vertex stage lit with the normal turned, which a mesh's tangents
    // must not overwrite.
    let l = DVec3::new(1.0, 0.5, 2.0);
    for mode in [ShadingMode::Flat, ShadingMode::Gouraud] {
        for back in [false, true] {
            let draw_lit = |mesh| {
                let mut s = lit(mesh, mode, l);
                if back {
                    turn_away(&mut s);
                }
                draw(&s)
            };
            let plain = draw_lit(square(None));
            assert_ne!(plain.pixel(32, 30), [0, 0, 0], "{mode:?}, back {back}: lit");
            for encoding in [NormalEncoding::Height, NormalEncoding::Tangent] {
                let mapped = draw_lit(square(Some((ramp(), encoding, 1.0))));
                assert_eq!(mapped.pixels, plain.pixels, "{mode:?}, back {back}, {encoding:?}");
            }
        }
    }
}

#[test]
fn a_mesh_without_tangents_draws_no_map() {
    let l = DVec3::new(1.0, 0.5, 2.0);
    let mut mesh = (*square(Some((ramp(), NormalEncoding::Height, 1.0)))).clone();
    mesh.tangents.clear();
    let image = draw(&lit(Arc::new(mesh), ShadingMode::Phong, l));
    assert_eq!(image.pixels, draw(&lit(square(None), ShadingMode::Phong, l)).pixels);
}

#[test]
fn seen_from_behind_the_perturbed_normal_turns_around() {
    // The square turned away (rotated 180° about y around its centre,
    // culling off): two-sided lighting negates the whole tangent frame
    // (N, T and B), so the back is lit with the front's perturbed normal
    // negated. Front: n′ = (−a, 0, 1) with a = 260/255; rotated it is
    // (a, 0, −1), negated (−a, 0, 1): lit from (−1, 0, 1) both sides are
    // nearly white. Turning N alone would give (a, 0, 1): nearly black.
    let k = 1.0;
    let l = DVec3::new(-1.0, 0.0, 1.0);
    let front = draw(&lit(square(Some((ramp(), NormalEncoding::Height, k))), ShadingMode::Phong, l));
    let mut s = lit(square(Some((ramp(), NormalEncoding::Height, k))), ShadingMode::Phong, l);
    turn_away(&mut s);
    let back = draw(&s);
    // The back's normal: the front normal (−a, 0, 1) rotated to (a, 0, −1),
    // negated by two-sided lighting: (−a, 0, 1) — the same as the front.
    let a = 260.0 / 255.0;
    let want = expected(DVec3::new(-a, 0.0, 1.0), l);
    assert_eq!(back.pixel(32, 30), [want; 3]);
    assert_eq!(front.pixel(32, 30), [want; 3]);
}

#[test]
fn the_normals_image_shows_the_perturbed_normal() {
    // The ramp with k = 1 tilts the normal to (−260/255, 0, 1), normalized:
    // the normals frame writes it encoded (n + 1)/2.
    let n = DVec3::new(-260.0 / 255.0, 0.0, 1.0).normalize();
    let want = ((n + DVec3::ONE) * 0.5).to_array().map(|c| (c * 255.0 + 0.5).floor() as u8);
    let s = lit(square(Some((ramp(), NormalEncoding::Height, 1.0))), ShadingMode::Phong, DVec3::Z);
    let image = zline_pipeline::render_normals(&s, &zline_pipeline::RenderOptions::default()).0;
    for (x, y) in [(32, 30), (24, 40), (40, 22)] {
        assert_eq!(image.pixel(x, y), want, "pixel ({x}, {y})");
    }
    let plain = lit(square(None), ShadingMode::Phong, DVec3::Z);
    let image = zline_pipeline::render_normals(&plain, &zline_pipeline::RenderOptions::default()).0;
    assert_eq!(image.pixel(32, 30), [128, 128, 255]);
}
