//! The span kernels: one function per table of [`KernelTables`] (the
//! planes a kernel reads are its type), each compiled once per SIMD level.
//!
//! [`TileTarget::blocks`] is the loop every kernel shares — depth test,
//! alpha test, depth and colour writes or blending — and each kernel passes
//! it the closure that shades eight samples from their interpolated
//! attributes. The choices that do not change the planes (interpolation,
//! clamp, pass, alpha use, level of detail, shadows) are run-time values
//! tested per block ([`super::params`]); the lighting of every Phong-family
//! kernel goes through one seam, [`lit`].
//!
//! [`KernelTables`]: crate::setup::KernelTables

use zline_raster::{for_each_block, AttributePlanes, DepthPlane, EdgeTable, Span, LANES};
use zline_shading::{MapTexels, Vec3x8};
use zline_simd::lanes::{f32x8, i32x8, Level};

use super::params::{AlphaTest, AnyPass, Interp, Lod, Pass};
use super::target::{load, load_for_blend, store, FrameTexture, ShadeContext, TileTarget};
use crate::setup::layout::{gouraud, phong, textured};
use crate::setup::{
    AlphaUse, Flat, Gouraud, LevelOfDetail, Phong, Primitive, TexturedFlat, TexturedGouraud, TexturedPhong,
};
use zline_shading::{Filter, PreparedLights, PreparedMaterial};

use crate::shadow_map::ShadowMaps;

/// What both Phong kernels recover per sample ([`phong`] layout): the
/// factor w, the eye position and the re-normalized normal.
#[inline(always)]
fn phong_point<const N: usize, S: Level>(
    interp: Interp,
    a: &[f32x8<S>; N],
) -> (f32x8<S>, Vec3x8<S>, Vec3x8<S>) {
    let w = interp.w(a[phong::Q]);
    (w, triple(a, phong::EYE, w), triple(a, phong::NORMAL, w).normalize_or_zero())
}

/// How a primitive's samples are lit: the frame's lights, the material,
/// and the shadows that fall on it (the frame's shadow maps, or the
/// material's planar shadow bits in the tile's mask).
#[derive(Clone, Copy)]
pub(super) struct Lit<'a> {
    lights: &'a PreparedLights,
    material: &'a PreparedMaterial,
    maps: Option<&'a ShadowMaps>,
    /// The block's planar shadow mask is read (the material receives).
    planar: bool,
    /// The material may be Cook–Torrance (false: the basic model only,
    /// known where the copy is compiled).
    microfacet: bool,
    /// The frame has an environment map (false: the uniform ambient light
    /// only, known where the copy is compiled).
    environment: bool,
}

impl<'a> Lit<'a> {
    /// The lighting of `material` in the frame `ctx` describes.
    #[inline(always)]
    pub(super) fn of(ctx: &ShadeContext<'a>, material: u32) -> Lit<'a> {
        let material = &ctx.materials[material as usize];
        let planar = ctx.maps.is_none() && material.shadow_bits.is_some();
        Lit {
            lights: ctx.lighting,
            material,
            maps: ctx.maps,
            planar,
            microfacet: material.microfacet.is_some(),
            environment: !ctx.lighting.uniform_ambient(),
        }
    }

    /// Runs `kernel` with this lighting and `normals` (the normals frame),
    /// in one of two copies: the basic model's unshadowed lighting of a
    /// colour frame under a uniform ambient light (the common case, where
    /// all four are constants: every shadow test, the microfacet model and
    /// the environment fold away), or any other. Both
    /// go through the one seam, [`lit`].
    #[inline(always)]
    pub(super) fn split<R>(self, normals: bool, kernel: impl FnOnce(Lit<'a>, bool) -> R) -> R {
        if self.maps.is_none() && !self.planar && !normals && !self.microfacet && !self.environment {
            kernel(Lit { maps: None, planar: false, microfacet: false, environment: false, ..self }, false)
        } else {
            kernel(self, normals)
        }
    }
}

/// The lighting seam: the unclamped colour of eight samples (eye-space
/// `eye`, unit `normal`) lit as `how` says — the material's model (basic
/// or Cook–Torrance) with `modulate` multiplying its colour (a texel, a
/// vertex colour) — with each light's share from the frame's shadow maps
/// when it has them, else with the lights the block's planar shadow `mask`
/// hides left out. Every Phong-family kernel (Phong, tinted, textured,
/// perturbed) lights through here, so a lighting model is one addition at
/// this function (`PreparedLights::shade_x8_with`).
#[inline(always)]
pub(super) fn lit<S: Level>(
    how: &Lit<'_>,
    eye: Vec3x8<S>,
    normal: Vec3x8<S>,
    mask: i32x8<S>,
    modulate: impl Fn(Vec3x8<S>) -> Vec3x8<S>,
    maps: MapTexels<S>,
) -> Vec3x8<S> {
    // Only builds the closure: the lookup runs where the lights are summed.
    let share = how.maps.map(
        #[inline(always)]
        |maps| {
            #[inline(always)]
            move |k: u32, p: Vec3x8<S>, n: Vec3x8<S>| maps.visibility_x8(k, p, n)
        },
    );
    let mask = if how.planar { Some(mask) } else { None };
    if how.microfacet {
        how.lights.shade_x8_with(how.material, (eye, normal), mask, share, modulate, maps)
    } else {
        how.lights.shade_x8_basic(how.material, (eye, normal), (mask, how.environment), share, modulate)
    }
}

/// A Cook–Torrance material's maps (metallic–roughness, occlusion,
/// emission), each with its level of detail on `planes` (the map's own
/// filter decides whether it reads mip levels), and the occlusion's
/// strength.
pub(super) struct SurfaceMaps<'a> {
    maps: [Option<(&'a FrameTexture, Lod)>; 3],
    strength: f32,
}

/// The maps of `material`, when it has any.
#[inline(always)]
pub(super) fn surface_maps<'a, const N: usize>(
    ctx: &ShadeContext<'a>,
    material: u32,
    planes: &AttributePlanes<N>,
) -> Option<SurfaceMaps<'a>> {
    let uses = ctx.surfaces.get(material as usize).filter(|u| u.any())?;
    let with_lod = |index: Option<u32>| {
        let map = &ctx.textures[index? as usize];
        let lod = match map.sampler.filter {
            Filter::Trilinear => LevelOfDetail::Derivatives,
            Filter::Nearest | Filter::Bilinear => LevelOfDetail::Base,
        };
        Some((map, Lod::new(lod, planes, map)))
    };
    let (occlusion, strength) = match uses.occlusion {
        Some((index, strength)) => (Some(index), strength),
        None => (None, 0.0),
    };
    Some(SurfaceMaps {
        maps: [with_lod(uses.metallic_roughness), with_lod(occlusion), with_lod(uses.emission)],
        strength,
    })
}

/// The modulation by a texel or vertex colour `by`: c ↦ by ⊙ c.
#[inline(always)]
pub(super) fn times<S: Level>(by: Vec3x8<S>) -> impl Fn(Vec3x8<S>) -> Vec3x8<S> {
    zline_simd::inlined(
        #[inline(always)]
        move |c: Vec3x8<S>| by * c,
    )
}

/// The modulation of an untinted surface: none.
#[inline(always)]
pub(super) fn unmodulated<S: Level>(c: Vec3x8<S>) -> Vec3x8<S> {
    c
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
    /// Scan-converts one primitive and runs [`Self::blocks`] on each span,
    /// unless the tile's coarse depth hides it whole (`tile::coarse`).
    ///
    /// The planes are copied to the stack first, so the compiler knows the
    /// kernel's stores into the tile's buffers leave them alone, and the
    /// shading closure is passed by value (it holds only references), so it
    /// is inlined into the block loop (through `&mut F` it was a call per
    /// block: 6 % more instructions in the Phong kernel, measured with
    /// callgrind).
    #[inline(always)]
    pub(super) fn scan<const N: usize, P: Pass, S: Level>(
        &mut self,
        (edges, depth): (&EdgeTable, &DepthPlane),
        planes: &AttributePlanes<N>,
        pass: &P,
        alpha: AlphaTest,
        shade: impl Fn(&[f32x8<S>; N], i32x8<S>) -> (Vec3x8<S>, f32x8<S>) + Copy,
    ) -> u64 {
        if self.hidden(edges.bounds(), depth) {
            return 0;
        }
        let (depth, planes) = (*depth, *planes);
        let mut n = 0;
        edges.scan(
            self.rect,
            #[inline(always)]
            |s| n += self.blocks(&depth, &planes, s, pass, &alpha, shade),
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
    fn blocks<const N: usize, P: Pass, S: Level>(
        &mut self,
        depth: &DepthPlane,
        attrs: &AttributePlanes<N>,
        span: Span,
        pass: &P,
        alpha_use: &AlphaTest,
        shade: impl Fn(&[f32x8<S>; N], i32x8<S>) -> (Vec3x8<S>, f32x8<S>),
    ) -> u64 {
        let row = self.index(self.origin, span.y);
        let origin = self.origin;
        let opacity = pass.opacity();
        let blends = pass.blends();
        let (zbuf, [red, green, blue], shadow) = (&mut self.depth, &mut self.rgb, &self.shadow);
        // The alpha plane, blended like a colour of 1 (coverage only).
        let mut coverage = (blends && self.coverage).then_some(&mut self.alpha);
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
                // Lane k of attribute i is anchor[i] + dx[i]·offset[k]
                // (`SampleBlock::attr`): one vector operation each, element
                // by element (`map` and `array::from_fn` stay calls).
                let offsets = f32x8::from(b.offsets);
                let mut attrs = [f32x8::ZERO; N];
                for (i, a) in attrs.iter_mut().enumerate() {
                    *a = f32x8::splat(b.anchor[i]) + f32x8::splat(b.dx[i]) * offsets;
                }
                let (c, alpha) = shade(&attrs, mask);
                let live = alpha_use.test(live, alpha);
                let bits = live.move_mask();
                if bits == 0 {
                    return;
                }
                n += u64::from(bits.count_ones());
                if blends {
                    // C = (1 − kt)·C_surface + kt·C_behind with 1 − kt =
                    // opacity·alpha (alpha is 1 but for textures whose alpha
                    // blends).
                    let keep = opacity * alpha_use.weight(alpha);
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
        self.scan::<_, _, S>(
            (&p.edges, &p.depth),
            &planes,
            pass,
            AlphaTest::Ignore,
            #[inline(always)]
            |_, _| (c, f32x8::ONE),
        )
    }

    /// SPEC §6 Gouraud: the lit vertex colours interpolated (and clamped
    /// per sample when `clamp` says so: the vertex colours were left
    /// unclamped).
    #[inline(always)]
    pub(super) fn gouraud<P: Pass, S: Level>(
        &mut self,
        p: &Primitive<Gouraud>,
        (interp, clamp): (Interp, bool),
        pass: &P,
    ) -> u64 {
        self.scan::<_, _, S>(
            (&p.edges, &p.depth),
            &p.shader.planes,
            pass,
            AlphaTest::Ignore,
            #[inline(always)]
            |a, _| {
                let (q, c) = (a[gouraud::Q], gouraud::COLOR);
                let c = Vec3x8 {
                    x: interp.divide(a[c], q),
                    y: interp.divide(a[c + 1], q),
                    z: interp.divide(a[c + 2], q),
                };
                (if clamp { c.clamp01() } else { c }, f32x8::ONE)
            },
        )
    }

    /// SPEC §6 Phong: normal and eye position interpolated, the normal
    /// re-normalized per sample, the lighting model per sample ([`lit`]);
    /// in the normals frame, the normal encoded instead.
    #[inline(always)]
    pub(super) fn phong<S: Level>(
        &mut self,
        p: &Primitive<Phong<{ phong::LEN }>>,
        interp: Interp,
        ctx: &ShadeContext<'_>,
        pass: &AnyPass<'_>,
    ) -> u64 {
        Lit::of(ctx, p.shader.material).split(
            ctx.normals,
            #[inline(always)]
            |how, normals| {
                let ceiling = self.ceiling;
                self.scan::<_, _, S>(
                    (&p.edges, &p.depth),
                    &p.shader.planes,
                    pass,
                    AlphaTest::Ignore,
                    #[inline(always)]
                    |a, mask| {
                        let (_, eye, normal) = phong_point(interp, a);
                        if normals {
                            return (encode_normal(normal), f32x8::ONE);
                        }
                        (
                            lit(&how, eye, normal, mask, unmodulated, MapTexels::NONE).clamp_to(ceiling),
                            f32x8::ONE,
                        )
                    },
                )
            },
        )
    }

    /// [`Self::phong`] with the vertex colour interpolated too, multiplying
    /// ka and kd like a texel: c ⊙ (ambient+diffuse) + specular, clamped.
    #[inline(always)]
    pub(super) fn phong_tinted<S: Level>(
        &mut self,
        p: &Primitive<Phong<{ phong::COLORED_LEN }>>,
        interp: Interp,
        ctx: &ShadeContext<'_>,
        pass: &AnyPass<'_>,
    ) -> u64 {
        Lit::of(ctx, p.shader.material).split(
            false,
            #[inline(always)]
            |how, _| {
                let ceiling = self.ceiling;
                self.scan::<_, _, S>(
                    (&p.edges, &p.depth),
                    &p.shader.planes,
                    pass,
                    AlphaTest::Ignore,
                    #[inline(always)]
                    |a, mask| {
                        let (w, eye, normal) = phong_point(interp, a);
                        let tint = times(triple(a, phong::COLOR, w));
                        (lit(&how, eye, normal, mask, tint, MapTexels::NONE).clamp_to(ceiling), f32x8::ONE)
                    },
                )
            },
        )
    }

    /// SPEC §7, the part every textured kernel shares: texture coordinates
    /// interpolated, the texel sampled with the map's sampler at the level
    /// `lod` finds, and the colour `color(attributes, w, mask, texel,
    /// metallic–roughness texel)` (texel ⊙ (ambient+diffuse) + specular
    /// for the basic model), clamped. A Cook–Torrance material's
    /// metallic–roughness map (`surface`) is read in the same loop as the
    /// texture, so the sampler is compiled once per kernel; its (B, G)
    /// reach `color`. One copy, the
    /// interpolation tested per block: a copy per interpolation saved 1 %
    /// of the textured plane's instructions and cost a fifth of the
    /// pipeline's build time (the sampler is the costliest code to
    /// compile).
    ///
    /// `MAPS` is false for the kernels whose material never has such maps
    /// (flat and Gouraud): they read the base texture alone, without the
    /// loop over the maps. Each kernel compiles one of the two bodies, so
    /// the sampler stays one copy per kernel; the loop, which the compiler
    /// keeps even where it runs once, with its loop-carried texels spilled
    /// around it, cost the textured floor 24 instructions of its 539 per
    /// block (callgrind).
    #[inline(always)]
    pub(super) fn textured<const N: usize, const MAPS: bool, S: Level>(
        &mut self,
        (edges, depth, planes): (&EdgeTable, &DepthPlane, &AttributePlanes<N>),
        (map, interp, lod, alpha): (&FrameTexture, Interp, Lod, AlphaTest),
        surface: Option<&SurfaceMaps<'_>>,
        pass: &AnyPass<'_>,
        color: impl Fn(&[f32x8<S>; N], f32x8<S>, i32x8<S>, Vec3x8<S>, MapTexels<S>) -> Vec3x8<S> + Copy,
    ) -> u64 {
        // The textures to read, present ones first, each with its slot
        // (0 the base texture, 1 + the map's index): a primitive without
        // maps runs the loop below once.
        let mut maps: [Option<(&FrameTexture, &Lod, u8)>; 4] = [Some((map, &lod, 0)), None, None, None];
        let ceiling = self.ceiling;
        let (mut count, mut strength) = (1, 0.0);
        if let Some(surface) = surface {
            strength = surface.strength;
            for (slot, m) in surface.maps.iter().enumerate() {
                if let Some((map, lod)) = m {
                    maps[count] = Some((*map, lod, slot as u8 + 1));
                    count += 1;
                }
            }
        }
        self.scan::<_, _, S>(
            (edges, depth),
            planes,
            pass,
            alpha,
            #[inline(always)]
            |a, mask| {
                let inv = interp.w(a[textured::Q]);
                let (s, t) = (a[textured::S] * inv, a[textured::T] * inv);
                if !MAPS {
                    let lods = lod.lods(interp, s, t, inv);
                    let [r, g, b, alpha] = map.texture.sample_x8(&map.sampler, s, t, lods);
                    let texel = Vec3x8 { x: r, y: g, z: b };
                    return (color(a, inv, mask, texel, MapTexels::NONE).clamp_to(ceiling), alpha);
                }
                // Each texel goes straight to its own local (no array indexed
                // by the loop counter), so they stay in registers.
                let [mut r, mut g, mut b, mut texel_alpha] = [f32x8::ZERO; 4];
                let mut surface = MapTexels::NONE;
                for m in &maps[..count] {
                    let Some((map, lod, slot)) = m else { continue };
                    let lods = lod.lods(interp, s, t, inv);
                    let texel = map.texture.sample_x8(&map.sampler, s, t, lods);
                    match slot {
                        0 => [r, g, b, texel_alpha] = texel,
                        1 => surface.metallic_roughness = Some((texel[2], texel[1])),
                        2 => {
                            let one = f32x8::ONE;
                            surface.occlusion = Some(one + f32x8::splat(strength) * (texel[0] - one));
                        }
                        _ => surface.emission = Some(Vec3x8 { x: texel[0], y: texel[1], z: texel[2] }),
                    }
                }
                let texel = Vec3x8 { x: r, y: g, z: b };
                (color(a, inv, mask, texel, surface).clamp_to(ceiling), texel_alpha)
            },
        )
    }

    /// Textured flat: the parts lit once at the centroid.
    #[inline(always)]
    pub(super) fn textured_flat<S: Level>(
        &mut self,
        p: &Primitive<TexturedFlat>,
        (interp, lod, alpha): (Interp, LevelOfDetail, AlphaUse),
        ctx: &ShadeContext<'_>,
        pass: &AnyPass<'_>,
    ) -> u64 {
        let map = &ctx.textures[p.shader.texture as usize];
        let uses =
            (map, interp, Lod::new(lod, &p.shader.planes, map), AlphaTest::new(alpha, pass.blends(), map));
        let (ad, spec) = (Vec3x8::splat(p.shader.ambient_diffuse), Vec3x8::splat(p.shader.specular));
        self.textured::<_, false, S>(
            (&p.edges, &p.depth, &p.shader.planes),
            uses,
            None,
            pass,
            #[inline(always)]
            |_, _, _, texel, _| texel * ad + spec,
        )
    }

    /// Textured Gouraud: the parts lit at the vertices, interpolated apart.
    #[inline(always)]
    pub(super) fn textured_gouraud<S: Level>(
        &mut self,
        p: &Primitive<TexturedGouraud>,
        (interp, lod, alpha): (Interp, LevelOfDetail, AlphaUse),
        ctx: &ShadeContext<'_>,
        pass: &AnyPass<'_>,
    ) -> u64 {
        let map = &ctx.textures[p.shader.texture as usize];
        let uses =
            (map, interp, Lod::new(lod, &p.shader.planes, map), AlphaTest::new(alpha, pass.blends(), map));
        self.textured::<_, false, S>(
            (&p.edges, &p.depth, &p.shader.planes),
            uses,
            None,
            pass,
            #[inline(always)]
            |a, w, _, texel, _| {
                texel * triple(a, textured::AMBIENT_DIFFUSE, w) + triple(a, textured::SPECULAR, w)
            },
        )
    }

    /// Textured Phong: the parts lit per sample.
    #[inline(always)]
    pub(super) fn textured_phong<S: Level>(
        &mut self,
        p: &Primitive<TexturedPhong<{ textured::PHONG_LEN }>>,
        (interp, lod, alpha): (Interp, LevelOfDetail, AlphaUse),
        ctx: &ShadeContext<'_>,
        pass: &AnyPass<'_>,
    ) -> u64 {
        let map = &ctx.textures[p.shader.texture as usize];
        let uses =
            (map, interp, Lod::new(lod, &p.shader.planes, map), AlphaTest::new(alpha, pass.blends(), map));
        let how = Lit::of(ctx, p.shader.material);
        let surface = surface_maps(ctx, p.shader.material, &p.shader.planes);
        self.textured::<_, true, S>(
            (&p.edges, &p.depth, &p.shader.planes),
            uses,
            surface.as_ref(),
            pass,
            #[inline(always)]
            |a, w, mask, texel, surface| {
                let normal = triple(a, textured::NORMAL, w).normalize_or_zero();
                lit(&how, triple(a, textured::EYE, w), normal, mask, times(texel), surface)
            },
        )
    }

    /// Textured Phong with vertex colours: the interpolated colour
    /// multiplies ambient+diffuse like the texel.
    #[inline(always)]
    pub(super) fn textured_colored_phong<S: Level>(
        &mut self,
        p: &Primitive<TexturedPhong<{ textured::COLORED_PHONG_LEN }>>,
        (interp, lod, alpha): (Interp, LevelOfDetail, AlphaUse),
        ctx: &ShadeContext<'_>,
        pass: &AnyPass<'_>,
    ) -> u64 {
        let map = &ctx.textures[p.shader.texture as usize];
        let uses =
            (map, interp, Lod::new(lod, &p.shader.planes, map), AlphaTest::new(alpha, pass.blends(), map));
        let how = Lit::of(ctx, p.shader.material);
        let surface = surface_maps(ctx, p.shader.material, &p.shader.planes);
        self.textured::<_, true, S>(
            (&p.edges, &p.depth, &p.shader.planes),
            uses,
            surface.as_ref(),
            pass,
            #[inline(always)]
            |a, w, mask, texel, surface| {
                let normal = triple(a, textured::NORMAL, w).normalize_or_zero();
                let color = triple(a, textured::COLOR, w);
                let tint = zline_simd::inlined(
                    #[inline(always)]
                    move |c: Vec3x8<S>| texel * (color * c),
                );
                lit(&how, triple(a, textured::EYE, w), normal, mask, tint, surface)
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
