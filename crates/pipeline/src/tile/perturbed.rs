//! The perturbed Phong kernels ([`Kernel::Perturbed`]): Phong shading with
//! the normal tilted per sample by a bump or normal map in the
//! interpolated tangent frame (`zline_scene::NormalMap` states the
//! formulas), untextured or with a diffuse texture.
//!
//! Two kernels, untextured and textured, each a job of its own per SIMD
//! level like the other kernels. The map's encoding is a run-time value
//! tested per block like the interpolation, the pass, the level of detail
//! and the alpha use; the map is sampled eight lanes at a time
//! (`Texture::sample_x8` at level 0: one read for a normal map, four for a
//! height map's central differences, in one loop: each copy of the
//! sampler in a kernel costs build time).
//!
//! [`Kernel::Perturbed`]: crate::setup::Kernel::Perturbed

use zline_scene::NormalEncoding;
use zline_shading::{Filter, Sampler, Texture, Vec3x8};
use zline_simd::lanes::{f32x8, Level};

use super::kernel::{encode_normal, lit, surface_maps, times, triple, unmodulated, Lit};
use super::params::{AlphaTest, AnyPass, Interp, Lod, Pass};
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
        self.texture.sample_base_x8(&self.sampler, s, t)
    }
}

/// The tangent-space normal m = (x, y, z) in the frame (T, B, N) at
/// (s, t), from a map of `encoding`:
/// - a height map: m = (−k·∂h/∂s, −k·∂h/∂t, 1), central differences one
///   texel apart;
/// - a normal map: m = ((2r − 1)·k, (2g − 1)·k, 2b − 1).
#[inline(always)]
fn tangent_normal<S: Level>(
    encoding: NormalEncoding,
    map: &MapReader<'_>,
    s: f32x8<S>,
    t: f32x8<S>,
) -> Vec3x8<S> {
    let scale = f32x8::<S>::splat(map.scale);
    match encoding {
        NormalEncoding::Height => {
            let (ds, dt) = (f32x8::<S>::splat(map.step.0), f32x8::<S>::splat(map.step.1));
            let (hw, hh) = (f32x8::<S>::splat(map.half.0), f32x8::<S>::splat(map.half.1));
            // h(s + ds, t), h(s − ds, t), h(s, t + dt), h(s, t − dt): one
            // read in a loop, so the sampler is compiled once here.
            let mut h = [f32x8::<S>::ZERO; 4];
            for (k, h) in h.iter_mut().enumerate() {
                let (u, v) = match k {
                    0 => (s + ds, t),
                    1 => (s - ds, t),
                    2 => (s, t + dt),
                    _ => (s, t - dt),
                };
                *h = map.read(u, v)[0];
            }
            let dh_ds = (h[0] - h[1]) * hw;
            let dh_dt = (h[2] - h[3]) * hh;
            Vec3x8 { x: -(scale * dh_ds), y: -(scale * dh_dt), z: f32x8::ONE }
        }
        NormalEncoding::Tangent => {
            let [r, g, b, _] = map.read(s, t);
            let (one, two) = (f32x8::ONE, f32x8::splat(2.0));
            Vec3x8 { x: (two * r - one) * scale, y: (two * g - one) * scale, z: two * b - one }
        }
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
fn perturbed_point<S: Level>(
    encoding: NormalEncoding,
    map: &MapReader<'_>,
    a: &[f32x8<S>; 15],
    w: f32x8<S>,
) -> (Vec3x8<S>, Vec3x8<S>) {
    let (s, t) = (a[S] * w, a[T] * w);
    let n = triple(a, NORMAL, w).normalize_or_zero();
    let m = tangent_normal(encoding, map, s, t);
    let perturbed =
        scaled(triple(a, TANGENT, w), m.x) + scaled(triple(a, BITANGENT, w), m.y) + scaled(n, m.z);
    (triple(a, EYE, w), perturbed.normalize_or_zero())
}

impl TileTarget {
    /// Untextured: c = clamp(ambient+diffuse + specular) with the perturbed
    /// normal (planar shadows and shadow maps as in the Phong kernel); in
    /// the normals frame, the perturbed normal encoded.
    #[inline(always)]
    pub(super) fn perturbed_plain<S: Level>(
        &mut self,
        p: &Primitive<Perturbed>,
        (encoding, interp): (NormalEncoding, Interp),
        ctx: &ShadeContext<'_>,
        pass: &AnyPass<'_>,
    ) -> u64 {
        let map = MapReader::new(&ctx.textures[p.shader.map as usize], p.shader.scale);
        // One copy, lighting as values (`Lit::split` would double the
        // map reads, the costliest code here to compile).
        let (how, normals) = (Lit::of(ctx, p.shader.material), ctx.normals);
        let ceiling = self.ceiling;
        self.scan::<_, _, S>(
            (&p.edges, &p.depth),
            &p.shader.planes,
            pass,
            AlphaTest::Ignore,
            #[inline(always)]
            |a, mask| {
                let (eye, normal) = perturbed_point(encoding, &map, a, interp.w(a[Q]));
                if normals {
                    return (encode_normal(normal), f32x8::ONE);
                }
                (
                    lit(&how, eye, normal, mask, unmodulated, zline_shading::MapTexels::NONE)
                        .clamp_to(ceiling),
                    f32x8::ONE,
                )
            },
        )
    }

    /// Textured: c = clamp(texel ⊙ (ambient+diffuse) + specular) with the
    /// perturbed normal.
    #[inline(always)]
    pub(super) fn perturbed_textured<S: Level>(
        &mut self,
        p: &Primitive<Perturbed>,
        (encoding, interp, lod, alpha): (NormalEncoding, Interp, LevelOfDetail, AlphaUse),
        ctx: &ShadeContext<'_>,
        pass: &AnyPass<'_>,
    ) -> u64 {
        let map = MapReader::new(&ctx.textures[p.shader.map as usize], p.shader.scale);
        let texture = &ctx.textures[p.shader.texture as usize];
        let uses = (
            texture,
            interp,
            Lod::new(lod, &p.shader.planes, texture),
            AlphaTest::new(alpha, pass.blends(), texture),
        );
        let how = Lit::of(ctx, p.shader.material);
        let surface = surface_maps(ctx, p.shader.material, &p.shader.planes);
        self.textured::<_, true, S>(
            (&p.edges, &p.depth, &p.shader.planes),
            uses,
            surface.as_ref(),
            pass,
            #[inline(always)]
            |a, w, mask, texel, surface| {
                let (eye, normal) = perturbed_point(encoding, &map, a, w);
                lit(&how, eye, normal, mask, times(texel), surface)
            },
        )
    }
}
