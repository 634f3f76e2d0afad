//! `cargo xtask scaling`: a model of the frame at more threads than this
//! machine has, from the benchmark scenes timed at 1 and 2 threads.
//!
//! Geometry, binning and the rest of the frame are extrapolated with
//! Amdahl's law: a stage's parallel share p comes from its own times,
//! T₂ = T₁·(1 − p + p/2), so p = 2·(1 − T₂/T₁) (clamped to [0, 1]), from
//! its fastest frames at 1 and 2 threads, and T_N = T₁·(1 − p + p/N) from
//! its 1-thread median. The raster stage is modelled from its
//! structure, at one thread: its units of parallel work are bands of tile
//! rows, cut into pieces when there are many threads
//! ([`zline::pipeline::pieces_per_band`], [`zline::pipeline::Renderer::unit_times`]), so at
//! N threads it takes its time outside the units plus the makespan of the
//! units that N threads would use, timed at one thread, handed out in
//! order, each to the thread that frees up first. (On this 2-vCPU machine a
//! 2-thread time moves by tens of per cent between runs, which Amdahl's p
//! doubles; the units' one-thread times do not depend on it.) The table
//! prints the model at 2 threads beside the measured time, the one check
//! this machine allows. It says which parts stay serial and where the
//! units' granularity, not the cores, bounds a scene; where a machine with
//! many cores is lent, `xtask bench --threads 1,2,4,8,16` checks it.

use std::path::Path;
use std::time::Duration;

use anyhow::{Context, Result};
use zline::pipeline::RenderOptions;
use zline::scene::Scene;

/// One scene's times at one thread count and cut of the bands: per timed
/// frame, the frame and its stages (geometry, binning, raster) in seconds,
/// and the tile stage's units' times.
#[derive(Default)]
struct Timings {
    frames: Vec<[f64; 4]>,
    units: Vec<Vec<f64>>,
}

impl Timings {
    /// Draws `frames` warm frames of `scene` in `pool` after a warm-up, the
    /// bands cut into `pieces` (`None`: as the pool's threads choose).
    fn record(
        &mut self,
        scene: &Scene,
        (pool, pieces): (&rayon::ThreadPool, Option<usize>),
        options: &RenderOptions,
        frames: usize,
    ) {
        crate::bench::each_frame(scene, (pool, pieces), options, frames, |frame, stats, renderer| {
            let s = |d: Duration| d.as_secs_f64();
            self.frames.push([frame, s(stats.geometry), s(stats.binning), s(stats.raster)]);
            self.units.push(renderer.unit_times().map(|d| d.as_secs_f64()).collect());
        });
    }

    /// The median of column `i` (0 the frame, 1–3 the stages).
    fn median(&self, i: usize) -> f64 {
        median(self.frames.iter().map(|f| f[i]).collect())
    }

    /// The shortest time of the rest of the frame (outside the stages),
    /// geometry and binning: noise on this machine only adds time, and a
    /// phase where its second core answers slowly can fill every frame of
    /// a timing, which moves a median but seldom the fastest frame.
    fn fastest(&self) -> [f64; 3] {
        let least = |f: &dyn Fn(&[f64; 4]) -> f64| self.frames.iter().map(f).fold(f64::INFINITY, f64::min);
        [least(&rest), least(&|t| t[1]), least(&|t| t[2])]
    }

    /// The median over frames of the raster stage's time outside its units
    /// (per frame, so the noise of the whole stage does not land on it).
    fn outside_units(&self) -> f64 {
        let sum = |units: &Vec<f64>| units.iter().sum::<f64>();
        median(self.frames.iter().zip(&self.units).map(|(f, u)| (f[3] - sum(u)).max(0.0)).collect())
    }

    /// Each unit's median time.
    fn unit_medians(&self) -> Vec<f64> {
        let count = self.units.iter().map(Vec::len).min().unwrap_or(0);
        (0..count).map(|b| median(self.units.iter().map(|f| f[b]).collect())).collect()
    }
}

/// The frame's time outside its three stages (`t`: the frame, geometry,
/// binning, raster).
fn rest(t: &[f64; 4]) -> f64 {
    (t[0] - t[1] - t[2] - t[3]).max(0.0)
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
/// and whether the slowest unit alone takes longer than an even share of
/// the units would (the units' granularity bounds the raster stage there).
///
/// `one` is the frame and its stages (geometry, binning, raster) at one
/// thread; the rest of the frame, geometry and binning follow Amdahl's law
/// with their parallel `shares`.
/// The raster stage is modelled from its structure, measured at one thread
/// with the bands cut as `n` threads cut them: `outside` is its time
/// outside the units, which stays serial, and `units` the units' times,
/// handed out in order.
pub(crate) fn model(
    one: [f64; 4],
    shares: [f64; 3],
    (outside, units): (f64, &[f64]),
    n: usize,
) -> (f64, bool) {
    let mut total = amdahl(rest(&one), shares[0], n);
    for stage in 1..3 {
        total += amdahl(one[stage], shares[stage], n);
    }
    let sum: f64 = units.iter().sum();
    let slowest = units.iter().copied().fold(0.0, f64::max);
    (total + outside + makespan(units, n), slowest > sum / n as f64)
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
    let last = model_threads.last().copied().unwrap_or(1);
    println!(
        "| scene | 1 thread ms | 2 threads ms (model) | p geometry | p binning | bands × pieces at {last} (slowest ms) |{heads} speedup at {last} | whole bands at {last}: ms, speedup |"
    );
    println!("|---|---:|---:|---:|---:|---:|{rules}---:|---:|");
    let tile = options.tile_size.clamp(1, zline::scene::MAX_TILE_SIZE);
    for case in cases.iter().filter(|c| filter.is_none_or(|f| c.name.contains(f))) {
        let scene = (case.build)()?;
        let (bands, cols) =
            (scene.settings.height.div_ceil(tile) as usize, scene.settings.width.div_ceil(tile) as usize);
        // The cut each modelled thread count makes, and one 1-thread timing per cut.
        let cut = |n: usize| zline::pipeline::pieces_per_band(n, bands, cols);
        let mut cuts: Vec<usize> = model_threads.iter().map(|&n| cut(n)).chain([1, cut(2)]).collect();
        cuts.sort_unstable();
        cuts.dedup();
        let mut timings = [Timings::default(), Timings::default()];
        let mut at_one: Vec<Timings> = cuts.iter().map(|_| Timings::default()).collect();
        for _ in 0..rounds.max(1) {
            for (t, pool) in timings.iter_mut().zip(&pools) {
                t.record(&scene, (pool, None), options, frames);
            }
            for (t, &pieces) in at_one.iter_mut().zip(&cuts) {
                t.record(&scene, (&pools[0], Some(pieces)), options, frames);
            }
        }
        let [one, two] = timings.each_ref().map(|t| [0, 1, 2, 3].map(|i| t.median(i)));
        let [least_one, least_two] = timings.each_ref().map(Timings::fastest);
        let shares = [0, 1, 2].map(|i| parallel_share(least_one[i], least_two[i]));
        let units: Vec<(f64, Vec<f64>)> =
            at_one.iter().map(|t| (t.outside_units(), t.unit_medians())).collect();
        let of_cut = |pieces: usize| {
            let (outside, units) = &units[cuts.binary_search(&pieces).expect("every cut was timed")];
            (*outside, &units[..])
        };
        let of = |n: usize| of_cut(cut(n));
        let ms = |s: f64| s * 1e3;
        let (_, last_units) = of(last);
        let mut row = format!(
            "| {} | {:.2} | {:.2} ({:.2}) | {:.2} | {:.2} | {} × {} ({:.2}) |",
            case.name,
            ms(one[0]),
            ms(two[0]),
            ms(model(one, shares, of(2), 2).0),
            shares[1],
            shares[2],
            bands,
            last_units.len() / bands.max(1),
            ms(last_units.iter().copied().fold(0.0, f64::max))
        );
        let mut time_at_last = one[0];
        for &n in model_threads {
            let (time, bound) = model(one, shares, of(n), n);
            row += &format!(" {:.2}{} |", ms(time), if bound { "ᵇ" } else { "" });
            time_at_last = time;
        }
        let (whole, _) = model(one, shares, of_cut(1), last);
        row += &format!(" {:.1}× | {:.2}, {:.1}× |", one[0] / time_at_last, ms(whole), one[0] / whole);
        println!("{row}");
    }
    println!(
        "\nModel: geometry, binning and the rest by Amdahl's law, their parallel shares p from their fastest frames at \
         1 and 2 threads ({rounds} rounds of {frames} frames, alternated), applied to their 1-thread medians; the \
         raster stage as its time outside its units (serial) plus the makespan \
         of its units — bands of tile rows, cut into the pieces each thread count makes, timed at one thread — \
         handed out in order. ᵇ: the slowest unit takes longer than an even share, so the units' granularity \
         bounds the raster stage at that count. The last column models the bands whole, as before they were cut."
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
        let (one, shares) = ([0.010, 0.0, 0.0, 0.010], [1.0, 1.0, 1.0]);
        let (t, banded) = model(one, shares, (0.0, &[0.010]), 16);
        assert!(banded && (t - 0.010).abs() < 1e-12);
        // The same work in 16 even bands: 1/16.
        let (t, banded) = model(one, shares, (0.0, &[0.010 / 16.0; 16]), 16);
        assert!(!banded && (t - 0.010 / 16.0).abs() < 1e-9, "{t}");
        // 2 ms of it outside the bands stays serial.
        let (t, _) = model(one, shares, (0.002, &[0.008 / 16.0; 16]), 16);
        assert!((t - (0.002 + 0.008 / 16.0)).abs() < 1e-9, "{t}");
    }
}
