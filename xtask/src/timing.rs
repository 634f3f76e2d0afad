//! Timing renders for the report: frames in interleaved rounds.

use std::time::Instant;

use zline::pipeline::{Image, RenderOptions, Renderer};
use zline::scene::Scene;

/// The fastest and the median wall time in ms of `frames` renders of each
/// variant (after a warm-up), and the images. Frames are taken in rounds —
/// one frame of every variant per round — so the machine's drifting speed
/// spreads over all variants instead of favouring whichever ran in a fast
/// phase; the fastest frame is the least disturbed measure of the work.
pub(crate) fn time_interleaved(variants: &[Scene], frames: usize) -> (Vec<(f64, f64)>, Vec<Image>) {
    let options = RenderOptions::default();
    let mut renderers: Vec<(Renderer, Image)> =
        variants.iter().map(|_| (Renderer::default(), Image::empty())).collect();
    for ((renderer, image), scene) in renderers.iter_mut().zip(variants) {
        renderer.render_into(scene, &options, image);
    }
    let mut times = vec![Vec::with_capacity(frames); variants.len()];
    for _ in 0..frames.max(1) {
        for (k, ((renderer, image), scene)) in renderers.iter_mut().zip(variants).enumerate() {
            let start = Instant::now();
            renderer.render_into(scene, &options, image);
            times[k].push(start.elapsed().as_secs_f64() * 1e3);
        }
    }
    let summary = times
        .into_iter()
        .map(|mut t| {
            t.sort_by(f64::total_cmp);
            (t[0], t[t.len() / 2])
        })
        .collect();
    (summary, renderers.into_iter().map(|(_, image)| image).collect())
}
