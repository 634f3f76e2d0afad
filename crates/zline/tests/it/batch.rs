//! `zline batch`: shards together are the whole batch, byte for byte; a
//! rerun skips what exists; a bad input is reported and the rest render.

use std::path::Path;
use std::process::{Command, Output};

use crate::repo;

/// `zline batch` run from the repository's root (the patterns are relative).
fn batch(args: &[&str]) -> Output {
    let mut all = vec!["batch", "assets/obj/*/*.obj", "assets/ply/*.ply", "--size", "96x72"];
    all.extend_from_slice(args);
    Command::new(env!("CARGO_BIN_EXE_zline")).args(&all).current_dir(repo()).output().unwrap()
}

#[track_caller]
fn check_ok(out: &Output) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "zline failed:\n{stderr}");
    stderr
}

/// The files in `dir`, sorted, with their bytes.
fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut f: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (e.file_name().into_string().unwrap(), std::fs::read(e.path()).unwrap())
        })
        .collect();
    f.sort();
    f
}

#[test]
fn two_shards_give_the_unsharded_batch_and_a_rerun_skips_what_exists() {
    let dir = tempfile::tempdir().unwrap();
    let (whole, sharded) = (dir.path().join("whole"), dir.path().join("sharded"));
    let o = |p: &Path| p.to_str().unwrap().to_string();
    let stderr = check_ok(&batch(&["-o", &o(&whole)]));
    // stderr is a pipe here: no progress bar, no escape codes.
    assert!(!stderr.contains('\x1b') && !stderr.contains('\r'), "{stderr:?}");
    assert!(stderr.contains("3 rendered, 0 skipped (already there), 0 failed, of 3 inputs"), "{stderr}");
    let first = check_ok(&batch(&["-o", &o(&sharded), "--shard", "1/2"]));
    assert!(first.contains("2 rendered") && first.contains("of 2 inputs of shard 1/2 (3 in all)"), "{first}");
    let second = check_ok(&batch(&["-o", &o(&sharded), "--shard", "2/2"]));
    assert!(second.contains("1 rendered") && second.contains("shard 2/2"), "{second}");
    let names: Vec<String> = files(&whole).into_iter().map(|(n, _)| n).collect();
    assert_eq!(names, ["bunny_lowres.png", "spot.png", "suzanne.png"]);
    assert_eq!(files(&whole), files(&sharded));
    // Each is the render command's image.
    let single = dir.path().join("single.png");
    let model = repo().join("assets/obj/spot/spot.obj");
    let out = crate::zline(&["render", model.to_str().unwrap(), "-o", &o(&single), "--size", "96x72"]);
    assert!(out.status.success());
    assert_eq!(std::fs::read(&single).unwrap(), std::fs::read(whole.join("spot.png")).unwrap());
    // A rerun renders nothing; one missing output is rendered again; an
    // existing one, even a wrong one, stays unless --force.
    std::fs::remove_file(whole.join("suzanne.png")).unwrap();
    std::fs::write(whole.join("spot.png"), b"left by a rerun").unwrap();
    let stderr = check_ok(&batch(&["-o", &o(&whole), "--verbose"]));
    assert!(stderr.contains("1 rendered, 2 skipped"), "{stderr}");
    assert!(stderr.contains("spot.png exists, skipped") && stderr.contains(" ms)"), "{stderr}");
    assert_eq!(std::fs::read(whole.join("spot.png")).unwrap(), b"left by a rerun");
    assert_eq!(files(&whole)[2], files(&sharded)[2], "suzanne.png");
    let stderr = check_ok(&batch(&["-o", &o(&whole), "--force", "--quiet"]));
    assert!(stderr.is_empty(), "--quiet printed:\n{stderr}");
    assert_eq!(files(&whole), files(&sharded));
}

#[test]
fn a_bad_input_is_reported_and_the_others_render() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("broken.obj");
    std::fs::write(&bad, "v 0 0 0\nf 1 2 3\n").unwrap();
    let missing = dir.path().join("missing.ply");
    let list = dir.path().join("list.txt");
    std::fs::write(
        &list,
        format!("# inputs\n{}\n\n{}\nassets/obj/suzanne/suzanne.obj\n", bad.display(), missing.display()),
    )
    .unwrap();
    let out_dir = dir.path().join("out");
    let out = batch(&["--list", list.to_str().unwrap(), "-o", out_dir.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(!stderr.contains("panicked") && !stderr.contains("internal error"), "{stderr}");
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(errors.len(), 3, "{stderr}");
    assert!(errors[0].starts_with(&format!("error: {}: ", bad.display())), "{stderr}");
    assert!(errors[1].starts_with(&format!("error: {}: ", missing.display())), "{stderr}");
    assert!(errors[2].contains("3 rendered, 0 skipped (already there), 2 failed, of 5 inputs"), "{stderr}");
    let names: Vec<String> = files(&out_dir).into_iter().map(|(n, _)| n).collect();
    assert_eq!(names, ["bunny_lowres.png", "spot.png", "suzanne.png"], "{stderr}");
}

#[test]
fn bad_batch_requests_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    for shard in ["0/2", "3/2", "1/0", "2", "a/b", "-1/2", ""] {
        let run = batch(&["-o", out.to_str().unwrap(), &format!("--shard={shard}")]);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "--shard '{shard}':\n{stderr}");
        assert!(stderr.contains("--shard") && !stderr.contains("panicked"), "{stderr}");
    }
    // A pattern that matches nothing, and two inputs that would write one file.
    let run = batch(&["assets/nothing/*.obj", "-o", out.to_str().unwrap()]);
    crate::check_clean_error(&run, &["assets/nothing/*.obj", "no file matches"]);
    let twin = dir.path().join("spot.ply");
    std::fs::copy(repo().join("assets/ply/bunny_lowres.ply"), &twin).unwrap();
    let run = batch(&[twin.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    crate::check_clean_error(&run, &["spot.png"]);
    assert!(!out.exists(), "a refused batch wrote files");
}
