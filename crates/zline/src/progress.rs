//! The progress bar and per-file lines of `zline turntable` and `zline
//! batch`.

use std::io::IsTerminal;
use std::time::Duration;

use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// `--verbose` (`--quiet` is one of the common render flags).
#[derive(Args)]
pub(crate) struct ProgressArgs {
    /// A line per file (or frame) with the time it took.
    #[arg(short, long, conflicts_with = "quiet")]
    pub(crate) verbose: bool,
}

/// A progress bar with an ETA on stderr, hidden when stderr is not a
/// terminal or with `--quiet`; lines printed through it do not tear it.
pub(crate) struct Progress {
    bar: ProgressBar,
    quiet: bool,
    verbose: bool,
}

impl Progress {
    /// A bar for `len` steps; `quiet` and `timings` are the common
    /// `--quiet` and `--timings` (which asks for the per-file lines as
    /// `--verbose` does).
    pub(crate) fn new(len: u64, args: &ProgressArgs, (quiet, timings): (bool, bool)) -> Progress {
        let bar = if quiet || !std::io::stderr().is_terminal() {
            ProgressBar::hidden()
        } else {
            let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
            let style = ProgressStyle::with_template(
                "{bar:40.cyan/blue} {pos}/{len} {wide_msg} [{elapsed}, ETA {eta}]",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar());
            bar.set_style(style);
            bar.enable_steady_tick(Duration::from_millis(250));
            bar
        };
        Progress { bar, quiet, verbose: args.verbose || (timings && !quiet) }
    }

    /// The name shown beside the bar.
    pub(crate) fn show(&self, name: &str) {
        self.bar.set_message(name.to_string());
    }

    /// One step done, with its line and time under `--verbose`.
    pub(crate) fn done(&self, line: &str, time: Duration) {
        if self.verbose {
            self.say(&format!("{line} ({:.1} ms)", time.as_secs_f64() * 1e3));
        }
        self.bar.inc(1);
    }

    /// A step skipped (no line unless `--verbose`).
    pub(crate) fn skipped(&self, line: &str) {
        if self.verbose {
            self.say(line);
        }
        self.bar.inc(1);
    }

    /// A step failed: its `error:` line, always printed.
    pub(crate) fn failed(&self, line: &str) {
        self.bar.suspend(|| eprintln!("error: {line}"));
        self.bar.inc(1);
    }

    /// A line on stderr unless `--quiet`.
    pub(crate) fn say(&self, line: &str) {
        if !self.quiet {
            self.bar.suspend(|| eprintln!("{line}"));
        }
    }

    /// Removes the bar.
    pub(crate) fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
