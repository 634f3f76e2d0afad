//! `cargo xtask kernels`: what the SIMD levels cost in compiled code, read
//! from the built binary.
//!
//! Every function that runs at a chosen SIMD level is a *job*
//! (`zline_simd::Vectorized`), and each monomorphized job is one function
//! per level: `zline_simd::run_apart` (baseline, for kernels called as jobs
//! of their own), `zline_simd::avx2::run_v3` and `run_v4`. Counting those
//! symbols in the binary counts the compiled jobs, whatever the source
//! says. The count is held against the budget in `xtask/kernels.toml`: a
//! new dimension of kernels is a decision written there, not an accident.
//!
//! The same pass checks the inlining rule that keeps jobs fast: inside a
//! job every lane operation is inlined, so the binary holds no out-of-line
//! copy of an AVX intrinsic (`core::core_arch::x86::avx*`). One that is
//! there is called from code compiled for the baseline — correct, and many
//! times slower.
//!
//! With `--by-kernel` the binary is built again with v0 symbol names
//! (`-C symbol-mangling-version=v0`, into `target/kernels`), whose job
//! symbols carry the closure or type each job was made from, and the jobs
//! are listed by it.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{bail, Context, Result};
use object::{Object, ObjectSymbol};

/// The budget file, relative to the workspace root.
const BUDGET_FILE: &str = "xtask/kernels.toml";

/// The counts read from one binary.
#[derive(Debug, Default)]
struct Jobs {
    /// Job symbols per level: baseline, v3, v4.
    per_level: [usize; 3],
    /// Demangled job names (without hash) per level, for `--by-kernel`.
    names: [Vec<String>; 3],
    /// Out-of-line AVX intrinsics and the functions that call them.
    intrinsics: Vec<String>,
}

pub(crate) fn run(binary: Option<PathBuf>, by_kernel: bool) -> Result<()> {
    let root = workspace_root()?;
    let budget = read_budget(&root.join(BUDGET_FILE))?;
    let binary = match (binary, by_kernel) {
        (Some(path), _) => path,
        (None, true) => build_v0(&root)?,
        (None, false) => default_binary(&root)?,
    };
    let jobs = read_jobs(&binary)?;
    println!("kernel jobs in {} (zline_simd's level trampolines):", binary.display());
    println!("| level | jobs |");
    println!("|---|---:|");
    let levels = ["baseline (run_apart)", "x86-64-v3 (run_v3)", "x86-64-v4 (run_v4)"];
    for (name, n) in levels.iter().zip(jobs.per_level) {
        println!("| {name} | {n} |");
    }
    let total: usize = jobs.per_level.iter().sum();
    println!("| all | {total} |");
    if by_kernel {
        print_by_kernel(&jobs);
    }
    let mut failed = false;
    if total > budget {
        println!("budget: {total} jobs > {budget} ({BUDGET_FILE}): over budget");
        failed = true;
    } else {
        println!("budget: {total} jobs <= {budget} ({BUDGET_FILE}): ok");
    }
    if jobs.intrinsics.is_empty() {
        println!("inlining: no AVX intrinsic left out of line: ok");
    } else {
        println!(
            "inlining: {} AVX intrinsics left out of line (called at the baseline):",
            jobs.intrinsics.len()
        );
        for line in &jobs.intrinsics {
            println!("  {line}");
        }
        failed = true;
    }
    if failed {
        bail!("kernels: over budget or out-of-line intrinsics (see above)");
    }
    Ok(())
}

/// The workspace root: the parent of this crate's folder.
fn workspace_root() -> Result<PathBuf> {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest.parent().map(Path::to_path_buf).context("xtask has no parent folder")
}

/// `budget = N` from the budget file.
fn read_budget(path: &Path) -> Result<usize> {
    let text = std::fs::read_to_string(path).with_context(|| format!("{}: cannot read", path.display()))?;
    let table: toml::Table = text.parse().with_context(|| format!("{}: not TOML", path.display()))?;
    let budget = table
        .get("budget")
        .and_then(toml::Value::as_integer)
        .with_context(|| format!("{}: no integer `budget`", path.display()))?;
    usize::try_from(budget).with_context(|| format!("{}: negative budget", path.display()))
}

/// The `zline` binary of the profile this xtask was built with (the one
/// `cargo test` or `cargo build` made beside it), or this xtask itself,
/// which links the same pipeline and so the same jobs.
fn default_binary(root: &Path) -> Result<PathBuf> {
    let me = std::env::current_exe().context("cannot find the xtask executable")?;
    let beside = me.with_file_name(format!("zline{}", std::env::consts::EXE_SUFFIX));
    if beside.is_file() {
        return Ok(beside);
    }
    let release = root.join("target/release").join(format!("zline{}", std::env::consts::EXE_SUFFIX));
    if release.is_file() {
        return Ok(release);
    }
    println!("(no zline binary beside xtask: reading xtask itself, which links the same pipeline)");
    Ok(me)
}

/// Builds the release `zline` with v0 symbol names into `target/kernels`.
fn build_v0(root: &Path) -> Result<PathBuf> {
    let target = root.join("target/kernels");
    let status = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()))
        .current_dir(root)
        .args(["build", "--release", "--package", "zline", "--bin", "zline", "--target-dir"])
        .arg(&target)
        .env("RUSTFLAGS", "-C symbol-mangling-version=v0")
        .status()
        .context("cannot run cargo")?;
    if !status.success() {
        bail!("cargo build with v0 symbol names failed");
    }
    Ok(target.join("release").join(format!("zline{}", std::env::consts::EXE_SUFFIX)))
}

/// Reads the job symbols and the out-of-line intrinsics of `binary`.
fn read_jobs(binary: &Path) -> Result<Jobs> {
    let data = std::fs::read(binary).with_context(|| format!("{}: cannot read", binary.display()))?;
    let file =
        object::File::parse(&*data).with_context(|| format!("{}: not an object file", binary.display()))?;
    let mut jobs = Jobs::default();
    let mut intrinsics = BTreeMap::new();
    for symbol in file.symbols().chain(file.dynamic_symbols()) {
        if !symbol.is_definition() {
            continue;
        }
        let Ok(raw) = symbol.name() else { continue };
        let name = format!("{:#}", rustc_demangle::demangle(raw));
        let level = if name.starts_with("zline_simd::run_apart") {
            0
        } else if name.starts_with("zline_simd::avx2::run_v3") {
            1
        } else if name.starts_with("zline_simd::avx2::run_v4") {
            2
        } else {
            if name.starts_with("core::core_arch::x86::avx") {
                intrinsics.insert(name, ());
            }
            continue;
        };
        jobs.per_level[level] += 1;
        jobs.names[level].push(name);
    }
    if jobs.per_level.iter().all(|&n| n == 0) {
        bail!("{}: no job symbols (stripped, or not a zline binary?)", binary.display());
    }
    jobs.intrinsics = intrinsics.into_keys().collect();
    Ok(jobs)
}

/// The v3 jobs grouped by what they were made from: the kernel function
/// whose closure a `Call` job runs, or the job type.
fn print_by_kernel(jobs: &Jobs) {
    let mut groups: BTreeMap<String, usize> = BTreeMap::new();
    for name in &jobs.names[1] {
        *groups.entry(job_origin(name)).or_default() += 1;
    }
    if jobs.names[1].iter().all(|n| !n.contains('<')) {
        println!("(job symbols carry no type names: build with v0 names, `--by-kernel`)");
        return;
    }
    println!("\njobs per level by origin (x86-64-v3; the other levels alike):");
    println!("| made from | jobs |");
    println!("|---|---:|");
    for (origin, n) in groups {
        println!("| `{origin}` | {n} |");
    }
}

/// The origin of a v0-demangled job name: for `Call<closure in F>`, the
/// function F with its closure number; else the job type.
fn job_origin(name: &str) -> String {
    let inner = name.split_once("::<").map_or(name, |(_, rest)| rest);
    let inner = inner.strip_suffix('>').unwrap_or(inner);
    let inner = inner.strip_prefix("zline_simd::job::Call<").unwrap_or(inner);
    // Drop generic arguments: keep the path and the closure number.
    let mut out = String::new();
    let mut depth = 0usize;
    for c in inner.chars() {
        match c {
            '<' => depth += 1,
            '>' => depth = depth.saturating_sub(1),
            _ if depth == 0 => out.push(c),
            _ => {}
        }
    }
    out.replace("::::", "::").trim_end_matches('>').to_string()
}
