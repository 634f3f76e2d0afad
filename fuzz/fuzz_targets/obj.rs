//! OBJ + MTL: the input up to its first 0xFF byte is `m.obj`, the rest
//! `m.mtl` (0xFF never occurs in UTF-8 text); `t.png` is a small texture
//! that `map_Kd t.png` can name. Loaded with `load_obj_with_options` and,
//! when it loads, framed and rendered at 32×32. Must never panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use zline_io::{load_obj_with_options, scene_for_model, LoadOptions};
use zline_scene::RenderSettings;

static TEXTURE: &[u8] = include_bytes!("../../assets/gltf/BoxTextured/glTF/CesiumLogoFlat.png");

fuzz_target!(|data: &[u8]| {
    let (obj, mtl) = match data.iter().position(|&b| b == 0xFF) {
        Some(i) => (&data[..i], &data[i + 1..]),
        None => (data, &[][..]),
    };
    zline_fuzz::write("t.png", TEXTURE);
    zline_fuzz::write("m.mtl", mtl);
    let path = zline_fuzz::write("m.obj", obj);
    if let Ok((meshes, _warnings)) = load_obj_with_options(&path, LoadOptions::default()) {
        let mut scene = scene_for_model(meshes, RenderSettings::default());
        zline_fuzz::render_small(&mut scene, 32);
    }
});
