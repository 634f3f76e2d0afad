//! What a span kernel ([`super::kernel`]) is told besides its primitive:
//! how attributes are recovered ([`Interp`]), the pass ([`Pass`],
//! [`AnyPass`]), the texel's alpha ([`AlphaTest`]) and the texture level of
//! detail ([`Lod`]).
//!
//! Each is a choice made once per primitive that does not change the planes
//! a kernel reads, so each is a **run-time value** tested once per block of
//! eight samples (the branch goes the same way for the whole primitive and
//! is predicted), not a type parameter: a choice added here adds a branch,
//! not a copy of every kernel (`cargo xtask kernels` counts the copies).
//! Only the pass of the two cheapest kernels (flat and Gouraud, whose
//! blocks are a few instructions) is still a type, [`Opaque`] or [`Blend`];
//! the shading kernels take the pass as an [`AnyPass`].
//!
//! | value | choices | decides |
//! |---|---|---|
//! | [`Interp`] | perspective, screen-linear | a/w ÷ 1/w per sample, or the plane value itself |
//! | [`Pass`] | [`Opaque`], [`Blend`], [`AnyPass`] | depth write and replace, or blend (fogged per sample when the frame has fog) |
//! | [`AlphaTest`] | ignore, mask, blend | the texel's alpha ignored, tested against the cutoff, or blended |
//! | [`Lod`] | base, derivatives | level 0, or the level from the exact derivatives of s and t |

use zline_raster::AttributePlanes;
use zline_scene::Interpolation;
use zline_shading::Vec3x8;
use zline_simd::lanes::{f32x8, Level};

use super::target::FrameTexture;
use crate::fog::FogPass;
use crate::setup::layout::textured;
use crate::setup::{AlphaUse, LevelOfDetail};

/// How attributes are recovered from their planes: perspective-correct
/// (planes hold a/w and 1/w) or screen-linear (planes hold a; no divide).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Interp {
    /// True for perspective-correct planes.
    pub(crate) perspective: bool,
}

impl Interp {
    /// The recovery for `interpolation`.
    #[inline(always)]
    pub(crate) fn of(interpolation: Interpolation) -> Interp {
        Interp { perspective: interpolation == Interpolation::PerspectiveCorrect }
    }

    /// The factor that turns a plane value into the attribute: 1/(1/w),
    /// or 1/1 in screen-linear mode, whose Q plane is 1 exactly (three
    /// equal vertex values give a zero slope and an anchor of exactly 1),
    /// so the division leaves every value as it is. Dividing in both modes
    /// costs screen-linear primitives a division per block and saves the
    /// perspective ones (the default) a branch per block.
    #[inline(always)]
    pub(crate) fn w<S: Level>(self, q: f32x8<S>) -> f32x8<S> {
        f32x8::ONE / q
    }

    /// `v` over `q` (in screen-linear mode q = 1: `v` itself, as for
    /// [`Self::w`]).
    #[inline(always)]
    pub(crate) fn divide<S: Level>(self, v: f32x8<S>, q: f32x8<S>) -> f32x8<S> {
        v / q
    }
}

/// The pass a primitive is drawn in.
pub(crate) trait Pass {
    /// False: depth is written and the colour replaced (opaque). True: depth
    /// is only tested and the colour blended over the stored one.
    fn blends(&self) -> bool;
    /// The surface's weight 1 − kt in the blend.
    fn opacity<S: Level>(&self) -> f32x8<S>;
    /// The fragment's colour after fog (blending passes fog per sample; the
    /// opaque pass leaves fog to [`TileTarget::fog_pass`]).
    ///
    /// [`TileTarget::fog_pass`]: super::TileTarget::fog_pass
    fn fog<S: Level>(&self, c: Vec3x8<S>, x: i32, y: i32, z: f32x8<S>) -> Vec3x8<S>;
    /// The same pass as a run-time value.
    fn any(&self) -> AnyPass<'_>;
}

/// The opaque pass.
pub(crate) struct Opaque;

/// The transparency pass, with per-sample fog when the frame has fog (one
/// kernel for both: the branch is taken per block, the same way for the
/// whole frame).
#[derive(Clone, Copy)]
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

/// Either pass as a value, for the shading kernels: the blocks branch on
/// it after shading.
#[derive(Clone, Copy)]
pub(crate) enum AnyPass<'a> {
    /// [`Opaque`].
    Opaque,
    /// [`Blend`].
    Blend(Blend<'a>),
}

impl Pass for Opaque {
    #[inline(always)]
    fn blends(&self) -> bool {
        false
    }
    #[inline(always)]
    fn opacity<S: Level>(&self) -> f32x8<S> {
        f32x8::ONE
    }
    #[inline(always)]
    fn fog<S: Level>(&self, c: Vec3x8<S>, _: i32, _: i32, _: f32x8<S>) -> Vec3x8<S> {
        c
    }
    #[inline(always)]
    fn any(&self) -> AnyPass<'_> {
        AnyPass::Opaque
    }
}

impl Pass for Blend<'_> {
    #[inline(always)]
    fn blends(&self) -> bool {
        true
    }
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
    #[inline(always)]
    fn any(&self) -> AnyPass<'_> {
        AnyPass::Blend(*self)
    }
}

impl Pass for AnyPass<'_> {
    #[inline(always)]
    fn blends(&self) -> bool {
        matches!(self, AnyPass::Blend(_))
    }
    #[inline(always)]
    fn opacity<S: Level>(&self) -> f32x8<S> {
        match self {
            AnyPass::Opaque => f32x8::ONE,
            AnyPass::Blend(b) => b.opacity(),
        }
    }
    #[inline(always)]
    fn fog<S: Level>(&self, c: Vec3x8<S>, x: i32, y: i32, z: f32x8<S>) -> Vec3x8<S> {
        match self {
            AnyPass::Opaque => c,
            AnyPass::Blend(b) => b.fog(c, x, y, z),
        }
    }
    #[inline(always)]
    fn any(&self) -> AnyPass<'_> {
        *self
    }
}

/// What the texel's alpha does: nothing (every lane stays live and the
/// pass's opacity is used as it is), a test against the cutoff, or a
/// factor on the opacity.
#[derive(Clone, Copy)]
pub(crate) enum AlphaTest {
    /// The alpha is ignored (and untextured kernels have none).
    Ignore,
    /// Samples whose alpha is below the cutoff are discarded before they
    /// write depth; the rest are drawn opaque.
    Mask(f32x8),
    /// The alpha multiplies the pass's opacity.
    Blend,
}

impl AlphaTest {
    /// The test for `texture` used as `alpha` says, in a pass that blends
    /// or not: a texture whose alpha blends is drawn in the transparency
    /// pass only, and its alpha ignored in the opaque pass.
    #[inline(always)]
    pub(crate) fn new(alpha: AlphaUse, blends: bool, texture: &FrameTexture) -> AlphaTest {
        match (alpha, blends) {
            (AlphaUse::Ignore, _) | (AlphaUse::Blend, false) => AlphaTest::Ignore,
            (AlphaUse::Mask, _) => AlphaTest::Mask(f32x8::splat(texture.cutoff)),
            (AlphaUse::Blend, true) => AlphaTest::Blend,
        }
    }

    /// The lanes still live after the alpha test.
    #[inline(always)]
    pub(crate) fn test<S: Level>(&self, live: f32x8<S>, alpha: f32x8<S>) -> f32x8<S> {
        match self {
            AlphaTest::Mask(cutoff) => live & alpha.cmp_ge(cutoff.at()),
            AlphaTest::Ignore | AlphaTest::Blend => live,
        }
    }

    /// The factor on the pass's opacity.
    #[inline(always)]
    pub(crate) fn weight<S: Level>(&self, alpha: f32x8<S>) -> f32x8<S> {
        match self {
            AlphaTest::Blend => alpha,
            AlphaTest::Ignore | AlphaTest::Mask(_) => f32x8::ONE,
        }
    }
}

/// How a textured kernel finds the level of detail: level 0 (nearest and
/// bilinear filtering), or the level from the exact per-sample derivatives
/// (trilinear filtering), read from the plane gradients.
#[derive(Clone, Copy)]
pub(crate) struct Lod {
    /// `None` for level 0.
    derivatives: Option<Derivatives>,
}

/// The plane gradients a derivative level of detail reads, in texels.
#[derive(Clone, Copy)]
struct Derivatives {
    dx: [f32; 3],
    dy: [f32; 3],
    size: (f32, f32),
}

impl Lod {
    /// The rule `lod` names, for `planes` (textured layout) over `texture`.
    pub(super) fn new<const N: usize>(
        lod: LevelOfDetail,
        planes: &AttributePlanes<N>,
        texture: &FrameTexture,
    ) -> Lod {
        let derivatives = match lod {
            LevelOfDetail::Base => None,
            LevelOfDetail::Derivatives => {
                let (dx, dy) = (planes.dx(), planes.dy());
                let (q, s, t) = (textured::Q, textured::S, textured::T);
                let (w, h) = (texture.texture.width(), texture.texture.height());
                Some(Derivatives {
                    dx: [dx[q], dx[s], dx[t]],
                    dy: [dy[q], dy[s], dy[t]],
                    size: (w as f32, h as f32),
                })
            }
        };
        Lod { derivatives }
    }

    /// The levels of eight samples at (s, t), with `inv` the
    /// [`Interp::w`] factor.
    ///
    /// `shading::lod` for eight lanes: ½·log2 of the larger squared
    /// footprint in texels, with `wide`'s vector log2 in the level's own
    /// operations (`f32x8::log2`; one call instead of
    /// eight of libm's, which measured ~12 % of a textured frame). Zero or
    /// NaN footprints read level 0.
    #[inline(always)]
    pub(crate) fn lods<S: Level>(&self, interp: Interp, s: f32x8<S>, t: f32x8<S>, inv: f32x8<S>) -> f32x8<S> {
        let Some(d) = &self.derivatives else { return f32x8::ZERO };
        // s = S/Q with S = s/w and Q = 1/w planes: ∂s/∂x = (∂S/∂x − s·∂Q/∂x)/Q.
        let derivative = zline_simd::inlined(
            #[inline(always)]
            |ds: f32, dq: f32, v: f32x8<S>| {
                if interp.perspective {
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
