//! Meshing: every scene triangle cut into patches of a stated size, each
//! an ideal diffuse reflector of constant radiosity (the course's patch).
//!
//! A triangle whose longest edge is L becomes k² patches, k = ⌈L / size⌉:
//! the k × k grid of its barycentric coordinates, k² similar triangles. A
//! patch's reflectance ρ is its material's kd, times its texture's mean
//! where it has one (four texels a patch: the centre and the midpoints
//! towards the corners), per channel; its emission E is the material's ke.
//! Patches keep the corners they share within an object, so that the
//! display can average the patches around a vertex.

use std::collections::HashMap;

use glam::{Vec2, Vec3};
use zline_trace::world::World;

use crate::error::RadiosityError;

/// Reflectances are clamped below this (ρ ≥ 1 would make the equation
/// diverge: a surface giving back more than it receives).
pub const MAX_REFLECTANCE: f32 = 0.99;

/// One patch: a triangle in world space of constant radiosity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Patch {
    /// The corners, counter-clockwise seen from the front.
    pub corners: [Vec3; 3],
    /// The unit normal (the front side, the one that emits and reflects).
    pub normal: Vec3,
    /// The centroid, where the hemicube stands.
    pub centre: Vec3,
    /// The area.
    pub area: f32,
    /// ρ per channel, in [0, [`MAX_REFLECTANCE`]].
    pub reflectance: Vec3,
    /// E per channel (radiant exitance of the surface's own light).
    pub emission: Vec3,
    /// The scene's lights reflected once: ρ times their irradiance,
    /// averaged over the patch (see [`crate::lights`]); 0 until lit.
    pub direct: Vec3,
    /// The index of the world triangle it was cut from.
    pub triangle: u32,
    /// The texture coordinates at the corners (zero without a texture).
    pub uvs: [Vec2; 3],
    /// Its corners' indices in [`Patches::vertices`].
    pub vertices: [u32; 3],
}

impl Patch {
    /// The patch with `corners` (its normal, centre and area derived from
    /// them), `None` for zero or non-finite area; `vertices`, `direct`,
    /// `triangle` and `uvs` all 0.
    pub fn new(corners: [Vec3; 3], reflectance: Vec3, emission: Vec3) -> Option<Patch> {
        let [p0, p1, p2] = corners;
        let cross = (p1 - p0).cross(p2 - p0);
        let area = 0.5 * cross.length();
        (area > 0.0 && area.is_finite()).then(|| Patch {
            corners,
            normal: cross / (2.0 * area),
            centre: (p0 + p1 + p2) / 3.0,
            area,
            reflectance,
            emission,
            direct: Vec3::ZERO,
            triangle: 0,
            uvs: [Vec2::ZERO; 3],
            vertices: [0; 3],
        })
    }

    /// What the patch gives out before any interreflection: its emission
    /// and the scene's lights reflected once, E + D.
    #[inline]
    pub fn source(&self) -> Vec3 {
        self.emission + self.direct
    }
}

/// The scene's patches and the corners they share.
#[derive(Clone, Debug, Default)]
pub struct Patches {
    /// The patches.
    pub patches: Vec<Patch>,
    /// Shared corners in world space.
    pub vertices: Vec<Vec3>,
    /// What was clamped, to be told the user.
    pub warnings: Vec<String>,
}

impl Patches {
    /// Cuts every triangle of `world` into patches no longer than `size`
    /// along an edge; refuses more than `max` patches before allocating
    /// them. Degenerate and non-finite triangles are left out.
    pub fn new(world: &World, size: f32, max: usize) -> Result<Patches, RadiosityError> {
        if !(size.is_finite() && size > 0.0) {
            return Err(RadiosityError::PatchSize(size));
        }
        let cuts = |t: &[Vec3; 3]| -> Option<f64> {
            let longest = (t[1] - t[0]).length().max((t[2] - t[1]).length()).max((t[0] - t[2]).length());
            let area = 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length();
            (longest.is_finite() && area > 0.0)
                .then(|| (f64::from(longest) / f64::from(size)).ceil().max(1.0))
        };
        // Counted in f64 first: a tiny size must not overflow or allocate.
        let total: f64 = world.triangles.iter().filter_map(cuts).map(|k| k * k).sum();
        if total > max as f64 {
            return Err(RadiosityError::TooManyPatches { size, patches: total, max });
        }
        let mut out = Patches::default();
        let mut shared: HashMap<(u32, [u32; 6]), u32> = HashMap::new();
        let (mut clamped, mut unlit) = (0usize, 0usize);
        for (index, t) in world.triangles.iter().enumerate() {
            let Some(k) = cuts(t) else { continue };
            let k = k as usize;
            let attributes = &world.attributes[index];
            let surface = &world.surfaces[attributes.surface as usize];
            let material = &surface.material;
            if !material.ke.is_finite() {
                return Err(RadiosityError::Emission { triangle: index, emission: material.ke });
            }
            let object = attributes.surface;
            let point = |i: usize, j: usize| {
                let (u, v) = (i as f32 / k as f32, j as f32 / k as f32);
                (t[0] + (t[1] - t[0]) * u + (t[2] - t[0]) * v, Vec2::new(u, v))
            };
            let uv_at = |b: Vec2| {
                let [a, bb, c] = attributes.uvs;
                a + (bb - a) * b.x + (c - a) * b.y
            };
            let mut corner = |p: Vec3, n: Vec3, out: &mut Patches| -> u32 {
                // Keyed by the point rounded to 2⁻¹⁶ of the patch size (the
                // same corner computed from two triangles meets itself) and
                // the normal to a quarter: corners are not shared across a
                // crease.
                let q = 65536.0 / size;
                let (p_key, n_key) = ((p * q).round(), (n * 4.0).round());
                let key =
                    // + 0.0 turns −0 into +0: one key for both zeros.
                    (object, [p_key.x, p_key.y, p_key.z, n_key.x, n_key.y, n_key.z].map(|v| (v + 0.0).to_bits()));
                *shared.entry(key).or_insert_with(|| {
                    out.vertices.push(p);
                    out.vertices.len() as u32 - 1
                })
            };
            let mut emit = |corners: [(Vec3, Vec2); 3], out: &mut Patches| {
                let Some(mut patch) =
                    Patch::new(corners.map(|c| c.0), Vec3::ZERO, material.ke.max(Vec3::ZERO))
                else {
                    return;
                };
                let mut kd = material.kd;
                if let Some(texture) = &surface.texture {
                    let mid = (corners[0].1 + corners[1].1 + corners[2].1) / 3.0;
                    let taps = [
                        mid,
                        (mid + corners[0].1) * 0.5,
                        (mid + corners[1].1) * 0.5,
                        (mid + corners[2].1) * 0.5,
                    ];
                    let mean = taps
                        .iter()
                        .map(|&b| {
                            let uv = uv_at(b);
                            texture.texture.sample(&texture.sampler, uv.x, uv.y, 0.0).truncate()
                        })
                        .sum::<Vec3>()
                        / 4.0;
                    kd *= mean;
                }
                let mut reflectance = kd;
                if !reflectance.is_finite() {
                    reflectance = Vec3::ZERO;
                    unlit += 1;
                }
                if reflectance.max_element() > MAX_REFLECTANCE || reflectance.min_element() < 0.0 {
                    reflectance = reflectance.clamp(Vec3::ZERO, Vec3::splat(MAX_REFLECTANCE));
                    clamped += 1;
                }
                patch.reflectance = reflectance;
                patch.triangle = index as u32;
                patch.uvs = corners.map(|c| uv_at(c.1));
                patch.vertices = patch.corners.map(|p| corner(p, patch.normal, out));
                out.patches.push(patch);
            };
            for i in 0..k {
                for j in 0..k - i {
                    emit([point(i, j), point(i + 1, j), point(i, j + 1)], &mut out);
                    if i + j + 1 < k {
                        emit([point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)], &mut out);
                    }
                }
            }
        }
        if clamped > 0 {
            out.warnings.push(format!(
                "{clamped} patches had a reflectance at or above 1 or below 0, clamped to [0, {MAX_REFLECTANCE}] (the radiosity equation converges only below 1)"
            ));
        }
        if unlit > 0 {
            out.warnings.push(format!("{unlit} patches had a non-finite reflectance, taken as 0"));
        }
        Ok(out)
    }

    /// The total emitted power Σ E·A (per channel).
    pub fn emitted(&self) -> Vec3 {
        self.patches.iter().map(|p| p.emission * p.area).sum()
    }

    /// The total source power Σ (E + D)·A (per channel): the emitted and
    /// the lights' first reflection.
    pub fn sourced(&self) -> Vec3 {
        self.patches.iter().map(|p| p.source() * p.area).sum()
    }
}
