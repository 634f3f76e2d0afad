//! The span kernels: one monomorphized function per [`Kernel`], pass and
//! texture use.
//!
//! [`TileTarget::blocks`] is the loop every kernel shares — depth test,
//! alpha test, depth and colour writes or blending — and each kernel passes
//! it the closure that shades eight samples from their interpolated
//! attributes. What varies between primitives is a type parameter, not a
//! branch in that loop (the one exception, the transparency pass's fog, is
//! the same for a whole frame); [`super::params`] has the parameters.
//!
//! [`Kernel`]: crate::setup::Kernel

use zline_raster::{for_each_block, AttributePlanes, DepthPlane, EdgeTable, Span, LANES};
use zline_shading::Vec3x8;
use zline_simd::lanes::{f32x8, i32x8, Level};

use super::params::{Alpha, Clamp, Derivatives, IgnoreAlpha, Interp, Lod, Pass};
use super::target::{load, load_for_blend, store, FrameTexture, ShadeContext, TileTarget};
use crate::setup::layout::{gouraud, phong, textured};
use crate::setup::{Flat, Gouraud, Phong, Primitive, TexturedFlat, TexturedGouraud, TexturedPhong};

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
