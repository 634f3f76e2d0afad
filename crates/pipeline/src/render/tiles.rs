//! The tile stage of a frame: every tile's passes, bands of tiles in
//! parallel ([`Renderer::draw_tiles`], [`TilePasses`]).

use std::ops::Range;
use std::sync::{Mutex, PoisonError};
use std::time::{Duration, Instant};

use glam::Vec3;
use rayon::iter::Either;
use rayon::prelude::*;
use zline_scene::{Scene, Visibility};

use zline_raster::Rect;

use super::{opaque_primitives, pixels_of, BandBuffers, Frame, Renderer};
use crate::bin::{pieces_per_band, Bins, PrimitiveRef, TileGrid, MAX_PIECES};
use crate::fog::FogPass;
use crate::image::{quantize_rgba, Image, ImageRows};
use crate::lines::Lines;
use crate::setup::{DepthEncoding, PrimitiveChunk};
use crate::sky::SkyView;
use crate::tile::{ShadeContext, TileTarget, DEPTH_CLEAR, DEPTH_CLEAR_REVERSED};

impl Renderer {
    /// Every tile, bands of tiles in parallel: each tile clears its depth,
    /// draws its opaque bin, fogs, draws its transparent bin and resolves
    /// into the image rows it owns ([`TilePasses::draw`]). A band is cut
    /// into pieces (runs of its tiles, drawn in parallel too) when the pool
    /// has more threads than the bands keep busy ([`pieces_per_band`]).
    /// Returns the samples shaded and the primitives the tiles' coarse
    /// depth skipped whole ([`super::RenderStats::hidden`]).
    pub(super) fn draw_tiles(
        &mut self,
        scene: &Scene,
        frame: &Frame,
        grid: &TileGrid,
        (image, depth): (&mut Image, Option<&mut Vec<f32>>),
    ) -> (u64, u64) {
        let (width, n) = (frame.width as usize, frame.n);
        let tile_size = (grid.tile_size / n) as usize;
        let coverage = scene.settings.transparent_background;
        image.width = frame.width;
        image.height = frame.height;
        image.transparent = coverage;
        image.pixels.resize(width * frame.height as usize, 0);
        let band_len = width * tile_size;
        let threads = self.prepare_band_buffers(grid, coverage);
        let buffers = &self.buffers[..threads];
        let clear = frame_clear(frame);
        let cols = grid.cols as usize;
        let chosen = self.band_pieces.unwrap_or_else(|| pieces_per_band(threads, grid.rows as usize, cols));
        let pieces = if tile_size > MAX_CUT_ROWS { 1 } else { chosen.clamp(1, cols.clamp(1, MAX_PIECES)) };
        // Piece k holds tile columns cols·k/pieces onwards; its first pixel column.
        let first = |k: usize| (k * cols / pieces * tile_size).min(width);
        let depth_bands = match depth {
            Some(d) => {
                d.clear();
                d.resize(image.pixels.len(), clear);
                Either::Left(d.par_chunks_mut(band_len).map(Some))
            }
            None => Either::Right((0..image.pixels.len().div_ceil(band_len)).into_par_iter().map(|_| None)),
        };
        // Taken out for the frame, so the bands can write it while `passes`
        // borrows the renderer; its capacity is kept from frame to frame.
        let mut bands = std::mem::take(&mut self.bands);
        let passes = self.tile_passes(scene, frame, grid, matches!(depth_bands, Either::Left(_)));
        // Tiles `tiles` of band `row` into `out` (and `depth`), with this
        // thread's buffers: the samples shaded and the time taken.
        let draw = |row: u32,
                    tiles: Range<usize>,
                    out: &mut ImageRows<u32>,
                    mut depth: Option<&mut ImageRows<f32>>| {
            let start = Instant::now();
            // Only this thread takes its own buffers: the lock is never
            // contended (a piece calls no rayon while holding it, and a
            // poisoned one holds plain buffers).
            let thread = rayon::current_thread_index().unwrap_or(0) % threads;
            let mut guard = buffers[thread].lock().unwrap_or_else(PoisonError::into_inner);
            let BandBuffers { target, order, untouched } = &mut *guard;
            untouched.clear();
            let mut shaded = 0;
            for col in tiles {
                let tile = (col as u32, row);
                match passes.draw((target, order), tile, out, depth.as_deref_mut()) {
                    Some(drawn) => shaded += drawn,
                    None => {
                        let rect = pixels_of(grid.rect(col as u32, row), n);
                        // A tile touching the last one lengthens its run.
                        match untouched.last_mut() {
                            Some(last) if last.x1 == rect.x0 => last.x1 = rect.x1,
                            _ => untouched.push(rect),
                        }
                    }
                }
            }
            fill_rects(out, untouched, passes.background.1);
            (shaded, start.elapsed())
        };
        image
            .pixels
            .par_chunks_mut(band_len)
            .zip(depth_bands)
            .enumerate()
            .map(|(row, (band, depth_band))| {
                let mut units = [(0, Duration::ZERO); MAX_PIECES];
                let row = row as u32;
                if pieces == 1 {
                    let mut depth = depth_band.map(|d| ImageRows::whole(d, width));
                    units[0] = draw(row, 0..cols, &mut ImageRows::whole(band, width), depth.as_mut());
                    return units;
                }
                let rows = band.len() / width.max(1);
                let (mut cut, mut depth_cut) = (Cut::<u32>::new(), Cut::<f32>::new());
                cut.fill(band, width, pieces, first);
                let has_depth = depth_band.is_some();
                if let Some(d) = depth_band {
                    depth_cut.fill(d, width, pieces, first);
                }
                units[..pieces]
                    .par_iter_mut()
                    .zip(&mut cut.0[..pieces])
                    .zip(&mut depth_cut.0[..pieces])
                    .enumerate()
                    .for_each(|(k, ((unit, out), depth))| {
                        let tiles = k * cols / pieces..(k + 1) * cols / pieces;
                        let mut out = ImageRows::Cut { rows: &mut out[..rows], first: first(k) };
                        let mut depth = ImageRows::Cut { rows: &mut depth[..rows], first: first(k) };
                        *unit = draw(row, tiles, &mut out, has_depth.then_some(&mut depth));
                    });
                units
            })
            .collect_into_vec(&mut bands);
        let shaded = bands.iter().flat_map(|units| &units[..pieces]).map(|&(n, _)| n).sum();
        // Each tile counts into the target of the thread that drew it; the
        // sum is the same whichever thread that was.
        let hidden =
            buffers.iter().map(|b| b.lock().unwrap_or_else(PoisonError::into_inner).target.hidden).sum();
        self.bands = bands;
        self.pieces = pieces;
        (shaded, hidden)
    }

    /// The tile stage's units of parallel work in the last frame drawn —
    /// bands of tile rows, or their pieces when the bands were cut
    /// ([`pieces_per_band`]) — band by band from the top, each band's
    /// pieces left to right: the time each took (empty before the first
    /// frame). With more threads than units' worth of work, the slowest
    /// unit bounds the stage: `cargo xtask scaling` models the frame at
    /// more threads from these times.
    pub fn unit_times(&self) -> impl Iterator<Item = Duration> + '_ {
        self.bands.iter().flat_map(|units| &units[..self.pieces]).map(|&(_, time)| time)
    }

    /// Cuts every band into `pieces` pieces (at most one a tile and
    /// [`MAX_PIECES`]; bands of tiles above 64 pixels stay whole), or, with
    /// `None` (the default), as many as [`pieces_per_band`] chooses for the
    /// pool's threads. The image is the same either way; `cargo xtask
    /// scaling` times at one thread the pieces more threads would use.
    pub fn set_band_pieces(&mut self, pieces: Option<usize>) {
        self.band_pieces = pieces;
    }

    /// What every tile of the frame draws with ([`TilePasses`]).
    pub(super) fn tile_passes<'a>(
        &'a self,
        scene: &Scene,
        frame: &Frame,
        grid: &'a TileGrid,
        export_depth: bool,
    ) -> TilePasses<'a> {
        let coverage = scene.settings.transparent_background;
        let t = &self.tables;
        let shade = ShadeContext {
            lighting: &t.lighting,
            materials: &t.materials,
            textures: &t.textures,
            surfaces: &t.surfaces,
            maps: self.maps_drawn.then_some(&self.maps),
            normals: self.normals,
        };
        let (vw, vh) = (frame.viewport.width, frame.viewport.height);
        // A transparent background is black (the colour planes then hold
        // premultiplied colour: `crate::coverage`) with alpha 0.
        let (background_color, background) = match coverage {
            false => {
                let shown = scene.settings.tone_mapping.apply(scene.background);
                (scene.background, quantize_rgba(shown.extend(1.0)))
            }
            true => (Vec3::ZERO, 0),
        };
        let wireframe = scene.settings.wireframe;
        TilePasses {
            grid,
            bins: &self.bins,
            chunks: &self.chunks[..self.used],
            shade,
            fog: scene.fog.map(|f| FogPass::new(f, frame.clip_from_eye, vw, vh, frame.depth)),
            lines: wireframe.drawn().then_some(&self.lines),
            lines_only: wireframe.only,
            painter: scene.settings.visibility == Visibility::Painter,
            export_depth,
            clear: frame_clear(frame),
            background: (background_color, background),
            sky: scene.environment.as_ref().filter(|e| e.background && !coverage).map(|e| {
                let size = (vw, vh, t.lighting.ceiling());
                SkyView::new(e, (frame.eye_from_world, frame.clip_from_eye), frame.viewer, size)
            }),
            coverage,
            tone: scene.settings.tone_mapping,
            ssaa: frame.n,
        }
    }

    /// One set of tile buffers per thread, each reserved for this frame's
    /// tiles (size, coverage plane, shadow mask, transparent sort); returns
    /// the thread count.
    fn prepare_band_buffers(&mut self, grid: &TileGrid, coverage: bool) -> usize {
        let threads = rayon::current_num_threads().max(1);
        if self.buffers.len() < threads {
            self.buffers.resize_with(threads, Mutex::default);
        }
        let shadows = self.bins.shadow.iter().any(|b| !b.is_empty());
        let transparent = self.bins.transparent.iter().map(Vec::len).max().unwrap_or(0);
        for b in &self.buffers[..threads] {
            let mut guard = b.lock().unwrap_or_else(PoisonError::into_inner);
            guard.target.set_coverage(coverage);
            guard.target.hidden = 0;
            guard.target.reserve(grid.tile_size, shadows);
            let order = &mut guard.order;
            order.reserve(transparent.saturating_sub(order.len()));
        }
        threads
    }
}

/// The depth buffer's clear value for the frame's encoding.
pub(super) fn frame_clear(frame: &Frame) -> f32 {
    match frame.depth {
        DepthEncoding::Normalized => DEPTH_CLEAR,
        DepthEncoding::Reversed { .. } => DEPTH_CLEAR_REVERSED,
    }
}

/// What every tile of a frame draws with: the bins, the primitives, the
/// shading context and the frame's choices of passes.
pub(super) struct TilePasses<'a> {
    pub(super) grid: &'a TileGrid,
    pub(super) bins: &'a Bins,
    pub(super) chunks: &'a [PrimitiveChunk],
    pub(super) shade: ShadeContext<'a>,
    pub(super) fog: Option<FogPass>,
    pub(super) lines: Option<&'a Lines>,
    /// `--wireframe-only`: the surfaces only decide which lines are hidden.
    pub(super) lines_only: bool,
    pub(super) painter: bool,
    pub(super) export_depth: bool,
    /// The depth buffer's far value.
    pub(super) clear: f32,
    /// The background as a colour and as a quantized pixel.
    pub(super) background: (Vec3, u32),
    /// The environment drawn behind the scene, when it is.
    pub(super) sky: Option<SkyView>,
    pub(super) coverage: bool,
    /// The frame's tone mapping, for the resolve.
    pub(super) tone: zline_shading::ToneMapping,
    /// The supersampling factor.
    pub(super) ssaa: u32,
}

impl TilePasses<'_> {
    /// Draws tile (`col`, `row`) with `target` and resolves it into `out`,
    /// its band's rows (and its depth into `depth` when the depth image is
    /// asked for). Returns the samples shaded, or `None` for a tile with nothing
    /// to draw, whose pixels the caller fills with the background
    /// ([`fill_rects`]).
    fn draw(
        &self,
        (target, order): (&mut TileTarget, &mut Vec<(f32, PrimitiveRef)>),
        (col, row): (u32, u32),
        out: &mut ImageRows<u32>,
        depth: Option<&mut ImageRows<f32>>,
    ) -> Option<u64> {
        let (n, chunks, bins) = (self.ssaa, self.chunks, self.bins);
        let tile = row as usize * self.grid.cols as usize + col as usize;
        let (rect, opaque, transparent) =
            (self.grid.rect(col, row), &bins.opaque[tile], &bins.transparent[tile]);
        let line_bin = self.lines.map_or(&[][..], |l| l.bin_of(tile));
        if opaque.is_empty() && transparent.is_empty() && line_bin.is_empty() && self.sky.is_none() {
            return None; // the background's bytes, without the buffers
        }
        target.clear(rect, self.background.0, self.clear);
        target.paint_sky(self.sky.as_ref());
        target.ceiling = self.shade.lighting.ceiling();
        let (shade, fog) = (&self.shade, self.fog.as_ref());
        let mut shaded = 0;
        if self.lines_only && self.lines.is_some() {
            target.depth_only_pass(chunks, opaque_primitives(chunks, opaque, transparent));
            target.fill_background();
        } else if self.painter {
            target.shadow_pass(chunks, &bins.shadow[tile]);
            shaded += target.painter_pass(chunks, transparent, shade, fog, order);
            let hidden_lines = self.lines.is_some_and(|l| l.mode.hides() && !line_bin.is_empty());
            if self.export_depth || hidden_lines {
                target.depth_only_pass(chunks, opaque_primitives(chunks, opaque, transparent));
            }
        } else {
            target.shadow_pass(chunks, &bins.shadow[tile]);
            shaded += target.opaque_pass(chunks, opaque, shade);
            if let Some(fog) = fog {
                target.fog_pass(fog);
            }
            if !transparent.is_empty() {
                shaded += target.transparency_pass(chunks, transparent, shade, fog, order);
            }
        }
        if let Some(lines) = self.lines {
            target.line_pass(lines, line_bin, n);
        }
        if let Some(depth) = depth {
            target.export_depth(depth, n);
        }
        target.tone = self.tone;
        match (self.coverage, n) {
            (false, 1) => target.resolve(out),
            (false, _) => target.resolve_supersampled(out, n),
            (true, 1) => target.resolve_coverage(out),
            (true, _) => target.resolve_coverage_supersampled(out, n),
        }
        Some(shaded)
    }
}

/// Fills the pixels of `runs` (runs of neighbouring untouched tiles of one
/// band, left to right, all of the band's rows) in `out` with one packed
/// colour, row by row across the band: tile by tile, each of a tile's rows
/// started a new stretch of the image a row below the last, and the fill
/// ran at half the speed.
fn fill_rects(out: &mut ImageRows<u32>, runs: &[Rect], color: u32) {
    let Some(runs_first) = runs.first() else {
        return;
    };
    let first = out.first();
    for row in 0..runs_first.height() as usize {
        let line = out.row(row);
        for r in runs {
            line[r.x0 as usize - first..r.x1 as usize - first].fill(color);
        }
    }
}

/// The most pixel rows a band may have to be cut into pieces (taller
/// bands, of tiles above 64 pixels, stay whole): the cut rows are kept on
/// the stack, 64 slices a piece.
const MAX_CUT_ROWS: usize = 64;

/// A band's rows cut at the pieces' first columns: `0[k][r]` is row r of
/// piece k.
struct Cut<'a, T>([[&'a mut [T]; MAX_CUT_ROWS]; MAX_PIECES]);

impl<'a, T> Cut<'a, T> {
    fn new() -> Self {
        Cut(std::array::from_fn(|_| std::array::from_fn(|_| Default::default())))
    }

    /// Cuts each row of `band` (`width` values a row, at most
    /// [`MAX_CUT_ROWS`] rows) into `pieces`, piece k from column `first(k)`.
    fn fill(&mut self, band: &'a mut [T], width: usize, pieces: usize, first: impl Fn(usize) -> usize) {
        for (r, line) in band.chunks_mut(width.max(1)).enumerate() {
            let mut rest = line;
            for k in 0..pieces {
                let end = if k + 1 == pieces { width } else { first(k + 1) };
                let (piece, after) = std::mem::take(&mut rest).split_at_mut(end - first(k));
                self.0[k][r] = piece;
                rest = after;
            }
        }
    }
}
