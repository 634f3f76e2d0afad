//! The f64 truth of the Whitted tree (SPEC §12): every rule of the ray
//! tracer evaluated in f64 with the truth's own lighting
//! ([`crate::lighting`]), texture reads ([`crate::texture`]) and fog
//! ([`crate::fog`]), on the scene model alone — none of `zline-trace`'s
//! code. The geometry (the ray–triangle test and the hierarchy) is
//! [`crate::whitted_hit`], the world (triangles, surfaces, texture reads
//! and shadow rays) [`crate::whitted_world`], what is recorded for the
//! mask [`crate::whitted_record`].
//!
//! **The world.** Every object's triangles in world space (corners by
//! the f64 model matrix; vertex normals by the inverse transpose of its
//! linear part, normalized, zero where it is singular), numbered object by
//! object in mesh order — the numbering of the tie rule. A triangle with
//! an index out of range, a non-finite corner or zero area is never hit.
//! Culling and the rasterizer's lighting sides do not apply: both sides of
//! every triangle are hit and lit.
//!
//! **Camera rays.** For the image point (x, y) the window point of SPEC
//! §1 is unprojected in f64 through the inverse of clip_from_eye ·
//! eye_from_world (the truth's f64 matrices from the camera's fields,
//! [`crate::camera`]) at NC depth −1 and +1: the ray runs from the near
//! point (t = 0) to the far point (t = 1), both ends open. With
//! `samples` = n the points are (x + (i + ½)/n, y + (j + ½)/n) for
//! i, j < n and the pixel is their mean; 1 is the pixel centre.
//! Adaptive supersampling is out of scope: with `adaptive` set, the truth
//! traces the regular grid that [`TraceOptions::checked`] leaves (one ray
//! a pixel), the image the adaptive scheme approximates.
//!
//! **Hits.** The nearest hit in the ray's open interval, by the tie rule
//! (lower triangle index at equal t), whatever `accel` asks for (the
//! truth's hierarchy answers as brute force). A secondary or shadow ray starts at
//! the exact hit point (from the barycentrics), skips the triangle it
//! starts on by index, and ignores hits at a distance ≤ 10⁻⁹·max(1,
//! |p|∞) from its start p (the neighbours of that triangle meet the ray
//! at its start, up to rounding, where it leaves an edge); no offset.
//!
//! **Shading a hit** (V the unit vector towards the ray's origin, N_g the
//! unit face normal): the normals are turned to V's side (`front` when V
//! is on the winding's outside, V·N_g ≥ 0); the shading normal N is the
//! face normal for a flat object and the normalized interpolated vertex
//! normal for a Gouraud or Phong one, the face normal instead where that
//! is zero or does not lie on N_g's side (N·N_g ≤ 0, the fast tracer's
//! convention where SPEC is silent). The lighting model of SPEC §5 (the
//! material's, sanitized) is evaluated at the hit point with the viewer
//! at the ray's origin: the truth's lighting in the world frame shifted
//! to put the ray's origin at 0. Light k adds s_k times its term, s_k
//! from its shadow ray (below), traced only where the term is not zero;
//! ambient, the environment (SPEC §5.3) and emission are not shadowed. A
//! diffuse texture (when the mesh has texture coordinates for every
//! vertex; the scene's filter override applies) is read at level 0
//! (trilinear reads level 0 bilinearly) at the interpolated coordinates,
//! its RGB multiplying the ambient and diffuse part under the basic model
//! (ka and kd, SPEC §7) and the base colour under Cook–Torrance (before
//! c_diff and f0 are formed, as SPEC §5.2 does per sample); vertex
//! colours, normal and bump maps and a Cook–Torrance material's other
//! maps are not read (SPEC §12 names the texture only). The lit colour is
//! clamped to [0, 1], fogged (SPEC §8) by the hit's eye-space point (f64
//! eye_from_world), and multiplied by the opacity d.
//!
//! **Texture alpha** (the same level-0 read): with a cutoff (a mask, which
//! takes precedence as in the rasterizer) a hit whose alpha is below it is
//! no surface — the same ray goes on from the hit point (the triangle
//! skipped, the rest of its interval) at the same depth and weight, one
//! more ray of the budget — and shadow rays ignore such hits; without a
//! cutoff, a blending map's alpha multiplies d, for the local colour, kt
//! and shadow rays alike.
//!
//! **Shadow rays.** From the hit to a point light's (or spot light's)
//! position, the segment's parameter t ∈ (ε, 1 − 10⁻⁴); along −direction
//! (normalized) for a directional light, t > ε. `Opaque`: any hit stops
//! the light. `Filtered`: the hits, sorted by (t, triangle), are grouped
//! into crossings — a hit of the same object as the current crossing's
//! first hit, within 10⁻⁵·max(1, t) of it in the ray's parameter, joins
//! it — and the light passes Π(1 − d) over the crossings (0 at an opaque
//! one); the shadow ray is not refracted.
//!
//! **The tree.** A node adds weight ⊙ d·I_local; its children are the
//! reflected ray R = 2(N·V)N − V with weight ⊙ kr (when kr ≠ 0) and the
//! transmitted ray with weight ⊙ kt, kt = 1 − d (when kt > 0): refracted
//! by the course's formula V′ = V/(V·N), radicand k_n²|V′|² − |N − V′|²,
//! T = (N − V′)/√radicand − N (normalized), k_n = ior from the outside
//! (`front`), 1/ior from the inside; along R where the radicand is ≤ 0
//! (total internal reflection) or V·N ≤ 0. A ray that hits nothing adds
//! weight ⊙ what it sees: the environment's radiance k·L along it (the
//! truth's bilinear panorama read, not clamped) where the scene draws the
//! environment as its background, else the background colour; neither
//! is fogged. Children are not traced at the
//! depth limit (`max_depth`, node depth 1 the camera ray) or when their
//! weight's largest channel is below `min_weight` (or not finite). The
//! nodes are taken depth first from a stack of their own (the transmitted
//! child before the reflected one); a tree stops pushing children once
//! the rays it traced and the rays waiting reach [`RAY_BUDGET`] — the
//! same order and count as `zline-trace`, so that a tree cut by the
//! budget is the same tree. Options are [`TraceOptions::checked`] first.
//!
//! **Expected differences from `zline-trace`.** It computes in f32:
//! world-space corners and the hit point round to about 10⁻⁷ relative,
//! and its secondary rays start off the surface by the hit point's error
//! bound, so silhouettes, shadow edges, refracted and reflected images
//! and the edges of nearest-filtered texels may move by a small fraction
//! of a pixel (more through several refractions);
//! [`TracedTruth::away_from_silhouettes`] marks the pixels no such move
//! can reach. It lights with `zline-shading`'s f32 models
//! (Cook–Torrance's split sum from its own table: up to 0.012 in E_s for
//! N·V ≥ 0.1, the truth integrates) and the environment from its f32 SH
//! and prefiltered levels ([`crate`]'s doc measures both). Its texture
//! multiplies Cook–Torrance's ambient-and-diffuse part instead of the
//! base colour: equal for metallic 0, but a textured metal's highlight
//! keeps the untextured colour there (measured: 215 steps on a square
//! with a four-colour texture, metallic 1, roughness 0.4). It does not
//! apply the scene's texture filter override, and its `budget_cut`
//! counts the nodes whose children the budget dropped, not the trees.
//! Measured (`tests/it/whitted.rs`, default options): on the Whitted
//! scene at 160 × 120 and the demo at 96 × 54 every pixel, silhouettes
//! included, is within one 8-bit step; at 320 × 240 three pixels of the
//! Whitted scene differ by 13 to 138 steps, each reproduced by moving the
//! truth's sample by at most 1.6·10⁻⁵ pixel (edges seen through the glass
//! sphere), and all three lie off the mask.

use glam::{DMat4, DVec3, DVec4, Vec3};
use rayon::prelude::*;
use zline_scene::trace_options::TraceOptions;
use zline_scene::Scene;

use crate::camera;
use crate::environment::EnvironmentF64;
use crate::fog::apply_fog;
use crate::image::TruthImage;
use crate::lighting::{EyeLights, MaterialF64, ModelF64, Parts, SampleMaps};
use crate::split_sum::SplitSum;
use crate::whitted_hit::{Hit, Ray};
pub use crate::whitted_record::{LightPath, RayKind, TracedTruth, TreeNode};
use crate::whitted_world::{self_distance, Alpha, World};
pub use crate::whitted_world::{SAME_CROSSING, SHADOW_SEGMENT_END};

/// Rays a pixel's tree traces at most (SPEC §12).
pub const RAY_BUDGET: u32 = 4096;

/// A ray waiting on the stack.
#[derive(Clone, Copy, Debug)]
struct Pending {
    ray: Ray,
    weight: DVec3,
    depth: u32,
    kind: RayKind,
}

/// What one pixel row (or one ray) cost.
#[derive(Clone, Copy, Debug, Default)]
struct Count {
    rays: u64,
    shadow_rays: u64,
    budget_cut: u64,
    deepest: u32,
}

/// A shaded hit: its local colour (times d), its children and what the
/// mask records.
struct Shaded {
    local: DVec3,
    children: [Option<(Ray, DVec3, RayKind)>; 2],
    node: TreeNode,
}

/// A scene prepared for the Whitted truth: the world's triangles in f64
/// and their hierarchy, the camera's rays and the lights.
#[derive(Debug)]
pub struct WhittedTruth<'a> {
    scene: &'a Scene,
    options: TraceOptions,
    world: World,
    /// The ambient light and the environment, no lights, in the world frame.
    ambient: EyeLights,
    world_from_clip: DMat4,
    eye_from_world: DMat4,
    size: (u32, u32),
}

impl<'a> WhittedTruth<'a> {
    /// Prepares `scene` for tracing with `options` (checked first).
    pub fn new(scene: &'a Scene, options: &TraceOptions) -> WhittedTruth<'a> {
        let (options, _) = options.checked();
        let s = &scene.settings;
        let size = (s.width.max(1), s.height.max(1));
        let eye_from_world = camera::eye_from_world(&scene.camera);
        let clip_from_eye = camera::clip_from_eye(&scene.camera, f64::from(size.0) / f64::from(size.1));
        let environment = scene.environment.as_ref().map(|e| EnvironmentF64::new(e, &DMat4::IDENTITY));
        let ambient = EyeLights::new(scene.ambient, &[], &DMat4::IDENTITY, SplitSum::Integral)
            .with_environment(environment);
        WhittedTruth {
            scene,
            options,
            world: World::new(scene),
            ambient,
            world_from_clip: (clip_from_eye * eye_from_world).inverse(),
            eye_from_world,
            size,
        }
    }

    /// The tree sum along the ray from `origin` in `direction` (any
    /// length; t ∈ (0, ∞)), the viewer at `origin`, as for a camera ray.
    pub fn trace(&self, origin: DVec3, direction: DVec3) -> DVec3 {
        let ray = Ray { origin, dir: direction, t_min: 0.0, t_max: f64::INFINITY, skip: None };
        self.tree(ray, None, &mut Count::default(), &mut Vec::new())
    }

    /// The camera ray through the image point (x, y) in pixels (y down),
    /// from the near point (t = 0) to the far point (t = 1).
    fn camera_ray(&self, x: f64, y: f64) -> Ray {
        let (w, h) = (f64::from(self.size.0), f64::from(self.size.1));
        let (xn, yn) = (2.0 * x / w - 1.0, 1.0 - 2.0 * y / h);
        let unproject = |z: f64| {
            let p = self.world_from_clip * DVec4::new(xn, yn, z, 1.0);
            p.truncate() / p.w
        };
        let near = unproject(-1.0);
        Ray { origin: near, dir: unproject(1.0) - near, t_min: 0.0, t_max: 1.0, skip: None }
    }

    /// Traces every pixel, in parallel over rows (the image does not
    /// depend on the thread count); with `record_trees`, keeps each
    /// pixel's tree for [`TracedTruth::away_from_silhouettes`].
    pub fn render(&self, record_trees: bool) -> TracedTruth {
        let (width, height) = self.size;
        let n = self.options.samples;
        let rows: Vec<(Vec<DVec3>, Vec<Vec<TreeNode>>, Count)> = (0..height)
            .into_par_iter()
            .map(|y| {
                let mut count = Count::default();
                let mut stack = Vec::new();
                let mut rgb = Vec::with_capacity(width as usize);
                let mut trees = Vec::new();
                for x in 0..width {
                    let mut sum = DVec3::ZERO;
                    let mut nodes = Vec::new();
                    for j in 0..n {
                        for i in 0..n {
                            let sx = f64::from(x) + (f64::from(i) + 0.5) / f64::from(n);
                            let sy = f64::from(y) + (f64::from(j) + 0.5) / f64::from(n);
                            let record = record_trees.then_some(&mut nodes);
                            sum += self.tree(self.camera_ray(sx, sy), record, &mut count, &mut stack);
                        }
                    }
                    rgb.push(sum / f64::from(n * n));
                    if record_trees {
                        trees.push(nodes);
                    }
                }
                (rgb, trees, count)
            })
            .collect();
        let mut out = TracedTruth {
            image: TruthImage { width, height, rgb: Vec::new(), diagnostics: None },
            trees: record_trees.then(Vec::new),
            rays: 0,
            shadow_rays: 0,
            budget_cut: 0,
            deepest: 0,
        };
        for (rgb, trees, count) in rows {
            out.image.rgb.extend(rgb);
            if let Some(all) = &mut out.trees {
                all.extend(trees);
            }
            out.rays += count.rays;
            out.shadow_rays += count.shadow_rays;
            out.budget_cut += count.budget_cut;
            out.deepest = out.deepest.max(count.deepest);
        }
        out
    }

    /// The tree sum of a camera ray, its nodes appended to `record`.
    fn tree(
        &self,
        camera: Ray,
        mut record: Option<&mut Vec<TreeNode>>,
        count: &mut Count,
        stack: &mut Vec<Pending>,
    ) -> DVec3 {
        let min_weight = f64::from(self.options.min_weight);
        let mut color = DVec3::ZERO;
        stack.clear();
        stack.push(Pending { ray: camera, weight: DVec3::ONE, depth: 1, kind: RayKind::Camera });
        let (mut rays, mut cut) = (0u32, false);
        while let Some(Pending { ray, weight, depth, kind }) = stack.pop() {
            rays += 1;
            count.rays += 1;
            let Some(hit) = self.world.triangles.closest(&ray) else {
                color += weight * self.missed(&ray);
                if let Some(nodes) = record.as_deref_mut() {
                    nodes.push(TreeNode::miss(depth, kind));
                }
                continue;
            };
            let texel = self.world.texel(hit.triangle, hit.b);
            if self.world.alpha(hit.triangle, texel) == Alpha::CutOut {
                // No surface: the same ray goes on past the hit, at the
                // same depth and weight, as one more ray of the budget.
                if let Some(nodes) = record.as_deref_mut() {
                    let attributes = &self.world.attributes[hit.triangle as usize];
                    let node = TreeNode {
                        object: Some(attributes.object),
                        cut_out: true,
                        ..TreeNode::miss(depth, kind)
                    };
                    nodes.push(node);
                }
                if rays + stack.len() as u32 >= RAY_BUDGET {
                    cut = true;
                    continue;
                }
                let p = self.world.point(hit.triangle, hit.b);
                let rest = Ray {
                    origin: p,
                    dir: ray.dir,
                    t_min: self_distance(p) / ray.dir.length(),
                    t_max: ray.t_max - hit.t,
                    skip: Some(hit.triangle),
                };
                stack.push(Pending { ray: rest, weight, depth, kind });
                continue;
            }
            count.deepest = count.deepest.max(depth);
            let shaded = self.shade(&ray, &hit, texel, (depth, kind), count);
            color += weight * shaded.local;
            if let Some(nodes) = record.as_deref_mut() {
                nodes.push(shaded.node);
            }
            if depth >= self.options.max_depth {
                continue;
            }
            for (child, k, kind) in shaded.children.into_iter().flatten() {
                let w = weight * k;
                if w.max_element() < min_weight || !w.is_finite() {
                    continue;
                }
                if rays + stack.len() as u32 >= RAY_BUDGET {
                    cut = true;
                    break;
                }
                stack.push(Pending { ray: child, weight: w, depth: depth + 1, kind });
            }
        }
        count.budget_cut += u64::from(cut);
        color
    }

    /// The local colour at `hit` (times d), the children and the node.
    fn shade(
        &self,
        ray: &Ray,
        hit: &Hit,
        texel: Option<DVec4>,
        (depth, kind): (u32, RayKind),
        count: &mut Count,
    ) -> Shaded {
        let attributes = &self.world.attributes[hit.triangle as usize];
        let surface = &self.world.surfaces[attributes.object as usize];
        let m = &surface.material;
        let c = &self.world.triangles.corners[hit.triangle as usize];
        let [b0, b1, b2] = hit.b;
        let p = self.world.point(hit.triangle, hit.b);
        let v = (-ray.dir).normalize_or_zero();
        let ng = (c[1] - c[0]).cross(c[2] - c[0]).normalize_or_zero();
        let front = v.dot(ng) >= 0.0;
        let ng = if front { ng } else { -ng };
        let mut n = ng;
        if !surface.flat {
            let [n0, n1, n2] = attributes.normals;
            let interpolated = if front { 1.0 } else { -1.0 } * (n0 * b0 + n1 * b1 + n2 * b2);
            let interpolated = interpolated.normalize_or_zero();
            if interpolated.dot(ng) > 0.0 {
                n = interpolated;
            }
        }
        let opacity = self.world.opacity(hit.triangle, texel);
        let texel = texel.map(DVec4::truncate);
        // The lighting with the ray's origin at 0: the viewer there.
        let point = p - ray.origin;
        let base = m.kd * texel.unwrap_or(DVec3::ONE);
        let lit_by = |lights: &EyeLights, material: &MaterialF64| match &material.model {
            ModelF64::Basic => lights.shade(material, point, n),
            ModelF64::CookTorrance(microfacet) => {
                lights.shade_microfacet(material, microfacet, (point, n), None, (base, SampleMaps::NONE))
            }
        };
        let mut parts = lit_by(&self.ambient, m);
        let dark = MaterialF64 { ke: DVec3::ZERO, ..*m };
        let to_origin = DMat4::from_translation(-ray.origin);
        let mut paths = Vec::with_capacity(self.scene.lights.len());
        for light in &self.scene.lights {
            let one = EyeLights::new(Vec3::ZERO, std::slice::from_ref(light), &to_origin, SplitSum::Integral);
            let term: Parts = lit_by(&one, &dark);
            if term.ambient_diffuse == DVec3::ZERO && term.specular == DVec3::ZERO {
                paths.push(LightPath::Unlit);
                continue;
            }
            count.shadow_rays += 1;
            let (passed, path) = self.world.shadow(p, hit.triangle, light, self.options.shadows);
            paths.push(path);
            parts.ambient_diffuse += passed * term.ambient_diffuse;
            parts.specular += passed * term.specular;
        }
        let lit = match (&m.model, texel) {
            (ModelF64::Basic, Some(texel)) => texel * parts.ambient_diffuse + parts.specular,
            _ => parts.ambient_diffuse + parts.specular,
        };
        let mut local = lit.clamp(DVec3::ZERO, DVec3::ONE);
        if let Some(fog) = &self.scene.fog {
            local = apply_fog(fog, local, self.eye_from_world.transform_point3(p));
        }
        // The children.
        let spawn = |dir: DVec3| Ray {
            origin: p,
            dir,
            t_min: self_distance(p),
            t_max: f64::INFINITY,
            skip: Some(hit.triangle),
        };
        let r = 2.0 * n.dot(v) * n - v;
        let mirror = (surface.kr.max_element() > 0.0).then(|| (spawn(r), surface.kr, RayKind::Reflected));
        let kt = 1.0 - opacity;
        let transmitted = (kt > 0.0).then(|| {
            let k_n = if front { surface.ior } else { 1.0 / surface.ior };
            match refract(v, n, k_n) {
                Some(t) => (spawn(t), DVec3::splat(kt), RayKind::Transmitted),
                None => (spawn(r), DVec3::splat(kt), RayKind::InternallyReflected),
            }
        });
        let flat_normal = surface.flat.then(|| (ng * 1e9).round().to_array().map(|x| x as i64));
        Shaded {
            local: opacity * local,
            children: [mirror, transmitted],
            node: TreeNode {
                depth,
                kind,
                object: Some(attributes.object),
                front,
                flat_normal,
                texel: self.world.texel_index(hit.triangle, hit.b),
                cut_out: false,
                lights: paths,
            },
        }
    }

    /// What a ray that hits nothing sees (SPEC §12): the environment's
    /// radiance along it where the scene draws the environment as its
    /// background, else the background colour; not clamped, not fogged.
    fn missed(&self, ray: &Ray) -> DVec3 {
        match self.ambient.environment().filter(|e| e.background) {
            Some(environment) => environment.radiance(ray.dir.normalize_or_zero()),
            None => self.scene.background.as_dvec3(),
        }
    }
}

/// The course's transmitted direction (SPEC §12) for unit `v` (towards
/// the ray's origin), unit `n` on v's side and k_n = n_t/n_i, normalized:
/// `None` where V·N ≤ 0 or the radicand is ≤ 0 (or NaN).
fn refract(v: DVec3, n: DVec3, k_n: f64) -> Option<DVec3> {
    let cos = v.dot(n);
    if cos <= 0.0 || cos.is_nan() {
        return None;
    }
    let v1 = v / cos;
    let tangent = n - v1;
    let radicand = k_n * k_n * v1.length_squared() - tangent.length_squared();
    if radicand <= 0.0 || radicand.is_nan() {
        return None;
    }
    Some((tangent / radicand.sqrt() - n).normalize_or_zero())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The course's formula is Snell's law: into glass at 45°, and total
    /// internal reflection leaving it at 45°.
    #[test]
    fn refraction_follows_snells_law() {
        let v = DVec3::new(-1.0, 1.0, 0.0).normalize();
        let t = refract(v, DVec3::Y, 1.5).unwrap();
        let sin_t = 0.5f64.sqrt() / 1.5;
        assert!((t - DVec3::new(sin_t, -(1.0 - sin_t * sin_t).sqrt(), 0.0)).length() < 1e-15, "{t}");
        assert_eq!(refract(v, DVec3::Y, 1.0 / 1.5), None);
        assert_eq!(refract(-v, DVec3::Y, 1.5), None, "no incident side");
        assert_eq!(refract(DVec3::Y, DVec3::Y, f64::NAN), None);
    }
}
