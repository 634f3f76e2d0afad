//! The hard cases of `zline_scenes::hard_cases`, each rendered by the fast
//! pipeline and checked against its stated outcome — most against the f64
//! truth of `zline-truth`.

use zline::pipeline::{render, Image, RenderOptions};
use zline::scene::{DepthMode, Scene};
use zline::scenes::hard_cases::{self, HardCase};
use zline_truth::{render_truth, ErrorStats};

/// `hard_cases::RED` and `GREEN` in 8 bits (SPEC §10: 0.85·255 + 0.5 =
/// 217.25, 0.12·255 + 0.5 = 31.1).
const RED8: [u8; 3] = [217, 31, 31];
const GREEN8: [u8; 3] = [31, 217, 31];

fn case(name: &str) -> HardCase {
    hard_cases::hard_cases().into_iter().find(|c| c.name == name).expect("a hard case of that name")
}

fn draw(scene: &Scene) -> Image {
    render(scene, &RenderOptions::default()).0
}

/// Pixels where the fast image differs from the truth although no pixel of
/// the truth's 3×3 neighbourhood differs from the pixel itself — that is,
/// away from every edge the truth shows. Vertices are snapped to 1/256 px,
/// which may move a covered sample across an edge, but only next to one.
fn stray_pixels(fast: &Image, truth: &[u8], width: u32, height: u32) -> Vec<(u32, u32)> {
    let px = |x: u32, y: u32| {
        let i = 3 * (y * width + x) as usize;
        [truth[i], truth[i + 1], truth[i + 2]]
    };
    let mut stray = Vec::new();
    for y in 0..height {
        for x in 0..width {
            if fast.pixel(x, y) == px(x, y) {
                continue;
            }
            let centre = px(x, y);
            let uniform = (y.saturating_sub(1)..(y + 2).min(height))
                .all(|v| (x.saturating_sub(1)..(x + 2).min(width)).all(|u| px(u, v) == centre));
            if uniform {
                stray.push((x, y));
            }
        }
    }
    stray
}

/// Renders a case with both renderers; returns the error statistics and
/// the stray pixels.
fn against_truth(name: &str) -> (ErrorStats, Vec<(u32, u32)>) {
    let c = case(name);
    let fast = draw(&c.scene);
    let truth = render_truth(&c.scene);
    let reference = truth.quantized_rgb8();
    let stats = ErrorStats::of_rgb8(&fast.to_rgb(), &truth);
    let stray = stray_pixels(&fast, &reference, fast.width, fast.height);
    eprintln!("{name}: exact {:.5}, max {}, stray {}", stats.share_exact, stats.max_abs, stray.len());
    (stats, stray)
}

/// The share of pixels the truth and the fast renderer must agree on
/// exactly: the report's own-model standard (99.9 %); the rest are edge
/// samples within 1/512 px of an edge, where snapping decides.
const EXACT_SHARE: f64 = 0.999;

#[test]
fn slivers_match_the_exact_edge_functions() {
    let (stats, stray) = against_truth("slivers");
    assert!(stats.share_exact >= EXACT_SHARE, "{stats:?}");
    assert!(stray.is_empty(), "{stray:?}");
}

#[test]
fn a_thousand_triangle_fan_is_covered_once() {
    let (stats, stray) = against_truth("fan");
    assert!(stats.share_exact >= EXACT_SHARE, "{stats:?}");
    assert!(stray.is_empty(), "{stray:?}");
    // Watertight: no background inside the disc of radius 249 px.
    let image = draw(&case("fan").scene);
    for y in 0..512u32 {
        for x in 0..512u32 {
            let (dx, dy) = (f64::from(x) + 0.5 - 256.0, f64::from(y) + 0.5 - 256.0);
            if dx.hypot(dy) < 249.0 {
                assert_ne!(image.pixel(x, y), [0, 0, 0], "hole at ({x}, {y})");
            }
        }
    }
}

#[test]
fn near_plane_and_w_zero_crossings_draw_no_stray_pixels() {
    let (stats, stray) = against_truth("near_plane");
    assert!(stats.share_exact >= EXACT_SHARE, "{stats:?}");
    assert!(stray.is_empty(), "{stray:?}");
}

#[test]
fn vertices_a_million_pixels_away() {
    let (stats, stray) = against_truth("huge_coordinates");
    assert!(stats.share_exact >= EXACT_SHARE, "{stats:?}");
    assert!(stray.is_empty(), "{stray:?}");
}

#[test]
fn sub_pixel_triangles_cover_the_centres_they_contain() {
    let (stats, _) = against_truth("sub_pixel");
    // Every pixel here is an edge pixel, so no stray test: 4000 triangles of
    // < 1 px each cover ~0.3 samples on average, and a snapped vertex moves
    // by ≤ 1/512 px, so only samples that close to an edge can change.
    assert!(stats.share_exact >= EXACT_SHARE, "{stats:?}");
}

#[test]
fn eight_thousand_pixel_spans() {
    let (stats, stray) = against_truth("long_spans");
    assert!(stats.share_exact >= EXACT_SHARE, "{stats:?}");
    assert!(stray.is_empty(), "{stray:?}");
}

/// Pixels of `image` equal to `color` (as 8-bit RGB).
fn count(image: &Image, color: [u8; 3]) -> usize {
    (0..image.height)
        .flat_map(|y| (0..image.width).map(move |x| (x, y)))
        .filter(|&(x, y)| image.pixel(x, y) == color)
        .count()
}

#[test]
fn a_t_junction_may_leave_pinholes_along_the_unshared_edge() {
    // Documented behaviour: the right half's vertex t is snapped to the
    // 1/256 grid and no longer lies exactly on the left triangle's edge
    // a–b, so the sliver between the edge and the two right triangles'
    // edges can contain sample centres (missed: background shows) or the
    // triangles overlap (samples drawn twice, invisible here). Only samples
    // within 1/512 px of the diagonal can be affected, so at most a few
    // pixels along it.
    let image = draw(&case("t_junction").scene);
    let mut holes = 0;
    for y in 21..235u32 {
        for x in 21..235u32 {
            if image.pixel(x, y) == [0, 0, 0] {
                let on_diagonal = (f64::from(x) + f64::from(y) + 1.0 - 256.0).abs() < 2.0;
                assert!(on_diagonal, "hole at ({x}, {y}) away from the T-junction's edge");
                holes += 1;
            }
        }
    }
    // Measured: none at this position (the snapped t happens to land on
    // the covered side); the bound is the claim, not the measurement.
    eprintln!("t_junction: {holes} pinholes");
    assert!(holes <= 8, "{holes} pinholes");
}

#[test]
fn coplanar_triangles_z_fight_without_holes() {
    // Documented behaviour: the two triangles' depth planes come from
    // different vertices, whose f32 clip coordinates round differently
    // (~10⁻⁷), more than one f32 step of NC depth here, so the overlap
    // shows both colours in patches (z-fighting, as in any depth buffer;
    // the truth's f64 barycentric depths tie no better). What must hold:
    // both colours appear and, taking red and green as one surface, no
    // pixel differs from the truth away from the silhouette.
    let c = case("coplanar");
    let image = draw(&c.scene);
    let (red, green) = (count(&image, RED8), count(&image, GREEN8));
    eprintln!("coplanar: red {red}, green {green}");
    assert!(red > 0 && green > 0);
    let surface = |p: [u8; 3]| if p == GREEN8 { RED8 } else { p };
    let truth: Vec<u8> =
        render_truth(&c.scene).quantized_rgb8().chunks(3).flat_map(|p| surface([p[0], p[1], p[2]])).collect();
    let mut merged = image.clone();
    for p in &mut merged.pixels {
        let b = p.to_le_bytes();
        let s = surface([b[0], b[1], b[2]]);
        *p = u32::from_le_bytes([s[0], s[1], s[2], b[3]]);
    }
    let stray = stray_pixels(&merged, &truth, image.width, image.height);
    assert!(stray.is_empty(), "{stray:?}");
}

#[test]
fn parallel_planes_need_reversed_depth() {
    for (mode, name) in
        [(DepthMode::Normalized, "parallel_planes"), (DepthMode::ReversedFloat, "parallel_planes_reversed")]
    {
        let c = case(name);
        assert_eq!(c.scene.settings.depth, mode);
        let image = draw(&c.scene);
        let far = count(&image, RED8);
        let share = far as f64 / f64::from(image.width * image.height);
        eprintln!("{name}: far plane visible on {:.1} %", 100.0 * share);
        // NC depth ties everywhere and keeps the first drawn (the far one);
        // reversed depth resolves the 1.2·10⁻⁴ gap at every sample.
        let expected = if mode == DepthMode::Normalized { 1.0 } else { 0.0 };
        assert_eq!(share, expected, "{name}");
    }
}
