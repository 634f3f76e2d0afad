//! The scene's lights as sources (SPEC §13). Point, spot and directional
//! lights — and area lights, which a scene holds as their point samples
//! (SPEC §5) — are not surfaces, so they are shot once, first, before any
//! patch shoots: each patch receives the light's irradiance Il·f_att·cos θ
//! (the local model's diffuse factor, SPEC §5, with a spot's cone) where
//! the light is seen from it, and reflects ρ times that. This first
//! reflection, D_i, joins the patch's emission as its source,
//! S_i = E_i + D_i, and the solvers carry it on from there.
//!
//! D_i is the mean over four points of the patch (its centroid and the
//! points halfway from it to each corner), so that a shadow's edge
//! crossing a patch gives a share of the light, not all or nothing. A
//! light is seen from a point when no triangle of the world crosses the
//! segment to it (the ray towards a directional light): the f64 test of
//! [`Occluders`], the one the truth's shadows use. Only a patch's front
//! side receives.

use glam::Vec3;
use rayon::prelude::*;
use zline_scene::{Occluders, TriangleId};
use zline_shading::Light;
use zline_trace::world::World;

use crate::patch::Patch;

/// Points of a patch where the lights are sampled: barycentric weights of
/// its corners (the centroid, then halfway from it to each corner).
const SAMPLES: [[f32; 3]; 4] = [
    [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0],
    [2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0],
    [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
    [1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0],
];

/// The world's triangles as occluders, each known by its world index.
pub fn occluders(world: &World) -> Occluders {
    Occluders::new(
        world
            .triangles
            .iter()
            .enumerate()
            .map(|(i, t)| (TriangleId { object: 0, triangle: i as u32 }, t.map(|p| p.as_dvec3()))),
    )
}

/// The irradiance `lights` give the point `at` of world triangle
/// `triangle`, whose front faces along the unit `normal`: Σ Il·f_att·cos θ
/// over the lights seen from it.
pub fn irradiance(lights: &[Light], occluders: &Occluders, at: Vec3, normal: Vec3, triangle: u32) -> Vec3 {
    let on = TriangleId { object: 0, triangle };
    let point = at.as_dvec3();
    let mut sum = Vec3::ZERO;
    for light in lights {
        let Some((to_light, intensity)) = light.incident(at) else { continue };
        let cos = normal.dot(to_light);
        if cos.is_nan() || cos <= 0.0 || intensity == Vec3::ZERO {
            continue;
        }
        let hidden = match light.position() {
            Some(position) => occluders.hides_point(point, on, position.as_dvec3()),
            None => occluders.hides_direction(point, on, to_light.as_dvec3().normalize()),
        };
        if !hidden {
            sum += intensity * cos;
        }
    }
    sum
}

/// Sets every patch's [`Patch::direct`]: ρ times the mean irradiance of
/// `lights` over its four sample points, in parallel (each patch's value
/// the same whatever the thread count). Non-finite results are taken as 0.
pub fn light(patches: &mut [Patch], world: &World, lights: &[Light]) {
    if lights.is_empty() {
        return;
    }
    let occluders = occluders(world);
    patches.par_iter_mut().for_each(|p| {
        let [a, b, c] = p.corners;
        let mean = SAMPLES
            .iter()
            .map(|w| irradiance(lights, &occluders, w[0] * a + w[1] * b + w[2] * c, p.normal, p.triangle))
            .sum::<Vec3>()
            / SAMPLES.len() as f32;
        let direct = p.reflectance * mean;
        p.direct = if direct.is_finite() { direct } else { Vec3::ZERO };
    });
}
