//! Rasterizing one tile: the opaque pass over its bin with a depth buffer in
//! NC depth (SPEC §4), then quantization into the image (SPEC §10).
//!
//! Kernels are chosen once per primitive — by shading mode and by
//! interpolation — and monomorphized, so the per-sample loop of a Gouraud
//! triangle contains no lighting and a screen-linear one no divide. The depth
//! test comes before any shading (STYLE habit 5).

use glam::{Vec3, Vec4};
use wide::f32x8;
use zline_raster::{for_each_sample, AttributePlanes, DepthPlane, Rect, Span};
use zline_shading::{PreparedLights, PreparedMaterial, Vec3x8};

use crate::bin::{PrimitiveChunk, PrimitiveRef};
use crate::image::{quantize_rgba, quantize_rgba_pair};
use crate::setup::{GouraudPlanes, PhongPlanes, Primitive, Shader};

/// Depth initialised to the far plane (SPEC §4).
pub const DEPTH_CLEAR: f32 = 1.0;

/// What shading reads besides the primitive.
#[derive(Clone, Copy, Debug)]
pub struct ShadeContext<'a> {
    /// Lights in eye space.
    pub lighting: &'a PreparedLights,
    /// The frame's materials, indexed by [`Shader::Phong::material`].
    pub materials: &'a [PreparedMaterial],
}

/// A tile's depth and colour buffers, one value per sample. Colours are
/// RGBA in a 16-byte SIMD type (alpha unused): clearing is a run of aligned
/// vector stores and resolving quantizes four lanes at once.
#[derive(Clone, Debug, Default)]
pub struct TileTarget {
    rect: Rect,
    stride: usize,
    depth: Vec<f32>,
    color: Vec<Vec4>,
}

impl TileTarget {
    /// Resets the buffers for a tile: depth 1, colour the background.
    pub fn clear(&mut self, rect: Rect, background: Vec3) {
        let n = (rect.width() * rect.height()) as usize;
        self.rect = rect;
        self.stride = rect.width() as usize;
        self.depth.clear();
        self.depth.resize(n, DEPTH_CLEAR);
        self.color.clear();
        self.color.resize(n, background.extend(1.0));
    }

    /// The tile's pixels.
    pub fn rect(&self) -> Rect {
        self.rect
    }

    /// Depth at a pixel of the tile (window coordinates).
    pub fn depth_at(&self, x: i32, y: i32) -> f32 {
        self.depth[self.index(x, y)]
    }

    #[inline]
    fn index(&self, x: i32, y: i32) -> usize {
        (y - self.rect.y0) as usize * self.stride + (x - self.rect.x0) as usize
    }

    /// Draws the primitives `bin` (references into `chunks`) in order; returns
    /// the number of samples that passed the depth test.
    pub fn opaque_pass(
        &mut self,
        chunks: &[PrimitiveChunk],
        bin: &[PrimitiveRef],
        ctx: &ShadeContext<'_>,
    ) -> u64 {
        let mut shaded = 0;
        for r in bin {
            shaded += self.draw(&chunks[r.chunk as usize].prims[r.index as usize], ctx);
        }
        shaded
    }

    /// Quantizes the colour buffer into `band`, the RGBA image rows that
    /// hold this tile (`band` starts at the tile's first row; `width` is the
    /// image width in pixels).
    pub fn resolve(&self, band: &mut [u32], width: usize) {
        if self.stride == 0 {
            return;
        }
        for (row, colors) in self.color.chunks_exact(self.stride).enumerate() {
            let start = row * width + self.rect.x0 as usize;
            let out = &mut band[start..start + colors.len()];
            // Two pixels per 8-lane vector, then the odd one out.
            let mut pairs = out.chunks_exact_mut(2);
            let mut colors2 = colors.chunks_exact(2);
            for (o, c) in (&mut pairs).zip(&mut colors2) {
                let [a, b] = quantize_rgba_pair(c[0], c[1]);
                o[0] = a;
                o[1] = b;
            }
            for (o, c) in pairs.into_remainder().iter_mut().zip(colors2.remainder()) {
                *o = quantize_rgba(*c);
            }
        }
    }

    fn draw(&mut self, p: &Primitive, ctx: &ShadeContext<'_>) -> u64 {
        let mut n = 0;
        let clip = self.rect;
        match (p.shader, p.perspective) {
            (Shader::Flat { color }, _) => p.edges.scan(clip, |s| n += self.flat_span(&p.depth, s, color)),
            (Shader::Gouraud { planes }, true) => {
                p.edges.scan(clip, |s| n += self.gouraud_span::<true>(&p.depth, &planes, s))
            }
            (Shader::Gouraud { planes }, false) => {
                p.edges.scan(clip, |s| n += self.gouraud_span::<false>(&p.depth, &planes, s))
            }
            (Shader::Phong { planes, material }, persp) => {
                let (m, l) = (&ctx.materials[material as usize], ctx.lighting);
                let mut batch = PhongBatch::default();
                if persp {
                    p.edges
                        .scan(clip, |s| n += self.phong_span::<true>(&p.depth, &planes, s, &mut batch, m, l));
                    batch.flush::<true>(&mut self.color, m, l);
                } else {
                    p.edges.scan(clip, |s| {
                        n += self.phong_span::<false>(&p.depth, &planes, s, &mut batch, m, l)
                    });
                    batch.flush::<false>(&mut self.color, m, l);
                }
            }
        }
        n
    }

    /// Runs `shade` on every sample of `span` that passes the depth test,
    /// writing depth and the returned colour.
    #[inline(always)]
    fn span<const N: usize>(
        &mut self,
        depth: &DepthPlane,
        attrs: &AttributePlanes<N>,
        span: Span,
        mut shade: impl FnMut(&[f32; N]) -> Vec3,
    ) -> u64 {
        let row = self.index(span.x0, span.y) as isize - span.x0 as isize;
        let (zbuf, cbuf) = (&mut self.depth, &mut self.color);
        let mut n = 0;
        for_each_sample(depth, attrs, span, |x, z, a| {
            let i = (row + x as isize) as usize;
            if z < zbuf[i] {
                zbuf[i] = z;
                cbuf[i] = shade(a).extend(1.0);
                n += 1;
            }
        });
        n
    }

    fn flat_span(&mut self, depth: &DepthPlane, span: Span, color: Vec3) -> u64 {
        self.span(depth, &AttributePlanes::NONE, span, |_| color)
    }

    fn gouraud_span<const PERSPECTIVE: bool>(
        &mut self,
        depth: &DepthPlane,
        planes: &GouraudPlanes,
        span: Span,
    ) -> u64 {
        self.span(depth, planes, span, |a| {
            let c = Vec3::new(a[1], a[2], a[3]);
            if PERSPECTIVE {
                c / a[0]
            } else {
                c
            }
        })
    }

    /// Depth-tests a Phong span and queues the passing samples; shading
    /// happens eight at a time in [`PhongBatch::flush`].
    fn phong_span<const PERSPECTIVE: bool>(
        &mut self,
        depth: &DepthPlane,
        planes: &PhongPlanes,
        span: Span,
        batch: &mut PhongBatch,
        material: &PreparedMaterial,
        lighting: &PreparedLights,
    ) -> u64 {
        let row = self.index(span.x0, span.y) as isize - span.x0 as isize;
        let (zbuf, cbuf) = (&mut self.depth, &mut self.color);
        let mut n = 0;
        for_each_sample(depth, planes, span, |x, z, a| {
            let i = (row + x as isize) as usize;
            if z < zbuf[i] {
                zbuf[i] = z;
                n += 1;
                if batch.push(i, a) {
                    batch.flush::<PERSPECTIVE>(cbuf, material, lighting);
                }
            }
        });
        n
    }
}

/// Samples per Phong batch: one `f32x8`.
const LANES: usize = 8;

/// Up to eight depth-tested Phong samples waiting to be shaded together,
/// stored attribute by attribute (SoA).
#[derive(Default)]
struct PhongBatch {
    index: [usize; LANES],
    attrs: [[f32; LANES]; 7],
    len: usize,
}

impl PhongBatch {
    /// Queues a sample; true when the batch is full.
    #[inline(always)]
    fn push(&mut self, index: usize, a: &[f32; 7]) -> bool {
        let k = self.len;
        self.index[k] = index;
        for (plane, &v) in self.attrs.iter_mut().zip(a) {
            plane[k] = v;
        }
        self.len += 1;
        self.len == LANES
    }

    /// Shades the queued samples (SPEC §6 Phong: the normal re-normalized
    /// per sample) and writes their colours. Unused lanes repeat lane 0 and
    /// are not written. Each lane does the scalar path's arithmetic, so a
    /// colour does not depend on how samples were batched.
    #[inline(never)]
    fn flush<const PERSPECTIVE: bool>(
        &mut self,
        cbuf: &mut [Vec4],
        material: &PreparedMaterial,
        lighting: &PreparedLights,
    ) {
        let len = std::mem::take(&mut self.len);
        if len == 0 {
            return;
        }
        for plane in &mut self.attrs {
            let first = plane[0];
            plane[len..].fill(first);
        }
        let a = self.attrs.map(f32x8::from);
        let w = if PERSPECTIVE { f32x8::ONE / a[0] } else { f32x8::ONE };
        let normal = Vec3x8 { x: a[1] * w, y: a[2] * w, z: a[3] * w }.normalize_or_zero();
        let eye = Vec3x8 { x: a[4] * w, y: a[5] * w, z: a[6] * w };
        let c = lighting.shade_x8(material, eye, normal);
        let (r, g, b) = (c.x.to_array(), c.y.to_array(), c.z.to_array());
        for k in 0..len {
            cbuf[self.index[k]] = Vec4::new(r[k], g[k], b[k], 1.0);
        }
    }
}
