//! The type parameters of the span kernels ([`super::kernel`]): how
//! attributes are recovered ([`Interp`]), how Gouraud colours are clamped
//! ([`Clamp`]), the pass ([`Pass`]), the texel's alpha ([`Alpha`]) and the
//! texture level of detail ([`Lod`]). Each is a choice made once per
//! primitive, so none is a branch in the per-sample loop (but [`Blend`]'s
//! fog, which is the same for a whole frame):
//!
//! | parameter | types | decides |
//! |---|---|---|
//! | [`Interp`] | [`Perspective`], [`Linear`] | a/w ÷ 1/w per sample, or the plane value itself |
//! | [`Pass`] | [`Opaque`], [`Blend`] | depth write and replace, or blend (fogged per sample when the frame has fog) |
//! | [`Alpha`] | [`IgnoreAlpha`], [`MaskAlpha`], [`TextureAlpha`] | the texel's alpha ignored, tested against the cutoff, or blended |
//! | [`Lod`] | [`BaseLod`], [`DerivativeLod`] | level 0, or the level from the exact derivatives of s and t |
//! | [`Clamp`] | [`ClampedAtVertices`], [`ClampPerSample`] | Gouraud: colours used as interpolated, or clamped per sample |

use zline_raster::AttributePlanes;
use zline_shading::Vec3x8;
use zline_simd::lanes::{f32x8, Level};

use super::target::FrameTexture;
use crate::fog::FogPass;
use crate::setup::layout::textured;

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
    pub(super) fn new<const N: usize>(planes: &AttributePlanes<N>, texture: &FrameTexture) -> Derivatives {
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
