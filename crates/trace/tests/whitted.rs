//! The Whitted tree against answers computed by hand (SPEC §12).

use std::sync::Arc;

use glam::{Mat4, Vec3};
use zline_scene::{Camera, Mesh, Object, Projection, RenderSettings, Scene};
use zline_shading::{Light, LightingModel, Material};
use zline_trace::accel::bvh::Bvh;
use zline_trace::ray::Ray;
use zline_trace::whitted::{ShadowRays, Tracer, Work};
use zline_trace::world::{Camera as Rays, World};
use zline_trace::{render, TraceOptions};

/// A square of side `2·half` in the plane z = `z`, facing +z when `up`
/// (counter-clockwise seen from +z), else −z.
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

/// The colour along one ray through `scene`, traced to `depth`.
fn trace(scene: &Scene, ray: Ray, depth: u32, shadows: ShadowRays) -> (Vec3, Work) {
    let world = World::new(scene);
    let bvh = Bvh::build(&world.triangles);
    let camera = Rays::new(scene);
    let lights = LightingModel { ambient: scene.ambient, lights: scene.lights.clone(), environment: None };
    let tracer = Tracer {
        world: &world,
        accel: &bvh,
        lights: &lights,
        camera: &camera,
        fog: scene.fog,
        background: scene.background,
        sky: scene.environment.as_ref().filter(|e| e.background),
        max_depth: depth,
        min_weight: 0.0,
        shadows,
    };
    let mut work = Work::default();
    let c = tracer.trace(ray, &mut work, &mut Vec::new());
    (c, work)
}

fn close(got: Vec3, want: Vec3) {
    assert!((got - want).abs().max_element() < 1e-5, "got {got}, want {want}");
}

/// A mirror (kr) facing the camera sends the ray back to a glowing square
/// behind the camera: the pixel is the mirror's own colour plus kr times
/// the glow; at depth 1 the mirror's colour alone.
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
    let ray = Ray::new(Vec3::ZERO, Vec3::NEG_Z);
    close(trace(&s, ray, 1, ShadowRays::Filtered).0, Vec3::splat(0.3));
    let (c, work) = trace(&s, ray, 2, ShadowRays::Filtered);
    close(c, Vec3::splat(0.3) + mirror.kr * ke);
    assert_eq!((work.primary.rays, work.secondary.rays, work.depth), (1, 1, 2));
    // A ray the mirror sends past the glow sees the background.
    let tilted = Ray::new(Vec3::ZERO, Vec3::new(0.49, 0.0, -1.0));
    let r = zline_trace::optics::reflect(-tilted.dir.normalize(), Vec3::Z);
    let at_glow = Vec3::new(0.49 * 2.0, 0.0, -2.0) + r * ((3.0 + 2.0) / r.z);
    assert!(at_glow.x < 5.0, "the reflected ray reaches the glow at {at_glow}");
    close(trace(&s, tilted, 2, ShadowRays::Filtered).0, Vec3::splat(0.3) + mirror.kr * ke);
}

/// A transparent pane (d = 0.25, η = 1) in front of a glowing wall: the
/// pane's colour times d plus the wall's times kt = 0.75, as the
/// rasterizer blends them.
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
    let (c, _) = trace(&s, Ray::new(Vec3::ZERO, Vec3::NEG_Z), 2, ShadowRays::Filtered);
    close(c, 0.25 * pane.ka + 0.75 * wall);
}

/// Through a glass slab 1 thick (η = 1.5) at 30°: the ray is displaced
/// by the refraction inside the slab, computed by hand with Snell's law,
/// and lands on the red half of a wall that the straight ray would see
/// blue; without refraction (η = 1) it lands on the blue half.
#[test]
fn a_glass_slab_displaces_the_ray_by_snells_law() {
    let (red, blue) = (Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0));
    let angle = 30f64.to_radians();
    let inside = (angle.sin() / 1.5).asin();
    // Entry at z = −2, exit at z = −3, wall at z = −5.
    let refracted_x = 2.0 * angle.tan() + inside.tan() + 2.0 * angle.tan();
    let straight_x = 5.0 * angle.tan();
    let edge = (0.5 * (refracted_x + straight_x)) as f32;
    let slab = |ior: f32| {
        let glass = Material { opacity: 0.0, ior, ..black() };
        vec![
            square((-9.0, 9.0), (-9.0, 9.0), -2.0, true, glass),
            square((-9.0, 9.0), (-9.0, 9.0), -3.0, false, glass),
            square((-20.0, edge), (-9.0, 9.0), -5.0, true, glow(red)),
            square((edge, 20.0), (-9.0, 9.0), -5.0, true, glow(blue)),
        ]
    };
    let ray = Ray::new(Vec3::ZERO, Vec3::new(angle.sin() as f32, 0.0, -angle.cos() as f32));
    close(trace(&scene(slab(1.5), vec![]), ray, 4, ShadowRays::Filtered).0, red);
    close(trace(&scene(slab(1.0), vec![]), ray, 4, ShadowRays::Filtered).0, blue);
}

/// Leaving glass (η = 1.5) at 45° is beyond the critical angle (41.8°):
/// the transmitted share reflects instead, back into the glass.
#[test]
fn total_internal_reflection_turns_the_ray_back() {
    let (above, below) = (Vec3::new(0.0, 1.0, 0.0), Vec3::new(1.0, 0.5, 0.0));
    let glass = Material { opacity: 0.0, ior: 1.5, ..black() };
    // The camera is inside the glass: the pane at z = −2 faces away from
    // it (its outside is −z), so the ray leaves the glass there.
    let objects = vec![
        square((-50.0, 50.0), (-50.0, 50.0), -2.0, false, glass),
        square((-50.0, 50.0), (-50.0, 50.0), -4.0, true, glow(below)),
        square((-50.0, 50.0), (-50.0, 50.0), 2.0, false, glow(above)),
    ];
    let s = scene(objects, vec![]);
    let steep = Ray::new(Vec3::ZERO, Vec3::new(1.0, 0.0, -1.0));
    close(trace(&s, steep, 3, ShadowRays::Filtered).0, above);
    // At 30° (below the critical angle) it leaves and sees the far wall.
    let shallow = Ray::new(Vec3::ZERO, Vec3::new(0.5, 0.0, -(0.75f32).sqrt()));
    close(trace(&s, shallow, 3, ShadowRays::Filtered).0, below);
}

/// No acne: a floor under a directional light, at scales from 10⁻³ to
/// 10⁵ and far from the origin, shows one colour everywhere (a shadow
/// ray that hit its own floor would darken a pixel).
#[test]
fn shadow_rays_never_hit_their_own_surface() {
    let light = Light::Directional { direction: Vec3::new(0.3, -1.0, -0.2), color: Vec3::ONE };
    let floor = Material { ka: Vec3::ZERO, kd: Vec3::splat(0.8), ks: Vec3::ZERO, ..Material::DEFAULT };
    for (scale, offset) in [(1e-3f32, 0.0f32), (1.0, 0.0), (1.0, 1e4), (1e3, 0.0), (1e5, 3e5)] {
        let at = Vec3::new(offset, offset, -offset);
        let positions = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .map(|(x, z)| at + scale * Vec3::new(50.0 * x, -1.0, 50.0 * z - 40.0));
        let mesh = Mesh::new("floor", positions.to_vec(), None, vec![[0, 2, 1], [0, 3, 2]], floor).unwrap();
        let mut s = scene(
            vec![Object {
                mesh: Arc::new(mesh),
                world_from_object: Mat4::IDENTITY,
                material: None,
                shading: None,
                cull_back_faces: false,
            }],
            vec![light],
        );
        s.camera.eye = at;
        s.camera.target = at + Vec3::new(0.0, -0.4, -1.0);
        if let Projection::Perspective { near, far, .. } = &mut s.camera.projection {
            *near = 0.01 * scale;
            *far = 500.0 * scale;
        }
        s.settings.width = 64;
        s.settings.height = 48;
        let options = TraceOptions { shadows: ShadowRays::Opaque, ..TraceOptions::default() };
        let image = render(&s, &options);
        let lit = floor.kd * light_n_dot_l(light);
        let floor_pixels: Vec<Vec3> = image.pixels.iter().copied().filter(|&c| c != s.background).collect();
        assert!(floor_pixels.len() > 1000, "scale {scale}: {} floor pixels", floor_pixels.len());
        for c in floor_pixels {
            assert!(
                (c - lit).abs().max_element() < 1e-5,
                "scale {scale} offset {offset}: {c} instead of {lit}"
            );
        }
        assert!(image.work.shadow.rays > 1000);
    }
}

fn light_n_dot_l(light: Light) -> f32 {
    let Light::Directional { direction, .. } = light else { unreachable!() };
    Vec3::Y.dot(-direction.normalize())
}

/// A shadow ray through a pane of d = 0.4 passes kt = 0.6 of the light
/// (filtered), or none (opaque).
#[test]
fn shadow_rays_pass_kt_of_each_transparent_occluder() {
    let light = Light::Point {
        position: Vec3::new(0.0, 0.0, 5.0),
        color: Vec3::ONE,
        attenuation: Default::default(),
    };
    let wall = Material { ka: Vec3::ZERO, kd: Vec3::ONE, ks: Vec3::ZERO, ..Material::DEFAULT };
    let pane = Material { opacity: 0.4, ..black() };
    let objects = vec![
        square((-9.0, 9.0), (-9.0, 9.0), -4.0, true, wall),
        // Beside the camera ray, between the wall and the light.
        square((-0.5, 0.5), (-0.5, 0.5), 1.0, true, pane),
    ];
    let s = scene(objects, vec![light]);
    // The ray starts beyond the pane (z = 0.5 < 1) and meets only the wall;
    // the wall's shadow ray to the light crosses the pane.
    let ray = Ray::new(Vec3::new(0.0, 0.0, 0.5), Vec3::NEG_Z);
    close(trace(&s, ray, 1, ShadowRays::Filtered).0, Vec3::splat(0.6));
    close(trace(&s, ray, 1, ShadowRays::Opaque).0, Vec3::ZERO);
}

/// A depth limit of a billion is clamped with a warning, and two facing
/// mirrors still finish: the tree is walked without recursion and cut by
/// the ray budget.
#[test]
fn a_billion_deep_tree_between_two_mirrors_finishes() {
    let mirror = Material { kr: Vec3::ONE, opacity: 0.5, ior: 1.0, ..black() };
    let mut s = scene(
        vec![
            square((-9.0, 9.0), (-9.0, 9.0), -2.0, true, mirror),
            square((-9.0, 9.0), (-9.0, 9.0), 2.0, false, mirror),
        ],
        vec![],
    );
    s.settings.width = 4;
    s.settings.height = 4;
    let image =
        render(&s, &TraceOptions { max_depth: 1_000_000_000, min_weight: 0.0, ..TraceOptions::default() });
    assert!(image.warnings.iter().any(|w| w.contains("depth")), "{:?}", image.warnings);
    assert!(image.pixels.iter().all(|c| c.is_finite()));
}

/// The image does not depend on the number of threads.
#[test]
fn threads_do_not_change_the_image() {
    let glass = Material { ka: Vec3::splat(0.1), opacity: 0.3, ior: 1.4, kr: Vec3::splat(0.2), ..black() };
    let light = Light::Point {
        position: Vec3::new(1.0, 2.0, 1.0),
        color: Vec3::ONE,
        attenuation: Default::default(),
    };
    let mut s = scene(
        vec![
            square((-1.0, 1.0), (-1.0, 1.0), -2.0, true, glass),
            square((-9.0, 9.0), (-9.0, 9.0), -5.0, true, Material::DEFAULT),
        ],
        vec![light],
    );
    s.settings.width = 40;
    s.settings.height = 30;
    let options = TraceOptions { samples: 2, ..TraceOptions::default() };
    let run = |threads| {
        rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(|| render(&s, &options))
    };
    let (one, three) = (run(1), run(3));
    assert_eq!(one.pixels, three.pixels);
    assert_eq!(one.work, three.work);
}

/// A ray that hits nothing sees the environment when the scene draws it
/// as its background, in reflections too; else the background colour.
#[test]
fn misses_see_the_drawn_environment() {
    use zline_shading::{Environment, EnvironmentLight, Panorama};
    let mirror = Material { kr: Vec3::ONE, ..black() };
    let mut s = scene(vec![square((-1.0, 1.0), (-1.0, 1.0), -2.0, true, mirror)], vec![]);
    s.ambient = Vec3::ZERO;
    let mut env = Environment::new(Arc::new(EnvironmentLight::new(Panorama::sky(64, 32))));
    env.intensity = 0.5;
    let up = Ray::new(Vec3::ZERO, Vec3::new(0.2, 1.0, 0.1));
    let at_mirror = Ray::new(Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0));
    s.environment = Some(env.clone());
    let (drawn, _) = trace(&s, up, 4, ShadowRays::Filtered);
    assert_eq!(drawn, s.background, "the environment is not drawn unless asked");
    env.background = true;
    s.environment = Some(env.clone());
    let (drawn, _) = trace(&s, up, 4, ShadowRays::Filtered);
    assert_eq!(drawn, env.background_radiance(up.dir.normalize()));
    // The mirror sends the ray straight back: the sky behind the camera.
    let (seen, _) = trace(&s, at_mirror, 4, ShadowRays::Filtered);
    let back = env.background_radiance(Vec3::Z);
    assert!((seen - back).abs().max_element() < 1e-5, "{seen} against {back}");
}

/// `square` with texture coordinates over [0, 1]² and a 2 × 2 diffuse map
/// whose left column has alpha 0 and right column alpha 1, read with the
/// nearest texel.
fn alpha_square(material: Material, cutoff: Option<f32>, blend: bool) -> Object {
    use zline_shading::{Filter, Sampler, Texture};
    let mut o = square((-1.0, 1.0), (-1.0, 1.0), -2.0, true, material);
    let rgba = [[255, 255, 255, 0], [255, 255, 255, 255], [255, 255, 255, 0], [255, 255, 255, 255]].concat();
    let texture = Texture::from_rgba8(2, 2, &rgba).unwrap();
    let uvs = vec![
        glam::Vec2::new(0.0, 0.0),
        glam::Vec2::new(1.0, 0.0),
        glam::Vec2::new(1.0, 1.0),
        glam::Vec2::new(0.0, 1.0),
    ];
    let mesh = (*o.mesh).clone().with_uvs(uvs).unwrap().with_diffuse_map(zline_scene::TextureMap {
        texture: Arc::new(texture),
        sampler: Sampler { filter: Filter::Nearest, ..Sampler::default() },
        alpha_blend: blend,
        alpha_cutoff: cutoff,
    });
    o.mesh = Arc::new(mesh);
    o
}

/// A cut-out texel removes the surface: the ray goes on to the wall behind
/// (the same ray, not a deeper one), and shadow rays pass there in both
/// shadow modes; where alpha is above the cutoff the square is opaque.
#[test]
fn cut_out_texels_let_rays_and_shadows_through() {
    let wall = Vec3::new(0.8, 0.2, 0.4);
    let card = Material { ka: Vec3::new(0.1, 0.5, 0.9), ..black() };
    let s = scene(
        vec![alpha_square(card, Some(0.5), false), square((-9.0, 9.0), (-9.0, 9.0), -6.0, true, glow(wall))],
        vec![],
    );
    let left = Ray::new(Vec3::ZERO, Vec3::new(-0.25, 0.0, -1.0));
    let right = Ray::new(Vec3::ZERO, Vec3::new(0.25, 0.0, -1.0));
    for shadows in [ShadowRays::Filtered, ShadowRays::Opaque] {
        let (c, work) = trace(&s, left, 1, shadows);
        close(c, wall);
        assert_eq!((work.primary.rays, work.depth), (2, 1), "one camera ray continued, depth 1");
        close(trace(&s, right, 1, shadows).0, card.ka);
    }
    // A light in front of the card lights the floor behind it through the
    // cut-out half only: rays from between the card and the floor look at
    // floor points whose shadow rays cross the card at x = ∓0.25.
    let floor = Material { kd: Vec3::ONE, ..black() };
    let position = Vec3::new(0.0, 0.0, -1.0);
    let light = Light::Point { position, color: Vec3::ONE, attenuation: Default::default() };
    let mut s = scene(
        vec![alpha_square(card, Some(0.5), false), square((-9.0, 9.0), (-9.0, 9.0), -3.0, true, floor)],
        vec![light],
    );
    s.ambient = Vec3::ZERO;
    let lit = (position - Vec3::new(-0.5, 0.0, -3.0)).normalize().z;
    for shadows in [ShadowRays::Filtered, ShadowRays::Opaque] {
        let through = trace(&s, Ray::new(Vec3::new(-0.5, 0.0, -2.5), Vec3::NEG_Z), 1, shadows).0;
        let blocked = trace(&s, Ray::new(Vec3::new(0.5, 0.0, -2.5), Vec3::NEG_Z), 1, shadows).0;
        close(through, Vec3::splat(lit));
        close(blocked, Vec3::ZERO);
    }
}

/// A blending map's alpha multiplies the opacity: kt = 1 − d·alpha.
#[test]
fn a_blending_alpha_multiplies_the_opacity() {
    let wall = Vec3::new(0.8, 0.2, 0.4);
    let pane = Material { ka: Vec3::new(0.2, 0.6, 1.0), opacity: 0.5, ..black() };
    let s = scene(
        vec![alpha_square(pane, None, true), square((-9.0, 9.0), (-9.0, 9.0), -6.0, true, glow(wall))],
        vec![],
    );
    let left = trace(&s, Ray::new(Vec3::ZERO, Vec3::new(-0.25, 0.0, -1.0)), 2, ShadowRays::Filtered).0;
    let right = trace(&s, Ray::new(Vec3::ZERO, Vec3::new(0.25, 0.0, -1.0)), 2, ShadowRays::Filtered).0;
    close(left, wall);
    close(right, 0.5 * pane.ka + 0.5 * wall);
}
