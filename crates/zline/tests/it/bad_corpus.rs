//! The broken-file corpus, `tests/bad/`: every case rendered by the
//! `zline` binary (`zline render CASE -o OUT.png --size 64x48`, run in
//! `tests/bad/`) gives what `tests/bad/EXPECTED.toml` says — exit code 1
//! and exactly one `error:` line naming the file and the problem, or exit
//! code 0, a 64×48 PNG and the expected `warning:` line — and never a
//! panic (exit 101, or zline's `error: internal error` line), a signal or
//! a hang.
//!
//! Bounds, per case:
//! - **time**: [`TIMEOUT`], 20 s (each case takes well under a second in
//!   the optimised test build, at most about 15 s unoptimised); a case still running then is killed, with its process
//!   group, and fails the test;
//! - **memory**: a maximum resident set size of [`MAX_RSS_KIB`], 512 MiB
//!   (most cases stay under 16 MiB; the largest, eight spheres of 1024 ×
//!   1024 refused at the third, about 170 MiB), read from `/usr/bin/time -f %M`, the
//!   kernel's own count at exit (`wait4`'s `ru_maxrss`). Without
//!   `/usr/bin/time`, from `VmHWM` in `/proc/PID/status`, polled every few
//!   milliseconds while zline runs (it may miss a peak in the last few);
//!   without either, the memory check is skipped with a printed note.
//!
//! The test also fails when a file or folder in `tests/bad/` is no case's
//! input, or a case's input does not exist, so the corpus and its
//! expectations cannot drift apart.

use std::collections::BTreeSet;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

use crate::repo;

/// Longest time one case may run.
const TIMEOUT: Duration = Duration::from_secs(20);

/// Largest maximum resident set size one case may reach, in KiB (512 MiB).
const MAX_RSS_KIB: u64 = 512 * 1024;

/// GNU time, which reports the child's maximum resident set size.
const TIME: &str = "/usr/bin/time";

/// What a case must give.
#[derive(Debug)]
enum Outcome {
    /// Exit code 1, one `error:` line containing this.
    Error(String),
    /// Exit code 0, a PNG, a `warning:` line containing this.
    Warning(String),
    /// Exit code 0, a PNG, no warning.
    Renders,
}

#[derive(Debug)]
struct Case {
    /// The file to render, relative to `tests/bad/`.
    input: String,
    outcome: Outcome,
}

/// How one run ended.
struct Run {
    status: ExitStatus,
    stderr: String,
    /// Maximum resident set size in KiB, if it could be measured.
    max_rss_kib: Option<u64>,
    elapsed: Duration,
}

fn corpus() -> PathBuf {
    repo().join("tests/bad")
}

/// The cases of `EXPECTED.toml`.
fn cases() -> Vec<Case> {
    let text = std::fs::read_to_string(corpus().join("EXPECTED.toml")).expect("tests/bad/EXPECTED.toml");
    let table: toml::Table = text.parse().expect("EXPECTED.toml is TOML");
    let cases = table["case"].as_array().expect("[[case]] tables");
    cases
        .iter()
        .map(|c| {
            let c = c.as_table().expect("a [[case]] table");
            let input = c["input"].as_str().expect("case.input, a string").to_owned();
            let text = |key: &str| c.get(key).map(|v| v.as_str().expect("a string").to_owned());
            let outcome = match (text("error"), text("warning"), c.get("renders")) {
                (Some(e), None, None) => Outcome::Error(e),
                (None, Some(w), None) => Outcome::Warning(w),
                (None, None, Some(r)) if r.as_bool() == Some(true) => Outcome::Renders,
                _ => panic!("{input}: give one of error = \"…\", warning = \"…\", renders = true"),
            };
            for key in c.keys() {
                assert!(
                    ["input", "error", "warning", "renders"].contains(&key.as_str()),
                    "{input}: key {key}?"
                );
            }
            Case { input, outcome }
        })
        .collect()
}

/// The case's top-level entry in `tests/bad/`: its file, or its folder.
fn entry(input: &str) -> &str {
    input.split('/').next().unwrap()
}

/// Runs `zline render INPUT -o png --size 64x48` in `tests/bad/`, under
/// [`TIMEOUT`], measuring its memory.
fn run(input: &str, png: &Path, rss_file: &Path) -> Run {
    let use_time = Path::new(TIME).exists();
    let zline = env!("CARGO_BIN_EXE_zline");
    let args = ["render", input, "-o", png.to_str().unwrap(), "--size", "64x48"];
    let mut command = if use_time {
        let mut c = Command::new(TIME);
        c.args(["-f", "%M", "-o", rss_file.to_str().unwrap(), zline]).args(args);
        c
    } else {
        let mut c = Command::new(zline);
        c.args(args);
        c
    };
    // Its own process group, so a hung zline under `time` is killed too.
    command.current_dir(corpus()).stdin(Stdio::null()).stdout(Stdio::null()).process_group(0);
    let stderr_file = rss_file.with_extension("stderr");
    command.stderr(std::fs::File::create(&stderr_file).unwrap());
    let start = Instant::now();
    let mut child = command.spawn().expect("zline starts");
    let mut hwm = None;
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if !use_time {
            hwm = vm_hwm_kib(child.id()).or(hwm);
        }
        if start.elapsed() > TIMEOUT {
            let group = format!("-{}", child.id());
            let _ = Command::new("kill").args(["-KILL", "--", &group]).status();
            let _ = child.kill();
            let _ = child.wait();
            panic!("{input}: still running after {TIMEOUT:?}; killed");
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    let elapsed = start.elapsed();
    let stderr = std::fs::read_to_string(&stderr_file).unwrap_or_default();
    let max_rss_kib = if use_time {
        // The last line: GNU time may write "Command exited with non-zero
        // status 1" before it.
        let report = std::fs::read_to_string(rss_file).unwrap_or_default();
        Some(
            report
                .lines()
                .last()
                .and_then(|l| l.trim().parse().ok())
                .unwrap_or_else(|| panic!("{input}: no maximum RSS from {TIME}: {report:?}")),
        )
    } else {
        hwm
    };
    Run { status, stderr, max_rss_kib, elapsed }
}

/// The peak resident set size of a running process, from `/proc`.
fn vm_hwm_kib(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// Checks one run against its case; returns what is wrong.
fn check(case: &Case, run: &Run, png: &Path) -> Result<(), String> {
    let stderr = &run.stderr;
    let code = run.status.code();
    if code.is_none() || code == Some(101) {
        return Err(format!("crashed or panicked ({}):\n{stderr}", run.status));
    }
    if stderr.contains("panicked") || stderr.contains("internal error") {
        return Err(format!("panicked:\n{stderr}"));
    }
    if let Some(rss) = run.max_rss_kib {
        if rss > MAX_RSS_KIB {
            return Err(format!("maximum RSS {rss} KiB, more than the bound of {MAX_RSS_KIB} KiB"));
        }
    }
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    let warnings: Vec<&str> = stderr.lines().filter(|l| l.starts_with("warning:")).collect();
    let named = |line: &str| line.contains(entry(&case.input));
    match &case.outcome {
        Outcome::Error(needle) => {
            if code != Some(1) {
                return Err(format!("expected exit code 1, got {code:?}:\n{stderr}"));
            }
            if errors.len() != 1 {
                return Err(format!("expected one error: line, got {}:\n{stderr}", errors.len()));
            }
            if !errors[0].contains(needle.as_str()) || !named(errors[0]) {
                return Err(format!("the error line lacks {needle:?}:\n{}", errors[0]));
            }
            if png.exists() {
                return Err("a failed run wrote its output".into());
            }
        }
        Outcome::Warning(_) | Outcome::Renders => {
            if code != Some(0) || !errors.is_empty() {
                return Err(format!("expected exit code 0 and no error, got {code:?}:\n{stderr}"));
            }
            let img = image::open(png).map_err(|e| format!("no readable PNG: {e}"))?;
            if (img.width(), img.height()) != (64, 48) {
                return Err(format!("a {}x{} PNG, not 64x48", img.width(), img.height()));
            }
            match &case.outcome {
                Outcome::Warning(needle)
                    if !warnings.iter().any(|w| w.contains(needle.as_str()) && named(w)) =>
                {
                    return Err(format!("no warning: line containing {needle:?}:\n{stderr}"));
                }
                Outcome::Renders if !warnings.is_empty() => {
                    return Err(format!("unexpected warning:\n{stderr}"))
                }
                _ => {}
            }
        }
    }
    Ok(())
}

/// Every file and folder of `tests/bad/` is a case's input (or holds it),
/// every input exists, and no input is listed twice.
#[test]
fn the_corpus_and_its_expectations_agree() {
    let cases = cases();
    let inputs: Vec<&str> = cases.iter().map(|c| c.input.as_str()).collect();
    let unique: BTreeSet<&str> = inputs.iter().copied().collect();
    assert_eq!(unique.len(), inputs.len(), "an input is listed twice in EXPECTED.toml");
    for input in &inputs {
        assert!(
            corpus().join(input).is_file(),
            "EXPECTED.toml lists {input}, which is not a file in tests/bad/"
        );
    }
    let listed: BTreeSet<&str> = inputs.iter().map(|i| entry(i)).collect();
    assert_eq!(listed.len(), inputs.len(), "two cases share a folder");
    let on_disk: BTreeSet<String> = std::fs::read_dir(corpus())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|name| name != "EXPECTED.toml")
        .collect();
    let on_disk: BTreeSet<&str> = on_disk.iter().map(String::as_str).collect();
    let missing: Vec<_> = on_disk.difference(&listed).collect();
    assert!(missing.is_empty(), "in tests/bad/ but not in EXPECTED.toml: {missing:?}");
    assert!(cases.len() >= 80, "the corpus shrank to {} cases", cases.len());
}

/// Runs every case; reports every failure at once, and the largest RSS
/// and the slowest case.
#[test]
fn every_broken_file_gives_its_expected_error_or_warning() {
    let dir = tempfile::tempdir().unwrap();
    if !Path::new(TIME).exists() {
        println!("note: no {TIME}: maximum RSS read from /proc/PID/status VmHWM, polled");
    }
    let mut failures = Vec::new();
    let (mut largest, mut slowest) = ((0, String::new()), (Duration::ZERO, String::new()));
    for (i, case) in cases().iter().enumerate() {
        let png = dir.path().join(format!("out{i}.png"));
        let run = run(&case.input, &png, &dir.path().join(format!("rss{i}.txt")));
        match run.max_rss_kib {
            Some(rss) if rss > largest.0 => largest = (rss, case.input.clone()),
            None => println!("note: {}: maximum RSS not measured", case.input),
            _ => {}
        }
        if run.elapsed > slowest.0 {
            slowest = (run.elapsed, case.input.clone());
        }
        if let Err(e) = check(case, &run, &png) {
            failures.push(format!("{}: {e}", case.input));
        }
    }
    println!(
        "largest maximum RSS: {} KiB ({}); slowest: {:?} ({})",
        largest.0, largest.1, slowest.0, slowest.1
    );
    assert!(failures.is_empty(), "{} case(s) failed:\n{}", failures.len(), failures.join("\n"));
}

/// The checks can fail: a wrong expectation, a missing warning, a panic's
/// exit code and a memory bound exceeded are each caught.
#[test]
fn the_checks_catch_what_they_should() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("o.png");
    let case = |input: &str, outcome| Case { input: input.into(), outcome };
    let error_run = run("obj_no_faces.obj", &png, &dir.path().join("rss.txt"));
    let wrong = case("obj_no_faces.obj", Outcome::Error("something else".into()));
    assert!(check(&wrong, &error_run, &png).unwrap_err().contains("lacks"));
    let renders = case("obj_no_faces.obj", Outcome::Renders);
    assert!(check(&renders, &error_run, &png).is_err());
    let right = case("obj_no_faces.obj", Outcome::Error("no triangles".into()));
    assert_eq!(check(&right, &error_run, &png), Ok(()));
    let named_other = case("other.obj", Outcome::Error("no triangles".into()));
    assert!(check(&named_other, &error_run, &png).is_err(), "the file is not named");
    let fat = Run {
        max_rss_kib: Some(MAX_RSS_KIB + 1),
        ..run("obj_no_faces.obj", &png, &dir.path().join("r2.txt"))
    };
    assert!(check(&right, &fat, &png).unwrap_err().contains("maximum RSS"));

    let png2 = dir.path().join("w.png");
    let warn_run = run("mtl_d_7/model.obj", &png2, &dir.path().join("r3.txt"));
    let silent = case("mtl_d_7/model.obj", Outcome::Renders);
    assert!(check(&silent, &warn_run, &png2).unwrap_err().contains("unexpected warning"));
    let other = case("mtl_d_7/model.obj", Outcome::Warning("d value 8".into()));
    assert!(check(&other, &warn_run, &png2).is_err());

    // A panic: Rust's exit code 101, or zline's own report of one.
    let panic_run =
        Command::new("sh").args(["-c", "echo 'thread main panicked' >&2; exit 101"]).output().unwrap();
    let panicked = Run {
        status: panic_run.status,
        stderr: String::from_utf8_lossy(&panic_run.stderr).into_owned(),
        max_rss_kib: None,
        elapsed: Duration::ZERO,
    };
    assert!(check(&right, &panicked, &png).unwrap_err().contains("panicked"));
}
