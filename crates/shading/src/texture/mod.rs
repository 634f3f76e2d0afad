//! Texture storage and sampling (SPEC §7): a mip chain of RGBA `f32` texels
//! built from 8-bit image data, read with nearest, bilinear or trilinear
//! filtering and repeat or clamp-to-edge wrapping. Pure functions: decoding
//! image files happens in the loaders, which hand over RGBA8 rows.
//! [`Texture::sample_x8`] (module `x8`) samples eight lanes at once, each
//! lane bit for bit equal to [`Texture::sample`].
//!
//! Conventions:
//! - s = 0 at the left of the image and t = 0 at the bottom (OBJ, OpenGL).
//!   Texel centres are at (k + 0.5)/size, so column x covers s ∈ [x/w, (x+1)/w)
//!   and the image's top row covers t ∈ [(h−1)/h, 1).
//! - Levels are stored bottom row first, so a level's row index grows with
//!   t; [`Texture::from_rgba8`] flips the image's top-to-bottom rows once.
//!   All levels live in one contiguous buffer, level 0 first.
//! - Values are byte/255 as stored: no sRGB decode (SPEC §7).
//! - Wrapping applies to integer texel indices, after the filter has chosen
//!   its texels: bilinear filtering at the border of a repeating texture
//!   blends with the opposite edge, and clamp-to-edge never reads outside.
//!
//! Decisions:
//! - Nearest picks floor(s·w): at a coordinate exactly between two texel
//!   centres, which is a texel boundary x/w, the texel to the right (above,
//!   for t) wins, so each texel owns a half-open interval as above.
//! - Interpolation is `a + (b − a)·f` with f ∈ [0, 1]: exact at f = 0 and
//!   when a = b, so a texel centre, a uniform region and a clamped border
//!   return stored texels bit for bit.
//! - Mip levels halve each side, rounding down (never below 1), and each
//!   texel of level l + 1 is the exact area average of level l over the same
//!   part of the image. For an even side that is the 2×2 box filter. For an
//!   odd side 2n + 1 → n, each coarse texel spans 2 + 1/n fine texels, so
//!   texel k averages fine texels 2k, 2k + 1, 2k + 2 with weights
//!   (n − k, n, k + 1)/(2n + 1) (5 → 2: 0.4, 0.4, 0.2 then 0.2, 0.4, 0.4).
//!   Unlike dropping or clamping the last row, this keeps the coarse texel
//!   centres aligned with the image and preserves the mean on every level.
//! - A non-finite s or t (NaN, ±∞, or a finite value whose product with the
//!   size overflows) reads texel column (row) 0 exactly, on every filter.
//!   Finite coordinates beyond the i32 range of texels saturate there.

use std::fmt;

use glam::{Vec2, Vec4};

/// The largest width or height [`Texture::from_rgba8`] accepts.
pub const MAX_TEXTURE_SIZE: u32 = 16384;

/// What happens to texel indices outside the texture, per axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Wrap {
    /// The texture tiles the plane: index modulo size (SPEC §7 default).
    #[default]
    Repeat,
    /// Indices clamp to [0, size − 1]: the edge texels extend outwards.
    ClampToEdge,
}

/// How texels are combined into a sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Filter {
    /// The texel of level 0 whose centre is nearest; no mipmapping.
    Nearest,
    /// Level 0, interpolated between the four texels around the sample:
    /// along s on the two rows, then along t. No mipmapping.
    Bilinear,
    /// Bilinear on the two mip levels around the level of detail, blended
    /// linearly; bilinear on level 0 when magnifying (lod ≤ 0).
    #[default]
    Trilinear,
}

/// How a texture is read: filter and wrap modes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Sampler {
    /// Texel filter.
    pub filter: Filter,
    /// Wrapping along s.
    pub wrap_s: Wrap,
    /// Wrapping along t.
    pub wrap_t: Wrap,
}

/// Why [`Texture::from_rgba8`] refused its input.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextureError {
    /// Width or height is zero.
    ZeroSize {
        /// Width asked for.
        width: u32,
        /// Height asked for.
        height: u32,
    },
    /// Width or height exceeds [`MAX_TEXTURE_SIZE`].
    TooLarge {
        /// Width asked for.
        width: u32,
        /// Height asked for.
        height: u32,
    },
    /// The pixel buffer is not width × height × 4 bytes long.
    WrongLength {
        /// Width asked for.
        width: u32,
        /// Height asked for.
        height: u32,
        /// Bytes needed.
        expected: usize,
        /// Bytes given.
        actual: usize,
    },
}

impl fmt::Display for TextureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            TextureError::ZeroSize { width, height } => {
                write!(f, "texture size {width}x{height} is empty: width and height must be at least 1")
            }
            TextureError::TooLarge { width, height } => write!(
                f,
                "texture size {width}x{height} exceeds the limit of {MAX_TEXTURE_SIZE} texels per side"
            ),
            TextureError::WrongLength { width, height, expected, actual } => write!(
                f,
                "texture of {width}x{height} texels needs {expected} bytes of RGBA8 data \
                 (4 per texel), got {actual}"
            ),
        }
    }
}

impl std::error::Error for TextureError {}

/// One mip level: where its texels start in the shared buffer, and its size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Level {
    offset: usize,
    width: u32,
    height: u32,
}

impl Level {
    /// Buffer index of texel (x, y), y counted from the bottom row.
    #[inline]
    fn index(self, x: u32, y: u32) -> usize {
        self.offset + (y * self.width + x) as usize
    }
}

/// Texels in a mip chain whose level 0 is `size`, down to 1×1.
fn mip_chain_len(mut size: (u32, u32)) -> usize {
    let mut total = size.0 as usize * size.1 as usize;
    while size != (1, 1) {
        size = half_size(size);
        total += size.0 as usize * size.1 as usize;
    }
    total
}

/// The next coarser level's size: each side halved, rounding down, at least 1.
fn half_size((width, height): (u32, u32)) -> (u32, u32) {
    ((width / 2).max(1), (height / 2).max(1))
}

/// An RGBA texture with its full mip chain down to 1×1.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// Every level's texels, level 0 first, each level bottom row first.
    texels: Box<[Vec4]>,
    /// Level 0 first; the last level is 1×1.
    levels: Box<[Level]>,
}

impl Texture {
    /// A texture from 8-bit RGBA pixels, rows top to bottom as image files
    /// store them, 4 bytes per texel; each channel becomes byte/255.
    /// Builds the mip chain (see the module documentation).
    pub fn from_rgba8(width: u32, height: u32, pixels: &[u8]) -> Result<Texture, TextureError> {
        if width == 0 || height == 0 {
            return Err(TextureError::ZeroSize { width, height });
        }
        if width > MAX_TEXTURE_SIZE || height > MAX_TEXTURE_SIZE {
            return Err(TextureError::TooLarge { width, height });
        }
        let expected = width as usize * height as usize * 4;
        if pixels.len() != expected {
            return Err(TextureError::WrongLength { width, height, expected, actual: pixels.len() });
        }
        let total = mip_chain_len((width, height));
        let mut texels = Vec::with_capacity(total);
        // Image rows run top to bottom; levels are stored bottom row first.
        for row in pixels.chunks_exact(width as usize * 4).rev() {
            texels.extend(
                row.chunks_exact(4)
                    .map(|p| Vec4::from_array([p[0], p[1], p[2], p[3]].map(f32::from)) / 255.0),
            );
        }
        let mut levels = vec![Level { offset: 0, width, height }];
        let mut last = levels[0];
        while (last.width, last.height) != (1, 1) {
            last = push_coarser_level(&mut texels, last);
            levels.push(last);
        }
        debug_assert_eq!(texels.len(), total);
        Ok(Texture { texels: texels.into_boxed_slice(), levels: levels.into_boxed_slice() })
    }

    /// The same image with its colour channels decoded from sRGB to linear
    /// (IEC 61966-2-1; alpha kept) and the mip chain rebuilt from the
    /// decoded level 0, so filtering averages linear values: what a colour
    /// texture becomes when the frame's tone mapping ends in sRGB
    /// (SPEC §7, §10).
    pub fn srgb_decoded(&self) -> Texture {
        let base = self.levels[0];
        let decode = |c: f32| if c <= 0.040_45 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) };
        let mut texels: Vec<Vec4> = self.texels[..(base.width * base.height) as usize]
            .iter()
            .map(|t| Vec4::new(decode(t.x), decode(t.y), decode(t.z), t.w))
            .collect();
        let mut levels = vec![base];
        let mut last = base;
        while (last.width, last.height) != (1, 1) {
            last = push_coarser_level(&mut texels, last);
            levels.push(last);
        }
        Texture { texels: texels.into_boxed_slice(), levels: levels.into_boxed_slice() }
    }

    /// A 1×1 texture of one colour (one level).
    pub fn solid(color: Vec4) -> Texture {
        Texture { texels: Box::new([color]), levels: Box::new([Level { offset: 0, width: 1, height: 1 }]) }
    }

    /// Width of level 0 in texels.
    #[inline]
    pub fn width(&self) -> u32 {
        self.levels[0].width
    }

    /// Height of level 0 in texels.
    #[inline]
    pub fn height(&self) -> u32 {
        self.levels[0].height
    }

    /// Number of mip levels, level 0 included: ⌊log2(max(w, h))⌋ + 1.
    #[inline]
    pub fn levels(&self) -> usize {
        self.levels.len()
    }

    /// Width and height of mip `level` (level 0 is the full texture).
    /// Panics when `level >= self.levels()`.
    #[inline]
    pub fn level_size(&self, level: usize) -> (u32, u32) {
        let lv = self.levels[level];
        (lv.width, lv.height)
    }

    /// The stored texel at column `x`, row `y` of mip `level`, rows counted
    /// from the bottom (t = 0), channels in [0, 1]. This is the value every
    /// filter reads; reference renderers sample through it. Panics when the
    /// level or position is out of range.
    pub fn texel(&self, level: usize, x: u32, y: u32) -> Vec4 {
        let lv = self.levels[level];
        assert!(x < lv.width && y < lv.height, "texel ({x}, {y}) outside level {level}");
        self.texels[lv.index(x, y)]
    }

    /// The filtered texture value at (s, t). `lod` is the level of detail
    /// from [`lod`]; only [`Filter::Trilinear`] uses it. A lod ≤ 0 or NaN
    /// reads level 0; a lod at or beyond the last level reads the last.
    #[inline]
    pub fn sample(&self, sampler: &Sampler, s: f32, t: f32, lod: f32) -> Vec4 {
        match sampler.filter {
            Filter::Nearest => self.nearest(0, sampler, s, t),
            Filter::Bilinear => self.bilinear(0, sampler, s, t),
            Filter::Trilinear => self.trilinear(sampler, s, t, lod),
        }
    }

    #[inline]
    fn nearest(&self, level: usize, sampler: &Sampler, s: f32, t: f32) -> Vec4 {
        let lv = self.levels[level];
        let x = nearest_index(s, lv.width, sampler.wrap_s);
        let y = nearest_index(t, lv.height, sampler.wrap_t);
        self.texels[lv.index(x, y)]
    }

    /// The seed's two-step interpolation: along s on the rows below and
    /// above the sample, then along t between the two results.
    #[inline]
    fn bilinear(&self, level: usize, sampler: &Sampler, s: f32, t: f32) -> Vec4 {
        let lv = self.levels[level];
        let (x0, x1, fs) = linear_taps(s, lv.width, sampler.wrap_s);
        let (y0, y1, ft) = linear_taps(t, lv.height, sampler.wrap_t);
        let texel = |x, y| self.texels[lv.index(x, y)];
        let below = lerp(texel(x0, y0), texel(x1, y0), fs);
        let above = lerp(texel(x0, y1), texel(x1, y1), fs);
        lerp(below, above, ft)
    }

    #[inline]
    fn trilinear(&self, sampler: &Sampler, s: f32, t: f32, lod: f32) -> Vec4 {
        let last = self.levels.len() - 1;
        if lod >= last as f32 {
            self.bilinear(last, sampler, s, t)
        } else if lod > 0.0 {
            let level = lod.floor();
            let finer = level as usize;
            let a = self.bilinear(finer, sampler, s, t);
            let b = self.bilinear(finer + 1, sampler, s, t);
            lerp(a, b, lod - level)
        } else {
            // Magnification, and a NaN lod (both comparisons false).
            self.bilinear(0, sampler, s, t)
        }
    }
}

/// The level of detail: log2 of the larger screen-axis footprint in level-0
/// texels, log2(max(|(∂s/∂x·w, ∂t/∂x·h)|, |(∂s/∂y·w, ∂t/∂y·h)|)) (the
/// usual OpenGL approximation). Zero derivatives give −∞, which samples
/// level 0; a NaN in one direction is ignored (`f32::max`), NaN in both
/// gives NaN, which also samples level 0.
#[inline]
pub fn lod(dsdx: f32, dtdx: f32, dsdy: f32, dtdy: f32, width: u32, height: u32) -> f32 {
    let size = Vec2::new(width as f32, height as f32);
    let along_x = (Vec2::new(dsdx, dtdx) * size).length_squared();
    let along_y = (Vec2::new(dsdy, dtdy) * size).length_squared();
    // log2(√q) = log2(q)/2 saves the square root.
    0.5 * along_x.max(along_y).log2()
}

impl Wrap {
    /// Index `i` wrapped into [0, size).
    #[inline]
    fn index(self, i: i32, size: u32) -> u32 {
        match self {
            Wrap::Repeat => repeat(i, size),
            Wrap::ClampToEdge => i.clamp(0, size as i32 - 1) as u32,
        }
    }

    /// Indices `i` and `i + 1` wrapped into [0, size), with at most one division.
    #[inline]
    fn pair(self, i: i32, size: u32) -> (u32, u32) {
        match self {
            Wrap::Repeat => {
                let a = repeat(i, size);
                (a, if a + 1 == size { 0 } else { a + 1 })
            }
            Wrap::ClampToEdge => {
                let last = size as i32 - 1;
                (i.clamp(0, last) as u32, i.saturating_add(1).clamp(0, last) as u32)
            }
        }
    }
}

/// i modulo size in [0, size). Indices inside the texture, the usual case,
/// skip the integer division: with it every time, nearest and bilinear
/// samples on repeat took about 1.5× as long as on clamp-to-edge (512×512
/// texture, x86-64-v3); without it they cost the same.
#[inline]
fn repeat(i: i32, size: u32) -> u32 {
    // A negative i becomes a huge u32 and takes the slow path.
    if (i as u32) < size {
        i as u32
    } else if size.is_power_of_two() {
        // Two's complement: the low bits are i mod size, negatives included.
        // A floor repeating far from the origin lands here on every sample:
        // the textured-floor benchmark went from 98 to 86 ms per frame
        // (single thread, one run each) without the division.
        (i as u32) & (size - 1)
    } else {
        i.rem_euclid(size as i32) as u32
    }
}

/// The texel whose centre is nearest to `coord` along an axis of `size`
/// texels: ⌊coord·size⌋, wrapped; 0 for a non-finite coord·size.
#[inline]
fn nearest_index(coord: f32, size: u32, wrap: Wrap) -> u32 {
    let u = coord * size as f32;
    let i = if u.is_finite() { u.floor() as i32 } else { 0 };
    wrap.index(i, size)
}

/// The two texels whose centres bracket `coord` along an axis of `size`
/// texels, wrapped, and the weight f ∈ [0, 1] of the second. A non-finite
/// coord·size gives texel 0 with weight 0 on its neighbour.
#[inline]
fn linear_taps(coord: f32, size: u32, wrap: Wrap) -> (u32, u32, f32) {
    // Texel k's centre is at u = k once the half-texel offset is removed.
    let u = coord * size as f32 - 0.5;
    let (i, f) = if u.is_finite() {
        let below = u.floor();
        (below as i32, u - below)
    } else {
        (0, 0.0)
    };
    let (a, b) = wrap.pair(i, size);
    (a, b, f)
}

/// a + (b − a)·f: exactly `a` at f = 0 and wherever a = b.
#[inline]
fn lerp(a: Vec4, b: Vec4, f: f32) -> Vec4 {
    a + (b - a) * f
}

/// Up to three texels of a finer axis of `size` texels that coarse texel `k`
/// covers, with their area weights (unused taps have weight 0 and a valid
/// index). See the module documentation for the odd case.
fn footprint(k: u32, size: u32) -> [(u32, f32); 3] {
    if size == 1 {
        [(0, 1.0), (0, 0.0), (0, 0.0)]
    } else if size % 2 == 1 {
        let (n, total) = ((size / 2) as f32, size as f32);
        let k_f = k as f32;
        [(2 * k, (n - k_f) / total), (2 * k + 1, n / total), (2 * k + 2, (k_f + 1.0) / total)]
    } else {
        [(2 * k, 0.5), (2 * k + 1, 0.5), (2 * k + 1, 0.0)]
    }
}

/// Appends the level below `finer` (half its size) to `texels`, each texel
/// the area average of the finer texels it covers, and returns it.
fn push_coarser_level(texels: &mut Vec<Vec4>, finer: Level) -> Level {
    let (width, height) = half_size((finer.width, finer.height));
    let coarser = Level { offset: texels.len(), width, height };
    for y in 0..height {
        let rows = footprint(y, finer.height);
        for x in 0..width {
            let columns = footprint(x, finer.width);
            let mut sum = Vec4::ZERO;
            for (fy, wy) in rows {
                for (fx, wx) in columns {
                    sum += texels[finer.index(fx, fy)] * (wy * wx);
                }
            }
            texels.push(sum);
        }
    }
    coarser
}

mod x8;

#[cfg(test)]
mod tests;
