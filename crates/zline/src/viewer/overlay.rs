//! From a rendered frame to the window's pixels: nearest-neighbour
//! upscaling of a preview, and lines of text drawn over it with the 8×8
//! bitmap font of `font8x8`.
//!
//! Window pixels are `0x00RRGGBB` words (the X server's 24-bit layout);
//! zline's [`Image`] stores R, G, B in its words' low bytes first.

use font8x8::legacy::BASIC_LEGACY;
use zline_pipeline::Image;

/// Text height in window pixels, a line's advance included.
pub const LINE_HEIGHT: usize = 10;
/// Left and top margin of the text.
const MARGIN: usize = 4;

/// An image pixel as a window pixel.
pub fn window_pixel(p: u32) -> u32 {
    let [r, g, b, _] = p.to_le_bytes();
    (u32::from(r) << 16) | (u32::from(g) << 8) | u32::from(b)
}

/// Fills `buffer` (resized to `width` × `height`) with `image`, each image
/// pixel covering `block` × `block` window pixels from the top-left corner;
/// window pixels past the image (a rounded-up edge) take the image's last
/// row or column.
pub fn upscale(image: &Image, block: u32, width: usize, height: usize, buffer: &mut Vec<u32>) {
    buffer.clear();
    buffer.resize(width * height, 0);
    if image.width == 0 || image.height == 0 || block == 0 {
        return;
    }
    let (iw, ih, b) = (image.width as usize, image.height as usize, block as usize);
    for (y, row) in buffer.chunks_exact_mut(width).enumerate() {
        let source = &image.pixels[(y / b).min(ih - 1) * iw..][..iw];
        for (x, out) in row.iter_mut().enumerate() {
            *out = window_pixel(source[(x / b).min(iw - 1)]);
        }
    }
}

/// Draws `lines` of text in the top-left corner of `buffer` (`width`
/// pixels wide): white glyphs on a darkened band, so that they read on any
/// frame. Characters outside ASCII draw as `?`; text past the buffer's
/// edges is cut.
pub fn draw_text(buffer: &mut [u32], width: usize, lines: &[&str]) {
    let height = buffer.len() / width.max(1);
    let columns = lines.iter().map(|l| l.chars().count()).max().unwrap_or(0);
    let band_w = (2 * MARGIN + 8 * columns).min(width);
    let band_h = (2 * MARGIN + LINE_HEIGHT * lines.len()).min(height);
    for row in buffer.chunks_exact_mut(width.max(1)).take(band_h) {
        for p in &mut row[..band_w] {
            // Halve each channel.
            *p = (*p >> 1) & 0x007f_7f7f;
        }
    }
    for (i, line) in lines.iter().enumerate() {
        for (j, c) in line.chars().enumerate() {
            let glyph = BASIC_LEGACY[if c.is_ascii() { c as usize } else { '?' as usize }];
            draw_glyph(buffer, width, height, MARGIN + 8 * j, MARGIN + LINE_HEIGHT * i + 1, glyph);
        }
    }
}

/// One 8×8 glyph, bit k of row r set for pixel (x + k, y + r).
fn draw_glyph(buffer: &mut [u32], width: usize, height: usize, x: usize, y: usize, glyph: [u8; 8]) {
    for (r, bits) in glyph.iter().enumerate() {
        let yy = y + r;
        if yy >= height {
            return;
        }
        for k in 0..8 {
            let xx = x + k;
            if bits >> k & 1 == 1 && xx < width {
                buffer[yy * width + xx] = 0x00ff_ffff;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_preview_is_scaled_up_by_repeating_pixels() {
        // 2×2 image, block 3, into a 5×4 window: the last column and row
        // are cut.
        let image = Image {
            width: 2,
            height: 2,
            pixels: vec![0x0000_00ff, 0x0000_ff00, 0x00ff_0000, 0x0001_0203],
            transparent: false,
        };
        let mut buffer = Vec::new();
        upscale(&image, 3, 5, 4, &mut buffer);
        let (red, green, blue) = (0x00ff_0000, 0x0000_ff00, 0x0000_00ff);
        let row0 = [red, red, red, green, green];
        let row3 = [blue, blue, blue, 0x0003_0201, 0x0003_0201];
        assert_eq!(&buffer[0..5], &row0);
        assert_eq!(&buffer[5..10], &row0);
        assert_eq!(&buffer[10..15], &row0);
        assert_eq!(&buffer[15..20], &row3);
    }

    #[test]
    fn text_is_white_on_a_darkened_band() {
        let (w, h) = (40, 20);
        let mut buffer = vec![0x0080_8080; w * h];
        draw_text(&mut buffer, w, &["1"]);
        // '1' in font8x8: row 1 of the glyph is 0x0E (columns 1..=3).
        let y = MARGIN + 1 + 1;
        let white: Vec<usize> = (0..w).filter(|&x| buffer[y * w + x] == 0x00ff_ffff).collect();
        assert_eq!(white, vec![MARGIN + 1, MARGIN + 2, MARGIN + 3]);
        assert_eq!(buffer[0], 0x0040_4040, "the band is darkened");
        assert_eq!(buffer[w - 1], 0x0080_8080, "past the band is untouched");
    }
}
