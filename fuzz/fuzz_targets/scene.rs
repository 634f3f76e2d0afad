//! Scene TOML: the input is written as `s.toml` next to `m.obj` (a
//! cube), `m.glb` (the Box sample) and `t.png`, which `model = "m.obj"`
//! and the like can name; loaded with `load_scene_with_options` and, when
//! it loads, rendered with the size clamped to 32×32 and ssaa to 2. Must
//! never panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use zline_io::{load_scene_with_options, LoadOptions};

static TEXTURE: &[u8] = include_bytes!("../../assets/gltf/BoxTextured/glTF/CesiumLogoFlat.png");
static GLB: &[u8] = include_bytes!("../../assets/gltf/Box/glTF-Binary/Box.glb");
static OBJ: &[u8] = b"mtllib m.mtl\nv -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl a\nf 1/1 4/4 3/3 2/2\nf 5/1 6/2 7/3 8/4\nf 1/1 2/2 6/3 5/4\nf 2/1 3/2 7/3 6/4\nf 3/1 4/2 8/3 7/4\nf 4/1 1/2 5/3 8/4\n";
static MTL: &[u8] = b"newmtl a\nKd 0.8 0.5 0.2\nKs 0.5 0.5 0.5\nNs 20\nmap_Kd t.png\n";

fuzz_target!(|data: &[u8]| {
    zline_fuzz::write("t.png", TEXTURE);
    zline_fuzz::write("m.glb", GLB);
    zline_fuzz::write("m.obj", OBJ);
    zline_fuzz::write("m.mtl", MTL);
    let path = zline_fuzz::write("s.toml", data);
    if let Ok(mut scene) = load_scene_with_options(&path, LoadOptions::default()) {
        zline_fuzz::render_small(&mut scene, 32);
    }
});
