//! What a run says while it runs (rank 0): on a terminal a progress bar with the step, the
//! increment, the load factor, the elapsed time and an estimate of the rest; otherwise (a pipe,
//! a file) a short line per increment (at most 100 characters), or with `--verbose` the long one
//! with every reaction and the contact. Under mpirun the plain lines too: OpenMPI hands its
//! ranks a pseudo-terminal whatever mpirun's own output is, so a rank cannot tell whether a
//! person is watching. Cutbacks and notes go above the bar or between the lines.

use super::history::HistoryRow;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;

/// Ticks of the bar per step (its position is the total time, step - 1 + load factor).
const TICKS_PER_STEP: u64 = 1000;

pub enum Progress {
    Bar(ProgressBar),
    /// A line per increment: the long one when true.
    Lines(bool),
    Quiet,
}

impl Progress {
    /// A bar when `show` and stdout is a terminal, plain lines (long ones when `verbose`)
    /// when only `show`.
    pub fn new(show: bool, verbose: bool, steps: usize) -> Self {
        if !show {
            return Progress::Quiet;
        }
        // set by mpirun (OpenMPI) or a PMI launcher (MPICH), not in a singleton run
        let launched = ["OMPI_COMMAND", "PMI_RANK"].iter().any(|v| std::env::var_os(v).is_some());
        if launched || !std::io::stdout().is_terminal() {
            return Progress::Lines(verbose);
        }
        let bar = ProgressBar::new(steps as u64 * TICKS_PER_STEP);
        let style = ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {percent:>3}% ETA {eta:>4} {msg}").map(|s| s.progress_chars("=> "));
        if let Ok(style) = style {
            bar.set_style(style);
        }
        Progress::Bar(bar)
    }

    /// A line above the bar, or a plain line.
    pub fn note(&self, text: &str) {
        match self {
            Progress::Bar(bar) => bar.println(text),
            Progress::Lines(_) => println!("{text}"),
            Progress::Quiet => {}
        }
    }

    /// A converged increment: the bar moves to it, or its line is printed (a `plane` model's
    /// reactions over its thickness).
    pub fn increment(&self, row: &HistoryRow, step_name: &str, steps: usize, plane: bool) {
        match self {
            Progress::Bar(bar) => {
                bar.set_position(((row.step - 1) as f64 * TICKS_PER_STEP as f64 + row.load_factor * TICKS_PER_STEP as f64).round() as u64);
                let penetration = row.contacts.iter().map(|c| c.max_penetration).fold(0.0, f64::max);
                bar.set_message(format!(
                    "step {}/{steps} {step_name} #{} lambda {:.4} newton {} ep_max {:.2e} pen {:.1e} mm",
                    row.step, row.number, row.load_factor, row.newton_iterations, row.max_plastic_strain, penetration
                ));
            }
            Progress::Lines(false) => println!("{}", row.short_line(step_name, steps, plane)),
            Progress::Lines(true) => println!("{}", row.progress_line(step_name, steps, plane)),
            Progress::Quiet => {}
        }
    }

    /// The run is over: the bar stays on the screen at its last position.
    pub fn finish(&self) {
        if let Progress::Bar(bar) = self {
            bar.abandon();
        }
    }
}
