//! Supersampling is rendering an image n× larger and box-filtering it: the
//! same sample positions, the same texture level of detail (derivatives
//! per sample step), the same colours.

use glam::DVec3;
use zline_scene::RenderSettings;
use zline_scenes::demo_scene;
use zline_truth::render_truth;

#[test]
fn ssaa_equals_a_larger_image_box_filtered() {
    let mut small = demo_scene();
    small.settings = RenderSettings { width: 40, height: 24, ssaa: 3, ..small.settings };
    let mut large = small.clone();
    large.settings = RenderSettings { width: 120, height: 72, ssaa: 1, ..small.settings };
    let (a, b) = (render_truth(&small), render_truth(&large));
    for y in 0..24 {
        for x in 0..40 {
            let mut sum = DVec3::ZERO;
            for j in 0..3 {
                for i in 0..3 {
                    sum += b.pixel(3 * x + i, 3 * y + j);
                }
            }
            let (got, want) = (a.pixel(x, y), sum / 9.0);
            assert!((got - want).abs().max_element() < 1e-12, "pixel ({x}, {y}): {got} vs {want}");
        }
    }
}
