//! The perturbed Phong kernels ([`Kernel::Perturbed`]): Phong shading with
//! the normal tilted per sample by a bump or normal map in the
//! interpolated tangent frame (`zline_scene::NormalMap` states the
//! formulas), untextured or with a diffuse texture.
//!
//! Separate from the other kernels and reached through one out-of-line
//! dispatch, so objects without a map compile and run exactly as before.
//! The map's encoding is a type parameter ([`Encoding`]) like the
//! interpolation, the pass, the level of detail and the alpha use; the
//! map is sampled eight lanes at a time (`Texture::sample_x8` at level 0:
//! one read for a normal map, four for a height map's central
//! differences).
//!
//! [`Kernel::Perturbed`]: crate::setup::Kernel::Perturbed

use zline_scene::{Interpolation, NormalEncoding};
use zline_shading::{Filter, Sampler, Texture, Vec3x8};
use zline_simd::lanes::{f32x8, Level};

use super::apart;
use super::kernel::{encode_normal, triple};
use super::params::{
    Alpha, BaseLod, DerivativeLod, IgnoreAlpha, Interp, Linear, Lod, MaskAlpha, Pass, Perspective,
    TextureAlpha,
};
use super::target::{FrameTexture, ShadeContext, TileTarget};
use crate::setup::layout::perturbed::{BITANGENT, EYE, NORMAL, Q, S, T, TANGENT};
use crate::setup::{AlphaUse, LevelOfDetail, Perturbed, Primitive};

/// A map as the kernel reads it.
pub(crate) struct MapReader<'a> {
    texture: &'a Texture,
    /// The map's sampler, trilinear read as bilinear: at level 0 they are
    /// the same filter (`Texture::sample` with a level of detail ≤ 0), and
    /// the bilinear path skips the per-lane level choice.
    sampler: Sampler,
    /// k.
    scale: f32,
    /// One texel in s and t: 1/W, 1/H.
    step: (f32, f32),
    /// W/2, H/2: the central differences' divisor 2/W, 2/H inverted.
    half: (f32, f32),
}

impl<'a> MapReader<'a> {
    fn new(map: &'a FrameTexture, scale: f32) -> MapReader<'a> {
        let (w, h) = (map.texture.width() as f32, map.texture.height() as f32);
        MapReader {
            texture: &map.texture,
            sampler: match map.sampler.filter {
                Filter::Trilinear => Sampler { filter: Filter::Bilinear, ..map.sampler },
                Filter::Nearest | Filter::Bilinear => map.sampler,
            },
            scale,
            step: (1.0 / w, 1.0 / h),
            half: (w * 0.5, h * 0.5),
        }
    }

    /// The map's texel at (s, t), level 0.
    #[inline(always)]
    fn read<S: Level>(&self, s: f32x8<S>, t: f32x8<S>) -> [f32x8<S>; 4] {
        self.texture.sample_x8(&self.sampler, s, t, f32x8::ZERO)
    }
}

/// What a map's texels hold: the tangent-space normal m at (s, t).
pub(crate) trait Encoding {
    /// m = (x, y, z) in the frame (T, B, N).
    fn tangent_normal<S: Level>(map: &MapReader<'_>, s: f32x8<S>, t: f32x8<S>) -> Vec3x8<S>;
}

/// A height map: m = (−k·∂h/∂s, −k·∂h/∂t, 1), central differences one
/// texel apart.
pub(crate) struct Height;

/// A normal map: m = ((2r − 1)·k, (2g − 1)·k, 2b − 1).
pub(crate) struct TangentNormal;

impl Encoding for Height {
    #[inline(always)]
    fn tangent_normal<S: Level>(map: &MapReader<'_>, s: f32x8<S>, t: f32x8<S>) -> Vec3x8<S> {
        let splat = zline_simd::inlined(
            #[inline(always)]
            |(a, b): (f32, f32)| (f32x8::<S>::splat(a), f32x8::<S>::splat(b)),
        );
        let ((ds, dt), (hw, hh)) = (splat(map.step), splat(map.half));
        let scale = f32x8::<S>::splat(map.scale);
        let h = zline_simd::inlined(
            #[inline(always)]
            |s, t| map.read(s, t)[0],
        );
        let dh_ds = (h(s + ds, t) - h(s - ds, t)) * hw;
        let dh_dt = (h(s, t + dt) - h(s, t - dt)) * hh;
        Vec3x8 { x: -(scale * dh_ds), y: -(scale * dh_dt), z: f32x8::ONE }
    }
}

impl Encoding for TangentNormal {
    #[inline(always)]
    fn tangent_normal<S: Level>(map: &MapReader<'_>, s: f32x8<S>, t: f32x8<S>) -> Vec3x8<S> {
        let [r, g, b, _] = map.read(s, t);
        let (one, two, scale) = (f32x8::ONE, f32x8::splat(2.0), f32x8::splat(map.scale));
        Vec3x8 { x: (two * r - one) * scale, y: (two * g - one) * scale, z: two * b - one }
    }
}

/// `v` times the lanes of `f`.
#[inline(always)]
fn scaled<S: Level>(v: Vec3x8<S>, f: f32x8<S>) -> Vec3x8<S> {
    Vec3x8 { x: v.x * f, y: v.y * f, z: v.z * f }
}

/// The eye position and the perturbed normal
/// normalize(m.x·T + m.y·B + m.z·normalize(N)) of eight samples.
#[inline(always)]
fn perturbed_point<E: Encoding, S: Level>(
    map: &MapReader<'_>,
    a: &[f32x8<S>; 15],
    w: f32x8<S>,
) -> (Vec3x8<S>, Vec3x8<S>) {
    let (s, t) = (a[S] * w, a[T] * w);
    let n = triple(a, NORMAL, w).normalize_or_zero();
    let m = E::tangent_normal(map, s, t);
    let perturbed =
        scaled(triple(a, TANGENT, w), m.x) + scaled(triple(a, BITANGENT, w), m.y) + scaled(n, m.z);
    (triple(a, EYE, w), perturbed.normalize_or_zero())
}

impl TileTarget {
    /// Draws a [`Perturbed`] primitive: the one dispatch from the kernel's
    /// choices to a monomorphized span function, each a job of its own.
    #[inline(always)]
    pub(super) fn perturbed<P: Pass, S: Level>(
        &mut self,
        p: &Primitive<Perturbed>,
        (encoding, interpolation, texture): (
            NormalEncoding,
            Interpolation,
            Option<(LevelOfDetail, AlphaUse)>,
        ),
        ctx: &ShadeContext<'_>,
        pass: &P,
    ) -> u64 {
        use Interpolation::{PerspectiveCorrect, ScreenLinear};
        match (encoding, interpolation) {
            (NormalEncoding::Height, PerspectiveCorrect) => {
                self.perturbed_texture::<Perspective, Height, P, S>(p, texture, ctx, pass)
            }
            (NormalEncoding::Height, ScreenLinear) => {
                self.perturbed_texture::<Linear, Height, P, S>(p, texture, ctx, pass)
            }
            (NormalEncoding::Tangent, PerspectiveCorrect) => {
                self.perturbed_texture::<Perspective, TangentNormal, P, S>(p, texture, ctx, pass)
            }
            (NormalEncoding::Tangent, ScreenLinear) => {
                self.perturbed_texture::<Linear, TangentNormal, P, S>(p, texture, ctx, pass)
            }
        }
    }

    #[inline(always)]
    fn perturbed_texture<I: Interp, E: Encoding, P: Pass, S: Level>(
        &mut self,
        p: &Primitive<Perturbed>,
        texture: Option<(LevelOfDetail, AlphaUse)>,
        ctx: &ShadeContext<'_>,
        pass: &P,
    ) -> u64 {
        match texture {
            None => apart::<S, _>(
                #[inline(always)]
                || self.perturbed_plain::<I, E, P, S>(p, ctx, pass),
            ),
            Some((LevelOfDetail::Base, alpha)) => {
                self.perturbed_alpha::<I, E, BaseLod, P, S>(p, alpha, ctx, pass)
            }
            Some((LevelOfDetail::Derivatives, alpha)) => {
                self.perturbed_alpha::<I, E, DerivativeLod, P, S>(p, alpha, ctx, pass)
            }
        }
    }

    /// As `TileTarget::textured_alpha`: a texture whose alpha blends is
    /// drawn in the transparency pass only, and its alpha ignored in the
    /// opaque pass.
    #[inline(always)]
    fn perturbed_alpha<I: Interp, E: Encoding, L: Lod, P: Pass, S: Level>(
        &mut self,
        p: &Primitive<Perturbed>,
        alpha: AlphaUse,
        ctx: &ShadeContext<'_>,
        pass: &P,
    ) -> u64 {
        match (alpha, P::BLENDS) {
            (AlphaUse::Ignore, _) | (AlphaUse::Blend, false) => apart::<S, _>(
                #[inline(always)]
                || self.perturbed_textured::<I, E, L, P, IgnoreAlpha, S>(p, ctx, pass),
            ),
            (AlphaUse::Mask, _) => apart::<S, _>(
                #[inline(always)]
                || self.perturbed_textured::<I, E, L, P, MaskAlpha, S>(p, ctx, pass),
            ),
            (AlphaUse::Blend, true) => apart::<S, _>(
                #[inline(always)]
                || self.perturbed_textured::<I, E, L, P, TextureAlpha, S>(p, ctx, pass),
            ),
        }
    }

    /// Untextured: c = clamp(ambient+diffuse + specular) with the perturbed
    /// normal (planar shadows and shadow maps as in the Phong kernel).
    #[inline(always)]
    fn perturbed_plain<I: Interp, E: Encoding, P: Pass, S: Level>(
        &mut self,
        p: &Primitive<Perturbed>,
        ctx: &ShadeContext<'_>,
        pass: &P,
    ) -> u64 {
        let (m, l, maps) = (&ctx.materials[p.shader.material as usize], ctx.lighting, ctx.maps);
        let map = MapReader::new(&ctx.textures[p.shader.map as usize], p.shader.scale);
        if ctx.normals {
            return self.scan::<_, _, _, S>(
                (&p.edges, &p.depth),
                &p.shader.planes,
                pass,
                &IgnoreAlpha,
                #[inline(always)]
                |a, _| (encode_normal(perturbed_point::<E, _>(&map, a, I::w(a[Q])).1), f32x8::ONE),
            );
        }
        self.scan::<_, _, _, S>(
            (&p.edges, &p.depth),
            &p.shader.planes,
            pass,
            &IgnoreAlpha,
            #[inline(always)]
            |a, mask| {
                let (eye, normal) = perturbed_point::<E, _>(&map, a, I::w(a[Q]));
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
                ((ambient_diffuse + specular).clamp01(), f32x8::ONE)
            },
        )
    }

    /// Textured: c = clamp(texel ⊙ (ambient+diffuse) + specular) with the
    /// perturbed normal.
    #[inline(always)]
    fn perturbed_textured<I: Interp, E: Encoding, L: Lod, P: Pass, A: Alpha, S: Level>(
        &mut self,
        p: &Primitive<Perturbed>,
        ctx: &ShadeContext<'_>,
        pass: &P,
    ) -> u64 {
        let (m, l, maps) = (&ctx.materials[p.shader.material as usize], ctx.lighting, ctx.maps);
        let map = MapReader::new(&ctx.textures[p.shader.map as usize], p.shader.scale);
        let texture = &ctx.textures[p.shader.texture as usize];
        let prim = (&p.edges, &p.depth, &p.shader.planes);
        self.textured::<_, I, L, P, A, S>(
            prim,
            texture,
            pass,
            #[inline(always)]
            |a, w, mask| {
                let (eye, normal) = perturbed_point::<E, _>(&map, a, w);
                match maps {
                    Some(maps) => l.shade_parts_x8_shared(
                        m,
                        eye,
                        normal,
                        #[inline(always)]
                        |k, p, n| maps.visibility_x8(k, p, n),
                    ),
                    None => l.shade_parts_x8_shadowed(m, eye, normal, mask),
                }
            },
        )
    }
}
