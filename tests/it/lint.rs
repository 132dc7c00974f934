//! `rigor lint` on lecture notes: the handout as it is, and two documents of our own with
//! deliberate mistakes; the full report of each is a snapshot.

use std::path::Path;
use std::process::Command;

fn lint(paths: &[&str]) -> (String, String, i32) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Command::new(env!("CARGO_BIN_EXE_rigor"))
        .arg("lint")
        .args(paths)
        .current_dir(root)
        .output()
        .expect("rigor runs");
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        out.status.code().unwrap_or(-1),
    )
}

#[test]
fn notes_with_mistakes_fail_at_the_mistakes_only() {
    let (out, err, code) = lint(&["tests/lint/rod_notes.md", "tests/lint/incline_notes.tex"]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(
        out.ends_with("chains: 8, verified: 5, failed: 2, needs context: 1\n"),
        "{out}"
    );
    assert!(
        out.contains("tests/lint/rod_notes.md:15:3: FAILED"),
        "{out}"
    );
    assert!(
        out.contains("tests/lint/incline_notes.tex:12:1: FAILED"),
        "{out}"
    );
    // Code blocks and inline code are never math.
    assert!(
        !out.contains("rod_notes.md:19") && !out.contains("rod_notes.md:18"),
        "{out}"
    );
    insta::assert_snapshot!(format!("{out}\n{err}"));
}

#[test]
fn the_handout_as_it_is_never_fails_and_verifies_what_holds_on_its_own() {
    let seed =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/seeds/000_4a418897358df19b.txt");
    let Ok(text) = std::fs::read_to_string(&seed) else {
        panic!("the handout is at {}", seed.display());
    };
    let dir = std::env::temp_dir().join(format!("rigor-lint-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let doc = dir.join("handout.md");
    std::fs::write(&doc, text).expect("written");
    let (out, err, code) = lint(&[&doc.display().to_string()]);
    assert_eq!(code, 0, "no chain of the handout is false:\n{out}{err}");
    let summary = out.lines().last().unwrap_or_default().to_string();
    assert!(
        summary.starts_with("chains: 51, verified: 21, failed: 0"),
        "{summary}"
    );
    // Scopes are checked in parallel: the report must not depend on which ran first.
    for _ in 0..2 {
        let (again, _, _) = lint(&[&doc.display().to_string()]);
        assert_eq!(again, out, "the same report every time");
    }
    let report = out.replace(&doc.display().to_string(), "handout.md");
    // The chains that hold on their own: the rod's I_G from the integral on, its I_O,
    // the disk's dm (its algebra) and its integral, the trapdoor's relations.
    for at in [
        "68:23", "69:3", "73:24", "77:27", "167:113", "171:3", "182:3",
    ] {
        assert!(
            report.contains(&format!("handout.md:{at}: verified")),
            "{at} is verified:\n{report}"
        );
    }
    // What rests on prose needs context, and says what.
    assert!(
        report.contains("handout.md:68:3: needs context: it integrates over dm"),
        "{report}"
    );
    assert!(
        report.contains("handout.md:73:3: needs context: this step brings in r, R"),
        "{report}"
    );
    // `a b = I_G/m` is the zero-acceleration condition divided by F/m (F = m y_G''):
    // nothing says F is not zero, and the report says so.
    assert!(
        report.contains("handout.md:216:3: needs context: not verified: this step is line 212 divided by m y_G'', so it follows only where m y_G'' != 0"),
        "{report}"
    );
    insta::assert_snapshot!(report);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_missing_document_is_bad_input() {
    let (_, err, code) = lint(&["tests/lint/no_such_notes.md"]);
    assert_eq!(code, 2);
    assert!(err.contains("no_such_notes.md"), "{err}");
}

/// The handout with its symbols declared in comments (the blow of the centre of
/// percussion nonzero too), and a comment heading where the notes change scenario
/// without one (frictionless, then slipping).
fn declared_handout(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        if line.starts_with("Sliding vs Rolling") {
            out.push_str("<!-- rigor: ## Sliding -->\n\n");
        }
        if line.starts_with("Sliding and Rolling") {
            out.push_str("<!-- rigor: ## Sliding and rolling -->\n\n");
        }
        out.push_str(line);
        out.push('\n');
        if line.starts_with("Example 5.1") {
            out.push_str("\n<!-- rigor: symbols m g R I_G > 0 -->\n");
            out.push_str("<!-- rigor: symbols 0 < beta < pi/2 -->\n");
        }
        if line.starts_with("5.3 Centre of Percussion") {
            out.push_str("\n<!-- rigor: symbols F != 0 -->\n");
        }
    }
    out
}

#[test]
fn the_handout_with_its_symbols_declared_verifies_the_rolling_and_sliding_accelerations() {
    let seed =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/seeds/000_4a418897358df19b.txt");
    let Ok(text) = std::fs::read_to_string(&seed) else {
        panic!("the handout is at {}", seed.display());
    };
    let declared = declared_handout(&text);
    assert_ne!(declared, text, "the comments went in");
    let dir = std::env::temp_dir().join(format!("rigor-lint-decl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let doc = dir.join("handout.md");
    std::fs::write(&doc, &declared).expect("written");
    let (out, err, code) = lint(&[&doc.display().to_string()]);
    let out = out.replace(&doc.display().to_string(), "handout.md");
    assert_eq!(code, 0, "no chain of the handout is false:\n{out}{err}");
    let line_of = |needle: &str| {
        declared
            .lines()
            .position(|l| l.contains(needle))
            .map(|i| i + 1)
            .unwrap_or_else(|| panic!("{needle} is in the handout"))
    };
    // N = mg cos(beta); the rolling acceleration; the sliding x'' and theta''.
    for needle in [
        "$$N = mg \\cos \\beta$$",
        "$$\\ddot{x} = -\\frac{g\\sin\\beta}{1 + I_G/\\left(mR^2\\right)}$$",
        "$$\\ddot{x} = g \\left(\\mu \\cos \\beta - \\sin \\beta \\right)$$",
        "$$\\ddot{\\theta} = \\frac{R\\mu mg \\cos \\beta}{I_G}$$",
    ] {
        let at = format!("handout.md:{}:3: verified", line_of(needle));
        assert!(out.contains(&at), "{at}\n{out}");
    }
    // The centre of percussion: `a b = I_G/m` verified from the condition before it,
    // `= k_G^2` needs the definition of k_G.
    let ab = line_of("$$a b = \\frac{I_G}{m} = k_G^2$$");
    for at in [
        format!("handout.md:{ab}:3: verified"),
        format!("handout.md:{ab}:9: needs context: this step brings in k_G"),
    ] {
        assert!(out.contains(&at), "{at}\n{out}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_centre_of_percussion_follows_only_where_the_blow_is_declared_nonzero() {
    let (out, err, code) = lint(&["tests/lint/percussion_notes.md"]);
    assert_eq!(code, 0, "{out}{err}");
    // F = m y_G'' with no sign: dividing the condition by it is not assumed, and the
    // report names what is missing.
    assert!(
        out.contains("percussion_notes.md:17:3: needs context: not verified: this step is line 15 divided by y_G'', so it follows only where y_G'' != 0"),
        "{out}"
    );
    // `F != 0` declared: `a b = I_G/m` follows, with nothing assumed; `= k_G^2` brings
    // in a symbol the notes define in prose.
    assert!(out.contains("percussion_notes.md:25:3: verified"), "{out}");
    assert!(
        out.contains("percussion_notes.md:25:9: needs context: this step brings in k_G"),
        "{out}"
    );
    // The same condition never verifies a wrong result.
    for at in ["31:3", "37:3"] {
        assert!(
            out.contains(&format!("percussion_notes.md:{at}: needs context")),
            "{at}\n{out}"
        );
    }
    assert!(
        out.ends_with("chains: 11, verified: 2, failed: 0, needs context: 9\n"),
        "{out}"
    );
    insta::assert_snapshot!(format!("{out}\n{err}"));
}

#[test]
fn headings_scope_what_the_notes_state_and_labels_and_arrows_split_relations() {
    let (out, err, code) = lint(&["tests/lint/scopes_notes.md"]);
    assert_eq!(code, 1, "{out}{err}");
    // `\sum F_y \qquad N - mg = m\ddot{y} = 0`: the label is left out and `= 0` is
    // stated, so `N = mg` follows.
    assert!(out.contains("scopes_notes.md:13:3: verified"), "{out}");
    // `R = 2mg \rightarrow R/2 = mg`: two relations, the second verified.
    assert!(out.contains("scopes_notes.md:17:37: verified"), "{out}");
    // `\ddot{y}_B` is the acceleration of y_B, found from the stated theta''.
    assert!(out.contains("scopes_notes.md:25:3: verified"), "{out}");
    // R is defined afresh under the second heading: not a contradiction of R = 2mg.
    assert!(out.contains("scopes_notes.md:27:3: verified"), "{out}");
    // The one slip fails, at its link.
    assert!(out.contains("scopes_notes.md:31:3: FAILED"), "{out}");
    assert!(err.contains("31:83"), "{err}");
    assert!(
        out.ends_with("chains: 13, verified: 8, failed: 1, needs context: 4\n"),
        "{out}"
    );
    insta::assert_snapshot!(format!("{out}\n{err}"));
}

#[test]
fn integrals_over_a_prose_mass_element_are_checked_for_linearity_only() {
    let (out, err, code) = lint(&["tests/lint/mass_notes.md"]);
    assert_eq!(code, 0, "{out}{err}");
    // Constants cross integrals, which add: verified for every body.
    assert!(out.contains("mass_notes.md:3:3: verified"), "{out}");
    assert!(out.contains("mass_notes.md:9:3: verified"), "{out}");
    // A square of an integral, or a dropped cross term, is not linearity: it may hold
    // for the body the notes mean (a centred one), so it needs context, never fails.
    assert!(out.contains("mass_notes.md:5:3: needs context"), "{out}");
    assert!(out.contains("mass_notes.md:7:3: needs context"), "{out}");
}

#[test]
fn a_slip_in_declared_symbols_is_not_taken_as_a_fact_for_what_follows() {
    // `(a + b)^2 = a^2 + b^2` fails; taken as stated it would give `ab = 0`, a false
    // line, as verified. A slip is a mistake, never a fact: `ab = 0` fails too.
    let (out, err, code) = lint(&["tests/lint/slip_then_more.md"]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(out.contains("slip_then_more.md:5:3: FAILED"), "{out}");
    assert!(out.contains("slip_then_more.md:9:3: FAILED"), "{out}");
}

#[test]
fn a_verified_chain_says_what_it_assumes_and_declared_signs_remove_it() {
    // `I = M R^2/2` divided by R^2: verified where R != 0, which nothing declares.
    let dir = std::env::temp_dir().join(format!("rigor-lint-assuming-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let bare = dir.join("bare.md");
    let signed = dir.join("signed.md");
    let eq = "$$\\frac{2 I}{R^2} = \\frac{2}{R^2} \\cdot \\frac{M R^2}{2} = M$$\n";
    std::fs::write(
        &bare,
        format!(
            "# Disk\n\n<!-- rigor: symbols I M R -->\n<!-- rigor: given I = M R^2/2 -->\n\n{eq}"
        ),
    )
    .expect("write");
    std::fs::write(&signed, format!("# Disk\n\n<!-- rigor: symbols I M R > 0 -->\n<!-- rigor: given I = M R^2/2 -->\n\n{eq}")).expect("write");
    let (out, err, code) = lint(&[bare.to_str().unwrap_or_default(), "--format", "json"]);
    assert_eq!(code, 0, "{out}{err}");
    let v: serde_json::Value =
        serde_json::from_str(out.lines().next().unwrap_or("{}")).expect("json");
    let chain = &v["chains"][0];
    assert_eq!(chain["verdict"], "verified", "{out}");
    assert!(
        chain["assuming"].as_array().is_some_and(|a| !a.is_empty()),
        "the division by R^2 is assumed safe and said: {out}"
    );
    let (out, err, code) = lint(&[signed.to_str().unwrap_or_default()]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        out.contains(":6:3: verified\n"),
        "with R > 0 nothing is assumed: {out}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
