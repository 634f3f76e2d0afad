//! The object-ID image: per pixel, which object of the scene is seen there.
//!
//! It is a frame of its own, drawn by the same pipeline with no new kernel:
//! every opaque object is given a flat, unlit material whose emission ke
//! encodes its index + 1 in 24 bits, one byte a channel (ke = byte/255,
//! which [`crate::image::quantize`] turns back into the same byte), and the
//! frame is drawn with one sample at each pixel's centre, no lights, fog,
//! shadows, tone mapping or lines, the z-buffer, on a black background
//! (0: nothing). The bytes are then read back as indices.
//!
//! What it shows is the depth image's surface: the nearest *opaque*
//! surface. Transparent objects (opacity below 1, or a texture whose alpha
//! blends) are left out, as they write no depth; an alpha-masked texture
//! still cuts its holes, as it does in the image. With one sample per
//! pixel (`ssaa` 1) a pixel has an ID exactly where the depth image has a
//! depth; with supersampling the ID is the one at the pixel's centre while
//! the depth is the nearest of its samples, so the two may differ along
//! silhouettes.

use std::sync::Arc;

use glam::Vec3;
use zline_scene::{Mesh, Object, Scene, ShadingMode, ShadowMode, SurfaceMaps, Visibility, Wireframe};
use zline_shading::Material;

use crate::image::Image;
use crate::render::{RenderOptions, RenderStats, Renderer};

/// The most objects an object-ID image can tell apart: 2²⁴ − 1 (index + 1
/// in 24 bits, 0 for nothing).
pub const MAX_OBJECT_IDS: usize = (1 << 24) - 1;

/// A frame's object-ID image: per pixel, the index in `Scene::objects` of
/// the object whose opaque surface is nearest at the pixel's centre, −1
/// where there is none. Rows top to bottom, as [`Image`].
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ObjectIds {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width · height` indices, −1 for the background.
    pub ids: Vec<i32>,
}

impl ObjectIds {
    /// The index at pixel (x, y) (−1 for the background).
    pub fn at(&self, x: u32, y: u32) -> i32 {
        self.ids[y as usize * self.width as usize + x as usize]
    }
}

/// The scene has more objects than [`MAX_OBJECT_IDS`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TooManyObjects(pub usize);

impl std::fmt::Display for TooManyObjects {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "the scene has {} objects; an object-ID image tells at most {MAX_OBJECT_IDS} apart", self.0)
    }
}

impl std::error::Error for TooManyObjects {}

pub use crate::render::is_transparent;

/// The emission that encodes `index`: (index + 1) in 24 bits, low byte in
/// red, each byte over 255.
fn id_color(index: usize) -> Vec3 {
    let [r, g, b, _] = ((index + 1) as u32).to_le_bytes();
    Vec3::new(f32::from(r), f32::from(g), f32::from(b)) / 255.0
}

/// The scene the ID frame draws (see the module's documentation).
fn id_scene(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    s.fog = None;
    s.shadows.mode = ShadowMode::None;
    s.background = Vec3::ZERO;
    s.ambient = Vec3::ZERO;
    s.lights.clear();
    s.environment = None;
    let r = &mut s.settings;
    r.ssaa = 1;
    r.adaptive_tolerance = None;
    r.tone_mapping = Default::default();
    r.visibility = Visibility::ZBuffer;
    r.wireframe = Wireframe::default();
    r.transparent_background = false;
    s.objects = scene
        .objects
        .iter()
        .enumerate()
        .filter(|(_, o)| !is_transparent(o))
        .map(|(index, o)| {
            // The diffuse map stays for its alpha mask; with ka = kd = 0 its
            // colour adds nothing. Vertex colours, the emissive texture
            // (which multiplies ke) and the normal map go.
            let mesh = Mesh {
                colors: Vec::new(),
                tangents: Vec::new(),
                normal_map: None,
                surface_maps: SurfaceMaps::default(),
                ..(*o.mesh).clone()
            };
            let material = Material {
                ke: id_color(index),
                ka: Vec3::ZERO,
                kd: Vec3::ZERO,
                ks: Vec3::ZERO,
                opacity: 1.0,
                ..Material::DEFAULT
            };
            Object {
                mesh: Arc::new(mesh),
                material: Some(material),
                shading: Some(ShadingMode::Flat),
                ..o.clone()
            }
        })
        .collect();
    s
}

impl Renderer {
    /// The object-ID image of `scene` (see the module's documentation) into
    /// `ids`; `image` receives the encoded frame.
    pub fn render_object_ids_into(
        &mut self,
        scene: &Scene,
        options: &RenderOptions,
        image: &mut Image,
        ids: &mut ObjectIds,
    ) -> Result<RenderStats, TooManyObjects> {
        if scene.objects.len() > MAX_OBJECT_IDS {
            return Err(TooManyObjects(scene.objects.len()));
        }
        let scene = id_scene(scene);
        let stats = self.render_into(&scene, options, image);
        (ids.width, ids.height) = (image.width, image.height);
        ids.ids.clear();
        ids.ids.extend(image.pixels.iter().map(|&p| (p & 0x00ff_ffff) as i32 - 1));
        Ok(stats)
    }
}

/// Renders the object-ID image of `scene` (see the module's
/// documentation).
pub fn render_object_ids(
    scene: &Scene,
    options: &RenderOptions,
) -> Result<(ObjectIds, RenderStats), TooManyObjects> {
    let (mut image, mut ids) = (Image::empty(), ObjectIds::default());
    let stats = Renderer::default().render_object_ids_into(scene, options, &mut image, &mut ids)?;
    Ok((ids, stats))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image::quantize;

    /// Every index an ID image can hold survives the trip through ke and
    /// the 8-bit quantization.
    #[test]
    fn every_id_survives_quantization() {
        for index in 0..MAX_OBJECT_IDS {
            let c = id_color(index);
            let word = u32::from_le_bytes([quantize(c.x), quantize(c.y), quantize(c.z), 0]);
            assert_eq!(word as usize, index + 1);
        }
    }
}
