//! The raster core: a small mesh with arbitrary f32 vertices (NaN, ±inf,
//! 1e30, subnormals, vertices on the eye plane so that w ≈ 0, degenerate
//! triangles), built in code with the mesh fields set directly (bypassing
//! `Mesh::new`'s checks, as a hand-built scene may), rendered at up to
//! 64×64 with shading, interpolation, depth mode, ssaa 1–2, tile size,
//! texture and culling chosen by the input. Must never panic, and must be
//! deterministic: the same scene rendered with 1 and with 2 threads, and
//! twice, gives identical pixels.
#![no_main]

use std::sync::Arc;

use arbitrary::{Arbitrary, Unstructured};
use glam::{Mat4, Vec2, Vec3};
use libfuzzer_sys::fuzz_target;
use zline_pipeline::{render, RenderOptions};
use zline_scene::{
    Camera, DepthMode, GouraudClamp, Interpolation, LightingSides, Mesh, Object, Projection, RenderSettings,
    Scene, TextureMap,
};
use zline_shading::{Attenuation, Filter, Light, Material, Sampler, ShadingMode, Texture, Wrap};

/// A float: mostly the interesting values, sometimes any bit pattern.
#[derive(Debug)]
struct F(f32);

const SPECIAL: [f32; 24] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    -0.5,
    2.0,
    -3.0,
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    1e30,
    -1e30,
    f32::MAX,
    f32::MIN,
    1e-30,
    -1e-30,
    1e-40, // subnormal
    f32::MIN_POSITIVE,
    f32::EPSILON,
    1e-7,
    -1e-7,
    1e7,
    -2.5e-3,
];

impl<'a> Arbitrary<'a> for F {
    fn arbitrary(u: &mut Unstructured<'a>) -> arbitrary::Result<F> {
        Ok(F(match u.int_in_range(0u8..=3)? {
            0 => f32::from_bits(u.arbitrary()?),
            1 => f32::from(u.arbitrary::<i8>()?) / 16.0,
            _ => *u.choose(&SPECIAL)?,
        }))
    }
}

fn v3(u: &mut Unstructured) -> arbitrary::Result<Vec3> {
    Ok(Vec3::new(F::arbitrary(u)?.0, F::arbitrary(u)?.0, F::arbitrary(u)?.0))
}

fn mesh(u: &mut Unstructured, texture: &Arc<Texture>) -> arbitrary::Result<Mesh> {
    let n = u.int_in_range(1usize..=9)?;
    // Vertices in the eye-space slab around z = −1; the camera sits at the
    // origin looking down −z, so z ≈ 0 gives w ≈ 0.
    let mut positions = Vec::with_capacity(n);
    for _ in 0..n {
        positions.push(v3(u)? + Vec3::new(0.0, 0.0, -f32::from(u.int_in_range(0u8..=2)?)));
    }
    let count = u.int_in_range(1usize..=8)?;
    let mut triangles = Vec::with_capacity(count);
    for _ in 0..count {
        let mut t = [0u32; 3];
        for i in &mut t {
            *i = u.int_in_range(0..=n as u32 - 1)?;
        }
        triangles.push(t);
    }
    let normals = if u.arbitrary()? {
        (0..n).map(|_| v3(u)).collect::<arbitrary::Result<_>>()?
    } else {
        vec![Vec3::Z; n]
    };
    let uvs = if u.arbitrary()? {
        (0..n)
            .map(|_| Ok(Vec2::new(F::arbitrary(u)?.0, F::arbitrary(u)?.0)))
            .collect::<arbitrary::Result<_>>()?
    } else {
        Vec::new()
    };
    let colors =
        if u.arbitrary()? { (0..n).map(|_| v3(u)).collect::<arbitrary::Result<_>>()? } else { Vec::new() };
    let diffuse_map = if !uvs.is_empty() && u.arbitrary()? {
        let filter = *u.choose(&[Filter::Nearest, Filter::Bilinear, Filter::Trilinear])?;
        let wrap = *u.choose(&[Wrap::Repeat, Wrap::ClampToEdge])?;
        Some(TextureMap {
            texture: texture.clone(),
            sampler: Sampler { filter, wrap_s: wrap, wrap_t: wrap },
            alpha_blend: u.arbitrary()?,
            alpha_cutoff: if u.arbitrary()? { Some(F::arbitrary(u)?.0) } else { None },
        })
    } else {
        None
    };
    let mut material = Material::DEFAULT;
    if u.arbitrary()? {
        material.kd = v3(u)?;
        material.ks = v3(u)?;
        material.ns = F::arbitrary(u)?.0;
        material.opacity = F::arbitrary(u)?.0;
    }
    Ok(Mesh { name: "fuzz".into(), positions, normals, triangles, material, uvs, colors, diffuse_map })
}

fn scene(u: &mut Unstructured, texture: &Arc<Texture>) -> arbitrary::Result<(Scene, u32)> {
    let near = *u.choose(&[1e-6f32, 1e-3, 0.1, 0.5, 1.0])?;
    let far = *u.choose(&[near * 2.0, 10.0, 100.0, 1e6, 1e30])?;
    let projection = if u.arbitrary()? {
        Projection::Perspective { fovy_degrees: f32::from(u.int_in_range(1u8..=179)?), near, far }
    } else {
        Projection::Orthographic { height: *u.choose(&[1e-6f32, 1.0, 4.0, 1e6])?, near, far }
    };
    let camera = Camera { eye: Vec3::ZERO, target: Vec3::NEG_Z, up: Vec3::Y, projection };
    let mut objects = Vec::new();
    for _ in 0..u.int_in_range(1u8..=2)? {
        let world_from_object = match u.int_in_range(0u8..=3)? {
            0 => Mat4::IDENTITY,
            1 => Mat4::from_scale(Vec3::splat(*u.choose(&[1e-30f32, 1e-3, 1e3, 1e30])?)),
            2 => Mat4::from_translation(Vec3::new(0.0, 0.0, *u.choose(&[-1.0f32, -1e-3, 1e-7, 0.5])?)),
            _ => Mat4::from_rotation_y(F::arbitrary(u)?.0),
        };
        let shading = if u.arbitrary()? { Some(*u.choose(&ShadingMode::ALL)?) } else { None };
        objects.push(Object {
            mesh: Arc::new(mesh(u, texture)?),
            world_from_object,
            material: None,
            shading,
            cull_back_faces: u.arbitrary()?,
        });
    }
    let mut lights = vec![Light::Directional { direction: Vec3::new(0.3, -1.0, -0.5), color: Vec3::ONE }];
    if u.arbitrary()? {
        lights.push(Light::Point {
            position: v3(u)?,
            color: Vec3::splat(0.8),
            attenuation: Attenuation { a0: 1.0, a1: F::arbitrary(u)?.0.abs(), a2: 0.0 },
        });
    }
    let settings = RenderSettings {
        width: u.int_in_range(1u32..=64)?,
        height: u.int_in_range(1u32..=64)?,
        shading: *u.choose(&ShadingMode::ALL)?,
        interpolation: *u.choose(&[Interpolation::PerspectiveCorrect, Interpolation::ScreenLinear])?,
        texture_filter: if u.arbitrary()? {
            Some(*u.choose(&[Filter::Nearest, Filter::Bilinear, Filter::Trilinear])?)
        } else {
            None
        },
        ssaa: u.int_in_range(1u32..=2)?,
        depth: *u.choose(&[DepthMode::Normalized, DepthMode::ReversedFloat])?,
        adaptive_tolerance: if u.arbitrary()? { Some(*u.choose(&[0.0f32, 0.5, 2.0])?) } else { None },
        gouraud_clamp: *u.choose(&[GouraudClamp::PerVertex, GouraudClamp::PerSample])?,
        lighting_sides: *u.choose(&[LightingSides::TwoSided, LightingSides::OneSided])?,
    };
    let tile = *u.choose(&[0u32, 1, 7, 8, 16, 64, u32::MAX])?;
    let scene = Scene {
        camera,
        background: Vec3::splat(0.1),
        ambient: Vec3::splat(0.15),
        lights,
        objects,
        settings,
        fog: None,
        shadows: Default::default(),
    };
    Ok((scene, tile))
}

fn texture() -> Arc<Texture> {
    static T: std::sync::OnceLock<Arc<Texture>> = std::sync::OnceLock::new();
    T.get_or_init(|| {
        let pixels: Vec<u8> = (0..8 * 4 * 4).map(|i| (i * 37 % 256) as u8).collect();
        Arc::new(Texture::from_rgba8(8, 4, &pixels).unwrap())
    })
    .clone()
}

fuzz_target!(|data: &[u8]| {
    let mut u = Unstructured::new(data);
    let Ok((scene, tile_size)) = scene(&mut u, &texture()) else { return };
    let options = RenderOptions { tile_size };
    let (one, _) = zline_fuzz::pool(1).install(|| render(&scene, &options));
    assert_eq!(one.pixels.len(), (scene.settings.width * scene.settings.height) as usize);
    let (two, _) = zline_fuzz::pool(2).install(|| render(&scene, &options));
    assert!(one.pixels == two.pixels, "1 and 2 threads differ");
    let (again, _) = zline_fuzz::pool(1).install(|| render(&scene, &options));
    assert!(one.pixels == again.pixels, "two renders differ");
    // Any tile size gives the same image.
    let (tiles, _) = zline_fuzz::pool(1).install(|| render(&scene, &RenderOptions { tile_size: 8 }));
    assert!(one.pixels == tiles.pixels, "tile size {tile_size} and 8 differ");
});
