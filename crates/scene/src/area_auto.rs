//! The adaptive choice of an area light's samples: the fewest k × k whose
//! light differs from a dense 16 × 16 sampling by at most a tolerance, on
//! the surfaces the camera sees — so a scene models only the samples it
//! needs.
//!
//! The measure ([`choose_area_samples`]):
//! - **Probes**: up to [`PROBES`] points spread over the scene's triangles
//!   by area (a fixed low-discrepancy sequence: the same scene gives the
//!   same probes), kept when they fall inside the camera's view volume and
//!   no triangle hides them from the eye (the f64 test of [`Occluders`]).
//!   Each probe's normal is its triangle's, turned towards the eye.
//! - **Light at a probe**: per channel, Σ over the samples of
//!   colour/k² · max(0, N·L) · f_att(d) · seen — the diffuse term of SPEC
//!   §5 on a white surface (kd = 1), the largest a material with kd ≤ 1
//!   can show; specular and clamping are left out. `seen` is the light's
//!   visibility as the scene's shadow mode decides it: always 1 without
//!   shadows (the renderer models none, so the samples need not resolve
//!   them), the ray test against the non-receivers for a receiver of
//!   planar shadows, and against every other triangle with shadow maps.
//! - **Difference**: the root mean square, over probes and channels, of
//!   255 · (light with k × k − light with 16 × 16), in 8-bit steps. The
//!   choice is the smallest k whose difference is at most the tolerance.

use glam::{DVec3, DVec4};
use zline_shading::Light;

use crate::area::AreaLight;
use crate::limits::MAX_AREA_SAMPLES_PER_SIDE;
use crate::model::{Projection, Scene, ShadowMode};
use crate::occluders::{Occluders, TriangleId};

/// The most probes the measure uses.
pub const PROBES: usize = 512;

/// Candidate points tried to find the probes (those outside the view or
/// hidden from the eye are dropped).
const CANDIDATES: usize = 4 * PROBES;

/// What [`choose_area_samples`] decided, and why.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AreaChoice {
    /// Samples per side: the light becomes k × k point lights.
    pub per_side: u32,
    /// The difference of that sampling from the dense one (RMSE in 8-bit
    /// steps over the probes).
    pub rmse: f32,
    /// How many probes measured it (0: nothing visible lies in the view,
    /// and one sample is chosen).
    pub probes: usize,
    /// True when `max_per_side` stopped the search before the tolerance
    /// was met.
    pub capped: bool,
}

/// A probe: a visible surface point, its normal towards the eye, and the
/// triangle it lies on.
struct Probe {
    point: DVec3,
    normal: DVec3,
    on: TriangleId,
    /// Whether the light's visibility is tested at this probe.
    receives: bool,
}

/// The smallest k in 1..=`max_per_side` (at most
/// [`MAX_AREA_SAMPLES_PER_SIDE`]) whose sampling of `light` in `scene`
/// differs from the dense one by at most `tolerance` (see the module
/// documentation for the measure).
pub fn choose_area_samples(
    scene: &Scene,
    light: &AreaLight,
    tolerance: f32,
    max_per_side: u32,
) -> AreaChoice {
    let max_per_side = max_per_side.clamp(1, MAX_AREA_SAMPLES_PER_SIDE);
    let triangles = world_triangles(scene);
    let probes = probes(scene, &triangles);
    if probes.is_empty() {
        return AreaChoice { per_side: 1, rmse: 0.0, probes: 0, capped: false };
    }
    let casters = match scene.shadows.mode {
        ShadowMode::None => None,
        mode => Some(Occluders::new(
            triangles
                .iter()
                .filter(|(id, _)| mode == ShadowMode::Map || !scene.shadows.receives(id.object as usize))
                .copied(),
        )),
    };
    let dense = light_at(&probes, &light.sample(MAX_AREA_SAMPLES_PER_SIDE), casters.as_ref());
    let mut last = AreaChoice { per_side: 1, rmse: f32::INFINITY, probes: probes.len(), capped: false };
    for k in 1..=max_per_side {
        let sampled = light_at(&probes, &light.sample(k), casters.as_ref());
        let squares: f64 =
            sampled.iter().zip(&dense).map(|(a, b)| (255.0 * (*a - *b)).length_squared()).sum();
        let rmse = (squares / (3 * probes.len()) as f64).sqrt() as f32;
        last = AreaChoice { per_side: k, rmse, probes: probes.len(), capped: false };
        if rmse <= tolerance {
            return last;
        }
    }
    AreaChoice { capped: true, ..last }
}

/// Every finite, non-degenerate triangle of the scene in world space, f64.
fn world_triangles(scene: &Scene) -> Vec<(TriangleId, [DVec3; 3])> {
    let mut out = Vec::new();
    for (o, object) in scene.objects.iter().enumerate() {
        let m = object.world_from_object.as_dmat4();
        let positions: Vec<DVec3> =
            object.mesh.positions.iter().map(|p| m.transform_point3(p.as_dvec3())).collect();
        for (t, tri) in object.mesh.triangles.iter().enumerate() {
            let Some(corners) =
                tri.iter().map(|&i| positions.get(i as usize).copied()).collect::<Option<Vec<_>>>()
            else {
                continue;
            };
            let [a, b, c] = [corners[0], corners[1], corners[2]];
            let n = (b - a).cross(c - a);
            if n.is_finite() && n != DVec3::ZERO {
                out.push((TriangleId { object: o as u32, triangle: t as u32 }, [a, b, c]));
            }
        }
    }
    out
}

/// The probes: candidate points by area, kept when in view and seen.
fn probes(scene: &Scene, triangles: &[(TriangleId, [DVec3; 3])]) -> Vec<Probe> {
    let mut cumulative = Vec::with_capacity(triangles.len());
    let mut total = 0.0f64;
    for (_, [a, b, c]) in triangles {
        total += 0.5 * (*b - *a).cross(*c - *a).length();
        cumulative.push(total);
    }
    if !(total.is_finite() && total > 0.0) {
        return Vec::new();
    }
    let camera = &scene.camera;
    let aspect = scene.settings.width.max(1) as f32 / scene.settings.height.max(1) as f32;
    let clip_from_world = (camera.clip_from_eye(aspect) * camera.eye_from_world()).as_dmat4();
    let eye = camera.eye.as_dvec3();
    let forward = (camera.target - camera.eye).as_dvec3().normalize_or_zero();
    let orthographic = matches!(camera.projection, Projection::Orthographic { .. });
    let blockers = Occluders::new(triangles.iter().copied());
    let mut out = Vec::new();
    for i in 0..CANDIDATES {
        let u = (i as f64 + 0.5) / CANDIDATES as f64 * total;
        let index = cumulative.partition_point(|&c| c < u).min(triangles.len() - 1);
        let (on, [a, b, c]) = triangles[index];
        // The R2 sequence's point i, folded into the triangle.
        let (mut s, mut t) = (
            (0.5 + 0.754_877_666_246_692_7 * i as f64).fract(),
            (0.5 + 0.569_840_290_998_053_2 * i as f64).fract(),
        );
        if s + t > 1.0 {
            (s, t) = (1.0 - s, 1.0 - t);
        }
        let point = a + s * (b - a) + t * (c - a);
        let clip = clip_from_world * DVec4::from((point, 1.0));
        let inside =
            clip.w > 0.0 && clip.x.abs() <= clip.w && clip.y.abs() <= clip.w && clip.z.abs() <= clip.w;
        let to_eye = if orthographic { -forward } else { eye - point };
        let seen = if orthographic {
            !blockers.hides_direction(point, on, to_eye)
        } else {
            !blockers.hides_point(point, on, eye)
        };
        if !inside || !seen {
            continue;
        }
        let normal = (b - a).cross(c - a).normalize();
        let normal = if normal.dot(to_eye) < 0.0 { -normal } else { normal };
        let receives = scene.shadows.receives(on.object as usize);
        out.push(Probe { point, normal, on, receives });
        if out.len() == PROBES {
            break;
        }
    }
    out
}

/// Each probe's light (RGB) from `samples` (point lights).
fn light_at(probes: &[Probe], samples: &[Light], casters: Option<&Occluders>) -> Vec<DVec3> {
    probes
        .iter()
        .map(|p| {
            samples
                .iter()
                .map(|light| {
                    let Light::Point { position, color, attenuation } = *light else {
                        return DVec3::ZERO;
                    };
                    let to_light = position.as_dvec3() - p.point;
                    let d = to_light.length();
                    let cos = if d > 0.0 { p.normal.dot(to_light / d) } else { 0.0 };
                    // A NaN (a non-finite light) counts as facing away.
                    if cos.is_nan() || cos <= 0.0 {
                        return DVec3::ZERO;
                    }
                    let hidden = p.receives
                        && casters.is_some_and(|c| c.hides_point(p.point, p.on, position.as_dvec3()));
                    if hidden {
                        return DVec3::ZERO;
                    }
                    let f = f64::from(attenuation.factor(d as f32));
                    color.as_dvec3() * (cos * f)
                })
                .sum()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::{Mat4, Vec3};
    use zline_shading::Attenuation;

    use super::*;
    use crate::area::AreaShape;
    use crate::model::{Camera, Object, RenderSettings, ShadowPlane, Shadows};
    use crate::primitives::{cube, plane};

    /// A floor with a box on it under a square light, seen from above at
    /// an angle, with the given shadow mode.
    fn scene(mode: ShadowMode) -> (Scene, AreaLight) {
        let object = |mesh, m| Object {
            mesh: Arc::new(mesh),
            world_from_object: m,
            material: None,
            shading: None,
            cull_back_faces: false,
        };
        let floor = object(plane(8.0, 2), Mat4::IDENTITY);
        let block = object(cube(0.8), Mat4::from_translation(Vec3::new(0.3, 0.4, 0.0)));
        let planes = match mode {
            ShadowMode::Planar => vec![ShadowPlane::of_object(0, &floor).expect("a flat floor")],
            _ => Vec::new(),
        };
        let scene = Scene {
            environment: None,
            camera: Camera {
                eye: Vec3::new(0.0, 5.0, 6.0),
                target: Vec3::ZERO,
                up: Vec3::Y,
                projection: Projection::Perspective { fovy_degrees: 45.0, near: 0.5, far: 50.0 },
            },
            background: Vec3::ZERO,
            ambient: Vec3::ZERO,
            lights: Vec::new(),
            objects: vec![floor, block],
            settings: RenderSettings::default(),
            fog: None,
            shadows: Shadows { mode, planes, ..Shadows::default() },
        };
        let light = AreaLight {
            shape: AreaShape::Rect {
                center: Vec3::new(0.0, 3.0, 0.0),
                u: Vec3::new(0.7, 0.0, 0.0),
                v: Vec3::new(0.0, 0.0, 0.7),
            },
            color: Vec3::ONE,
            attenuation: Attenuation::NONE,
        };
        (scene, light)
    }

    /// The choice is the definition: its difference is within the
    /// tolerance, and one sample per side fewer is not.
    #[test]
    fn the_choice_is_the_fewest_samples_within_the_tolerance() {
        for mode in [ShadowMode::None, ShadowMode::Planar, ShadowMode::Map] {
            let (scene, light) = scene(mode);
            for tolerance in [0.25, 1.0, 4.0] {
                let choice = choose_area_samples(&scene, &light, tolerance, MAX_AREA_SAMPLES_PER_SIDE);
                assert!(!choice.capped && choice.rmse <= tolerance, "{mode:?} {tolerance}: {choice:?}");
                assert!(choice.probes > PROBES / 2, "{choice:?}");
                if choice.per_side > 1 {
                    let fewer = choose_area_samples(&scene, &light, tolerance, choice.per_side - 1);
                    assert!(fewer.capped && fewer.rmse > tolerance, "{mode:?} {tolerance}: {fewer:?}");
                }
            }
        }
    }

    /// Shadows need more samples than the unshadowed light; a tolerance of
    /// zero needs all 16 × 16 (the dense sampling itself).
    #[test]
    fn shadows_need_more_samples_and_zero_tolerance_all() {
        let k = |mode, tolerance| {
            let (scene, light) = scene(mode);
            choose_area_samples(&scene, &light, tolerance, MAX_AREA_SAMPLES_PER_SIDE).per_side
        };
        assert!(k(ShadowMode::None, 1.0) < k(ShadowMode::Planar, 1.0));
        assert!(k(ShadowMode::None, 1.0) < k(ShadowMode::Map, 1.0));
        assert_eq!(k(ShadowMode::Map, 0.0), MAX_AREA_SAMPLES_PER_SIDE);
    }

    /// Nothing in view: no probes, one sample.
    #[test]
    fn a_scene_out_of_view_takes_one_sample() {
        let (mut scene, light) = scene(ShadowMode::Map);
        scene.camera.target = Vec3::new(0.0, 10.0, 6.0);
        scene.camera.eye = Vec3::new(0.0, 10.0, 0.0);
        let choice = choose_area_samples(&scene, &light, 0.0, MAX_AREA_SAMPLES_PER_SIDE);
        assert_eq!(choice, AreaChoice { per_side: 1, rmse: 0.0, probes: 0, capped: false });
    }
}
