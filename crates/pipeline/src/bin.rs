//! Binning: which primitives each tile must draw, in draw order.

use zline_raster::Rect;

use crate::setup::Primitive;

/// The window cut into square tiles, row-major.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TileGrid {
    /// Window width in pixels.
    pub width: u32,
    /// Window height in pixels.
    pub height: u32,
    /// Tile edge in pixels (≥ 1).
    pub tile_size: u32,
    /// Tiles per row.
    pub cols: u32,
    /// Rows of tiles.
    pub rows: u32,
}

impl TileGrid {
    /// The grid for a window; a tile size of 0 is taken as 1.
    pub fn new(width: u32, height: u32, tile_size: u32) -> TileGrid {
        let tile_size = tile_size.max(1);
        TileGrid {
            width,
            height,
            tile_size,
            cols: width.div_ceil(tile_size),
            rows: height.div_ceil(tile_size),
        }
    }

    /// Number of tiles.
    pub fn len(&self) -> usize {
        self.cols as usize * self.rows as usize
    }

    /// True when the window has no pixels.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The pixels of tile (col, row), cut at the window's edge.
    pub fn rect(&self, col: u32, row: u32) -> Rect {
        let (x0, y0) = (col * self.tile_size, row * self.tile_size);
        let (x1, y1) = ((x0 + self.tile_size).min(self.width), (y0 + self.tile_size).min(self.height));
        Rect { x0: x0 as i32, y0: y0 as i32, x1: x1 as i32, y1: y1 as i32 }
    }

    /// The whole window.
    pub fn window(&self) -> Rect {
        Rect { x0: 0, y0: 0, x1: self.width as i32, y1: self.height as i32 }
    }
}

/// Lists in `bins`, per tile (row-major), the indices of the primitives
/// whose bounds touch it, in increasing order — the draw order. The inner
/// vectors keep their capacity from frame to frame.
pub fn bin_primitives(prims: &[Primitive], grid: &TileGrid, bins: &mut Vec<Vec<u32>>) {
    bins.resize_with(grid.len(), Vec::new);
    bins.truncate(grid.len());
    bins.iter_mut().for_each(Vec::clear);
    let window = grid.window();
    let ts = grid.tile_size as i32;
    for (i, p) in prims.iter().enumerate() {
        let b = p.edges.bounds().intersect(&window);
        if b.is_empty() {
            continue;
        }
        for row in b.y0 / ts..=(b.y1 - 1) / ts {
            for col in b.x0 / ts..=(b.x1 - 1) / ts {
                bins[(row as u32 * grid.cols + col as u32) as usize].push(i as u32);
            }
        }
    }
}
