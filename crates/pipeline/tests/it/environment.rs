//! The environment map (SPEC §5.3) and tone mapping (SPEC §10) through the
//! whole pipeline: the sky behind undrawn samples, a uniform environment
//! equal to the ambient light it stands for, colours above 1 reaching the
//! tone mapping in every shading mode, and sRGB colour textures decoded
//! under a display tone mapping.

use std::sync::Arc;

use glam::{DVec3, Vec2, Vec3, Vec4};
use zline_pipeline::{render, RenderOptions};
use zline_scene::{Mesh, Scene, TextureMap};
use zline_shading::{
    Environment, EnvironmentLight, Filter, Material, Microfacet, Model, Panorama, Sampler, ShadingMode,
    Texture, ToneMap, ToneMapping, Wrap,
};

use crate::support::{draw, object, scene, square};

fn sky(intensity: f32, rotation: f32, background: bool) -> Environment {
    let light = Arc::new(EnvironmentLight::new(Panorama::sky(128, 64)));
    let mut e = Environment::new(light);
    (e.intensity, e.rotation_degrees, e.background) = (intensity, rotation, background);
    e
}

fn sphere(material: Material, center: Vec3) -> zline_scene::Object {
    let mesh = zline_scene::uv_sphere(24, 48, 0.8);
    let mut o = object(Arc::new(Mesh { material, ..mesh }), Some(ShadingMode::Phong));
    o.world_from_object = glam::Mat4::from_translation(center);
    o
}

/// Undrawn samples show the panorama along their ray: each corner pixel
/// against the panorama read along the ray computed here (f64 camera
/// inverse), within one step (the direction's last bits differ).
#[test]
fn the_sky_fills_the_undrawn_pixels() {
    let black = Material { ka: Vec3::ZERO, kd: Vec3::ZERO, ks: Vec3::ZERO, ..Material::default() };
    let mut s = scene(64, Vec3::ZERO, vec![], vec![object(square(0.0, 0.0, 0.2, -2.0, black), None)]);
    let env = sky(0.8, 25.0, true);
    s.environment = Some(env.clone());
    let image = draw(&s);
    let clip_from_eye = s.camera.clip_from_eye(1.0).as_dmat4();
    let eye_from_clip = clip_from_eye.inverse();
    for (x, y) in [(0u32, 0u32), (63, 0), (0, 63), (63, 63), (10, 40)] {
        let ndc = DVec3::new((x as f64 + 0.5) / 32.0 - 1.0, 1.0 - (y as f64 + 0.5) / 32.0, 0.0);
        let d = eye_from_clip.project_point3(ndc).normalize();
        let d = if d.z > 0.0 { -d } else { d };
        // The camera looks down −z from the origin: eye space is world space.
        let c = env.background_radiance(d.as_vec3());
        let want = c.to_array().map(|v| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as i32);
        let got = image.pixel(x, y).map(i32::from);
        assert!((0..3).all(|k| (got[k] - want[k]).abs() <= 1), "pixel ({x}, {y}): {got:?} vs {want:?}");
    }
    // The square in the middle is drawn, not the sky.
    assert_eq!(image.pixel(32, 32), [0, 0, 0]);
    // Without `background`, the background colour.
    s.environment = Some(sky(0.8, 25.0, false));
    assert_eq!(draw(&s).pixel(0, 0), [0, 0, 0]);
}

/// A panorama of one radiance c at intensity k lights like the ambient
/// light Ia + k·c: both models, images within one step (and mostly equal).
#[test]
fn a_uniform_environment_is_the_ambient_light_it_stands_for() {
    let c = Vec3::new(0.3, 0.5, 0.8);
    let uniform = Panorama::new(32, 16, vec![c; 32 * 16]).unwrap().0;
    let mut env = Environment::new(Arc::new(EnvironmentLight::new(uniform)));
    env.intensity = 0.5;
    let metal = Material {
        kd: Vec3::new(0.9, 0.7, 0.3),
        model: Model::CookTorrance(Microfacet { metallic: 1.0, roughness: 0.4, ..Microfacet::default() }),
        ..Material::default()
    };
    let dielectric = Material {
        kd: Vec3::new(0.2, 0.6, 0.9),
        model: Model::CookTorrance(Microfacet { metallic: 0.0, roughness: 0.7, ..Microfacet::default() }),
        ..Material::default()
    };
    let basic = Material::plastic(Vec3::new(0.8, 0.4, 0.3), 0.5, 30.0);
    let light =
        zline_shading::Light::Directional { direction: Vec3::new(-0.3, -1.0, -0.5), color: Vec3::ONE };
    let objects = vec![
        sphere(metal, Vec3::new(-1.0, 0.5, -4.0)),
        sphere(dielectric, Vec3::new(1.0, 0.5, -4.0)),
        sphere(basic, Vec3::new(0.0, -0.9, -4.0)),
    ];
    let ambient = Vec3::splat(0.1);
    let mut with_env = scene(96, ambient, vec![light], objects);
    with_env.environment = Some(env);
    let mut plain = with_env.clone();
    plain.environment = None;
    plain.ambient = ambient + 0.5 * c;
    let (a, b) = (draw(&with_env), draw(&plain));
    let mut differ = 0;
    for (p, q) in a.pixels.iter().zip(&b.pixels) {
        let (p, q) = (p.to_le_bytes(), q.to_le_bytes());
        let most = (0..3).map(|k| (i32::from(p[k]) - i32::from(q[k])).abs()).max().unwrap_or(0);
        assert!(most <= 1, "{p:?} vs {q:?}");
        differ += usize::from(most > 0);
    }
    // Measured: a handful of pixels (f32 rounding of the SH sum).
    assert!(differ < a.pixels.len() / 50, "{differ} pixels differ");
}

/// A square lit head-on by a light of 3 (no ambient), colour 3·kd, reaches
/// the tone mapping unclamped in flat, Gouraud and Phong shading, with a
/// texture and without: the pixel is the operator's value, computed here.
#[test]
fn colours_above_one_reach_the_tone_mapping() {
    let kd = Vec3::new(1.0, 0.5, 0.2);
    let ke = 3.0 * kd;
    let emissive = Material { ka: Vec3::ZERO, kd, ks: Vec3::ZERO, ..Material::default() };
    let light = zline_shading::Light::Directional { direction: Vec3::NEG_Z, color: Vec3::splat(3.0) };
    for operator in ToneMap::ALL {
        for exposure in [1.0, 0.25] {
            let tone = ToneMapping { operator, exposure };
            let want = tone.apply(ke).to_array().map(|v| (v * 255.0 + 0.5) as u8);
            for mode in ShadingMode::ALL {
                for textured in [false, true] {
                    let mut mesh = (*square(0.0, 0.0, 1.0, -2.0, emissive)).clone();
                    if textured {
                        mesh = white_texture(mesh);
                    }
                    let mut s = scene(16, Vec3::ZERO, vec![light], vec![object(Arc::new(mesh), Some(mode))]);
                    s.settings.tone_mapping = tone;
                    let got = draw(&s).pixel(8, 8);
                    assert_eq!(got, want, "{operator:?} exposure {exposure} {mode:?} textured {textured}");
                }
            }
        }
    }
}

fn white_texture(mesh: Mesh) -> Mesh {
    let uvs = vec![Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y];
    let sampler = Sampler { filter: Filter::Nearest, wrap_s: Wrap::ClampToEdge, wrap_t: Wrap::ClampToEdge };
    mesh.with_uvs(uvs).expect("uvs").with_diffuse_map(TextureMap {
        texture: Arc::new(Texture::solid(Vec4::ONE)),
        sampler,
        alpha_blend: false,
        alpha_cutoff: None,
    })
}

/// Under a display tone mapping a colour texture is read decoded from
/// sRGB; without one, as stored.
#[test]
fn colour_textures_are_decoded_from_srgb_under_a_display_tone_mapping() {
    let byte = 128u8;
    let texture = Texture::from_rgba8(1, 1, &[byte, byte, byte, 255]).unwrap();
    let unlit = Material { ka: Vec3::ONE, kd: Vec3::ZERO, ks: Vec3::ZERO, ..Material::default() };
    let mut mesh = (*square(0.0, 0.0, 1.0, -2.0, unlit)).clone();
    let uvs = vec![Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y];
    let sampler = Sampler { filter: Filter::Bilinear, wrap_s: Wrap::Repeat, wrap_t: Wrap::Repeat };
    mesh = mesh.with_uvs(uvs).expect("uvs").with_diffuse_map(TextureMap {
        texture: Arc::new(texture),
        sampler,
        alpha_blend: false,
        alpha_cutoff: None,
    });
    let mut s: Scene = scene(16, Vec3::ONE, vec![], vec![object(Arc::new(mesh), Some(ShadingMode::Phong))]);
    assert_eq!(draw(&s).pixel(8, 8), [byte; 3]);
    s.settings.tone_mapping = ToneMapping { operator: ToneMap::KhrPbrNeutral, exposure: 1.0 };
    let stored = f32::from(byte) / 255.0;
    let linear = ((stored + 0.055) / 1.055).powf(2.4);
    let want = s.settings.tone_mapping.apply(Vec3::splat(linear)).x;
    assert_eq!(draw(&s).pixel(8, 8), [(want * 255.0 + 0.5) as u8; 3]);
}

/// Threads and tiles do not change a frame with the sky behind it, a
/// tone mapping and supersampling.
#[test]
fn the_sky_and_tone_mapping_are_the_same_whatever_the_threads_and_tiles() {
    let mut s = scene(
        72,
        Vec3::splat(0.05),
        vec![],
        vec![sphere(
            Material {
                kd: Vec3::new(0.9, 0.9, 0.9),
                model: Model::CookTorrance(Microfacet {
                    metallic: 1.0,
                    roughness: 0.2,
                    ..Microfacet::default()
                }),
                ..Material::default()
            },
            Vec3::new(0.0, 0.0, -3.0),
        )],
    );
    s.environment = Some(sky(1.0, -40.0, true));
    s.settings.tone_mapping = ToneMapping { operator: ToneMap::Aces, exposure: 1.3 };
    s.settings.ssaa = 2;
    let reference = render(&s, &RenderOptions { tile_size: 64 }).0;
    for (threads, tile_size) in [(1, 8), (3, 16), (2, 40)] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        let other = pool.install(|| render(&s, &RenderOptions { tile_size }).0);
        assert_eq!(other.pixels, reference.pixels, "{threads} threads, tiles of {tile_size}");
    }
}
