//! Binning: which primitives each tile must draw, in draw order.

use rayon::prelude::*;
use zline_raster::Rect;

use crate::setup::{Draw, Kernel, PassKind, PrimitiveChunk};

/// The window cut into square tiles, row-major.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TileGrid {
    /// Window width in pixels.
    pub width: u32,
    /// Window height in pixels.
    pub height: u32,
    /// Tile edge in pixels, in 1..=max(width, height, 1).
    pub tile_size: u32,
    /// Tiles per row.
    pub cols: u32,
    /// Rows of tiles.
    pub rows: u32,
}

impl TileGrid {
    /// The grid for a window; a tile size of 0 is taken as 1, and one
    /// larger than the window's longer side as that side (the same single
    /// tile, and no overflow in the tiles' bounds).
    pub fn new(width: u32, height: u32, tile_size: u32) -> TileGrid {
        let tile_size = tile_size.clamp(1, width.max(height).max(1));
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

/// The most pieces a band is cut into.
pub const MAX_PIECES: usize = 16;

/// How many pieces each of `bands` bands of `cols` tiles is cut into for
/// `threads` threads: about four units of work a thread, so that a thread
/// done early takes another while the heaviest units finish (one band each
/// for 1 or 2 threads at 1920×1080 in 64-pixel tiles, 17 bands), at most
/// one a tile and [`MAX_PIECES`]. The image is the same for any count: each
/// tile is drawn alone.
pub fn pieces_per_band(threads: usize, bands: usize, cols: usize) -> usize {
    (4 * threads).div_ceil(bands.max(1)).clamp(1, cols.clamp(1, MAX_PIECES))
}

/// Where a binned primitive lives: `chunks[chunk].draws[index]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PrimitiveRef {
    /// The chunk.
    pub chunk: u32,
    /// The index in the chunk.
    pub index: u32,
}

/// An opaque primitive in a tile's bin: its chunk, its kernel and its index
/// in that kernel's table, so the tile reaches the primitive in one load,
/// not through the chunk's draw list.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OpaqueRef {
    /// The chunk.
    pub chunk: u32,
    /// The kernel that draws it.
    pub kernel: Kernel,
    /// Its index in the kernel's table.
    pub index: u32,
}

/// Per tile (row-major), the primitives whose bounds touch it, in draw order
/// (chunks in order, then primitives in order): opaque ones in `opaque`,
/// those of transparent chunks ([`PassKind::Transparent`]) in `transparent`, planar shadows in `shadow`. The inner vectors keep their
/// capacity from frame to frame.
#[derive(Debug, Default)]
pub struct Bins {
    /// Opaque primitives per tile.
    pub opaque: Vec<Vec<OpaqueRef>>,
    /// Transparent primitives per tile.
    pub transparent: Vec<Vec<PrimitiveRef>>,
    /// Planar shadow primitives per tile ([`PassKind::Shadow`]).
    pub shadow: Vec<Vec<PrimitiveRef>>,
    /// Which bands each chunk's primitives meet, when there are several.
    bands: ChunkBands,
}

/// Which bands of tile rows each chunk's primitives meet, found in
/// parallel before the bands are filled, so that a band reads the bounds of
/// the chunks that meet it ([`bin_into`]).
#[derive(Debug, Default)]
struct ChunkBands {
    /// The number of bands.
    bands: usize,
    /// Per chunk, the first and last band its bounds' rows meet (first
    /// above last when none).
    spans: Vec<(u32, u32)>,
    /// Per chunk and band (at `chunk * bands + band`), for a chunk spread
    /// over more than [`SCANNED_BANDS`] bands, the indices of its
    /// primitives whose rows meet the band, in order; empty otherwise.
    parts: Vec<Vec<u32>>,
}

/// The most bands a chunk may meet and still be scanned whole by each of
/// them. A mesh's chunks are runs of neighbouring triangles, often a strip
/// of the image that meets one or two bands; a chunk spread wider (a
/// scanned mesh's triangles are often stored in no order of place) is
/// sorted to the bands it meets, so a band does not read every bound.
const SCANNED_BANDS: u32 = 2;

/// Whether a chunk meeting bands `first..=last` is spread over more than
/// [`SCANNED_BANDS`], so its primitives are sorted to the bands.
fn spread(first: u32, last: u32) -> bool {
    first + SCANNED_BANDS <= last
}

/// Fills `bins` for this frame's primitives (see [`Bins`]).
pub fn bin_primitives(chunks: &[PrimitiveChunk], grid: &TileGrid, bins: &mut Bins) {
    bin_into(chunks, grid, bins, false);
}

/// Fills `bins` for the painter's algorithm (`Visibility::Painter`): every
/// drawn primitive, opaque or transparent, in `transparent` in draw order
/// (the painter pass sorts them), none in `opaque`; shadows as
/// [`bin_primitives`] puts them.
pub fn bin_primitives_painter(chunks: &[PrimitiveChunk], grid: &TileGrid, bins: &mut Bins) {
    bin_into(chunks, grid, bins, true);
}

/// Bins in bands of tile rows, one rayon task a band, as many bands as the
/// pool has threads (one on one thread): each band appends to its own
/// tiles' lists only, so no list is shared, no second pass merges
/// anything, and every list is in draw order however many bands there
/// are. With several bands, each band reads only the chunks that meet it,
/// and of a chunk spread over many bands only its own primitives
/// ([`ChunkBands`]).
fn bin_into(chunks: &[PrimitiveChunk], grid: &TileGrid, bins: &mut Bins, painter: bool) {
    reset(&mut bins.opaque, grid.len());
    reset(&mut bins.transparent, grid.len());
    reset(&mut bins.shadow, grid.len());
    if grid.is_empty() {
        return;
    }
    let rows_per_band = rows_per_band(grid);
    let bands = &mut bins.bands;
    bands.find(chunks, grid, rows_per_band as u32);
    let bands = &*bands;
    let tiles = rows_per_band * grid.cols as usize;
    let opaque = bins.opaque.par_chunks_mut(tiles);
    let lists = opaque.zip(bins.transparent.par_chunks_mut(tiles)).zip(bins.shadow.par_chunks_mut(tiles));
    lists.enumerate().for_each(|(band, ((opaque, transparent), shadow))| {
        let first_row = (band * rows_per_band) as u32;
        let mut lists =
            BandLists { opaque, transparent, shadow, first_tile: first_row as usize * grid.cols as usize };
        lists.bin((chunks, bands), grid, (band, first_row), painter);
    });
}

impl ChunkBands {
    /// Finds, per chunk in parallel, the bands (of `rows_per_band` tile
    /// rows of `grid`) its bounds' rows meet, and sorts the primitives of a
    /// chunk spread over more than [`SCANNED_BANDS`] to them. With one
    /// band, nothing: the band reads every chunk.
    fn find(&mut self, chunks: &[PrimitiveChunk], grid: &TileGrid, rows_per_band: u32) {
        self.bands = grid.rows.div_ceil(rows_per_band) as usize;
        self.spans.clear();
        if self.bands < 2 {
            return;
        }
        let (bands, band_px, height) = (self.bands, rows_per_band * grid.tile_size, grid.height as i32);
        // The bands that rows y0..y1 meet, first above last when none.
        let rows = move |y0: i32, y1: i32| {
            let (y0, y1) = (y0.max(0), y1.min(height));
            if y0 < y1 {
                (y0 as u32 / band_px, (y1 - 1) as u32 / band_px)
            } else {
                (1, 0)
            }
        };
        self.parts.resize_with(chunks.len() * bands, Vec::new);
        let spans = chunks.par_iter().zip(self.parts.par_chunks_mut(bands)).map(|(chunk, parts)| {
            let (y0, y1) =
                chunk.bounds.iter().fold((i32::MAX, i32::MIN), |(y0, y1), b| (y0.min(b.y0), y1.max(b.y1)));
            let (first, last) = rows(y0, y1);
            parts.iter_mut().for_each(Vec::clear);
            if spread(first, last) {
                for (i, b) in chunk.bounds.iter().enumerate() {
                    let (first, last) = rows(b.y0, b.y1);
                    for part in parts.get_mut(first as usize..=last as usize).unwrap_or_default() {
                        part.push(i as u32);
                    }
                }
            }
            (first, last)
        });
        self.spans.par_extend(spans);
    }

    /// The indices of chunk `c`'s primitives that `band` must read: none
    /// when the chunk misses the band, those sorted to it when the chunk
    /// was spread over many bands, else (`None`) every one.
    fn primitives(&self, c: usize, band: usize) -> Option<&[u32]> {
        let &(first, last) = self.spans.get(c)?;
        let band = band as u32;
        if band < first || band > last {
            Some(&[])
        } else if spread(first, last) {
            Some(&self.parts[c * self.bands + band as usize])
        } else {
            None
        }
    }
}

/// Tile rows per band when a grid's tiles are filled in parallel: as many
/// bands as the pool has threads (one on one thread), at least a row each.
/// Shared by the primitives' and the lines' binning.
pub(crate) fn rows_per_band(grid: &TileGrid) -> usize {
    let rows = grid.rows as usize;
    rows.div_ceil(rayon::current_num_threads().clamp(1, rows.max(1)))
}

/// The tile lists of one band of tile rows ([`bin_into`]).
struct BandLists<'a> {
    opaque: &'a mut [Vec<OpaqueRef>],
    transparent: &'a mut [Vec<PrimitiveRef>],
    shadow: &'a mut [Vec<PrimitiveRef>],
    /// The window's index of the band's first tile.
    first_tile: usize,
}

impl BandLists<'_> {
    /// Appends every primitive whose bounds meet band `band` (tile rows
    /// from `first_row`) to the lists of the tiles it meets there, reading of
    /// each chunk the primitives [`ChunkBands::primitives`] gives.
    fn bin(
        &mut self,
        (chunks, bands): (&[PrimitiveChunk], &ChunkBands),
        grid: &TileGrid,
        (band, first_row): (usize, u32),
        painter: bool,
    ) {
        let rows = (self.opaque.len() / grid.cols as usize) as u32;
        let y0 = (first_row * grid.tile_size) as i32;
        let y1 = ((first_row + rows) * grid.tile_size).min(grid.height) as i32;
        let area = Rect { x0: 0, y0, x1: grid.width as i32, y1 };
        for (c, chunk) in chunks.iter().enumerate() {
            match bands.primitives(c, band) {
                None => {
                    for (i, (b, d)) in chunk.bounds.iter().zip(&chunk.draws).enumerate() {
                        self.add((chunk, c, i), (b.intersect(&area), d), grid, painter);
                    }
                }
                Some(indices) => {
                    for &i in indices {
                        let i = i as usize;
                        let b = chunk.bounds[i].intersect(&area);
                        self.add((chunk, c, i), (b, &chunk.draws[i]), grid, painter);
                    }
                }
            }
        }
    }

    /// Appends primitive `i` of chunk `c`, of bounds `b` within the band,
    /// to the lists of the tiles it meets.
    #[inline(always)]
    fn add(
        &mut self,
        (chunk, c, i): (&PrimitiveChunk, usize, usize),
        (b, d): (Rect, &Draw),
        grid: &TileGrid,
        painter: bool,
    ) {
        if b.is_empty() {
            return;
        }
        let (ts, first) = (grid.tile_size as i32, self.first_tile);
        match chunk.pass {
            PassKind::Opaque if !painter => {
                let r = OpaqueRef { chunk: c as u32, kernel: d.kernel, index: d.index };
                for_each_tile(b, ts, grid.cols, |t| self.opaque[t - first].push(r));
            }
            PassKind::Opaque | PassKind::Transparent { .. } => {
                let r = PrimitiveRef { chunk: c as u32, index: i as u32 };
                for_each_tile(b, ts, grid.cols, |t| self.transparent[t - first].push(r));
            }
            PassKind::Shadow { .. } => {
                let r = PrimitiveRef { chunk: c as u32, index: i as u32 };
                for_each_tile(b, ts, grid.cols, |t| self.shadow[t - first].push(r));
            }
        }
    }
}

/// Calls `push` with the index of every tile (of `size` px, `cols` to a
/// row) that `b` meets, row by row. Plain loops: the `flat_map` this was
/// stayed out of line (a call per primitive, 3 % of the instructions of a
/// 1M-triangle frame).
#[inline(always)]
fn for_each_tile(b: Rect, size: i32, cols: u32, mut push: impl FnMut(usize)) {
    for row in b.y0 / size..=(b.y1 - 1) / size {
        for col in b.x0 / size..=(b.x1 - 1) / size {
            push(row as usize * cols as usize + col as usize);
        }
    }
}

/// `n` empty lists, keeping the lists' capacity.
fn reset<T>(lists: &mut Vec<Vec<T>>, n: usize) {
    lists.resize_with(n, Vec::new);
    lists.truncate(n);
    lists.iter_mut().for_each(Vec::clear);
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Chunks of the given passes, each primitive with the given bounds.
    fn chunks(primitives: &[(u8, [i32; 4])]) -> Vec<PrimitiveChunk> {
        let mut chunks: Vec<PrimitiveChunk> = Vec::new();
        for (k, &(pass, [x, y, w, h])) in primitives.iter().enumerate() {
            let pass = match pass % 3 {
                0 => PassKind::Opaque,
                1 => PassKind::Transparent { kt: 0.5 },
                _ => PassKind::Shadow { bit: 0 },
            };
            if k % 4 == 0 || chunks.last().is_none_or(|c| c.pass != pass) {
                let mut chunk = PrimitiveChunk::default();
                chunk.reset(pass);
                chunks.push(chunk);
            }
            let chunk = chunks.last_mut().unwrap();
            let index = chunk.draws.len() as u32;
            chunk.draws.push(crate::setup::Draw {
                kernel: Kernel::Flat,
                index,
                sort_depth: 0.0,
                far_depth: 0.0,
            });
            chunk.bounds.push(Rect { x0: x, y0: y, x1: x + w, y1: y + h });
        }
        chunks
    }

    proptest! {
        /// Every tile's lists are the same, in the same order, whatever
        /// the number of bands (threads), for both binnings: bounds inside,
        /// across and outside the window, empty ones too.
        #[test]
        fn bins_do_not_depend_on_the_bands(
            primitives in proptest::collection::vec((0u8..3, [-40i32..140, -40..140, 0..90, 0..90]), 0..60),
            tile_size in 1u32..50,
            painter in any::<bool>(),
            strips in any::<bool>(),
        ) {
            let mut primitives = primitives;
            if strips {
                // Chunks as a mesh's often are: strips of the image, whose
                // spans of rows meet a few bands, edges on band edges too.
                primitives.sort_by_key(|&(_, [_, y, _, h])| (y, h));
            }
            let chunks = chunks(&primitives);
            let grid = TileGrid::new(100, 70, tile_size);
            let bin = |threads: usize| {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let mut bins = Bins::default();
                pool.install(|| bin_into(&chunks, &grid, &mut bins, painter));
                (bins.opaque, bins.transparent, bins.shadow)
            };
            let one = bin(1);
            // The brute force: each tile against each primitive, in order.
            let mut expected = (vec![Vec::new(); grid.len()], vec![Vec::new(); grid.len()], vec![Vec::new(); grid.len()]);
            for t in 0..grid.len() {
                let tile = grid.rect(t as u32 % grid.cols, t as u32 / grid.cols);
                for (c, chunk) in chunks.iter().enumerate() {
                    for (i, (b, d)) in chunk.bounds.iter().zip(&chunk.draws).enumerate() {
                        if b.intersect(&tile).is_empty() {
                            continue;
                        }
                        let r = PrimitiveRef { chunk: c as u32, index: i as u32 };
                        match chunk.pass {
                            PassKind::Opaque if !painter => {
                                expected.0[t].push(OpaqueRef { chunk: c as u32, kernel: d.kernel, index: d.index })
                            }
                            PassKind::Opaque | PassKind::Transparent { .. } => expected.1[t].push(r),
                            PassKind::Shadow { .. } => expected.2[t].push(r),
                        }
                    }
                }
            }
            prop_assert!(one == expected);
            for threads in [2, 3, 7, 16] {
                prop_assert!(bin(threads) == one, "{} threads", threads);
            }
        }
    }

    #[test]
    fn any_tile_size_gives_tiles_inside_the_window() {
        for tile_size in [0, 1, 7, 64, 1 << 31, u32::MAX] {
            let grid = TileGrid::new(100, 30, tile_size);
            assert!((1..=100).contains(&grid.tile_size), "tile {tile_size}: edge {}", grid.tile_size);
            let mut pixels = 0;
            for row in 0..grid.rows {
                for col in 0..grid.cols {
                    let r = grid.rect(col, row);
                    assert!(r.x0 >= 0 && r.y0 >= 0 && r.x1 <= 100 && r.y1 <= 30 && !r.is_empty());
                    pixels += r.width() * r.height();
                }
            }
            assert_eq!(pixels, 100 * 30, "tile {tile_size}: the tiles do not cover the window once");
        }
        assert_eq!(TileGrid::new(100, 30, u32::MAX).len(), 1);
        assert_eq!(TileGrid::new(0, 0, u32::MAX).len(), 0);
    }
}
