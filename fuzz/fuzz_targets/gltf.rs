//! glTF / GLB: the input is written as `m.glb` and as `m.gltf` (next to a
//! small `t.png` and a `b.bin` of 4 KiB that URIs can name), each loaded
//! with `load_gltf_with_options` and, when it loads, framed and rendered
//! at 32×32. Must never panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use zline_io::{load_gltf_with_options, scene_for_gltf, LoadOptions};
use zline_scene::RenderSettings;

static TEXTURE: &[u8] = include_bytes!("../../assets/gltf/BoxTextured/glTF/CesiumLogoFlat.png");
static BUFFER: &[u8] = include_bytes!("../../assets/gltf/BoxTextured/glTF/BoxTextured0.bin");

fuzz_target!(|data: &[u8]| {
    zline_fuzz::write("t.png", TEXTURE);
    zline_fuzz::write("b.bin", BUFFER);
    for name in ["m.glb", "m.gltf"] {
        let path = zline_fuzz::write(name, data);
        if let Ok((gltf, _warnings)) = load_gltf_with_options(&path, LoadOptions::default()) {
            let mut scene = scene_for_gltf(gltf, RenderSettings::default());
            zline_fuzz::render_small(&mut scene, 32);
        }
    }
});
