//! The two conventions SPEC leaves open (SPEC §11), in both readings:
//! where untextured Gouraud clamps (`GouraudClamp`) and how a back face
//! drawn without culling is lit (`LightingSides`). Pixel colours computed
//! here in f64 from SPEC §5–8 and §10; each test also checks that the two
//! readings give different answers, so it fails if the switch is ignored.
//!
//! Set-up as in `lit_square`: camera at the origin looking down −z (fovy
//! 90°), a 65×65 image whose centre sample lies on the optical axis, a
//! square of half-size 1 at z = −2. The centre sample is the midpoint of
//! the square's diagonal from (−1, −1) to (1, 1): Gouraud gives it the mean
//! of those two vertices' colours (w is the same at every vertex), in
//! whichever triangle the top-left rule puts it.

use std::sync::Arc;

use glam::{DVec3, Vec3};
use zline_pipeline::{render, RenderOptions};
use zline_scene::{Fog, FogCoordinate, FogMode, GouraudClamp, LightingSides, Mesh, Scene};
use zline_shading::{Attenuation, Light, Material, ShadingMode};

use crate::support::{draw, mesh, object, quantize_robust, scene, square};

const AMBIENT: [f64; 3] = [0.2, 0.2, 0.2];
const KA: [f64; 3] = [0.3, 0.3, 0.3];
const KD: [f64; 3] = [0.6, 0.5, 0.4];
/// Vertex colours of the tinted variants (multiplying ka and kd).
const TINT: [f64; 3] = [0.9, 0.8, 1.0];
/// Linear fog from 0 to 4: f = ½ at the square's eye-plane distance 2.
const FOG: [f64; 3] = [0.1, 0.2, 0.3];

fn v(a: [f64; 3]) -> DVec3 {
    DVec3::from_array(a)
}

fn f32s(a: [f64; 3]) -> Vec3 {
    Vec3::from_array(a.map(|x| x as f32))
}

fn material(ks: f64, ns: f64) -> Material {
    Material { ka: f32s(KA), kd: f32s(KD), ks: Vec3::splat(ks as f32), ns: ns as f32, ..Material::default() }
}

/// The square wound clockwise as seen from the origin, normals −z: its
/// front faces away from the viewer.
fn back_square(m: Material) -> Arc<Mesh> {
    let front = square(0.0, 0.0, 1.0, -2.0, m);
    mesh(
        front.positions.clone(),
        vec![-Vec3::Z; 4],
        front.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect(),
        m,
    )
}

/// `mesh` with every vertex coloured [`TINT`].
fn tinted(mesh: &Mesh) -> Arc<Mesh> {
    Arc::new(mesh.clone().with_colors(vec![f32s(TINT); mesh.positions.len()]).expect("one colour per vertex"))
}

/// Halfway through [`FOG`]: C = ½·C_surface + ½·C_fog.
fn fogged(c: DVec3) -> DVec3 {
    c * 0.5 + v(FOG) * 0.5
}

fn add_fog(s: &mut Scene) {
    s.fog = Some(Fog {
        mode: FogMode::Linear { start: 0.0, end: 4.0 },
        color: f32s(FOG),
        coordinate: FogCoordinate::EyePlane,
    });
}

// --- Gouraud: clamp per vertex or per sample -------------------------------

const BULB: [f64; 3] = [1.2, 1.2, -1.2];
const BULB_COLOR: [f64; 3] = [2.0, 1.3, 1.0];
const KS: f64 = 0.5;
const NS: f64 = 8.0;

/// SPEC §5 with the point light [`BULB`] (no attenuation), normal +z, eye at
/// the origin, unclamped; the ambient+diffuse part times `tint`.
fn bulb_lighting(p: DVec3, tint: DVec3) -> DVec3 {
    let (n, l) = (DVec3::Z, (v(BULB) - p).normalize());
    let h = (l + (-p).normalize()).normalize();
    let n_dot_l = n.dot(l).max(0.0);
    let specular = if n_dot_l > 0.0 { n.dot(h).max(0.0).powf(NS) } else { 0.0 };
    (v(KA) * v(AMBIENT) + v(BULB_COLOR) * v(KD) * n_dot_l) * tint + v(BULB_COLOR) * KS * specular
}

/// The centre's unfogged colour: the mean of the two diagonal vertices'
/// colours, each clamped (per vertex), or their unclamped mean clamped (per
/// sample).
fn gouraud_centre(clamp: GouraudClamp, tint: DVec3) -> DVec3 {
    let (a, b) =
        (bulb_lighting(DVec3::new(1.0, 1.0, -2.0), tint), bulb_lighting(DVec3::new(-1.0, -1.0, -2.0), tint));
    match clamp {
        GouraudClamp::PerVertex => {
            (a.clamp(DVec3::ZERO, DVec3::ONE) + b.clamp(DVec3::ZERO, DVec3::ONE)) * 0.5
        }
        GouraudClamp::PerSample => ((a + b) * 0.5).clamp(DVec3::ZERO, DVec3::ONE),
    }
}

/// The centre pixel of the square under [`BULB`], drawn Gouraud with
/// culling off: seen from the front, or (`back`) from behind with two-sided
/// lighting, which turns its normals to +z and so lights it alike.
fn draw_gouraud(clamp: GouraudClamp, tinted_mesh: bool, back: bool, fog: bool) -> [u8; 3] {
    let m = material(KS, NS);
    let mut mesh = if back { back_square(m) } else { square(0.0, 0.0, 1.0, -2.0, m) };
    if tinted_mesh {
        mesh = tinted(&mesh);
    }
    let light =
        Light::Point { position: f32s(BULB), color: f32s(BULB_COLOR), attenuation: Attenuation::NONE };
    let mut o = object(mesh, Some(ShadingMode::Gouraud));
    o.cull_back_faces = false;
    let mut s = scene(65, f32s(AMBIENT), vec![light], vec![o]);
    s.settings.gouraud_clamp = clamp;
    if fog {
        add_fog(&mut s);
    }
    draw(&s).pixel(32, 32)
}

#[test]
fn gouraud_interpolates_clamped_or_unclamped_vertex_colours() {
    // The (1, 1) vertex is lit above 1 in red and green, the (−1, −1) one
    // below: clamping first loses the excess, clamping last keeps it.
    for tint in [None, Some(v(TINT))] {
        let want = |clamp| quantize_robust(gouraud_centre(clamp, tint.unwrap_or(DVec3::ONE)));
        let (vertex, sample) = (want(GouraudClamp::PerVertex), want(GouraudClamp::PerSample));
        assert!(vertex[0].abs_diff(sample[0]) > 10, "the readings differ: {vertex:?} vs {sample:?}");
        for back in [false, true] {
            for (clamp, expected) in [(GouraudClamp::PerVertex, vertex), (GouraudClamp::PerSample, sample)] {
                let got = draw_gouraud(clamp, tint.is_some(), back, false);
                assert_eq!(got, expected, "{clamp:?}, tinted {}, back {back}", tint.is_some());
            }
        }
    }
}

#[test]
fn gouraud_clamped_per_sample_is_clamped_before_fog() {
    // The centre's unclamped red is above 1: fog must blend 1, not more.
    let unclamped = (bulb_lighting(DVec3::new(1.0, 1.0, -2.0), DVec3::ONE)
        + bulb_lighting(DVec3::new(-1.0, -1.0, -2.0), DVec3::ONE))
        * 0.5;
    assert!(unclamped.x > 1.1, "{unclamped}");
    for clamp in [GouraudClamp::PerVertex, GouraudClamp::PerSample] {
        let expected = quantize_robust(fogged(gouraud_centre(clamp, DVec3::ONE)));
        assert_eq!(draw_gouraud(clamp, false, false, true), expected, "{clamp:?}");
    }
    assert_ne!(
        quantize_robust(fogged(gouraud_centre(GouraudClamp::PerSample, DVec3::ONE))),
        quantize_robust(fogged(unclamped)),
        "the test sees a missing clamp"
    );
}

#[test]
fn adaptive_gouraud_drawn_flat_clamps_an_unclamped_colour() {
    // A head-on directional light lights every vertex alike, red above 1:
    // the adaptive mode draws the triangles flat in that colour, which with
    // per-sample clamping arrives unclamped and must be clamped before fog.
    let m = material(0.0, 1.0);
    let light = Light::Directional { direction: Vec3::NEG_Z, color: Vec3::new(2.0, 0.5, 0.3) };
    let lit = v(KA) * v(AMBIENT) + DVec3::new(2.0, 0.5, 0.3) * v(KD);
    assert!(lit.x > 1.2, "{lit}");
    for adaptive in [None, Some(8.0)] {
        let mut s = scene(
            65,
            f32s(AMBIENT),
            vec![light],
            vec![object(square(0.0, 0.0, 1.0, -2.0, m), Some(ShadingMode::Gouraud))],
        );
        s.settings.gouraud_clamp = GouraudClamp::PerSample;
        s.settings.adaptive_tolerance = adaptive;
        add_fog(&mut s);
        let image = draw(&s);
        for (x, y) in [(32, 32), (24, 40), (40, 22)] {
            let expected = quantize_robust(fogged(lit.clamp(DVec3::ZERO, DVec3::ONE)));
            assert_eq!(image.pixel(x, y), expected, "adaptive {adaptive:?} at ({x}, {y})");
        }
    }
}

// --- Back faces: two-sided or one-sided lighting ---------------------------

/// Travels towards −z: lights the side facing +z (the viewer).
const FRONT_LIGHT: ([f64; 3], [f64; 3]) = ([0.3, -0.4, -1.0], [0.9, 0.7, 0.2]);
/// Travels towards +z: lights the side facing −z (away from the viewer).
const BACK_LIGHT: ([f64; 3], [f64; 3]) = ([-0.2, 0.1, 1.0], [0.2, 0.6, 0.9]);

/// SPEC §5 without specular: the same at every point of the square, so
/// flat, Gouraud and Phong agree. `normal` is +z or −z.
fn matte_lighting(normal: DVec3, tint: DVec3) -> DVec3 {
    let diffuse = |(direction, color): ([f64; 3], [f64; 3])| {
        v(color) * v(KD) * normal.dot(-v(direction).normalize()).max(0.0)
    };
    (v(KA) * v(AMBIENT) + diffuse(FRONT_LIGHT) + diffuse(BACK_LIGHT)) * tint
}

#[test]
fn a_back_face_is_lit_turned_towards_the_viewer_or_as_given() {
    let lights = [FRONT_LIGHT, BACK_LIGHT]
        .map(|(d, c)| Light::Directional { direction: f32s(d), color: f32s(c) })
        .to_vec();
    let m = material(0.0, 1.0);
    for mode in ShadingMode::ALL {
        for tint in [None, Some(v(TINT))] {
            let t = tint.unwrap_or(DVec3::ONE);
            // Two-sided: the back's normals are turned to +z, facing the
            // front light; one-sided: they stay −z, facing the back light.
            let two = quantize_robust(matte_lighting(DVec3::Z, t));
            let one = quantize_robust(matte_lighting(-DVec3::Z, t));
            assert!(two[0].abs_diff(one[0]) > 50, "the readings differ: {two:?} vs {one:?}");
            for (sides, back_expected) in [(LightingSides::TwoSided, two), (LightingSides::OneSided, one)] {
                for (back, cull) in [(false, false), (true, false), (true, true)] {
                    let mut mesh = if back { back_square(m) } else { square(0.0, 0.0, 1.0, -2.0, m) };
                    if tint.is_some() {
                        mesh = tinted(&mesh);
                    }
                    let mut o = object(mesh, Some(mode));
                    o.cull_back_faces = cull;
                    let mut s = scene(65, f32s(AMBIENT), lights.clone(), vec![o]);
                    s.settings.lighting_sides = sides;
                    let image = draw(&s);
                    // A front face is lit as given either way; culling
                    // removes the back face either way.
                    let expected = match (back, cull) {
                        (false, _) => two,
                        (true, false) => back_expected,
                        (true, true) => [0, 0, 0],
                    };
                    for (x, y) in [(32, 32), (24, 40), (40, 22)] {
                        assert_eq!(
                            image.pixel(x, y),
                            expected,
                            "{mode:?} {sides:?}, tinted {}, back {back}, cull {cull} at ({x}, {y})",
                            tint.is_some()
                        );
                    }
                }
            }
        }
    }
}

/// A triangle in window coordinates (16 px window, plane z = −2, where a
/// pixel is 0.25 units), counter-clockwise as seen.
fn window_triangle(p: [(f32, f32); 3]) -> Scene {
    let world = p.map(|(x, y)| Vec3::new((x / 8.0 - 1.0) * 2.0, (1.0 - y / 8.0) * 2.0, -2.0)).to_vec();
    let m = Material { ka: Vec3::ONE, kd: Vec3::ZERO, ks: Vec3::ZERO, ..Material::default() };
    let object = object(mesh(world, vec![Vec3::Z; 3], vec![[0, 2, 1]], m), None);
    scene(16, Vec3::ONE, vec![], vec![object])
}

#[test]
fn a_triangle_whose_bounds_hold_no_sample_centre_makes_no_primitive() {
    // Inside pixel (5, 5) right of and below its centre (5.5, 5.5): no
    // sample, so setup makes no primitive and the pixel stays background.
    let between = window_triangle([(5.6, 5.6), (5.95, 5.6), (5.6, 5.95)]);
    let (image, stats) = render(&between, &RenderOptions::default());
    assert_eq!((stats.triangles_drawn, stats.primitives), (1, 0), "{stats:?}");
    assert!((0..16).all(|y| (0..16).all(|x| image.pixel(x, y) == [0, 0, 0])));
    // Moved 0.3 px up and left it covers that centre: one primitive, one
    // white sample.
    let over = window_triangle([(5.3, 5.3), (5.95, 5.3), (5.3, 5.95)]);
    let (image, stats) = render(&over, &RenderOptions::default());
    assert_eq!((stats.triangles_drawn, stats.primitives), (1, 1), "{stats:?}");
    let lit: Vec<(u32, u32)> = (0..16)
        .flat_map(|y| (0..16).map(move |x| (x, y)))
        .filter(|&(x, y)| image.pixel(x, y) != [0, 0, 0])
        .collect();
    assert_eq!(lit, [(5, 5)]);
}
