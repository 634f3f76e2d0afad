//! A tile's buffers: the depth buffer and the R, G, B colour planes, one
//! value per sample, and what the kernels read besides the primitive.

use std::sync::Arc;

use glam::Vec3;
use zline_raster::{Rect, LANES};
use zline_shading::{PreparedLights, PreparedMaterial, Sampler, Texture};
use zline_simd::lanes::{f32x8, i32x8, Level};

/// NC depth initialised to the far plane (SPEC §4).
pub const DEPTH_CLEAR: f32 = 1.0;

/// Reversed depth's far plane (see [`crate::setup::DepthEncoding`]).
pub const DEPTH_CLEAR_REVERSED: f32 = 0.0;

/// A texture as the frame's kernels read it: the texels (shared with the
/// scene, not copied) and the sampler after the frame's filter override.
#[derive(Clone, Debug)]
pub struct FrameTexture {
    /// The texels.
    pub texture: Arc<Texture>,
    /// Filtering and wrapping.
    pub sampler: Sampler,
    /// The cutoff of [`AlphaUse::Mask`](crate::setup::AlphaUse::Mask).
    pub cutoff: f32,
}

/// A Cook–Torrance material's maps: indices in the frame's textures.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SurfaceUse {
    /// The metallic–roughness map (B metallic, G roughness).
    pub metallic_roughness: Option<u32>,
    /// The occlusion map (R) and its strength.
    pub occlusion: Option<(u32, f32)>,
    /// The emissive map (RGB).
    pub emission: Option<u32>,
}

impl SurfaceUse {
    /// True when the material has any of the maps.
    pub fn any(&self) -> bool {
        self.metallic_roughness.is_some() || self.occlusion.is_some() || self.emission.is_some()
    }
}

/// What shading reads besides the primitive.
#[derive(Clone, Copy, Debug)]
pub struct ShadeContext<'a> {
    /// Lights in eye space.
    pub lighting: &'a PreparedLights,
    /// The frame's materials, indexed by the primitives' `material`.
    pub materials: &'a [PreparedMaterial],
    /// The frame's textures, indexed by the primitives' `texture`.
    pub textures: &'a [FrameTexture],
    /// Per material (indexed like `materials`): the maps of its
    /// Cook–Torrance parameters, read by the Phong-family textured kernels
    /// (SPEC §5.2).
    pub surfaces: &'a [SurfaceUse],
    /// The frame's shadow maps (`ShadowMode::Map`): every Phong kernel
    /// scales each light by the share of it its sample sees.
    pub maps: Option<&'a crate::shadow_map::ShadowMaps>,
    /// The normals frame (`Renderer::render_normals_into`): every Phong
    /// kernel writes the encoded eye-space normal (n + 1)/2 instead of
    /// lighting. Decided once per primitive, never per sample.
    pub normals: bool,
}

/// A tile's depth buffer and colour planes, one value per sample, covering
/// columns `origin..origin + stride` (the tile widened to multiples of
/// [`LANES`]). One per thread, kept from frame to frame.
#[derive(Clone, Debug, Default)]
pub struct TileTarget {
    pub(crate) rect: Rect,
    pub(crate) origin: i32,
    pub(crate) stride: usize,
    /// Depth, eight samples a vector: `f32x8` keeps every block of the
    /// buffers 32-byte aligned, inside one cache line.
    pub(crate) depth: Vec<f32x8>,
    /// The far plane's depth: [`DEPTH_CLEAR`] or [`DEPTH_CLEAR_REVERSED`].
    pub(crate) far: f32,
    pub(crate) rgb: [Vec<f32x8>; 3],
    pub(crate) background: Vec3,
    /// The environment's radiance behind each sample (`crate::sky`), read
    /// instead of `background` when `sky_drawn`.
    pub(crate) sky: [Vec<f32x8>; 3],
    /// True when this tile's undrawn samples show the sky.
    pub(crate) sky_drawn: bool,
    /// Applied by the resolve, before quantization.
    pub(crate) tone: zline_shading::ToneMapping,
    /// The largest value a lit colour keeps (`PreparedLights::ceiling`),
    /// set for the frame.
    pub(crate) ceiling: f32,
    /// False while undrawn samples (depth `far`) hold stale colours that
    /// the resolve replaces by the background.
    pub(crate) colors_valid: bool,
    /// The tile's shadow mask, one bit per (receiving plane, light) pair
    /// per sample, eight samples a vector (see [`TileTarget::shadow_pass`]);
    /// empty when no shadow falls on the tile, which reads as all lit.
    pub(crate) shadow: Vec<i32x8>,
    /// Coverage (`RenderSettings::transparent_background`): the alpha plane
    /// is kept, written wherever colour is blended or replaced outside the
    /// opaque pass; off, it is never allocated or touched.
    pub(crate) coverage: bool,
    /// Alpha per sample, valid where `colors_valid` (before that, a sample
    /// is 1 when drawn and 0 when not, read from the depth buffer).
    pub(crate) alpha: Vec<f32x8>,
    /// The coarse depth tested before a primitive's spans are walked.
    pub(crate) coarse: CoarseDepth,
    /// Primitives the coarse depth skipped whole, counted over every tile
    /// drawn with this target since the count was last set to 0 (a tile's
    /// clear leaves it); the renderer sums its targets' counts per frame.
    pub(crate) hidden: u64,
}

impl TileTarget {
    /// Resets the buffers for a tile (`rect` in samples): depth `far`
    /// ([`DEPTH_CLEAR`], or [`DEPTH_CLEAR_REVERSED`] for reversed depth).
    ///
    /// Only the depth buffer is written. A sample whose depth is still
    /// `far` was never drawn — a fragment is written only when z < stored,
    /// so a written depth is below `far` — and the resolve gives it the
    /// background; the colour planes are not cleared at all (they only
    /// grow to the tile's size). That saves three of the four stores per
    /// sample of a clear.
    pub fn clear(&mut self, rect: Rect, background: Vec3, far: f32) {
        let lanes = LANES as i32;
        self.rect = rect;
        self.origin = rect.x0 & !(lanes - 1);
        self.stride = ((rect.x1 + lanes - 1) & !(lanes - 1)).saturating_sub(self.origin).max(0) as usize;
        let n = self.stride * rect.height() as usize;
        self.depth.clear();
        self.depth.resize(n / LANES, f32x8::splat(far));
        self.far = far;
        self.coarse = CoarseDepth::cleared(far);
        self.background = background;
        self.sky_drawn = false;
        self.colors_valid = false;
        self.shadow.clear();
        for plane in &mut self.rgb {
            plane.resize(n / LANES, f32x8::ZERO);
        }
        if self.coverage {
            self.alpha.resize(n / LANES, f32x8::ZERO);
        }
    }

    /// Turns the alpha plane on or off for the frame's tiles (see
    /// [`zline_scene::RenderSettings::transparent_background`]).
    pub fn set_coverage(&mut self, on: bool) {
        self.coverage = on;
    }

    /// Makes room for a tile of `side` × `side` samples (and its shadow
    /// mask when `shadows`), so that no later [`Self::clear`] of such a tile
    /// allocates: every thread's buffers are sized by the frame, not by the
    /// first tile the scheduler happens to hand that thread.
    pub fn reserve(&mut self, side: u32, shadows: bool) {
        let lanes = LANES;
        // A tile may start anywhere in a block of eight columns: one more block.
        let blocks = (side as usize).div_ceil(lanes).saturating_add(1).saturating_mul(side as usize);
        let grow = |v: &mut Vec<f32x8>| v.reserve(blocks.saturating_sub(v.len()));
        grow(&mut self.depth);
        self.rgb.iter_mut().for_each(grow);
        if self.coverage {
            grow(&mut self.alpha);
        }
        if shadows {
            self.shadow.reserve(blocks.saturating_sub(self.shadow.len()));
        }
    }

    #[inline]
    pub(crate) fn index(&self, x: i32, y: i32) -> usize {
        (y - self.rect.y0) as usize * self.stride + (x - self.origin) as usize
    }

    /// The background behind samples `i..i + 8` (`i` a multiple of
    /// [`LANES`]): the sky there, or the background colour.
    #[inline(always)]
    pub(crate) fn background_block<S: Level>(&self, i: usize) -> zline_shading::Vec3x8<S> {
        if self.sky_drawn {
            let [r, g, b] = &self.sky;
            zline_shading::Vec3x8 { x: load(r, i), y: load(g, i), z: load(b, i) }
        } else {
            zline_shading::Vec3x8::splat(self.background)
        }
    }

    /// The background behind sample `i`.
    /// Sample (x, y)'s stored depth, its colour (the background's where
    /// nothing was drawn yet) and its alpha (1 without the coverage plane):
    /// what the pixel inspector reads between primitives.
    pub(crate) fn sample_state(&self, x: i32, y: i32) -> (f32, Vec3, f32) {
        let i = self.index(x, y);
        let depth = sample(&self.depth, i);
        let drawn = self.colors_valid || depth < self.far;
        let [r, g, b] = &self.rgb;
        let color =
            if drawn { Vec3::new(sample(r, i), sample(g, i), sample(b, i)) } else { self.background_at(i) };
        let alpha = match (self.coverage, self.colors_valid) {
            (true, true) => sample(&self.alpha, i),
            (true, false) => f32::from(u8::from(depth < self.far)),
            (false, _) => 1.0,
        };
        (depth, color, alpha)
    }

    /// Sample (x, y)'s planar shadow mask (0 where no shadow falls on the
    /// tile).
    pub(crate) fn shadow_mask_at(&self, x: i32, y: i32) -> i32 {
        if self.shadow.is_empty() {
            return 0;
        }
        bytemuck::cast_slice::<_, i32>(&self.shadow)[self.index(x, y)]
    }

    #[inline]
    pub(crate) fn background_at(&self, i: usize) -> Vec3 {
        if self.sky_drawn {
            let [r, g, b] = &self.sky;
            Vec3::new(sample(r, i), sample(g, i), sample(b, i))
        } else {
            self.background
        }
    }
}

/// Samples `i..i + 8` of a buffer (`i` a multiple of [`LANES`]).
#[inline(always)]
pub(crate) fn load<S: Level>(buf: &[f32x8], i: usize) -> f32x8<S> {
    buf[i / LANES].at()
}

/// [`load`] for a block that is then written back blended: read so that
/// the compiler keeps a plain load, blend and store instead of forming a
/// masked store (microcoded and slow on AMD cores; `zline_simd::read_opaque`).
#[inline(always)]
pub(crate) fn load_for_blend<S: Level>(buf: &[f32x8], i: usize) -> f32x8<S> {
    zline_simd::read_opaque(&buf[i / LANES]).at()
}

/// Writes samples `i..i + 8` of a buffer (`i` a multiple of [`LANES`]).
#[inline(always)]
pub(crate) fn store<S: Level>(buf: &mut [f32x8], i: usize, v: f32x8<S>) {
    buf[i / LANES] = v.at();
}

/// Sample `i` of a buffer.
#[inline(always)]
pub(crate) fn sample(buf: &[f32x8], i: usize) -> f32 {
    bytemuck::cast_slice::<f32x8, f32>(buf)[i]
}

/// A tile's coarse depth and the state of its test (see `tile::coarse`).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct CoarseDepth {
    /// At least every depth the tile's buffer holds.
    pub(super) most: f32,
    /// Samples the opaque pass wrote since `most` was found.
    pub(super) written: u64,
    /// Tests that failed in a row, at most `tile::coarse`'s `MAX_BACKOFF`.
    pub(super) misses: u32,
    /// Primitives to pass untested.
    pub(super) wait: u32,
}

impl CoarseDepth {
    /// A cleared tile's: every sample at `far`.
    pub(crate) fn cleared(far: f32) -> CoarseDepth {
        CoarseDepth { most: far, ..CoarseDepth::default() }
    }
}
