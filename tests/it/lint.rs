//! `rigor lint` on lecture notes: our own notes on rigid bodies as a lecturer writes them
//! (Markdown and LaTeX), and documents of our own with deliberate mistakes; the full
//! report of each is a snapshot.

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
        out.ends_with("chains: 8, verified: 3, defined: 2, failed: 2, needs context: 1\n"),
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
fn a_missing_document_is_bad_input() {
    let (_, err, code) = lint(&["tests/lint/no_such_notes.md"]);
    assert_eq!(code, 2);
    assert!(err.contains("no_such_notes.md"), "{err}");
}

/// The text of a fixture under `tests/lint`.
fn fixture(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/lint")
        .join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The number of the one line of `text` that holds `needle`.
fn line_of(text: &str, needle: &str) -> usize {
    let found: Vec<usize> = text
        .lines()
        .enumerate()
        .filter(|(_, l)| l.contains(needle))
        .map(|(i, _)| i + 1)
        .collect();
    assert_eq!(
        found.len(),
        1,
        "`{needle}` is on one line of the notes: {found:?}"
    );
    found[0]
}

/// `line:column` of `part` in the one line of `text` that holds `needle` (columns count
/// from 1, as the report's do).
fn place(text: &str, needle: &str, part: &str) -> String {
    let n = line_of(text, needle);
    let line = text.lines().nth(n - 1).unwrap_or_default();
    let col = line
        .find(part)
        .unwrap_or_else(|| panic!("`{part}` is on the line of `{needle}`"));
    format!("{n}:{}", col + 1)
}

/// Lints `path` three times and asserts the reports are the same: scopes are checked in
/// parallel, and the report must not depend on which ran first.
fn lint_steadily(path: &str) -> (String, String, i32) {
    let first = lint(&[path]);
    for _ in 0..2 {
        assert_eq!(lint(&[path]), first, "the same report every time");
    }
    first
}

#[test]
fn the_lecture_notes_as_written_never_fail_and_verify_what_holds_on_its_own() {
    let doc = "tests/lint/handout_notes.md";
    let text = fixture("handout_notes.md");
    let (out, err, code) = lint_steadily(doc);
    assert_eq!(code, 0, "no chain of the notes is false:\n{out}{err}");
    assert!(
        out.ends_with("\nchains: 58, verified: 12, defined: 8, failed: 0, needs context: 38\n"),
        "{out}"
    );
    let has = |at: &str, what: &str| {
        let line = format!("{doc}:{at}: {what}");
        assert!(out.contains(&line), "{line}\n{out}");
    };
    // The chains that hold on their own: the rod's I_G from the integral on, its I_O,
    // the disk's dm (its algebra) and its integral, the trapdoor's y_G''.
    for (needle, part) in [
        ("$$I_G = \\int y^2 dm", "\\int_{-L/2}"),
        ("$$I_O = \\frac{mL^2}{12}", "I_O"),
        ("$$dm = m\\frac{dA}{A}", "m\\frac{2\\pi"),
        ("$$I_G = \\int_0^R", "\\frac{2m}{R^2} \\int"),
        ("$$\\ddot{y}_G = ", "\\ddot{y}_G"),
    ] {
        has(&place(&text, needle, part), "verified");
    }
    // With no signs declared, the trapdoor's moment chain `I_A theta'' = m L^2/3 theta''`
    // lets theta'' be solved only assuming 3 I_A != m L^2, and then the facts hold only
    // where g m = 0: the step is not verified (it used to be, vacuously, and so was
    // theta'' = 5 g L^2 in its place), and neither is R = mg/4 after it.
    for (needle, part) in [
        ("\\sum M(A):", "\\ddot{\\theta} = -\\frac{3}{2}"),
        ("$$R = ", "R"),
    ] {
        has(
            &place(&text, needle, part),
            "needs context: not verified: this step assumes L != 0",
        );
    }
    // What rests on prose needs context, and says what.
    has(
        &place(&text, "$$I_G = \\int y^2 dm", "I_G"),
        "needs context: it integrates over dm",
    );
    has(
        &place(&text, "$$dm = m\\frac{dA}{A}", "dm"),
        "needs context: this step brings in r, R",
    );
    // `a b = I_G/m` is the zero-acceleration condition divided by F/m (F = m y_G''):
    // nothing says F is not zero, and the report says so.
    let condition = line_of(&text, "$$\\frac{F}{m} - b");
    has(
        &place(&text, "$$a b = ", "a b"),
        &format!("needs context: not verified: this step is line {condition} divided by m y_G'', so it follows only where m y_G'' != 0"),
    );
    insta::assert_snapshot!(format!("{out}\n{err}"));
}

/// The notes with their symbols declared in comments (the blow of the centre of
/// percussion nonzero too), and a comment heading where the notes change scenario
/// without one (frictionless, then slipping): each comment goes before or after the one
/// line that holds its anchor.
fn declared(text: &str) -> String {
    let before = [
        ("**No friction.**", "<!-- rigor: ## Frictionless slope -->"),
        (
            "**Slipping while rolling.**",
            "<!-- rigor: ## Sliding and rolling -->",
        ),
    ];
    let after = [
        (
            "## Example 5.1",
            "<!-- rigor: symbols m g R I_G > 0 -->\n<!-- rigor: symbols 0 < beta < pi/2 -->",
        ),
        (
            "## 5.3 Centre of percussion",
            "<!-- rigor: symbols F != 0 -->",
        ),
    ];
    for (anchor, _) in before.iter().chain(&after) {
        line_of(text, anchor);
    }
    let mut out = String::new();
    for line in text.lines() {
        for (anchor, comment) in before {
            if line.starts_with(anchor) {
                out.push_str(&format!("{comment}\n\n"));
            }
        }
        out.push_str(line);
        out.push('\n');
        for (anchor, comment) in after {
            if line.starts_with(anchor) {
                out.push_str(&format!("\n{comment}\n"));
            }
        }
    }
    out
}

#[test]
fn the_lecture_notes_with_their_symbols_declared_verify_the_rolling_and_sliding_accelerations() {
    let text = declared(&fixture("handout_notes.md"));
    let dir = std::env::temp_dir().join(format!("rigor-lint-decl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let doc = dir.join("handout_notes_declared.md");
    std::fs::write(&doc, &text).expect("written");
    let (out, err, code) = lint(&[&doc.display().to_string()]);
    let _ = std::fs::remove_dir_all(&dir);
    let out = out.replace(&doc.display().to_string(), "handout_notes_declared.md");
    assert_eq!(code, 0, "no chain of the notes is false:\n{out}{err}");
    assert!(
        out.ends_with("\nchains: 58, verified: 14, defined: 6, failed: 0, needs context: 38\n"),
        "{out}"
    );
    let has = |at: &str, what: &str| {
        let line = format!("handout_notes_declared.md:{at}: {what}");
        assert!(out.contains(&line), "{line}\n{out}");
    };
    // Verified with nothing assumed (the lines it rests on named, if any).
    let plain = |at: &str| {
        let head = format!("handout_notes_declared.md:{at}: verified");
        let line = out.lines().find(|l| l.starts_with(&head));
        assert!(
            line.is_some_and(|l| l == head
                || (l.starts_with(&format!("{head} from line")) && !l.contains("assuming"))),
            "{head}\n{out}"
        );
    };
    // N = mg cos(beta); the rolling acceleration; the sliding x'' and theta''.
    for needle in [
        "$$N = mg",
        "$$\\ddot{x} = -\\frac{g\\sin\\beta}",
        "$$\\ddot{x} = g \\left(\\mu",
        "$$\\ddot{\\theta} = \\frac{R\\mu",
    ] {
        plain(&format!("{}:3", line_of(&text, needle)));
    }
    // The centre of percussion: `a b = I_G/m` verified from the condition before it,
    // `= k_G^2` needs the definition of k_G.
    plain(&place(&text, "$$a b = ", "a b"));
    has(
        &place(&text, "$$a b = ", "\\frac{I_G}{m}"),
        "needs context: this step brings in k_G",
    );
    insta::assert_snapshot!(format!("{out}\n{err}"));
}

#[test]
fn the_lecture_notes_in_latex_never_fail_and_verify_the_same_chains() {
    let doc = "tests/lint/handout_notes.tex";
    let text = fixture("handout_notes.tex");
    let (out, err, code) = lint_steadily(doc);
    assert_eq!(code, 0, "no chain of the notes is false:\n{out}{err}");
    assert!(
        out.ends_with("\nchains: 47, verified: 13, defined: 7, failed: 0, needs context: 27\n"),
        "{out}"
    );
    let has = |at: &str, what: &str| {
        let line = format!("{doc}:{at}: {what}");
        assert!(out.contains(&line), "{line}\n{out}");
    };
    // `equation` (with `\label`), `align*` (a chain a line, labels left out),
    // `equation*` and `\[ … \]`, with `%` comments between them and `$…$` in the prose
    // read in a scope of their own. `M = I_O \ddot{\theta}` is a definition (M is new),
    // reported as one; the rest are checked.
    has(
        &place(&text, "M = I_O \\ddot{\\theta} \\label", "M"),
        "defines M",
    );
    for (needle, part) in [
        ("= \\int \\left((x+a)^2", "\\int"),
        ("I_G &= \\int_{-L/2}^{L/2}", "I_G"),
        ("I_O &= \\frac{mL^2}{12}", "I_O"),
        ("dm = m\\frac{dA}{A}", "m\\frac{2\\pi"),
        ("I_G = \\int_0^R", "\\frac{2m}{R^2} \\int"),
        ("N = mg \\cos \\beta", "N"),
        ("\\ddot{x} = -\\frac{g \\sin \\beta}", "\\ddot{x}"),
        ("\\ddot{x} &= g \\left(\\mu", "\\ddot{x}"),
        ("\\ddot{\\theta} &= \\frac{R \\mu m g", "\\ddot{\\theta}"),
        ("\\ddot{y}_G &= \\ddot{\\theta}", "\\ddot{y}_G"),
        ("a b = \\frac{I_G}{m}", "a b"),
    ] {
        has(&place(&text, needle, part), "verified");
    }
    // The trapdoor with no signs declared: see the Markdown test.
    for (needle, part) in [
        (
            "\\qquad \\rightarrow \\qquad \\ddot{\\theta}",
            "\\ddot{\\theta} = -",
        ),
        ("R = \\frac{mg}{4}", "R"),
    ] {
        has(
            &place(&text, needle, part),
            "needs context: not verified: this step assumes L != 0",
        );
    }
    // The parallel axis theorem's step into I_G and the disk's first step rest on prose.
    has(
        &place(&text, "= \\int (x^2 + y^2)", "\\int"),
        "needs context: it integrates over dm",
    );
    has(
        &place(&text, "dm = m\\frac{dA}{A}", "dm"),
        "needs context: this step brings in r, R",
    );
    has(
        &place(&text, "a b = \\frac{I_G}{m}", "\\frac{I_G}{m}"),
        "needs context: this step brings in k_G",
    );
    insta::assert_snapshot!(format!("{out}\n{err}"));
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
        out.ends_with("chains: 11, verified: 1, defined: 1, failed: 0, needs context: 9\n"),
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
    assert!(out.contains("scopes_notes.md:27:3: defines R"), "{out}");
    // The one slip fails, reported at its link.
    assert!(out.contains("scopes_notes.md:31:83: FAILED"), "{out}");
    assert!(err.contains("31:83"), "{err}");
    assert!(
        out.ends_with("chains: 13, verified: 6, defined: 2, failed: 1, needs context: 4\n"),
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

/// Several documents linted together (their scopes in one queue, most chains first)
/// give each document the report it has alone, in the order given.
#[test]
fn documents_linted_together_are_reported_as_each_alone() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let names = [
        "tests/lint/rod_notes.md",
        "tests/lint/handout_notes.tex",
        "tests/lint/scopes_notes.md",
        "tests/lint/readings_given_value.md",
        "tests/lint/corpus/sections_carry.md",
    ];
    let docs: Vec<rigor::lint::Document> = names
        .iter()
        .map(|n| rigor::lint::Document {
            name: n.to_string(),
            text: std::fs::read_to_string(root.join(n)).expect("the fixture reads"),
            kind: rigor::lint::DocKind::of(n),
        })
        .collect();
    let opts = crate::no_budget();
    let together = rigor::lint::lint_all(&docs, &opts);
    assert_eq!(together.len(), docs.len());
    for (d, r) in docs.iter().zip(&together) {
        let alone = rigor::lint::lint(&d.name, &d.text, d.kind, &opts);
        assert!(!alone.chains.is_empty(), "{}: no chains", d.name);
        assert_eq!(format!("{r:?}"), format!("{alone:?}"), "{}", d.name);
    }
}
