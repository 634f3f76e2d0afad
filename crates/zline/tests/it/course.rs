//! The course companion (docs/course/): every `zline` command in its
//! ```sh blocks runs from the repository root and succeeds, its outputs
//! sent to a temporary folder, so no page goes stale.

use std::process::Command;

use crate::repo;

/// A command line split on spaces, double quotes keeping a word whole.
fn words(line: &str) -> Vec<String> {
    let (mut out, mut word, mut quoted) = (Vec::new(), String::new(), false);
    for c in line.chars() {
        match c {
            '"' => quoted = !quoted,
            ' ' if !quoted => {
                if !word.is_empty() {
                    out.push(std::mem::take(&mut word));
                }
            }
            c => word.push(c),
        }
    }
    if !word.is_empty() {
        out.push(word);
    }
    out
}

#[test]
fn every_command_of_the_course_pages_runs() {
    let folder = repo().join("docs/course");
    let mut pages: Vec<_> = std::fs::read_dir(&folder).unwrap().map(|e| e.unwrap().path()).collect();
    pages.sort();
    let out = tempfile::tempdir().unwrap();
    let mut ran = 0;
    for page in pages.iter().filter(|p| p.extension().is_some_and(|e| e == "md")) {
        let text = std::fs::read_to_string(page).unwrap();
        let mut in_sh = false;
        for line in text.lines() {
            if line.starts_with("```") {
                in_sh = line == "```sh";
                continue;
            }
            if !in_sh || !line.starts_with("zline ") {
                continue;
            }
            let mut args = words(line);
            args.remove(0);
            // Outputs into the temporary folder.
            for k in 1..args.len() {
                if ["-o", "--image", "--html"].contains(&args[k - 1].as_str()) {
                    args[k] = out.path().join(&args[k]).to_str().unwrap().to_string();
                }
            }
            let run =
                Command::new(env!("CARGO_BIN_EXE_zline")).args(&args).current_dir(repo()).output().unwrap();
            assert!(
                run.status.success(),
                "{}: `{line}` failed:\n{}",
                page.display(),
                String::from_utf8_lossy(&run.stderr)
            );
            ran += 1;
        }
    }
    assert!(ran >= 20, "{ran} commands");
}
