//! `cargo xtask scaling`: a model of the frame at more threads than this
//! machine has, from the benchmark scenes timed at 1 and 2 threads.
//!
//! Geometry, binning and the rest of the frame are extrapolated with
//! Amdahl's law: a stage's parallel share p comes from its own times,
//! T₂ = T₁·(1 − p + p/2), so p = 2·(1 − T₂/T₁) (clamped to [0, 1]), and
//! T_N = T₁·(1 − p + p/N). The raster stage is modelled from its
//! structure, at one thread: its unit of parallel work is a band of tile
//! rows ([`Renderer::band_times`]), so at N threads it takes its time
//! outside the bands plus the makespan of the bands handed out in order,
//! each to the thread that frees up first. (On this 2-vCPU machine a
//! 2-thread time moves by tens of per cent between runs, which Amdahl's p
//! doubles; the bands' one-thread times do not depend on it.) The table
//! prints the model at 2 threads beside the measured time, the one check
//! this machine allows. It says which parts stay serial and where the
//! bands' granularity, not the cores, bounds a scene; where a machine with
//! many cores is lent, `xtask bench --threads 1,2,4,8,16` checks it.

use std::path::Path;
use std::time::{Duration, Instant};

use anyhow::{Context, Result};
use zline::pipeline::{Image, RenderOptions, Renderer};
use zline::scene::Scene;

/// One scene's times at one thread count: per timed frame, the frame and
/// its stages (geometry, binning, raster) in seconds, and the bands' times.
#[derive(Default)]
struct Timings {
    frames: Vec<[f64; 4]>,
    bands: Vec<Vec<f64>>,
}

impl Timings {
    /// Draws `frames` warm frames of `scene` in `pool` after a warm-up.
    fn record(&mut self, scene: &Scene, pool: &rayon::ThreadPool, options: &RenderOptions, frames: usize) {
        let mut renderer = Renderer::default();
        let mut image = Image::empty();
        pool.install(|| renderer.render_into(scene, options, &mut image));
        for _ in 0..frames.max(1) {
            let start = Instant::now();
            let stats = pool.install(|| renderer.render_into(scene, options, &mut image));
            let frame = start.elapsed().as_secs_f64();
            let s = |d: Duration| d.as_secs_f64();
            self.frames.push([frame, s(stats.geometry), s(stats.binning), s(stats.raster)]);
            self.bands.push(renderer.band_times().map(|d| d.as_secs_f64()).collect());
        }
    }

    /// The median of column `i` (0 the frame, 1–3 the stages).
    fn median(&self, i: usize) -> f64 {
        median(self.frames.iter().map(|f| f[i]).collect())
    }

    /// Each band's median time.
    fn band_medians(&self) -> Vec<f64> {
        let count = self.bands.iter().map(Vec::len).min().unwrap_or(0);
        (0..count).map(|b| median(self.bands.iter().map(|f| f[b]).collect())).collect()
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The parallel share p of a stage that takes `one` seconds on one thread
/// and `two` on two: 2·(1 − two/one), in [0, 1] (0 for a stage too short
/// to time).
pub(crate) fn parallel_share(one: f64, two: f64) -> f64 {
    if one <= 0.0 {
        return 0.0;
    }
    (2.0 * (1.0 - two / one)).clamp(0.0, 1.0)
}

/// Amdahl's law: `one` seconds with parallel share `p` at `n` threads.
pub(crate) fn amdahl(one: f64, p: f64, n: usize) -> f64 {
    one * (1.0 - p + p / n as f64)
}

/// The time `n` threads take to run `jobs` (seconds each) handed out in
/// order, each to the thread that frees up first.
pub(crate) fn makespan(jobs: &[f64], n: usize) -> f64 {
    let mut free = vec![0.0f64; n.max(1)];
    for &job in jobs {
        let first = free.iter_mut().min_by(|a, b| a.total_cmp(b)).expect("at least one thread");
        *first += job;
    }
    free.into_iter().fold(0.0, f64::max)
}

/// What the model says of one scene at `n` threads: the frame's seconds,
/// and whether the slowest band alone takes longer than an even share of
/// the bands would (the bands' granularity bounds the raster stage there).
///
/// `one` and `two` are the frame and its stages (geometry, binning,
/// raster) at 1 and 2 threads, `bands` the raster stage's bands at one
/// thread. Geometry, binning and the rest of the frame follow Amdahl's law
/// with the share their 1- and 2-thread times give. The raster stage is
/// modelled from its structure, measured at one thread alone: its time
/// outside the bands stays serial, and the bands are handed out in order.
pub(crate) fn model(one: [f64; 4], two: [f64; 4], bands: &[f64], n: usize) -> (f64, bool) {
    let rest = |t: [f64; 4]| (t[0] - t[1] - t[2] - t[3]).max(0.0);
    let mut total = amdahl(rest(one), parallel_share(rest(one), rest(two)), n);
    for stage in 1..3 {
        total += amdahl(one[stage], parallel_share(one[stage], two[stage]), n);
    }
    let sum: f64 = bands.iter().sum();
    let serial = (one[3] - sum).max(0.0);
    let slowest = bands.iter().copied().fold(0.0, f64::max);
    (total + serial + makespan(bands, n), slowest > sum / n as f64)
}

pub(crate) fn run(
    (frames, rounds): (usize, usize),
    model_threads: &[usize],
    assets: &Path,
    filter: Option<&str>,
    options: &RenderOptions,
) -> Result<()> {
    let pools: Vec<rayon::ThreadPool> = [1, 2]
        .iter()
        .map(|&t| rayon::ThreadPoolBuilder::new().num_threads(t).build().context("thread pool"))
        .collect::<Result<_>>()?;
    let cases = crate::bench::cases(assets)?;
    let heads: String = model_threads.iter().map(|n| format!(" {n} threads |")).collect();
    let rules: String = model_threads.iter().map(|_| "---:|").collect();
    println!(
        "| scene | 1 thread ms | 2 threads ms (model) | p geometry | p binning | raster outside bands ms | bands (slowest ms) |{heads} speedup at {} |",
        model_threads.last().copied().unwrap_or(1)
    );
    println!("|---|---:|---:|---:|---:|---:|---:|{rules}---:|");
    for case in cases.iter().filter(|c| filter.is_none_or(|f| c.name.contains(f))) {
        let scene = (case.build)()?;
        let mut timings = [Timings::default(), Timings::default()];
        for _ in 0..rounds.max(1) {
            for (t, pool) in timings.iter_mut().zip(&pools) {
                t.record(&scene, pool, options, frames);
            }
        }
        let [one, two] = timings.each_ref().map(|t| [0, 1, 2, 3].map(|i| t.median(i)));
        let bands = timings[0].band_medians();
        let slowest = bands.iter().copied().fold(0.0, f64::max);
        let ms = |s: f64| s * 1e3;
        let mut row = format!(
            "| {} | {:.2} | {:.2} ({:.2}) | {:.2} | {:.2} | {:.2} | {} ({:.2}) |",
            case.name,
            ms(one[0]),
            ms(two[0]),
            ms(model(one, two, &bands, 2).0),
            parallel_share(one[1], two[1]),
            parallel_share(one[2], two[2]),
            ms((one[3] - bands.iter().sum::<f64>()).max(0.0)),
            bands.len(),
            ms(slowest)
        );
        let mut last = one[0];
        for &n in model_threads {
            let (time, banded) = model(one, two, &bands, n);
            row += &format!(" {:.2}{} |", ms(time), if banded { "ᵇ" } else { "" });
            last = time;
        }
        row += &format!(" {:.1}× |", one[0] / last);
        println!("{row}");
    }
    println!(
        "\nModel: geometry, binning and the rest by Amdahl's law from their 1- and 2-thread medians ({rounds} rounds \
         of {frames} frames, alternated); the raster stage as its time outside the bands (serial) plus the makespan \
         of its bands (tile rows, 1-thread medians) handed out in order. ᵇ: the slowest band takes longer than an \
         even share, so the bands' granularity bounds the raster stage at that count."
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stage_that_halves_is_all_parallel_and_one_that_stays_is_serial() {
        assert_eq!(parallel_share(10.0, 5.0), 1.0);
        assert_eq!(parallel_share(10.0, 10.0), 0.0);
        assert!((parallel_share(10.0, 7.5) - 0.5).abs() < 1e-12);
        // Faster than half, or slower on two threads: clamped.
        assert_eq!(parallel_share(10.0, 4.0), 1.0);
        assert_eq!(parallel_share(10.0, 12.0), 0.0);
        assert_eq!(parallel_share(0.0, 0.0), 0.0);
        assert!((amdahl(10.0, 0.5, 4) - 6.25).abs() < 1e-12);
    }

    #[test]
    fn makespan_hands_bands_to_the_first_free_thread() {
        assert_eq!(makespan(&[1.0, 1.0, 1.0, 1.0], 2), 2.0);
        assert_eq!(makespan(&[4.0, 1.0, 1.0, 1.0, 1.0], 2), 4.0);
        assert_eq!(makespan(&[1.0, 2.0, 3.0], 8), 3.0);
        assert_eq!(makespan(&[], 4), 0.0);
    }

    #[test]
    fn one_heavy_band_bounds_the_raster_stage() {
        // 10 ms of raster in one band: no more threads help.
        let (one, two) = ([0.010, 0.0, 0.0, 0.010], [0.005, 0.0, 0.0, 0.005]);
        let (t, banded) = model(one, two, &[0.010], 16);
        assert!(banded && (t - 0.010).abs() < 1e-12);
        // The same work in 16 even bands: 1/16.
        let (t, banded) = model(one, two, &[0.010 / 16.0; 16], 16);
        assert!(!banded && (t - 0.010 / 16.0).abs() < 1e-9, "{t}");
        // 2 ms of it outside the bands stays serial.
        let (t, _) = model(one, two, &[0.008 / 16.0; 16], 16);
        assert!((t - (0.002 + 0.008 / 16.0)).abs() < 1e-9, "{t}");
    }
}
