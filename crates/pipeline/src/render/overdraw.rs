//! The overdraw image: per pixel, how many fragments the frame's triangles
//! made there — every covered sample of every drawn primitive, whether or
//! not it then passed the depth test — the depth complexity a z-buffer
//! pays for.
//!
//! It is counted, not drawn: the frame runs the geometry, setup and binning
//! stages as usual, then each tile walks its bins' primitives in draw order
//! and counts their samples. Under the top-left rule the samples are the
//! kernels' own ([`EdgeTable::scan`]'s spans); under
//! [`TieRule::Closed`] or [`TieRule::Open`] they are the samples a
//! renderer without the rule would cover ([`zline_raster::covers`]), so a
//! mesh's shared edges show up counted twice, or as cracks. Culled back
//! faces and clipped-away parts count nothing, as they draw nothing; lines
//! and shadow primitives are not counted.

use rayon::prelude::*;
use zline_raster::{covers, EdgeTable, Rect, TieRule};
use zline_scene::Scene;

use super::{RenderOptions, RenderStats, Renderer};
use crate::bin::{OpaqueRef, PrimitiveRef, TileGrid};
use crate::setup::PrimitiveChunk;

/// A frame's overdraw counts (see the module's documentation). Rows top to
/// bottom.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Overdraw {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Samples per pixel (n² with n×n supersampling).
    pub samples: u32,
    /// Per pixel, the fragments of all its samples together.
    pub counts: Vec<u32>,
}

impl Overdraw {
    /// The count at pixel (x, y).
    pub fn at(&self, x: u32, y: u32) -> u32 {
        self.counts[y as usize * self.width as usize + x as usize]
    }

    /// All fragments of the frame.
    pub fn total(&self) -> u64 {
        self.counts.iter().map(|&c| u64::from(c)).sum()
    }
}

impl Renderer {
    /// The overdraw of `scene` under `rule` into `overdraw` (see the
    /// module's documentation).
    pub fn render_overdraw_into(
        &mut self,
        scene: &Scene,
        options: &RenderOptions,
        rule: TieRule,
        overdraw: &mut Overdraw,
    ) -> RenderStats {
        let mut image = crate::image::Image::empty();
        self.overdraw = Some(rule);
        let stats = self.render_frame(scene, options, &mut image, None);
        self.overdraw = None;
        let n = scene.settings.ssaa.clamp(1, zline_scene::MAX_SSAA);
        (overdraw.width, overdraw.height, overdraw.samples) = (image.width, image.height, n * n);
        overdraw.counts = image.pixels;
        stats
    }

    /// The counting that replaces the tile passes in an overdraw frame:
    /// bands of tiles in parallel, each pixel's count into `pixels`.
    pub(super) fn count_tiles(
        &self,
        grid: &TileGrid,
        (width, height, n): (u32, u32, u32),
        rule: TieRule,
        pixels: &mut Vec<u32>,
    ) {
        let chunks = &self.chunks[..self.used];
        pixels.clear();
        pixels.resize(width as usize * height as usize, 0);
        let tile_pixels = (grid.tile_size / n) as usize;
        pixels.par_chunks_mut(width as usize * tile_pixels).enumerate().for_each(|(row, band)| {
            let mut samples = Vec::new();
            for col in 0..grid.cols {
                let tile = row * grid.cols as usize + col as usize;
                let rect = grid.rect(col, row as u32);
                samples.clear();
                samples.resize(rect.width() as usize * rect.height() as usize, 0u32);
                let bins = (&self.bins.opaque[tile][..], &self.bins.transparent[tile][..]);
                count_tile(chunks, bins, rect, rule, &mut samples);
                let w = rect.width() as usize;
                for (i, &c) in samples.iter().enumerate() {
                    let (sx, sy) = ((i % w) as i32 + rect.x0, (i / w) as i32 + rect.y0);
                    let (px, py) = ((sx / n as i32) as usize, (sy / n as i32) as usize - row * tile_pixels);
                    band[py * width as usize + px] += c;
                }
            }
        });
    }
}

/// Counts the fragments of a tile's bins into `samples` (the tile's
/// samples, row by row).
fn count_tile(
    chunks: &[PrimitiveChunk],
    (opaque, transparent): (&[OpaqueRef], &[PrimitiveRef]),
    rect: Rect,
    rule: TieRule,
    samples: &mut [u32],
) {
    let w = rect.width() as usize;
    let mut count = |edges: &EdgeTable| {
        if rule == TieRule::TopLeft {
            edges.scan(rect, |s| {
                let row = (s.y - rect.y0) as usize * w;
                for c in &mut samples[row + (s.x0 - rect.x0) as usize..row + (s.x1 - rect.x0) as usize] {
                    *c += 1;
                }
            });
            return;
        }
        // A closed triangle may also cover the samples on its right and
        // bottom edges, one past the edge table's bounds.
        let b = edges.bounds();
        let area = Rect { x1: b.x1.saturating_add(1), y1: b.y1.saturating_add(1), ..b }.intersect(&rect);
        let vertices = edges.sorted_vertices();
        for y in area.y0..area.y1 {
            for x in area.x0..area.x1 {
                if covers(vertices, x.into(), y.into(), rule) {
                    samples[(y - rect.y0) as usize * w + (x - rect.x0) as usize] += 1;
                }
            }
        }
    };
    for r in opaque {
        count(chunks[r.chunk as usize].tables.edges(r.kernel, r.index));
    }
    for r in transparent {
        let chunk = &chunks[r.chunk as usize];
        let d = chunk.draws[r.index as usize];
        count(chunk.tables.edges(d.kernel, d.index));
    }
}

/// Counts the overdraw of `scene` under `rule` (see the module's
/// documentation).
pub fn render_overdraw(scene: &Scene, options: &RenderOptions, rule: TieRule) -> (Overdraw, RenderStats) {
    let mut overdraw = Overdraw::default();
    let stats = Renderer::default().render_overdraw_into(scene, options, rule, &mut overdraw);
    (overdraw, stats)
}
