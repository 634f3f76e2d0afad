//! How the stages cut their work into rayon tasks.

/// Items per rayon task for `n` items on the current pool: about four tasks
/// a thread, so that one done early takes another while the rest finish,
/// within `[least, most]` (a small task costs its scheduling, a big one
/// leaves threads idle). Shared by the vertex and setup stages; a task
/// changes only which thread does the work, never the result.
pub(crate) fn task_len(n: usize, (least, most): (usize, usize)) -> usize {
    n.div_ceil(rayon::current_num_threads().max(1) * 4).clamp(least, most)
}
