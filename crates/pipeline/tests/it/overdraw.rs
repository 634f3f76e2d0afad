//! The overdraw count (`zline_pipeline::render_overdraw`): stacked squares
//! counted by hand, a shared diagonal through sample centres under each tie
//! rule, and the counts against the depth image.

use glam::Vec3;
use zline_pipeline::object_ids::is_transparent;
use zline_pipeline::{render_depth, render_overdraw, Overdraw, RenderOptions};
use zline_raster::TieRule;
use zline_scene::Scene;
use zline_scenes::hard_cases::{pixel_camera, plain};

use crate::support::{object, scene, square};

const SIZE: u32 = 16;

/// Three squares stacked along z, each covering window pixels 4..12 in x
/// and y, split along a diagonal through the sample centres (i, 15 − i).
fn stack() -> Scene {
    let layers = (0..3).map(|k| object(square(0.0, 0.0, 4.0, -(k as f32), plain(Vec3::ONE)), None)).collect();
    let mut s = scene(SIZE, Vec3::ONE, vec![], layers);
    s.camera = pixel_camera(SIZE);
    s
}

fn count(s: &Scene, rule: TieRule) -> Overdraw {
    let (o, _) = render_overdraw(s, &RenderOptions::default(), rule);
    assert_eq!(
        (o.width, o.height, o.counts.len()),
        (s.settings.width, s.settings.height, (SIZE * SIZE) as usize)
    );
    o
}

#[test]
fn stacked_squares_count_by_hand_under_each_rule() {
    let s = stack();
    for rule in TieRule::ALL {
        let o = count(&s, rule);
        for y in 0..SIZE {
            for x in 0..SIZE {
                let inside = (4..12).contains(&x) && (4..12).contains(&y);
                let want = match (inside, x + y == 15, rule) {
                    (false, _, _) => 0,
                    (true, false, _) | (true, true, TieRule::TopLeft) => 3,
                    (true, true, TieRule::Closed) => 6,
                    (true, true, TieRule::Open) => 0,
                };
                assert_eq!(o.at(x, y), want, "{rule:?} at ({x}, {y})");
            }
        }
    }
    // Four samples a pixel: four times the fragments.
    let mut fine = s.clone();
    fine.settings.ssaa = 2;
    let (o, _) = render_overdraw(&fine, &RenderOptions::default(), TieRule::TopLeft);
    assert_eq!(o.samples, 4);
    assert_eq!(o.total(), 4 * 3 * 64);
}

#[test]
fn a_pixel_has_fragments_exactly_where_the_depth_image_has_a_depth() {
    let mut s = zline_scenes::demo_scene();
    s.objects.retain(|o| !is_transparent(o));
    (s.settings.width, s.settings.height, s.settings.ssaa) = (120, 90, 1);
    let (_, depth, stats) = render_depth(&s, &RenderOptions::default());
    for tile_size in [8, 64] {
        let options = RenderOptions { tile_size };
        let (o, _) = render_overdraw(&s, &options, TieRule::TopLeft);
        for (i, (&c, &d)) in o.counts.iter().zip(&depth.depth).enumerate() {
            assert_eq!(c > 0, !d.is_nan(), "pixel {i}: {c} fragments, depth {d}");
        }
        // The samples shaded are those that passed the depth test: never
        // more than the fragments, and some were hidden.
        assert!(stats.fragments < o.total(), "{} vs {}", stats.fragments, o.total());
    }
}
