//! Reading an X window dump (XWD, version 7): the format in which Xvfb's
//! `-fbdir` exposes its screen, so that tests can see what a window
//! really showed.
//!
//! The file is a header of 25 big-endian 32-bit fields (`XWDFileHeader` in
//! X11/XWDFile.h), the window name, `ncolors` colour map entries of 12
//! bytes, then the pixels: `height` rows of `bytes_per_line` bytes. Only
//! what Xvfb writes for a TrueColor screen of depth 24 is read: ZPixmap,
//! 24 or 32 bits per pixel, channels given by the red, green and blue
//! masks, in the file's byte order.

use zline_pipeline::Image;

/// `XWD_FILE_VERSION`.
const VERSION: u32 = 7;
/// `ZPixmap`.
const Z_PIXMAP: u32 = 2;
/// The header's fields.
const FIELDS: usize = 25;

/// Reads an XWD file's pixels as an [`Image`]; `Err` says what in the
/// file is not what Xvfb writes.
pub fn read(bytes: &[u8]) -> Result<Image, String> {
    let field = |i: usize| -> Result<u32, String> {
        bytes
            .get(4 * i..4 * i + 4)
            .map(|b| u32::from_be_bytes([b[0], b[1], b[2], b[3]]))
            .ok_or_else(|| format!("the header ends at byte {} of {}", bytes.len(), 4 * FIELDS))
    };
    let header_size = field(0)? as usize;
    let (version, format, width, height) = (field(1)?, field(2)?, field(4)?, field(5)?);
    let (byte_order, bits_per_pixel, bytes_per_line) = (field(7)?, field(11)?, field(12)? as usize);
    let masks = [field(14)?, field(15)?, field(16)?];
    let ncolors = field(19)? as usize;
    if version != VERSION {
        return Err(format!("version {version}, expected {VERSION}"));
    }
    if format != Z_PIXMAP {
        return Err(format!("pixmap format {format}, expected ZPixmap ({Z_PIXMAP})"));
    }
    if bits_per_pixel != 24 && bits_per_pixel != 32 {
        return Err(format!("{bits_per_pixel} bits per pixel, expected 24 or 32"));
    }
    if masks.contains(&0) {
        return Err(format!("colour masks {masks:08x?}: not a TrueColor screen"));
    }
    let step = bits_per_pixel as usize / 8;
    let start =
        header_size.checked_add(ncolors.checked_mul(12).ok_or("too many colours")?).ok_or("bad header")?;
    let (w, h) = (width as usize, height as usize);
    if bytes_per_line < w.saturating_mul(step) {
        return Err(format!("{bytes_per_line} bytes per line hold fewer than {w} pixels"));
    }
    let end = bytes_per_line.checked_mul(h).and_then(|n| n.checked_add(start));
    if end.is_none_or(|end| end > bytes.len()) {
        return Err(format!("{w}x{h} pixels need more than the file's {} bytes", bytes.len()));
    }
    let mut pixels = Vec::with_capacity(w * h);
    for row in bytes[start..].chunks_exact(bytes_per_line).take(h) {
        for p in row[..w * step].chunks_exact(step) {
            let mut word = [0u8; 4];
            word[..step].copy_from_slice(p);
            // byte_order 0 is LSBFirst.
            let value = if byte_order == 0 {
                u32::from_le_bytes(word)
            } else {
                u32::from_be_bytes(word) >> (32 - bits_per_pixel)
            };
            let [r, g, b] = masks.map(|m| channel(value, m));
            pixels.push(u32::from_le_bytes([r, g, b, 0]));
        }
    }
    Ok(Image { width, height, pixels, transparent: false })
}

/// The channel under `mask`, scaled to 8 bits.
fn channel(value: u32, mask: u32) -> u8 {
    let shift = mask.trailing_zeros();
    let max = mask >> shift;
    let v = (value & mask) >> shift;
    if max == 0xff {
        v as u8
    } else {
        (u64::from(v) * 255 / u64::from(max)) as u8
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An XWD file as Xvfb writes it: 32 bits per pixel, LSBFirst, an
    /// 8-byte name and 2 colour entries; rows padded to `pad` pixels.
    fn xwd(width: u32, height: u32, pad: u32, pixel: impl Fn(u32, u32) -> u32) -> Vec<u8> {
        let name = b"Xvfb\0\0\0\0";
        let header_size = 4 * FIELDS as u32 + name.len() as u32;
        let mut fields = [0u32; FIELDS];
        fields[0] = header_size;
        fields[1] = VERSION;
        fields[2] = Z_PIXMAP;
        fields[3] = 24;
        fields[4] = width;
        fields[5] = height;
        fields[11] = 32;
        fields[12] = 4 * pad;
        fields[14] = 0x00ff_0000;
        fields[15] = 0x0000_ff00;
        fields[16] = 0x0000_00ff;
        fields[19] = 2;
        let mut bytes: Vec<u8> = fields.iter().flat_map(|f| f.to_be_bytes()).collect();
        bytes.extend_from_slice(name);
        bytes.extend(std::iter::repeat_n(0xee, 24));
        for y in 0..height {
            for x in 0..pad {
                bytes.extend_from_slice(&pixel(x, y).to_le_bytes());
            }
        }
        bytes
    }

    #[test]
    fn pixels_are_read_through_the_masks() {
        let bytes = xwd(3, 2, 4, |x, y| 0x0010_2030 + x * 0x0001_0000 + y);
        let image = read(&bytes).unwrap();
        assert_eq!((image.width, image.height), (3, 2));
        assert_eq!(image.pixel(0, 0), [0x10, 0x20, 0x30]);
        assert_eq!(image.pixel(2, 0), [0x12, 0x20, 0x30]);
        assert_eq!(image.pixel(1, 1), [0x11, 0x20, 0x31]);
    }

    #[test]
    fn a_short_or_foreign_file_is_an_error() {
        let bytes = xwd(3, 2, 4, |_, _| 0);
        assert!(read(&bytes[..50]).unwrap_err().contains("header ends"));
        assert!(read(&bytes[..bytes.len() - 1]).unwrap_err().contains("need more"));
        let mut other = bytes.clone();
        other[11] = 1;
        assert!(read(&other).unwrap_err().contains("pixmap format 1"));
        let mut narrow = bytes;
        narrow[51] = 8;
        assert!(read(&narrow).unwrap_err().contains("fewer than 3 pixels"));
    }
}
