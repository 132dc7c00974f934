//! The expression parser, and lowering to the normal form of whatever parses.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rigor::syntax::{parse_expr, ParseOptions};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(e) = parse_expr(text, &ParseOptions::default()) else {
        return;
    };
    // Whatever parses is lowered too, within a small budget: no input may panic.
    use rigor::normal::limits;
    let _limits = limits::install(limits::Limits {
        max_terms: 2_000,
        ..limits::Limits::DEFAULT
    });
    let _deadline = limits::until(rigor::clock::Deadline::after(
        std::time::Duration::from_millis(200),
        rigor::clock::system(),
    ));
    let _ = rigor::lower::lower(&e, &rigor::lower::Env::default());
});
