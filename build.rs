//! Links the `rigor` executable as a position-dependent one on Linux with glibc.
//!
//! A position-independent executable has about 6,800 relocations that the dynamic
//! loader applies at every start, writing to some forty pages of relocated data. For a
//! command that runs for a millisecond or two (`rigor simplify` in a script, one
//! process per expression) that is a tenth of its time; see bench/RESULTS.md. The code is
//! still compiled position-independent; only the link differs, and only for the
//! binary (the library, its tests and the browser build are not affected). The cost is
//! that the executable's own code is not placed at a random address.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let env = std::env::var("CARGO_CFG_TARGET_ENV").unwrap_or_default();
    if os == "linux" && env == "gnu" {
        println!("cargo:rustc-link-arg-bins=-no-pie");
    }
}
