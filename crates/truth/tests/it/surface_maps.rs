//! A Cook–Torrance material's metallic–roughness, occlusion and emissive
//! maps (SPEC §5.2, `zline_scene::SurfaceMaps`) in the truth: a pixel by
//! hand, property tests against the fast renderer with random small maps,
//! and the repository's scene `tests/scenes/cook_torrance.toml` (whose
//! box reads all three) against the fast renderer.
//!
//! Both renderers take the truth's bound of `versus_fast` (TOLERANCE =
//! 0.01 step beyond rounding and the truth's sensitivity away from edges,
//! 95 % exact pixels), the truth reading zline's split-sum table
//! (`SplitSum::ZlineTable`), as `cook_torrance`'s property tests do.

use std::path::Path;
use std::sync::Arc;

use glam::{DVec3, Vec2, Vec3};
use proptest::prelude::*;
use zline_scene::{Interpolation, Object, RenderSettings, Scene, SurfaceMaps, TextureMap};
use zline_shading::{
    Distribution, Filter, Light, Material, Microfacet, Model, Sampler, ShadingMode, Texture,
};
use zline_truth::{render_truth, SplitSum};

use crate::cook_torrance::cook_torrance_material;
use crate::support::{check_close, mesh, object, scene};
use crate::versus_fast::{
    camera, cases, color, compare_skipping, light, opaque_object_of, texture_map, EXACT_SHARE, SIZE,
};

/// A 1×1 texture of `rgb` (8-bit values), nearest.
fn flat_map(rgb: [u8; 3]) -> TextureMap {
    TextureMap {
        texture: Arc::new(Texture::from_rgba8(1, 1, &[rgb[0], rgb[1], rgb[2], 255]).expect("a texture")),
        sampler: Sampler { filter: Filter::Nearest, ..Sampler::default() },
        alpha_blend: false,
        alpha_cutoff: None,
    }
}

/// The centre pixel of `cook_torrance::head_on`'s triangle (N = L = V = H)
/// with a white base texture and the maps `maps`, shaded `mode`, under a
/// white directional light and ambient `ambient`.
fn head_on_with_maps(m: Material, maps: SurfaceMaps, ambient: Vec3, mode: ShadingMode) -> DVec3 {
    let p = vec![Vec3::new(-1.0, -1.0, -3.0), Vec3::new(2.0, -1.0, -3.0), Vec3::new(-1.0, 2.0, -3.0)];
    let mut mesh = (*mesh(p, vec![Vec3::Z; 3], vec![[0, 1, 2]], m)).clone();
    mesh.uvs = vec![Vec2::ZERO, Vec2::X, Vec2::Y];
    mesh.diffuse_map = Some(flat_map([255, 255, 255]));
    mesh.surface_maps = maps;
    let light = Light::Directional { direction: Vec3::NEG_Z, color: Vec3::ONE };
    let s = scene(5, ambient, vec![light], vec![object(Arc::new(mesh), Some(mode))]);
    render_truth(&s).pixel(2, 2)
}

/// Head-on (N·L = N·V = N·H = V·H = 1), no ambient light: I = ke ⊙ E +
/// (1 − f0)·c_diff/π + f0/(4π·α²), with the maps' factors:
/// - metallic–roughness texel (·, G, B) = (·, 153, 51): roughness 0.5 ×
///   0.6 = 0.3 (α² = 0.0081), metallic 1 × 0.2 = 0.2;
/// - emissive texel (255, 51, 0): ke = (0.1, 0.2, 0.3) becomes (0.1, 0.04, 0);
/// - occlusion: with Ia = 0 it changes nothing; with Ia = 0.5 and no
///   light the pixel is ke ⊙ E + Ia·occ·[c_diff(1 − E_s) + E_s], so a
///   texel R = 0 with strength 0.5 halves the environment term.
///
/// Flat and Gouraud shading ignore the maps.
#[test]
fn maps_change_the_parameters_per_sample() {
    let pi = std::f64::consts::PI;
    let kd = Vec3::new(0.75, 0.5, 0.25);
    let m = Material {
        kd,
        ke: Vec3::new(0.1, 0.2, 0.3),
        model: Model::CookTorrance(Microfacet {
            metallic: 1.0,
            roughness: 0.5,
            distribution: Distribution::Ggx,
        }),
        ..Material::DEFAULT
    };
    let maps = SurfaceMaps {
        metallic_roughness: Some(flat_map([0, 153, 51])),
        occlusion: None,
        emission: Some(flat_map([255, 51, 0])),
    };
    let base = DVec3::new(0.75, 0.5, 0.25);
    let (metallic, roughness) = (51.0 / 255.0, 0.5 * 153.0 / 255.0);
    let alpha2 = f64::powi(roughness, 4);
    let c_diff = base * (1.0 - metallic);
    let f0 = DVec3::splat(0.04) + (base - 0.04) * metallic;
    let ke = DVec3::new(0.1, 0.2 * 51.0 / 255.0, 0.0);
    let want = ke + (DVec3::ONE - f0) * c_diff / pi + f0 / (4.0 * pi * alpha2);
    let phong = head_on_with_maps(m, maps.clone(), Vec3::ZERO, ShadingMode::Phong);
    check_close(phong, want.min(DVec3::ONE), 1e-6);
    // Without maps, or shaded flat: the factors alone.
    let plain = head_on_with_maps(m, SurfaceMaps::default(), Vec3::ZERO, ShadingMode::Phong);
    let flat = head_on_with_maps(m, maps.clone(), Vec3::ZERO, ShadingMode::Flat);
    check_close(flat, plain, 1e-12);
    assert!((plain - phong).abs().max_element() > 0.05, "{plain} vs {phong}");
    // Occlusion scales the environment only: no light, Ia = 0.5.
    let dark = |occlusion| {
        let maps = SurfaceMaps { occlusion, ..SurfaceMaps::default() };
        let s = {
            let p = vec![Vec3::new(-1.0, -1.0, -3.0), Vec3::new(2.0, -1.0, -3.0), Vec3::new(-1.0, 2.0, -3.0)];
            let mut mesh =
                (*mesh(p, vec![Vec3::Z; 3], vec![[0, 1, 2]], Material { ke: Vec3::ZERO, ..m })).clone();
            mesh.uvs = vec![Vec2::ZERO, Vec2::X, Vec2::Y];
            mesh.diffuse_map = Some(flat_map([255, 255, 255]));
            mesh.surface_maps = maps;
            scene(5, Vec3::splat(0.5), Vec::new(), vec![object(Arc::new(mesh), Some(ShadingMode::Phong))])
        };
        render_truth(&s).pixel(2, 2)
    };
    let (full, half) = (dark(None), dark(Some((flat_map([0, 0, 0]), 0.5))));
    check_close(half, full * 0.5, 1e-12);
}

/// Random small maps (1 to 8 texels a side, bilinear or trilinear), each
/// present in half the cases, occlusion strength in [0, 1].
fn surface_maps() -> impl Strategy<Value = SurfaceMaps> {
    (
        prop::option::of(texture_map()),
        prop::option::of((texture_map(), 0.0f32..=1.0)),
        prop::option::of(texture_map()),
    )
        .prop_map(|(metallic_roughness, occlusion, emission)| SurfaceMaps {
            metallic_roughness,
            occlusion,
            emission,
        })
}

/// `versus_fast`'s random opaque objects with Cook–Torrance materials
/// and random maps (read where the object is textured and lit per
/// sample).
fn mapped_object() -> impl Strategy<Value = Object> {
    (opaque_object_of(cook_torrance_material()), surface_maps()).prop_map(|(mut object, maps)| {
        let mut mesh = (*object.mesh).clone();
        mesh.surface_maps = maps;
        object.mesh = Arc::new(mesh);
        object
    })
}

prop_compose! {
    /// One to three mapped objects, Phong the scene's mode in three cases
    /// of four, ambient light up to 0.4 (so that occlusion shows).
    fn mapped_scene()(
        camera in camera(),
        objects in prop::collection::vec(mapped_object(), 1..=3),
        lights in prop::collection::vec(light(), 1..=3),
        ambient in color(),
        background in color(),
        shading in prop_oneof![3 => Just(ShadingMode::Phong), 1 => prop::sample::select(ShadingMode::ALL.to_vec())],
        linear in any::<bool>(),
    ) -> Scene {
        let interpolation = if linear { Interpolation::ScreenLinear } else { Interpolation::PerspectiveCorrect };
        Scene {
            environment: None,
            shadows: Default::default(),
            camera,
            background,
            ambient: ambient * 0.4,
            lights,
            objects,
            settings: RenderSettings { width: SIZE, height: SIZE, shading, interpolation, ..RenderSettings::default() },
            fog: None,
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    /// The fast renderer within `versus_fast`'s bound of the truth on
    /// Cook–Torrance scenes with maps.
    #[test]
    fn mapped_cook_torrance_is_within_the_bound_of_the_truth(scene in mapped_scene()) {
        let (compared, exact) =
            compare_skipping(&scene, &[], SplitSum::ZlineTable).map_err(TestCaseError::fail)?;
        let allowed = ((1.0 - EXACT_SHARE) * compared as f64).max(2.0);
        prop_assert!((compared - exact) as f64 <= allowed, "{} of {compared} compared pixels inexact", compared - exact);
    }
}

/// The repository's scene `tests/scenes/cook_torrance.toml` (GGX and
/// Beckmann spheres, a box with metallic–roughness, occlusion and
/// emissive maps; a point and a directional light, ambient 0.5) rendered
/// by both, the truth with zline's split-sum table: every compared pixel
/// (one pixel or more from an edge or a lighting switch) within
/// `versus_fast`'s bound, and at least `versus_fast`'s share of them
/// exact. The bound is the property tests' own: the scene has nothing
/// they do not (its spheres are Phong-shaded meshes, its maps bilinear
/// textures), so the same f32 rounding budget applies.
#[test]
fn the_cook_torrance_scene_is_within_the_bound_of_the_truth() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/scenes/cook_torrance.toml");
    let scene = zline_io::load_scene_with_options(&path, zline_io::LoadOptions { allow_outside: true })
        .expect("the scene loads");
    assert!(scene.objects.iter().any(|o| o.mesh.surface_maps.occlusion.is_some()), "the box has its maps");
    let (compared, exact) = compare_skipping(&scene, &[], SplitSum::ZlineTable).unwrap();
    let share = exact as f64 / compared as f64;
    eprintln!("cook_torrance.toml: {exact} of {compared} compared pixels exact ({:.3} %)", 100.0 * share);
    assert!(compared > 20_000, "{compared}");
    assert!(share >= EXACT_SHARE, "{share}");
}
