//! A report of how close interpolation comes to its stated error bounds:
//! the largest measured error relative to each bound, per kind of triangle,
//! over a fixed pseudo-random set of cases (the same on every run). Printed
//! with `eprintln!`; see it with `cargo test -p zline-raster -- --nocapture
//! error_margins`. The bounds themselves are asserted on every sample.

use crate::attributes::{check_gouraud, check_linear, linear};
use crate::depth::{depth_errors, depths, Worst};
use crate::shapes::Shape;
use proptest::array::uniform3;
use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

/// Cases per kind of triangle and per bound.
const REPORT_CASES: usize = 64;

/// `REPORT_CASES` values of `s`, from a fixed seed.
fn cases<S: Strategy>(s: S) -> Vec<S::Value> {
    let rng = TestRng::deterministic_rng(RngAlgorithm::ChaCha);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    (0..REPORT_CASES).map(|_| s.new_tree(&mut runner).expect("strategy generates").current()).collect()
}

fn line(name: &str, shape: Shape, w: Worst) -> String {
    format!("{name:<8} {:<8} {:>10.4} {:>10.3e} {:>9}", format!("{shape:?}"), w.ratio, w.max_error, w.samples)
}

#[test]
fn error_margins_report() {
    let mut out = vec![format!(
        "{:<8} {:<8} {:>10} {:>10} {:>9}",
        "bound", "shape", "err/bound", "max |err|", "samples"
    )];
    for shape in Shape::ALL {
        let tri = shape.triangles();
        let colours = uniform3(uniform3(0.0..=1.0f32));
        let depth = cases((tri.clone(), depths())).into_iter().map(|(t, k)| depth_errors(t, k));
        let depth = depth.fold(Worst::default(), Worst::max);
        let gouraud = cases((tri.clone(), colours)).into_iter().map(|(t, c)| check_gouraud(t, c, false));
        let lin = cases((tri, linear())).into_iter().map(|(t, l)| check_linear(t, l));
        out.push(line("depth", shape, depth));
        out.push(line("gouraud", shape, gouraud.fold(Worst::default(), Worst::max)));
        out.push(line("linear", shape, lin.fold(Worst::default(), Worst::max)));
    }
    eprintln!(
        "largest interpolation error relative to its bound ({REPORT_CASES} cases each):\n{}",
        out.join("\n")
    );
}
