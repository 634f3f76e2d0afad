//! Scenes that stress numerical stability: the hard cases every renderer
//! must survive. Each comes with the outcome a correct zline gives; tests
//! and `cargo xtask report` render them and compare with the f64 truth.
//!
//! Most use a *pixel camera*: an orthographic camera whose view is exactly
//! the window, so world (x, y) = (x_win − W/2, H/2 − y_win) and positions
//! can be written in pixels ([`pixel_camera`], [`at_pixel`]).

use std::sync::Arc;

use glam::{Mat4, Vec3};
use zline_scene::{plane, Camera, DepthMode, Mesh, Object, Projection, RenderSettings, Scene};
use zline_shading::{Light, Material, ShadingMode};

/// A named hard case with the outcome it must have.
#[derive(Clone, Debug)]
pub struct HardCase {
    /// Short name (file-name safe).
    pub name: &'static str,
    /// What the scene stresses and what a correct render shows.
    pub expectation: &'static str,
    /// The scene.
    pub scene: Scene,
}

/// Every hard case, in a fixed order.
pub fn hard_cases() -> Vec<HardCase> {
    let case = |name, expectation, scene| HardCase { name, expectation, scene };
    vec![
        case("slivers", "90 triangles 1 px × 8000 px at 2° steps, mostly outside the window: coverage equals the exact edge functions'", slivers()),
        case("fan", "1000 triangles round one vertex: every sample of the disc covered once, as in the truth", fan(1000)),
        case("near_plane", "triangles crossing the near plane, with a vertex at w ≈ 0 and one behind the eye: no stray pixels, the clipped shapes of the truth", near_plane()),
        case("huge_coordinates", "vertices at ±10⁶ pixels: the visible parts as in the truth", huge_coordinates()),
        case("sub_pixel", "4000 triangles smaller than a pixel: each covers the sample centres it contains, nothing more", sub_pixel(4000)),
        case("t_junction", "a vertex on its neighbour's edge (a T-junction): the edge is not shared, so samples along it may be missed or hit twice; zline does not repair T-junctions", t_junction()),
        case("coplanar", "two overlapping triangles in one plane: equal depths tie, the strictly-less test keeps the first drawn (red) except where the two planes' roundings differ", coplanar()),
        case("parallel_planes", "two planes 10⁻⁴ apart at distance 1000: NC depth ties everywhere (the first drawn wins); reversed depth puts the nearer in front", parallel_planes(DepthMode::Normalized)),
        case("parallel_planes_reversed", "as parallel_planes with reversed-Z float depth: the nearer (green) plane everywhere", parallel_planes(DepthMode::ReversedFloat)),
        case("long_spans", "an 8192-pixel-wide image of a tilted, lit plane: depth and attributes on 8192-sample spans as in the truth", long_spans()),
    ]
}

/// An orthographic camera looking down −z whose view is exactly a window
/// `height` pixels high (its width follows from the image's aspect), one
/// world unit per pixel.
pub fn pixel_camera(height: u32) -> Camera {
    Camera {
        eye: Vec3::new(0.0, 0.0, 10.0),
        target: Vec3::ZERO,
        up: Vec3::Y,
        projection: Projection::Orthographic { height: height as f32, near: 1.0, far: 100.0 },
    }
}

/// The world position (z = 0) of window position (x, y) under
/// [`pixel_camera`].
pub fn at_pixel(width: u32, height: u32, x: f64, y: f64) -> Vec3 {
    Vec3::new((x - f64::from(width) / 2.0) as f32, (f64::from(height) / 2.0 - y) as f32, 0.0)
}

/// An ambient-lit colour: ka = the colour, no diffuse or specular, so a
/// flat-shaded triangle shows exactly `color` under white ambient light.
pub fn plain(color: Vec3) -> Material {
    Material { ka: color, kd: Vec3::ZERO, ks: Vec3::ZERO, ..Material::DEFAULT }
}

/// The first-drawn or farther surface of `coplanar` and `parallel_planes`
/// (8-bit: 217, 31, 31).
pub const RED: Vec3 = Vec3::new(0.85, 0.12, 0.12);
/// The second-drawn or nearer surface (8-bit: 31, 217, 31).
pub const GREEN: Vec3 = Vec3::new(0.12, 0.85, 0.12);

/// Eight distinct plain colours, each channel at least 0.05 of an 8-bit
/// step away from a rounding boundary (c·255 + ½ not within 0.05 of an
/// integer), so f32 and f64 renderers quantize them alike.
const PALETTE: [Vec3; 8] = [
    Vec3::new(0.88, 0.2, 0.2),
    Vec3::new(0.2, 0.8, 0.32),
    Vec3::new(0.25, 0.35, 0.95),
    Vec3::new(0.95, 0.85, 0.2),
    Vec3::new(0.8, 0.32, 0.85),
    Vec3::new(0.2, 0.85, 0.85),
    Vec3::new(0.6, 0.6, 0.6),
    Vec3::new(0.95, 0.55, 0.15),
];

/// A flat-shaded, plain-coloured object of one mesh whose normals are all
/// `normal`.
fn flat_object(
    name: &str,
    positions: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    normal: Vec3,
    color: Vec3,
    cull: bool,
) -> Object {
    let mesh = Mesh {
        name: name.into(),
        normals: vec![normal; positions.len()],
        positions,
        triangles,
        material: plain(color),
        uvs: Vec::new(),
        diffuse_map: None,
        tangents: Vec::new(),
        normal_map: None,
        colors: Vec::new(),
        surface_maps: Default::default(),
    };
    Object {
        mesh: Arc::new(mesh),
        world_from_object: Mat4::IDENTITY,
        material: None,
        shading: Some(ShadingMode::Flat),
        cull_back_faces: cull,
    }
}

/// One object per triangle, flat-shaded, culling off.
fn flat_objects(triangles: Vec<([Vec3; 3], Vec3)>) -> Vec<Object> {
    triangles
        .into_iter()
        .map(|(p, color)| {
            let normal = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or(Vec3::Z);
            flat_object("hard case", p.to_vec(), vec![[0, 1, 2]], normal, color, false)
        })
        .collect()
}

/// A flat, ambient-lit scene of `objects` seen by `camera`.
fn flat_scene(width: u32, height: u32, camera: Camera, objects: Vec<Object>) -> Scene {
    Scene {
        environment: None,
        shadows: Default::default(),
        camera,
        background: Vec3::ZERO,
        ambient: Vec3::ONE,
        lights: Vec::new(),
        objects,
        settings: RenderSettings { width, height, shading: ShadingMode::Flat, ..RenderSettings::default() },
        fog: None,
    }
}

/// Slivers 1 px wide at their base and 8000 px long, at 2° steps, each on a
/// line through a different point of a 512 × 512 window.
pub fn slivers() -> Scene {
    let (w, h) = (512, 512);
    let tris = (0..90)
        .map(|k| {
            let angle = (k as f64 * 2.0 + 0.7).to_radians();
            let (dir, perp) = ((angle.cos(), angle.sin()), (-angle.sin(), angle.cos()));
            let offset = (k as f64 - 45.0) * 5.3;
            let c = (256.0 + perp.0 * offset, 256.0 + perp.1 * offset);
            let p = |along: f64, across: f64| {
                at_pixel(w, h, c.0 + dir.0 * along + perp.0 * across, c.1 + dir.1 * along + perp.1 * across)
            };
            ([p(-4000.0, 0.0), p(4000.0, -0.5), p(4000.0, 0.5)], PALETTE[k % PALETTE.len()])
        })
        .collect();
    flat_scene(w, h, pixel_camera(h), flat_objects(tris))
}

/// `n` triangles round the centre of a 512 × 512 window (radius 250 px),
/// sharing their edges, one mesh.
pub fn fan(n: u32) -> Scene {
    let (w, h) = (512, 512);
    let n = n.max(3);
    let mut positions = vec![at_pixel(w, h, 256.0, 256.0)];
    for k in 0..n {
        let a = f64::from(k) / f64::from(n) * std::f64::consts::TAU;
        positions.push(at_pixel(w, h, 256.0 + 250.0 * a.cos(), 256.0 - 250.0 * a.sin()));
    }
    let triangles = (0..n).map(|k| [0, k + 1, (k + 1) % n + 1]).collect();
    let object = flat_object("fan", positions, triangles, Vec3::Z, PALETTE[0], true);
    flat_scene(w, h, pixel_camera(h), vec![object])
}

/// A perspective camera at the origin looking down −z (90°, near 0.5).
fn origin_camera(near: f32, far: f32) -> Camera {
    Camera {
        eye: Vec3::ZERO,
        target: Vec3::NEG_Z,
        up: Vec3::Y,
        projection: Projection::Perspective { fovy_degrees: 90.0, near, far },
    }
}

/// Triangles that cross the near plane (0.5), one with a vertex in the eye
/// plane (w = 10⁻⁷) and one with a vertex behind the eye, plus one wholly
/// behind the eye, which draws nothing.
pub fn near_plane() -> Scene {
    let tris = vec![
        ([Vec3::new(-2.0, -1.0, -3.0), Vec3::new(1.0, -0.5, 0.3), Vec3::new(0.5, 1.5, -4.0)], PALETTE[0]),
        ([Vec3::new(-1.5, 0.2, -1e-7), Vec3::new(1.8, 0.4, -2.0), Vec3::new(-0.3, 1.6, -2.5)], PALETTE[1]),
        ([Vec3::new(0.4, -1.2, 2.0), Vec3::new(1.6, -0.2, -1.5), Vec3::new(-0.8, -0.9, -1.0)], PALETTE[2]),
        ([Vec3::new(-1.0, -1.0, 1.0), Vec3::new(1.0, -1.0, 1.0), Vec3::new(0.0, 1.0, 1.0)], PALETTE[3]),
    ];
    flat_scene(256, 256, origin_camera(0.5, 50.0), flat_objects(tris))
}

/// Triangles with vertices about 10⁶ pixels outside a 256 × 256 window,
/// whose edges cross it.
pub fn huge_coordinates() -> Scene {
    let (w, h) = (256, 256);
    let p = |x: f64, y: f64| at_pixel(w, h, x, y);
    // At depths 0, −1 and −2 so no two tie: the first is in front.
    let at = |v: Vec3, z: f32| Vec3::new(v.x, v.y, z);
    let tris = vec![
        ([p(-1e6, 100.3), p(1e6, 60.7), p(3.0, 1e6)].map(|v| at(v, 0.0)), PALETTE[0]),
        ([p(-1e6, -1e6), p(1e6 + 0.25, -1e6), p(200.6, 1e6)].map(|v| at(v, -1.0)), PALETTE[1]),
        ([p(130.2, -1e6), p(1e6, 1e6), p(-1e6, 1e6 - 0.5)].map(|v| at(v, -2.0)), PALETTE[2]),
    ];
    flat_scene(w, h, pixel_camera(h), flat_objects(tris))
}

/// A small deterministic generator (64-bit LCG) for scenes with many
/// random-looking triangles.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `n` triangles each inside a 0.9-pixel box, scattered over 256 × 256.
pub fn sub_pixel(n: u32) -> Scene {
    let (w, h) = (256, 256);
    let mut rng = Lcg(7);
    let tris = (0..n)
        .map(|k| {
            let (x, y) = (rng.next() * 255.0, rng.next() * 255.0);
            let mut v = || at_pixel(w, h, x + rng.next() * 0.9, y + rng.next() * 0.9);
            ([v(), v(), v()], PALETTE[k as usize % PALETTE.len()])
        })
        .collect();
    flat_scene(w, h, pixel_camera(h), flat_objects(tris))
}

/// A square whose left half is one triangle and whose right half is two
/// triangles meeting at a point one third of the way along the shared
/// diagonal — a T-junction, in one mesh.
pub fn t_junction() -> Scene {
    let (w, h) = (256, 256);
    let p = |x: f64, y: f64| at_pixel(w, h, x, y);
    let (a, b, c) = (p(20.0, 236.0), p(236.0, 20.0), p(236.0, 236.0));
    let d = p(20.0, 20.0);
    let t = p(20.0 + 216.0 / 3.0, 236.0 - 216.0 / 3.0); // on a–b, not representable exactly
    let positions = vec![a, b, c, d, t];
    // Left: a, b, d (covers the upper-left half); right: a, c, t and t, c, b.
    let triangles = vec![[0, 3, 1], [0, 4, 2], [4, 1, 2]];
    let object = flat_object("t-junction", positions, triangles, Vec3::Z, PALETTE[3], false);
    flat_scene(w, h, pixel_camera(h), vec![object])
}

/// Two overlapping triangles in one tilted plane seen in perspective, red
/// drawn before green.
pub fn coplanar() -> Scene {
    let plane_point = |x: f32, y: f32| Vec3::new(x, y, -4.0 - 0.6 * x - 0.3 * y);
    let red = [plane_point(-2.0, -1.5), plane_point(1.5, -1.2), plane_point(-0.5, 1.8)];
    let green = [plane_point(-1.4, 1.2), plane_point(-1.0, -1.7), plane_point(1.9, 0.9)];
    let tris = vec![(red, RED), (green, GREEN)];
    flat_scene(256, 256, origin_camera(0.5, 50.0), flat_objects(tris))
}

/// Two squares filling the view, facing the camera 10⁻⁴ apart at distance
/// 1000 (near 0.1, far 10⁴): the far one red and drawn first, the near one
/// green.
pub fn parallel_planes(depth: DepthMode) -> Scene {
    let square = |z: f32| {
        let d = 1000.0;
        [(-d, -d), (d, -d), (d, d), (-d, d)].map(|(x, y)| Vec3::new(x, y, z))
    };
    let (far, near) = (square(-1000.0), square(-1000.0 + 1e-4));
    let tris = vec![
        ([far[0], far[1], far[2]], RED),
        ([far[0], far[2], far[3]], RED),
        ([near[0], near[1], near[2]], GREEN),
        ([near[0], near[2], near[3]], GREEN),
    ];
    let mut s = flat_scene(128, 128, origin_camera(0.1, 10_000.0), flat_objects(tris));
    s.settings.depth = depth;
    s
}

/// A lit, Phong-shaded plane receding from the camera in an 8192 × 48
/// window, so every span is 8192 samples long.
pub fn long_spans() -> Scene {
    let mut floor = plane(40.0, 8);
    floor.material = Material::plastic(Vec3::new(0.7, 0.6, 0.4), 0.5, 30.0);
    let object = Object {
        mesh: Arc::new(floor),
        world_from_object: Mat4::from_translation(Vec3::new(0.0, -1.0, -10.0)) * Mat4::from_rotation_z(0.15),
        material: None,
        shading: Some(ShadingMode::Phong),
        cull_back_faces: false,
    };
    Scene {
        environment: None,
        shadows: Default::default(),
        camera: Camera {
            eye: Vec3::ZERO,
            target: Vec3::new(0.0, -0.2, -1.0),
            up: Vec3::Y,
            projection: Projection::Perspective { fovy_degrees: 10.0, near: 0.5, far: 100.0 },
        },
        background: Vec3::ZERO,
        ambient: Vec3::splat(0.1),
        lights: vec![Light::Directional { direction: Vec3::new(-0.4, -1.0, -0.3), color: Vec3::ONE }],
        objects: vec![object],
        settings: RenderSettings {
            width: 8192,
            height: 48,
            shading: ShadingMode::Phong,
            ..RenderSettings::default()
        },
        fog: None,
    }
}
