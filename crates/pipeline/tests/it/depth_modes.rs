//! The depth buffer's two encodings (`RenderSettings::depth`): the seed's NC
//! depth and reversed depth in floating point.

use glam::Vec3;
use zline_scene::{DepthMode, Scene};
use zline_shading::{Material, ShadingMode};

use crate::support::{draw, mesh, object, origin_camera, scene, wavy_grid};

#[test]
fn both_encodings_draw_an_ordinary_scene_alike() {
    // Surfaces here are far apart compared with either encoding's precision,
    // so the same fragments win and the images match byte for byte.
    let lights = vec![zline_shading::Light::Directional { direction: Vec3::NEG_Z, color: Vec3::ONE }];
    for mode in ShadingMode::ALL {
        let objects = vec![object(wavy_grid(30, -3.0), Some(mode)), object(wavy_grid(20, -3.4), Some(mode))];
        let mut s = scene(90, Vec3::splat(0.2), lights.clone(), objects);
        let normalized = draw(&s);
        s.settings.depth = DepthMode::ReversedFloat;
        assert!(draw(&s) == normalized, "{mode:?}");
    }
}

/// Two parallel squares facing the camera, `gap` apart around depth
/// `distance`: the far one red and drawn first... or second.
fn parallel_planes(distance: f32, gap: f32, near_first: bool, depth: DepthMode) -> Scene {
    let plane = |z: f32, color: Vec3| {
        let h = distance; // fills the 90° view
        let p = [(-h, -h), (h, -h), (h, h), (-h, h)].map(|(x, y)| Vec3::new(x, y, z)).to_vec();
        let material = Material { ka: color, kd: Vec3::ZERO, ks: Vec3::ZERO, ..Material::DEFAULT };
        object(mesh(p, vec![Vec3::Z; 4], vec![[0, 1, 2], [0, 2, 3]], material), Some(ShadingMode::Flat))
    };
    let far = plane(-distance, Vec3::X);
    let near = plane(-distance + gap, Vec3::Y);
    let objects = if near_first { vec![near, far] } else { vec![far, near] };
    let mut s = scene(128, Vec3::ONE, Vec::new(), objects);
    s.camera = origin_camera(0.1, 10_000.0);
    s.settings.depth = depth;
    s
}

/// The share of pixels showing the far (red) plane instead of the near one.
fn wrong_share(s: &Scene) -> f64 {
    let image = draw(s);
    let (w, h) = (image.width, image.height);
    let wrong = (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).filter(|&(x, y)| image.pixel(x, y)[0] > 0);
    wrong.count() as f64 / f64::from(w * h)
}

/// Hard case: planes 10⁻⁴ apart at distance 1000 (near 0.1, far 10⁴). In
/// NC depth they differ by 2n·gap/d² ≈ 2·10⁻¹¹ near z = 1, where f32
/// steps by 6·10⁻⁸: every sample ties, so whichever plane is drawn first
/// wins everywhere. Reversed depth stores ≈ n/d ≈ 10⁻⁴ with steps of
/// 7·10⁻¹²; the planes differ by n·gap/d² = 10⁻¹¹, about 1.4 steps, so
/// after the single f32 rounding the nearer plane must win at every
/// sample: rounding is monotonic, and values more than one step apart
/// cannot round to the same float. (In f32 the near plane's z is
/// −999.99988, so the gap as stored is 1.2·10⁻⁴.)
#[test]
fn parallel_planes_a_ten_thousandth_apart_at_distance_1000() {
    for near_first in [false, true] {
        let nc = wrong_share(&parallel_planes(1000.0, 1e-4, near_first, DepthMode::Normalized));
        let reversed = wrong_share(&parallel_planes(1000.0, 1e-4, near_first, DepthMode::ReversedFloat));
        eprintln!("near first {near_first}: wrong order NC {nc:.4}, reversed {reversed:.4}");
        // NC depth cannot tell the planes apart: the first drawn wins
        // (strictly-less test), so it is all wrong when the far one is first.
        assert_eq!(nc, if near_first { 0.0 } else { 1.0 }, "NC depth, near first: {near_first}");
        assert_eq!(reversed, 0.0, "reversed depth, near first: {near_first}");
    }
}
