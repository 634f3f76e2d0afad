//! Rasterizing one tile: the opaque pass over its bin with a depth buffer
//! (SPEC §4), fog on the samples it settled, then the transparency pass.
//! [`crate::resolve`] turns the tile's samples into image pixels.
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
//! Each primitive names its kernel ([`Kernel`], chosen in setup); `kernel`
//! holds one span function per kernel table, compiled once per SIMD level,
//! and the choices that do not change the planes it reads are run-time
//! values tested per block (`params`). The pass (opaque, transparent,
//! transparent with fog) is an argument of the draw, not state kept on the
//! tile.

mod coarse;
mod kernel;
mod lines;
mod painter;
mod params;
mod perturbed;
mod target;

pub(crate) use target::{load, load_for_blend, sample, store};
pub use target::{FrameTexture, ShadeContext, SurfaceUse, TileTarget, DEPTH_CLEAR, DEPTH_CLEAR_REVERSED};

use zline_raster::LANES;
use zline_scene::GouraudClamp;
use zline_shading::Vec3x8;
use zline_simd::lanes::{f32x8, Level};
use zline_simd::Vectorized;

use crate::bin::{OpaqueRef, PrimitiveRef};
use crate::fog::{FogFactors, FogPass, FogVisitor};
use crate::setup::{Kernel, PassKind, PrimitiveChunk, TexturedLighting};

use params::{AnyPass, Blend, Interp, Opaque, Pass};

/// How many primitives ahead in a bin the opaque pass asks for.
const PREFETCH_AHEAD: usize = 4;

impl TileTarget {
    /// Draws the primitives `bin` (references into `chunks`) in order;
    /// returns the number of samples that passed the depth test.
    pub fn opaque_pass(
        &mut self,
        chunks: &[PrimitiveChunk],
        bin: &[OpaqueRef],
        ctx: &ShadeContext<'_>,
    ) -> u64 {
        zline_simd::dispatch(OpaquePass { target: self, chunks, bin, ctx })
    }

    /// [`Self::opaque_pass`] at level `S`.
    #[inline(always)]
    fn opaque_pass_at<S: Level>(
        &mut self,
        chunks: &[PrimitiveChunk],
        bin: &[OpaqueRef],
        ctx: &ShadeContext<'_>,
    ) -> u64 {
        let mut shaded = 0;
        for (k, r) in bin.iter().enumerate() {
            if let Some(ahead) = bin.get(k + PREFETCH_AHEAD) {
                chunks[ahead.chunk as usize].tables.prefetch(ahead.kernel, ahead.index);
            }
            let n = self.draw::<Opaque, S>(&chunks[r.chunk as usize], (r.kernel, r.index), ctx, &Opaque);
            self.wrote(n);
            shaded += n;
        }
        shaded
    }

    /// SPEC §9, pass 2: the transparent primitives `bin` back to front
    /// (largest mean NC depth first; ties in draw order, so every tile sorts
    /// alike), each depth-tested against the opaque depth without writing
    /// it, fogged per sample when the scene has fog, and blended as
    /// C = (1 − kt)·C_surface + kt·C_behind. `order` is scratch space.
    /// Returns the samples blended.
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
        zline_simd::dispatch(TransparencyPass { target: self, chunks, bin, ctx, fog, order })
    }

    /// [`Self::transparency_pass`] at level `S`.
    #[inline(always)]
    fn transparency_pass_at<S: Level>(
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
        back_to_front(
            order,
            bin.iter().map(
                #[inline(always)]
                |r| (draw(r).sort_depth, *r),
            ),
        );
        let mut shaded = 0;
        for (_, r) in order.iter() {
            let chunk = &chunks[r.chunk as usize];
            let PassKind::Transparent { kt } = chunk.pass else {
                continue; // binning puts only transparent chunks here
            };
            let d = draw(r);
            shaded += self.draw::<_, S>(chunk, (d.kernel, d.index), ctx, &Blend::new(kt, fog));
        }
        shaded
    }

    /// Planar shadows, before the opaque pass: rasterizes each shadow
    /// primitive of `bin` (a caster projected onto a receiving plane from
    /// one light, [`PassKind::Shadow`]) into the tile's shadow mask, setting
    /// its bit in every sample it covers — once however many shadow
    /// triangles overlap. No depth test: the receiver's own samples decide
    /// where the mask is read (its Phong kernel leaves out the lights whose
    /// bits are set), so the shadow cannot fight the plane for depth.
    pub fn shadow_pass(&mut self, chunks: &[PrimitiveChunk], bin: &[PrimitiveRef]) {
        self.shadow.clear();
        if bin.is_empty() {
            return;
        }
        self.shadow.resize(self.depth.len(), zline_simd::lanes::i32x8::ZERO);
        let (origin, stride, rect) = (self.origin, self.stride, self.rect);
        let mask: &mut [i32] = bytemuck::cast_slice_mut(&mut self.shadow);
        for r in bin {
            let chunk = &chunks[r.chunk as usize];
            let PassKind::Shadow { bit } = chunk.pass else {
                continue; // binning puts only shadow chunks here
            };
            let d = chunk.draws[r.index as usize];
            let Kernel::Flat = d.kernel else {
                continue; // shadows are set up flat
            };
            let p = &chunk.tables.flat[d.index as usize];
            let bit = 1i32 << bit;
            p.edges.scan(
                rect,
                #[inline(always)]
                |s| {
                    let row = (s.y - rect.y0) as usize * stride;
                    let (a, b) = (row + (s.x0 - origin) as usize, row + (s.x1 - origin) as usize);
                    mask[a..b].iter_mut().for_each(
                        #[inline(always)]
                        |m| *m |= bit,
                    );
                },
            );
        }
    }

    /// Writes the background into undrawn samples, so blending reads it as
    /// C_behind.
    #[inline(always)]
    pub(crate) fn materialize_background<S: Level>(&mut self) {
        // Once per tile: the samples it fills may then be blended over, and
        // a second fill would erase that (the pixel inspector runs a pass
        // one primitive per call).
        if self.colors_valid {
            return;
        }
        if self.sky_drawn {
            self.fill_undrawn::<S>(
                #[inline(always)]
                |t, i| t.background_block(i),
            );
        } else {
            let plain = Vec3x8::<S>::splat(self.background);
            self.fill_undrawn::<S>(
                #[inline(always)]
                move |_, _| plain,
            );
        }
        if self.coverage {
            // Drawn samples are opaque (alpha 1), undrawn ones empty (0).
            for i in (0..self.depth.len() * LANES).step_by(LANES) {
                let empty = load::<S>(&self.depth, i).cmp_eq(f32x8::splat(self.far));
                store(&mut self.alpha, i, empty.blend(f32x8::ZERO, f32x8::ONE));
            }
        }
        self.colors_valid = true;
    }

    /// Writes `background(self, i)` into the undrawn samples of each block
    /// i (one loop per kind of background, the branch outside it).
    #[inline(always)]
    fn fill_undrawn<S: Level>(&mut self, background: impl Fn(&TileTarget, usize) -> Vec3x8<S>) {
        for i in (0..self.depth.len() * LANES).step_by(LANES) {
            let bg = background(self, i);
            let empty = load(&self.depth, i).cmp_eq(f32x8::splat(self.far));
            let [red, green, blue] = &mut self.rgb;
            for (plane, c) in [(&mut *red, bg.x), (&mut *green, bg.y), (&mut *blue, bg.z)] {
                let old = load_for_blend(plane, i);
                store(plane, i, empty.blend(c, old));
            }
        }
    }

    /// Fogs every drawn sample of the tile (see [`crate::fog`]), with the
    /// fog's coordinate and mode chosen once for the tile.
    pub fn fog_pass(&mut self, pass: &FogPass) {
        pass.specialized(FogTile { target: self, color: pass.color() });
    }

    /// Draws one primitive with its kernel in `pass`: where a primitive's
    /// [`Kernel`] picks its span function, each a job of its own at level
    /// `S` ([`apart`]). Flat and Gouraud primitives (a few instructions a
    /// block) have a job per pass; the shading kernels take the pass as a
    /// value ([`Self::draw_shaded`]).
    #[inline(always)]
    fn draw<P: Pass, S: Level>(
        &mut self,
        chunk: &PrimitiveChunk,
        (kernel, index): (Kernel, u32),
        ctx: &ShadeContext<'_>,
        pass: &P,
    ) -> u64 {
        let (t, i) = (&chunk.tables, index as usize);
        match kernel {
            Kernel::Flat => apart::<S, _>(
                #[inline(always)]
                || self.flat::<P, S>(&t.flat[i], pass),
            ),
            Kernel::Gouraud { interpolation, clamp } => {
                // Lit colours are never negative: with a tone mapping
                // (ceiling above 1) there is nothing left to clamp.
                let clamp = clamp == GouraudClamp::PerSample && ctx.lighting.ceiling() == 1.0;
                let how = (Interp::of(interpolation), clamp);
                apart::<S, _>(
                    #[inline(always)]
                    || self.gouraud::<P, S>(&t.gouraud[i], how, pass),
                )
            }
            _ => self.draw_shaded::<S>(chunk, (kernel, index), ctx, pass.any()),
        }
    }

    /// The shading kernels of [`Self::draw`]: one job per table and level,
    /// whatever the pass, interpolation, level of detail, alpha use, map
    /// encoding or shadows (run-time values, see [`params`]). Generic over
    /// the level only, so that each closure here is one job per level.
    #[inline(always)]
    fn draw_shaded<S: Level>(
        &mut self,
        chunk: &PrimitiveChunk,
        (kernel, index): (Kernel, u32),
        ctx: &ShadeContext<'_>,
        pass: AnyPass<'_>,
    ) -> u64 {
        let (t, i, pass) = (&chunk.tables, index as usize, &pass);
        match kernel {
            // `draw` draws these with the pass as a type.
            Kernel::Flat | Kernel::Gouraud { .. } => 0,
            Kernel::Phong(interpolation) => apart::<S, _>(
                #[inline(always)]
                || self.phong::<S>(&t.phong[i], Interp::of(interpolation), ctx, pass),
            ),
            Kernel::ColoredPhong(interpolation) => apart::<S, _>(
                #[inline(always)]
                || self.phong_tinted::<S>(&t.colored_phong[i], Interp::of(interpolation), ctx, pass),
            ),
            Kernel::Textured { lighting, interpolation, lod, alpha } => {
                let how = (Interp::of(interpolation), lod, alpha);
                match lighting {
                    TexturedLighting::Flat => apart::<S, _>(
                        #[inline(always)]
                        || self.textured_flat::<S>(&t.textured_flat[i], how, ctx, pass),
                    ),
                    TexturedLighting::Gouraud => apart::<S, _>(
                        #[inline(always)]
                        || self.textured_gouraud::<S>(&t.textured_gouraud[i], how, ctx, pass),
                    ),
                    TexturedLighting::Phong => apart::<S, _>(
                        #[inline(always)]
                        || self.textured_phong::<S>(&t.textured_phong[i], how, ctx, pass),
                    ),
                    TexturedLighting::ColoredPhong => apart::<S, _>(
                        #[inline(always)]
                        || self.textured_colored_phong::<S>(&t.textured_colored_phong[i], how, ctx, pass),
                    ),
                }
            }
            Kernel::Perturbed { encoding, interpolation, texture } => {
                let (p, interp) = (&t.perturbed[i], Interp::of(interpolation));
                match texture {
                    None => apart::<S, _>(
                        #[inline(always)]
                        || self.perturbed_plain::<S>(p, (encoding, interp), ctx, pass),
                    ),
                    Some((lod, alpha)) => apart::<S, _>(
                        #[inline(always)]
                        || self.perturbed_textured::<S>(p, (encoding, interp, lod, alpha), ctx, pass),
                    ),
                }
            }
        }
    }
}

/// Runs one kernel as a job of its own at level `S`
/// ([`zline_simd::vectorize_at`]): each kernel is compiled once per level,
/// with the level's instructions, as a function apart from the others and
/// from the pass loop that calls it. `kernel` should be an
/// `#[inline(always)]` closure, so that its body lands in the job.
#[inline(always)]
pub(super) fn apart<S: Level, R>(kernel: impl FnOnce() -> R) -> R {
    zline_simd::vectorize_at::<S, _>(zline_simd::Call(kernel))
}

/// Fills `order` with `keyed` sorted far to near (largest key first), ties
/// in draw order (chunk, then index: the bin's order), so every tile sorts
/// alike. An unstable sort with the draw order as the tie-break gives the
/// stable sort's order without its scratch allocation.
pub(crate) fn back_to_front(
    order: &mut Vec<(f32, PrimitiveRef)>,
    keyed: impl Iterator<Item = (f32, PrimitiveRef)>,
) {
    order.clear();
    order.extend(keyed);
    order.sort_unstable_by(
        #[inline(always)]
        |a, b| {
            b.0.total_cmp(&a.0).then_with(
                #[inline(always)]
                || (a.1.chunk, a.1.index).cmp(&(b.1.chunk, b.1.index)),
            )
        },
    );
}

/// The fog pass over one tile, generic over the fog's factors.
struct FogTile<'a> {
    target: &'a mut TileTarget,
    color: glam::Vec3,
}

/// The loop of [`FogTile`] with its factors, as a job.
struct FogLoop<'a, F> {
    target: &'a mut TileTarget,
    color: glam::Vec3,
    factors: F,
}

/// [`TileTarget::opaque_pass`] as a job.
struct OpaquePass<'a, 'c> {
    target: &'a mut TileTarget,
    chunks: &'a [PrimitiveChunk],
    bin: &'a [OpaqueRef],
    ctx: &'a ShadeContext<'c>,
}

impl Vectorized for OpaquePass<'_, '_> {
    type Output = u64;
    #[inline(always)]
    fn run<S: Level>(self) -> u64 {
        self.target.opaque_pass_at::<S>(self.chunks, self.bin, self.ctx)
    }
}

/// [`TileTarget::transparency_pass`] as a job.
struct TransparencyPass<'a, 'c> {
    target: &'a mut TileTarget,
    chunks: &'a [PrimitiveChunk],
    bin: &'a [PrimitiveRef],
    ctx: &'a ShadeContext<'c>,
    fog: Option<&'a FogPass>,
    order: &'a mut Vec<(f32, PrimitiveRef)>,
}

impl Vectorized for TransparencyPass<'_, '_> {
    type Output = u64;
    #[inline(always)]
    fn run<S: Level>(self) -> u64 {
        self.target.transparency_pass_at::<S>(self.chunks, self.bin, self.ctx, self.fog, self.order)
    }
}

impl FogVisitor for FogTile<'_> {
    type Output = ();

    fn visit<F: FogFactors>(self, factors: F) {
        zline_simd::vectorize(FogLoop { target: self.target, color: self.color, factors });
    }
}

impl<F: FogFactors> Vectorized for FogLoop<'_, F> {
    type Output = ();

    #[inline(always)]
    fn run<S: Level>(self) {
        let (t, fog, factors) = (self.target, Vec3x8::<S>::splat(self.color), self.factors);
        let [red, green, blue] = &mut t.rgb;
        for row in 0..t.rect.height() as usize {
            let y = t.rect.y0 + row as i32;
            for x in (t.origin..t.origin + t.stride as i32).step_by(LANES) {
                let i = row * t.stride + (x - t.origin) as usize;
                let z = load(&t.depth, i);
                let drawn = z.cmp_lt(f32x8::splat(t.far));
                if drawn.none() {
                    continue;
                }
                let f = factors.at(x, y, z);
                let g = f32x8::ONE - f;
                for (plane, c) in [(&mut *red, fog.x), (&mut *green, fog.y), (&mut *blue, fog.z)] {
                    let old = load_for_blend(plane, i);
                    store(plane, i, drawn.blend(old * f + c * g, old));
                }
            }
        }
    }
}
