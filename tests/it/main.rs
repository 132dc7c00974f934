//! rigor's integration tests: one binary, one module per feature.

mod action;
mod calculus;
mod check;
mod cli;
mod differential;
mod docs;
mod documents;
mod equiv;
mod error_index;
mod fuzz;
mod guard;
mod hostile;
mod identities;
mod latex_readings;
mod library;
mod lint;
mod lint_display;
mod lint_readings;
mod lsp;
mod mark;
mod normal;
mod props;
mod readme;
mod repository;
mod soundness;
mod tidy;
mod views;
mod web;
mod workloads;

/// The number of proptest cases: `default`, or `PROPTEST_CASES` when it is set, so a
/// long soak run (`PROPTEST_CASES=100000 cargo test --release props`) needs no edit.
pub fn cases(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// A proptest configuration of [`cases`]`(default)` cases whose budget of rejected
/// inputs grows with the number of cases.
pub fn config(default: u32) -> proptest::test_runner::Config {
    let cases = cases(default);
    proptest::test_runner::Config {
        cases,
        max_global_rejects: cases.max(1024),
        ..proptest::test_runner::Config::default()
    }
}

/// Checker options for tests about verdicts: no wall-clock budget, so that a loaded
/// machine cannot turn a verdict into "ran out of its time budget". Tests of the budget
/// itself set a clock of their own.
pub fn no_budget() -> rigor::Options {
    rigor::Options {
        clock: None,
        ..rigor::Options::default()
    }
}

/// A clock that advances one microsecond each time it is read, on each thread: a budget
/// on it is a budget of work, the same on every machine however loaded. For tests whose
/// inputs are random and may hold a pathological case.
pub fn ticking_clock() -> std::time::Duration {
    use std::cell::Cell;
    thread_local!(static TICKS: Cell<u64> = const { Cell::new(0) });
    TICKS.with(|t| {
        t.set(t.get() + 1);
        std::time::Duration::from_micros(t.get())
    })
}
