//! The tile stage of a frame: every tile's passes, bands of tiles in
//! parallel ([`Renderer::draw_tiles`], [`TilePasses`]).

use std::sync::{Mutex, PoisonError};
use std::time::Instant;

use glam::Vec3;

use rayon::iter::Either;
use rayon::prelude::*;
use zline_scene::{Scene, Visibility};

use zline_raster::Rect;

use super::{opaque_primitives, pixels_of, BandBuffers, Frame, Renderer};
use crate::bin::{Bins, PrimitiveRef, TileGrid};
use crate::fog::FogPass;
use crate::image::{quantize_rgba, Image};
use crate::lines::Lines;
use crate::setup::{DepthEncoding, PrimitiveChunk};
use crate::sky::SkyView;
use crate::tile::{ShadeContext, TileTarget, DEPTH_CLEAR, DEPTH_CLEAR_REVERSED};

impl Renderer {
    /// Every tile, bands of tiles in parallel: each tile clears its depth,
    /// draws its opaque bin, fogs, draws its transparent bin and resolves
    /// into the image rows it owns ([`TilePasses::draw`]). Returns the
    /// samples shaded.
    pub(super) fn draw_tiles(
        &mut self,
        scene: &Scene,
        frame: &Frame,
        grid: &TileGrid,
        (image, depth): (&mut Image, Option<&mut Vec<f32>>),
    ) -> u64 {
        let (width, n) = (frame.width, frame.n);
        let tile_size = grid.tile_size / n;
        let coverage = scene.settings.transparent_background;
        image.width = width;
        image.height = frame.height;
        image.transparent = coverage;
        image.pixels.resize(width as usize * frame.height as usize, 0);
        let band_len = width as usize * tile_size as usize;
        let threads = self.prepare_band_buffers(grid, coverage);
        let buffers = &self.buffers[..threads];
        let clear = frame_clear(frame);
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
        image
            .pixels
            .par_chunks_mut(band_len)
            .zip(depth_bands)
            .enumerate()
            .map(|(row, (band, mut depth_band))| {
                let start = Instant::now();
                // Only this thread takes its own buffers: the lock is never
                // contended (and a poisoned one holds plain buffers).
                let thread = rayon::current_thread_index().unwrap_or(0) % threads;
                let mut guard = buffers[thread].lock().unwrap_or_else(PoisonError::into_inner);
                let BandBuffers { target, order, untouched } = &mut *guard;
                untouched.clear();
                let shaded = (0..grid.cols)
                    .map(|col| {
                        let tile = (col, row as u32);
                        let drawn = passes.draw((target, order), tile, band, depth_band.as_deref_mut());
                        drawn.unwrap_or_else(|| {
                            let rect = pixels_of(grid.rect(col, row as u32), n);
                            // A tile touching the last one lengthens its run.
                            match untouched.last_mut() {
                                Some(last) if last.x1 == rect.x0 => last.x1 = rect.x1,
                                _ => untouched.push(rect),
                            }
                            0
                        })
                    })
                    .sum::<u64>();
                fill_rects(band, width as usize, untouched, passes.background.1);
                (shaded, start.elapsed())
            })
            .collect_into_vec(&mut bands);
        let shaded = bands.iter().map(|&(n, _)| n).sum();
        self.bands = bands;
        shaded
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
            size: (frame.width, frame.n),
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
    /// The image width and the supersampling factor.
    pub(super) size: (u32, u32),
}

impl TilePasses<'_> {
    /// Draws tile (`col`, `row`) with `target` and resolves it into `band`
    /// (and its depth into `depth_band` when the depth image is asked
    /// for). Returns the samples shaded, or `None` for a tile with nothing
    /// to draw, whose pixels the caller fills with the background
    /// ([`fill_rects`]).
    fn draw(
        &self,
        (target, order): (&mut TileTarget, &mut Vec<(f32, PrimitiveRef)>),
        (col, row): (u32, u32),
        band: &mut [u32],
        depth_band: Option<&mut [f32]>,
    ) -> Option<u64> {
        let ((width, n), chunks, bins) = (self.size, self.chunks, self.bins);
        let width = width as usize;
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
        if let Some(depth_band) = depth_band {
            target.export_depth(depth_band, width, n);
        }
        target.tone = self.tone;
        match (self.coverage, n) {
            (false, 1) => target.resolve(band, width),
            (false, _) => target.resolve_supersampled(band, width, n),
            (true, 1) => target.resolve_coverage(band, width),
            (true, _) => target.resolve_coverage_supersampled(band, width, n),
        }
        Some(shaded)
    }
}

/// Fills the pixels of `runs` (runs of neighbouring untouched tiles of one
/// band, left to right, all of the band's rows) in `band` with one packed
/// colour, row by row across the band: tile by tile, each of a tile's rows
/// started a new stretch of the image a row below the last, and the fill
/// ran at half the speed.
fn fill_rects(band: &mut [u32], width: usize, runs: &[Rect], color: u32) {
    let Some(first) = runs.first() else {
        return;
    };
    for row in 0..first.height() as usize {
        let line = &mut band[row * width..(row + 1) * width];
        for r in runs {
            line[r.x0 as usize..r.x1 as usize].fill(color);
        }
    }
}
