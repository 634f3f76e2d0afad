//! A steady stream of frames allocates nothing: after a first frame has
//! sized the renderer's buffers, rendering the same scene again makes no
//! heap allocation, on one thread or several, with or without
//! supersampling, with planar shadows or shadow maps, with lines, and with
//! the painter's algorithm. This test binary's global allocator counts every
//! allocation and reallocation, on every thread, while frames render.

use std::alloc::System;

use stats_alloc::{Region, StatsAlloc, INSTRUMENTED_SYSTEM};
use zline_pipeline::{Image, RenderOptions, Renderer};
use zline_scene::{Scene, ShadowMode, Visibility, WireframeMode};
use zline_scenes::{demo_scene, room_scene};

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

/// Allocations made by `frames` frames after a first one, in a pool of
/// `threads`.
fn allocations_after_first_frame(scene: &Scene, threads: usize, frames: usize) -> usize {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    let (mut renderer, mut image, options) = (Renderer::default(), Image::empty(), RenderOptions::default());
    pool.install(|| renderer.render_into(scene, &options, &mut image));
    let first = image.clone();
    let region = Region::new(GLOBAL);
    for _ in 0..frames {
        pool.install(|| renderer.render_into(scene, &options, &mut image));
    }
    let stats = region.change();
    assert_eq!(image, first, "a later frame differs from the first");
    stats.allocations + stats.reallocations
}

/// The demo (flat, Gouraud and Phong spheres, a textured floor, a
/// transparent sphere, fog) at a small size.
fn demo(ssaa: u32) -> Scene {
    let mut scene = demo_scene();
    (scene.settings.width, scene.settings.height, scene.settings.ssaa) = (160, 90, ssaa);
    scene
}

/// The room (planar shadows on the floor) in `mode`, small.
fn room(mode: ShadowMode) -> Scene {
    let mut scene = room_scene();
    (scene.settings.width, scene.settings.height) = (160, 90);
    scene.shadows.mode = mode;
    scene
}

// One test function: the count is global, so no other test may run
// (and allocate) in this binary while it counts.
//
// Rayon's own queues may grow (and shrink again) while a busy machine
// steals work, which allocates now and then in a multi-threaded pool: an
// attempt of three frames failed about one time in ten that way on a loaded
// machine, and with other builds and fuzzers sharing two cores five
// attempts in a row once did. So each setting gets up to twelve attempts
// and must have one with no allocation at all; an allocation made by the
// renderer would show in every attempt.
#[test]
fn steady_frames_allocate_nothing() {
    let mut lines = demo(1);
    lines.settings.wireframe.mode = WireframeMode::HiddenRemoved;
    let mut painter = demo(1);
    painter.settings.visibility = Visibility::Painter;
    let scenes = [
        ("demo", 1, demo(1)),
        ("demo", 2, demo(1)),
        ("demo ssaa 2", 2, demo(2)),
        ("room, planar shadows", 2, room(ShadowMode::Planar)),
        ("room, shadow maps", 2, room(ShadowMode::Map)),
        ("demo, hidden lines removed", 2, lines),
        ("demo, painter", 2, painter),
    ];
    for (name, threads, scene) in &scenes {
        let (scene, threads) = (scene, *threads);
        let counts: Vec<usize> = (0..12)
            .map(|_| allocations_after_first_frame(scene, threads, 3))
            .scan(false, |done, n| (!std::mem::replace(done, n == 0)).then_some(n))
            .collect();
        assert_eq!(
            counts.last(),
            Some(&0),
            "allocations in 3 frames ({name}, {threads} threads): {counts:?}"
        );
    }
}
