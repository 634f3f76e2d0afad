//! STL and PLY input: the bunny PLY of `assets/` and an STL written from it
//! render from the command line, and load as the same mesh.

use std::io::Write as _;

use crate::{check_png, repo, zline};

/// Writes the triangles of `mesh` as a binary STL.
fn write_stl(path: &std::path::Path, mesh: &zline::scene::Mesh) {
    let mut bytes = vec![0u8; 80];
    bytes.extend((mesh.triangles.len() as u32).to_le_bytes());
    for t in &mesh.triangles {
        bytes.extend([0u8; 12]);
        for &i in t {
            mesh.positions[i as usize].to_array().iter().for_each(|c| bytes.extend(c.to_le_bytes()));
        }
        bytes.extend([0u8; 2]);
    }
    std::fs::File::create(path).unwrap().write_all(&bytes).unwrap();
}

#[test]
fn the_bunny_renders_from_ply_and_from_stl() {
    let dir = tempfile::tempdir().unwrap();
    let ply = repo().join("assets/ply/bunny_lowres.ply");
    let meshes = zline::io::load_ply(&ply).unwrap();
    assert_eq!(meshes.len(), 1);
    assert_eq!((meshes[0].triangles.len(), meshes[0].positions.len()), (6598, 3301));
    let stl = dir.path().join("bunny.stl");
    write_stl(&stl, &meshes[0]);
    let from_stl = zline::io::load_stl(&stl).unwrap();
    assert_eq!(from_stl[0].triangles.len(), 6598);
    // STL repeats corners per triangle; welding them gives the PLY's
    // vertices back (the remesh has no duplicate positions).
    assert_eq!(from_stl[0].positions.len(), 3301);
    let mut images = Vec::new();
    for input in [&ply, &stl] {
        let png = dir.path().join(format!("{}.png", input.extension().unwrap().to_str().unwrap()));
        let out = zline(&["render", input.to_str().unwrap(), "-o", png.to_str().unwrap(), "--size", "96x72"]);
        let img = check_png(&out, &png, (96, 72));
        let background = *img.get_pixel(0, 0);
        let covered = img.pixels().filter(|p| **p != background).count();
        assert!(covered > 96 * 72 / 8, "{}: the bunny covers only {covered} pixels", input.display());
        images.push(img);
    }
    // Same triangles, same framing: the same picture, up to the order in
    // which each vertex's face normals are summed.
    let far = images[0]
        .pixels()
        .zip(images[1].pixels())
        .filter(|(a, b)| a.0.iter().zip(b.0.iter()).any(|(x, y)| x.abs_diff(*y) > 1));
    assert_eq!(far.count(), 0, "PLY and STL images differ by more than one step");
}

#[test]
fn a_broken_ply_is_a_clean_error() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.ply");
    std::fs::write(&bad, "ply\nformat ascii 1.0\nelement vertex 99999999\nproperty float x\nend_header\n1\n")
        .unwrap();
    let out = zline(&["render", bad.to_str().unwrap(), "-o", dir.path().join("x.png").to_str().unwrap()]);
    crate::check_clean_error(&out, &["bad.ply", "element 'vertex' claims 99999999 entries"]);
}

/// `zline info` reads every model of `assets/` and the scene files of
/// `tests/scenes/`, as text and as JSON that parses and agrees with the
/// text.
#[test]
fn info_describes_every_repository_asset() {
    let mut inputs = vec![
        "assets/obj/suzanne/suzanne.obj",
        "assets/obj/spot/spot.obj",
        "assets/ply/bunny_lowres.ply",
        "assets/gltf/Box/glTF-Binary/Box.glb",
        "assets/gltf/BoxTextured/glTF/BoxTextured.gltf",
        "assets/gltf/TextureCoordinateTest/glTF/TextureCoordinateTest.gltf",
        "assets/gltf/VertexColorTest/glTF-Binary/VertexColorTest.glb",
    ];
    inputs.push("tests/scenes/shadows_area.toml");
    for input in inputs {
        let path = repo().join(input);
        let text = zline(&["info", path.to_str().unwrap()]);
        assert!(text.status.success(), "{input}: {}", String::from_utf8_lossy(&text.stderr));
        let text = String::from_utf8(text.stdout).unwrap();
        let json = zline(&["info", "--json", path.to_str().unwrap()]);
        assert!(json.status.success(), "{input}");
        let json: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
        let triangles = json["triangles"].as_u64().unwrap();
        assert!(triangles > 0, "{input}");
        assert!(text.contains(&format!("  triangles  {triangles}\n")), "{input}: {text}");
    }
    let spot = zline(&["info", repo().join("assets/obj/spot/spot.obj").to_str().unwrap()]);
    let spot = String::from_utf8(spot.stdout).unwrap();
    assert!(spot.contains("triangles  5856") && spot.contains("1024 × 1024"), "{spot}");
}

#[test]
fn info_on_a_missing_file_is_a_clean_error() {
    let out = zline(&["info", "no/such/model.ply"]);
    crate::check_clean_error(&out, &["no/such/model.ply"]);
}

/// `-o out.jpg` writes a JPEG of the same picture as the PNG (lossy: the
/// mean difference stays under 3 steps); another extension is refused
/// before rendering.
#[test]
fn the_output_format_follows_the_extension() {
    let dir = tempfile::tempdir().unwrap();
    let model = repo().join("assets/obj/spot/spot.obj");
    let (png, jpg) = (dir.path().join("spot.png"), dir.path().join("spot.JPG"));
    for out in [&png, &jpg] {
        let o = zline(&["render", model.to_str().unwrap(), "-o", out.to_str().unwrap(), "--size", "96x72"]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    assert_eq!(image::ImageFormat::from_path(&jpg).unwrap(), image::ImageFormat::Jpeg);
    let bytes = std::fs::read(&jpg).unwrap();
    assert_eq!(&bytes[..3], &[0xFF, 0xD8, 0xFF], "a JPEG file");
    let a = image::open(&png).unwrap().to_rgb8();
    let b = image::load_from_memory(&bytes).unwrap().to_rgb8();
    assert_eq!(a.dimensions(), b.dimensions());
    let total: u64 = a.as_raw().iter().zip(b.as_raw()).map(|(x, y)| u64::from(x.abs_diff(*y))).sum();
    let mean = total as f64 / a.as_raw().len() as f64;
    assert!(mean < 3.0, "JPEG differs from the PNG by {mean} steps on average");
    let out = zline(&["render", model.to_str().unwrap(), "-o", dir.path().join("x.bmp").to_str().unwrap()]);
    crate::check_clean_error(&out, &["x.bmp", ".png, .jpg or .jpeg"]);
}

/// Runs `zline ARGS` with `stdin` as its standard input, in folder `dir`.
fn zline_with_stdin(args: &[&str], stdin: &[u8], dir: &std::path::Path) -> std::process::Output {
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_zline"))
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // A loader that fails early may close its input before reading all of it.
    let _ = child.stdin.take().unwrap().write_all(stdin);
    child.wait_with_output().unwrap()
}

/// `-` reads the model from standard input, whatever its format, and the
/// image is byte for byte the one rendered from the file.
#[test]
fn standard_input_renders_as_the_file_does() {
    let dir = tempfile::tempdir().unwrap();
    let ply = repo().join("assets/ply/bunny_lowres.ply");
    let stl = dir.path().join("bunny.stl");
    write_stl(&stl, &zline::io::load_ply(&ply).unwrap()[0]);
    let glb = repo().join("assets/gltf/Box/glTF-Binary/Box.glb");
    let spot = repo().join("assets/obj/spot/spot.obj");
    for input in [&ply, &stl, &glb, &spot] {
        let (from_file, from_stdin) = (dir.path().join("file.png"), dir.path().join("stdin.png"));
        let size = ["--size", "64x48"];
        let out = zline(
            &[&["render", input.to_str().unwrap(), "-o", from_file.to_str().unwrap()], &size[..]].concat(),
        );
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        // Files the input names are looked up in the current folder: the model's.
        let folder = input.parent().unwrap();
        let args = [&["render", "-", "-o", from_stdin.to_str().unwrap()], &size[..]].concat();
        let out = zline_with_stdin(&args, &std::fs::read(input).unwrap(), folder);
        assert!(out.status.success(), "{}: {}", input.display(), String::from_utf8_lossy(&out.stderr));
        assert_eq!(
            std::fs::read(&from_file).unwrap(),
            std::fs::read(&from_stdin).unwrap(),
            "{}: stdin and file renders differ",
            input.display()
        );
    }
    let out = zline_with_stdin(&["info", "-"], &std::fs::read(&ply).unwrap(), dir.path());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success() && text.contains("<stdin> (PLY)") && text.contains("6598"), "{text}");
}

#[test]
fn unreadable_standard_input_is_a_clean_error() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("x.png");
    for (stdin, why) in [(&b""[..], "empty input"), (b"hello there\n", "could not tell the format")] {
        let out = zline_with_stdin(&["render", "-", "-o", png.to_str().unwrap()], stdin, dir.path());
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(err.contains("<stdin>") && err.contains(why) && !err.contains("panicked"), "{err}");
    }
    assert!(!png.exists());
}
