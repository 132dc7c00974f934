//! The whole checker on one source text, with small limits so that every run is short.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rigor::check::{check_source, MemoryResolver, Options};
use std::time::Duration;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let opts = Options {
        limits: rigor::normal::limits::Limits {
            max_terms: 2_000,
            ..rigor::normal::limits::Limits::DEFAULT
        },
        timeout: Duration::from_millis(200),
        ..Options::default()
    };
    // No other file exists: `use` finds nothing to import.
    let report = check_source("input.deriv", text, &opts, &MemoryResolver::new());
    // Rendering the report must not panic either.
    let _ = rigor::render::human::report(&report, true);
    let _ = rigor::render::json::report(&report);
    let _ = rigor::render::github::report(&report);
    if report.ast.is_some() {
        let _ = rigor::render::latex::document(&report);
        let _ = rigor::render::markdown::document(&report);
    }
});
