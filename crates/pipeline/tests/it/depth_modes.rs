//! The depth buffer's two encodings (`RenderSettings::depth`): the seed's NC
//! depth and reversed depth in floating point.

use glam::Vec3;
use zline_scene::{DepthMode, Scene};
use zline_shading::ShadingMode;

use crate::support::{draw, object, scene, wavy_grid};

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

/// `hard_cases::parallel_planes`, drawn far plane first or near plane first.
fn parallel_planes(near_first: bool, depth: DepthMode) -> Scene {
    let mut s = zline_scenes::hard_cases::parallel_planes(depth);
    if near_first {
        s.objects.rotate_left(2); // the near plane's two triangles first
    }
    s
}

/// The share of pixels showing the far (red) plane instead of the near one.
fn wrong_share(s: &Scene) -> f64 {
    let image = draw(s);
    let (w, h) = (image.width, image.height);
    let wrong = (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).filter(|&(x, y)| image.pixel(x, y)[0] > 128);
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
        let nc = wrong_share(&parallel_planes(near_first, DepthMode::Normalized));
        let reversed = wrong_share(&parallel_planes(near_first, DepthMode::ReversedFloat));
        eprintln!("near first {near_first}: wrong order NC {nc:.4}, reversed {reversed:.4}");
        // NC depth cannot tell the planes apart: the first drawn wins
        // (strictly-less test), so it is all wrong when the far one is first.
        assert_eq!(nc, if near_first { 0.0 } else { 1.0 }, "NC depth, near first: {near_first}");
        assert_eq!(reversed, 0.0, "reversed depth, near first: {near_first}");
    }
}
