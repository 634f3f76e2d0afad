//! The Whitted truth (SPEC §12): scenes with hand-computed answers (those
//! of `zline-trace`'s own hand tests, to 10⁻⁹), the fast tracer against
//! the truth on the built-in scenes in 8-bit steps away from silhouettes,
//! and thread-count independence.

use std::sync::Arc;
use std::time::Instant;

use glam::{DVec3, Mat4, Vec3};
use zline_pipeline::image::quantize_rgba;
use zline_scene::trace_options::{ShadowRays, TraceOptions};
use zline_scene::{Camera, Mesh, Object, Projection, RenderSettings, Scene};
use zline_scenes::{demo_scene, whitted_scene};
use zline_shading::{Light, Material, ToneMap};
use zline_truth::{trace_truth, TracedTruth, WhittedTruth, RAY_BUDGET};

/// A rectangle in the plane z = `z`, facing +z when `up` (counter-clockwise
/// seen from +z), else −z; split along the diagonal from (x.0, y.0).
fn square(x: (f32, f32), y: (f32, f32), z: f32, up: bool, material: Material) -> Object {
    let p =
        vec![Vec3::new(x.0, y.0, z), Vec3::new(x.1, y.0, z), Vec3::new(x.1, y.1, z), Vec3::new(x.0, y.1, z)];
    let t = if up { vec![[0, 1, 2], [0, 2, 3]] } else { vec![[0, 2, 1], [0, 3, 2]] };
    Object {
        mesh: Arc::new(Mesh::new("square", p, None, t, material).unwrap()),
        world_from_object: Mat4::IDENTITY,
        material: None,
        shading: None,
        cull_back_faces: false,
    }
}

fn black() -> Material {
    Material { ka: Vec3::ZERO, kd: Vec3::ZERO, ks: Vec3::ZERO, ..Material::DEFAULT }
}

fn glow(ke: Vec3) -> Material {
    Material { ke, ..black() }
}

/// The hand tests' scene: a camera at the origin looking down −z, white
/// ambient light, a dark grey background.
fn scene(objects: Vec<Object>, lights: Vec<Light>) -> Scene {
    Scene {
        environment: None,
        shadows: Default::default(),
        camera: Camera {
            eye: Vec3::ZERO,
            target: Vec3::NEG_Z,
            up: Vec3::Y,
            projection: Projection::Perspective { fovy_degrees: 90.0, near: 0.01, far: 100.0 },
        },
        background: Vec3::new(0.05, 0.05, 0.05),
        ambient: Vec3::ONE,
        lights,
        objects,
        settings: RenderSettings { width: 9, height: 9, ..RenderSettings::default() },
        fog: None,
    }
}

fn options(depth: u32, shadows: ShadowRays) -> TraceOptions {
    TraceOptions { max_depth: depth, min_weight: 0.0, shadows, ..TraceOptions::default() }
}

/// The tree sum along one ray from `origin`, traced to `depth`.
fn trace(s: &Scene, origin: DVec3, dir: DVec3, depth: u32, shadows: ShadowRays) -> DVec3 {
    WhittedTruth::new(s, &options(depth, shadows)).trace(origin, dir)
}

fn close(got: DVec3, want: DVec3) {
    assert!((got - want).abs().max_element() < 1e-9, "got {got}, want {want}");
}

/// A mirror facing the camera sends the ray back to a glowing square
/// behind the camera: the mirror's own colour plus kr ⊙ the glow; at
/// depth 1 the mirror's colour alone; a tilted ray the same.
#[test]
fn a_mirror_shows_what_is_behind_the_camera() {
    let ke = Vec3::new(0.2, 0.4, 0.6);
    let mirror = Material { ka: Vec3::splat(0.3), kr: Vec3::new(1.0, 0.5, 0.25), ..black() };
    let s = scene(
        vec![
            square((-1.0, 1.0), (-1.0, 1.0), -2.0, true, mirror),
            square((-5.0, 5.0), (-5.0, 5.0), 3.0, false, glow(ke)),
        ],
        vec![],
    );
    let f = ShadowRays::Filtered;
    let ka = DVec3::splat(f64::from(0.3f32));
    close(trace(&s, DVec3::ZERO, DVec3::NEG_Z, 1, f), ka);
    let want = ka + mirror.kr.as_dvec3() * ke.as_dvec3();
    close(trace(&s, DVec3::ZERO, DVec3::NEG_Z, 2, f), want);
    close(trace(&s, DVec3::ZERO, DVec3::new(0.49, 0.0, -1.0), 2, f), want);
    // Past the mirror: the background.
    close(trace(&s, DVec3::ZERO, DVec3::new(0.51, 0.0, -1.0), 2, f), DVec3::splat(0.05));
}

/// The mirror in front of a lit square: the square's diffuse and
/// specular terms (SPEC §5.1) at the reflected ray's hit, with the viewer
/// at the reflected ray's origin (the mirror), not at the camera.
#[test]
fn a_mirror_shows_a_lit_square_seen_from_the_mirror() {
    let kr = Vec3::new(0.9, 0.6, 0.3);
    let mirror = Material { kr, ..black() };
    let lit = Material { kd: Vec3::splat(0.8), ks: Vec3::splat(0.5), ns: 10.0, ..black() };
    let light = Light::Point {
        position: Vec3::new(0.0, 2.0, 2.0),
        color: Vec3::ONE,
        attenuation: Default::default(),
    };
    let s = scene(
        vec![
            square((-1.0, 1.0), (-1.0, 1.0), -2.0, true, mirror),
            square((-5.0, 5.0), (-5.0, 5.0), 3.0, false, lit),
        ],
        vec![light],
    );
    // The reflected ray leaves (0, 0, −2) along +z and hits (0, 0, 3):
    // N = −z, L = (0, 2, −1)/√5, V = −z (towards the mirror), f = 1.
    let n_dot_l = 1.0 / 5f64.sqrt();
    let l = DVec3::new(0.0, 2.0, -1.0) / 5f64.sqrt();
    let h = (l + DVec3::NEG_Z).normalize();
    let n_dot_h = h.dot(DVec3::NEG_Z);
    let (kd, ks) = (f64::from(0.8f32), 0.5);
    let seen = kd * n_dot_l + ks * n_dot_h.powf(10.0);
    let got = trace(&s, DVec3::ZERO, DVec3::NEG_Z, 2, ShadowRays::Filtered);
    close(got, kr.as_dvec3() * seen);
    // A tilted ray: the mirror at (0.4, 0, −2) sends it to (1.4, 0, 3),
    // where the viewer is the mirror's hit point, not the camera.
    let got = trace(&s, DVec3::ZERO, DVec3::new(0.2, 0.0, -1.0), 2, ShadowRays::Filtered);
    let at = DVec3::new(1.4, 0.0, 3.0);
    let v = (DVec3::new(0.4, 0.0, -2.0) - at).normalize();
    let l = (DVec3::new(0.0, 2.0, 2.0) - at).normalize();
    let seen = kd * l.dot(DVec3::NEG_Z) + ks * (l + v).normalize().dot(DVec3::NEG_Z).powf(10.0);
    close(got, kr.as_dvec3() * seen);
    let from_camera = (l - at.normalize()).normalize().dot(DVec3::NEG_Z).powf(10.0);
    assert!((from_camera - (l + v).normalize().dot(DVec3::NEG_Z).powf(10.0)).abs() > 1e-3, "{from_camera}");
}

/// A transparent pane (d = 0.25, η = 1) in front of a glowing wall: the
/// pane's colour times d plus the wall's times kt = 0.75.
#[test]
fn a_pane_without_refraction_blends_as_the_rasterizer_does() {
    let wall = Vec3::new(0.8, 0.2, 0.4);
    let pane = Material { ka: Vec3::new(0.2, 0.6, 1.0), opacity: 0.25, ..black() };
    let s = scene(
        vec![
            square((-1.0, 1.0), (-1.0, 1.0), -2.0, true, pane),
            square((-9.0, 9.0), (-9.0, 9.0), -6.0, true, glow(wall)),
        ],
        vec![],
    );
    let got = trace(&s, DVec3::ZERO, DVec3::NEG_Z, 2, ShadowRays::Filtered);
    close(got, 0.25 * pane.ka.as_dvec3() + 0.75 * wall.as_dvec3());
}

/// Through a glass slab 1 thick (η = 1.5) at 30°: the ray is displaced by
/// Snell's law and lands on a wall lit by a point light, whose diffuse
/// term at the landing point (computed by hand) is the pixel; and on the
/// red half of a two-coloured wall that the straight ray sees blue.
#[test]
fn a_glass_slab_displaces_the_ray_by_snells_law() {
    let angle = 30f64.to_radians();
    let inside = (angle.sin() / 1.5).asin();
    // Entry at z = −2, exit at z = −3, wall at z = −5.
    let refracted_x = 2.0 * angle.tan() + inside.tan() + 2.0 * angle.tan();
    let straight_x = 5.0 * angle.tan();
    let glass = |ior: f32| Material { opacity: 0.0, ior, ..black() };
    let slab = |ior: f32| {
        vec![
            square((-9.0, 9.0), (-9.0, 9.0), -2.0, true, glass(ior)),
            square((-9.0, 9.0), (-9.0, 9.0), -3.0, false, glass(ior)),
        ]
    };
    let dir = DVec3::new(angle.sin(), 0.0, -angle.cos());
    // A white diffuse wall under a light at (0, 0, −4.5): N·L at x.
    let wall = Material { kd: Vec3::ONE, ..black() };
    let light = Light::Point {
        position: Vec3::new(0.0, 0.0, -4.5),
        color: Vec3::ONE,
        attenuation: Default::default(),
    };
    let mut objects = slab(1.5);
    objects.push(square((-20.0, 20.0), (-9.0, 9.0), -5.0, true, wall));
    let got = trace(&scene(objects, vec![light]), DVec3::ZERO, dir, 4, ShadowRays::Filtered);
    close(got, DVec3::splat(0.5 / (refracted_x * refracted_x + 0.25).sqrt()));
    // Red where the refracted ray lands, blue where the straight one would.
    let (red, blue) = (Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0));
    let edge = (0.5 * (refracted_x + straight_x)) as f32;
    let walls = |ior: f32| {
        let mut o = slab(ior);
        o.push(square((-20.0, edge), (-9.0, 9.0), -5.0, true, glow(red)));
        o.push(square((edge, 20.0), (-9.0, 9.0), -5.0, true, glow(blue)));
        o
    };
    close(trace(&scene(walls(1.5), vec![]), DVec3::ZERO, dir, 4, ShadowRays::Filtered), red.as_dvec3());
    close(trace(&scene(walls(1.0), vec![]), DVec3::ZERO, dir, 4, ShadowRays::Filtered), blue.as_dvec3());
}

/// Leaving glass (η = 1.5) at 45° is beyond the critical angle (41.8°):
/// the transmitted share reflects back into the glass; at 30° it leaves.
#[test]
fn total_internal_reflection_turns_the_ray_back() {
    let (above, below) = (Vec3::new(0.0, 1.0, 0.0), Vec3::new(1.0, 0.5, 0.0));
    let glass = Material { opacity: 0.0, ior: 1.5, ..black() };
    let objects = vec![
        square((-50.0, 50.0), (-50.0, 50.0), -2.0, false, glass),
        square((-50.0, 50.0), (-50.0, 50.0), -4.0, true, glow(below)),
        square((-50.0, 50.0), (-50.0, 50.0), 2.0, false, glow(above)),
    ];
    let s = scene(objects, vec![]);
    let f = ShadowRays::Filtered;
    close(trace(&s, DVec3::ZERO, DVec3::new(1.0, 0.0, -1.0), 3, f), above.as_dvec3());
    close(trace(&s, DVec3::ZERO, DVec3::new(0.5, 0.0, -0.75f64.sqrt()), 3, f), below.as_dvec3());
}

/// A shadow ray through a pane of d = 0.4 passes kt = 0.6 (filtered) or
/// nothing (opaque); through two panes 0.6 · 0.5; through the diagonal
/// shared by a pane's two triangles, one crossing.
#[test]
fn shadow_rays_pass_kt_of_each_transparent_crossing() {
    let light = Light::Point {
        position: Vec3::new(0.0, 0.0, 5.0),
        color: Vec3::ONE,
        attenuation: Default::default(),
    };
    let wall = Material { kd: Vec3::ONE, ..black() };
    let pane = |d: f32| Material { opacity: d, ..black() };
    let origin = DVec3::new(0.0, 0.0, 0.5);
    let one = scene(
        vec![
            square((-9.0, 9.0), (-9.0, 9.0), -4.0, true, wall),
            square((-0.5, 0.5), (-0.5, 0.5), 1.0, true, pane(0.4)),
        ],
        vec![light],
    );
    close(trace(&one, origin, DVec3::NEG_Z, 1, ShadowRays::Filtered), DVec3::splat(1.0 - f64::from(0.4f32)));
    close(trace(&one, origin, DVec3::NEG_Z, 1, ShadowRays::Opaque), DVec3::ZERO);
    let two = scene(
        vec![
            square((-9.0, 9.0), (-9.0, 9.0), -4.0, true, wall),
            square((-0.5, 0.5), (-0.5, 0.5), 1.0, true, pane(0.4)),
            square((-0.5, 0.5), (-0.5, 0.5), 2.0, false, pane(0.5)),
        ],
        vec![light],
    );
    close(
        trace(&two, origin, DVec3::NEG_Z, 1, ShadowRays::Filtered),
        DVec3::splat((1.0 - f64::from(0.4f32)) * 0.5),
    );
    // The pane's diagonal runs from (−0.5, −0.5) to (0.5, 0.5); the
    // shadow ray from the wall at (0.2, 0.2, −4) to the light at
    // (0.2, 0.2, 5) crosses it exactly there.
    let diagonal_light = Light::Point {
        position: Vec3::new(0.2, 0.2, 5.0),
        color: Vec3::ONE,
        attenuation: Default::default(),
    };
    let mut s = one.clone();
    s.lights = vec![diagonal_light];
    close(
        trace(&s, DVec3::new(0.2, 0.2, 0.5), DVec3::NEG_Z, 1, ShadowRays::Filtered),
        DVec3::splat(1.0 - f64::from(0.4f32)),
    );
}

/// `square` at z = −2 with texture coordinates over [0, 1]² and a 2 × 2
/// diffuse map whose left column has alpha 0 and right column alpha 1,
/// read with the nearest texel (`zline-trace`'s alpha scenes).
fn alpha_square(material: Material, cutoff: Option<f32>, blend: bool) -> Object {
    use zline_shading::{Filter, Sampler, Texture};
    let mut o = square((-1.0, 1.0), (-1.0, 1.0), -2.0, true, material);
    let rgba = [[255, 255, 255, 0], [255, 255, 255, 255], [255, 255, 255, 0], [255, 255, 255, 255]].concat();
    let texture = Texture::from_rgba8(2, 2, &rgba).unwrap();
    let uvs = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(|(u, v)| glam::Vec2::new(u, v)).to_vec();
    let mesh = (*o.mesh).clone().with_uvs(uvs).unwrap().with_diffuse_map(zline_scene::TextureMap {
        texture: Arc::new(texture),
        sampler: Sampler { filter: Filter::Nearest, ..Sampler::default() },
        alpha_blend: blend,
        alpha_cutoff: cutoff,
    });
    o.mesh = Arc::new(mesh);
    o
}

/// A cut-out texel removes the surface: the ray goes on to the wall
/// behind at the same depth (depth 1 suffices), and shadow rays pass
/// there in both shadow modes; where alpha is above the cutoff the card
/// is opaque.
#[test]
fn cut_out_texels_let_rays_and_shadows_through() {
    let wall = Vec3::new(0.8, 0.2, 0.4);
    let card = Material { ka: Vec3::new(0.1, 0.5, 0.9), ..black() };
    let s = scene(
        vec![alpha_square(card, Some(0.5), false), square((-9.0, 9.0), (-9.0, 9.0), -6.0, true, glow(wall))],
        vec![],
    );
    let (left, right) = (DVec3::new(-0.25, 0.0, -1.0), DVec3::new(0.25, 0.0, -1.0));
    for shadows in [ShadowRays::Filtered, ShadowRays::Opaque] {
        close(trace(&s, DVec3::ZERO, left, 1, shadows), wall.as_dvec3());
        close(trace(&s, DVec3::ZERO, right, 1, shadows), card.ka.as_dvec3());
    }
    // A light between the card and the floor behind it lights the floor
    // where the shadow ray crosses the card's cut-out half (x = −0.25).
    let floor = Material { kd: Vec3::ONE, ..black() };
    let light = Light::Point {
        position: Vec3::new(0.0, 0.0, -1.0),
        color: Vec3::ONE,
        attenuation: Default::default(),
    };
    let mut s = scene(
        vec![alpha_square(card, Some(0.5), false), square((-9.0, 9.0), (-9.0, 9.0), -3.0, true, floor)],
        vec![light],
    );
    s.ambient = Vec3::ZERO;
    let lit = 2.0 / 4.25f64.sqrt();
    for shadows in [ShadowRays::Filtered, ShadowRays::Opaque] {
        close(trace(&s, DVec3::new(-0.5, 0.0, -2.5), DVec3::NEG_Z, 1, shadows), DVec3::splat(lit));
        close(trace(&s, DVec3::new(0.5, 0.0, -2.5), DVec3::NEG_Z, 1, shadows), DVec3::ZERO);
    }
}

/// A blending map's alpha multiplies the opacity: kt = 1 − d·alpha.
#[test]
fn a_blending_alpha_multiplies_the_opacity() {
    let wall = Vec3::new(0.8, 0.2, 0.4).as_dvec3();
    let pane = Material { ka: Vec3::new(0.2, 0.6, 1.0), opacity: 0.5, ..black() };
    let s = scene(
        vec![
            alpha_square(pane, None, true),
            square((-9.0, 9.0), (-9.0, 9.0), -6.0, true, glow(wall.as_vec3())),
        ],
        vec![],
    );
    let f = ShadowRays::Filtered;
    close(trace(&s, DVec3::ZERO, DVec3::new(-0.25, 0.0, -1.0), 2, f), wall);
    close(trace(&s, DVec3::ZERO, DVec3::new(0.25, 0.0, -1.0), 2, f), 0.5 * pane.ka.as_dvec3() + 0.5 * wall);
}

/// A ray that hits nothing sees the environment where the scene draws it
/// as its background (in reflections too), else the background colour:
/// a panorama of one colour per row, read bilinearly (rows clamp).
#[test]
fn misses_see_the_drawn_environment() {
    use zline_shading::{Environment, EnvironmentLight, Panorama};
    let rows = [
        Vec3::new(0.9, 0.1, 0.2),
        Vec3::new(0.3, 0.6, 0.1),
        Vec3::new(0.2, 0.2, 0.8),
        Vec3::new(0.5, 0.4, 0.3),
    ];
    let texels = rows.iter().flat_map(|&c| [c; 8]).collect();
    let (panorama, _) = Panorama::new(8, 4, texels).unwrap();
    let mut env = Environment::new(Arc::new(EnvironmentLight::new(panorama)));
    env.intensity = 0.5;
    let mirror = Material { kr: Vec3::ONE, ..black() };
    let mut s = scene(vec![square((-1.0, 1.0), (-1.0, 1.0), -2.0, true, mirror)], vec![]);
    s.ambient = Vec3::ZERO;
    s.environment = Some(env.clone());
    let f = ShadowRays::Filtered;
    close(trace(&s, DVec3::ZERO, DVec3::Y, 4, f), s.background.as_dvec3());
    env.background = true;
    s.environment = Some(env);
    // Straight up: the top row; straight down: the bottom row.
    close(trace(&s, DVec3::ZERO, DVec3::Y, 4, f), 0.5 * rows[0].as_dvec3());
    close(trace(&s, DVec3::ZERO, DVec3::NEG_Y, 4, f), 0.5 * rows[3].as_dvec3());
    // The mirror sends the ray back along +z, on the horizon: halfway
    // between the two middle rows.
    let horizon = 0.25 * (rows[1].as_dvec3() + rows[2].as_dvec3());
    close(trace(&s, DVec3::ZERO, DVec3::NEG_Z, 4, f), horizon);
}

/// A depth limit of a billion is clamped, and mirrors that pass half the
/// light between mirrors that pass none (kr + kt > 1, both children
/// bouncing) finish: each tree stops at the ray budget, and the fast
/// tracer cuts the same trees.
#[test]
fn a_billion_deep_tree_between_mirrors_stops_at_the_budget() {
    let half = Material { kr: Vec3::ONE, opacity: 0.5, ior: 1.0, ka: Vec3::splat(0.01), ..black() };
    let full = Material { kr: Vec3::ONE, ka: Vec3::splat(0.01), ..black() };
    let mut s = scene(
        vec![
            square((-1e3, 1e3), (-1e3, 1e3), -2.0, true, half),
            square((-1e3, 1e3), (-1e3, 1e3), 2.0, false, half),
            square((-1e3, 1e3), (-1e3, 1e3), -4.0, true, full),
            square((-1e3, 1e3), (-1e3, 1e3), 4.0, false, full),
        ],
        vec![],
    );
    s.settings.width = 4;
    s.settings.height = 4;
    let options = TraceOptions { max_depth: 1_000_000_000, min_weight: 0.0, ..TraceOptions::default() };
    let truth = WhittedTruth::new(&s, &options).render(false);
    assert_eq!(truth.budget_cut, 16, "every tree is cut");
    assert!(truth.rays <= 16 * u64::from(RAY_BUDGET), "{} rays", truth.rays);
    assert!(truth.image.rgb.iter().all(|c| c.is_finite()));
    let fast = zline_trace::render(&s, &options);
    assert_eq!(fast.work.budget_cut, 16, "trees, as the truth counts them");
    assert_eq!(fast.work.primary.rays + fast.work.secondary.rays, truth.rays);
    for (f, t) in fast.pixels.iter().zip(&truth.image.rgb) {
        assert!((f.as_dvec3() - *t).abs().max_element() < 1e-4 * t.max_element().max(1.0), "{f} vs {t}");
    }
}

/// The fast tracer's 8-bit image as `zline render --renderer raytrace`
/// writes it: the scene's tone mapping, then SPEC §10's quantization.
fn fast_rgb8(scene: &Scene, options: &TraceOptions) -> Vec<u8> {
    let traced = zline_trace::render(scene, options);
    let tone = scene.settings.tone_mapping;
    traced
        .pixels
        .iter()
        .flat_map(|&c| quantize_rgba(tone.apply(c).extend(1.0)).to_le_bytes()[..3].to_vec())
        .collect()
}

/// What a comparison found, for the assertion message and the report.
struct Comparison {
    pixels: usize,
    masked: usize,
    within_one: usize,
    worst: (u32, u32, [u8; 3], [u8; 3], i32),
    worst_anywhere: i32,
}

impl std::fmt::Display for Comparison {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (x, y, fast, truth, d) = self.worst;
        write!(
            f,
            "{} of {} pixels away from silhouettes ({:.2} %); within 1 step: {:.4} %; worst there ({x}, {y}): \
             fast {fast:?} truth {truth:?}, {d} steps; worst anywhere {} steps",
            self.masked,
            self.pixels,
            100.0 * self.masked as f64 / self.pixels as f64,
            100.0 * self.within_one as f64 / self.masked.max(1) as f64,
            self.worst_anywhere
        )
    }
}

/// The fast tracer against the truth in 8-bit steps, over the pixels the
/// truth's trees mark away from silhouettes.
fn compare(scene: &Scene, options: &TraceOptions) -> (Comparison, TracedTruth) {
    assert!(
        scene.settings.tone_mapping.operator == ToneMap::None && scene.settings.tone_mapping.exposure == 1.0,
        "the truth has no tone mapping"
    );
    let started = Instant::now();
    let truth = WhittedTruth::new(scene, options).render(true);
    let truth_time = started.elapsed();
    let fast = fast_rgb8(scene, options);
    let reference = truth.image.quantized_rgb8();
    let mask = truth.away_from_silhouettes().expect("trees recorded");
    let width = truth.image.width;
    let mut c = Comparison {
        pixels: mask.len(),
        masked: 0,
        within_one: 0,
        worst: (0, 0, [0; 3], [0; 3], 0),
        worst_anywhere: 0,
    };
    for (i, &away) in mask.iter().enumerate() {
        let f: [u8; 3] = fast[3 * i..3 * i + 3].try_into().unwrap();
        let t: [u8; 3] = reference[3 * i..3 * i + 3].try_into().unwrap();
        let d = (0..3).map(|k| (i32::from(f[k]) - i32::from(t[k])).abs()).max().unwrap_or(0);
        c.worst_anywhere = c.worst_anywhere.max(d);
        if !away {
            continue;
        }
        c.masked += 1;
        c.within_one += usize::from(d <= 1);
        if d > c.worst.4 {
            c.worst = (i as u32 % width, i as u32 / width, f, t, d);
        }
    }
    eprintln!(
        "{}×{}, {} samples a pixel: truth {:.2} s ({} rays, {} shadow rays); {c}",
        scene.settings.width,
        scene.settings.height,
        options.samples * options.samples,
        truth_time.as_secs_f64(),
        truth.rays,
        truth.shadow_rays
    );
    (c, truth)
}

fn assert_close_to_truth(name: &str, scene: &Scene, options: &TraceOptions) {
    let (c, _) = compare(scene, options);
    assert!(c.masked as f64 >= 0.5 * c.pixels as f64, "{name}: the mask is too small: {c}");
    assert!(c.within_one as f64 >= 0.999 * c.masked as f64, "{name}: {c}");
}

#[test]
fn the_fast_tracer_matches_the_truth_on_the_whitted_scene() {
    let mut s = whitted_scene();
    s.settings.width = 160;
    s.settings.height = 120;
    assert_close_to_truth("whitted 160×120", &s, &TraceOptions::default());
}

#[test]
fn the_fast_tracer_matches_the_truth_on_the_demo_scene() {
    let mut s = demo_scene();
    s.settings.width = 96;
    s.settings.height = 54;
    assert_close_to_truth("demo 96×54", &s, &TraceOptions::default());
}

/// 2 × 2 rays a pixel, opaque shadow rays: the regular grid's mean.
#[test]
fn the_fast_tracer_matches_the_truth_with_supersampling() {
    let mut s = demo_scene();
    s.settings.width = 64;
    s.settings.height = 36;
    let options = TraceOptions { samples: 2, shadows: ShadowRays::Opaque, ..TraceOptions::default() };
    assert_close_to_truth("demo 64×36, 2×2, opaque shadows", &s, &options);
}

#[test]
fn threads_do_not_change_the_truth() {
    let mut s = whitted_scene();
    s.settings.width = 48;
    s.settings.height = 36;
    let options = TraceOptions { samples: 2, ..TraceOptions::default() };
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| WhittedTruth::new(&s, &options).render(true))
    };
    let (one, three) = (run(1), run(3));
    assert!(one == three, "the traced truth differs between 1 and 3 threads");
    assert_eq!(trace_truth(&s, &options), one.image);
}

/// Non-finite and degenerate input, out-of-range options: no panic, and
/// the finite part of the scene still drawn.
#[test]
fn degenerate_input_never_panics() {
    let nan = Vec3::splat(f32::NAN);
    let weird = Material { kr: nan, ior: f32::NAN, opacity: f32::NAN, ..Material::DEFAULT };
    let positions = vec![
        Vec3::new(-1.0, -1.0, -2.0),
        Vec3::new(1.0, -1.0, -2.0),
        Vec3::new(0.0, 1.0, -2.0),
        nan,
        Vec3::new(0.5, 0.5, -2.0),
    ];
    let normals = vec![Vec3::Z, nan, Vec3::ZERO, Vec3::Z, Vec3::Z];
    let triangles = vec![[0, 1, 2], [0, 1, 3], [4, 4, 4], [0, 1, 9]];
    let mesh = crate::support::mesh(positions, normals, triangles, weird);
    let mut s = scene(vec![crate::support::object(mesh, None)], vec![]);
    s.lights = vec![
        Light::Point { position: nan, color: Vec3::ONE, attenuation: Default::default() },
        Light::Directional { direction: Vec3::ZERO, color: Vec3::ONE },
    ];
    s.settings.width = 16;
    s.settings.height = 12;
    for options in [
        TraceOptions { max_depth: 0, min_weight: f32::NAN, samples: 0, ..TraceOptions::default() },
        TraceOptions { max_depth: u32::MAX, min_weight: 0.0, samples: 99, ..TraceOptions::default() },
    ] {
        let image = trace_truth(&s, &options);
        assert_eq!(image.rgb.len(), 16 * 12);
    }
    s.camera.target = s.camera.eye;
    assert_eq!(trace_truth(&s, &TraceOptions::default()).rgb.len(), 16 * 12);
}

/// A textured Cook–Torrance metal: the texel multiplies the base colour,
/// so the highlight takes the texture's colour (SPEC §5.2), in both
/// tracers.
#[test]
fn the_fast_tracer_matches_the_truth_on_a_textured_metal() {
    use zline_scene::TextureMap;
    use zline_shading::{Distribution, Filter, Microfacet, Model, Sampler, Texture};
    let metal = Material {
        ka: Vec3::splat(0.8),
        kd: Vec3::splat(0.8),
        ks: Vec3::splat(0.5),
        model: Model::CookTorrance(Microfacet {
            metallic: 1.0,
            roughness: 0.4,
            distribution: Distribution::Ggx,
        }),
        ..Material::DEFAULT
    };
    let mut o = square((-1.0, 1.0), (-1.0, 1.0), -2.0, true, metal);
    let rgba = [[230, 40, 30, 255], [40, 220, 60, 255], [50, 60, 240, 255], [240, 230, 40, 255]].concat();
    let uvs = vec![glam::Vec2::ZERO, glam::Vec2::X, glam::Vec2::ONE, glam::Vec2::Y];
    let mesh = (*o.mesh).clone().with_uvs(uvs).unwrap().with_diffuse_map(TextureMap {
        texture: std::sync::Arc::new(Texture::from_rgba8(2, 2, &rgba).unwrap()),
        sampler: Sampler { filter: Filter::Nearest, ..Sampler::default() },
        alpha_blend: false,
        alpha_cutoff: None,
    });
    o.mesh = std::sync::Arc::new(mesh);
    let light = Light::Point {
        position: Vec3::new(0.3, 0.4, 0.5),
        color: Vec3::ONE,
        attenuation: Default::default(),
    };
    let mut s = scene(vec![o], vec![light]);
    (s.settings.width, s.settings.height) = (64, 64);
    assert_close_to_truth("textured metal", &s, &options(2, ShadowRays::Filtered));
}
