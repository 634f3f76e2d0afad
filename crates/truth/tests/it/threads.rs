//! The same image, bit for bit, on one thread and on two.

use zline_scene::{RenderSettings, Scene};
use zline_scenes::demo_scene;
use zline_truth::{render_truth_with, TruthImage, TruthOptions};

fn on_threads(threads: usize, scene: &Scene, options: &TruthOptions) -> TruthImage {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a thread pool");
    pool.install(|| render_truth_with(scene, options))
}

#[test]
fn one_and_two_threads_give_identical_images() {
    // The demo has every shading mode, textures, fog and transparency.
    let mut scene = demo_scene();
    scene.settings = RenderSettings { width: 96, height: 64, ssaa: 2, ..scene.settings };
    for diagnostics in [false, true] {
        let options = TruthOptions { diagnostics, ..TruthOptions::default() };
        let (one, two) = (on_threads(1, &scene, &options), on_threads(2, &scene, &options));
        assert!(one == two, "images differ between 1 and 2 threads (diagnostics {diagnostics})");
    }
}
