//! A square facing a point light: the centre pixel's exact 8-bit colour in
//! each shading mode, computed here in f64 straight from SPEC §5–6 and §10.
//!
//! Set-up: camera at the origin looking down −z (fovy 90°), a 65×65 image so
//! the centre pixel's sample lies exactly on the optical axis, a square of
//! half-size 1 at z = −2 facing +z (corners project to NC ±0.5), a point
//! light at (0.3, 0.8, −0.9) with attenuation (1, 0.2, 0.5) and a specular
//! material. The square is two triangles split along the diagonal from
//! (−1, −1) to (1, 1), which passes through the centre sample: by the
//! top-left rule the sample belongs to the lower-right triangle (the diagonal
//! is that triangle's left edge in window space).

use glam::{DVec3, Vec3};
use zline_shading::{Attenuation, Cone, Light, Material, ShadingMode};

use crate::support::{draw, object, quantize_robust, scene, square};

const LIGHT: [f64; 3] = [0.3, 0.8, -0.9];
const LIGHT_COLOR: [f64; 3] = [1.0, 0.85, 0.7];
const ATTENUATION: [f64; 3] = [1.0, 0.2, 0.5];
const AMBIENT: [f64; 3] = [0.15, 0.1, 0.05];
const KA: [f64; 3] = [0.3, 0.4, 0.5];
const KD: [f64; 3] = [0.7, 0.45, 0.3];
const KS: [f64; 3] = [0.5, 0.5, 0.5];
const NS: f64 = 12.0;

fn v(a: [f64; 3]) -> DVec3 {
    DVec3::from_array(a)
}

/// SPEC §5 in f64 for one point light, the eye at the origin, unclamped.
fn lighting(p: DVec3, n: DVec3) -> DVec3 {
    lighting_shaped(p, n, |_, _| 1.0)
}

/// [`lighting`] with the light's intensity also scaled by `shape(unit
/// vector from the light to p, distance)`: a range window, a spot cone.
fn lighting_shaped(p: DVec3, n: DVec3, shape: impl Fn(DVec3, f64) -> f64) -> DVec3 {
    let to_light = v(LIGHT) - p;
    let d = to_light.length();
    let l = to_light / d;
    let view = (-p).normalize();
    let h = (l + view).normalize();
    let [a0, a1, a2] = ATTENUATION;
    let f = (1.0 / (a0 + a1 * d + a2 * d * d)).min(1.0) * shape(-l, d);
    let n_dot_l = n.dot(l).max(0.0);
    let spec = if n_dot_l > 0.0 { n.dot(h).max(0.0).powf(NS) } else { 0.0 };
    v(KA) * v(AMBIENT) + f * v(LIGHT_COLOR) * (v(KD) * n_dot_l + v(KS) * spec)
}

#[track_caller]
fn check_centre(mode: ShadingMode, expected: DVec3) {
    let light = Light::Point {
        position: Vec3::from_array(LIGHT.map(|x| x as f32)),
        color: Vec3::from_array(LIGHT_COLOR.map(|x| x as f32)),
        attenuation: Attenuation::new(1.0, 0.2, 0.5),
    };
    check_centre_lit(mode, light, expected);
}

#[track_caller]
fn check_centre_lit(mode: ShadingMode, light: Light, expected: DVec3) {
    let material = Material {
        ka: Vec3::from_array(KA.map(|x| x as f32)),
        kd: Vec3::from_array(KD.map(|x| x as f32)),
        ks: Vec3::from_array(KS.map(|x| x as f32)),
        ns: NS as f32,
        opacity: 1.0,
        ..Material::default()
    };
    let s = scene(
        65,
        Vec3::from_array(AMBIENT.map(|x| x as f32)),
        vec![light],
        vec![object(square(0.0, 0.0, 1.0, -2.0, material), Some(mode))],
    );
    let image = draw(&s);
    assert_eq!(image.pixel(32, 32), quantize_robust(expected), "{mode:?}");
}

#[test]
fn phong_centre_is_the_lighting_model_at_the_centre() {
    check_centre(ShadingMode::Phong, lighting(DVec3::new(0.0, 0.0, -2.0), DVec3::Z));
}

#[test]
fn gouraud_centre_averages_the_diagonal_vertices() {
    // The centre is the midpoint of the shared diagonal: barycentrics (½, ½)
    // on its two vertices. w is the same at every vertex, so perspective
    // correction changes nothing. Vertex colours are clamped before
    // interpolation (the default `GouraudClamp::PerVertex`, SPEC §11; the
    // other reading is tested in `conventions`).
    let at = |x: f64, y: f64| lighting(DVec3::new(x, y, -2.0), DVec3::Z).clamp(DVec3::ZERO, DVec3::ONE);
    check_centre(ShadingMode::Gouraud, (at(-1.0, -1.0) + at(1.0, 1.0)) * 0.5);
}

#[test]
fn flat_centre_is_the_lower_right_triangles_centroid() {
    let centroid = DVec3::new(1.0 / 3.0, -1.0 / 3.0, -2.0);
    check_centre(ShadingMode::Flat, lighting(centroid, DVec3::Z));
}

/// The same light as a spot with a range (SPEC §5.1), aimed so that the
/// centre lies within the cone's falloff (about 0.24 rad off its axis,
/// between 0.15 and 0.4) and at 0.56 of its range.
#[test]
fn a_spot_light_with_a_range_scales_the_centre_by_its_window_and_cone() {
    let (inner, outer, range) = (0.15f64, 0.4f64, 2.5f64);
    let aim = DVec3::new(0.2, 0.3, -2.0);
    let axis = (aim - v(LIGHT)).normalize();
    let shape = |from_light: DVec3, d: f64| {
        let window = (1.0 - (d / range).powi(4)).clamp(0.0, 1.0);
        let t = (axis.dot(from_light) - outer.cos()) / (inner.cos() - outer.cos());
        window * t.clamp(0.0, 1.0).powi(2)
    };
    let centre = DVec3::new(0.0, 0.0, -2.0);
    let (from_light, d) = ((centre - v(LIGHT)).normalize(), (centre - v(LIGHT)).length());
    let share = shape(from_light, d);
    assert!(0.3 < share && share < 0.6, "the centre is within the falloff and the window: {share}");
    let light = Light::Spot {
        position: Vec3::from_array(LIGHT.map(|x| x as f32)),
        direction: (aim - v(LIGHT)).as_vec3(),
        color: Vec3::from_array(LIGHT_COLOR.map(|x| x as f32)),
        attenuation: Attenuation::new(1.0, 0.2, 0.5).with_range(range as f32),
        cone: Cone { inner: inner as f32, outer: outer as f32 },
    };
    check_centre_lit(ShadingMode::Phong, light, lighting_shaped(centre, DVec3::Z, shape));
    // Flat shading lights the lower-right triangle's centroid.
    let centroid = DVec3::new(1.0 / 3.0, -1.0 / 3.0, -2.0);
    check_centre_lit(ShadingMode::Flat, light, lighting_shaped(centroid, DVec3::Z, shape));
}

#[test]
fn overlapping_squares_give_the_same_image_in_either_order() {
    let red = Material::plastic(Vec3::new(0.9, 0.1, 0.1), 0.3, 16.0);
    let blue = Material::plastic(Vec3::new(0.1, 0.2, 0.9), 0.3, 16.0);
    let near = square(-0.3, -0.2, 1.0, -2.0, red);
    let far = square(0.4, 0.3, 1.2, -2.5, blue);
    let light =
        Light::Point { position: Vec3::new(0.0, 0.0, 1.0), color: Vec3::ONE, attenuation: Attenuation::NONE };
    let build = |first, second| {
        scene(97, Vec3::splat(0.2), vec![light], vec![object(first, None), object(second, None)])
    };
    let a = draw(&build(near.clone(), far.clone()));
    let b = draw(&build(far, near));
    assert_eq!(a, b);
    // The near red square wins where they overlap: around NC (0, 0) it is in front.
    let [r, _, bl] = a.pixel(48, 48);
    assert!(r > bl, "overlap shows the far square: {:?}", a.pixel(48, 48));
}

#[test]
fn lit_colour_is_within_range_and_background_elsewhere() {
    let s = scene(33, Vec3::ONE, vec![], vec![object(square(0.0, 0.0, 0.5, -2.0, Material::DEFAULT), None)]);
    let image = draw(&s);
    // ka·Ia = 0.8 → floor(0.8·255 + 0.5) = 204 inside; background 0 in the corner.
    assert_eq!(image.pixel(16, 16), [204, 204, 204]);
    assert_eq!(image.pixel(0, 0), [0, 0, 0]);
}

#[test]
fn undrawn_samples_get_the_background_in_tiles_with_and_without_geometry() {
    let mut s =
        scene(40, Vec3::ONE, vec![], vec![object(square(0.0, 0.0, 0.3, -2.0, Material::DEFAULT), None)]);
    s.background = Vec3::new(0.2, 0.4, 0.6);
    // 0.2·255 + 0.5 = 51.5 → 51; 0.4 → 102.5 → 102; 0.6 → 153.5 → 153.
    let bg = [51, 102, 153];
    for tile_size in [8, 64] {
        let image = zline_pipeline::render(&s, &zline_pipeline::RenderOptions { tile_size }).0;
        assert_eq!(image.pixel(20, 20), [204, 204, 204], "tile {tile_size}: the square");
        assert_eq!(image.pixel(14, 20), bg, "tile {tile_size}: beside the square, in its tile");
        assert_eq!(image.pixel(0, 0), bg, "tile {tile_size}: corner");
    }
}

#[test]
fn a_square_seen_from_behind_is_lit_like_its_front_when_culling_is_off() {
    // The same square twice: wound counter-clockwise with normals towards
    // the viewer, and clockwise with normals away (its back faces us). With
    // culling off, two-sided lighting turns the back's normals around, so
    // both light alike; one-sided lighting (`LightingSides::OneSided`,
    // tested in `conventions`) would leave the back at ka·Ia.
    let light =
        Light::Point { position: Vec3::new(0.3, 0.8, 0.5), color: Vec3::ONE, attenuation: Attenuation::NONE };
    let m = Material::plastic(Vec3::new(0.7, 0.4, 0.2), 0.5, 16.0);
    for mode in ShadingMode::ALL {
        let front = square(0.0, 0.0, 1.0, -2.0, m);
        let back = crate::support::mesh(
            front.positions.clone(),
            vec![-Vec3::Z; 4],
            front.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect(),
            m,
        );
        let draw_one = |mesh| {
            let mut o = object(mesh, Some(mode));
            o.cull_back_faces = false;
            draw(&scene(65, Vec3::splat(0.1), vec![light], vec![o]))
        };
        let (a, b) = (draw_one(front), draw_one(back));
        for (x, y) in [(32, 32), (24, 40), (40, 22)] {
            let (p, q) = (a.pixel(x, y), b.pixel(x, y));
            let diff = p.iter().zip(q).map(|(u, v)| u.abs_diff(v)).max().unwrap_or(0);
            assert!(diff <= 1, "{mode:?} at ({x}, {y}): front {p:?}, back {q:?}");
            assert!(p[0] > 60, "{mode:?}: the square is lit ({p:?})");
        }
    }
}
