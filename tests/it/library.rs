//! The checker as a library: one pure entry, `rigor::check_source`, with imports through
//! a resolver the caller passes in.

use rigor::check::{Justification, Status};
use rigor::diag::FactRef;
use rigor::{check_source, MemoryResolver, Options};

const ROD: &str = "# A rod
symbols m L > 0
body rod: dm = m/L dy, y from -L/2 to L/2
claim [IG] int(y^2, rod) = m L^2/12
";

const MAIN: &str = "# The rod about its end
symbols M a > 0
unknowns I_A
use [IG] from \"lib/rod.deriv\" with m = M, L = 2 a
given [PA] I_A = M a^2 + M (2 a)^2/12
claim [end] I_A = 4 M a^2/3 by [PA]
";

#[test]
fn an_in_memory_derivation_imports_another_through_the_resolver() {
    let mut files = MemoryResolver::new();
    files.insert("lib/rod.deriv", ROD);
    let r = check_source("main.deriv", MAIN, &crate::no_budget(), &files);
    assert!(r.ok(), "{:?}", r.diagnostics);
    assert_eq!((r.claims.len(), r.verified(), r.failed()), (1, 1, 0));
    assert_eq!(
        r.claims[0].links[0].status,
        Status::Verified {
            how: Justification::Facts(vec![FactRef::Label("PA".into())]),
            side_conditions: Vec::new()
        }
    );
    // An imported claim with an unknown is a fact here, instantiated by `with`.
    files.insert(
        "lib/tension.deriv",
        "symbols m g L > 0\nunknowns T\ngiven [T] T = m g L\nclaim [TT] T = m g L by [T]\n",
    );
    let uses = "symbols M h > 0\nunknowns T\nuse [TT] from \"lib/tension.deriv\" with m = M, g = 10, L = h\nclaim [t] T = 10 M h by [TT]\nclaim [wrong] T = 9 M h by [TT]\n";
    let r = check_source("main.deriv", uses, &crate::no_budget(), &files);
    assert_eq!((r.verified(), r.failed()), (1, 1), "{:?}", r.diagnostics);
    assert_eq!(
        r.claims[0].links[0].status,
        Status::Verified {
            how: Justification::Facts(vec![FactRef::Label("TT".into())]),
            side_conditions: Vec::new()
        }
    );
}

#[test]
fn a_missing_import_is_an_error_at_the_path() {
    let files = MemoryResolver::new();
    let r = check_source("main.deriv", MAIN, &crate::no_budget(), &files);
    assert!(r.input_error);
    let d = &r.diagnostics[0];
    assert_eq!(d.code.as_str(), "E0206");
    assert!(
        d.message.contains("cannot read \"lib/rod.deriv\""),
        "{}",
        d.message
    );
}

#[test]
fn imports_may_not_leave_the_root_or_go_round_in_a_cycle() {
    let mut files = MemoryResolver::new();
    files.insert("a.deriv", "use [x] from \"b.deriv\"\n");
    files.insert("b.deriv", "use [y] from \"a.deriv\"\n");
    let r = check_source(
        "a.deriv",
        "use [x] from \"b.deriv\"\n",
        &Options::default(),
        &files,
    );
    let msg = &r.diagnostics[0].message;
    assert!(
        msg.contains("import cycle: a.deriv → b.deriv → a.deriv"),
        "{msg}"
    );
    let r = check_source(
        "a.deriv",
        "use [x] from \"../c.deriv\"\n",
        &Options::default(),
        &files,
    );
    assert!(
        r.diagnostics[0].message.contains("outside the folder"),
        "{:?}",
        r.diagnostics
    );
}

#[test]
fn without_a_clock_there_is_no_time_budget_and_the_verdict_is_the_same() {
    let mut files = MemoryResolver::new();
    files.insert("lib/rod.deriv", ROD);
    let no_clock = Options {
        clock: None,
        ..Options::default()
    };
    let a = check_source("main.deriv", MAIN, &no_clock, &files);
    let with_clock = Options {
        clock: Some(crate::ticking_clock),
        ..Options::default()
    };
    let b = check_source("main.deriv", MAIN, &with_clock, &files);
    assert_eq!(a.claims, b.claims);
    assert!(a.ok());
}

#[test]
fn a_byte_order_mark_is_not_part_of_the_text() {
    let files = MemoryResolver::new();
    let text = format!("\u{feff}{ROD}");
    let r = check_source("rod.deriv", &text, &crate::no_budget(), &files);
    assert!(r.ok(), "{:?}", r.diagnostics);
    assert_eq!(r.verified(), 1);
    // Spans point into the text as reported (without the mark).
    assert_eq!(r.source, ROD);
}

#[test]
fn a_root_index_above_64_is_refused_with_that_limit() {
    let files = MemoryResolver::new();
    let text = "symbols x > 0\nclaim [r] x^(1/65) = x^(1/65)\n";
    let r = check_source("r.deriv", text, &crate::no_budget(), &files);
    assert!(!r.ok());
    let msg: Vec<&str> = r.diagnostics.iter().map(|d| d.message.as_str()).collect();
    assert!(
        msg.iter().any(|m| m.contains("a root index above 64")),
        "{msg:?}"
    );
    // The 64th root itself is taken.
    let text = "symbols x > 0\nclaim [r] (x^64)^(1/64) = x\n";
    let r = check_source("r.deriv", text, &crate::no_budget(), &files);
    assert!(r.ok(), "{:?}", r.diagnostics);
}

/// The codes and hints of `src`'s diagnostics, in order.
fn diagnoses(src: &str) -> Vec<(String, String)> {
    let r = check_source("x.deriv", src, &crate::no_budget(), &MemoryResolver::new());
    r.diagnostics
        .iter()
        .map(|d| {
            let hint = d.primary.as_ref().map(|p| p.1.clone()).unwrap_or_default();
            (d.code.to_string(), hint)
        })
        .collect()
}

#[test]
fn a_slash_then_glued_factors_warns_how_it_was_read() {
    let warned = |src: &str| {
        diagnoses(src)
            .iter()
            .filter(|(c, _)| c == "W0101")
            .map(|(_, h)| h.clone())
            .collect::<Vec<_>>()
    };
    // Glued after a `/`: read as (3 g/2) L, and said so.
    assert_eq!(
        warned("symbols g L > 0\nclaim 3 g/2L = 3 g L/2\n"),
        ["if 2 L is the denominator, write `3 g/(2 L)`"]
    );
    assert_eq!(
        warned("symbols g L > 0\nclaim g/2L^2 = g L^2/2\n"),
        ["if 2 L^2 is the denominator, write `g/(2 L^2)`"]
    );
    // Spaced, parenthesised, multiplied explicitly or written as \frac: no warning
    // (these claims are true, so nothing at all is said).
    for src in [
        "symbols m v > 0\nclaim 1/2 m v^2 = m v^2/2\n",
        "symbols g L > 0\nclaim 3 g/(2L) = 3 g/(2 L)\n",
        "symbols g L > 0\nclaim 3 g/2*L = 3 g L/2\n",
        "symbols g L > 0\nclaim $$\\frac{3g}{2}L = \\frac{3gL}{2}$$\n",
    ] {
        assert!(diagnoses(src).is_empty(), "{src}: {:?}", diagnoses(src));
    }
}

#[test]
fn an_undeclared_name_is_diagnosed_as_the_format_would_read_it() {
    let hint = |src: &str| diagnoses(src).first().cloned().unwrap_or_default();
    // Declared names glued together: the fewest pieces.
    assert_eq!(
        hint("symbols m g d > 0\nclaim mgd = m g d\n"),
        (
            "E0201".into(),
            "did you mean `m g d`? (a product needs a space between its factors)".into()
        )
    );
    assert_eq!(
        hint("symbols m I_G R > 0\nclaim I_Gm = m I_G\n").1,
        "did you mean `I_G m`? (a product needs a space between its factors)"
    );
    // A derivative of a constant.
    assert_eq!(
        hint("symbols theta\nclaim theta' = 0\n").1,
        "`theta` is declared with `symbols`, so it has no time derivative: declare it with `time theta`"
    );
    // A near miss is still a near miss.
    assert_eq!(
        hint("symbols omega > 0\nclaim omgea = omega\n").1,
        "did you mean `omega`?"
    );
}

#[test]
fn a_body_whose_bounds_run_backwards_gets_a_warning() {
    let backwards = "symbols m L > 0\nbody rod: dm = m/L dy, y from L/2 to -L/2\n";
    assert_eq!(
        diagnoses(backwards),
        [(
            "W0102".to_string(),
            "do its bounds run backwards?".to_string()
        )]
    );
    let forwards = "symbols m L > 0\nbody rod: dm = m/L dy, y from -L/2 to L/2\n";
    assert!(diagnoses(forwards).is_empty());
    // A disk in polar coordinates, the angle backwards.
    let disk = "symbols m R > 0\nbody disk: dm = m/(pi R^2) r dr dphi, r from 0 to R, phi from 2 pi to 0\n";
    assert_eq!(diagnoses(disk)[0].0, "W0102");
}

#[test]
fn a_forgotten_mass_times_squared_distance_is_named_where_inertia_is_concerned() {
    let hint = |a: &str, b: &str| {
        let opts = rigor::syntax::ParseOptions::default();
        let env = rigor::lower::Env::default();
        let lower = |s: &str| {
            rigor::lower::lower(&rigor::syntax::parse_expr(s, &opts).unwrap(), &env).unwrap()
        };
        let (a, b) = (lower(a), lower(b));
        let d = a.sub(&b).unwrap();
        let d = rigor::decide::diagnose(&a, &b, &d).expect("a diagnosis");
        assert_eq!(d.mistake, rigor::diag::Mistake::MissingTerm);
        d.text
    };
    assert_eq!(
        hint("I_G", "I_G + m d^2"),
        "the left side is missing the term d^2 m that the right side has: a parallel-axis term (mass × squared distance)?"
    );
    // Kinetic energy is a mass times a squared speed, but nothing here is an inertia.
    assert_eq!(
        hint("m g h", "m g h + m v^2/2"),
        "the left side is missing the term m v^2/2 that the right side has"
    );
}

/// A product of two six-term sums: 36 terms.
const PRODUCT: &str = "symbols a b c d e f p q r s u v > 0
claim [x] (a + b + c + d + e + f) (p + q + r + s + u + v) = (a + b + c + d + e + f) (p + q + r + s + u + v)
";

fn with_terms(max_terms: usize) -> Options {
    Options {
        limits: rigor::normal::limits::Limits {
            max_terms,
            ..rigor::normal::limits::Limits::DEFAULT
        },
        ..crate::no_budget()
    }
}

#[test]
fn the_library_and_the_command_line_have_the_same_limits() {
    use rigor::normal::limits::{self, Limits};
    assert_eq!(Options::default().limits, Limits::DEFAULT);
    // The defaults docs/commands.md gives for --max-terms and --max-digits.
    assert_eq!(
        (Limits::DEFAULT.max_terms, Limits::DEFAULT.max_digits),
        (200_000, 120_000)
    );
    // Outside any check, a thread works with the defaults.
    assert_eq!(limits::current(), Limits::DEFAULT);
}

#[test]
fn options_limits_below_the_default_refuse_a_large_expansion_saying_the_limit() {
    let files = MemoryResolver::new();
    let r = check_source("p.deriv", PRODUCT, &crate::no_budget(), &files);
    assert!(r.ok(), "{:?}", r.diagnostics);
    let r = check_source("p.deriv", PRODUCT, &with_terms(20), &files);
    assert!(!r.ok());
    let d = r
        .diagnostics
        .iter()
        .find(|d| d.code == rigor::diag::Code::SizeLimit)
        .unwrap_or_else(|| panic!("{:?}", r.diagnostics));
    assert_eq!(
        d.message,
        "refused: the result would have more than the limit of 20 terms"
    );
    // The check's limits held only while it ran.
    assert_eq!(
        rigor::normal::limits::current(),
        rigor::normal::limits::Limits::DEFAULT
    );
}

#[test]
fn the_limit_in_force_is_carried_in_the_error() {
    use rigor::lower::{lower, Env, LowerErrorKind};
    use rigor::normal::limits::{self, Limits};
    use rigor::normal::Limit;
    let e = rigor::syntax::parse_expr(
        "(a + b + c + d + e + f) (p + q + r + s + u + v)",
        &Default::default(),
    )
    .unwrap();
    assert!(lower(&e, &Env::default()).is_ok());
    let err = {
        let _limits = limits::install(Limits {
            max_terms: 20,
            ..Limits::DEFAULT
        });
        lower(&e, &Env::default()).unwrap_err()
    };
    assert_eq!(err.kind, LowerErrorKind::Limit(Limit::Terms(20)));
    assert!(!err.to_string().contains("--"), "{err}");
    let e = rigor::syntax::parse_expr("3^100000", &Default::default()).unwrap();
    let err = {
        let _limits = limits::install(Limits {
            max_digits: 1000,
            ..Limits::DEFAULT
        });
        lower(&e, &Env::default()).unwrap_err()
    };
    assert_eq!(err.kind, LowerErrorKind::Limit(Limit::Digits(1000)));
    assert_eq!(
        err.to_string(),
        "refused: a number would have more than the limit of 1000 digits"
    );
}

#[test]
fn checks_on_two_threads_with_different_limits_do_not_see_each_others() {
    let barrier = std::sync::Barrier::new(2);
    let run = |max_terms: usize| {
        let files = MemoryResolver::new();
        let opts = with_terms(max_terms);
        barrier.wait();
        (0..20)
            .map(|_| {
                let r = check_source("p.deriv", PRODUCT, &opts, &files);
                (
                    r.ok(),
                    r.diagnostics
                        .iter()
                        .map(|d| d.message.clone())
                        .collect::<Vec<_>>(),
                )
            })
            .collect::<Vec<_>>()
    };
    let (small, large) = std::thread::scope(|s| {
        let small = s.spawn(|| run(20));
        let large = s.spawn(|| run(1000));
        (small.join().unwrap(), large.join().unwrap())
    });
    for (ok, msgs) in small {
        assert!(!ok);
        assert!(
            msgs.iter()
                .any(|m| m.contains("more than the limit of 20 terms")),
            "{msgs:?}"
        );
    }
    for (ok, msgs) in large {
        assert!(ok, "{msgs:?}");
    }
}

#[test]
fn a_resolver_says_why_an_import_cannot_be_had() {
    use rigor::check::{ImportError, Resolver};
    use rigor::files::FsResolver;
    let mut files = MemoryResolver::new();
    files.insert("lib/rod.deriv", ROD);
    assert!(files.resolve("main.deriv", "lib/rod.deriv").is_ok());
    let cases = [
        (
            "/etc/rod.deriv",
            ImportError::Absolute {
                path: "/etc/rod.deriv".into(),
            },
        ),
        (
            "../rod.deriv",
            ImportError::OutsideRoot {
                path: "../rod.deriv".into(),
            },
        ),
        (
            "lib/none.deriv",
            ImportError::NotFound {
                path: "lib/none.deriv".into(),
                reason: None,
            },
        ),
    ];
    for (path, want) in cases {
        assert_eq!(files.resolve("main.deriv", path), Err(want), "{path}");
    }
    // The messages are the ones shown at the path.
    assert_eq!(
        files
            .resolve("main.deriv", "x.deriv")
            .unwrap_err()
            .to_string(),
        "cannot read \"x.deriv\": no such file"
    );
    let dir = crate::cli::scratch("import-errors");
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    std::fs::write(dir.join("sub/rod.deriv"), ROD).unwrap();
    std::fs::write(dir.join("sub/latin1.deriv"), b"% caf\xe9\n").unwrap();
    std::fs::write(dir.join("outside.deriv"), ROD).unwrap();
    let fs = FsResolver {
        root: dir.join("sub"),
        max_file_size: 100,
    };
    let main = dir.join("sub/main.deriv").display().to_string();
    assert!(matches!(
        fs.resolve(&main, "rod.deriv"),
        Err(ImportError::TooLarge { size, max: 100, .. }) if size == ROD.len() as u64
    ));
    assert!(matches!(
        fs.resolve(&main, "none.deriv"),
        Err(ImportError::NotFound {
            reason: Some(_),
            ..
        })
    ));
    assert_eq!(
        fs.resolve(&main, "latin1.deriv"),
        Err(ImportError::NotUtf8 {
            path: "latin1.deriv".into(),
            offset: 5
        })
    );
    assert_eq!(
        fs.resolve(&main, "../outside.deriv"),
        Err(ImportError::OutsideRoot {
            path: "../outside.deriv".into()
        })
    );
    // A folder is there but is not a file.
    let fs = FsResolver {
        max_file_size: 10_000_000,
        ..fs
    };
    assert!(matches!(
        fs.resolve(&main, "."),
        Err(ImportError::Unreadable { .. })
    ));
    let _ = std::fs::remove_dir_all(&dir);
}
