//! Encoding the extra outputs of a render: the depth image as a 16-bit
//! greyscale PNG ([`encode_depth_png`]; `zline::save_depth_png` writes it).
//! The normals image and a transparent image are `Image`s, written by
//! `zline::save_image`.

use zline_pipeline::{DepthImage, DepthRange};

/// The keyword of the depth PNG's tEXt chunk that states its mapping.
pub const DEPTH_TEXT_KEYWORD: &str = "zline:depth";

/// How a depth image's grey values map to eye-space depth, as printed and
/// as stored in the PNG's tEXt chunk: `65535 = near NEAR, 1 = far FAR
/// (eye-plane distance, world units, linear); 0 = nothing drawn`.
pub fn describe_depth_range(range: Option<DepthRange>) -> String {
    match range {
        Some(r) => format!(
            "65535 = near {}, 1 = far {} (eye-plane distance, world units, linear); 0 = nothing drawn",
            r.near, r.far
        ),
        None => "nothing drawn: every pixel 0".into(),
    }
}

/// Encodes `depth` as a 16-bit greyscale PNG: linear in eye-space depth,
/// the nearest drawn pixel 65535, the farthest drawn 1, nothing drawn 0
/// ([`DepthImage::to_gray16`]), with the mapping in a tEXt chunk
/// ([`DEPTH_TEXT_KEYWORD`]). Returns the file's bytes and the mapping.
pub fn encode_depth_png(depth: &DepthImage) -> std::io::Result<(Vec<u8>, Option<DepthRange>)> {
    let (grey, range) = depth.to_gray16();
    let bytes: Vec<u8> = grey.iter().flat_map(|v| v.to_be_bytes()).collect();
    let mut png = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut png, depth.width, depth.height);
        encoder.set_color(png::ColorType::Grayscale);
        encoder.set_depth(png::BitDepth::Sixteen);
        encoder.set_compression(png::Compression::Fast);
        encoder
            .add_text_chunk(DEPTH_TEXT_KEYWORD.into(), describe_depth_range(range))
            .map_err(std::io::Error::other)?;
        let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
        writer.write_image_data(&bytes).map_err(std::io::Error::other)?;
        writer.finish().map_err(std::io::Error::other)?;
    }
    Ok((png, range))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn depth_png_is_16_bit_grey_with_its_mapping() {
        let depth = DepthImage { width: 3, height: 1, depth: vec![2.0, f32::NAN, 4.0] };
        let (bytes, range) = encode_depth_png(&depth).unwrap();
        let range = range.unwrap();
        assert_eq!((range.near, range.far), (2.0, 4.0));
        let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        let mut reader = decoder.read_info().unwrap();
        let info = reader.info();
        assert_eq!((info.color_type, info.bit_depth), (png::ColorType::Grayscale, png::BitDepth::Sixteen));
        let text = info.uncompressed_latin1_text.iter().find(|t| t.keyword == DEPTH_TEXT_KEYWORD).unwrap();
        assert!(text.text.contains("near 2") && text.text.contains("far 4"), "{}", text.text);
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        reader.next_frame(&mut buf).unwrap();
        let values: Vec<u16> = buf.chunks(2).map(|b| u16::from_be_bytes([b[0], b[1]])).collect();
        assert_eq!(values, [65535, 0, 1]);
    }
}
