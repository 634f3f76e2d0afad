//! Patches after a solve: subdivision where radiosity changes fast (the
//! cut, the marks, a solve replayed from its cuts) and the display of a
//! textured surface.

use std::sync::Arc;

use glam::{Mat4, Vec3};
use zline_radiosity::subdivide::{marks, split};
use zline_radiosity::{mesh, replay, solve, Method, Options};
use zline_scene::{Camera, Mesh, Object, Projection, RenderSettings, Scene};
use zline_shading::{Light, Material};

/// The square |x|, |z| ≤ 1 at y = 0 facing +y, ρ = 0.5, under `lights`.
fn floor(lights: Vec<Light>) -> Scene {
    let p = vec![
        Vec3::new(-1.0, 0.0, -1.0),
        Vec3::new(-1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, -1.0),
    ];
    let material = Material { ka: Vec3::ZERO, kd: Vec3::splat(0.5), ks: Vec3::ZERO, ..Material::DEFAULT };
    let object = Object {
        mesh: Arc::new(Mesh::new("floor", p, None, vec![[0, 1, 2], [0, 2, 3]], material).unwrap()),
        world_from_object: Mat4::IDENTITY,
        material: None,
        shading: None,
        cull_back_faces: false,
    };
    Scene {
        environment: None,
        shadows: Default::default(),
        camera: Camera {
            eye: Vec3::new(0.0, 3.0, 0.1),
            target: Vec3::ZERO,
            up: Vec3::Y,
            projection: Projection::Perspective { fovy_degrees: 60.0, near: 0.01, far: 100.0 },
        },
        background: Vec3::ZERO,
        ambient: Vec3::ZERO,
        lights,
        objects: vec![object],
        settings: RenderSettings { width: 8, height: 8, ..RenderSettings::default() },
        fog: None,
    }
}

#[test]
fn a_cut_keeps_the_area_and_neighbours_share_their_midpoints() {
    let (patches, _) =
        mesh(&floor(Vec::new()), &Options { patch_size: Some(4.0), ..Options::default() }).unwrap();
    // The two triangles of the square, sharing the diagonal.
    assert_eq!((patches.patches.len(), patches.vertices.len()), (2, 4));
    let area = |p: &zline_radiosity::Patches| p.patches.iter().map(|p| p.area).sum::<f32>();
    let both = split(&patches, &[0, 1]);
    assert_eq!(both.patches.len(), 8);
    // Four corners, four edge midpoints, one on the diagonal they share.
    assert_eq!(both.vertices.len(), 9);
    assert!((area(&both) - area(&patches)).abs() < 1e-6);
    let one = split(&patches, &[1]);
    assert_eq!((one.patches.len(), one.vertices.len()), (5, 7));
    assert_eq!(one.patches[0], patches.patches[0], "an uncut patch keeps its place");
    for child in &one.patches[1..] {
        assert_eq!((child.reflectance, child.emission, child.triangle), (Vec3::splat(0.5), Vec3::ZERO, 1));
        assert_eq!(child.normal, patches.patches[1].normal);
        for (v, c) in child.vertices.iter().zip(&child.corners) {
            assert_eq!(one.vertices[*v as usize], *c);
        }
    }
}

#[test]
fn patches_are_cut_where_radiosity_steps_and_nowhere_else() {
    let (patches, _) =
        mesh(&floor(Vec::new()), &Options { patch_size: Some(0.25), ..Options::default() }).unwrap();
    // A step at x = 0: bright on the left, dark on the right.
    let b: Vec<Vec3> =
        patches.patches.iter().map(|p| if p.centre.x < 0.0 { Vec3::ONE } else { Vec3::splat(0.5) }).collect();
    let cut = marks(&patches, &b);
    assert!(!cut.is_empty());
    for (i, p) in patches.patches.iter().enumerate() {
        let on_step = p.corners.iter().any(|c| c.x.abs() < 1e-6);
        assert_eq!(cut.contains(&(i as u32)), on_step, "patch at {:?}", p.centre);
    }
    // A spread below the threshold (1/16 of the bright level): no cut.
    let smooth: Vec<Vec3> = patches.patches.iter().map(|p| Vec3::splat(1.0 + 0.05 * p.centre.x)).collect();
    assert!(marks(&patches, &smooth).is_empty());
}

#[test]
fn a_subdivided_solve_keeps_the_balance_and_replays_from_its_cuts() {
    // A spot's cone edge across the floor: the radiosity steps there.
    let spot = Light::Spot {
        position: Vec3::new(0.0, 1.0, 0.0),
        direction: Vec3::NEG_Y,
        color: Vec3::ONE,
        attenuation: zline_shading::Attenuation::NONE,
        cone: zline_shading::Cone { inner: 0.5, outer: 0.52 },
    };
    let scene = floor(vec![spot]);
    // Tolerance 0: every patch shoots, no ambient term is left.
    let options = Options {
        patch_size: Some(0.25),
        subdivide: 2,
        method: Method::Progressive,
        tolerance: 0.0,
        ..Options::default()
    };
    let solution = solve(&scene, &options).unwrap();
    assert_eq!(solution.splits.len(), 2, "two levels cut");
    let (uniform, _) = mesh(&scene, &options).unwrap();
    assert!(solution.patches.patches.len() > uniform.patches.len());
    // A lone floor reflects nothing onto itself: B = D on every patch.
    for (p, b) in solution.patches.patches.iter().zip(&solution.radiosity) {
        assert_eq!(*b, p.direct, "at {:?}", p.centre);
    }
    let replayed = replay(&scene, uniform.clone(), &solution.splits, &options).expect("the cuts fit");
    assert_eq!(replayed.patches, solution.patches.patches);
    assert_eq!(replayed.vertices, solution.patches.vertices);
    // Cuts that name patches not there: refused.
    assert!(replay(&scene, uniform, &[vec![u32::MAX]], &options).is_none());
}

/// The floor with a 2 × 2 texture of texels `a` and `b` (a checker).
fn textured_floor(lights: Vec<Light>, a: u8, b: u8) -> Scene {
    let mut scene = floor(lights);
    let texels = [a, a, a, 255, b, b, b, 255, b, b, b, 255, a, a, a, 255];
    let texture = zline_shading::Texture::from_rgba8(2, 2, &texels).unwrap();
    let map = zline_scene::TextureMap {
        texture: Arc::new(texture),
        sampler: zline_shading::Sampler::default(),
        alpha_blend: false,
        alpha_cutoff: None,
    };
    let uvs = vec![
        glam::Vec2::new(0.0, 0.0),
        glam::Vec2::new(0.0, 1.0),
        glam::Vec2::new(1.0, 1.0),
        glam::Vec2::new(1.0, 0.0),
    ];
    let mesh = (*scene.objects[0].mesh).clone().with_uvs(uvs).unwrap().with_diffuse_map(map);
    scene.objects[0].mesh = Arc::new(mesh);
    scene
}

#[test]
fn a_textured_surface_shows_its_texture_lit_by_what_it_received() {
    let light = Light::Directional { direction: Vec3::new(0.3, -1.0, 0.2), color: Vec3::ONE };
    let options = Options { patch_size: Some(0.5), tolerance: 0.0, ..Options::default() };
    // An even texture: the display's vertex colours times the texel are
    // the corners' radiosities, as for an untextured surface.
    let even = textured_floor(vec![light], 128, 128);
    let solution = solve(&even, &options).unwrap();
    let shown = solution.display_scene_scaled(&even, 1.0);
    assert_eq!(shown.objects.len(), 1);
    let mesh = &shown.objects[0].mesh;
    assert!(mesh.diffuse_map.is_some() && mesh.uvs.len() == mesh.positions.len());
    let texel = 128.0f32 / 255.0;
    let expected = solution.vertex_radiosity();
    for (position, color) in mesh.positions.iter().zip(&mesh.colors) {
        let v = solution.patches.vertices.iter().position(|p| p == position).unwrap();
        let got = *color * texel;
        assert!(
            (got - expected[v]).abs().max_element() <= 1e-5 * expected[v].max_element(),
            "{got} against {}",
            expected[v]
        );
    }
    // A checker with the same mean: the same solve, the texture's detail
    // on top (the colours are the same, the texels differ).
    let checker = textured_floor(vec![light], 64, 192);
    let other = solve(&checker, &options).unwrap();
    let reflectance =
        |s: &zline_radiosity::Solution| s.patches.patches.iter().map(|p| p.reflectance.x).sum::<f32>();
    assert!((reflectance(&solution) - reflectance(&other)).abs() < 1e-3 * reflectance(&solution));
}
