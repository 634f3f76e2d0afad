//! Shadows (`ShadowMode::Planar`, and `ShadowMode::Map` where every
//! surface receives and casts, its own mesh included) as light visibility,
//! with answers computed here from the geometry, independently of the
//! truth's code.
//!
//! The scenes: a floor at y = 0 (x, z ∈ [−8, 8], normal +y, the shadow
//! receiver) and a unit square, the occluder, at y = 2 over
//! x ∈ [1.25, 2.25], z ∈ [−0.5, 0.5], seen straight down by an
//! orthographic camera over x, z ∈ [−6, 6] on 96×96 pixels (8 pixels per
//! unit; image right is +x, image down is +z). Pixel (i, j) samples the
//! world point x = −6 + (i + ½)/8, z = −6 + (j + ½)/8, so window
//! coordinate x_win = 8·(x + 6): every edge below sits at a whole window
//! coordinate, between pixel centres, never on one.

use std::sync::Arc;

use glam::{DVec3, Vec3};
use zline_scene::{Camera, Mesh, Projection, RenderSettings, Scene, ShadowMode, ShadowPlane, Shadows};
use zline_shading::{Attenuation, Light, Material, ShadingMode};
use zline_truth::{render_truth, TruthImage};

use crate::support::{check_close, d, emissive, mesh, object, F64_TOLERANCE};

/// Image size in pixels.
pub(crate) const SIZE: u32 = 96;

/// The floor's material: no specular term unless a test adds one.
const FLOOR: Material = Material {
    ke: Vec3::ZERO,
    ka: Vec3::new(0.5, 0.5, 0.5),
    kd: Vec3::new(0.75, 0.75, 0.75),
    ks: Vec3::ZERO,
    ns: 1.0,
    opacity: 1.0,
    model: zline_shading::Model::Basic,
    ..Material::DEFAULT
};

const AMBIENT: Vec3 = Vec3::new(0.25, 0.25, 0.25);

/// No attenuation: f = 1.
const NO_ATTENUATION: Attenuation = Attenuation::new(1.0, 0.0, 0.0);

/// A white point light at height 4 over the origin.
pub(crate) const TOP: Vec3 = Vec3::new(0.0, 4.0, 0.0);

/// A horizontal square at height `y` over [x0, x1] × [z0, z1], normal +y
/// (counter-clockwise seen from above).
fn slab(x: [f32; 2], z: [f32; 2], y: f32, material: Material) -> Arc<Mesh> {
    let p = vec![
        Vec3::new(x[0], y, z[0]),
        Vec3::new(x[0], y, z[1]),
        Vec3::new(x[1], y, z[1]),
        Vec3::new(x[1], y, z[0]),
    ];
    mesh(p, vec![Vec3::Y; 4], vec![[0, 1, 2], [0, 2, 3]], material)
}

/// The floor, drawn Flat: as a receiver it is lit per sample all the same.
pub(crate) fn floor(material: Material) -> zline_scene::Object {
    object(slab([-8.0, 8.0], [-8.0, 8.0], 0.0, material), Some(ShadingMode::Flat))
}

/// The occluder, green under the ambient light alone.
pub(crate) fn occluder() -> zline_scene::Object {
    object(slab([1.25, 2.25], [-0.5, 0.5], 2.0, emissive(Vec3::new(0.0, 1.0, 0.0), 1.0)), None)
}

/// A scene seen from height `eye_y` straight down; object 0 receives
/// shadows (plane y = 0) in `mode`.
pub(crate) fn scene(
    eye_y: f32,
    lights: Vec<Light>,
    objects: Vec<zline_scene::Object>,
    mode: ShadowMode,
) -> Scene {
    Scene {
        environment: None,
        shadows: Shadows {
            mode,
            planes: vec![ShadowPlane { receiver: 0, plane: glam::Vec4::Y }],
            ..Default::default()
        },
        camera: Camera {
            eye: Vec3::new(0.0, eye_y, 0.0),
            target: Vec3::ZERO,
            up: Vec3::NEG_Z,
            projection: Projection::Orthographic { height: 12.0, near: 0.5, far: 20.0 },
        },
        background: Vec3::ZERO,
        ambient: AMBIENT,
        lights,
        objects,
        settings: RenderSettings { width: SIZE, height: SIZE, ..RenderSettings::default() },
        fog: None,
    }
}

pub(crate) fn point_light(position: Vec3, color: Vec3) -> Light {
    Light::Point { position, color, attenuation: NO_ATTENUATION }
}

/// The world point pixel (i, j)'s sample sees at height `y`.
fn world(i: u32, j: u32, y: f64) -> DVec3 {
    DVec3::new(-6.0 + (f64::from(i) + 0.5) / 8.0, y, -6.0 + (f64::from(j) + 0.5) / 8.0)
}

/// Pixels i ∈ [i0, i1], j ∈ [j0, j1] (inclusive).
pub(crate) fn in_box(i: u32, j: u32, [i0, i1, j0, j1]: [u32; 4]) -> bool {
    (i0..=i1).contains(&i) && (j0..=j1).contains(&j)
}

/// The occluder's pixels: x ∈ [1.25, 2.25] is x_win ∈ [58, 66], z ∈
/// [−0.5, 0.5] is y_win ∈ [44, 52].
pub(crate) const OCCLUDER_PIXELS: [u32; 4] = [58, 65, 44, 51];

/// The shadow of the occluder (height 2) from the light at height 4 over
/// the origin: the segment from floor point (x, 0, z) meets y = 2 at its
/// midpoint (x/2, 2, z/2), so the shadow is x ∈ [2.5, 4.5], z ∈ [−1, 1]:
/// x_win ∈ [68, 84], y_win ∈ [40, 56].
pub(crate) const SHADOW_PIXELS: [u32; 4] = [68, 83, 40, 55];

/// Diffuse (and specular) of one light on the floor at `p` (N = +y), the
/// viewer at `eye`: f·Il·[kd·N·L + ks·(N·H)^ns], 0 where N·L ≤ 0.
fn contribution(m: &Material, p: DVec3, to_light: DVec3, color: Vec3, eye: DVec3) -> DVec3 {
    let l = to_light.normalize();
    let n_dot_l = l.y;
    if n_dot_l <= 0.0 {
        return DVec3::ZERO;
    }
    let h = (l + (eye - p).normalize()).normalize();
    d(color) * (d(m.kd) * n_dot_l + d(m.ks) * h.y.max(0.0).powf(f64::from(m.ns)))
}

fn ambient(m: &Material) -> DVec3 {
    d(m.ka) * d(AMBIENT)
}

/// The number of pixels (i, j) of `image` whose colour c satisfies f(i, j, c).
fn count(image: &TruthImage, mut f: impl FnMut(u32, u32, DVec3) -> bool) -> usize {
    (0..SIZE)
        .flat_map(|j| (0..SIZE).map(move |i| (i, j)))
        .filter(|&(i, j)| f(i, j, image.pixel(i, j)))
        .count()
}

/// (a) The occluder's shadow on the floor under a point light straight
/// above: exactly the 16×16 pixels of `SHADOW_PIXELS` show ambient light
/// only; every other floor pixel is lit as Phong at its own point (the
/// floor's Flat mode is overridden), and the occluder shows its green.
#[test]
fn a_square_casts_its_projected_square() {
    let s =
        scene(10.0, vec![point_light(TOP, Vec3::ONE)], vec![floor(FLOOR), occluder()], ShadowMode::Planar);
    let image = render_truth(&s);
    let eye = DVec3::new(0.0, 10.0, 0.0);
    for j in 0..SIZE {
        for i in 0..SIZE {
            let got = image.pixel(i, j);
            let want = if in_box(i, j, OCCLUDER_PIXELS) {
                DVec3::new(0.0, 0.25, 0.0)
            } else if in_box(i, j, SHADOW_PIXELS) {
                ambient(&FLOOR)
            } else {
                let p = world(i, j, 0.0);
                ambient(&FLOOR) + contribution(&FLOOR, p, d(TOP) - p, Vec3::ONE, eye)
            };
            check_close(got, want.min(DVec3::ONE), F64_TOLERANCE);
        }
    }
    // Only the shadow is ambient alone: elsewhere on the floor the light adds
    // at least 0.75·N·L ≥ 0.75·4/√(6² + 6² + 4²) > 0.3.
    let dark = count(&image, |_, _, c| (c - ambient(&FLOOR)).abs().max_element() < 1e-9);
    assert_eq!(dark, 16 * 16);
}

/// (b) Only what lies between the point and the light shadows it. A second
/// receiver, a plate at height 3 over x ∈ [1, 3], z ∈ [−1, 1], sits above
/// the occluder (between it and the light): it is fully lit. A large
/// square at height 6, beyond the light at height 4 (and behind the
/// camera at height 5, so not drawn), darkens nothing. The floor keeps
/// the occluder's shadow where the plate does not cover it.
#[test]
fn only_what_lies_between_point_and_light_shadows() {
    let plate = object(slab([1.0, 3.0], [-1.0, 1.0], 3.0, FLOOR), Some(ShadingMode::Gouraud));
    let ceiling = object(slab([-6.0, 6.0], [-6.0, 6.0], 6.0, emissive(Vec3::ONE, 1.0)), None);
    let mut s = scene(
        5.0,
        vec![point_light(TOP, Vec3::ONE)],
        vec![floor(FLOOR), plate, occluder(), ceiling],
        ShadowMode::Planar,
    );
    s.shadows.planes.push(ShadowPlane { receiver: 1, plane: glam::Vec4::new(0.0, 1.0, 0.0, -3.0) });
    let image = render_truth(&s);
    let eye = DVec3::new(0.0, 5.0, 0.0);
    // The plate: x_win ∈ [56, 72], y_win ∈ [40, 56].
    let plate_pixels = [56, 71, 40, 55];
    for j in 0..SIZE {
        for i in 0..SIZE {
            let y = if in_box(i, j, plate_pixels) { 3.0 } else { 0.0 };
            let p = world(i, j, y);
            let lit = ambient(&FLOOR) + contribution(&FLOOR, p, d(TOP) - p, Vec3::ONE, eye);
            let want = if y == 0.0 && in_box(i, j, SHADOW_PIXELS) { ambient(&FLOOR) } else { lit };
            check_close(image.pixel(i, j), want.min(DVec3::ONE), F64_TOLERANCE);
        }
    }
    // The floor's shadow left of the plate's edge at x = 3 (x_win 72).
    let dark = count(&image, |_, _, c| (c - ambient(&FLOOR)).abs().max_element() < 1e-9);
    assert_eq!(dark, (83 - 72 + 1) * 16);
}

/// (c) Coloured shadows: a red point light straight above and a blue
/// directional light along (−1, −1, 0). Each light's shadow keeps the
/// other light's contribution, specular term included. The blue ray from
/// (x, 0, z) along (1, 1, 0)/√2 meets y = 2 at (x + 2, 2, z), so the blue
/// shadow is x ∈ [−0.75, 0.25], z ∈ [−0.5, 0.5]: x_win ∈ [42, 50],
/// y_win ∈ [44, 52]; the red one is `SHADOW_PIXELS`.
#[test]
fn a_hidden_light_leaves_the_others_colour() {
    let m = Material { ks: Vec3::splat(0.25), ns: 8.0, ..FLOOR };
    let red = Vec3::new(1.0, 0.0, 0.0);
    let blue = Vec3::new(0.0, 0.0, 1.0);
    let lights = vec![
        point_light(TOP, red),
        Light::Directional { direction: Vec3::new(-1.0, -1.0, 0.0), color: blue },
    ];
    let s = scene(10.0, lights, vec![floor(m), occluder()], ShadowMode::Planar);
    let image = render_truth(&s);
    let eye = DVec3::new(0.0, 10.0, 0.0);
    let blue_shadow = [42, 49, 44, 51];
    let (mut red_only, mut blue_only) = (0, 0);
    for j in 0..SIZE {
        for i in 0..SIZE {
            if in_box(i, j, OCCLUDER_PIXELS) {
                continue;
            }
            let p = world(i, j, 0.0);
            let mut want = ambient(&m);
            if !in_box(i, j, SHADOW_PIXELS) {
                want += contribution(&m, p, d(TOP) - p, red, eye);
            } else {
                blue_only += 1;
            }
            if !in_box(i, j, blue_shadow) {
                want += contribution(&m, p, DVec3::new(1.0, 1.0, 0.0), blue, eye);
            } else {
                red_only += 1;
            }
            check_close(image.pixel(i, j), want.min(DVec3::ONE), F64_TOLERANCE);
        }
    }
    assert_eq!((red_only, blue_only), (64, 256));
    // In the red shadow blue stays and red is ambient; in the blue one the reverse.
    let (r, b) = (image.pixel(75, 47), image.pixel(45, 47));
    assert_eq!(r.x, 0.125);
    assert!(r.z > 0.125 + 0.5, "{r}");
    assert_eq!(b.z, 0.125);
    assert!(b.x > 0.125 + 0.5, "{b}");
}

/// (d) With `ShadowMode::None` the receiver list is ignored: the image is
/// bit for bit the one without any shadow settings, and the floor keeps
/// its Flat shading (lit at its triangles' centroids, no shadow). In
/// Planar mode the non-receivers are unchanged, bit for bit.
#[test]
fn shadow_mode_none_changes_nothing() {
    let lights = vec![point_light(TOP, Vec3::ONE)];
    let objects = vec![floor(FLOOR), occluder()];
    let none = render_truth(&scene(10.0, lights.clone(), objects.clone(), ShadowMode::None));
    let mut plain = scene(10.0, lights.clone(), objects.clone(), ShadowMode::None);
    plain.shadows = Shadows::default();
    assert_eq!(none.rgb, render_truth(&plain).rgb);
    // The floor's two triangles are (−8, −8), (−8, 8), (8, 8) in (x, z),
    // where z > x, and (−8, −8), (8, 8), (8, −8); centroids (∓8/3, 0, ±8/3).
    // Pixels on the diagonal i = j are left out (the shared edge).
    let eye = DVec3::new(0.0, 10.0, 0.0);
    for j in 0..SIZE {
        for i in (0..SIZE).filter(|&i| i != j && !in_box(i, j, OCCLUDER_PIXELS)) {
            let c = if j > i { DVec3::new(-8.0, 0.0, 8.0) / 3.0 } else { DVec3::new(8.0, 0.0, -8.0) / 3.0 };
            let want = ambient(&FLOOR) + contribution(&FLOOR, c, d(TOP) - c, Vec3::ONE, eye);
            check_close(none.pixel(i, j), want.min(DVec3::ONE), F64_TOLERANCE);
        }
    }
    let planar = render_truth(&scene(10.0, lights, objects, ShadowMode::Planar));
    for j in 0..SIZE {
        for i in 0..SIZE {
            if in_box(i, j, OCCLUDER_PIXELS) {
                assert_eq!(planar.pixel(i, j), none.pixel(i, j), "({i}, {j})");
            }
        }
    }
}

/// A receiver without casters (every object receives) is lit as Phong,
/// with no light hidden: the same image as the scene drawn in Phong
/// without shadows.
#[test]
fn a_receiver_without_casters_is_lit_as_phong() {
    let lights = vec![point_light(TOP, Vec3::ONE)];
    let s = scene(10.0, lights.clone(), vec![floor(FLOOR)], ShadowMode::Planar);
    let mut phong = scene(10.0, lights, vec![floor(FLOOR)], ShadowMode::None);
    phong.objects[0].shading = Some(ShadingMode::Phong);
    assert_eq!(render_truth(&s).rgb, render_truth(&phong).rgb);
}

/// (a) under a perspective camera (fovy 90°, square image) at height 10
/// looking straight down: pixel (i, j)'s sample looks along world
/// direction (x_nc, −1, −y_nc) from (0, 10, 0), so it meets height h at
/// (x_nc·(10 − h), h, −y_nc·(10 − h)). Each pixel is classified here from
/// that point: on the occluder, in its shadow (the midpoint of the segment
/// to the light on the occluder), or lit.
#[test]
fn the_shadow_under_a_perspective_camera() {
    let size = 88;
    let floor = object(slab([-12.0, 12.0], [-12.0, 12.0], 0.0, FLOOR), Some(ShadingMode::Gouraud));
    let mut s = scene(10.0, vec![point_light(TOP, Vec3::ONE)], vec![floor, occluder()], ShadowMode::Planar);
    s.camera.projection = Projection::Perspective { fovy_degrees: 90.0, near: 0.5, far: 20.0 };
    (s.settings.width, s.settings.height) = (size, size);
    let image = render_truth(&s);
    let eye = DVec3::new(0.0, 10.0, 0.0);
    let on_occluder = |x: f64, z: f64| (1.25..=2.25).contains(&x) && (-0.5..=0.5).contains(&z);
    // Distance from the occluder's outline (in x or z): no sample's point
    // lies within 1e-6 of an edge with 88 pixels (44 per unit of NC).
    let margin =
        |x: f64, z: f64| [x - 1.25, x - 2.25, z + 0.5, z - 0.5].map(f64::abs).into_iter().fold(1.0, f64::min);
    let (mut shadowed, mut occluded) = (0, 0);
    for j in 0..size {
        for i in 0..size {
            let nc = (f64::from(i) + 0.5) / 44.0 - 1.0;
            let nc_y = 1.0 - (f64::from(j) + 0.5) / 44.0;
            let at = |h: f64| DVec3::new(nc * (10.0 - h), h, -nc_y * (10.0 - h));
            let (high, low) = (at(2.0), at(0.0));
            assert!(margin(high.x, high.z) > 1e-6 && margin(low.x / 2.0, low.z / 2.0) > 1e-6);
            let want = if on_occluder(high.x, high.z) {
                occluded += 1;
                DVec3::new(0.0, 0.25, 0.0)
            } else if on_occluder(low.x / 2.0, low.z / 2.0) {
                shadowed += 1;
                ambient(&FLOOR)
            } else {
                ambient(&FLOOR) + contribution(&FLOOR, low, d(TOP) - low, Vec3::ONE, eye)
            };
            check_close(image.pixel(i, j), want.min(DVec3::ONE), F64_TOLERANCE);
        }
    }
    // The occluder spans 44/8 = 5.5 pixels a side (side 1 at distance 8,
    // 44 pixels per unit of NC), its shadow 44·2/10 = 8.8 (side 2 at
    // distance 10).
    assert!((25..=36).contains(&occluded) && (64..=81).contains(&shadowed), "{occluded} {shadowed}");
}

/// `ShadowMode::Map` without planes: every object receives and casts.
fn map_scene(eye_y: f32, lights: Vec<Light>, objects: Vec<zline_scene::Object>) -> Scene {
    let mut s = scene(eye_y, lights, objects, ShadowMode::Map);
    s.shadows.planes.clear();
    s
}

/// A white directional light straight down.
fn sun() -> Light {
    Light::Directional { direction: Vec3::NEG_Y, color: Vec3::ONE }
}

/// Map (a) The occluder under a directional light straight down, in Map
/// mode with no planes: its shadow is its own footprint, x_win ∈ [58, 66],
/// y_win ∈ [44, 52]. Facing down (clockwise from above) and culled, the
/// occluder is not drawn but still casts, so the camera sees exactly
/// `OCCLUDER_PIXELS` of floor at ambient alone and every other floor pixel
/// lit. Drawn facing up, with a diffuse term, it is lit itself: its two
/// coplanar triangles do not shadow each other.
#[test]
fn map_mode_a_square_shadows_its_footprint() {
    let p =
        [(1.25, -0.5), (1.25, 0.5), (2.25, 0.5), (2.25, -0.5)].map(|(x, z)| Vec3::new(x, 2.0, z)).to_vec();
    let down =
        mesh(p, vec![Vec3::NEG_Y; 4], vec![[0, 2, 1], [0, 3, 2]], emissive(Vec3::new(0.0, 1.0, 0.0), 1.0));
    let culled = zline_scene::Object { cull_back_faces: true, ..object(down, None) };
    let image = render_truth(&map_scene(10.0, vec![sun()], vec![floor(FLOOR), culled]));
    let lit = ambient(&FLOOR) + d(FLOOR.kd);
    for j in 0..SIZE {
        for i in 0..SIZE {
            let want = if in_box(i, j, OCCLUDER_PIXELS) { ambient(&FLOOR) } else { lit };
            check_close(image.pixel(i, j), want, F64_TOLERANCE);
        }
    }
    let dark = count(&image, |_, _, c| (c - ambient(&FLOOR)).abs().max_element() < 1e-9);
    assert_eq!(dark, 8 * 8);

    let green = Material { kd: Vec3::new(0.0, 0.5, 0.0), ..emissive(Vec3::new(0.0, 1.0, 0.0), 1.0) };
    let up = object(slab([1.25, 2.25], [-0.5, 0.5], 2.0, green), Some(ShadingMode::Gouraud));
    let image = render_truth(&map_scene(10.0, vec![sun()], vec![floor(FLOOR), up]));
    for j in 0..SIZE {
        for i in 0..SIZE {
            let want = if in_box(i, j, OCCLUDER_PIXELS) { DVec3::new(0.0, 0.75, 0.0) } else { lit };
            check_close(image.pixel(i, j), want, F64_TOLERANCE);
        }
    }
}

/// Map (a) with the lights of the planar test (c), a red point light
/// straight above and a blue directional light along (−1, −1, 0): in Map
/// mode without planes the floor shows the same two shadows.
#[test]
fn map_mode_matches_the_planar_shadows_on_the_floor() {
    let m = Material { ks: Vec3::splat(0.25), ns: 8.0, ..FLOOR };
    let red = Vec3::new(1.0, 0.0, 0.0);
    let blue = Vec3::new(0.0, 0.0, 1.0);
    let lights = vec![
        point_light(TOP, red),
        Light::Directional { direction: Vec3::new(-1.0, -1.0, 0.0), color: blue },
    ];
    let image = render_truth(&map_scene(10.0, lights.clone(), vec![floor(m), occluder()]));
    let eye = DVec3::new(0.0, 10.0, 0.0);
    let blue_shadow = [42, 49, 44, 51];
    for j in 0..SIZE {
        for i in 0..SIZE {
            if in_box(i, j, OCCLUDER_PIXELS) {
                // The occluder receives too; with kd = ks = 0 it stays green.
                check_close(image.pixel(i, j), DVec3::new(0.0, 0.25, 0.0), F64_TOLERANCE);
                continue;
            }
            let p = world(i, j, 0.0);
            let mut want = ambient(&m);
            if !in_box(i, j, SHADOW_PIXELS) {
                want += contribution(&m, p, d(TOP) - p, red, eye);
            }
            if !in_box(i, j, blue_shadow) {
                want += contribution(&m, p, DVec3::new(1.0, 1.0, 0.0), blue, eye);
            }
            check_close(image.pixel(i, j), want.min(DVec3::ONE), F64_TOLERANCE);
        }
    }
    let planar = render_truth(&scene(10.0, lights, vec![floor(m), occluder()], ShadowMode::Planar));
    for j in 0..SIZE {
        for i in (0..SIZE).filter(|&i| !in_box(i, j, OCCLUDER_PIXELS)) {
            assert_eq!(image.pixel(i, j), planar.pixel(i, j), "({i}, {j})");
        }
    }
}

/// Map (b) Self-shadowing. One object, an L: the floor (x, z ∈ [−8, 8],
/// y = 0, facing up) and a wall at x = 2 over z ∈ [−2, 2], y ∈ [0, 2],
/// facing −x, in one mesh. Under a directional light along (−1, −1, 0)
/// the ray from floor point (x, 0, z) along (1, 1, 0)/√2 reaches x = 2 at
/// height 2 − x, so the wall hides the light from x ∈ (0, 2), z ∈ (−2, 2):
/// x_win ∈ [48, 64], y_win ∈ [32, 64]. The wall, edge-on to the camera,
/// draws nothing. In Map mode those 16 × 32 pixels show ambient alone; in
/// Planar mode without planes nothing receives and every pixel is lit.
#[test]
fn map_mode_a_concave_object_shadows_itself() {
    let p = vec![
        Vec3::new(-8.0, 0.0, -8.0),
        Vec3::new(-8.0, 0.0, 8.0),
        Vec3::new(8.0, 0.0, 8.0),
        Vec3::new(8.0, 0.0, -8.0),
        Vec3::new(2.0, 0.0, -2.0),
        Vec3::new(2.0, 0.0, 2.0),
        Vec3::new(2.0, 2.0, 2.0),
        Vec3::new(2.0, 2.0, -2.0),
    ];
    let n = [Vec3::Y; 4].into_iter().chain([Vec3::NEG_X; 4]).collect();
    // The wall's corners seen from −x: (z, y) = (−2, 0), (2, 0), (2, 2),
    // (−2, 2) run clockwise, so the triangles list them the other way.
    let l = mesh(p, n, vec![[0, 1, 2], [0, 2, 3], [4, 6, 5], [4, 7, 6]], FLOOR);
    let light = Light::Directional { direction: Vec3::new(-1.0, -1.0, 0.0), color: Vec3::ONE };
    let objects = vec![object(l, Some(ShadingMode::Flat))];
    let lit = ambient(&FLOOR) + d(FLOOR.kd) * std::f64::consts::FRAC_1_SQRT_2;
    let shadow = [48, 63, 32, 63];

    let map = render_truth(&map_scene(10.0, vec![light], objects.clone()));
    for j in 0..SIZE {
        for i in 0..SIZE {
            let want = if in_box(i, j, shadow) { ambient(&FLOOR) } else { lit };
            check_close(map.pixel(i, j), want, F64_TOLERANCE);
        }
    }
    let dark = count(&map, |_, _, c| (c - ambient(&FLOOR)).abs().max_element() < 1e-9);
    assert_eq!(dark, 16 * 32);

    let mut planar = map_scene(10.0, vec![light], objects);
    planar.shadows.mode = ShadowMode::Planar;
    let planar = render_truth(&planar);
    for j in 0..SIZE {
        for i in 0..SIZE {
            check_close(planar.pixel(i, j), lit, F64_TOLERANCE);
        }
    }
}

/// A flat-shaded cube of half side 1 around the origin: four corners and
/// one normal per face, counter-clockwise from outside.
fn cube(material: Material) -> Arc<Mesh> {
    let faces = [
        (Vec3::X, Vec3::Y, Vec3::Z),
        (Vec3::NEG_X, Vec3::Z, Vec3::Y),
        (Vec3::Y, Vec3::Z, Vec3::X),
        (Vec3::NEG_Y, Vec3::X, Vec3::Z),
        (Vec3::Z, Vec3::X, Vec3::Y),
        (Vec3::NEG_Z, Vec3::Y, Vec3::X),
    ];
    let (mut p, mut n, mut t) = (Vec::new(), Vec::new(), Vec::new());
    for (k, (normal, u, v)) in faces.into_iter().enumerate() {
        assert_eq!(u.cross(v), normal);
        p.extend([(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(a, b)| normal + u * a + v * b));
        n.extend([normal; 4]);
        let b = 4 * k as u32;
        t.extend([[b, b + 1, b + 2], [b, b + 2, b + 3]]);
    }
    mesh(p, n, t, material)
}

/// Map (c) A convex object never shadows its own lit faces. A flat-shaded
/// cube seen obliquely (orthographic, from (6, 5, 4)) shows its +x, +y
/// and +z faces. Under a directional light along −(1, 2, 3) all three face
/// the light (N·L = 1, 2, 3 over √14) and each shows exactly its lit
/// colour; every pixel is background or one of those three. Under a point
/// light at (3, 4, 5) as well, the Map image is bit for bit the image
/// without shadows drawn in Phong: no light is hidden anywhere.
#[test]
fn map_mode_a_convex_cube_does_not_shadow_its_lit_faces() {
    let m = Material { ks: Vec3::ZERO, ..FLOOR };
    let cube_scene = |light: Light, mode: ShadowMode| {
        let shading = if mode == ShadowMode::None { ShadingMode::Phong } else { ShadingMode::Flat };
        let mut s = map_scene(10.0, vec![light], vec![object(cube(m), Some(shading))]);
        s.shadows.mode = mode;
        s.camera = Camera {
            eye: Vec3::new(6.0, 5.0, 4.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            projection: Projection::Orthographic { height: 4.0, near: 0.5, far: 20.0 },
        };
        s
    };
    let sun = Light::Directional { direction: Vec3::new(-1.0, -2.0, -3.0), color: Vec3::ONE };
    let image = render_truth(&cube_scene(sun, ShadowMode::Map));
    let faces = [1.0, 2.0, 3.0].map(|c: f64| ambient(&m) + d(m.kd) * (c / 14f64.sqrt()));
    let mut seen = [0; 3];
    for j in 0..SIZE {
        for i in 0..SIZE {
            let c = image.pixel(i, j);
            if c == DVec3::ZERO {
                continue;
            }
            let k = faces.iter().position(|f| (c - *f).abs().max_element() < 1e-9);
            let k = k.unwrap_or_else(|| panic!("({i}, {j}): {c} is no lit face"));
            seen[k] += 1;
        }
    }
    assert!(seen.iter().all(|&n| n > 300), "{seen:?}");
    assert_eq!(image.rgb, render_truth(&cube_scene(sun, ShadowMode::None)).rgb);

    let bulb = point_light(Vec3::new(3.0, 4.0, 5.0), Vec3::ONE);
    let map = render_truth(&cube_scene(bulb, ShadowMode::Map));
    assert_eq!(map.rgb, render_truth(&cube_scene(bulb, ShadowMode::None)).rgb);
}
