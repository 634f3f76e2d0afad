//! `zline turntable`: the frames of a GIF, an animated PNG and a folder
//! are the same turn, frame k the render command's `--azimuth 360·k/N`.

use std::path::Path;

use image::AnimationDecoder;

use crate::{check_clean_error, repo, zline};

const SIZE: (u32, u32) = (160, 120);

fn turntable(out: &Path, extra: &[&str]) -> std::process::Output {
    let model = repo().join("assets/obj/suzanne/suzanne.obj");
    let mut args =
        vec!["turntable", model.to_str().unwrap(), "-o", out.to_str().unwrap(), "--size", "160x120"];
    args.extend_from_slice(extra);
    let out = zline(&args);
    assert!(out.status.success(), "zline failed:\n{}", String::from_utf8_lossy(&out.stderr));
    out
}

/// An animation's frames as RGB images.
fn frames(decoder: impl AnimationDecoder<'static>) -> Vec<image::RgbImage> {
    let frames = decoder.into_frames().collect_frames().expect("frames decode");
    frames.into_iter().map(|f| image::DynamicImage::ImageRgba8(f.into_buffer()).to_rgb8()).collect()
}

fn open_file(path: &Path) -> std::io::BufReader<std::fs::File> {
    std::io::BufReader::new(std::fs::File::open(path).unwrap())
}

/// The mean absolute difference per channel, in 8-bit steps.
fn mean_difference(a: &image::RgbImage, b: &image::RgbImage) -> f64 {
    let sum: u64 = a.as_raw().iter().zip(b.as_raw()).map(|(x, y)| u64::from(x.abs_diff(*y))).sum();
    sum as f64 / a.as_raw().len() as f64
}

#[test]
fn a_gif_an_apng_and_a_folder_hold_the_same_four_frames() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // The folder: frame k is `zline render --azimuth 90·k`, byte for byte.
    turntable(&d.join("frames/"), &["--frames", "4"]);
    let model = repo().join("assets/obj/suzanne/suzanne.obj");
    let mut folder = Vec::new();
    for k in 0..4 {
        let frame = d.join(format!("frames/frame-{k:04}.png"));
        let single = d.join(format!("single-{k}.png"));
        let azimuth = format!("{}", 90 * k);
        let mut args =
            vec!["render", model.to_str().unwrap(), "-o", single.to_str().unwrap(), "--size", "160x120"];
        if k > 0 {
            args.extend_from_slice(&["--azimuth", &azimuth]);
        }
        assert!(zline(&args).status.success());
        assert_eq!(std::fs::read(&frame).unwrap(), std::fs::read(&single).unwrap(), "frame {k}");
        folder.push(image::open(&frame).unwrap().to_rgb8());
    }
    assert_eq!(std::fs::read_dir(d.join("frames")).unwrap().count(), 4);
    for (i, a) in folder.iter().enumerate() {
        assert_eq!(a.dimensions(), SIZE);
        for b in &folder[i + 1..] {
            assert!(mean_difference(a, b) > 1.0, "two frames are (nearly) the same");
        }
    }
    // The animated PNG: the same pixels exactly.
    turntable(&d.join("turn.png"), &["--frames", "4", "--fps", "10"]);
    let apng = image::codecs::png::PngDecoder::new(open_file(&d.join("turn.png"))).unwrap().apng().unwrap();
    let apng = apng.into_frames().collect_frames().unwrap();
    assert!(apng.iter().all(|f| f.delay().numer_denom_ms() == (100, 1)), "--fps 10: 100 ms a frame");
    let apng: Vec<image::RgbImage> =
        apng.into_iter().map(|f| image::DynamicImage::ImageRgba8(f.into_buffer()).to_rgb8()).collect();
    assert_eq!(apng, folder);
    // The GIF: four frames of the size, each within the palette's error of
    // the PNG frame (256 colours a frame).
    turntable(&d.join("turn.gif"), &["--frames", "4"]);
    // Looping forever (the NETSCAPE2.0 extension with a count of 0), 12
    // frames a second stored as 8/100 s.
    let bytes = std::fs::read(d.join("turn.gif")).unwrap();
    let netscape = bytes.windows(11).position(|w| w == b"NETSCAPE2.0").expect("a loop extension");
    assert_eq!(bytes[netscape + 11..netscape + 15], [3, 1, 0, 0], "loop count 0: forever");
    let decoded = image::codecs::gif::GifDecoder::new(open_file(&d.join("turn.gif"))).unwrap();
    let delays: Vec<(u32, u32)> =
        decoded.into_frames().map(|f| f.unwrap().delay().numer_denom_ms()).collect();
    assert_eq!(delays, [(80, 1); 4]);
    let gif = frames(image::codecs::gif::GifDecoder::new(open_file(&d.join("turn.gif"))).unwrap());
    assert_eq!(gif.len(), 4);
    for (k, (g, p)) in gif.iter().zip(&folder).enumerate() {
        assert_eq!(g.dimensions(), SIZE);
        let diff = mean_difference(g, p);
        assert!(diff < 3.0, "GIF frame {k} differs from the PNG frame by {diff} on average");
    }
    for (i, a) in gif.iter().enumerate() {
        for b in &gif[i + 1..] {
            assert_ne!(a, b, "two GIF frames are the same");
        }
    }
}

#[test]
fn a_frame_range_renders_part_of_the_turn_with_the_turns_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let (all, part) = (dir.path().join("all"), dir.path().join("part"));
    std::fs::create_dir(&all).unwrap();
    turntable(&all, &["--frames", "8", "--quiet"]);
    turntable(&dir.path().join("part/"), &["--frames", "8", "--frame-range", "5..7"]);
    let mut names: Vec<String> =
        std::fs::read_dir(&part).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    names.sort();
    assert_eq!(names, ["frame-0005.png", "frame-0006.png"]);
    for name in names {
        assert_eq!(
            std::fs::read(all.join(&name)).unwrap(),
            std::fs::read(part.join(&name)).unwrap(),
            "{name}"
        );
    }
}

#[test]
fn bad_turntable_requests_fail_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let model = repo().join("assets/obj/suzanne/suzanne.obj");
    let run = |out: &str, extra: &[&str]| {
        let out = dir.path().join(out);
        let mut args = vec!["turntable", model.to_str().unwrap(), "-o", out.to_str().unwrap()];
        args.extend_from_slice(extra);
        zline(&args)
    };
    check_clean_error(&run("a.jpg", &[]), &["a.jpg", ".gif or .png"]);
    check_clean_error(
        &run("f/", &["--frames", "4", "--frame-range", "2..5"]),
        &["--frame-range", "4 frames"],
    );
    check_clean_error(&run("nowhere/a.gif", &[]), &["a.gif"]);
    for bad in [&["--frames", "0"][..], &["--frame-range", "3..3"], &["--frame-range", "x"], &["--fps", "0"]]
    {
        let out = run("a.gif", bad);
        assert_eq!(out.status.code(), Some(2), "{bad:?}: {}", String::from_utf8_lossy(&out.stderr));
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "files left behind");
}
