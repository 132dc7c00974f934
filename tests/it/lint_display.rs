//! `rigor lint` reads display maths as authors write it (issue 30): `align`, `aligned`,
//! `split`, `alignat`, `eqnarray`, `gather`, `multline`, `equation`, `displaymath`,
//! `\[ \]` and `$$ $$` in LaTeX; `$$`, `\[ \]`, bare environments, MyST `{math}` blocks
//! and roles and inline `$…$` in Markdown. Each chain of `tests/lint/display_forms.tex`
//! and `.md` has its verdict asserted at its line and column, the planted slips among
//! them; the summary counts definitions apart from what was checked.

use std::path::Path;
use std::process::Command;

fn lint(args: &[&str]) -> (String, String, i32) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Command::new(env!("CARGO_BIN_EXE_rigor"))
        .arg("lint")
        .args(args)
        .current_dir(root)
        .output()
        .expect("rigor runs");
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        out.status.code().unwrap_or(-1),
    )
}

/// Every chain of `note` as `line:column verdict` (`verified`, `defines X`, `FAILED`,
/// `needs context`), in the report's order, and the summary line.
fn verdicts(note: &str) -> (Vec<String>, String, String, i32) {
    let (out, err, code) = lint(&[note]);
    let mut got = Vec::new();
    for line in out.lines() {
        let Some(rest) = line.strip_prefix(note).and_then(|r| r.strip_prefix(':')) else {
            continue;
        };
        let mut parts = rest.splitn(3, ':');
        let (Some(l), Some(c), Some(v)) = (parts.next(), parts.next(), parts.next()) else {
            continue;
        };
        let v = v.trim_start();
        let kind = if let Some(d) = v.strip_prefix("defines ") {
            format!("defines {d}")
        } else {
            ["verified", "FAILED", "needs context"]
                .into_iter()
                .find(|k| v.starts_with(k))
                .unwrap_or("?")
                .to_string()
        };
        got.push(format!("{l}:{c} {kind}"));
    }
    let summary = out.lines().last().unwrap_or_default().to_string();
    (got, summary, format!("{out}\n{err}"), code)
}

#[test]
fn every_latex_display_environment_is_read_with_one_link_per_row() {
    let (got, summary, text, code) = verdicts("tests/lint/display_forms.tex");
    let want = [
        // `equation` with a trailing full stop and `\label`: a definition.
        "11:3 defines I_G",
        // `$d = L/2$` in the prose: an inline definition.
        "13:51 defines d",
        // `align*` over three rows, `\tag` dropped: one chain, its first link a
        // definition and the rest checked.
        "15:3 verified",
        // `align` with `\nonumber`: a row with its own left side is its own chain; the
        // slip (5/2 for 3/2) is reported on its own row.
        "22:3 defines J_G",
        "25:8 FAILED",
        // `gather*`: each row its own chain, the second a slip.
        "30:3 verified",
        "31:3 FAILED",
        // `eqnarray` (`&=&`), `multline` (a row starting with `+`), `split` in
        // `equation`, `alignat` with a text column.
        "36:3 verified",
        "42:3 verified",
        "49:3 verified",
        "56:3 verified",
        "57:3 verified",
        // `displaymath`; `aligned` inside `$$` with row-end punctuation, `\mathrm{d}`
        // and an evaluation bar; `\boxed` around `\left. … \right|_0^h`.
        "62:3 verified",
        "65:3 verified",
        "66:3 verified",
        "68:12 verified",
        // A double integral with `\!` and `\rho{}`, then a slip in the same form.
        "73:3 verified",
        "77:3 FAILED",
        // `K_\mathrm{rot}`, `y_{\text{CM}}`; a run of `~` sets two relations apart.
        "81:4 defines K_rot",
        "82:4 defines y_CM",
        "82:39 defines x_CM",
        // A vector is not a scalar.
        "83:4 needs context",
        // Before an arrow, a premise the notes impose; after it, steps checked with it.
        "84:4 needs context",
        "84:24 verified",
        "84:43 verified",
        // `\theta \ll 1` in the prose makes theta small: sin θ ≈ θ holds to first
        // order, cos θ ≈ 1 − θ does not.
        "88:4 verified",
        "88:38 FAILED",
        // With nothing small, an approximation needs context and never fails.
        "91:4 needs context",
    ];
    assert_eq!(got, want, "{text}");
    assert_eq!(
        summary, "chains: 28, verified: 15, defined: 6, failed: 4, needs context: 3",
        "{text}"
    );
    assert_eq!(code, 1, "{text}");
    // Each slip's diagnostic points at its own row, with the source line shown.
    for at in [
        "display_forms.tex:25:8",
        "display_forms.tex:31:3",
        "display_forms.tex:77:3",
    ] {
        assert!(
            text.contains(&format!("--> tests/lint/{at}")),
            "{at}\n{text}"
        );
    }
    assert!(text.contains("25 |       &= \\frac{5}{2} m R^2"), "{text}");
}

#[test]
fn markdown_reads_dollars_brackets_myst_and_inline_maths() {
    let (got, summary, text, code) = verdicts("tests/lint/display_forms.md");
    let want = [
        // `$$` around `aligned`, a trailing comma.
        "12:1 verified",
        // `\[ \]` as MathJax reads them: a true identity and a slip.
        "20:3 verified",
        "24:3 FAILED",
        // A bare `align` with `\label`; the division by L - h is said.
        "30:3 verified",
        // MyST blocks: the `:label:` line is not maths.
        "38:1 defines K_tot",
        "42:1 verified",
        // A `{math}` role and inline `$…$`: a chain in prose, a slip in prose; the
        // condition `$h = 0$` is no chain, and code is never maths.
        "47:33 verified",
        "48:36 verified",
        "49:19 FAILED",
        // `\mathrm{d}x`, and an evaluation bar whose value is half what it should be.
        "60:3 verified",
        "62:3 FAILED",
    ];
    assert_eq!(got, want, "{text}");
    assert_eq!(
        summary, "chains: 11, verified: 7, defined: 1, failed: 3, needs context: 0",
        "{text}"
    );
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("30:3: verified, assuming h - L != 0"),
        "{text}"
    );
}

#[test]
fn json_counts_definitions_apart_and_names_the_symbol() {
    let (out, err, code) = lint(&["--format", "json", "tests/lint/display_forms.tex"]);
    assert_eq!(code, 1, "{out}{err}");
    let v: serde_json::Value = serde_json::from_str(out.trim()).expect("json");
    assert_eq!(v["defined"], 6, "{out}");
    assert_eq!(v["verified"], 15, "{out}");
    assert_eq!(v["failed"], 4, "{out}");
    assert_eq!(v["needs_context"], 3, "{out}");
    let first = &v["chains"][0];
    assert_eq!(first["verdict"], "defined", "{out}");
    assert_eq!(first["defines"], "I_G", "{out}");
}

#[test]
fn a_wrong_centroidal_value_is_a_definition_never_verified() {
    // The example: I_G = mL^2/3 for a rod about its centre is wrong, and
    // stated once it defines I_G; it must never be counted as checked.
    let dir = std::env::temp_dir().join(format!("rigor-lint-defines-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let doc = dir.join("rod.md");
    std::fs::write(
        &doc,
        "# Rod\n\n<!-- rigor: symbols m L > 0 -->\n\n$$I_G = \\frac{mL^2}{3}$$\n",
    )
    .expect("write");
    let (out, err, code) = lint(&[doc.to_str().unwrap_or_default()]);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains(":5:3: defines I_G\n"), "{out}");
    assert!(
        out.ends_with("chains: 1, verified: 0, defined: 1, failed: 0, needs context: 0\n"),
        "{out}"
    );
}

/// The notes of `tests/lint/corpus/`: our own notes in the forms public lecture notes
/// use (LaTeX chapters, Markdown summaries, Obsidian bullets, MyST, MathJax `\[ \]`),
/// none written for rigor (no `rigor:` comment), with nine slips planted and the
/// adversarial cases: two wrong premises under one heading, a wrong definition, vectors,
/// approximations with nothing declared small.
const CORPUS: [&str; 10] = [
    "tests/lint/corpus/adversarial.tex",
    "tests/lint/corpus/impact.tex",
    "tests/lint/corpus/inertia.md",
    "tests/lint/corpus/kinetics.md",
    "tests/lint/corpus/pendulum.tex",
    "tests/lint/corpus/pendulum_obsidian.md",
    "tests/lint/corpus/rolling_myst.md",
    "tests/lint/corpus/sections_carry.md",
    "tests/lint/corpus/sections_carry.tex",
    "tests/lint/corpus/two_slips.md",
];

#[test]
fn the_corpus_of_notes_fails_only_its_slips_and_needs_context_for_at_most_two_in_five() {
    let (mut chains, mut needs) = (0, 0);
    let mut failed = Vec::new();
    for note in CORPUS {
        let (got, summary, text, _) = verdicts(note);
        chains += got.len();
        needs += got.iter().filter(|v| v.ends_with("needs context")).count();
        failed.extend(
            got.iter()
                .filter(|v| v.ends_with("FAILED"))
                .map(|v| format!("{note}:{}", v.split(':').next().unwrap_or_default())),
        );
        assert!(
            summary.starts_with(&format!("chains: {}", got.len())),
            "{text}"
        );
    }
    // Every failure is a planted slip, on its line: an inverted restitution power, the
    // plate's corner distance, a radius of gyration without its root, the pin reaction
    // (mg/2 for mg/4: with the stated angular acceleration it would make g zero), the
    // disk's pendulum frequency inverted, the rod's pendulum frequency inverted, the
    // disk's rolling acceleration, a fraction inverted after an arrow, the rod's kinetic
    // energy doubled (with I_O from an earlier section).
    assert_eq!(
        failed,
        [
            "tests/lint/corpus/impact.tex:43",
            "tests/lint/corpus/inertia.md:50",
            "tests/lint/corpus/inertia.md:64",
            "tests/lint/corpus/kinetics.md:41",
            "tests/lint/corpus/pendulum.tex:45",
            "tests/lint/corpus/pendulum_obsidian.md:41",
            "tests/lint/corpus/rolling_myst.md:54",
            "tests/lint/corpus/sections_carry.md:58",
            "tests/lint/corpus/sections_carry.tex:46",
        ]
    );
    // No false line is verified: what follows only from two slips under one heading
    // (`4 a = 3 a`, `3 a = 2 a`) needs context, and so do the slips themselves.
    for (note, lines) in [
        (
            "tests/lint/corpus/adversarial.tex",
            ["21:3", "25:3", "29:3"],
        ),
        ("tests/lint/corpus/two_slips.md", ["9:4", "13:4", "13:4"]),
    ] {
        let (got, _, text, _) = verdicts(note);
        for at in lines {
            assert!(got.contains(&format!("{at} needs context")), "{at}: {text}");
        }
    }
    // `\sqrt{R^2/2} = R/\sqrt{2}` holds for R > 0, which the notes never say: it needs
    // that sign, and the report gives the comment that declares it.
    let (out, _, _) = lint(&["tests/lint/corpus/inertia.md"]);
    assert!(
        out.contains("inertia.md:58:1: needs context: this holds where R > 0, which the notes do not declare; `rigor: symbols R > 0` in a comment makes it checkable"),
        "{out}"
    );
    // `1 - \cos\theta \approx \theta^2/2` is a second-order statement, with `theta`
    // kept to the first order by `\theta \ll 1`: at that order `\theta^2/3` would pass
    // too, so it needs the order, which the JSON report names.
    let (out, _, _) = lint(&["--format", "json", "tests/lint/corpus/pendulum.tex"]);
    let v: serde_json::Value = serde_json::from_str(out.trim()).expect("json");
    let last = v["chains"]
        .as_array()
        .and_then(|c| c.last())
        .cloned()
        .unwrap_or_default();
    assert_eq!(last["line"], 53, "{out}");
    assert_eq!(last["verdict"], "needs context", "{out}");
    assert_eq!(last["comment"], "rigor: small theta to order 2", "{out}");
    assert_eq!(chains, 105);
    assert!(needs * 5 <= chains * 2, "{needs} of {chains} need context");
}

#[test]
fn json_and_github_give_each_chain_that_needs_context_its_reason_and_the_comment_that_helps() {
    let (out, err, _) = lint(&["--format", "json", "tests/lint/display_forms.tex"]);
    let v: serde_json::Value = serde_json::from_str(out.trim()).expect("json");
    let needs: Vec<(u64, String, Option<String>)> = v["chains"]
        .as_array()
        .into_iter()
        .flatten()
        .filter(|c| c["verdict"] == "needs context")
        .map(|c| {
            (
                c["line"].as_u64().unwrap_or_default(),
                c["reason"].as_str().unwrap_or_default().to_string(),
                c["comment"].as_str().map(String::from),
            )
        })
        .collect();
    assert_eq!(
        needs,
        [
            (83, "unread".to_string(), None),
            (84, "imposed".to_string(), None),
            (
                91,
                "approximation".to_string(),
                Some("rigor: small phi".to_string())
            ),
        ],
        "{out}{err}"
    );
    // The sign a true chain needs, as a notice on its line with the comment to add.
    let (out, _, code) = lint(&["--format", "github", "tests/lint/corpus/inertia.md"]);
    assert_eq!(code, 1, "{out}");
    let notices: Vec<&str> = out.lines().filter(|l| l.starts_with("::notice")).collect();
    assert_eq!(notices.len(), 1, "{out}");
    assert!(
        notices[0].starts_with("::notice file=tests/lint/corpus/inertia.md,line=58,"),
        "{out}"
    );
    assert!(
        notices[0].contains("[sign]%0Ato have it checked: rigor: symbols R > 0"),
        "{out}"
    );
    assert_eq!(
        out.lines().filter(|l| l.starts_with("::error")).count(),
        2,
        "{out}"
    );
}

#[test]
fn a_chain_verified_from_premises_names_their_lines_in_every_format() {
    let note = "tests/lint/corpus/kinetics.md";
    let (out, _, _) = lint(&[note]);
    assert!(
        out.contains("kinetics.md:20:4: verified from lines 13, 15 and 16, assuming"),
        "{out}"
    );
    let (out, _, _) = lint(&["--format", "json", note]);
    let v: serde_json::Value = serde_json::from_str(out.trim()).expect("json");
    let at20 = v["chains"]
        .as_array()
        .into_iter()
        .flatten()
        .find(|c| c["line"] == 20)
        .cloned()
        .unwrap_or_default();
    assert_eq!(at20["from"], serde_json::json!([13, 15, 16]), "{out}");
    let (out, _, _) = lint(&["--format", "github", note]);
    assert!(
        out.contains(
            "::notice file=tests/lint/corpus/kinetics.md,line=20,col=4,endLine=20,endColumn="
        ) && out.contains("title=verified::verified from lines 13, 15 and 16\n"),
        "{out}"
    );
    // A chain that holds with nothing stated names nothing.
    let (out, _, _) = lint(&["tests/lint/corpus/inertia.md"]);
    assert!(out.contains("inertia.md:17:1: verified\n"), "{out}");
}

#[test]
fn a_result_stays_in_scope_under_later_headings_unless_stated_again() {
    for (note, using) in [
        (
            "tests/lint/corpus/sections_carry.md",
            [
                ":28:4: verified, using I_G = \\frac{1}{2} m R^2 from line 9\n",
                ":38:4: verified, using I_G = \\frac{1}{2} m R^2 from line 9 and v_G = \\omega R from line 30\n",
            ],
        ),
        (
            "tests/lint/corpus/sections_carry.tex",
            [
                ":16:3: verified, using I_G = \\frac{m L^2}{12} from line 9\n",
                ":46:7: FAILED: this step does not hold\n",
            ],
        ),
    ] {
        let (out, _, _) = lint(&[note]);
        for u in using {
            assert!(out.contains(&format!("{note}{u}")), "{u}\n{out}");
        }
    }
    // Section 5 of the Markdown notes states I_G again (a ring): its chain holds with that
    // one and uses nothing carried.
    let (out, _, _) = lint(&["tests/lint/corpus/sections_carry.md"]);
    assert!(out.contains("sections_carry.md:46:4: verified\n"), "{out}");
}

#[test]
fn a_link_equal_to_zero_imposes_a_condition_and_what_follows_uses_it() {
    for (note, line, lhs) in [
        ("tests/lint/corpus/sections_carry.md", 20, "v_C"),
        ("tests/lint/corpus/sections_carry.tex", 29, "v_P"),
    ] {
        let (out, _, code) = lint(&["--format", "json", note]);
        let v: serde_json::Value = serde_json::from_str(out.trim()).expect("json");
        let chain = v["chains"]
            .as_array()
            .into_iter()
            .flatten()
            .find(|c| c["line"] == line)
            .cloned()
            .unwrap_or_default();
        assert_eq!(chain["verdict"], "needs context", "{out}");
        assert_eq!(chain["reason"], "imposed", "{out}");
        let message = chain["diagnostics"][0]["message"]
            .as_str()
            .unwrap_or_default();
        assert!(
            message.starts_with(&format!("needs context: the notes impose {lhs} = 0 here")),
            "{message}"
        );
        // The prose's `v_G = \omega R` just after follows from it.
        assert!(
            v["chains"]
                .as_array()
                .into_iter()
                .flatten()
                .any(|c| c["line"] == line + 2
                    && c["verdict"] == "verified"
                    && c["from"] == serde_json::json!([line])),
            "{out}"
        );
        assert_eq!(code, 1, "{out}");
    }
}

#[test]
fn a_value_the_prose_gives_is_suggested_as_the_comment_that_makes_a_chain_checkable() {
    let (out, _, _) = lint(&["tests/lint/corpus/sections_carry.md"]);
    assert!(
        out.contains("sections_carry.md:51:4: needs context: this step brings in A, which nothing before it defines; the notes must give it; `<!-- rigor: let r = A -->` makes it checkable\n"),
        "{out}"
    );
    let (out, _, _) = lint(&["--format", "json", "tests/lint/corpus/sections_carry.tex"]);
    let v: serde_json::Value = serde_json::from_str(out.trim()).expect("json");
    let chain = v["chains"]
        .as_array()
        .into_iter()
        .flatten()
        .find(|c| c["line"] == 38)
        .cloned()
        .unwrap_or_default();
    assert_eq!(chain["comment"], "rigor: let h = 2", "{out}");
    // The comment, added, does make it checkable: the chain is then verified.
    let dir = std::env::temp_dir().join(format!("rigor-lint-value-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let text = std::fs::read_to_string("tests/lint/corpus/sections_carry.tex").expect("read");
    let doc = dir.join("carry.tex");
    std::fs::write(
        &doc,
        text.replace("\\section{Falling", "% rigor: let h = 2\n\\section{Falling"),
    )
    .expect("write");
    let (out, _, _) = lint(&[doc.to_str().unwrap_or_default()]);
    let _ = std::fs::remove_dir_all(&dir);
    assert!(out.contains("carry.tex:39:3: verified"), "{out}");
}
