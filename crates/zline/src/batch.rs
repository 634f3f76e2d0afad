//! `zline batch`: many models or scene files, each rendered to
//! `OUTDIR/<stem>.png` with the same flags.
//!
//! Made to be rerun and split: each PNG is written to a temporary file in
//! OUTDIR and renamed when whole, and an input whose PNG exists is skipped
//! (unless `--force`), so a rerun after a crash or a killed machine renders
//! only what is missing; `--shard I/N` takes every N-th input of the sorted
//! list, starting at the I-th, so N machines given the same inputs render
//! disjoint parts that together are the whole. A failing input is reported
//! (`error: FILE: reason`) and the others still render; the exit code is 1
//! when any failed.

use std::collections::BTreeMap;
use std::panic::AssertUnwindSafe;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{anyhow, bail, Context, Result};
use clap::Args;
use zline::pipeline::render;

use crate::job::Job;
use crate::progress::{Progress, ProgressArgs};

/// The options of `zline batch` besides the common ones.
#[derive(Args)]
pub(crate) struct BatchArgs {
    /// Models (.obj, .gltf, .glb, .stl, .ply) or .toml scene files, or
    /// glob patterns zline expands (quote them: 'assets/obj/*/*.obj').
    #[arg(value_name = "INPUTS", required_unless_present = "list")]
    inputs: Vec<PathBuf>,
    /// A file of inputs, one path per line (blank lines and lines starting
    /// with # are skipped; relative paths are from the current folder).
    #[arg(long, value_name = "FILE")]
    list: Option<PathBuf>,
    /// Render only the inputs whose index in the sorted list is I−1 modulo
    /// N (I in 1..=N): N machines with the same inputs and `--shard 1/N`
    /// … `--shard N/N` split the work.
    #[arg(long, value_name = "I/N", value_parser = parse_shard)]
    shard: Option<(usize, usize)>,
    /// Render an input even when its PNG exists (by default it is
    /// skipped, so a rerun renders only what is missing).
    #[arg(long)]
    force: bool,
    /// As for `render`: read files the inputs name outside their folders.
    #[arg(long)]
    pub(crate) allow_paths_outside: bool,
    #[command(flatten)]
    progress: ProgressArgs,
}

/// `-o` for `zline batch`.
pub(crate) fn output_arg(arg: clap::Arg) -> clap::Arg {
    arg.value_name("OUTDIR").help(
        "The folder for the PNGs, OUTDIR/<input's stem>.png (created if missing); each is written \
         to a temporary file there and renamed when whole",
    )
}

/// `I/N` with 1 ≤ I ≤ N.
fn parse_shard(s: &str) -> Result<(usize, usize), String> {
    let bad = |why: &str| format!("expected I/N with 1 ≤ I ≤ N, e.g. 1/4, got '{s}'{why}");
    let (i, n) = s.split_once('/').ok_or_else(|| bad(""))?;
    let (i, n) = match (i.trim().parse::<usize>(), n.trim().parse::<usize>()) {
        (Ok(i), Ok(n)) => (i, n),
        _ => return Err(bad("")),
    };
    match (i, n) {
        (_, 0) => Err(bad(": N must be at least 1")),
        (0, _) => Err(bad(": shards count from 1")),
        (i, n) if i > n => Err(bad(": I is more than N")),
        _ => Ok((i, n)),
    }
}

/// True when `s` has a glob pattern's special characters.
fn is_pattern(s: &str) -> bool {
    s.contains(['*', '?', '['])
}

/// The inputs: the arguments (patterns expanded) and `--list`'s lines,
/// sorted, each once.
fn inputs(args: &BatchArgs) -> Result<Vec<PathBuf>> {
    let mut all = Vec::new();
    let mut add = |path: PathBuf| -> Result<()> {
        let text = path.to_string_lossy();
        if !is_pattern(&text) || path.exists() {
            all.push(path);
            return Ok(());
        }
        let matches = glob::glob(&text).map_err(|e| anyhow!("{text}: not a valid pattern: {e}"))?;
        let before = all.len();
        for m in matches {
            all.push(m.map_err(|e| anyhow!("{text}: {e}"))?);
        }
        if all.len() == before {
            bail!("{text}: no file matches the pattern");
        }
        Ok(())
    };
    for input in &args.inputs {
        add(input.clone())?;
    }
    if let Some(list) = &args.list {
        let text = std::fs::read_to_string(list)
            .with_context(|| format!("{}: cannot read the list", list.display()))?;
        for line in text.lines().map(str::trim).filter(|l| !l.is_empty() && !l.starts_with('#')) {
            add(PathBuf::from(line))?;
        }
    }
    all.sort();
    all.dedup();
    Ok(all)
}

/// Refuses two inputs with the same stem: they would write the same PNG.
fn check_stems(inputs: &[PathBuf]) -> Result<()> {
    let mut seen: BTreeMap<String, &Path> = BTreeMap::new();
    for input in inputs {
        let stem = stem(input)?;
        if let Some(other) = seen.insert(stem.clone(), input) {
            bail!(
                "{} and {} would both be written to {stem}.png; rename one or render them in separate batches",
                other.display(),
                input.display()
            );
        }
    }
    Ok(())
}

fn stem(input: &Path) -> Result<String> {
    input
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .filter(|s| !s.is_empty())
        .ok_or_else(|| anyhow!("{}: the input has no file name", input.display()))
}

/// `zline batch`.
pub(crate) fn run(args: &BatchArgs, job: &Job) -> Result<()> {
    let outdir = &job.output;
    let all = inputs(args)?;
    check_stems(&all)?;
    let (shard, shards) = args.shard.unwrap_or((1, 1));
    let mine: Vec<&PathBuf> = all.iter().skip(shard - 1).step_by(shards).collect();
    std::fs::create_dir_all(outdir)
        .with_context(|| format!("{}: cannot create the folder", outdir.display()))?;
    let started = Instant::now();
    let progress = Progress::new(mine.len() as u64, &args.progress, (job.quiet, job.timings));
    let (mut rendered, mut skipped, mut failed) = (0usize, 0usize, 0usize);
    for input in &mine {
        let png = outdir.join(format!("{}.png", stem(input)?));
        progress.show(&input.display().to_string());
        if !args.force && png.exists() {
            skipped += 1;
            progress.skipped(&format!("{}: {} exists, skipped", input.display(), png.display()));
            continue;
        }
        let start = Instant::now();
        let one = || -> Result<()> {
            let (mut scene, framed) = (job.load)(input)?;
            (job.aim)(&mut scene, framed, 0.0);
            let options = &job.options;
            let (image, _) = job.pool.install(|| render(&scene, options));
            zline::save_png(&image, &png).with_context(|| format!("{}: cannot write PNG", png.display()))
        };
        match std::panic::catch_unwind(AssertUnwindSafe(one)) {
            Ok(Ok(())) => {
                rendered += 1;
                progress.done(&format!("{} -> {}", input.display(), png.display()), start.elapsed());
            }
            Ok(Err(e)) => {
                failed += 1;
                let why = (job.describe)(&e);
                let name = input.display().to_string();
                // Loader errors often start with the file's name already.
                let line = if why.starts_with(&name) { why } else { format!("{name}: {why}") };
                progress.failed(&line);
            }
            Err(_) => {
                failed += 1;
                progress.failed(&format!("{}: internal error (a bug in zline)", input.display()));
            }
        }
    }
    progress.finish();
    let of = match args.shard {
        Some((i, n)) => format!("{} inputs of shard {i}/{n} ({} in all)", mine.len(), all.len()),
        None => format!("{} inputs", mine.len()),
    };
    let summary = format!(
        "{rendered} rendered, {skipped} skipped (already there), {failed} failed, of {of} in {:.2} s",
        started.elapsed().as_secs_f64()
    );
    if failed > 0 {
        bail!("batch: {summary}");
    }
    progress.say(&format!("batch: {summary}"));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_are_one_based_and_at_most_n() {
        assert_eq!(parse_shard("1/1"), Ok((1, 1)));
        assert_eq!(parse_shard(" 3 / 4 "), Ok((3, 4)));
        for bad in ["0/4", "5/4", "1/0", "1", "a/b", "-1/2", "1/2/3", ""] {
            assert!(parse_shard(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn the_shards_split_the_sorted_inputs() {
        let all: Vec<usize> = (0..10).collect();
        let mut union: Vec<usize> =
            (1..=3).flat_map(|i| all.iter().copied().skip(i - 1).step_by(3).collect::<Vec<_>>()).collect();
        union.sort();
        assert_eq!(union, all);
    }

    #[test]
    fn two_inputs_with_one_stem_are_refused() {
        let e = check_stems(&[PathBuf::from("a/m.obj"), PathBuf::from("b/m.ply")]).unwrap_err();
        assert!(e.to_string().contains("m.png"), "{e}");
        assert!(check_stems(&[PathBuf::from("a/m.obj"), PathBuf::from("b/n.ply")]).is_ok());
    }
}
