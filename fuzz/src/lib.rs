//! Helpers shared by the zline fuzz targets (see README.md).

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use zline_pipeline::{render, Image, RenderOptions};
use zline_scene::Scene;

/// A rayon pool of `threads` threads, built once per process.
pub fn pool(threads: usize) -> &'static rayon::ThreadPool {
    static ONE: OnceLock<rayon::ThreadPool> = OnceLock::new();
    static TWO: OnceLock<rayon::ThreadPool> = OnceLock::new();
    let cell = if threads <= 1 { &ONE } else { &TWO };
    cell.get_or_init(|| rayon::ThreadPoolBuilder::new().num_threads(threads.max(1)).build().unwrap())
}

/// A folder of this process's own for the files of one input, created
/// once and reused (files are overwritten for every input).
pub fn work_dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("zline-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    })
}

/// Writes `bytes` to `name` inside the work folder and returns its path.
pub fn write(name: &str, bytes: &[u8]) -> PathBuf {
    let path = work_dir().join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// Clamps the image size and samples to something small (a fuzz input
/// must stay fast) and renders with one thread.
pub fn render_small(scene: &mut Scene, side: u32) -> Image {
    let s = &mut scene.settings;
    s.width = s.width.clamp(1, side);
    s.height = s.height.clamp(1, side);
    s.ssaa = s.ssaa.clamp(1, 2);
    let options = RenderOptions { tile_size: 16 };
    let (image, _) = pool(1).install(|| render(scene, &options));
    assert_eq!(image.pixels.len(), (scene.settings.width * scene.settings.height) as usize);
    image
}
