//! Extra outputs of a render, each only when asked for (a frame that asks
//! for none pays nothing for them):
//!
//! - **the depth image** ([`Renderer::render_with_depth`]): each pixel's
//!   eye-space depth, the distance to the eye plane −z_eye, of the nearest
//!   opaque surface among its samples. The tiles copy their depth buffers
//!   out after every pass (the nearest of a pixel's n×n samples, a fixed
//!   reduction), and the stored depth — NC depth, or reversed depth — is
//!   turned back into eye depth with the frame's projection in f64. With
//!   the painter's algorithm (which keeps no depth) the tile runs the
//!   depth-only pass for it. Transparent surfaces write no depth and do not
//!   appear; nor do lines.
//! - **the normals image** ([`Renderer::render_normals_into`]): a second
//!   frame of the scene in which every object is drawn opaque and each
//!   sample's colour is its eye-space shading normal n encoded as
//!   (n + 1)/2 (x right, y up, z toward the viewer): interpolated and
//!   re-normalized per sample as Phong shading does, with bump and normal
//!   maps applied; flat-shaded objects show their face normal. A triangle
//!   seen from behind shows its normals turned toward the viewer.
//!   Textures, vertex colours, fog, shadows, transparency, lines and the
//!   adaptive mode play no part; the background is (0, 0, 0), or
//!   transparent when the scene's background is.
//!
//! Both are the same for any thread count and tile size, as the image is.

use rayon::prelude::*;
use zline_scene::{LightingSides, Scene, ShadowMode, Visibility, Wireframe};

use crate::image::{Image, ImageRows};
use crate::render::{RenderOptions, RenderStats, Renderer};
use crate::setup::DepthEncoding;
use crate::tile::{sample, TileTarget};

/// A frame's depth image: per pixel, the eye-space depth (−z_eye, in world
/// units) of the nearest opaque surface drawn in it, `NaN` where nothing
/// was drawn. Rows top to bottom, as [`Image`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DepthImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width · height` depths.
    pub depth: Vec<f32>,
}

/// How [`DepthImage::to_gray16`] maps depths to 16-bit values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthRange {
    /// The nearest drawn depth (world units): 65535.
    pub near: f32,
    /// The farthest drawn depth: 1.
    pub far: f32,
}

impl DepthImage {
    /// The depth of pixel (x, y) (`NaN` where nothing was drawn).
    pub fn at(&self, x: u32, y: u32) -> f32 {
        self.depth[y as usize * self.width as usize + x as usize]
    }

    /// The nearest and farthest drawn depths; `None` when nothing was drawn.
    pub fn range(&self) -> Option<DepthRange> {
        let drawn = self.depth.iter().copied().filter(|d| !d.is_nan());
        drawn.fold(None, |r, d| match r {
            None => Some(DepthRange { near: d, far: d }),
            Some(DepthRange { near, far }) => Some(DepthRange { near: near.min(d), far: far.max(d) }),
        })
    }

    /// The image as 16-bit grey values, linear in depth: the nearest drawn
    /// pixel 65535, the farthest drawn 1 (every drawn pixel 65535 when they
    /// are all at one depth), nothing drawn 0; rounded half up in f64. With
    /// the range it was mapped with.
    pub fn to_gray16(&self) -> (Vec<u16>, Option<DepthRange>) {
        let range = self.range();
        let map = |d: f32| -> u16 {
            let Some(r) = range.filter(|_| !d.is_nan()) else {
                return 0;
            };
            let (near, far, d) = (f64::from(r.near), f64::from(r.far), f64::from(d));
            if far <= near {
                return u16::MAX;
            }
            let v = 1.0 + ((far - d) / (far - near) * 65534.0 + 0.5).floor();
            v.clamp(1.0, 65535.0) as u16
        };
        (self.depth.iter().map(|&d| map(d)).collect(), range)
    }
}

/// Turns a stored depth back into eye depth (−z_eye) with the frame's
/// projection: how setup encoded it ([`DepthEncoding`]), inverted in f64.
#[derive(Clone, Copy, Debug)]
struct EyeDepth {
    encoding: DepthEncoding,
    perspective: bool,
    near: f64,
    far: f64,
    /// The depth buffer's clear value: nothing drawn.
    clear: f32,
}

impl EyeDepth {
    fn new(scene: &Scene) -> EyeDepth {
        let (perspective, (near, far)) =
            (scene.camera.projection.is_perspective(), scene.camera.projection.near_far());
        let encoding = match scene.settings.depth {
            zline_scene::DepthMode::Normalized => DepthEncoding::Normalized,
            zline_scene::DepthMode::ReversedFloat => {
                let (a, b) = scene.camera.reversed_depth_coefficients();
                DepthEncoding::Reversed { a, b, perspective }
            }
        };
        let clear = match encoding {
            DepthEncoding::Normalized => crate::tile::DEPTH_CLEAR,
            DepthEncoding::Reversed { .. } => crate::tile::DEPTH_CLEAR_REVERSED,
        };
        EyeDepth { encoding, perspective, near: f64::from(near), far: f64::from(far), clear }
    }

    /// −z_eye of a stored depth `z`; `NaN` for the clear value.
    fn distance(&self, z: f32) -> f32 {
        if z >= self.clear || z.is_nan() {
            return f32::NAN;
        }
        let (n, f, z) = (self.near, self.far, f64::from(z));
        let d = match (self.encoding, self.perspective) {
            // z_nc = ((f + n)·z_e + 2fn) / ((f − n)·z_e), z_e = −d.
            (DepthEncoding::Normalized, true) => 2.0 * f * n / ((f + n) - z * (f - n)),
            // z_nc = (−2·z_e − (f + n)) / (f − n).
            (DepthEncoding::Normalized, false) => (z * (f - n) + (f + n)) / 2.0,
            // d = (a·z_e + b) / (2·z_e) (w = −z_e).
            (DepthEncoding::Reversed { a, b, .. }, true) => b / (a - 2.0 * z),
            // d = −(a·z_e + b) / 2 (w = 1).
            (DepthEncoding::Reversed { a, b, .. }, false) => (2.0 * z + b) / a,
        };
        d as f32
    }
}

impl TileTarget {
    /// Copies the tile's depth out: each pixel of the tile (n×n samples)
    /// gets the smallest stored depth of its samples — the nearest, in both
    /// encodings — into `out` (rows from the tile's first pixel row).
    pub fn export_depth(&self, out: &mut ImageRows<'_, '_, f32>, n: u32) {
        let n = n as i32;
        let (py0, px0, first) = (self.rect.y0 / n, self.rect.x0 / n, out.first());
        for py in py0..self.rect.y1 / n {
            let out = out.row((py - py0) as usize);
            for px in px0..self.rect.x1 / n {
                let mut nearest = self.far;
                for sy in py * n..(py + 1) * n {
                    for sx in px * n..(px + 1) * n {
                        nearest = nearest.min(sample(&self.depth, self.index(sx, sy)));
                    }
                }
                out[px as usize - first] = nearest;
            }
        }
    }
}

impl Renderer {
    /// [`Renderer::render_into`], and the frame's depth image into `depth`
    /// (resized to the image). The image is the same as without it.
    pub fn render_with_depth(
        &mut self,
        scene: &Scene,
        options: &RenderOptions,
        image: &mut Image,
        depth: &mut DepthImage,
    ) -> RenderStats {
        self.normals = false;
        let stats = self.render_frame(scene, options, image, Some(&mut depth.depth));
        (depth.width, depth.height) = (image.width, image.height);
        let eye = EyeDepth::new(scene);
        depth.depth.par_iter_mut().for_each(|z| *z = eye.distance(*z));
        stats
    }

    /// The normals image of `scene` (see the module's documentation) into
    /// `image`.
    pub fn render_normals_into(
        &mut self,
        scene: &Scene,
        options: &RenderOptions,
        image: &mut Image,
    ) -> RenderStats {
        let scene = normals_scene(scene);
        self.normals = true;
        let stats = self.render_frame(&scene, options, image, None);
        self.normals = false;
        stats
    }
}

/// The scene as the normals frame draws it: no fog, shadows, lines or
/// adaptive shortcuts, the z-buffer, two-sided normals, a black background.
fn normals_scene(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    s.fog = None;
    s.shadows.mode = ShadowMode::None;
    s.background = glam::Vec3::ZERO;
    let r = &mut s.settings;
    r.adaptive_tolerance = None;
    r.tone_mapping = Default::default();
    r.visibility = Visibility::ZBuffer;
    r.wireframe = Wireframe::default();
    r.lighting_sides = LightingSides::TwoSided;
    s
}

/// Renders `scene` and its depth image (see [`Renderer::render_with_depth`]).
pub fn render_depth(scene: &Scene, options: &RenderOptions) -> (Image, DepthImage, RenderStats) {
    let (mut image, mut depth) = (Image::empty(), DepthImage::default());
    let stats = Renderer::default().render_with_depth(scene, options, &mut image, &mut depth);
    (image, depth, stats)
}

/// Renders the normals image of `scene` (see the module's documentation).
pub fn render_normals(scene: &Scene, options: &RenderOptions) -> (Image, RenderStats) {
    let mut image = Image::empty();
    let stats = Renderer::default().render_normals_into(scene, options, &mut image);
    (image, stats)
}
