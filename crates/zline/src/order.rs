//! Draw order for the classroom's "what breaks without it": each mesh's
//! triangles in a shuffled order (`render --shuffle SEED`, the viewer's
//! `X`). With the z-buffer the picture stays the same unless surfaces tie
//! in depth; the work (the samples shaded) follows the order.

use std::sync::Arc;

use zline_scene::Scene;

/// Fisher–Yates with a 64-bit xorshift seeded by `seed`: the same order
/// for the same seed.
fn shuffle<T>(items: &mut [T], seed: u64) {
    let mut state = seed | 1;
    for i in (1..items.len()).rev() {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        items.swap(i, (state % (i as u64 + 1)) as usize);
    }
}

/// Shuffles the triangles of every object's mesh by `seed` (each object
/// with a seed of its own, drawn from `seed` and its index).
pub fn shuffle_triangles(scene: &mut Scene, seed: u64) {
    for (k, object) in scene.objects.iter_mut().enumerate() {
        let mut mesh = (*object.mesh).clone();
        shuffle(&mut mesh.triangles, seed ^ (k as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15));
        object.mesh = Arc::new(mesh);
    }
}
