//! The object-ID image (`zline_pipeline::object_ids`): a pixel has an ID
//! exactly where the depth image has a depth (one sample a pixel), and the
//! object it names is the one whose surface the depth image measured.

use zline_pipeline::object_ids::{is_transparent, MAX_OBJECT_IDS};
use zline_pipeline::{render_depth, render_object_ids, Image, ObjectIds, RenderOptions};
use zline_scene::{Scene, ShadowMode, Visibility};

fn ids_of(s: &Scene) -> ObjectIds {
    let (ids, _) = render_object_ids(s, &RenderOptions::default()).expect("few objects");
    assert_eq!(ids.ids.len(), (ids.width * ids.height) as usize);
    ids
}

fn small(mut s: Scene, width: u32, height: u32) -> Scene {
    (s.settings.width, s.settings.height, s.settings.ssaa) = (width, height, 1);
    s
}

/// Every pixel: an ID where a depth is and only there, and the scene with
/// only that object (the others taken out) has the same depth there, bit
/// for bit: the same triangle drew the same sample.
fn check_against_depth(s: &Scene) {
    let ids = ids_of(s);
    let (_, depth, _) = render_depth(s, &RenderOptions::default());
    assert_eq!((ids.width, ids.height), (depth.width, depth.height));
    let mut seen = vec![0usize; s.objects.len()];
    for (i, (&id, &d)) in ids.ids.iter().zip(&depth.depth).enumerate() {
        assert_eq!(id >= 0, !d.is_nan(), "pixel {i}: id {id}, depth {d}");
        if id >= 0 {
            assert!(!is_transparent(&s.objects[id as usize]), "pixel {i}: a transparent object's id");
            seen[id as usize] += 1;
        }
    }
    for (k, &count) in seen.iter().enumerate().filter(|(_, &c)| c > 0) {
        let mut alone = s.clone();
        alone.objects = vec![s.objects[k].clone()];
        let (_, own, _) = render_depth(&alone, &RenderOptions::default());
        for (i, _) in ids.ids.iter().enumerate().filter(|(_, &id)| id == k as i32) {
            assert_eq!(own.depth[i].to_bits(), depth.depth[i].to_bits(), "object {k} at pixel {i}");
        }
        assert!(count > 0);
    }
}

#[test]
fn the_demo_scene_ids_are_its_depth_images_objects() {
    let s = small(zline_scenes::demo_scene(), 160, 120);
    assert!(s.objects.iter().any(is_transparent), "the demo scene has its glass sphere");
    check_against_depth(&s);
    let ids = ids_of(&s);
    let mut names: Vec<i32> = ids.ids.clone();
    names.sort_unstable();
    names.dedup();
    // Every opaque object of the demo is in view, and the background.
    let opaque = s.objects.iter().filter(|o| !is_transparent(o)).count();
    assert_eq!(names.len(), opaque + 1, "{names:?}");
}

#[test]
fn the_room_with_textures_and_shadows_and_the_painters_algorithm() {
    let mut s = small(zline_scenes::room_scene(), 96, 72);
    s.shadows.mode = ShadowMode::Map;
    check_against_depth(&s);
    // The painter's algorithm draws the image without a depth buffer; the
    // IDs are still the nearest surface's.
    let mut painter = s.clone();
    painter.settings.visibility = Visibility::Painter;
    assert_eq!(ids_of(&painter), ids_of(&s));
}

#[test]
fn supersampling_leaves_the_ids_unchanged() {
    // The demo has fog too, which the ID frame leaves out.
    let s = small(zline_scenes::demo_scene(), 80, 60);
    let mut fine = s.clone();
    fine.settings.ssaa = 3;
    assert_eq!(ids_of(&fine), ids_of(&s));
}

#[test]
fn the_id_frame_image_is_the_encoded_ids() {
    let s = small(zline_scenes::demo_scene(), 64, 48);
    let mut renderer = zline_pipeline::Renderer::default();
    let (mut image, mut ids) = (Image::empty(), ObjectIds::default());
    renderer.render_object_ids_into(&s, &RenderOptions::default(), &mut image, &mut ids).unwrap();
    for (&p, &id) in image.pixels.iter().zip(&ids.ids) {
        assert_eq!(p >> 24, 255);
        assert_eq!((p & 0xff_ffff) as i32, id + 1);
    }
    assert!(MAX_OBJECT_IDS >= s.objects.len());
}
