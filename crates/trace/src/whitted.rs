//! The Whitted model (SPEC §12): at each hit the local model with a
//! shadow ray per light, plus a reflected ray weighted by kr and a
//! transmitted ray weighted by kt = 1 − d, refracted by the course's
//! formula ([`crate::optics`]), or reflected where the radicand says total
//! internal reflection.
//!
//! The ray tree is walked with an explicit stack, not recursion: a pixel's
//! colour is the sum over the tree's nodes of each node's path weight (the
//! product of the kr and kt on the way) times its local colour, so the
//! nodes can be taken in any order, and a depth limit of a billion costs
//! no thread stack. A branch ends at the depth limit, where its weight
//! falls below the cutoff, or when the pixel's ray budget is spent.

use glam::Vec3;
use zline_shading::{Fog, FogCoordinate, Light, LightingModel, Material, Model};

use crate::accel::{Accelerator, Counters};
use crate::optics::{reflect, refract};
use crate::ray::{offset_origin, Hit, Ray};
use crate::world::{Camera, World};

pub use zline_scene::trace_options::ShadowRays;

/// Rays per primary ray at most (the tree's nodes): the bound on a
/// pixel's work whatever the depth limit and the weights (a kr + kt above
/// 1 would otherwise let a tree grow as 2^depth).
pub const RAY_BUDGET: u32 = 1 << 12;

/// Hits of one surface along a shadow ray closer than this (relative to
/// the ray parameter) are one crossing: where a ray passes through an edge
/// or a corner, the watertight test reports each triangle that meets
/// there, at t equal up to rounding.
pub const SAME_CROSSING: f32 = 1e-5;

/// Work done, by ray kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Work {
    /// Camera rays.
    pub primary: Counters,
    /// Reflected and transmitted rays.
    pub secondary: Counters,
    /// Shadow rays.
    pub shadow: Counters,
    /// The deepest node reached (1: the camera ray's hit).
    pub depth: u32,
    /// Trees cut by [`RAY_BUDGET`].
    pub budget_cut: u64,
}

impl std::ops::Add for Work {
    type Output = Work;

    /// The sum of two counts (the deepest of the two depths).
    fn add(self, o: Work) -> Work {
        Work {
            primary: self.primary + o.primary,
            secondary: self.secondary + o.secondary,
            shadow: self.shadow + o.shadow,
            depth: self.depth.max(o.depth),
            budget_cut: self.budget_cut + o.budget_cut,
        }
    }
}

/// Everything a ray is traced with.
pub struct Tracer<'a> {
    /// The triangles and their shading.
    pub world: &'a World,
    /// The structure over `world.triangles`.
    pub accel: &'a dyn Accelerator,
    /// The scene's lights, in world space.
    pub lights: &'a LightingModel,
    /// The camera, for the fog coordinate.
    pub camera: &'a Camera,
    /// The scene's fog.
    pub fog: Option<Fog>,
    /// The colour of rays that hit nothing.
    pub background: Vec3,
    /// The environment, when it is drawn as the background (SPEC §5.3).
    pub sky: Option<&'a zline_shading::Environment>,
    /// Nodes deeper than this are not traced (1: the local model only).
    pub max_depth: u32,
    /// Branches whose weight (largest channel) is below this are cut.
    pub min_weight: f32,
    /// How shadow rays pass transparent occluders.
    pub shadows: ShadowRays,
}

impl Tracer<'_> {
    /// What a ray that hits nothing sees: the environment drawn as the
    /// background (its radiance along the ray), else the background colour.
    fn missed(&self, ray: &Ray) -> Vec3 {
        match self.sky {
            Some(sky) => sky.background_radiance(ray.dir.normalize_or_zero()),
            None => self.background,
        }
    }

    /// The colour seen along the camera ray `ray`.
    pub fn trace(&self, ray: Ray, work: &mut Work, stack: &mut Vec<(Ray, Vec3, u32)>) -> Vec3 {
        let mut color = Vec3::ZERO;
        stack.clear();
        stack.push((ray, Vec3::ONE, 1));
        let mut rays = 0;
        let mut cut = false;
        while let Some((ray, weight, depth)) = stack.pop() {
            rays += 1;
            let count = if depth == 1 { &mut work.primary } else { &mut work.secondary };
            let Some(hit) = self.accel.closest(&self.world.triangles, &ray, count) else {
                color += weight * self.missed(&ray);
                continue;
            };
            let Some(opacity) = self.opacity(hit.triangle, hit.b) else {
                // No surface here: the same ray goes on past it, at the
                // same depth and weight.
                if rays + stack.len() as u32 >= RAY_BUDGET {
                    cut = true;
                    continue;
                }
                let corners = &self.world.triangles[hit.triangle as usize];
                let (p, error) = hit.point_error(corners);
                let ng = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
                let origin = offset_origin(p, error, ng.normalize_or_zero(), ray.dir);
                stack.push((Ray { origin, dir: ray.dir, t_max: ray.t_max - hit.t }, weight, depth));
                continue;
            };
            work.depth = work.depth.max(depth);
            let node = self.shade(&ray, &hit, opacity, work);
            color += weight * node.local;
            if depth >= self.max_depth {
                continue;
            }
            for (child, k) in node.children.into_iter().flatten() {
                let w = weight * k;
                if w.max_element() < self.min_weight || !w.is_finite() {
                    continue;
                }
                if rays + stack.len() as u32 >= RAY_BUDGET {
                    cut = true;
                    break;
                }
                stack.push((child, w, depth + 1));
            }
        }
        work.budget_cut += u64::from(cut);
        color
    }

    /// The local colour at `hit` (times the opacity d) and the two
    /// children with their weights.
    fn shade(&self, ray: &Ray, hit: &Hit, opacity: f32, work: &mut Work) -> Node {
        let corners = &self.world.triangles[hit.triangle as usize];
        let attributes = &self.world.attributes[hit.triangle as usize];
        let surface = &self.world.surfaces[attributes.surface as usize];
        let m = &surface.material;
        let (p, error) = hit.point_error(corners);
        let v = (-ray.dir).normalize_or_zero();
        let ng = (corners[1] - corners[0]).cross(corners[2] - corners[0]).normalize_or_zero();
        // Both sides are lit: the normals turned to the side the ray came
        // from; `front` says whether that is the outside (the winding's).
        let front = v.dot(ng) >= 0.0;
        let side = if front { 1.0 } else { -1.0 };
        let ng = side * ng;
        let [b0, b1, b2] = hit.b;
        let mut n = attributes.normal(surface, hit.b).map_or(ng, |n| (side * n).normalize_or_zero());
        if n.dot(ng) <= 0.0 {
            n = ng;
        }
        let texel = surface.texture.as_ref().map(|t| {
            let [u0, u1, u2] = attributes.uvs;
            let uv = b0 * u0 + b1 * u1 + b2 * u2;
            t.texture.sample(&t.sampler, uv.x, uv.y, 0.0).truncate()
        });
        // Cook–Torrance: the texel multiplies the base colour, so also the
        // metal's F0 (SPEC §5.2); the basic model: ambient + diffuse (§7).
        let base = match (texel, m.model) {
            (Some(texel), Model::CookTorrance(_)) => Material { ka: m.ka * texel, kd: m.kd * texel, ..*m },
            _ => *m,
        };
        let parts = self.lights.shade_parts_seen(&base, (p, n, p + v), |k, to_light| {
            self.shadow(p, error, ng, &self.lights.lights[k], to_light, &mut work.shadow)
        });
        let lit = match (texel, m.model) {
            (Some(texel), Model::Basic) => texel * parts.ambient_diffuse + parts.specular,
            _ => parts.ambient_diffuse + parts.specular,
        };
        let mut local = lit.clamp(Vec3::ZERO, Vec3::ONE);
        if let Some(fog) = &self.fog {
            let radial = fog.coordinate == FogCoordinate::Radial;
            local = fog.apply(local, self.camera.fog_distance(p, radial));
        }
        let spawn = |w: Vec3| Ray::new(offset_origin(p, error, ng, w), w);
        let r = reflect(v, n);
        let mirror = (m.kr.max_element() > 0.0).then(|| (spawn(r), m.kr));
        let kt = 1.0 - opacity;
        let transmitted = (kt > 0.0).then(|| {
            // k_n = n_t / n_i: into the material from its outside, out of
            // it from inside.
            let k_n = if front { m.ior } else { 1.0 / m.ior };
            match refract(v, n, k_n) {
                Some(t) => (spawn(t), Vec3::splat(kt)),
                // Total internal reflection: the transmitted share reflects.
                None => (spawn(r), Vec3::splat(kt)),
            }
        });
        Node { local: opacity * local, children: [mirror, transmitted] }
    }

    /// What reaches `p` (error bound `error`, geometric normal `ng` on the
    /// lit side) from `light` in the direction `to_light`: `None` for all
    /// of it.
    fn shadow(
        &self,
        p: Vec3,
        error: Vec3,
        ng: Vec3,
        light: &Light,
        to_light: Vec3,
        count: &mut Counters,
    ) -> Option<Vec3> {
        let origin = offset_origin(p, error, ng, to_light);
        // pbrt's shadow epsilon: the segment stops just short of the light.
        let ray = match light.position() {
            Some(position) => Ray { origin, dir: position - origin, t_max: 1.0 - 1e-4 },
            None => Ray::new(origin, to_light),
        };
        match self.shadows {
            ShadowRays::Opaque => {
                let mut blocked = false;
                self.accel.each_hit(&self.world.triangles, &ray, count, &mut |hit| {
                    blocked = self.opacity(hit.triangle, hit.b).is_some();
                    !blocked
                });
                blocked.then_some(Vec3::ZERO)
            }
            ShadowRays::Filtered => {
                let mut hits = Vec::new();
                let mut opaque = false;
                self.accel.each_hit(&self.world.triangles, &ray, count, &mut |hit| {
                    let Some(d) = self.opacity(hit.triangle, hit.b) else {
                        return true; // no surface: not a crossing
                    };
                    let kt = 1.0 - d;
                    // An opaque occluder ends the ray before anything is kept.
                    opaque = kt <= 0.0;
                    if !opaque {
                        hits.push((hit, kt));
                    }
                    !opaque
                });
                if opaque {
                    return Some(Vec3::ZERO);
                }
                if hits.is_empty() {
                    return None;
                }
                // In the tie rule's order, so the product does not depend
                // on the traversal. A segment through an edge or a corner
                // hits every triangle there (the test is watertight): the
                // hits of one surface within [`SAME_CROSSING`] of each other
                // are one crossing.
                hits.sort_by(|a, b| a.0.t.total_cmp(&b.0.t).then(a.0.triangle.cmp(&b.0.triangle)));
                let mut passed = 1.0;
                let mut last: Option<(f32, u32)> = None;
                for (hit, kt) in hits {
                    let surface = self.world.attributes[hit.triangle as usize].surface;
                    let same =
                        last.is_some_and(|(t, s)| s == surface && hit.t - t <= SAME_CROSSING * t.max(1.0));
                    if !same {
                        passed *= kt;
                        last = Some((hit.t, surface));
                    }
                }
                Some(Vec3::splat(passed))
            }
        }
    }

    /// The opacity d at barycentrics `b` of `triangle`: the material's,
    /// times the diffuse map's alpha where the map blends; `None` where a
    /// mask's alpha is below its cutoff: no surface (SPEC §7 and §9, the
    /// texture read at level 0 as the colour is, once a hit).
    fn opacity(&self, triangle: u32, b: [f32; 3]) -> Option<f32> {
        let attributes = &self.world.attributes[triangle as usize];
        let surface = &self.world.surfaces[attributes.surface as usize];
        let d = surface.material.opacity;
        let Some(map) = surface.texture.as_ref().filter(|m| m.alpha_blend || m.alpha_cutoff.is_some()) else {
            return Some(d);
        };
        let [u0, u1, u2] = attributes.uvs;
        let uv = b[0] * u0 + b[1] * u1 + b[2] * u2;
        let alpha = map.texture.sample(&map.sampler, uv.x, uv.y, 0.0).w;
        match map.alpha_cutoff {
            Some(cutoff) if alpha < cutoff => None,
            Some(_) => Some(d),
            None => Some(d * alpha),
        }
    }
}

/// A node of the ray tree: its local colour (times d) and its children
/// (the reflected and the transmitted ray, each with its weight).
struct Node {
    local: Vec3,
    children: [Option<(Ray, Vec3)>; 2],
}
