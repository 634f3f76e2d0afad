//! The xtask binary answers. Having a test makes `cargo test --workspace`
//! build the binary with the workspace's unified features, so `.ci/run`
//! runs the render regression and the checks from that build
//! (`target/debug/xtask`) instead of building the pipeline's kernels a
//! second time for `cargo run -p xtask` alone.

use std::process::Command;

#[test]
fn the_tasks_are_listed() {
    let out = Command::new(env!("CARGO_BIN_EXE_xtask")).arg("--help").output().expect("xtask runs");
    let help = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for task in ["regress", "modules", "kernels", "bench"] {
        assert!(help.contains(task), "{task} missing from:\n{help}");
    }
}
