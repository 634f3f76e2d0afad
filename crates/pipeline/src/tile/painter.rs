//! The painter's algorithm (`Visibility::Painter`): a tile's primitives
//! sorted back to front and painted in that order, with no depth test and
//! no depth write — the transparency pass's machinery (sort, blending
//! kernels) with every primitive in it.
//!
//! **Sort key**: the largest NC depth of the primitive's three vertices
//! (`Draw::far_depth`; each triangle of a clipped polygon's fan is a
//! primitive of its own), far to near, ties in draw order. The order
//! depends only on the primitives, never on the tile, so the image is the
//! same for any tile size and thread count.
//!
//! **Painting**: an opaque primitive replaces the colour (drawn by the
//! blending kernels with opacity 1: 1·C + 0·C_behind = C exactly), a
//! transparent one blends with opacity 1 − kt; fog, when the scene has it,
//! is applied per sample as each primitive is painted. The depth buffer
//! keeps its clear value, so every sample that a primitive covers is
//! painted (the blending kernels test z < far, which only a sample exactly
//! on the far plane fails — as in the z-buffer). Where no two primitives
//! overlap, the image is the z-buffer's bit for bit (a test checks).
//!
//! **Where it fails**: three triangles overlapping in a cycle have no
//! correct order, and of two intersecting triangles the one painted later
//! covers the other everywhere, also where it lies behind
//! (`tests/scenes/visibility_painter_cyclic.toml`; `cargo test -p
//! zline-pipeline --release --test it painter` prints the share of wrong
//! pixels).

use zline_simd::lanes::Level;
use zline_simd::Vectorized;

use super::params::Blend;
use super::{apart, back_to_front, ShadeContext, TileTarget};
use crate::bin::PrimitiveRef;
use crate::fog::FogPass;
use crate::setup::{PassKind, PrimitiveChunk};

impl TileTarget {
    /// Paints the primitives of `bin` (opaque and transparent, binned by
    /// `bin::bin_primitives_painter`) back to front by their farthest NC
    /// depth, ties in draw order, without depth test or write; fogged per
    /// sample when the scene has fog. `order` is scratch space. Returns the
    /// samples painted.
    pub fn painter_pass(
        &mut self,
        chunks: &[PrimitiveChunk],
        bin: &[PrimitiveRef],
        ctx: &ShadeContext<'_>,
        fog: Option<&FogPass>,
        order: &mut Vec<(f32, PrimitiveRef)>,
    ) -> u64 {
        zline_simd::dispatch(PainterPass { target: self, chunks, bin, ctx, fog, order })
    }

    /// [`Self::painter_pass`] at level `S`, each kernel a job of its own.
    #[inline(always)]
    fn painter_pass_at<S: Level>(
        &mut self,
        chunks: &[PrimitiveChunk],
        bin: &[PrimitiveRef],
        ctx: &ShadeContext<'_>,
        fog: Option<&FogPass>,
        order: &mut Vec<(f32, PrimitiveRef)>,
    ) -> u64 {
        apart::<S, _>(
            #[inline(always)]
            || self.materialize_background::<S>(),
        );
        let draw = |r: &PrimitiveRef| chunks[r.chunk as usize].draws[r.index as usize];
        back_to_front(order, bin.iter().map(|r| (draw(r).far_depth, *r)));
        let mut painted = 0;
        for (_, r) in order.iter() {
            let chunk = &chunks[r.chunk as usize];
            let kt = match chunk.pass {
                PassKind::Opaque => 0.0, // opacity 1 − 0 = 1 exactly
                PassKind::Transparent { kt } => kt,
                PassKind::Shadow { .. } => continue, // binned apart
            };
            let d = draw(r);
            painted += self.draw::<_, S>(chunk, (d.kernel, d.index), ctx, &Blend::new(kt, fog));
        }
        painted
    }
}

/// [`TileTarget::painter_pass`] as a job.
struct PainterPass<'a, 'c> {
    target: &'a mut TileTarget,
    chunks: &'a [PrimitiveChunk],
    bin: &'a [PrimitiveRef],
    ctx: &'a ShadeContext<'c>,
    fog: Option<&'a FogPass>,
    order: &'a mut Vec<(f32, PrimitiveRef)>,
}

impl Vectorized for PainterPass<'_, '_> {
    type Output = u64;
    #[inline(always)]
    fn run<S: Level>(self) -> u64 {
        self.target.painter_pass_at::<S>(self.chunks, self.bin, self.ctx, self.fog, self.order)
    }
}
