//! The span kernels: one monomorphized function per [`Kernel`], pass and
//! texture use.
//!
//! [`TileTarget::blocks`] is the loop every kernel shares — depth test,
//! alpha test, depth and colour writes or blending — and each kernel passes
//! it the closure that shades eight samples from their interpolated
//! attributes. What varies between primitives is a type parameter, not a
//! branch in that loop (the one exception, the transparency pass's fog, is
//! the same for a whole frame):
//!
//! | parameter | types | decides |
//! |---|---|---|
//! | [`Interp`] | [`Perspective`], [`Linear`] | a/w ÷ 1/w per sample, or the plane value itself |
//! | [`Pass`] | [`Opaque`], [`Blend`] | depth write and replace, or blend (fogged per sample when the frame has fog) |
//! | [`Alpha`] | [`IgnoreAlpha`], [`MaskAlpha`], [`TextureAlpha`] | the texel's alpha ignored, tested against the cutoff, or blended |
//! | [`Lod`] | [`BaseLod`], [`DerivativeLod`] | level 0, or the level from the exact derivatives of s and t |
//! | [`Clamp`] | [`ClampedAtVertices`], [`ClampPerSample`] | Gouraud: colours used as interpolated, or clamped per sample |
//!
//! [`Kernel`]: crate::setup::Kernel

use zline_raster::{for_each_block, AttributePlanes, DepthPlane, EdgeTable, Span, LANES};
use zline_shading::Vec3x8;
use zline_simd::lanes::{f32x8, i32x8, Level};

use super::target::{load, load_for_blend, store, FrameTexture, ShadeContext, TileTarget};
use crate::fog::FogPass;
use crate::setup::layout::{gouraud, phong, textured};
use crate::setup::{Flat, Gouraud, Phong, Primitive, TexturedFlat, TexturedGouraud, TexturedPhong};

/// How attributes are recovered from their planes.
pub(crate) trait Interp {
    /// True for perspective-correct planes (a/w and 1/w).
    const PERSPECTIVE: bool;
    /// The factor that turns a plane value into the attribute: 1/(1/w) or 1.
    fn w<S: Level>(q: f32x8<S>) -> f32x8<S>;
    /// `v` over `q` (perspective) or `v` itself.
    fn divide<S: Level>(v: f32x8<S>, q: f32x8<S>) -> f32x8<S>;
}

/// Perspective-correct interpolation: planes hold a/w and 1/w.
pub(crate) struct Perspective;

/// Screen-linear interpolation: planes hold a; no divide.
pub(crate) struct Linear;

impl Interp for Perspective {
    const PERSPECTIVE: bool = true;
    #[inline(always)]
    fn w<S: Level>(q: f32x8<S>) -> f32x8<S> {
        f32x8::ONE / q
    }
    #[inline(always)]
    fn divide<S: Level>(v: f32x8<S>, q: f32x8<S>) -> f32x8<S> {
        v / q
    }
}

impl Interp for Linear {
    const PERSPECTIVE: bool = false;
    #[inline(always)]
    fn w<S: Level>(_: f32x8<S>) -> f32x8<S> {
        f32x8::ONE
    }
    #[inline(always)]
    fn divide<S: Level>(v: f32x8<S>, _: f32x8<S>) -> f32x8<S> {
        v
    }
}

/// What the Gouraud kernel does with a sample's interpolated colour
/// (`zline_scene::GouraudClamp`).
pub(crate) trait Clamp {
    /// The colour drawn.
    fn clamp<S: Level>(c: Vec3x8<S>) -> Vec3x8<S>;
}

/// The vertex colours were clamped to [0, 1]: their interpolation is used
/// as it is.
pub(crate) struct ClampedAtVertices;

/// The vertex colours are unclamped: each sample is clamped to [0, 1].
pub(crate) struct ClampPerSample;

impl Clamp for ClampedAtVertices {
    #[inline(always)]
    fn clamp<S: Level>(c: Vec3x8<S>) -> Vec3x8<S> {
        c
    }
}

impl Clamp for ClampPerSample {
    #[inline(always)]
    fn clamp<S: Level>(c: Vec3x8<S>) -> Vec3x8<S> {
        c.clamp01()
    }
}

/// The pass a primitive is drawn in.
pub(crate) trait Pass {
    /// False: depth is written and the colour replaced (opaque). True: depth
    /// is only tested and the colour blended over the stored one.
    const BLENDS: bool;
    /// The surface's weight 1 − kt in the blend.
    fn opacity<S: Level>(&self) -> f32x8<S>;
    /// The fragment's colour after fog (blending passes fog per sample; the
    /// opaque pass leaves fog to [`TileTarget::fog_pass`]).
    fn fog<S: Level>(&self, c: Vec3x8<S>, x: i32, y: i32, z: f32x8<S>) -> Vec3x8<S>;
}

/// The opaque pass.
pub(crate) struct Opaque;

/// The transparency pass, with per-sample fog when the frame has fog (one
/// kernel for both: the branch is taken per block, the same way for the
/// whole frame, and halves the transparency pass's kernel count).
pub(crate) struct Blend<'a> {
    /// 1 − kt.
    pub(crate) opacity: f32x8,
    /// The frame's fog and its colour.
    pub(crate) fog: Option<(&'a FogPass, Vec3x8)>,
}

impl<'a> Blend<'a> {
    /// The pass for a surface of transmission `kt` under `fog`.
    #[inline(always)]
    pub(crate) fn new(kt: f32, fog: Option<&'a FogPass>) -> Self {
        Blend { opacity: f32x8::splat(1.0 - kt), fog: fog.map(|f| (f, Vec3x8::splat(f.color()))) }
    }
}

impl Pass for Opaque {
    const BLENDS: bool = false;
    #[inline(always)]
    fn opacity<S: Level>(&self) -> f32x8<S> {
        f32x8::ONE
    }
    #[inline(always)]
    fn fog<S: Level>(&self, c: Vec3x8<S>, _: i32, _: i32, _: f32x8<S>) -> Vec3x8<S> {
        c
    }
}

impl Pass for Blend<'_> {
    const BLENDS: bool = true;
    #[inline(always)]
    fn opacity<S: Level>(&self) -> f32x8<S> {
        self.opacity.at()
    }
    #[inline(always)]
    fn fog<S: Level>(&self, c: Vec3x8<S>, x: i32, y: i32, z: f32x8<S>) -> Vec3x8<S> {
        let Some((fog, color)) = self.fog else { return c };
        let (f, fc) = (fog.factors(x, y, z), color.at::<S>());
        let g = f32x8::ONE - f;
        Vec3x8 { x: c.x * f + fc.x * g, y: c.y * f + fc.y * g, z: c.z * f + fc.z * g }
    }
}

/// What the texel's alpha does. By default nothing: every lane stays live
/// and the pass's opacity is used as it is.
pub(crate) trait Alpha: Sized {
    /// The use for a texture.
    fn new(texture: &FrameTexture) -> Self;
    /// The lanes still live after the alpha test.
    #[inline(always)]
    fn test<S: Level>(&self, live: f32x8<S>, _alpha: f32x8<S>) -> f32x8<S> {
        live
    }
    /// The factor on the pass's opacity.
    #[inline(always)]
    fn weight<S: Level>(_alpha: f32x8<S>) -> f32x8<S> {
        f32x8::ONE
    }
}

/// The alpha is ignored (and untextured kernels have none).
pub(crate) struct IgnoreAlpha;

/// Samples whose alpha is below the cutoff are discarded before they write
/// depth; the rest are drawn opaque.
pub(crate) struct MaskAlpha(f32x8);

/// The alpha multiplies the pass's opacity.
pub(crate) struct TextureAlpha;

impl Alpha for IgnoreAlpha {
    #[inline(always)]
    fn new(_: &FrameTexture) -> Self {
        IgnoreAlpha
    }
}

impl Alpha for MaskAlpha {
    #[inline(always)]
    fn new(texture: &FrameTexture) -> Self {
        MaskAlpha(f32x8::splat(texture.cutoff))
    }
    #[inline(always)]
    fn test<S: Level>(&self, live: f32x8<S>, alpha: f32x8<S>) -> f32x8<S> {
        live & alpha.cmp_ge(self.0.at())
    }
}

impl Alpha for TextureAlpha {
    #[inline(always)]
    fn new(_: &FrameTexture) -> Self {
        TextureAlpha
    }
    #[inline(always)]
    fn weight<S: Level>(alpha: f32x8<S>) -> f32x8<S> {
        alpha
    }
}

/// How a textured kernel finds the level of detail.
pub(crate) trait Lod {
    /// The levels of eight samples at (s, t), from the plane gradients
    /// `dx`, `dy` (planes Q, S, T) and `inv` (the [`Interp::w`] factor).
    fn lods<I: Interp, S: Level>(d: &Derivatives, s: f32x8<S>, t: f32x8<S>, inv: f32x8<S>) -> f32x8<S>;
}

/// The plane gradients a [`DerivativeLod`] reads, in texels.
pub(crate) struct Derivatives {
    dx: [f32; 3],
    dy: [f32; 3],
    size: (f32, f32),
}

impl Derivatives {
    fn new<const N: usize>(planes: &AttributePlanes<N>, texture: &FrameTexture) -> Derivatives {
        let (dx, dy) = (planes.dx(), planes.dy());
        let (q, s, t) = (textured::Q, textured::S, textured::T);
        let (w, h) = (texture.texture.width(), texture.texture.height());
        Derivatives { dx: [dx[q], dx[s], dx[t]], dy: [dy[q], dy[s], dy[t]], size: (w as f32, h as f32) }
    }
}

/// Level 0 (nearest and bilinear filtering).
pub(crate) struct BaseLod;

/// The level from the exact per-sample derivatives (trilinear filtering).
pub(crate) struct DerivativeLod;

impl Lod for BaseLod {
    #[inline(always)]
    fn lods<I: Interp, S: Level>(_: &Derivatives, _: f32x8<S>, _: f32x8<S>, _: f32x8<S>) -> f32x8<S> {
        f32x8::ZERO
    }
}

impl Lod for DerivativeLod {
    /// `shading::lod` for eight lanes: ½·log2 of the larger squared
    /// footprint in texels, with `wide`'s vector log2 (one call instead of
    /// eight of libm's, which measured ~12 % of a textured frame). Zero or
    /// NaN footprints read level 0.
    #[inline(always)]
    fn lods<I: Interp, S: Level>(d: &Derivatives, s: f32x8<S>, t: f32x8<S>, inv: f32x8<S>) -> f32x8<S> {
        // s = S/Q with S = s/w and Q = 1/w planes: ∂s/∂x = (∂S/∂x − s·∂Q/∂x)/Q.
        let derivative = zline_simd::inlined(
            #[inline(always)]
            |ds: f32, dq: f32, v: f32x8<S>| {
                if I::PERSPECTIVE {
                    (f32x8::splat(ds) - v * f32x8::splat(dq)) * inv
                } else {
                    f32x8::splat(ds)
                }
            },
        );
        let (fw, fh) = (f32x8::splat(d.size.0), f32x8::splat(d.size.1));
        let (dx, dy) = (d.dx, d.dy);
        let (sx, tx) = (derivative(dx[1], dx[0], s) * fw, derivative(dx[2], dx[0], t) * fh);
        let (sy, ty) = (derivative(dy[1], dy[0], s) * fw, derivative(dy[2], dy[0], t) * fh);
        let footprint = (sx * sx + tx * tx).max(sy * sy + ty * ty);
        f32x8::splat(0.5) * footprint.log2()
    }
}

/// What both Phong kernels recover per sample ([`phong`] layout): the
/// factor w, the eye position and the re-normalized normal.
#[inline(always)]
fn phong_point<const N: usize, I: Interp, S: Level>(a: &[f32x8<S>; N]) -> (f32x8<S>, Vec3x8<S>, Vec3x8<S>) {
    let w = I::w(a[phong::Q]);
    (w, triple(a, phong::EYE, w), triple(a, phong::NORMAL, w).normalize_or_zero())
}

/// A unit normal as a colour: (n + 1)/2 per axis (the normals frame).
#[inline(always)]
pub(super) fn encode_normal<S: Level>(n: Vec3x8<S>) -> Vec3x8<S> {
    let (half, one) = (f32x8::splat(0.5), f32x8::ONE);
    Vec3x8 { x: (n.x + one) * half, y: (n.y + one) * half, z: (n.z + one) * half }
}

/// Three consecutive planes from `i`, each times `w`.
#[inline(always)]
pub(super) fn triple<const N: usize, S: Level>(a: &[f32x8<S>; N], i: usize, w: f32x8<S>) -> Vec3x8<S> {
    Vec3x8 { x: a[i] * w, y: a[i + 1] * w, z: a[i + 2] * w }
}

impl TileTarget {
    /// Scan-converts one primitive and runs [`Self::blocks`] on each span.
    ///
    /// The planes are copied to the stack first, so the compiler knows the
    /// kernel's stores into the tile's buffers leave them alone, and the
    /// shading closure is passed by value (it holds only references), so it
    /// is inlined into the block loop (through `&mut F` it was a call per
    /// block: 6 % more instructions in the Phong kernel, measured with
    /// callgrind).
    #[inline(always)]
    pub(super) fn scan<const N: usize, P: Pass, A: Alpha, S: Level>(
        &mut self,
        (edges, depth): (&EdgeTable, &DepthPlane),
        planes: &AttributePlanes<N>,
        pass: &P,
        alpha: &A,
        shade: impl Fn(&[f32x8<S>; N], i32x8<S>) -> (Vec3x8<S>, f32x8<S>) + Copy,
    ) -> u64 {
        let (depth, planes) = (*depth, *planes);
        let mut n = 0;
        edges.scan(
            self.rect,
            #[inline(always)]
            |s| n += self.blocks(&depth, &planes, s, pass, alpha, shade),
        );
        n
    }

    /// The loop every kernel shares: depth-tests each block of `span`, and
    /// where any lane passes, shades the block with `shade` (colour and
    /// alpha, from the attributes and the block's shadow mask: see
    /// [`TileTarget::shadow_pass`]; kernels that ignore the mask never load
    /// it), applies the alpha test, then writes depth and colour
    /// (opaque) or fogs and blends the colour without writing depth
    /// (transparent). Returns the samples that passed.
    #[inline(always)]
    fn blocks<const N: usize, P: Pass, A: Alpha, S: Level>(
        &mut self,
        depth: &DepthPlane,
        attrs: &AttributePlanes<N>,
        span: Span,
        pass: &P,
        alpha_use: &A,
        shade: impl Fn(&[f32x8<S>; N], i32x8<S>) -> (Vec3x8<S>, f32x8<S>),
    ) -> u64 {
        let row = self.index(self.origin, span.y);
        let origin = self.origin;
        let opacity = pass.opacity();
        let (zbuf, [red, green, blue], shadow) = (&mut self.depth, &mut self.rgb, &self.shadow);
        // The alpha plane, blended like a colour of 1 (coverage only).
        let mut coverage = (P::BLENDS && self.coverage).then_some(&mut self.alpha);
        let mut n = 0;
        for_each_block(
            depth,
            attrs,
            span,
            #[inline(always)]
            |b| {
                let i = row + (b.x - origin) as usize;
                let (z, stored) = (f32x8::from(b.z), load(zbuf, i));
                let live = lane_mask(b.mask) & z.cmp_lt(stored);
                if live.none() {
                    return;
                }
                let mask = shadow.get(i / LANES).map_or(
                    i32x8::ZERO,
                    #[inline(always)]
                    |m| m.at(),
                );
                // Element by element: `map` and `array::from_fn` stay calls
                // (`try_map`) plus a copy of the array in some kernels (the
                // normal-mapped one measured 1.1x).
                let mut attrs = [f32x8::ZERO; N];
                for (a, w) in attrs.iter_mut().zip(&b.attrs) {
                    *a = f32x8::from(*w);
                }
                let (c, alpha) = shade(&attrs, mask);
                let live = alpha_use.test(live, alpha);
                let bits = live.move_mask();
                if bits == 0 {
                    return;
                }
                n += u64::from(bits.count_ones());
                if P::BLENDS {
                    // C = (1 − kt)·C_surface + kt·C_behind with 1 − kt =
                    // opacity·alpha (alpha is 1 but for textures whose alpha
                    // blends).
                    let keep = opacity * A::weight(alpha);
                    let behind = f32x8::ONE - keep;
                    let c = pass.fog(c, b.x, span.y, z);
                    for (plane, v) in [(&mut *red, c.x), (&mut *green, c.y), (&mut *blue, c.z)] {
                        let old = load_for_blend(plane, i);
                        store(plane, i, live.blend(v * keep + old * behind, old));
                    }
                    if let Some(alpha) = coverage.as_deref_mut() {
                        let old = load_for_blend(alpha, i);
                        store(alpha, i, live.blend(keep + old * behind, old));
                    }
                } else {
                    store(zbuf, i, live.blend(z, stored));
                    for (plane, v) in [(&mut *red, c.x), (&mut *green, c.y), (&mut *blue, c.z)] {
                        let old = load_for_blend(plane, i);
                        store(plane, i, live.blend(v, old));
                    }
                }
            },
        );
        n
    }

    /// SPEC §6 flat: one colour.
    #[inline(always)]
    pub(super) fn flat<P: Pass, S: Level>(&mut self, p: &Primitive<Flat>, pass: &P) -> u64 {
        let c = Vec3x8::<S>::splat(p.shader.color);
        let planes = AttributePlanes::NONE;
        self.scan::<_, _, _, S>(
            (&p.edges, &p.depth),
            &planes,
            pass,
            &IgnoreAlpha,
            #[inline(always)]
            |_, _| (c, f32x8::ONE),
        )
    }

    /// SPEC §6 Gouraud: the lit vertex colours interpolated (and clamped
    /// per sample when `C` says so).
    #[inline(always)]
    pub(super) fn gouraud<I: Interp, C: Clamp, P: Pass, S: Level>(
        &mut self,
        p: &Primitive<Gouraud>,
        pass: &P,
    ) -> u64 {
        self.scan::<_, _, _, S>(
            (&p.edges, &p.depth),
            &p.shader.planes,
            pass,
            &IgnoreAlpha,
            #[inline(always)]
            |a, _| {
                let (q, c) = (a[gouraud::Q], gouraud::COLOR);
                let c =
                    Vec3x8 { x: I::divide(a[c], q), y: I::divide(a[c + 1], q), z: I::divide(a[c + 2], q) };
                (C::clamp(c), f32x8::ONE)
            },
        )
    }

    /// SPEC §6 Phong: normal and eye position interpolated, the normal
    /// re-normalized per sample, the lighting model per sample.
    #[inline(always)]
    pub(super) fn phong<I: Interp, P: Pass, S: Level>(
        &mut self,
        p: &Primitive<Phong<{ phong::LEN }>>,
        ctx: &ShadeContext<'_>,
        pass: &P,
    ) -> u64 {
        let (m, l) = (&ctx.materials[p.shader.material as usize], ctx.lighting);
        let (edges, planes) = ((&p.edges, &p.depth), &p.shader.planes);
        if ctx.normals {
            return self.scan::<_, _, _, S>(
                edges,
                planes,
                pass,
                &IgnoreAlpha,
                #[inline(always)]
                |a, _| (encode_normal(phong_point::<_, I, _>(a).2), f32x8::ONE),
            );
        }
        if let Some(maps) = ctx.maps {
            return self.scan::<_, _, _, S>(
                edges,
                planes,
                pass,
                &IgnoreAlpha,
                #[inline(always)]
                |a, _| {
                    let (_, eye, normal) = phong_point::<_, I, _>(a);
                    let (ad, sp) = l.shade_parts_x8_shared(
                        m,
                        eye,
                        normal,
                        #[inline(always)]
                        |k, p, n| maps.visibility_x8(k, p, n),
                    );
                    ((ad + sp).clamp01(), f32x8::ONE)
                },
            );
        }
        if m.shadow_bits.is_some() {
            return self.scan::<_, _, _, S>(
                edges,
                planes,
                pass,
                &IgnoreAlpha,
                #[inline(always)]
                |a, mask| {
                    let (_, eye, normal) = phong_point::<_, I, _>(a);
                    (l.shade_x8_shadowed(m, eye, normal, mask), f32x8::ONE)
                },
            );
        }
        self.scan::<_, _, _, S>(
            edges,
            planes,
            pass,
            &IgnoreAlpha,
            #[inline(always)]
            |a, _| {
                let (_, eye, normal) = phong_point::<_, I, _>(a);
                (l.shade_x8(m, eye, normal), f32x8::ONE)
            },
        )
    }

    /// [`Self::phong`] with the vertex colour interpolated too, multiplying
    /// ka and kd like a texel: c ⊙ (ambient+diffuse) + specular, clamped.
    #[inline(always)]
    pub(super) fn phong_tinted<I: Interp, P: Pass, S: Level>(
        &mut self,
        p: &Primitive<Phong<{ phong::COLORED_LEN }>>,
        ctx: &ShadeContext<'_>,
        pass: &P,
    ) -> u64 {
        let (m, l) = (&ctx.materials[p.shader.material as usize], ctx.lighting);
        let (edges, planes) = ((&p.edges, &p.depth), &p.shader.planes);
        if let Some(maps) = ctx.maps {
            return self.scan::<_, _, _, S>(
                edges,
                planes,
                pass,
                &IgnoreAlpha,
                #[inline(always)]
                |a, _| {
                    let (w, eye, normal) = phong_point::<_, I, _>(a);
                    let (ambient_diffuse, specular) = l.shade_parts_x8_shared(
                        m,
                        eye,
                        normal,
                        #[inline(always)]
                        |k, p, n| maps.visibility_x8(k, p, n),
                    );
                    ((triple(a, phong::COLOR, w) * ambient_diffuse + specular).clamp01(), f32x8::ONE)
                },
            );
        }
        if m.shadow_bits.is_some() {
            return self.scan::<_, _, _, S>(
                edges,
                planes,
                pass,
                &IgnoreAlpha,
                #[inline(always)]
                |a, mask| {
                    let (w, eye, normal) = phong_point::<_, I, _>(a);
                    let (ambient_diffuse, specular) = l.shade_parts_x8_shadowed(m, eye, normal, mask);
                    ((triple(a, phong::COLOR, w) * ambient_diffuse + specular).clamp01(), f32x8::ONE)
                },
            );
        }
        self.scan::<_, _, _, S>(
            edges,
            planes,
            pass,
            &IgnoreAlpha,
            #[inline(always)]
            |a, _| {
                let (w, eye, normal) = phong_point::<_, I, _>(a);
                let (ambient_diffuse, specular) = l.shade_parts_x8(m, eye, normal);
                ((triple(a, phong::COLOR, w) * ambient_diffuse + specular).clamp01(), f32x8::ONE)
            },
        )
    }

    /// SPEC §7, the part every textured kernel shares: texture coordinates
    /// interpolated, the texel sampled with the map's sampler at the level
    /// `L` finds, and c = texel ⊙ (ambient+diffuse) + specular, clamped,
    /// with the parts from `parts(attributes, w)`.
    #[inline(always)]
    pub(super) fn textured<const N: usize, I: Interp, L: Lod, P: Pass, A: Alpha, S: Level>(
        &mut self,
        (edges, depth, planes): (&EdgeTable, &DepthPlane, &AttributePlanes<N>),
        map: &FrameTexture,
        pass: &P,
        parts: impl Fn(&[f32x8<S>; N], f32x8<S>, i32x8<S>) -> (Vec3x8<S>, Vec3x8<S>) + Copy,
    ) -> u64 {
        let derivatives = Derivatives::new(planes, map);
        let (texture, sampler) = (&*map.texture, &map.sampler);
        self.scan::<_, _, _, S>(
            (edges, depth),
            planes,
            pass,
            &A::new(map),
            #[inline(always)]
            |a, mask| {
                let inv = I::w(a[textured::Q]);
                let (s, t) = (a[textured::S] * inv, a[textured::T] * inv);
                let lods = L::lods::<I, _>(&derivatives, s, t, inv);
                let [r, g, b, texel_alpha] = texture.sample_x8(sampler, s, t, lods);
                let texel = Vec3x8 { x: r, y: g, z: b };
                let (ambient_diffuse, specular) = parts(a, inv, mask);
                ((texel * ambient_diffuse + specular).clamp01(), texel_alpha)
            },
        )
    }

    /// Textured flat: the parts lit once at the centroid.
    #[inline(always)]
    pub(super) fn textured_flat<I: Interp, L: Lod, P: Pass, A: Alpha, S: Level>(
        &mut self,
        p: &Primitive<TexturedFlat>,
        ctx: &ShadeContext<'_>,
        pass: &P,
    ) -> u64 {
        let map = &ctx.textures[p.shader.texture as usize];
        let (ad, spec) = (Vec3x8::splat(p.shader.ambient_diffuse), Vec3x8::splat(p.shader.specular));
        self.textured::<_, I, L, P, A, S>(
            (&p.edges, &p.depth, &p.shader.planes),
            map,
            pass,
            #[inline(always)]
            |_, _, _| (ad, spec),
        )
    }

    /// Textured Gouraud: the parts lit at the vertices, interpolated apart.
    #[inline(always)]
    pub(super) fn textured_gouraud<I: Interp, L: Lod, P: Pass, A: Alpha, S: Level>(
        &mut self,
        p: &Primitive<TexturedGouraud>,
        ctx: &ShadeContext<'_>,
        pass: &P,
    ) -> u64 {
        let map = &ctx.textures[p.shader.texture as usize];
        self.textured::<_, I, L, P, A, S>(
            (&p.edges, &p.depth, &p.shader.planes),
            map,
            pass,
            #[inline(always)]
            |a, w, _| (triple(a, textured::AMBIENT_DIFFUSE, w), triple(a, textured::SPECULAR, w)),
        )
    }

    /// Textured Phong: the parts lit per sample.
    #[inline(always)]
    pub(super) fn textured_phong<I: Interp, L: Lod, P: Pass, A: Alpha, S: Level>(
        &mut self,
        p: &Primitive<TexturedPhong<{ textured::PHONG_LEN }>>,
        ctx: &ShadeContext<'_>,
        pass: &P,
    ) -> u64 {
        let map = &ctx.textures[p.shader.texture as usize];
        let (m, l) = (&ctx.materials[p.shader.material as usize], ctx.lighting);
        let prim = (&p.edges, &p.depth, &p.shader.planes);
        if let Some(maps) = ctx.maps {
            return self.textured::<_, I, L, P, A, S>(
                prim,
                map,
                pass,
                #[inline(always)]
                |a, w, _| {
                    let normal = triple(a, textured::NORMAL, w).normalize_or_zero();
                    let share = zline_simd::inlined(
                        #[inline(always)]
                        |k, p, n| maps.visibility_x8(k, p, n),
                    );
                    l.shade_parts_x8_shared(m, triple(a, textured::EYE, w), normal, share)
                },
            );
        }
        if m.shadow_bits.is_some() {
            return self.textured::<_, I, L, P, A, S>(
                prim,
                map,
                pass,
                #[inline(always)]
                |a, w, mask| {
                    let normal = triple(a, textured::NORMAL, w).normalize_or_zero();
                    l.shade_parts_x8_shadowed(m, triple(a, textured::EYE, w), normal, mask)
                },
            );
        }
        self.textured::<_, I, L, P, A, S>(
            prim,
            map,
            pass,
            #[inline(always)]
            |a, w, _| {
                l.shade_parts_x8(
                    m,
                    triple(a, textured::EYE, w),
                    triple(a, textured::NORMAL, w).normalize_or_zero(),
                )
            },
        )
    }

    /// Textured Phong with vertex colours: the interpolated colour
    /// multiplies ambient+diffuse like the texel.
    #[inline(always)]
    pub(super) fn textured_colored_phong<I: Interp, L: Lod, P: Pass, A: Alpha, S: Level>(
        &mut self,
        p: &Primitive<TexturedPhong<{ textured::COLORED_PHONG_LEN }>>,
        ctx: &ShadeContext<'_>,
        pass: &P,
    ) -> u64 {
        let map = &ctx.textures[p.shader.texture as usize];
        let (m, l) = (&ctx.materials[p.shader.material as usize], ctx.lighting);
        // Shadowed or not in one body: this kernel is out of line already.
        let maps = ctx.maps;
        self.textured::<_, I, L, P, A, S>(
            (&p.edges, &p.depth, &p.shader.planes),
            map,
            pass,
            #[inline(always)]
            |a, w, mask| {
                let normal = triple(a, textured::NORMAL, w).normalize_or_zero();
                let eye = triple(a, textured::EYE, w);
                let (ambient_diffuse, specular) = match maps {
                    Some(maps) => l.shade_parts_x8_shared(
                        m,
                        eye,
                        normal,
                        #[inline(always)]
                        |k, p, n| maps.visibility_x8(k, p, n),
                    ),
                    None => l.shade_parts_x8_shadowed(m, eye, normal, mask),
                };
                (triple(a, textured::COLOR, w) * ambient_diffuse, specular)
            },
        )
    }
}

/// An all-ones lane for each set bit of `bits`.
#[inline(always)]
fn lane_mask<S: Level>(bits: u8) -> f32x8<S> {
    let lane_bits = i32x8::<S>::from([1, 2, 4, 8, 16, 32, 64, 128]);
    let set = (i32x8::splat(i32::from(bits)) & lane_bits).cmp_eq(lane_bits);
    bytemuck::cast(set)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lane_masks_follow_bits() {
        let m: [u32; 8] = bytemuck::cast(lane_mask::<zline_simd::lanes::Baseline>(0b1010_0110));
        assert_eq!(m.map(|v| v != 0), [false, true, true, false, false, true, false, true]);
    }
}
