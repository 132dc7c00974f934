//! The guard: a broken engine is simulated (every right side "normalises" to its left
//! side, so every link would be verified as an identity); the independent evaluation
//! of both sides as written must then catch the false steps, and only those.

use rigor::check::{FileReport, Options, Status};
use rigor::files::check_paths;
use std::path::PathBuf;

fn corrupt() -> Options {
    Options {
        corrupt_for_tests: true,
        ..crate::no_budget()
    }
}

fn check(dir: &str, opts: &Options) -> Vec<FileReport> {
    let d = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(dir);
    check_paths(&[d], opts)
}

fn undecided(r: &FileReport) -> usize {
    r.claims
        .iter()
        .flat_map(|c| &c.links)
        .filter(|l| l.status == Status::Undecided)
        .count()
}

#[test]
fn a_forced_wrong_normal_form_is_caught_and_made_undecided() {
    let src = "symbols x m L > 0\nclaim [bad] x + 1 = x + 2\nclaim [good] (x + 1)^2 = x^2 + 2 x + 1\nclaim [int] int(y^2 m/L, y, -L/2, L/2) = m L^2/3\n";
    let r = rigor::check_source("t.deriv", src, &corrupt(), &rigor::MemoryResolver::new());
    let statuses: Vec<&Status> = r.claims.iter().map(|c| &c.links[0].status).collect();
    assert_eq!(statuses[0], &Status::Undecided, "{:?}", r.diagnostics);
    assert!(statuses[1].is_verified());
    assert_eq!(statuses[2], &Status::Undecided);
    let codes: Vec<&str> = r.diagnostics.iter().map(|d| d.code.as_str()).collect();
    assert_eq!(codes, ["E0903", "E0903"]);
    assert!(
        r.diagnostics[0].notes[0]
            .to_string()
            .contains("the left side is ≈ "),
        "{:?}",
        r.diagnostics[0]
    );
    // Without the fault, the engine itself refutes them.
    let r = rigor::check_source(
        "t.deriv",
        src,
        &crate::no_budget(),
        &rigor::MemoryResolver::new(),
    );
    assert_eq!((r.verified(), r.failed()), (1, 2));
}

#[test]
fn the_guard_checks_most_verified_links_of_the_handout_and_never_doubts_them() {
    let (mut verified, mut guarded) = (0, 0);
    for dir in ["derivations", "tests/check/pass"] {
        for r in check(dir, &crate::no_budget()) {
            assert!(r.ok(), "{}: {:?}", r.path, r.diagnostics);
            assert_eq!(undecided(&r), 0, "{}", r.path);
            verified += r.verified();
            guarded += r.guarded;
        }
    }
    // The rest are links the guard cannot evaluate (approximations, abstract bodies,
    // time instants, antiderivatives) or whose facts it cannot meet at a point.
    assert!(
        guarded * 20 >= verified * 11,
        "guarded {guarded} of {verified}"
    );
}

#[test]
fn with_a_broken_engine_the_guard_still_stops_most_false_steps() {
    let reports = check("tests/check/fail", &corrupt());
    let honest = check("tests/check/fail", &crate::no_budget());
    let mut refuted = 0;
    let mut caught = 0;
    for (broken, real) in reports.iter().zip(&honest) {
        let real_failed: Vec<bool> = real
            .claims
            .iter()
            .flat_map(|c| &c.links)
            .map(|l| l.status == Status::Failed)
            .collect();
        let guarded: Vec<bool> = broken
            .claims
            .iter()
            .flat_map(|c| &c.links)
            .map(|l| !l.status.is_verified())
            .collect();
        for (f, g) in real_failed.iter().zip(&guarded) {
            refuted += usize::from(*f);
            caught += usize::from(*f && *g);
        }
    }
    // Refuted links whose sides the guard can evaluate (not time instants, abstract
    // bodies or antiderivatives) are caught; at least two thirds of all.
    assert!(refuted > 20, "{refuted}");
    assert!(caught * 2 >= refuted, "caught {caught} of {refuted}");
}

#[test]
fn with_a_broken_engine_the_soundness_fixtures_are_caught() {
    for name in [
        "rod_factor_two",
        "kind_wrong_power",
        "sound_let_bound_name",
        "sound_odd_root_quotient",
        "sound_subs_outside_sign",
        "sound_body_coordinate_sign",
    ] {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join(format!("tests/check/fail/{name}.deriv"));
        let r = &check_paths(&[path], &corrupt())[0];
        assert!(undecided(r) > 0, "{name}: {:?}", r.claims);
        assert!(
            r.diagnostics.iter().any(|d| d.code.as_str() == "E0903"),
            "{name}"
        );
    }
}
