//! Level of detail: the adaptive mode's shortcut for geometry ("model only
//! what the scene needs", issue 9). With `RenderSettings::adaptive_tolerance`
//! set, an object whose triangles project far below a sample is drawn from a
//! simplified copy of its mesh; without it, nothing here runs.
//!
//! **The levels.** [`Pyramid`] holds, per mesh, [`LEVELS`] simplified meshes
//! made by meshoptimizer's edge-collapse simplifier
//! (`meshopt::simplify_with_attributes_and_locks`) from the full mesh,
//! level k with the absolute target error e_k = R·2^−(k+3) (R: the radius
//! of the mesh's bounding sphere, object units), so level 0 is the
//! coarsest. The simplifier keeps a subset of the original vertices, so
//! every kept vertex carries its exact normal, texture coordinates, colour
//! and tangent; it collapses along texture and normal seams only in ways
//! that keep both sides together (vertices that share a position are
//! paired), and the mesh's open borders are locked (`LockBorder`), so two
//! meshes that meet along a border (one per material of a model) never open
//! a crack. Its error metric weighs the vertex normals with R (in its own
//! units, R divided by its extent): a normal chord δ counts as the distance
//! R·δ. Each level reports its error ≤ e_k — meshoptimizer's estimate (the
//! square root of the largest quadric error of a collapse) — so level k
//! lies within e_k of the full surface and its interpolated normals within
//! the chord δ_k = e_k/R = 2^−(k+3) of the full mesh's, as far as that
//! estimate goes. Its vertices are compacted into a mesh of their own, so
//! the vertex stage shrinks with the triangles.
//!
//! **The cache.** A level is built the first time a frame asks for it and
//! kept (`OnceLock`) in a process-wide table keyed by the mesh's `Arc`
//! (held as a `Weak`, so the address cannot be reused while the entry
//! lives; entries of dropped meshes are removed at the next look-up).
//! Frames of the same scene — the viewer, a turntable, `render()` called
//! again — reuse it; each level is made from the full mesh alone, so the
//! same mesh always gives the same levels, whichever were asked for first
//! and on whichever thread.
//!
//! **The choice** ([`LodView::choose`], once per object and frame). Let s be
//! the object's largest scale in eye space (exact for translate · rotate ·
//! scale matrices, the Frobenius norm as an upper bound otherwise), d the
//! eye depth of the bounding sphere's nearest point, and p the samples per
//! eye unit at that depth (from the projection matrix and the window).
//! Every point of the object is at depth ≥ d, so an object-space length ℓ
//! projects to at most ℓ·s·p samples.
//!
//! 1. *Triangles far below a sample*: the mean triangle area A (object
//!    units) must project to A·(s·p)² ≤ [`MAX_MEAN_AREA`] samples², and
//!    the mesh must have at least [`MIN_TRIANGLES`] triangles. Otherwise
//!    the full mesh is drawn — close-up objects are drawn exactly as
//!    without the level of detail.
//! 2. *Geometry within a fraction of a pixel*: e_k·s·p/n ≤ ε(τ) pixels (n:
//!    samples per pixel along an axis), ε(τ) = [`pixel_error`] = τ/32 px,
//!    at most ¼ px.
//! 3. *Normals within the tolerance*: a normal moved by the chord δ moves
//!    the lit colour by at most S·δ, S = Σ Il·(kd + 1.05·ks·√ns)
//!    (`material_sensitivity`); level k is allowed when S·δ_k ≤ τ/255
//!    ([`normal_level`]).
//!
//! The coarsest level that meets 2 and 3 is drawn; a level that keeps more
//! than ¾ of the triangles is not worth drawing, and the full mesh is
//! drawn instead.
//!
//! **What this keeps, and what it cannot.** Moving the surface by at most
//! ε px moves a silhouette or an occlusion boundary by at most ε px, so
//! only samples within ε px of one can change what they see; elsewhere a
//! sample sees the same surface displaced by ≤ ε px, lit with normals
//! within τ/255 of colour (as far as meshoptimizer's estimate holds). A
//! per-pixel maximum cannot hold: with one sample per pixel a boundary
//! moved by any amount flips the samples it crosses, by the full contrast,
//! and the adaptive mode's own shortcuts already move each image by up to
//! τ — the full mesh's image as much as the simplified one's. And the
//! full mesh's image is itself that sensitive: its triangles are below a
//! sample, so a sub-pixel move of the camera resamples them. The measure
//! the tests and `cargo xtask report` hold the level of detail to is
//! therefore the share of pixels that differ from the full-mesh image by
//! more than τ, and the RMSE, set against the same measures for the full
//! mesh moved ¼ px (BENCHMARKS.md, "Simplified meshes").

use std::collections::HashMap;
use std::sync::{Arc, LazyLock, Mutex, OnceLock, PoisonError, Weak};

use glam::{Mat4, Vec3, Vec4Swizzles};
#[cfg(feature = "simplify")]
use meshopt::{SimplifyOptions, VertexDataAdapter};
use zline_scene::{Mesh, Object, Scene};
use zline_shading::Material;

/// Levels per mesh: target errors R/8 down to R/4096.
pub const LEVELS: usize = 10;

/// Meshes with fewer triangles are always drawn in full.
pub const MIN_TRIANGLES: usize = 1024;

/// The largest mean projected triangle area (samples²) at which an object
/// is drawn from a simplified level: its triangles are then "far below a
/// sample" (the mean area bounds the projected one from above: depth at
/// the nearest point, no foreshortening).
pub const MAX_MEAN_AREA: f32 = 0.5;

/// A level keeping more than this share of the triangles is not drawn.
const MAX_KEPT: f32 = 0.75;

/// ε(τ): the largest projected error, in pixels, of a level drawn with
/// adaptive tolerance `tolerance` (8-bit steps): τ/32 px, at most ¼ px.
pub fn pixel_error(tolerance: f32) -> f32 {
    (tolerance / 32.0).clamp(0.0, 0.25)
}

/// The coarsest level whose normal error moves the lit colour by at most
/// τ/255: level k keeps normals within the chord δ_k = 2^−(k+3) (the
/// module documentation), and a normal moved by δ moves the colour by at
/// most `sensitivity`·δ ([`LodView::choose`]). [`LEVELS`] when none is fine
/// enough.
pub fn normal_level(tolerance: f32, sensitivity: f32) -> usize {
    let budget = tolerance / 255.0;
    (0..LEVELS).find(|&k| sensitivity * (0.5f32).powi(k as i32 + 3) <= budget).unwrap_or(LEVELS)
}

/// One simplified level of a mesh.
#[derive(Debug)]
pub struct Level {
    /// The simplified mesh (its own compacted vertices).
    pub mesh: Arc<Mesh>,
    /// The simplifier's error estimate in object units.
    pub error: f32,
}

/// A mesh's bounds and its levels, built lazily.
#[derive(Debug)]
pub struct Pyramid {
    /// The bounding sphere (centre of the box, radius to the farthest
    /// vertex), object units.
    center: Vec3,
    radius: f32,
    /// Mean triangle area, object units².
    mean_area: f32,
    /// False when the mesh cannot be simplified (too small, an index out
    /// of range, a non-finite position).
    usable: bool,
    /// Level k (target error R·2^−(k+3)); `None` inside when the simplifier
    /// made nothing usable.
    levels: [OnceLock<Option<Level>>; LEVELS],
}

impl Pyramid {
    /// The bounds of `mesh`; no level is built yet.
    pub fn new(mesh: &Mesh) -> Pyramid {
        let n = mesh.positions.len();
        let finite = mesh.positions.iter().all(|p| p.is_finite());
        let (lo, hi) = mesh
            .positions
            .iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
        let center = if n > 0 && finite { (lo + hi) * 0.5 } else { Vec3::ZERO };
        let radius = mesh.positions.iter().map(|p| (*p - center).length()).fold(0.0, f32::max);
        let area = |t: &[u32; 3]| {
            let p = |k: usize| mesh.positions.get(t[k] as usize).copied().unwrap_or(Vec3::ZERO);
            (p(1) - p(0)).cross(p(2) - p(0)).length() * 0.5
        };
        let total: f64 = mesh.triangles.iter().map(|t| area(t) as f64).sum();
        let mean_area = (total / mesh.triangles.len().max(1) as f64) as f32;
        let usable = simplifiable(mesh) && radius.is_finite() && radius > 0.0 && mean_area.is_finite();
        Pyramid { center, radius, mean_area, usable, levels: Default::default() }
    }

    /// Level `k` (< [`LEVELS`]) of `mesh` (the mesh this pyramid was made
    /// for), built on first use. `None` when the mesh cannot be simplified.
    pub fn level(&self, mesh: &Mesh, k: usize) -> Option<&Level> {
        if !self.usable || k >= LEVELS {
            return None;
        }
        self.levels[k].get_or_init(|| simplify(mesh, self.target_error(k), self.radius)).as_ref()
    }

    /// Level k's target error, object units.
    pub fn target_error(&self, k: usize) -> f32 {
        self.radius * (0.5f32).powi(k as i32 + 3)
    }
}

/// True when meshoptimizer can take `mesh` and its levels can carry every
/// attribute: vertices (at most `u32::MAX`), finite positions and one
/// finite normal each, every index in range, and texture coordinates,
/// colours and tangents each absent or one per vertex. Checked again
/// before each simplification (the simplifier's C++ would read out of
/// bounds on a bad index).
fn simplifiable(mesh: &Mesh) -> bool {
    let n = mesh.positions.len();
    let per_vertex = |len: usize| len == 0 || len == n;
    n > 0
        && n <= u32::MAX as usize
        && mesh.normals.len() == n
        && mesh.positions.iter().chain(&mesh.normals).all(|v| v.is_finite())
        && mesh.triangles.iter().flatten().all(|&i| (i as usize) < n)
        && per_vertex(mesh.uvs.len())
        && per_vertex(mesh.colors.len())
        && per_vertex(mesh.tangents.len())
}

/// True when this build has the simplifier (the `simplify` feature);
/// without it no level is ever built and every mesh is drawn in full.
pub const SIMPLIFIER: bool = cfg!(feature = "simplify");

/// Without the simplifier (the `simplify` feature off): no level.
#[cfg(not(feature = "simplify"))]
fn simplify(_: &Mesh, _: f32, _: f32) -> Option<Level> {
    None
}

/// The level of `mesh` with absolute target error `target`: meshopt's
/// simplification, its vertices compacted in order of first use.
#[cfg(feature = "simplify")]
fn simplify(mesh: &Mesh, target: f32, radius: f32) -> Option<Level> {
    if !simplifiable(mesh) {
        return None;
    }
    let positions: Vec<[f32; 3]> = mesh.positions.iter().map(|p| p.to_array()).collect();
    let adapter = VertexDataAdapter::new(bytemuck::cast_slice(&positions), 12, 0).ok()?;
    let indices: &[u32] = bytemuck::cast_slice(&mesh.triangles);
    // meshoptimizer measures positions in units of its extent (`scale`)
    // and attributes times their weight; a normal chord δ then counts as
    // the distance R·δ, so a level within e_k is also within e_k/R of the
    // normals (the module documentation).
    let scale = meshopt::simplify_scale(&adapter);
    let weight = radius / scale;
    if !(weight.is_finite() && weight > 0.0) {
        return None;
    }
    let normals: &[f32] = bytemuck::cast_slice(&mesh.normals);
    let unlocked = vec![false; positions.len()];
    let mut error = 0.0;
    let options = SimplifyOptions::ErrorAbsolute | SimplifyOptions::LockBorder;
    let kept = meshopt::simplify_with_attributes_and_locks(
        indices,
        &adapter,
        normals,
        &[weight; 3],
        12,
        &unlocked,
        0,
        target,
        options,
        Some(&mut error),
    );
    if kept.is_empty() || !error.is_finite() {
        return None;
    }
    Some(Level { mesh: Arc::new(compact(mesh, &kept)), error: error.max(0.0) })
}

/// The mesh of the triangles `indices` (into `mesh`), with only the
/// vertices they use, numbered in order of first use.
#[cfg(feature = "simplify")]
fn compact(mesh: &Mesh, indices: &[u32]) -> Mesh {
    let mut remap = vec![u32::MAX; mesh.positions.len()];
    let mut order = Vec::new();
    let triangles = indices
        .chunks_exact(3)
        .map(|t| {
            [0, 1, 2].map(|k| {
                let old = t[k] as usize;
                if remap[old] == u32::MAX {
                    remap[old] = order.len() as u32;
                    order.push(old);
                }
                remap[old]
            })
        })
        .collect();
    fn pick<T: Copy>(values: &[T], order: &[usize]) -> Vec<T> {
        if values.is_empty() {
            return Vec::new();
        }
        order.iter().map(|&i| values[i]).collect()
    }
    Mesh {
        name: mesh.name.clone(),
        positions: pick(&mesh.positions, &order),
        normals: pick(&mesh.normals, &order),
        triangles,
        material: mesh.material,
        uvs: pick(&mesh.uvs, &order),
        colors: pick(&mesh.colors, &order),
        diffuse_map: mesh.diffuse_map.clone(),
        tangents: pick(&mesh.tangents, &order),
        normal_map: mesh.normal_map.clone(),
        surface_maps: Default::default(),
    }
}

/// The process-wide cache: one pyramid per live mesh, keyed by the mesh's
/// address (the `Weak` keeps the allocation, so the address is not reused
/// while the entry lives).
static CACHE: LazyLock<Mutex<HashMap<usize, CacheEntry>>> = LazyLock::new(Default::default);

/// A cached mesh (held weakly) and its pyramid.
type CacheEntry = (Weak<Mesh>, Arc<Pyramid>);

/// The pyramid of `mesh`, from the cache or made now (bounds only; levels
/// are built on first use). A look-up is one hash; entries of dropped
/// meshes are removed when a new mesh is added.
pub fn pyramid(mesh: &Arc<Mesh>) -> Arc<Pyramid> {
    let key = Arc::as_ptr(mesh) as usize;
    let mut cache = CACHE.lock().unwrap_or_else(PoisonError::into_inner);
    if let Some((weak, p)) = cache.get(&key) {
        if weak.strong_count() > 0 {
            return p.clone();
        }
    }
    cache.retain(|_, (weak, _)| weak.strong_count() > 0);
    let p = Arc::new(Pyramid::new(mesh));
    cache.insert(key, (Arc::downgrade(mesh), p.clone()));
    p
}

/// What the frame's level choice needs: the camera and the window.
#[derive(Clone, Copy, Debug)]
pub struct LodView {
    /// Eye from world.
    pub eye_from_world: Mat4,
    /// Clip from eye (the projection).
    pub clip_from_eye: Mat4,
    /// The window's height in samples.
    pub height_samples: u32,
    /// Samples per pixel along an axis.
    pub samples: u32,
    /// The adaptive tolerance τ (8-bit steps).
    pub tolerance: f32,
    /// Σ over the lights of the largest channel of each light's colour.
    pub light_sum: f32,
}

/// Which mesh an object is drawn with.
#[derive(Clone, Debug)]
pub enum Choice {
    /// The full mesh.
    Full,
    /// Level `k`.
    Level {
        /// The level's index (0 is the coarsest).
        k: usize,
        /// Its mesh.
        mesh: Arc<Mesh>,
    },
}

impl LodView {
    /// The view of a frame of `scene` with the camera matrices and the
    /// window height in samples (`samples` per pixel along an axis) the
    /// renderer computed; `None` without the adaptive mode, or with a
    /// tolerance that is not a finite number ≥ 0 (which the renderer
    /// ignores too).
    pub fn new(
        scene: &Scene,
        eye_from_world: Mat4,
        clip_from_eye: Mat4,
        height_samples: u32,
        samples: u32,
    ) -> Option<LodView> {
        let tolerance = scene.settings.adaptive_tolerance.filter(|t| t.is_finite() && *t >= 0.0)?;
        Some(LodView {
            eye_from_world,
            clip_from_eye,
            height_samples,
            samples,
            tolerance,
            light_sum: scene.lights.iter().map(|l| l.color().max_element().max(0.0)).sum(),
        })
    }

    /// The mesh `object` is drawn with (the module documentation states the
    /// rule).
    pub fn choose(&self, object: &Object) -> Choice {
        let mesh = &object.mesh;
        if mesh.triangles.len() < MIN_TRIANGLES {
            return Choice::Full;
        }
        let pyramid = pyramid(mesh);
        if !pyramid.usable {
            return Choice::Full;
        }
        let Some(per_unit) = self.samples_per_unit(&pyramid, object.world_from_object) else {
            return Choice::Full;
        };
        // (NaN is not small: `partial_cmp` is `None` then.)
        let area = pyramid.mean_area * per_unit * per_unit;
        if area.partial_cmp(&MAX_MEAN_AREA).is_none_or(|o| o.is_gt()) {
            return Choice::Full;
        }
        let allowed = pixel_error(self.tolerance) * self.samples.max(1) as f32 / per_unit;
        let sensitivity = self.light_sum * material_sensitivity(&object.material());
        let first = normal_level(self.tolerance, sensitivity);
        let Some(k) = (first..LEVELS).find(|&k| pyramid.target_error(k) <= allowed) else {
            return Choice::Full;
        };
        match pyramid.level(mesh, k) {
            Some(level)
                if level.error <= allowed
                    && (level.mesh.triangles.len() as f32) <= MAX_KEPT * mesh.triangles.len() as f32 =>
            {
                Choice::Level { k, mesh: level.mesh.clone() }
            }
            _ => Choice::Full,
        }
    }

    /// s·p: the samples an object-space unit covers at most, anywhere on
    /// the object. `None` when the bounding sphere reaches w ≤ 0 or the
    /// numbers are not finite.
    fn samples_per_unit(&self, pyramid: &Pyramid, world_from_object: Mat4) -> Option<f32> {
        let eye_from_object = self.eye_from_world * world_from_object;
        let scale = largest_scale(eye_from_object);
        let center = eye_from_object.transform_point3(pyramid.center);
        // The eye looks down −z: the nearest point is at z + s·R.
        let nearest = center.z + scale * pyramid.radius;
        let p = self.clip_from_eye;
        let w = p.z_axis.w * nearest + p.w_axis.w;
        let per_unit = p.y_axis.y.abs() * self.height_samples as f32 * 0.5 / w * scale;
        (w > 0.0 && per_unit.is_finite() && per_unit > 0.0).then_some(per_unit)
    }
}

/// How far a unit normal moved by the chord δ ≤ 1 can move the lit colour
/// per light of unit intensity, over δ: kd + ks·1.05·√ns. The diffuse
/// term max(0, N·L) moves by at most δ (N·L is 1-Lipschitz in N); the
/// normal turns by the angle α = 2·asin(δ/2) ≤ 1.05·δ, which turns N·H's
/// angle θ by at most α, and cos^ns θ changes with θ by at most
/// max ns·cos^(ns−1)θ·sin θ = √ns·(1 − 1/ns)^((ns−1)/2) ≤ √ns (ns ≥ 1).
/// Attenuation, texels and vertex colours are ≤ 1. Infinite (no level)
/// when ns < 1 with specular, where (N·H)^ns has no bounded slope.
fn material_sensitivity(m: &Material) -> f32 {
    let m = m.sanitized();
    let (kd, ks) = (m.kd.max_element(), m.ks.max_element());
    if ks > 0.0 && m.ns < 1.0 {
        return f32::INFINITY;
    }
    kd + ks * 1.05 * m.ns.sqrt()
}

/// The largest factor by which `m`'s linear part stretches a length:
/// exact when its columns are orthogonal (translate · rotate · scale), the
/// Frobenius norm (an upper bound) otherwise.
fn largest_scale(m: Mat4) -> f32 {
    let c = [m.x_axis.xyz(), m.y_axis.xyz(), m.z_axis.xyz()];
    let len = c.map(Vec3::length);
    let orthogonal =
        [(0, 1), (1, 2), (2, 0)].iter().all(|&(i, j)| c[i].dot(c[j]).abs() <= 1e-5 * len[i] * len[j]);
    if orthogonal {
        len[0].max(len[1]).max(len[2]) * (1.0 + 1e-5)
    } else {
        (len[0] * len[0] + len[1] * len[1] + len[2] * len[2]).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Quat;

    #[test]
    fn the_pixel_budget_is_a_32nd_of_the_tolerance_up_to_a_quarter() {
        assert_eq!(pixel_error(2.0), 1.0 / 16.0);
        assert_eq!(pixel_error(8.0), 0.25);
        assert_eq!(pixel_error(100.0), 0.25);
        assert_eq!(pixel_error(0.0), 0.0);
    }

    #[test]
    fn the_normal_level_is_the_coarsest_within_the_colour_budget() {
        // τ = 8: 8/255 = 0.03137 ≥ 2^−5 = 0.03125 (k = 2), < 2^−4.
        assert_eq!(normal_level(8.0, 1.0), 2);
        // τ = 2: 0.00784 ≥ 2^−7 = 0.0078125 (k = 4).
        assert_eq!(normal_level(2.0, 1.0), 4);
        // Twice the sensitivity: one level finer.
        assert_eq!(normal_level(2.0, 2.0), 5);
        assert_eq!(normal_level(8.0, f32::INFINITY), LEVELS);
        assert_eq!(normal_level(8.0, f32::NAN), LEVELS);
        // The default material: 0.8 + 0.2·1.05·√32.
        let s = material_sensitivity(&Material::DEFAULT);
        assert!((s - (0.8 + 0.2 * 1.05 * 32f32.sqrt())).abs() < 1e-6, "{s}");
        let soft = Material { ns: 0.5, ..Material::DEFAULT };
        assert_eq!(material_sensitivity(&soft), f32::INFINITY);
    }

    #[test]
    fn the_largest_scale_is_exact_for_rotate_scale_and_bounds_a_shear() {
        let trs = Mat4::from_scale_rotation_translation(
            Vec3::new(2.0, 3.0, 0.5),
            Quat::from_rotation_y(0.7),
            Vec3::ONE,
        );
        assert!((largest_scale(trs) - 3.0).abs() < 1e-3, "{}", largest_scale(trs));
        let shear = Mat4::from_cols_array(&[
            1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
        ]);
        // Its largest singular value is the golden ratio ≈ 1.618.
        assert!(largest_scale(shear) >= 1.618, "{}", largest_scale(shear));
    }

    #[test]
    #[cfg(feature = "simplify")]
    fn compaction_keeps_every_attribute_of_the_kept_vertices() {
        let positions: Vec<Vec3> = (0..6).map(|i| Vec3::new(i as f32, (i * i) as f32, 0.0)).collect();
        let mesh = Mesh {
            name: "m".into(),
            normals: (0..6).map(|i| Vec3::new(0.0, (i as f32).sin(), (i as f32).cos())).collect(),
            uvs: (0..6).map(|i| glam::Vec2::new(i as f32 * 0.1, 0.5)).collect(),
            colors: (0..6).map(|i| Vec3::splat(i as f32 / 6.0)).collect(),
            positions,
            triangles: vec![[0, 1, 2], [3, 4, 5]],
            material: Material::DEFAULT,
            diffuse_map: None,
            tangents: Vec::new(),
            normal_map: None,
            surface_maps: Default::default(),
        };
        let c = compact(&mesh, &[5, 2, 4, 2, 5, 0]);
        assert_eq!(c.triangles, vec![[0, 1, 2], [1, 0, 3]]);
        for (new, old) in [5usize, 2, 4, 0].into_iter().enumerate() {
            assert_eq!(c.positions[new], mesh.positions[old]);
            assert_eq!(c.normals[new], mesh.normals[old]);
            assert_eq!(c.uvs[new], mesh.uvs[old]);
            assert_eq!(c.colors[new], mesh.colors[old]);
        }
        assert!(c.tangents.is_empty() && c.positions.len() == 4);
    }
}
