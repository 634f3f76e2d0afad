//! Property test: bump and normal maps in the fast renderer against the
//! truth's f64 evaluation of the same perturbation (`zline_scene::NormalMap`)
//! — a wavy grid with texture coordinates and MikkTSpace tangents, under a
//! random rotation (mirrored or not) and light, with a random height map
//! (scale of either sign) or normal map, bilinear, drawn with Phong.
//!
//! The bound is `versus_fast`'s, unchanged: away from edges (1 px), each
//! channel within ½ + 0.01 step plus the truth's sensitivity to the 1/256
//! px vertex snap, and at least 95 % of the compared pixels exact. The
//! perturbation adds f32 rounding only: texel reads (the same stored
//! texels, filtered in f32 and in f64), central differences of two f32
//! samples one texel apart (an absolute error of a few 2⁻²⁴ in h, times
//! W/2 and k), and one more normalization. Bilinear maps make the
//! perturbed normal continuous, so the sensitivity still bounds what the
//! snap moves.

use std::sync::Arc;

use glam::{Mat4, Quat, Vec2, Vec3};
use proptest::prelude::*;
use zline_scene::{Mesh, NormalEncoding, NormalMap, Object, RenderSettings, Scene, TextureMap};
use zline_shading::{Filter, Sampler, ShadingMode, Texture, Wrap};

use crate::versus_fast::{camera, cases, compare, light, material, EXACT_SHARE, SIZE};

/// An n × n grid over [−3, 3]² at z = 0, bent by a gentle wave, texture
/// coordinates repeating `repeat` times across it, MikkTSpace tangents.
fn wavy(n: u32, repeat: f32, material: zline_shading::Material) -> Mesh {
    let (mut positions, mut normals, mut uvs) = (Vec::new(), Vec::new(), Vec::new());
    for j in 0..=n {
        for i in 0..=n {
            let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
            let (x, y) = (6.0 * u - 3.0, 6.0 * v - 3.0);
            let z = 0.3 * (x * 0.8).sin() * (y * 0.6).cos();
            let (dx, dy) =
                (0.24 * (x * 0.8).cos() * (y * 0.6).cos(), -0.18 * (x * 0.8).sin() * (y * 0.6).sin());
            positions.push(Vec3::new(x, y, z));
            normals.push(Vec3::new(-dx, -dy, 1.0).normalize());
            uvs.push(Vec2::new(u, v) * repeat);
        }
    }
    let index = |i: u32, j: u32| j * (n + 1) + i;
    let triangles = (0..n)
        .flat_map(|j| {
            (0..n).flat_map(move |i| {
                let (a, b, c, d) = (index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1));
                [[a, b, c], [a, c, d]]
            })
        })
        .collect();
    Mesh::new("wavy", positions, Some(normals), triangles, material)
        .and_then(|m| m.with_uvs(uvs))
        .expect("valid mesh")
        .with_generated_tangents()
}

/// A random map: an 8 × 8 height map or a 4 × 4 normal map (b ≥ 128, so
/// every normal faces out), with its scale.
fn map() -> impl Strategy<Value = (Texture, NormalEncoding, f32)> {
    prop_oneof![
        (prop::collection::vec(any::<u8>(), 64), -0.15f32..0.15).prop_map(|(h, k)| {
            let px: Vec<u8> = h.iter().flat_map(|&v| [v, v, v, 255]).collect();
            (Texture::from_rgba8(8, 8, &px).expect("valid"), NormalEncoding::Height, k)
        }),
        (prop::collection::vec((any::<u8>(), any::<u8>(), 128u8..=255), 16), 0.0f32..1.5).prop_map(
            |(n, k)| {
                let px: Vec<u8> = n.iter().flat_map(|&(r, g, b)| [r, g, b, 255]).collect();
                (Texture::from_rgba8(4, 4, &px).expect("valid"), NormalEncoding::Tangent, k)
            }
        ),
    ]
}

prop_compose! {
    fn bump_scene()(
        (texture, encoding, scale) in map(),
        repeat in 0.5f32..2.0,
        material in material(),
        (ax, ay, mirrored) in (-0.8f32..0.8, -0.8f32..0.8, any::<bool>()),
        light in light(),
        camera in camera(),
        wrap in prop::sample::select(vec![Wrap::Repeat, Wrap::ClampToEdge]),
    ) -> Scene {
        let sampler = Sampler { filter: Filter::Bilinear, wrap_s: wrap, wrap_t: wrap };
        let map = TextureMap { texture: Arc::new(texture), sampler, alpha_blend: false, alpha_cutoff: None };
        let mesh = wavy(6, repeat, material).with_normal_map(NormalMap { map, encoding, scale });
        let mirror = if mirrored { Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0)) } else { Mat4::IDENTITY };
        let world_from_object = Mat4::from_translation(Vec3::new(0.0, 0.0, -6.0))
            * Mat4::from_quat(Quat::from_rotation_x(ax) * Quat::from_rotation_y(ay))
            * mirror;
        let object = Object {
            mesh: Arc::new(mesh),
            world_from_object,
            material: None,
            shading: Some(ShadingMode::Phong),
            cull_back_faces: false,
        };
        Scene {
            environment: None,
            shadows: Default::default(),
            camera,
            background: Vec3::ZERO,
            ambient: Vec3::splat(0.1),
            lights: vec![light],
            objects: vec![object],
            settings: RenderSettings { width: SIZE, height: SIZE, ..RenderSettings::default() },
            fog: None,
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    #[test]
    fn bump_and_normal_maps_are_within_the_bound_of_the_truth(scene in bump_scene()) {
        let (compared, exact) = compare(&scene).map_err(TestCaseError::fail)?;
        prop_assert!(compared > 0 || scene.objects.is_empty(), "nothing compared");
        let allowed = ((1.0 - EXACT_SHARE) * compared as f64).max(2.0);
        prop_assert!((compared - exact) as f64 <= allowed, "{} of {compared} compared pixels inexact", compared - exact);
    }
}
