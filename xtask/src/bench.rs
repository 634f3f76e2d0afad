//! `cargo xtask bench`: median ms/frame, triangles/s and shaded samples/s at
//! 1920×1080 for the benchmark scenes of BENCHMARKS.md.

use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result};
use std::sync::Arc;

use glam::{Mat4, Vec3};
use zline::io::{default_lights, load_obj, scene_for_model, DEFAULT_AMBIENT, DEFAULT_BACKGROUND};
use zline::pipeline::{Image, RenderOptions, RenderStats, Renderer};
use zline::scene::{uv_sphere, Camera, Object, Projection, RenderSettings, Scene, ShadingMode};

const WIDTH: u32 = 1920;
const HEIGHT: u32 = 1080;

/// One benchmark case: a label and how to build its scene (built only
/// when the case is selected).
pub(crate) struct Case {
    pub(crate) name: String,
    pub(crate) build: Box<dyn Fn() -> Result<Scene>>,
}

/// Times each selected case at each thread count: `frames` warm frames,
/// the bands cut into `pieces` (`None`: as the thread count chooses).
pub(crate) fn run(
    (frames, pieces): (usize, Option<usize>),
    threads: &[usize],
    assets: &Path,
    filter: Option<&str>,
    options: &RenderOptions,
) -> Result<()> {
    let cases: Vec<Case> =
        cases(assets)?.into_iter().filter(|c| filter.is_none_or(|f| c.name.contains(f))).collect();
    println!(
        "| scene | threads | ms/frame (median of {frames}) | geometry ms | binning ms | raster ms | triangles/s | shaded samples/s | samples shaded | skipped by hierarchical depth |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for case in &cases {
        let scene = (case.build)()?;
        for &t in threads {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(t).build().context("thread pool")?;
            let runs = time_frames(&scene, (&pool, pieces), options, frames);
            let (median, stats) = runs[runs.len() / 2];
            let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
            println!(
                "| {} | {t} | {:.2} | {:.2} | {:.2} | {:.2} | {:.1} M | {:.0} M | {} | {} |",
                case.name,
                median * 1e3,
                ms(stats.geometry),
                ms(stats.binning),
                ms(stats.raster),
                stats.triangles as f64 / median / 1e6,
                stats.fragments as f64 / median / 1e6,
                stats.fragments,
                stats.hidden
            );
        }
    }
    Ok(())
}

/// `frames` (at least one) warm frames of `scene` drawn in `pool` by one
/// renderer after one warm-up frame, its bands cut into `pieces` (`None`:
/// as the pool's threads choose): each frame's seconds and statistics,
/// fastest first.
pub(crate) fn time_frames(
    scene: &Scene,
    (pool, pieces): (&rayon::ThreadPool, Option<usize>),
    options: &RenderOptions,
    frames: usize,
) -> Vec<(f64, RenderStats)> {
    let mut runs = Vec::new();
    each_frame(scene, (pool, pieces), options, frames, |seconds, stats, _| runs.push((seconds, stats)));
    runs.sort_by(|a, b| a.0.total_cmp(&b.0));
    runs
}

/// Draws [`time_frames`]' frames and calls `f` after each with its seconds,
/// its statistics and the renderer (whose `unit_times` are that frame's).
pub(crate) fn each_frame(
    scene: &Scene,
    (pool, pieces): (&rayon::ThreadPool, Option<usize>),
    options: &RenderOptions,
    frames: usize,
    mut f: impl FnMut(f64, RenderStats, &Renderer),
) {
    let mut renderer = Renderer::default();
    renderer.set_band_pieces(pieces);
    let mut image = Image::empty();
    pool.install(|| renderer.render_into(scene, options, &mut image)); // warm-up
    for _ in 0..frames.max(1) {
        let start = Instant::now();
        let stats = pool.install(|| renderer.render_into(scene, options, &mut image));
        f(start.elapsed().as_secs_f64(), stats, &renderer);
    }
}

fn settings(shading: ShadingMode) -> RenderSettings {
    RenderSettings { width: WIDTH, height: HEIGHT, shading, ..RenderSettings::default() }
}

/// A UV sphere of radius 1 seen from `distance` with a 40° field of view,
/// lit by the default key and fill lights.
pub(crate) fn sphere_scene(rings: u32, segments: u32, distance: f32, shading: ShadingMode) -> Scene {
    // Built directly rather than through `scene_for_model`: the sphere is
    // known to be closed, and checking that on a million triangles would
    // dominate the benchmark's start-up.
    Scene {
        environment: None,
        shadows: Default::default(),
        camera: Camera {
            eye: Vec3::new(0.0, 0.0, distance),
            target: Vec3::ZERO,
            up: Vec3::Y,
            projection: Projection::Perspective {
                fovy_degrees: 40.0,
                near: distance - 1.5,
                far: distance + 1.5,
            },
        },
        background: DEFAULT_BACKGROUND,
        ambient: DEFAULT_AMBIENT,
        lights: default_lights(),
        objects: vec![Object {
            mesh: Arc::new(uv_sphere(rings, segments, 1.0)),
            world_from_object: Mat4::IDENTITY,
            material: None,
            shading: None,
            cull_back_faces: true,
        }],
        settings: settings(shading),
        fog: None,
    }
}

/// `assets/bump/sphere.obj` framed at 1920×1080 with Phong shading:
/// without its bump map (`None`), with it (`Some(false)`), or with its
/// image read as a tangent-space normal map (`Some(true)`).
fn bump_sphere(normal: Option<bool>) -> Result<Scene> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/bump/sphere.obj");
    let mut meshes = load_obj(&path)?;
    for mesh in &mut meshes {
        match normal {
            None => mesh.normal_map = None,
            Some(false) => {}
            Some(true) => {
                if let Some(map) = &mut mesh.normal_map {
                    map.encoding = zline::scene::NormalEncoding::Tangent;
                    map.scale = 1.0;
                }
            }
        }
    }
    let mut scene = scene_for_model(meshes, settings(ShadingMode::Phong));
    if let zline::scene::Projection::Perspective { fovy_degrees, .. } = &mut scene.camera.projection {
        *fovy_degrees *= 0.6;
    }
    Ok(scene)
}

/// The checkerboard floor at 1920×1080 with fog, optionally with two
/// overlapping 2k spheres (the front one transparent) standing on it.
pub(crate) fn textured_plane(spheres: bool) -> Result<Scene> {
    use zline::scene::{Fog, FogCoordinate, FogMode, Interpolation, Material};
    use zline::shading::Filter;
    let floor = crate::docs::floor(Arc::new(crate::docs::checker()?), Filter::Trilinear, -400.0, 200.0)?;
    let mut scene = crate::docs::scene(floor, Interpolation::PerspectiveCorrect);
    scene.settings.width = WIDTH;
    scene.settings.height = HEIGHT;
    scene.fog = Some(Fog {
        mode: FogMode::Linear { start: 5.0, end: 60.0 },
        color: scene.background,
        coordinate: FogCoordinate::EyePlane,
    });
    if spheres {
        scene.lights = default_lights();
        scene.ambient = DEFAULT_AMBIENT;
        let sphere = Arc::new(uv_sphere(32, 32, 0.45));
        for (x, opacity) in [(-0.25, 1.0), (0.25, 0.5)] {
            let z = if opacity < 1.0 { -2.6 } else { -3.2 };
            scene.objects.push(Object {
                mesh: sphere.clone(),
                world_from_object: Mat4::from_translation(Vec3::new(x, -0.55, z)),
                material: Some(Material {
                    opacity,
                    ..Material::plastic(Vec3::new(0.8, 0.3, 0.2), 0.5, 32.0)
                }),
                shading: Some(ShadingMode::Phong),
                cull_back_faces: opacity >= 1.0,
            });
        }
    }
    Ok(scene)
}

/// The Stanford bunny under the shared asset folder, when it is there.
pub(crate) fn bunny(assets: &Path) -> Option<std::path::PathBuf> {
    Some(assets.join("obj/bunny/bunny.obj")).filter(|p| p.exists())
}

/// The painter's algorithm on the bunny and the transparent spheres, and
/// lines (every edge, and feature edges, hidden ones dashed) over the bunny.
fn visibility_cases(assets: &Path, out: &mut Vec<Case>) {
    use zline::scene::{Visibility, Wireframe, WireframeMode};
    let with = |scene: Result<Scene>, visibility: Visibility, wireframe: Wireframe| {
        let mut scene = scene?;
        scene.settings.visibility = visibility;
        scene.settings.wireframe = wireframe;
        Ok(scene)
    };
    let dashed = |feature_angle| Wireframe { mode: WireframeMode::HiddenDashed, only: false, feature_angle };
    if let Some(bunny) = bunny(assets) {
        let load = move || Ok(scene_for_model(load_obj(&bunny)?, settings(ShadingMode::Phong)));
        let variants = [
            ("painter", Visibility::Painter, Wireframe::default()),
            ("+ lines hidden-dashed", Visibility::ZBuffer, dashed(None)),
            ("+ feature lines 40°", Visibility::ZBuffer, dashed(Some(40.0))),
        ];
        for (name, visibility, wireframe) in variants {
            let load = load.clone();
            out.push(Case {
                name: format!("bunny 69k phong {name}"),
                build: Box::new(move || with(load(), visibility, wireframe)),
            });
        }
    }
    out.push(Case {
        name: "transparent spheres painter".into(),
        build: Box::new(move || with(textured_plane(true), Visibility::Painter, Wireframe::default())),
    });
}

pub(crate) fn cases(assets: &Path) -> Result<Vec<Case>> {
    let mut out = Vec::new();
    if let Some(bunny) = bunny(assets) {
        for mode in [ShadingMode::Gouraud, ShadingMode::Phong] {
            let path = bunny.clone();
            let build = move || Ok(scene_for_model(load_obj(&path)?, settings(mode)));
            out.push(Case { name: format!("bunny 69k {}", mode.name()), build: Box::new(build) });
        }
    } else {
        eprintln!(
            "note: no obj/bunny/bunny.obj under {}; skipping the bunny (pass --assets)",
            assets.display()
        );
    }
    // 32 rings × 32 segments ≈ 2k triangles; at distance 2.6 the sphere covers about half the frame.
    for mode in [ShadingMode::Gouraud, ShadingMode::Phong] {
        out.push(Case {
            name: format!("sphere 2k {}", mode.name()),
            build: Box::new(move || Ok(sphere_scene(32, 32, 2.6, mode))),
        });
    }
    // SPEC §7–9 scenes: the docs' checkerboard floor to the horizon with
    // trilinear filtering and linear fog; two overlapping spheres, the front
    // one transparent, over that floor.
    out.push(Case { name: "plane textured + fog".into(), build: Box::new(|| textured_plane(false)) });
    out.push(Case { name: "transparent spheres".into(), build: Box::new(|| textured_plane(true)) });
    // The same with the floor receiving planar shadows from both spheres
    // (two default lights): the cost of the shadow mode.
    out.push(Case {
        name: "transparent spheres + planar shadows".into(),
        build: Box::new(|| {
            let mut scene = textured_plane(true)?;
            let floor =
                zline::scene::ShadowPlane::of_object(0, &scene.objects[0]).context("the floor is flat")?;
            scene.shadows = zline::scene::Shadows {
                mode: zline::scene::ShadowMode::Planar,
                planes: vec![floor],
                ..Default::default()
            };
            Ok(scene)
        }),
    });
    // And with shadow maps (every surface receives and casts; 1024², PCF).
    out.push(Case {
        name: "transparent spheres + shadow maps".into(),
        build: Box::new(|| {
            let mut scene = textured_plane(true)?;
            scene.shadows =
                zline::scene::Shadows { mode: zline::scene::ShadowMode::Map, ..Default::default() };
            Ok(scene)
        }),
    });
    // Bump and normal maps: the repository's 16 × 32 OBJ sphere (960
    // triangles) filling the frame, without its map, with its height map
    // (four reads per sample) and with that image read as a normal map (one).
    for (label, map) in [("no map", None), ("bump map", Some(false)), ("normal map", Some(true))] {
        out.push(Case {
            name: format!("obj sphere phong, {label}"),
            build: Box::new(move || bump_sphere(map)),
        });
    }
    // The painter's algorithm and lines (issue 12): the same scenes drawn
    // another way.
    visibility_cases(assets, &mut out);
    // 500 × 1000 ≈ 1M triangles.
    for mode in [ShadingMode::Gouraud, ShadingMode::Phong] {
        out.push(Case {
            name: format!("sphere 1M {}", mode.name()),
            build: Box::new(move || Ok(sphere_scene(500, 1000, 2.6, mode))),
        });
    }
    // Hidden work: the same sphere with a wall drawn before it, in front of
    // its left half (its triangles there fail the depth test in every
    // sample: the tiles' coarse depth skips them whole).
    out.push(Case {
        name: "sphere 1M gouraud, half behind a wall".into(),
        build: Box::new(|| {
            let mut scene = sphere_scene(500, 1000, 2.6, ShadingMode::Gouraud);
            scene.objects.insert(0, wall()?);
            Ok(scene)
        }),
    });
    Ok(out)
}

/// An opaque quad facing the camera of [`sphere_scene`] at distance 2.6,
/// between it and the sphere (z = 1.2), over the left half of the view.
fn wall() -> Result<Object> {
    use zline::scene::{Material, Mesh};
    let positions = vec![
        Vec3::new(-3.0, -3.0, 1.2),
        Vec3::new(0.0, -3.0, 1.2),
        Vec3::new(0.0, 3.0, 1.2),
        Vec3::new(-3.0, 3.0, 1.2),
    ];
    let material = Material::plastic(Vec3::new(0.55, 0.5, 0.45), 0.2, 8.0);
    let mesh =
        Mesh::new("wall", positions, None, vec![[0, 1, 2], [0, 2, 3]], material).context("the wall")?;
    Ok(Object {
        mesh: Arc::new(mesh),
        world_from_object: Mat4::IDENTITY,
        material: None,
        shading: None,
        cull_back_faces: false,
    })
}
