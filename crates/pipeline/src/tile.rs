//! Rasterizing one tile: the opaque pass over its bin with a depth buffer in
//! NC depth (SPEC §4), then quantization into the image (SPEC §10).
//!
//! Spans are walked eight samples at a time ([`zline_raster::for_each_block`]):
//! the depth test, the writes and the shading of a block are `f32x8`
//! operations, with lanes outside the span or behind the stored depth
//! masked off. Shading the masked lanes too costs less than gathering the
//! live ones (a batch-and-scatter variant of the Phong kernel measured about
//! a third slower). The colour buffer is three planes (R, G, B) so that
//! blocks load and store whole vectors; the buffers are padded to multiples
//! of eight columns on the global grid, which keeps blocks inside them for
//! any tile size.
//!
//! Kernels are chosen once per primitive — by shading mode and by
//! interpolation — and monomorphized, so a Gouraud block contains no
//! lighting and a screen-linear one no divide.

use glam::Vec3;
use wide::{f32x8, i32x8, CmpEq, CmpGe, CmpLt};
use zline_raster::{for_each_block, AttributePlanes, DepthPlane, Rect, Span, LANES};
use zline_scene::TextureMap;
use zline_shading::{Filter, PreparedLights, PreparedMaterial, Vec3x8};

use crate::bin::{PrimitiveChunk, PrimitiveRef};
use crate::fog::FogPass;
use crate::setup::{
    ColoredPhongAttributes, ColoredPhongPlanes, GouraudPlanes, PhongPlanes, Primitive, Shader, TexturedKind,
    TexturedPlanes,
};

/// NC depth initialised to the far plane (SPEC §4).
pub const DEPTH_CLEAR: f32 = 1.0;

/// Reversed depth's far plane (see [`crate::setup::DepthEncoding`]).
pub const DEPTH_CLEAR_REVERSED: f32 = 0.0;

/// What shading reads besides the primitive.
#[derive(Clone, Copy, Debug)]
pub struct ShadeContext<'a> {
    /// Lights in eye space.
    pub lighting: &'a PreparedLights,
    /// The frame's materials, indexed by [`Shader::Phong::material`].
    pub materials: &'a [PreparedMaterial],
    /// The frame's textures, indexed by [`TexturedPlanes::texture`].
    pub textures: &'a [TextureMap],
}

/// A tile's depth buffer and colour planes, one value per sample, covering
/// columns `origin..origin + stride` (the tile widened to multiples of
/// [`LANES`]).
#[derive(Clone, Debug, Default)]
pub struct TileTarget {
    rect: Rect,
    origin: i32,
    stride: usize,
    depth: Vec<f32>,
    /// The far plane's depth: [`DEPTH_CLEAR`] or [`DEPTH_CLEAR_REVERSED`].
    far: f32,
    rgb: [Vec<f32>; 3],
    background: Vec3,
    /// False while undrawn samples (depth 1) hold stale colours that
    /// [`Self::resolve`] replaces by the background.
    colors_valid: bool,
    /// The transparent primitive being drawn: its opacity and the fog.
    blend: Option<(f32, Option<FogPass>)>,
    /// The alpha cutoff of the textured primitive being drawn (glTF MASK).
    cutoff: Option<f32>,
}

impl TileTarget {
    /// Resets the buffers for a tile (`rect` in samples): depth `far`
    /// ([`DEPTH_CLEAR`], or [`DEPTH_CLEAR_REVERSED`] for reversed depth),
    /// colour the background.
    ///
    /// Only the depth buffer is written. A sample whose depth is still
    /// `far` was never drawn — a fragment is written only when z < stored,
    /// so a written depth is below `far` — and [`Self::resolve`] gives it
    /// the background; the colour planes are not cleared at all. That saves
    /// three of the four stores per sample of a clear.
    pub fn clear(&mut self, rect: Rect, background: Vec3, far: f32) {
        let lanes = LANES as i32;
        self.rect = rect;
        self.origin = rect.x0 & !(lanes - 1);
        self.stride = ((rect.x1 + lanes - 1) & !(lanes - 1)).saturating_sub(self.origin).max(0) as usize;
        let n = self.stride * rect.height() as usize;
        self.depth.clear();
        self.depth.resize(n, far);
        self.far = far;
        self.background = background;
        self.colors_valid = false;
        for plane in &mut self.rgb {
            plane.resize(n, 0.0);
        }
    }

    #[inline]
    fn index(&self, x: i32, y: i32) -> usize {
        (y - self.rect.y0) as usize * self.stride + (x - self.origin) as usize
    }

    /// Draws the primitives `bin` (references into `chunks`) in order;
    /// returns the number of samples that passed the depth test.
    pub fn opaque_pass(
        &mut self,
        chunks: &[PrimitiveChunk],
        bin: &[PrimitiveRef],
        ctx: &ShadeContext<'_>,
    ) -> u64 {
        let mut shaded = 0;
        for r in bin {
            let chunk = &chunks[r.chunk as usize];
            shaded += self.draw::<false>(&chunk.prims[r.index as usize], chunk, ctx);
        }
        shaded
    }

    /// SPEC §9, pass 2: the transparent primitives `bin` back to front
    /// (largest mean NC depth first; ties in draw order, so every tile sorts
    /// alike), each depth-tested against the opaque depth without writing
    /// it, fogged per sample, and blended as C = (1 − kt)·C_surface +
    /// kt·C_behind. `order` is scratch space. Returns the samples blended.
    ///
    /// Where transparent surfaces intersect, each triangle is blended whole
    /// in its sorted place, so the nearer part of the one sorted first ends
    /// up behind the other: the classic artefact of sorting by triangle,
    /// which per-sample sorting (not done here) would remove.
    pub fn transparency_pass(
        &mut self,
        chunks: &[PrimitiveChunk],
        bin: &[PrimitiveRef],
        ctx: &ShadeContext<'_>,
        fog: Option<&FogPass>,
        order: &mut Vec<(f32, PrimitiveRef)>,
    ) -> u64 {
        self.materialize_background();
        let prim = |r: &PrimitiveRef| &chunks[r.chunk as usize].prims[r.index as usize];
        let chunk = |r: &PrimitiveRef| &chunks[r.chunk as usize];
        order.clear();
        order.extend(bin.iter().map(|r| (prim(r).sort_depth, *r)));
        order.sort_by(|a, b| b.0.total_cmp(&a.0)); // stable: ties keep draw order
        let mut shaded = 0;
        for (_, r) in order.iter() {
            let p = prim(r);
            self.blend = Some((1.0 - p.kt, fog.copied()));
            shaded += self.draw::<true>(p, chunk(r), ctx);
        }
        self.blend = None;
        shaded
    }

    /// Writes the background into undrawn samples, so blending reads it as
    /// C_behind.
    fn materialize_background(&mut self) {
        let bg = Vec3x8::splat(self.background);
        let [red, green, blue] = &mut self.rgb;
        for i in (0..self.depth.len()).step_by(LANES) {
            let empty = load(&self.depth, i).cmp_eq(f32x8::splat(self.far));
            for (plane, c) in [(&mut *red, bg.x), (&mut *green, bg.y), (&mut *blue, bg.z)] {
                let old = load(plane, i);
                store(plane, i, empty.blend(c, old));
            }
        }
        self.colors_valid = true;
    }

    /// Quantizes the tile into `band`, the packed RGBA image rows that hold
    /// it (`band` starts at the tile's first row; `width` is the image width
    /// in pixels).
    pub fn resolve(&self, band: &mut [u32], width: usize) {
        if self.stride == 0 {
            return;
        }
        let lanes = LANES as i32;
        let [red, green, blue] = &self.rgb;
        let bg = Vec3x8::splat(self.background);
        for row in 0..self.rect.height() as usize {
            let line = row * self.stride;
            let out = &mut band[row * width..(row + 1) * width];
            for x in (self.origin..self.origin + self.stride as i32).step_by(LANES) {
                let i = line + (x - self.origin) as usize;
                let empty = if self.colors_valid {
                    f32x8::ZERO
                } else {
                    load(&self.depth, i).cmp_eq(f32x8::splat(self.far))
                };
                let c = |plane: &[f32], b: f32x8| empty.blend(b, load(plane, i));
                let px = pack_rgba(c(red, bg.x), c(green, bg.y), c(blue, bg.z));
                if x >= self.rect.x0 && x + lanes <= self.rect.x1 {
                    out[x as usize..x as usize + LANES].copy_from_slice(&px);
                } else {
                    for (k, &p) in px.iter().enumerate() {
                        let c = x + k as i32;
                        if (self.rect.x0..self.rect.x1).contains(&c) {
                            out[c as usize] = p;
                        }
                    }
                }
            }
        }
    }

    /// Box-filters the tile's n×n samples per pixel into `band` (the packed
    /// image rows from the tile's first pixel row; `width` in pixels): each
    /// pixel gets the mean of its samples' colours (the background where a
    /// sample was never drawn), summed in a fixed order, then SPEC §10's
    /// quantization. The tile's rect is in samples and a multiple of n.
    pub fn resolve_supersampled(&self, band: &mut [u32], width: usize, n: u32) {
        let n = n as i32;
        let scale = 1.0 / (n * n) as f32;
        let [red, green, blue] = &self.rgb;
        let (py0, px0) = (self.rect.y0 / n, self.rect.x0 / n);
        for py in py0..self.rect.y1 / n {
            let out = &mut band[(py - py0) as usize * width..][..width];
            for px in px0..self.rect.x1 / n {
                let mut sum = Vec3::ZERO;
                for sy in py * n..(py + 1) * n {
                    for sx in px * n..(px + 1) * n {
                        let i = self.index(sx, sy);
                        let drawn = self.colors_valid || self.depth[i] != self.far;
                        sum += if drawn { Vec3::new(red[i], green[i], blue[i]) } else { self.background };
                    }
                }
                out[px as usize] = crate::image::quantize_rgba((sum * scale).extend(1.0));
            }
        }
    }

    /// Fogs every drawn sample of the tile (see [`crate::fog`]).
    pub fn fog_pass(&mut self, pass: &FogPass) {
        let fog = Vec3x8::splat(pass.color());
        let [red, green, blue] = &mut self.rgb;
        for row in 0..self.rect.height() as usize {
            let y = self.rect.y0 + row as i32;
            for x in (self.origin..self.origin + self.stride as i32).step_by(LANES) {
                let i = row * self.stride + (x - self.origin) as usize;
                let z = load(&self.depth, i);
                let drawn = z.cmp_lt(f32x8::splat(self.far));
                if drawn.none() {
                    continue;
                }
                let f = pass.factors(x, y, z);
                let g = f32x8::ONE - f;
                for (plane, c) in [(&mut *red, fog.x), (&mut *green, fog.y), (&mut *blue, fog.z)] {
                    let old = load(plane, i);
                    store(plane, i, drawn.blend(old * f + c * g, old));
                }
            }
        }
    }

    /// Draws one primitive, opaque (`T` false: depth written, colour
    /// replaced) or transparent (`T` true: see [`Self::transparency_pass`]).
    fn draw<const T: bool>(&mut self, p: &Primitive, chunk: &PrimitiveChunk, ctx: &ShadeContext<'_>) -> u64 {
        let mut n = 0;
        let clip = self.rect;
        match (p.shader, p.perspective) {
            (Shader::Flat { color }, _) => {
                let c = Vec3x8::splat(color);
                p.edges.scan(clip, |s| {
                    n += self.blocks::<0, T>(&p.depth, &AttributePlanes::NONE, s, |_| (c, f32x8::ONE))
                });
            }
            (Shader::Gouraud { planes }, true) => {
                p.edges.scan(clip, |s| n += self.gouraud::<true, T>(&p.depth, &planes, s));
            }
            (Shader::Gouraud { planes }, false) => {
                p.edges.scan(clip, |s| n += self.gouraud::<false, T>(&p.depth, &planes, s));
            }
            (Shader::Textured { index }, persp) => {
                let t = &chunk.textured[index as usize];
                let (map, m) = (&ctx.textures[t.texture as usize], &ctx.materials[t.material as usize]);
                self.cutoff = map.alpha_cutoff;
                if persp {
                    p.edges.scan(clip, |s| {
                        n += self.textured::<9, true, T>(&p.depth, t, map, m, ctx.lighting, s)
                    });
                } else {
                    p.edges.scan(clip, |s| {
                        n += self.textured::<9, false, T>(&p.depth, t, map, m, ctx.lighting, s)
                    });
                }
                self.cutoff = None;
            }
            (Shader::Phong { planes, material }, persp) => {
                let (m, l) = (&ctx.materials[material as usize], ctx.lighting);
                if persp {
                    p.edges.scan(clip, |s| n += self.phong::<true, T>(&p.depth, &planes, s, m, l));
                } else {
                    p.edges.scan(clip, |s| n += self.phong::<false, T>(&p.depth, &planes, s, m, l));
                }
            }
            (Shader::ColoredPhong { index }, persp) => {
                n += self.draw_colored_phong::<T>(p, &chunk.colored_phong[index as usize], persp, ctx);
            }
            (Shader::TexturedColored { index }, persp) => {
                n += self.draw_textured_colored::<T>(p, &chunk.textured_colored[index as usize], persp, ctx);
            }
        }
        n
    }

    /// Draws an untextured Phong primitive with vertex colours. Kept out of
    /// [`Self::draw`] (not inlined) so that the kernels of primitives
    /// without colours are compiled as if these did not exist.
    #[inline(never)]
    fn draw_colored_phong<const T: bool>(
        &mut self,
        p: &Primitive,
        c: &ColoredPhongPlanes,
        persp: bool,
        ctx: &ShadeContext<'_>,
    ) -> u64 {
        let (m, l) = (&ctx.materials[c.material as usize], ctx.lighting);
        let (clip, mut n) = (self.rect, 0);
        if persp {
            p.edges.scan(clip, |s| n += self.colored_phong::<true, T>(&p.depth, &c.planes, s, m, l));
        } else {
            p.edges.scan(clip, |s| n += self.colored_phong::<false, T>(&p.depth, &c.planes, s, m, l));
        }
        n
    }

    /// Draws a textured Phong primitive with vertex colours (out of line
    /// like [`Self::draw_colored_phong`]).
    #[inline(never)]
    fn draw_textured_colored<const T: bool>(
        &mut self,
        p: &Primitive,
        t: &TexturedPlanes<12>,
        persp: bool,
        ctx: &ShadeContext<'_>,
    ) -> u64 {
        let (map, m) = (&ctx.textures[t.texture as usize], &ctx.materials[t.material as usize]);
        let (clip, mut n) = (self.rect, 0);
        self.cutoff = map.alpha_cutoff;
        if persp {
            p.edges.scan(clip, |s| n += self.textured::<12, true, T>(&p.depth, t, map, m, ctx.lighting, s));
        } else {
            p.edges.scan(clip, |s| n += self.textured::<12, false, T>(&p.depth, t, map, m, ctx.lighting, s));
        }
        self.cutoff = None;
        n
    }

    /// The block kernel: depth-tests each block of `span`, and where any
    /// lane passes, writes depth and the colours `shade` returns for the
    /// block's attributes (in every passing lane). Transparent (`T`): no
    /// depth write; the colour is fogged and blended over the stored one.
    #[inline(always)]
    fn blocks<const N: usize, const T: bool>(
        &mut self,
        depth: &DepthPlane,
        attrs: &AttributePlanes<N>,
        span: Span,
        mut shade: impl FnMut(&[f32x8; N]) -> (Vec3x8, f32x8),
    ) -> u64 {
        let row = self.index(self.origin, span.y);
        let origin = self.origin;
        let (opacity, fog) = self.blend.unwrap_or((1.0, None));
        let cutoff = self.cutoff;
        let opacity = f32x8::splat(opacity);
        let (zbuf, [red, green, blue]) = (&mut self.depth, &mut self.rgb);
        let mut n = 0;
        for_each_block(depth, attrs, span, |b| {
            let i = row + (b.x - origin) as usize;
            let (z, stored) = (f32x8::from(b.z), load(zbuf, i));
            let mut live = lane_mask(b.mask) & z.cmp_lt(stored);
            if live.none() {
                return;
            }
            let (mut c, alpha) = shade(&b.attrs.map(f32x8::from));
            if let Some(cut) = cutoff {
                // MASK: a sample below the cutoff is discarded before it can
                // write depth.
                live &= alpha.cmp_ge(f32x8::splat(cut));
            }
            let bits = live.move_mask();
            if bits == 0 {
                return;
            }
            n += u64::from(bits.count_ones());
            let alpha = if cutoff.is_some() { f32x8::ONE } else { alpha };
            // C = (1 − kt)·C_surface + kt·C_behind with 1 − kt = opacity·alpha
            // (alpha is 1 but for textures whose alpha blends).
            let keep = opacity * alpha;
            let behind = f32x8::ONE - keep;
            if T {
                if let Some(fog) = &fog {
                    let (f, fc) = (fog.factors(b.x, span.y, z), Vec3x8::splat(fog.color()));
                    let g = f32x8::ONE - f;
                    c = Vec3x8 { x: c.x * f + fc.x * g, y: c.y * f + fc.y * g, z: c.z * f + fc.z * g };
                }
            } else {
                store(zbuf, i, live.blend(z, stored));
            }
            for (plane, v) in [(&mut *red, c.x), (&mut *green, c.y), (&mut *blue, c.z)] {
                let old = load(plane, i);
                let new = if T { v * keep + old * behind } else { v };
                store(plane, i, live.blend(new, old));
            }
        });
        n
    }

    fn gouraud<const PERSPECTIVE: bool, const T: bool>(
        &mut self,
        depth: &DepthPlane,
        planes: &GouraudPlanes,
        span: Span,
    ) -> u64 {
        self.blocks::<4, T>(depth, planes, span, |a| {
            let c = Vec3x8 { x: a[1], y: a[2], z: a[3] };
            let c = if PERSPECTIVE { Vec3x8 { x: c.x / a[0], y: c.y / a[0], z: c.z / a[0] } } else { c };
            (c, f32x8::ONE)
        })
    }

    /// SPEC §6 Phong: normal and eye position interpolated, the normal
    /// re-normalized per sample, the lighting model per sample.
    fn phong<const PERSPECTIVE: bool, const T: bool>(
        &mut self,
        depth: &DepthPlane,
        planes: &PhongPlanes,
        span: Span,
        material: &PreparedMaterial,
        lighting: &PreparedLights,
    ) -> u64 {
        self.blocks::<7, T>(depth, planes, span, |a| {
            let w = if PERSPECTIVE { f32x8::ONE / a[0] } else { f32x8::ONE };
            let normal = Vec3x8 { x: a[1] * w, y: a[2] * w, z: a[3] * w }.normalize_or_zero();
            let eye = Vec3x8 { x: a[4] * w, y: a[5] * w, z: a[6] * w };
            (lighting.shade_x8(material, eye, normal), f32x8::ONE)
        })
    }

    /// [`Self::phong`] with the vertex colour c interpolated too, multiplying
    /// ka and kd like a texel: c ⊙ (ambient+diffuse) + specular, clamped.
    fn colored_phong<const PERSPECTIVE: bool, const T: bool>(
        &mut self,
        depth: &DepthPlane,
        planes: &ColoredPhongAttributes,
        span: Span,
        material: &PreparedMaterial,
        lighting: &PreparedLights,
    ) -> u64 {
        self.blocks::<10, T>(depth, planes, span, |a| {
            let w = if PERSPECTIVE { f32x8::ONE / a[0] } else { f32x8::ONE };
            let normal = Vec3x8 { x: a[1] * w, y: a[2] * w, z: a[3] * w }.normalize_or_zero();
            let eye = Vec3x8 { x: a[4] * w, y: a[5] * w, z: a[6] * w };
            let tint = Vec3x8 { x: a[7] * w, y: a[8] * w, z: a[9] * w };
            let (ambient_diffuse, specular) = lighting.shade_parts_x8(material, eye, normal);
            ((tint * ambient_diffuse + specular).clamp01(), f32x8::ONE)
        })
    }

    /// SPEC §7: texture coordinates interpolated (perspective-correct or
    /// not), the texel sampled with the map's sampler — the level of detail
    /// from the exact per-sample derivatives of s and t — and
    /// c = texel ⊙ (ambient+diffuse) + specular, clamped. With twelve
    /// planes (`N` = 12, Phong with vertex colours) the interpolated vertex
    /// colour multiplies ambient+diffuse too.
    #[allow(clippy::too_many_arguments, reason = "one kernel's inputs, passed through unchanged")]
    fn textured<const N: usize, const PERSPECTIVE: bool, const T: bool>(
        &mut self,
        depth: &DepthPlane,
        t: &TexturedPlanes<N>,
        map: &TextureMap,
        material: &PreparedMaterial,
        lighting: &PreparedLights,
        span: Span,
    ) -> u64 {
        let (dx, dy) = (t.planes.dx(), t.planes.dy());
        let (w, h) = (map.texture.width(), map.texture.height());
        let trilinear = map.sampler.filter == Filter::Trilinear;
        let blend_alpha = (T && map.alpha_blend) || map.alpha_cutoff.is_some();
        let kind = t.kind;
        self.blocks::<N, T>(depth, &t.planes, span, |a| {
            let inv = if PERSPECTIVE { f32x8::ONE / a[0] } else { f32x8::ONE };
            let (s, tt) = (a[1] * inv, a[2] * inv);
            let lods = if trilinear {
                // s = S/Q with S = s/w and Q = 1/w planes: ∂s/∂x = (∂S/∂x − s·∂Q/∂x)/Q.
                let d = |ds: f32, dq: f32, v: f32x8| {
                    if PERSPECTIVE {
                        (f32x8::splat(ds) - v * f32x8::splat(dq)) * inv
                    } else {
                        f32x8::splat(ds)
                    }
                };
                // `shading::lod` for eight lanes: ½·log2 of the larger squared
                // footprint in texels, with `wide`'s vector log2 (one call
                // instead of eight of libm's, which measured ~12 % of a
                // textured frame). Zero or NaN footprints read level 0.
                let (fw, fh) = (f32x8::splat(w as f32), f32x8::splat(h as f32));
                let (sx, tx) = (d(dx[1], dx[0], s) * fw, d(dx[2], dx[0], tt) * fh);
                let (sy, ty) = (d(dy[1], dy[0], s) * fw, d(dy[2], dy[0], tt) * fh);
                let footprint = (sx * sx + tx * tx).max(sy * sy + ty * ty);
                f32x8::splat(0.5) * footprint.log2()
            } else {
                f32x8::ZERO
            };
            let [r, g, b, texel_alpha] = map.texture.sample_x8(&map.sampler, s, tt, lods);
            let texel = Vec3x8 { x: r, y: g, z: b };
            let pair = |i: usize| Vec3x8 { x: a[i] * inv, y: a[i + 1] * inv, z: a[i + 2] * inv };
            let (ambient_diffuse, specular) = match kind {
                TexturedKind::Flat { ambient_diffuse, specular } => {
                    (Vec3x8::splat(ambient_diffuse), Vec3x8::splat(specular))
                }
                TexturedKind::Gouraud => (pair(3), pair(6)),
                TexturedKind::Phong => {
                    lighting.shade_parts_x8(material, pair(6), pair(3).normalize_or_zero())
                }
            };
            let ambient_diffuse = if N == 12 { pair(9) * ambient_diffuse } else { ambient_diffuse };
            let alpha = if blend_alpha { texel_alpha } else { f32x8::ONE };
            ((texel * ambient_diffuse + specular).clamp01(), alpha)
        })
    }
}

/// Eight floats from `buf[i..i + 8]`.
#[inline(always)]
fn load(buf: &[f32], i: usize) -> f32x8 {
    let lanes: [f32; LANES] = buf[i..i + LANES].try_into().unwrap_or([0.0; LANES]);
    f32x8::from(lanes)
}

/// Writes eight floats to `buf[i..i + 8]`.
#[inline(always)]
fn store(buf: &mut [f32], i: usize, v: f32x8) {
    buf[i..i + LANES].copy_from_slice(&v.to_array());
}

/// An all-ones lane for each set bit of `bits`.
#[inline(always)]
fn lane_mask(bits: u8) -> f32x8 {
    let lane_bits = i32x8::from([1, 2, 4, 8, 16, 32, 64, 128]);
    let set = (i32x8::splat(i32::from(bits)) & lane_bits).cmp_eq(lane_bits);
    bytemuck::cast(set)
}

/// SPEC §10 for eight pixels: each channel clamped (NaN to 0), scaled,
/// rounded half up, packed as in [`crate::Image`]. c·255 + 0.5 lies in
/// [0.5, 255.5] after the clamp, where truncation is the floor.
#[inline(always)]
fn pack_rgba(r: f32x8, g: f32x8, b: f32x8) -> [u32; LANES] {
    let q = |c: f32x8| {
        let c = c.cmp_eq(c).blend(c, f32x8::ZERO);
        (c.fast_max(f32x8::ZERO).fast_min(f32x8::ONE) * f32x8::splat(255.0) + f32x8::splat(0.5))
            .fast_trunc_int()
    };
    let alpha = i32x8::splat(0xFF << 24);
    let packed = q(r) | (q(g) * i32x8::splat(1 << 8)) | (q(b) * i32x8::splat(1 << 16)) | alpha;
    bytemuck::cast(packed)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image::quantize;

    #[test]
    fn pack_matches_the_scalar_quantizer() {
        let r: [f32; 8] = [0.0, 1.0, 0.5, f32::NAN, -2.0, 7.0, 0.2, 100.0 / 255.0];
        let g = r.map(|v| v * 0.7);
        let b = r.map(|v| 1.0 - v);
        let got = pack_rgba(f32x8::from(r), f32x8::from(g), f32x8::from(b));
        for k in 0..8 {
            let want = u32::from_le_bytes([quantize(r[k]), quantize(g[k]), quantize(b[k]), 255]);
            assert_eq!(got[k], want, "lane {k}");
        }
    }

    #[test]
    fn lane_masks_follow_bits() {
        let m: [u32; 8] = bytemuck::cast(lane_mask(0b1010_0110));
        assert_eq!(m.map(|v| v != 0), [false, true, true, false, false, true, false, true]);
    }
}
