//! `cargo xtask docs-images`: the texture-mapping pictures of the docs — a
//! checkerboard floor receding to the horizon, rendered with
//! perspective-correct and affine mapping, and with nearest and trilinear
//! filtering.

use std::path::Path;
use std::sync::Arc;

use anyhow::{Context, Result};
use glam::{Mat4, Vec2, Vec3};
use zline::pipeline::{render, RenderOptions};
use zline::scene::{
    Camera, Interpolation, Mesh, Object, Projection, RenderSettings, Scene, ShadingMode, TextureMap,
};
use zline::shading::{Filter, Material, Sampler, Texture, Wrap};

/// Texels per checker cell and cells per texture side.
const CELL: u32 = 8;
const CELLS: u32 = 8;

/// A black-and-white checkerboard, CELLS × CELLS cells of CELL texels.
pub(crate) fn checker() -> Result<Texture> {
    let side = CELL * CELLS;
    let mut rgba = Vec::with_capacity((side * side * 4) as usize);
    for y in 0..side {
        for x in 0..side {
            let v = if (x / CELL + y / CELL).is_multiple_of(2) { 235 } else { 20 };
            rgba.extend([v, v, v, 255]);
        }
    }
    Ok(Texture::from_rgba8(side, side, &rgba)?)
}

/// One quad (two triangles) at y = −1 from z = −0.5 to z = `far`, 2·`half`
/// wide, one checker cell per world unit.
pub(crate) fn floor(texture: Arc<Texture>, filter: Filter, far: f32, half: f32) -> Result<Mesh> {
    let near = -0.5f32;
    let positions = vec![
        Vec3::new(-half, -1.0, near),
        Vec3::new(half, -1.0, near),
        Vec3::new(half, -1.0, far),
        Vec3::new(-half, -1.0, far),
    ];
    let repeat = CELLS as f32;
    let uvs = positions.iter().map(|p| Vec2::new(p.x / repeat, -p.z / repeat)).collect();
    let unlit = Material {
        ka: Vec3::ONE,
        kd: Vec3::ZERO,
        ks: Vec3::ZERO,
        ns: 1.0,
        opacity: 1.0,
        ..Material::default()
    };
    let mesh = Mesh::new("floor", positions, None, vec![[0, 1, 2], [0, 2, 3]], unlit)?.with_uvs(uvs)?;
    let sampler = Sampler { filter, wrap_s: Wrap::Repeat, wrap_t: Wrap::Repeat };
    Ok(mesh.with_diffuse_map(TextureMap { texture, sampler, alpha_blend: false, alpha_cutoff: None }))
}

pub(crate) fn scene(mesh: Mesh, interpolation: Interpolation) -> Scene {
    Scene {
        environment: None,
        shadows: Default::default(),
        camera: Camera {
            eye: Vec3::new(0.0, 0.0, 0.0),
            target: Vec3::new(0.0, -0.25, -4.0),
            up: Vec3::Y,
            projection: Projection::Perspective { fovy_degrees: 60.0, near: 0.1, far: 500.0 },
        },
        background: Vec3::new(0.55, 0.65, 0.8),
        ambient: Vec3::ONE,
        lights: Vec::new(),
        objects: vec![Object {
            mesh: Arc::new(mesh),
            world_from_object: Mat4::IDENTITY,
            material: None,
            shading: Some(ShadingMode::Flat),
            cull_back_faces: false,
        }],
        settings: RenderSettings {
            width: 480,
            height: 270,
            shading: ShadingMode::Flat,
            interpolation,
            texture_filter: None,
            ..RenderSettings::default()
        },
        fog: None,
    }
}

pub(crate) fn run(out: &Path) -> Result<()> {
    std::fs::create_dir_all(out).with_context(|| format!("{}: cannot create", out.display()))?;
    let texture = Arc::new(checker()?);
    // A short floor shows the mapping (affine bends the rows and breaks at
    // the diagonal); a floor to the horizon shows the filtering.
    let (short, horizon) = ((-12.0, 6.0), (-400.0, 200.0));
    let cases = [
        ("checker-perspective.png", Interpolation::PerspectiveCorrect, Filter::Trilinear, short),
        ("checker-affine.png", Interpolation::ScreenLinear, Filter::Trilinear, short),
        ("checker-horizon-trilinear.png", Interpolation::PerspectiveCorrect, Filter::Trilinear, horizon),
        ("checker-horizon-nearest.png", Interpolation::PerspectiveCorrect, Filter::Nearest, horizon),
    ];
    for (name, interpolation, filter, (far, half)) in cases {
        let s = scene(floor(texture.clone(), filter, far, half)?, interpolation);
        let (image, _) = render(&s, &RenderOptions::default());
        let path = out.join(name);
        zline::save_png(&image, &path).with_context(|| format!("{}: cannot write", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
