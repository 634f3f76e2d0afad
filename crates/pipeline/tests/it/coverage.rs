//! A transparent background (`RenderSettings::transparent_background`):
//! alpha is the coverage, colour is straight, and compositing the RGBA
//! image over a background reproduces the render on that background.

use glam::{DVec3, Vec3};
use proptest::prelude::*;
use zline_pipeline::{render, Image, RenderOptions};
use zline_scene::{Fog, FogCoordinate, FogMode, Scene, Visibility, WireframeMode};
use zline_shading::Material;

use crate::support::{draw, object, quantize_robust, scene, square};

const SIZE: u32 = 16;

/// An unlit material showing `color` (ka = color under white ambient light).
fn unlit(color: [f64; 3], opacity: f32) -> Material {
    let c = Vec3::from_array(color.map(|v| v as f32));
    Material { ka: c, kd: Vec3::ZERO, ks: Vec3::ZERO, ns: 1.0, opacity, ..Material::default() }
}

/// Squares (centre x, half-size, z, material) in draw order; transparent
/// ones drawn from both sides.
fn squares(layers: &[(f32, f32, f32, Material)]) -> Scene {
    let objects = layers
        .iter()
        .map(|&(cx, half, z, m)| {
            let mut o = object(square(cx, 0.0, half, z, m), None);
            o.cull_back_faces = m.opacity >= 1.0;
            o
        })
        .collect();
    let mut s = scene(SIZE, Vec3::ONE, vec![], objects);
    s.background = Vec3::new(0.3, 0.35, 0.4);
    s
}

fn transparent(s: &Scene) -> Image {
    let mut s = s.clone();
    s.settings.transparent_background = true;
    let image = draw(&s);
    assert!(image.transparent);
    image
}

fn rgba(image: &Image, x: u32, y: u32) -> [u8; 4] {
    let [r, g, b] = image.pixel(x, y);
    [r, g, b, image.alpha(x, y)]
}

const RED: [f64; 3] = [0.83, 0.17, 0.11];
const BLUE: [f64; 3] = [0.13, 0.29, 0.91];

#[test]
fn an_opaque_square_over_nothing_is_opaque_inside_and_empty_outside() {
    // At z = −2 the 90° view spans ±2: the square covers pixels 4..12.
    let s = squares(&[(0.0, 1.0, -2.0, unlit(RED, 1.0))]);
    let opaque = draw(&s);
    assert!(!opaque.transparent && opaque.alpha(8, 8) == 255 && opaque.alpha(0, 0) == 255);
    let image = transparent(&s);
    let [r, g, b] = quantize_robust(DVec3::from_array(RED));
    assert_eq!(rgba(&image, 8, 8), [r, g, b, 255]);
    assert_eq!(image.pixel(8, 8), opaque.pixel(8, 8));
    for (x, y) in [(0, 0), (3, 8), (12, 8), (8, 15)] {
        assert_eq!(rgba(&image, x, y), [0, 0, 0, 0], "({x}, {y})");
    }
    // Only the alpha bytes and the background differ from the opaque render.
    for y in 4..12 {
        for x in 4..12 {
            assert_eq!(image.pixel(x, y), opaque.pixel(x, y));
        }
    }
}

#[test]
fn a_transparent_square_over_nothing_has_its_opacity_as_alpha() {
    // kt = 0.25: alpha = round(0.75·255) = 191, straight colour the surface's.
    let s = squares(&[(0.0, 1.0, -2.0, unlit(BLUE, 0.75))]);
    let image = transparent(&s);
    let [r, g, b] = quantize_robust(DVec3::from_array(BLUE));
    assert_eq!(rgba(&image, 8, 8), [r, g, b, 191]);
    assert_eq!(rgba(&image, 1, 1), [0, 0, 0, 0]);
    // The same with fog (it touches drawn samples only) and with the painter.
    let mut fogged = s.clone();
    fogged.fog = Some(Fog {
        mode: FogMode::Linear { start: 1.0, end: 5.0 },
        color: Vec3::new(0.5, 0.6, 0.7),
        coordinate: FogCoordinate::EyePlane,
    });
    let f = 0.75f64; // (5 − 2)/(5 − 1) at the eye-plane distance 2
    let c = DVec3::from_array(BLUE) * f + DVec3::new(0.5, 0.6, 0.7) * (1.0 - f);
    let [r, g, b] = quantize_robust(c);
    assert_eq!(rgba(&transparent(&fogged), 8, 8), [r, g, b, 191]);
    assert_eq!(rgba(&transparent(&fogged), 1, 1), [0, 0, 0, 0]);
    let mut painter = s.clone();
    painter.settings.visibility = Visibility::Painter;
    assert_eq!(transparent(&painter), image);
}

#[test]
fn a_transparent_square_over_an_opaque_one_is_opaque() {
    let s = squares(&[(0.0, 1.0, -2.0, unlit(BLUE, 0.75)), (0.0, 1.5, -3.0, unlit(RED, 1.0))]);
    let (image, opaque) = (transparent(&s), draw(&s));
    assert_eq!(image.alpha(8, 8), 255);
    assert_eq!(image.pixel(8, 8), opaque.pixel(8, 8));
    let want = quantize_robust(DVec3::from_array(BLUE) * 0.75 + DVec3::from_array(RED) * 0.25);
    assert_eq!(image.pixel(8, 8), want);
    assert_eq!(image.alpha(0, 0), 0);
}

#[test]
fn a_supersampled_edge_pixel_has_the_covered_share_as_alpha() {
    // The square's left edge at window x = 4.25: with 4×4 samples at
    // x = 4.125, 4.375, 4.625, 4.875, three columns of four are covered
    // (alpha 12/16), the straight colour stays the surface's.
    let mut s = squares(&[(0.9375, 1.875, -2.0, unlit(RED, 1.0))]);
    s.settings.ssaa = 4;
    let image = transparent(&s);
    let [r, g, b] = quantize_robust(DVec3::from_array(RED));
    assert_eq!(rgba(&image, 4, 8), [r, g, b, 191]); // 0.75·255 + 0.5 = 191.75
    assert_eq!(rgba(&image, 5, 8), [r, g, b, 255]);
    assert_eq!(rgba(&image, 3, 8), [0, 0, 0, 0]);
    // Half a transparent square's opacity over the other half of nothing.
    let mut s = squares(&[(0.9375, 1.875, -2.0, unlit(BLUE, 0.5))]);
    s.settings.ssaa = 4;
    let image = transparent(&s);
    let [r, g, b] = quantize_robust(DVec3::from_array(BLUE));
    assert_eq!(rgba(&image, 4, 8), [r, g, b, 96]); // 0.375·255 + 0.5 = 96.125
}

#[test]
fn lines_are_opaque_over_nothing() {
    let mut s = squares(&[(0.0, 1.0, -2.0, unlit(RED, 1.0))]);
    s.settings.wireframe.mode = WireframeMode::All;
    s.settings.wireframe.only = true;
    let image = transparent(&s);
    let alphas: Vec<u8> = (0..SIZE).map(|x| image.alpha(x, 8)).collect();
    assert!(alphas.iter().all(|&a| a == 0 || a == 255), "{alphas:?}");
    assert!(alphas.contains(&255) && alphas.contains(&0), "{alphas:?}");
    // Lines over the surfaces: alpha 255 wherever anything is drawn.
    s.settings.wireframe.only = false;
    let image = transparent(&s);
    assert_eq!(image.alpha(8, 8), 255);
    assert_eq!(image.alpha(0, 0), 0);
}

#[test]
fn off_costs_nothing_in_the_image() {
    let s = squares(&[(0.0, 1.0, -2.0, unlit(BLUE, 0.75)), (0.3, 1.5, -3.0, unlit(RED, 1.0))]);
    let image = draw(&s);
    assert!(!image.transparent);
    assert!(image.pixels.iter().all(|p| p >> 24 == 0xFF));
}

/// Composites straight RGBA over `background` in f64, then SPEC §10.
fn over(px: [u8; 4], background: Vec3) -> [u8; 3] {
    let a = f64::from(px[3]) / 255.0;
    std::array::from_fn(|k| {
        let c = f64::from(px[k]) / 255.0 * a + (1.0 - a) * f64::from(background[k]);
        (c.clamp(0.0, 1.0) * 255.0 + 0.5).floor() as u8
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Over any background B the RGBA image gives the render on B within
    /// one step per channel: the exact composite S·α + (1 − α)·B differs
    /// from the quantized one by (S_q − S)·α_q + (α_q − α)·(S − B), at most
    /// ½·α_q + ½·|S − B| ≤ 1 step, and two values within one step round to
    /// bytes at most one apart.
    #[test]
    fn compositing_over_a_background_gives_the_render_on_it(
        layers in prop::collection::vec(
            (-1.5f32..1.5, 0.3f32..1.8, -6.0f32..-1.0, prop::array::uniform3(0.0f64..1.0), 0.1f32..1.2),
            1..5,
        ),
        background in prop::array::uniform3(0.0f32..1.0),
        ssaa in 1u32..4,
        painter: bool,
        fog: bool,
    ) {
        let layers: Vec<_> =
            layers.iter().map(|&(cx, half, z, c, o)| (cx, half, z, unlit(c, o.min(1.0)))).collect();
        let mut s = squares(&layers);
        s.background = Vec3::from_array(background);
        s.settings.ssaa = ssaa;
        if painter {
            s.settings.visibility = Visibility::Painter;
        }
        if fog {
            s.fog = Some(Fog {
                mode: FogMode::Exponential { density: 0.2 },
                color: Vec3::new(0.9, 0.8, 0.7),
                coordinate: FogCoordinate::Radial,
            });
        }
        let on_background = render(&s, &RenderOptions::default()).0;
        let rgba_image = transparent(&s);
        for y in 0..SIZE {
            for x in 0..SIZE {
                let got = over(rgba(&rgba_image, x, y), s.background);
                let want = on_background.pixel(x, y);
                for k in 0..3 {
                    prop_assert!(
                        got[k].abs_diff(want[k]) <= 1,
                        "({x}, {y}): composite {got:?}, render {want:?}, rgba {:?}",
                        rgba(&rgba_image, x, y)
                    );
                }
            }
        }
    }
}
