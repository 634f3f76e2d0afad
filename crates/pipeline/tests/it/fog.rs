//! Fog (SPEC §8) on a square at a known distance: pixel colours computed
//! here from the formulas, for each mode and fog coordinate.

use glam::{DVec3, Vec3};
use zline_scene::{Fog, FogCoordinate, FogMode, Projection};
use zline_shading::Material;

use crate::support::{draw, object, quantize_robust, scene, square};

const SIZE: u32 = 65;
const SURFACE: [f64; 3] = [0.91, 0.33, 0.12];
const FOG: [f64; 3] = [0.52, 0.61, 0.74];

fn fogged(f: f64) -> DVec3 {
    let f = f.clamp(0.0, 1.0);
    DVec3::from_array(SURFACE) * f + DVec3::from_array(FOG) * (1.0 - f)
}

/// A large unlit square at z = `z` (colour = ka·Ia = SURFACE) seen through
/// fog from the origin camera.
fn render(
    mode: FogMode,
    coordinate: FogCoordinate,
    z: f32,
    projection: Option<Projection>,
) -> zline_pipeline::Image {
    let m = Material {
        ka: Vec3::from_array(SURFACE.map(|v| v as f32)),
        kd: Vec3::ZERO,
        ks: Vec3::ZERO,
        ns: 1.0,
        opacity: 1.0,
        ..Material::default()
    };
    let mut s = scene(SIZE, Vec3::ONE, vec![], vec![object(square(0.0, 0.0, 0.9 * -z, z, m), None)]);
    s.camera = crate::support::origin_camera(1.0, 100.0);
    if let Some(p) = projection {
        s.camera.projection = p;
    }
    s.fog = Some(Fog { mode, color: Vec3::from_array(FOG.map(|v| v as f32)), coordinate });
    draw(&s)
}

#[test]
fn linear_fog_halfway_between_start_and_end() {
    let image = render(FogMode::Linear { start: 10.0, end: 30.0 }, FogCoordinate::EyePlane, -20.0, None);
    assert_eq!(image.pixel(32, 32), quantize_robust(fogged(0.5)));
    // Off-centre pixels share the eye-plane distance.
    assert_eq!(image.pixel(22, 40), quantize_robust(fogged(0.5)));
}

#[test]
fn linear_fog_clamps_before_start_and_after_end() {
    let near = render(FogMode::Linear { start: 10.0, end: 30.0 }, FogCoordinate::EyePlane, -5.0, None);
    assert_eq!(near.pixel(32, 32), quantize_robust(fogged(1.0)));
    let far = render(FogMode::Linear { start: 10.0, end: 30.0 }, FogCoordinate::EyePlane, -40.0, None);
    assert_eq!(far.pixel(32, 32), quantize_robust(fogged(0.0)));
}

#[test]
fn exponential_fogs() {
    let e = render(FogMode::Exponential { density: 0.05 }, FogCoordinate::EyePlane, -20.0, None);
    assert_eq!(e.pixel(32, 32), quantize_robust(fogged((-1.0f64).exp())));
    let e2 = render(FogMode::SquaredExponential { density: 0.04 }, FogCoordinate::EyePlane, -20.0, None);
    assert_eq!(e2.pixel(32, 32), quantize_robust(fogged((-(0.8f64 * 0.8)).exp())));
}

#[test]
fn radial_distance_grows_off_axis() {
    // Pixel (12, 32): NC x = (12.5/65)·2 − 1, on the plane z = −20 the eye
    // point is (x_nc·20, 0, −20) (fovy 90°), at distance 20·√(1 + x_nc²).
    let x_nc = 12.5 / 65.0 * 2.0 - 1.0;
    let d = 20.0 * (1.0f64 + x_nc * x_nc).sqrt();
    let radial = render(FogMode::Linear { start: 10.0, end: 30.0 }, FogCoordinate::Radial, -20.0, None);
    assert_eq!(radial.pixel(12, 32), quantize_robust(fogged((30.0 - d) / 20.0)));
    assert_eq!(radial.pixel(32, 32), quantize_robust(fogged(0.5)));
}

#[test]
fn orthographic_fog_uses_the_eye_plane_distance() {
    let ortho = Projection::Orthographic { height: 4.0, near: 1.0, far: 100.0 };
    let image =
        render(FogMode::Linear { start: 0.0, end: 40.0 }, FogCoordinate::EyePlane, -30.0, Some(ortho));
    assert_eq!(image.pixel(32, 32), quantize_robust(fogged(0.25)));
}

#[test]
fn the_background_is_not_fogged() {
    let mut s =
        scene(SIZE, Vec3::ONE, vec![], vec![object(square(0.0, 0.0, 0.5, -2.0, Material::DEFAULT), None)]);
    s.background = Vec3::new(0.2, 0.4, 0.6);
    s.fog = Some(Fog {
        mode: FogMode::Exponential { density: 5.0 },
        color: Vec3::ONE,
        coordinate: FogCoordinate::EyePlane,
    });
    let image = draw(&s);
    assert_eq!(image.pixel(0, 0), [51, 102, 153]);
    assert_eq!(image.pixel(32, 32), [255, 255, 255], "e^(−10) leaves the fog colour");
}
