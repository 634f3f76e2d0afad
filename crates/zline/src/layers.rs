//! Encoding the extra outputs of a render: the depth image as a 16-bit
//! greyscale PNG ([`encode_depth_png`]; `zline::save_depth_png` writes it).
//! The normals image and a transparent image are `Image`s, written by
//! `zline::save_image`; the overdraw count becomes one by
//! [`overdraw_heat_map`].

use zline_pipeline::{DepthImage, DepthRange, Image, Overdraw};
use zline_raster::TieRule;

/// The heat map's colours for 0, 1, …, 8 fragments a sample (8 and more
/// the last): black, dark blue, cyan, green, yellow, orange, red, magenta,
/// white.
pub const HEAT: [[u8; 3]; 9] = [
    [0, 0, 0],
    [30, 40, 150],
    [40, 200, 220],
    [60, 190, 70],
    [230, 220, 50],
    [240, 140, 30],
    [220, 40, 30],
    [200, 60, 200],
    [255, 255, 255],
];

/// The overdraw as a heat map: each pixel's fragments a sample (its count
/// over its samples, rounded to the nearest whole number) as [`HEAT`]'s
/// colour.
pub fn overdraw_heat_map(o: &Overdraw) -> Image {
    let samples = o.samples.max(1);
    let pixels = o
        .counts
        .iter()
        .map(|&c| {
            let level = ((c + samples / 2) / samples).min(HEAT.len() as u32 - 1) as usize;
            let [r, g, b] = HEAT[level];
            u32::from_le_bytes([r, g, b, 255])
        })
        .collect();
    Image { width: o.width, height: o.height, pixels, transparent: false }
}

/// The depth image as grey pixels: the 16-bit PNG's values
/// ([`DepthImage::to_gray16`]: nearest drawn 65535, farthest 1, nothing 0)
/// rounded to 8 bits, so `--depth-image`'s picture.
pub fn depth_as_image(depth: &DepthImage) -> Image {
    let (grey, _) = depth.to_gray16();
    let pixels = grey
        .iter()
        .map(|&v| {
            let g = ((u32::from(v) * 255 + 32767) / 65535) as u8;
            u32::from_le_bytes([g, g, g, 255])
        })
        .collect();
    Image { width: depth.width, height: depth.height, pixels, transparent: false }
}

/// A line on the overdraw: its mean and largest fragments a pixel, what
/// the rule shows, and (given the same frame's count under the top-left
/// rule) how many fragments the rule changed.
pub fn describe_overdraw(o: &Overdraw, rule: TieRule, top_left: Option<&Overdraw>) -> String {
    let drawn = o.counts.iter().filter(|&&c| c > 0).count().max(1);
    let mean = o.total() as f64 / o.samples.max(1) as f64 / drawn as f64;
    let max = o.counts.iter().max().copied().unwrap_or(0) as f64 / o.samples.max(1) as f64;
    let what = match rule {
        TieRule::TopLeft => "the top-left rule: each sample of a shared edge drawn once",
        TieRule::Closed => {
            "closed triangles, no top-left rule: samples on shared edges drawn twice (the mesh's edges light up a step brighter)"
        }
        TieRule::Open => {
            "open triangles, no top-left rule: samples on shared edges drawn by neither triangle (black cracks along the mesh's edges)"
        }
    };
    let changed = top_left.filter(|_| rule != TieRule::TopLeft).map_or(String::new(), |t| {
        let (gained, lost) = o.counts.iter().zip(&t.counts).fold((0u64, 0u64), |(g, l), (&a, &b)| {
            (g + u64::from(a.saturating_sub(b)), l + u64::from(b.saturating_sub(a)))
        });
        format!("; {gained} fragments more and {lost} fewer than under the top-left rule (samples exactly on an edge)")
    });
    format!(
        "overdraw under {what}; {mean:.2} fragments a drawn pixel on average, at most {max}{changed}; colours: black 0, dark blue 1, cyan 2, green 3, yellow 4, orange 5, red 6, magenta 7, white 8 or more"
    )
}

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
