//! The solution drawn by the rasterizer (SPEC §13): the patches as
//! meshes whose vertex colours carry the radiosity, lit by ambient light
//! 1 on ka = 1 and nothing else, Gouraud-interpolated, so that a new
//! viewpoint costs one frame.
//!
//! An untextured patch shows B itself. A textured one shows its texture
//! lit by what it received: its reflectance ρ = kd·t̄ used the texture's
//! mean t̄ over the patch, so the vertex colour is V = (B − E)·kd/ρ (the
//! irradiance times kd), which the rasterizer multiplies by the texel,
//! and the emission E is added as the material's ke. Where the texel
//! equals its mean this is B again; elsewhere the planks and the
//! wallpaper keep their detail.

use std::collections::HashMap;
use std::sync::Arc;

use glam::{Mat4, Vec2, Vec3};
use zline_scene::{Mesh, Object, Scene};
use zline_shading::{Material, ShadingMode};
use zline_trace::world::World;

use crate::Solution;

/// ka = 1 and nothing else but the emission `ke`.
fn unlit(ke: Vec3) -> Material {
    let mut material = Material::default();
    (material.ka, material.kd, material.ks, material.ke) = (Vec3::ONE, Vec3::ZERO, Vec3::ZERO, ke);
    material
}

/// Drawn with Gouraud shading, both sides, where it is.
fn object(mesh: Mesh) -> Object {
    Object {
        mesh: Arc::new(mesh),
        world_from_object: Mat4::IDENTITY,
        material: None,
        shading: Some(ShadingMode::Gouraud),
        cull_back_faces: false,
    }
}

impl Solution {
    /// The radiosity at each shared corner: the area-weighted mean of the
    /// patches around it.
    pub fn vertex_radiosity(&self) -> Vec<Vec3> {
        self.corner_means(&self.radiosity)
    }

    /// The area-weighted mean of `values` (one a patch) at each shared
    /// corner.
    fn corner_means(&self, values: &[Vec3]) -> Vec<Vec3> {
        let mut sum = vec![Vec3::ZERO; self.patches.vertices.len()];
        let mut weight = vec![0.0f32; self.patches.vertices.len()];
        for (p, b) in self.patches.patches.iter().zip(values) {
            for &v in &p.vertices {
                sum[v as usize] += *b * p.area;
                weight[v as usize] += p.area;
            }
        }
        sum.iter().zip(&weight).map(|(s, &w)| if w > 0.0 { *s / w } else { Vec3::ZERO }).collect()
    }

    /// The display's scale: emission is at most 1 (a material's ke), so a
    /// room's walls come out far darker, and interreflection brightens a
    /// room lit by lights past the local model's range; B is shown times
    /// the scale that puts the 99th percentile by area of the patches that
    /// emit nothing (their brightest channel) at 0.85.
    pub fn display_scale(&self) -> f32 {
        let lit = self.patches.patches.iter().zip(&self.radiosity).filter(|(p, _)| p.emission == Vec3::ZERO);
        crate::subdivide::bright_level(lit.map(|(p, b)| (b.max_element(), p.area)))
            .map_or(1.0, |level| 0.85 / level)
    }

    /// `scene` with its objects replaced by the solution (module doc),
    /// times [`Self::display_scale`]: one mesh of the untextured patches,
    /// one a textured surface.
    pub fn display_scene(&self, scene: &Scene) -> Scene {
        self.display_scene_scaled(scene, self.display_scale())
    }

    /// [`Self::display_scene`] with B shown times `scale` (to compare two
    /// solutions in the same units).
    pub fn display_scene_scaled(&self, scene: &Scene, scale: f32) -> Scene {
        let mut out = scene.clone();
        out.lights.clear();
        out.ambient = Vec3::ONE;
        // Drawn by the rasterizer: a scene to be solved no more.
        out.settings.renderer = zline_scene::trace_options::Renderer::Raster;
        out.objects.clear();
        let world = World::new(scene);
        let surface =
            |p: &crate::Patch| world.attributes.get(p.triangle as usize).map(|a| a.surface as usize);
        let texture = |p: &crate::Patch| surface(p).and_then(|s| world.surfaces[s].texture.as_ref());
        // What each patch shows at its corners: B, or V for a textured one.
        let shown: Vec<Vec3> = self
            .patches
            .patches
            .iter()
            .zip(&self.radiosity)
            .map(|(p, b)| match (texture(p), surface(p)) {
                (Some(_), Some(s)) => {
                    let kd = world.surfaces[s].material.kd;
                    let ratio = Vec3::select(p.reflectance.cmpgt(Vec3::ZERO), kd / p.reflectance, Vec3::ZERO);
                    (*b - p.emission) * ratio
                }
                _ => *b,
            })
            .collect();
        let colors: Vec<Vec3> = self
            .corner_means(&shown)
            .iter()
            .map(|c| if c.is_finite() { *c * scale } else { Vec3::ZERO })
            .collect();
        let plain: Vec<[u32; 3]> =
            self.patches.patches.iter().filter(|p| texture(p).is_none()).map(|p| p.vertices).collect();
        if !plain.is_empty() {
            let mesh = Mesh::new("radiosity", self.patches.vertices.clone(), None, plain, unlit(Vec3::ZERO))
                .and_then(|m| m.with_colors(colors.clone()))
                .expect("patches index their own finite corners");
            out.objects.push(object(mesh));
        }
        // A textured surface: its own mesh, a vertex for each corner and
        // texture coordinate (a seam keeps both sides' coordinates).
        let mut textured: Vec<(usize, Vec<usize>)> = Vec::new();
        for (i, p) in self.patches.patches.iter().enumerate() {
            if let (Some(_), Some(s)) = (texture(p), surface(p)) {
                match textured.iter_mut().find(|(t, _)| *t == s) {
                    Some((_, list)) => list.push(i),
                    None => textured.push((s, vec![i])),
                }
            }
        }
        for (s, list) in textured {
            let (mut positions, mut uvs, mut shades) = (Vec::new(), Vec::new(), Vec::new());
            let mut index: HashMap<(u32, [u32; 2]), u32> = HashMap::new();
            let mut triangles = Vec::with_capacity(list.len());
            for &i in &list {
                let p = &self.patches.patches[i];
                let mut triangle = [0u32; 3];
                for (k, slot) in triangle.iter_mut().enumerate() {
                    let (v, uv) = (p.vertices[k], p.uvs[k]);
                    *slot = *index.entry((v, uv.to_array().map(f32::to_bits))).or_insert_with(|| {
                        positions.push(self.patches.vertices[v as usize]);
                        uvs.push(if uv.is_finite() { uv } else { Vec2::ZERO });
                        shades.push(colors[v as usize]);
                        positions.len() as u32 - 1
                    });
                }
                triangles.push(triangle);
            }
            let surface = &world.surfaces[s];
            let map = surface.texture.clone().expect("a textured surface");
            let ke = surface.material.ke.max(Vec3::ZERO) * scale;
            let mesh = Mesh::new("radiosity, textured", positions, None, triangles, unlit(ke))
                .and_then(|m| m.with_uvs(uvs))
                .and_then(|m| m.with_colors(shades))
                .expect("patches index their own finite corners")
                .with_diffuse_map(map);
            out.objects.push(object(mesh));
        }
        out
    }
}
