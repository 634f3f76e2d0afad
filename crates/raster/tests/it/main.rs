//! Integration tests of zline-raster, one binary with a module per property
//! (STYLE habits 11–12).
//!
//! - [`oracle`]: a brute-force rasteriser with exact integer edge functions
//!   and the top-left rule, sharing no code with the crate's edge table. The
//!   coverage tests compare against it.
//! - [`coverage`]: the scan converter agrees with the oracle sample for
//!   sample — exhaustively on a small lattice, and by proptest on general
//!   triangles, slivers, sub-pixel triangles, vertices on samples and large
//!   coordinates (SPEC §3).
//! - [`watertight`]: fans and jittered grids cover every sample inside them
//!   exactly once and nothing outside, for several tile layouts (SPEC §3).
//! - [`depth`], [`attributes`]: incremental depth and attribute interpolation
//!   stay within the error bounds the crate states, including spans of 8192
//!   pixels (SPEC §4, §6).
//! - [`tiling`]: the bits a pixel gets do not depend on the tiles (SPEC §10).
//!
//! ## Case counts
//! Every property runs [`CASES`] = 256 random cases: enough to hit the tie
//! cases the generators aim at (vertices on sample positions, edges through
//! samples), while the whole binary stays within a few seconds on the 2-core
//! CI machine with the optimised test profile. The exhaustive lattice test
//! and the error report are deterministic.

mod attributes;
mod coverage;
mod depth;
mod exact;
mod margins;
mod oracle;
mod shapes;
mod tiling;
mod watertight;

use proptest::test_runner::Config;

/// Random cases per property (see the module doc for the choice).
const CASES: u32 = 256;

/// The proptest configuration shared by every property: [`CASES`] cases,
/// unless `PROPTEST_CASES` asks for another number (for a deeper local run).
fn config() -> Config {
    let mut config = Config::default();
    if std::env::var_os("PROPTEST_CASES").is_none() {
        config.cases = CASES;
    }
    config
}
