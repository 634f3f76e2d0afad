//! The scene's lights as sources (SPEC §13) against closed forms: a
//! directional light's cos θ, a shadow's share of a patch, Gauss's law for
//! a point light inside a closed room, and the power balance of a closed
//! room that reflects half of what it receives.

use std::f64::consts::PI;
use std::sync::Arc;

use glam::{Mat4, Vec3};
use zline_radiosity::{mesh, solve, Method, Options};
use zline_scene::{Camera, Mesh, Object, Projection, RenderSettings, Scene};
use zline_shading::{Attenuation, Light, Material};

const RHO: f32 = 0.5;

fn grey(rho: f32) -> Material {
    Material { ka: Vec3::ZERO, kd: Vec3::splat(rho), ks: Vec3::ZERO, ..Material::DEFAULT }
}

/// The quadrilateral a, b, c, d (counter-clockwise seen from its front).
fn quad(corners: [Vec3; 4], material: Material) -> Object {
    Object {
        mesh: Arc::new(
            Mesh::new("quad", corners.to_vec(), None, vec![[0, 1, 2], [0, 2, 3]], material).unwrap(),
        ),
        world_from_object: Mat4::IDENTITY,
        material: None,
        shading: None,
        cull_back_faces: false,
    }
}

/// The square |x|, |z| ≤ `half` at height `y`, facing +y.
fn floor(half: f32, y: f32) -> Object {
    let p = |x: f32, z: f32| Vec3::new(x * half, y, z * half);
    quad([p(-1.0, -1.0), p(-1.0, 1.0), p(1.0, 1.0), p(1.0, -1.0)], grey(RHO))
}

/// The six inner faces of the cube [−h, h]³, each facing the centre.
fn room(h: f32) -> Vec<Object> {
    let mut out = Vec::new();
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let (u, v) = (Vec3::AXES[(axis + 1) % 3], Vec3::AXES[(axis + 2) % 3]);
            let c = Vec3::AXES[axis] * sign * h;
            // Counter-clockwise around u × v = +axis; the face at +h must
            // face −axis, inwards.
            let mut corners = [c - h * u - h * v, c + h * u - h * v, c + h * u + h * v, c - h * u + h * v];
            if sign > 0.0 {
                corners.reverse();
            }
            out.push(quad(corners, grey(RHO)));
        }
    }
    out
}

fn scene(objects: Vec<Object>, lights: Vec<Light>) -> Scene {
    Scene {
        environment: None,
        shadows: Default::default(),
        camera: Camera {
            eye: Vec3::new(0.0, 0.0, 0.0),
            target: Vec3::NEG_Z,
            up: Vec3::Y,
            projection: Projection::Perspective { fovy_degrees: 90.0, near: 0.01, far: 100.0 },
        },
        background: Vec3::ZERO,
        ambient: Vec3::ZERO,
        lights,
        objects,
        settings: RenderSettings { width: 8, height: 8, ..RenderSettings::default() },
        fog: None,
    }
}

#[test]
fn a_directional_light_gives_rho_cos_theta_and_a_shadow_its_share() {
    // Light falling at 60° from the vertical: cos θ = 1/2.
    let slanted = Light::Directional { direction: Vec3::new(3f32.sqrt(), -1.0, 0.0), color: Vec3::ONE };
    let open = scene(vec![floor(1.0, 0.0)], vec![slanted]);
    let options = Options { patch_size: Some(0.25), ..Options::default() };
    let (patches, _) = mesh(&open, &options).unwrap();
    for p in &patches.patches {
        assert!((p.direct - Vec3::splat(RHO * 0.5)).abs().max_element() < 1e-6, "{:?}", p.direct);
    }
    // Straight down, with an opaque square over the middle (its edges
    // crossing the patches, 0.25 a side, at ±0.4): the
    // patches under it get nothing, those clear of it everything, and a
    // patch the shadow's edge crosses a share in quarters (four samples).
    let down = Light::Directional { direction: Vec3::NEG_Y, color: Vec3::ONE };
    let blocker = floor(0.4, 1.0);
    let shaded = scene(vec![floor(1.0, 0.0), blocker], vec![down]);
    let (patches, _) = mesh(&shaded, &options).unwrap();
    let (mut dark, mut lit, mut shared) = (0, 0, 0);
    for p in patches.patches.iter().filter(|p| p.centre.y == 0.0) {
        let share = p.direct.x / RHO;
        assert!([0.0, 0.25, 0.5, 0.75, 1.0].contains(&share), "{share} at {:?}", p.centre);
        let inside = p.corners.iter().all(|c| c.x.abs() <= 0.4 && c.z.abs() <= 0.4);
        let outside = p.corners.iter().all(|c| c.x.abs() >= 0.4 || c.z.abs() >= 0.4);
        match share {
            0.0 => dark += 1,
            1.0 => lit += 1,
            _ => shared += 1,
        }
        if inside {
            assert_eq!(share, 0.0, "under the blocker at {:?}", p.centre);
        } else if outside {
            assert_eq!(share, 1.0, "clear of the blocker at {:?}", p.centre);
        }
    }
    eprintln!("{dark} dark, {lit} lit, {shared} shared");
    assert!(dark > 0 && lit > 0 && shared > 0, "{dark} dark, {lit} lit, {shared} shared");
    // A face turned away from the light receives nothing.
    let away = Light::Directional { direction: Vec3::Y, color: Vec3::ONE };
    let (patches, _) = mesh(&scene(vec![floor(1.0, 0.0)], vec![away]), &options).unwrap();
    assert!(patches.patches.iter().all(|p| p.direct == Vec3::ZERO));
}

#[test]
fn a_point_light_in_a_closed_room_delivers_four_pi_times_its_intensity() {
    // Gauss's law: with f_att = 1/d² (every wall at d ≥ 2 > 1, where the
    // attenuation's clamp at 1 does not act) the irradiance I·cos θ / d²
    // integrates over any closed surface around the light to 4π·I.
    let bulb = Light::Point {
        position: Vec3::new(0.3, -0.2, 0.1),
        color: Vec3::ONE,
        attenuation: Attenuation::new(0.0, 0.0, 1.0),
    };
    let closed = scene(room(2.0), vec![bulb]);
    let options = Options { patch_size: Some(0.25), ..Options::default() };
    let (patches, _) = mesh(&closed, &options).unwrap();
    let received: f64 = patches.patches.iter().map(|p| f64::from(p.direct.x / RHO * p.area)).sum();
    let exact = 4.0 * PI;
    eprintln!("received {received:.6}, 4π = {exact:.6}");
    assert!(((received - exact) / exact).abs() < 5e-4, "{received} against 4π = {exact}");
    // Off, the lights give nothing, and the solve says nothing lights it.
    let off = Options { lights: false, ..options };
    let (patches, _) = mesh(&closed, &off).unwrap();
    assert!(patches.patches.iter().all(|p| p.direct == Vec3::ZERO));
    assert!(
        patches.warnings.iter().any(|w| w.contains("nothing lights the scene")),
        "{:?}",
        patches.warnings
    );
}

#[test]
fn a_closed_room_returns_the_first_reflection_over_one_minus_rho() {
    // Σ A·B = Σ A·(E + D) / (1 − ρ) in a closed room of uniform ρ: the
    // power balance, exact for progressive refinement with the ambient
    // term (each shot hands on ρ of what it shoots).
    let bulb = Light::Point {
        position: Vec3::new(0.5, 0.7, -0.4),
        color: Vec3::ONE,
        attenuation: Attenuation::NONE,
    };
    let closed = scene(room(2.0), vec![bulb]);
    for method in [Method::Progressive, Method::GaussSeidel] {
        let options = Options { patch_size: Some(1.0), method, tolerance: 1e-5, ..Options::default() };
        let solution = solve(&closed, &options).unwrap();
        let source: f64 = solution.patches.patches.iter().map(|p| f64::from(p.source().x * p.area)).sum();
        let total: f64 = solution
            .patches
            .patches
            .iter()
            .zip(&solution.radiosity)
            .map(|(p, b)| f64::from(b.x * p.area))
            .sum();
        let expected = source / (1.0 - f64::from(RHO));
        let error = (total - expected).abs() / expected;
        eprintln!("{}: Σ A·B {total:.6}, Σ A·S / (1 − ρ) {expected:.6}, error {error:.2e}", method.name());
        // The sweeps' rows sum to 1 but are reciprocal only to the
        // hemicube's point sampling (SPEC §13): 8.4·10⁻⁴ here.
        let within = if method == Method::Progressive { 1e-5 } else { 2e-3 };
        assert!(error < within, "{}: {total} against {expected}", method.name());
    }
}
