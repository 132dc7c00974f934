//! Checker fixtures: `tests/check/pass` must verify, every `tests/check/fail` file must
//! fail with the diagnostic in its snapshot, and every handout derivation must verify.

use rigor::check::{FileReport, Status};
use rigor::files::check_paths;
use std::path::{Path, PathBuf};

fn check_one(path: &Path) -> FileReport {
    let mut reports = check_paths(&[path.to_path_buf()], &crate::no_budget());
    assert_eq!(reports.len(), 1, "one report per file");
    reports.remove(0)
}

/// The diagnostics as the terminal shows them, with the file name only.
fn rendered(r: &FileReport, path: &Path) -> String {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    r.diagnostics
        .iter()
        .map(|d| rigor::diag::render(d, &name, &r.source))
        .collect()
}

#[test]
fn passing_fixtures_verify() {
    insta::glob!("..", "check/pass/*.deriv", |path| {
        let r = check_one(path);
        assert!(
            r.ok(),
            "{} should verify:\n{}",
            path.display(),
            rendered(&r, path)
        );
        assert!(r.links() > 0 || r.claims.is_empty(), "claims are checked");
        insta::assert_snapshot!(justified(&r));
    });
}

#[test]
fn failing_fixtures_fail_with_their_diagnostic() {
    insta::glob!("..", "check/fail/*.deriv", |path| {
        let r = check_one(path);
        assert!(!r.ok(), "{} should not verify", path.display());
        let text = rendered(&r, path);
        assert!(!text.is_empty(), "a failure comes with a diagnostic");
        // The first line of the fixture says what the mistake is and where.
        let first = r.source.lines().next().unwrap_or_default().to_string();
        insta::assert_snapshot!(format!("{first}\n\n{text}"));
    });
}

fn justification(s: &Status) -> String {
    match s {
        Status::Verified {
            how,
            side_conditions,
        } => {
            let how = how.to_string();
            if side_conditions.is_empty() {
                how
            } else {
                format!("{how}; assuming {}", side_conditions.join(", "))
            }
        }
        Status::Failed => "FAILED".into(),
        Status::Undecided => "UNDECIDED".into(),
        Status::Error => "ERROR".into(),
        Status::NotChecked => "NOT CHECKED".into(),
    }
}

/// Each claim's links and how each was justified.
fn justified(r: &FileReport) -> String {
    let mut out = String::new();
    for c in &r.claims {
        let label = c
            .label
            .clone()
            .map_or_else(|| "(unlabelled)".into(), |l| format!("[{l}]"));
        out.push_str(&format!("{label} line {}\n", c.line));
        for l in &c.links {
            out.push_str(&format!(
                "    {} {} {}    -- {}\n",
                l.lhs.as_deref().unwrap_or("?"),
                l.op,
                l.rhs.as_deref().unwrap_or("?"),
                justification(&l.status)
            ));
        }
    }
    out
}

#[test]
fn handout_derivations_verify() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("derivations");
    insta::glob!("../..", "derivations/*.deriv", |path| {
        let r = check_one(path);
        assert!(
            r.ok(),
            "{} must verify:\n{}",
            dir.display(),
            rendered(&r, path)
        );
        let out = justified(&r);
        insta::assert_snapshot!(out);
    });
}

#[test]
fn results_come_in_a_stable_order() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("derivations");
    let a: Vec<String> = check_paths(std::slice::from_ref(&dir), &crate::no_budget())
        .into_iter()
        .map(|r| r.path)
        .collect();
    let mut sorted = a.clone();
    sorted.sort();
    assert_eq!(a, sorted);
    assert!(a.len() >= 9);
}

/// `% expect E0305 line 11: …` on a fixture's first line: the code and line of the
/// first error it must produce.
fn expectation(first_line: &str) -> Option<(String, usize)> {
    let rest = first_line.strip_prefix("% expect ")?;
    let (head, _) = rest.split_once(':')?;
    let mut words = head.split_whitespace();
    let code = words.next()?.to_string();
    (words.next()? == "line").then_some(())?;
    let line = words.next()?.parse().ok()?;
    Some((code, line))
}

#[test]
fn fixtures_with_an_expectation_fail_with_that_code_on_that_line_and_only_there() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/check/fail");
    let mut checked = 0;
    let mut entries: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("the fail fixtures")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "deriv"))
        .collect();
    entries.sort();
    for path in entries {
        let text = std::fs::read_to_string(&path).expect("readable fixture");
        let first_line = text.lines().next().unwrap_or_default();
        let Some((code, line)) = expectation(first_line) else {
            panic!(
                "{}: the first line must be `% expect CODE line N: …`",
                path.display()
            );
        };
        let r = check_one(&path);
        let first = r
            .diagnostics
            .iter()
            .find(|d| d.severity == rigor::diag::Severity::Error)
            .unwrap_or_else(|| panic!("{}: no error reported", path.display()));
        let at = first.primary.as_ref().map_or(0, |(span, _)| {
            r.source[..span.start.min(r.source.len())]
                .matches('\n')
                .count()
                + 1
        });
        assert_eq!(
            (first.code.as_str(), at),
            (code.as_str(), line),
            "{}: first error `{}`",
            path.display(),
            first.message
        );
        // One mistake, one error: what follows from it is a note, not a second error.
        let errors: Vec<&str> = r
            .diagnostics
            .iter()
            .filter(|d| d.severity == rigor::diag::Severity::Error)
            .map(|d| d.message.as_str())
            .collect();
        assert_eq!(errors.len(), 1, "{}: {errors:?}", path.display());
        checked += 1;
    }
    assert!(
        checked >= 15,
        "the soundness fixtures carry expectations ({checked})"
    );
}

#[test]
fn expectation_lines_parse() {
    assert_eq!(
        expectation("% expect E0305 line 11: a division"),
        Some(("E0305".into(), 11))
    );
    assert_eq!(expectation("% mistake: no code"), None);
}

#[test]
fn mixed_scales_in_one_sum_are_a_warning_not_a_failure() {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/check/pass/units_mixed_scales.deriv");
    let r = check_one(&path);
    assert!(r.ok());
    let warnings: Vec<&str> = r.diagnostics.iter().map(|d| d.code.as_str()).collect();
    assert_eq!(warnings, ["W0401", "W0401"]);
}

/// The error-severity codes and the `N0205` notes of a fixture in `tests/check/fail/`.
fn errors_and_notes(name: &str) -> (Vec<&'static str>, usize, FileReport) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/check/fail")
        .join(name);
    let r = check_one(&path);
    let errors = r
        .diagnostics
        .iter()
        .filter(|d| d.severity == rigor::diag::Severity::Error)
        .map(|d| d.code.as_str())
        .collect();
    let notes = r
        .diagnostics
        .iter()
        .filter(|d| d.code.as_str() == "N0205" && d.severity == rigor::diag::Severity::Note)
        .count();
    (errors, notes, r)
}

#[test]
fn one_mistake_is_one_error_and_what_cites_it_is_not_checked() {
    // A failed claim cited by `by [..]`, and through it a second claim: notes, and no
    // "unknown label" (which would be an input error, exit status 2).
    let (errors, notes, r) = errors_and_notes("cascade_by_failed_claim.deriv");
    assert_eq!(errors, ["E0301"], "{:?}", r.diagnostics);
    assert_eq!((notes, r.not_checked(), r.failed()), (2, 2, 1));
    assert!(!r.input_error);
    // An undeclared symbol in a given: reported once; the claim citing it is not checked.
    let (errors, notes, r) = errors_and_notes("cascade_given_undeclared.deriv");
    assert_eq!(errors, ["E0201"], "{:?}", r.diagnostics);
    assert_eq!((notes, r.not_checked()), (1, 1));
    // A failed import: the claim citing the label it should have brought in is not a
    // second error.
    let (errors, notes, _) = errors_and_notes("kind_use_missing_file.deriv");
    assert_eq!((errors, notes), (vec!["E0206"], 1));
    // The odd line of a chain: one error, on that line (8), and the next link is not
    // checked.
    let (errors, _, r) = errors_and_notes("chain_odd_one_out.deriv");
    assert_eq!(errors, ["E0301"]);
    let d = &r.diagnostics[0];
    assert!(
        d.message.contains("the chain holds without it"),
        "{}",
        d.message
    );
    let line = d
        .primary
        .as_ref()
        .map(|(s, _)| r.source[..s.start].lines().count());
    assert_eq!(line, Some(8));
    assert_eq!((r.failed(), r.not_checked()), (1, 1));
}

#[test]
fn two_independent_mistakes_stay_two_errors_and_a_consequence_becomes_a_note() {
    let check = |text: &str| {
        rigor::check_source(
            "two.deriv",
            text,
            &crate::no_budget(),
            &rigor::check::MemoryResolver::new(),
        )
    };
    let errors = |r: &FileReport| {
        r.diagnostics
            .iter()
            .filter(|d| d.severity == rigor::diag::Severity::Error)
            .count()
    };
    let base = "symbols m L > 0\nbody rod_end: dm = m/L dy, y from 0 to L/2\nlet I_O = int(y^2, rod_end)\nclaim [IO] I_O = int(y^2 m/L, y, 0, L)\n  = m L^2/3\n";
    // A later step that holds with I_O = m L^2/3 is a consequence of the first mistake.
    let r = check(&format!("{base}claim [twice] 2 I_O = 2 m L^2/3\n"));
    assert_eq!(errors(&r), 1, "{:?}", r.diagnostics);
    assert!(
        r.diagnostics.iter().any(|d| d.code.as_str() == "N0206"),
        "{:?}",
        r.diagnostics
    );
    assert!(!r.ok());
    // A slip that has nothing to do with I_O is a second mistake.
    let r = check(&format!(
        "{base}claim [slip] m L^2/12 + m L^2/4 = m L^2/6\n"
    ));
    assert_eq!(errors(&r), 2, "{:?}", r.diagnostics);
    assert!(!r.diagnostics.iter().any(|d| d.code.as_str() == "N0206"));
}

/// After a step that did not check, a later step undecided on all the facts in scope
/// is "not checked" (N0205) only when the failed step could have given it a fact: an
/// equation whose quantities a chain of facts ties to the later step's. A failed `~=`
/// brings no fact, nor does a failed equation about other quantities; the later step
/// then keeps its own "not verified" (E0302).
#[test]
fn only_a_step_that_could_have_given_a_fact_makes_a_later_one_not_checked() {
    let codes = |text: &str| -> Vec<(String, usize)> {
        let r = rigor::check_source(
            "dep.deriv",
            text,
            &crate::no_budget(),
            &rigor::check::MemoryResolver::new(),
        );
        r.diagnostics
            .iter()
            .filter_map(|d| {
                let (span, _) = d.primary.as_ref()?;
                let line = text[..span.start].matches('\n').count() + 1;
                Some((d.code.as_str().to_string(), line))
            })
            .collect()
    };
    let owned = |v: &[(&str, usize)]| -> Vec<(String, usize)> {
        v.iter().map(|(c, l)| (c.to_string(), *l)).collect()
    };
    // a^3 = b^3 ties a and b, but rigor cannot solve it: `a = b` is not verified.
    let head = "symbols a b c h\nsymbols theta\nsmall theta\ngiven [cube] a^3 = b^3\n";
    // An undecided `~=` (line 5) gives no fact: line 6 is undecided on its own.
    let approx = format!("{head}claim [pole] cos(theta)/theta ~= 1\nclaim [same] a = b\n");
    assert_eq!(codes(&approx), owned(&[("E0302", 5), ("E0302", 6)]));
    // A false equation about h alone (nothing ties h to a or b) gives none either.
    let other = format!("{head}claim [h] h = h + cos(h) - cos(h) + h^2\nclaim [same] a = b\n");
    assert_eq!(codes(&other), owned(&[("E0301", 5), ("E0302", 6)]));
    // A failed equation about a might have been the missing fact: not checked.
    let tied = format!("{head}claim [ac] a = c + cos(c)\nclaim [same] a = b\n");
    assert_eq!(codes(&tied), owned(&[("E0302", 5), ("N0205", 6)]));
    // Nor through a fact that ties h to b.
    let chain =
        format!("{head}given [hb] h = b + c\nclaim [h] h = c + cos(c)\nclaim [same] a = b\n");
    assert_eq!(codes(&chain), owned(&[("E0302", 6), ("N0205", 7)]));
}

/// The kind of mistake travels as data, from where the checker finds it: on the
/// failing link, on its diagnostic, and into mark's gradebook kind. The words of the
/// message play no part (a symbol named `power` or `missing` changes nothing).
#[test]
fn a_failed_link_carries_its_kind_of_mistake() {
    use rigor::diag::Mistake;
    let cases: &[(&str, Mistake, &str)] = &[
        // A whole side with the wrong sign, and one term with it.
        (
            "symbols a b > 0\nclaim a - b = b - a\n",
            Mistake::Sign,
            "sign",
        ),
        (
            "symbols a power > 0\nclaim a + power = a - power\n",
            Mistake::Sign,
            "sign",
        ),
        // After the facts, every term is a multiple of g m sin(beta): a factor between
        // the sides as reduced is not what was written; the term with its sign is.
        (
            "symbols m g > 0\nsymbols beta\ntime x\nunknowns F\n\
             given [Fx] m g sin(beta) - F = m x''\ngiven [F] F = 2/5 m x''\n\
             claim m g sin(beta) = m x'' - 2/5 m x'' by [Fx], [F]\n",
            Mistake::Sign,
            "sign",
        ),
        (
            "symbols m L > 0\nclaim m L^2/6 = m L^2/12\n",
            Mistake::Factor,
            "factor",
        ),
        (
            "symbols a b > 0\nclaim a + b = a + 2 b\n",
            Mistake::Factor,
            "factor",
        ),
        (
            "symbols x y > 0\nclaim x^2 + y = x^2 + y^2\n",
            Mistake::Power,
            "power",
        ),
        (
            "symbols m L > 0\nclaim m L^2 = m L^3\n",
            Mistake::Power,
            "power",
        ),
        (
            "symbols m d missing > 0\nsymbols I_G\nclaim I_G = I_G + m d^2\n",
            Mistake::MissingTerm,
            "missing_term",
        ),
        (
            "symbols m g > 0\nunknowns F\nclaim F = m g\n",
            Mistake::MissingFact,
            "missing_fact",
        ),
        (
            "symbols m g R > 0\nsymbols 0 < beta < pi/2\nsymbols F\ntime x theta\n\
             given [Fx] m x'' = m g sin(beta) - F\ngiven [MG] (m R^2/2) theta'' = F R\n\
             constraint [noslip] x = R theta\n\
             claim [acc] x'' = 2 g sin(beta)/3 by [Fx], [MG], [noslip]\n",
            Mistake::DeclaredGiven("F".into()),
            "undecided",
        ),
    ];
    for (src, mistake, kind) in cases {
        let r = rigor::check_source(
            "k.deriv",
            src,
            &crate::no_budget(),
            &rigor::MemoryResolver::new(),
        );
        let link = r
            .claims
            .iter()
            .flat_map(|c| &c.links)
            .find(|l| !l.status.is_verified())
            .unwrap_or_else(|| panic!("{src}: every link verified"));
        assert_eq!(
            link.mistake.as_ref(),
            Some(mistake),
            "{src}: {:?}",
            r.diagnostics
        );
        let d = r
            .diagnostics
            .iter()
            .find(|d| d.severity == rigor::diag::Severity::Error)
            .unwrap_or_else(|| panic!("{src}: no error"));
        assert_eq!(d.mistake.as_ref(), Some(mistake), "{src}: {d:?}");
        assert_eq!(rigor::mark::kind(d), *kind, "{src}: {d:?}");
    }
}

/// `stop_at_determined_given` (what `rigor lint` checks with while it looks for the
/// quantities to solve for): the check stops at the statement whose failure names a
/// `symbols` quantity the facts determine, and checks nothing after it; without it, the
/// statements after it are checked.
#[test]
fn a_check_may_stop_where_the_facts_determine_a_given_quantity() {
    let src = concat!(
        "symbols m g L I_A\ntime theta\n",
        "given $$ -mg\\frac{L}{2} = I_A \\ddot{\\theta} $$\n",
        "given $$ I_A \\ddot{\\theta} = \\frac{mL^2}{3} \\ddot{\\theta} $$\n",
        "symbols R\ntime y_G\n",
        "given $$ R - mg = m \\ddot{y}_G $$\n",
        "given $$ \\ddot{y}_G = \\ddot{\\theta} \\frac{L}{2} $$\n",
        "claim $$ R = \\frac{mg}{2} $$\n",
        "claim $$ g = 2 g $$\n",
        "claim $$ L = L $$\n",
    );
    let determined = |r: &rigor::check::FileReport| {
        r.diagnostics
            .iter()
            .filter(|d| matches!(d.mistake, Some(rigor::diag::Mistake::DeclaredGiven(_))))
            .count()
    };
    let full = rigor::check_source(
        "s.deriv",
        src,
        &crate::no_budget(),
        &rigor::MemoryResolver::new(),
    );
    assert_eq!(determined(&full), 1, "{:?}", full.diagnostics);
    assert_eq!(full.claims.len(), 3, "{:?}", full.claims);
    let opts = rigor::Options {
        stop_at_determined_given: true,
        ..crate::no_budget()
    };
    let stopped = rigor::check_source("s.deriv", src, &opts, &rigor::MemoryResolver::new());
    assert_eq!(determined(&stopped), 1, "{:?}", stopped.diagnostics);
    assert_eq!(stopped.claims.len(), 2, "{:?}", stopped.claims);
}

/// `verdicts_only` (what `rigor lint` checks with when it asks whether a stated relation
/// forces its sides to zero): the same links hold and fail as in a full check, and a
/// failing `=` link is "not verified" with no counterexample sought.
#[test]
fn verdicts_only_keeps_every_verdict_and_drops_the_explanations() {
    let src = concat!(
        "symbols m g h > 0\n",
        "symbols v\n",
        "given $$ \\frac{1}{2} m v^2 = m g h $$\n",
        "claim $$ v^2 = 2 g h $$\n",
        "claim $$ v^2 = 3 g h $$\n",
        "claim $$ (g + h)^2 = g^2 + 2 g h + h^2 = g^2 + h^2 $$\n",
    );
    let check = |opts: &rigor::Options| {
        rigor::check_source("v.deriv", src, opts, &rigor::MemoryResolver::new())
    };
    let full = check(&crate::no_budget());
    let lean = check(&rigor::Options {
        verdicts_only: true,
        ..crate::no_budget()
    });
    let verdicts = |r: &rigor::check::FileReport| -> Vec<Vec<bool>> {
        r.claims
            .iter()
            .map(|c| c.links.iter().map(|l| l.status.is_verified()).collect())
            .collect()
    };
    assert_eq!(
        verdicts(&full),
        vec![vec![true], vec![false], vec![true, false]],
        "{:?}",
        full.diagnostics
    );
    assert_eq!(verdicts(&lean), verdicts(&full), "{:?}", lean.diagnostics);
    // The full check refutes the two false links, with a counterexample.
    let refuted = |r: &rigor::check::FileReport| {
        r.diagnostics
            .iter()
            .filter(|d| d.code == rigor::diag::Code::Refuted)
            .count()
    };
    assert_eq!(refuted(&full), 2, "{:?}", full.diagnostics);
    assert_eq!(refuted(&lean), 0, "{:?}", lean.diagnostics);
    let errors: Vec<_> = lean
        .diagnostics
        .iter()
        .filter(|d| d.severity == rigor::diag::Severity::Error)
        .collect();
    assert_eq!(errors.len(), 2, "{errors:?}");
    assert!(
        errors
            .iter()
            .all(|d| d.code == rigor::diag::Code::NotVerified && d.notes.is_empty()),
        "{errors:?}"
    );
}
