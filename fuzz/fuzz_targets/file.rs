//! The derivation-file parser.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rigor::syntax::{parse_file, ParseOptions};

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = parse_file(text, &ParseOptions::default());
    }
});
