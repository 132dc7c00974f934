//! The independent evaluation of a pair, the verdicts, and the tests.

use super::pairs::*;
use super::*;

// ---------------------------------------------------------------- the independent evaluation

/// What the evaluation says about a pair.
#[derive(Clone, Debug, PartialEq)]
enum Truth {
    /// The sides agree at this many valid points (and differ at none).
    Agree(usize),
    /// The sides clearly differ at this point.
    Differ(String),
    /// No valid, well-conditioned point was found.
    Unknown,
}

/// Both sides parsed, for the guard.
struct Parsed {
    lhs: Expr,
    rhs: Expr,
}

fn parse_pair(p: &Pair) -> Result<Parsed, String> {
    let opts = ParseOptions::default();
    let one = |e: &E| parse_expr(&e.print(), &opts).map_err(|x| format!("{}: {x:?}", e.print()));
    Ok(Parsed {
        lhs: one(&p.lhs)?,
        rhs: one(&p.rhs)?,
    })
}

/// The guard's value of `x`, checked against this file's own evaluation of `e` (a
/// difference means the text does not say what the tree says: a bug of this test or
/// of the parser). `None` when undefined or ill-conditioned.
fn value(x: &Expr, e: &E, pt: &HashMap<String, f64>) -> Result<Option<f64>, String> {
    let Ok(b) = guard::eval(x, &GuardEnv::default(), pt) else {
        return Ok(None);
    };
    let scale = 1f64.max(b.mid.abs());
    if b.rad > 1e-9 * scale {
        return Ok(None);
    }
    if let Some(v) = e.val(pt) {
        if (v - b.mid).abs() > 1e-7 * scale.max(v.abs()) {
            return Err(format!(
                "`{}` is {v} by the tree but {} by the guard at {pt:?}",
                e.print(),
                b.mid
            ));
        }
    }
    Ok(Some(b.mid))
}

fn show_point(pt: &HashMap<String, f64>) -> String {
    let sorted: BTreeMap<_, _> = pt.iter().collect();
    sorted
        .iter()
        .map(|(k, v)| format!("{k} = {v}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// `A = B` at random points of the declarations.
fn truth_eq(p: &Pair, x: &Parsed, sc: &Scope, rng: &mut Rng) -> Result<Truth, String> {
    let mut agree = 0;
    for _ in 0..16 {
        if agree >= 6 {
            break;
        }
        let pt = sc.point(rng);
        let (Some(a), Some(b)) = (value(&x.lhs, &p.lhs, &pt)?, value(&x.rhs, &p.rhs, &pt)?) else {
            continue;
        };
        let scale = 1f64.max(a.abs()).max(b.abs());
        let d = (a - b).abs();
        if d > 1e-6 * scale {
            return Ok(Truth::Differ(format!(
                "at {} the left side is {a} and the right side {b}",
                show_point(&pt)
            )));
        }
        if d <= 1e-9 * scale {
            agree += 1;
        }
    }
    Ok(if agree > 0 {
        Truth::Agree(agree)
    } else {
        Truth::Unknown
    })
}

/// `A ~= B` to the order kept in `theta`: the Taylor coefficients of `A − B` up to that
/// order, by central differences at `theta = 0, ±h`, must vanish.
fn truth_small(p: &Pair, x: &Parsed, sc: &Scope, rng: &mut Rng) -> Result<Truth, String> {
    let order = sc.small.unwrap_or(1);
    let mut agree = 0;
    for _ in 0..12 {
        if agree >= 4 {
            break;
        }
        let mut pt = sc.point(rng);
        let mut d = |t: f64| -> Result<Option<(f64, f64)>, String> {
            pt.insert(THETA.to_string(), t);
            let (Some(a), Some(b)) = (value(&x.lhs, &p.lhs, &pt)?, value(&x.rhs, &p.rhs, &pt)?)
            else {
                return Ok(None);
            };
            Ok(Some((a - b, 1f64.max(a.abs()).max(b.abs()))))
        };
        let (Some((d0, s0)), Some((dp1, _)), Some((dm1, _)), Some((dp2, _)), Some((dm2, _))) =
            (d(0.0)?, d(1e-4)?, d(-1e-4)?, d(1e-3)?, d(-1e-3)?)
        else {
            continue;
        };
        let c1 = (dp1 - dm1) / 2e-4;
        let c2 = (dp2 - 2.0 * d0 + dm2) / 1e-6;
        let coeffs = if order == 1 {
            vec![d0, c1]
        } else {
            vec![d0, c1, c2]
        };
        let big = coeffs.iter().any(|c| c.abs() > 1e-2 * s0);
        let tiny = coeffs.iter().all(|c| c.abs() < 1e-4 * s0);
        if big {
            pt.remove(THETA);
            return Ok(Truth::Differ(format!(
                "at {} the coefficients of theta^0..{order} of left − right are {coeffs:?}",
                show_point(&pt)
            )));
        }
        agree += usize::from(tiny);
    }
    Ok(if agree > 0 {
        Truth::Agree(agree)
    } else {
        Truth::Unknown
    })
}

fn truth(p: &Pair, sc: &Scope, rng: &mut Rng) -> Result<Truth, String> {
    let x = parse_pair(p)?;
    if p.approx {
        truth_small(p, &x, sc, rng)
    } else {
        truth_eq(p, &x, sc, rng)
    }
}

// ---------------------------------------------------------------- the engine's verdict

#[derive(Clone, Debug, PartialEq)]
enum Verdict {
    Verified,
    Refuted,
    /// Neither: the diagnostic's code.
    Undecided(String),
}

fn derivation(p: &Pair, sc: &Scope) -> String {
    let op = if p.approx { "~=" } else { "=" };
    format!(
        "{}claim {} {op} {}\n",
        sc.header(),
        p.lhs.print(),
        p.rhs.print()
    )
}

fn verdict(text: &str) -> Verdict {
    let opts = Options {
        // A budget of work, not of time: the same verdicts on a loaded machine.
        timeout: Duration::from_secs(3),
        clock: Some(crate::ticking_clock),
        ..Options::default()
    };
    let r = check_source("pair.deriv", text, &opts, &MemoryResolver::new());
    let code = r
        .diagnostics
        .iter()
        .find(|d| d.code.as_str().starts_with('E'))
        .map_or("", |d| d.code.as_str())
        .to_string();
    match r
        .claims
        .first()
        .and_then(|c| c.links.first())
        .map(|l| &l.status)
    {
        Some(s) if s.is_verified() => Verdict::Verified,
        Some(Status::Failed) if code == "E0301" || code == "E0304" => Verdict::Refuted,
        // The guard withdrew a refutation (its counterexample looked like equal sides)
        // or a verification (the sides as written differ): the second is the exact
        // engine wrong, and fails the test.
        Some(Status::Failed) if code == "E0903" => Verdict::Undecided("E0903 refutation".into()),
        Some(Status::Undecided) if code == "E0903" => {
            Verdict::Undecided("E0903 verification".into())
        }
        _ => Verdict::Undecided(code),
    }
}

// ---------------------------------------------------------------- the run

#[derive(Default)]
struct Tally {
    total: usize,
    true_pairs: usize,
    verified_true: usize,
    undecided_true: usize,
    false_pairs: usize,
    refuted_false: usize,
    undecided_false: usize,
    skipped: usize,
    wrong: Vec<String>,
    /// Pairs the exact engine found equal but its own guard did not (E0903).
    caught: Vec<String>,
    /// Per kind: (true pairs, undecided true pairs, one example).
    kinds: BTreeMap<&'static str, (usize, usize, Option<String>)>,
    /// Undecided pairs by diagnostic code.
    codes: BTreeMap<String, usize>,
}

/// Builds pair `i` and checks it; `Err` for a bug of this test (a pair that is not
/// what it was built to be).
fn run_one(i: u64, seed: u64, t: &mut Tally) -> Result<(), String> {
    let mut rng = Rng(seed ^ i.wrapping_mul(0xA076_1D64_78BD_642F));
    let kind = KINDS[(i as usize) % KINDS.len()];
    let mut sc = Scope::random(&mut rng);
    let good = true_pair(&mut rng, kind, &mut sc);
    if good.lhs.size() > 120 || good.rhs.size() > 160 {
        t.skipped += 1;
        return Ok(());
    }
    let truth_good = truth(&good, &sc, &mut rng)?;
    if let Truth::Differ(why) = &truth_good {
        return Err(format!(
            "pair {i} of kind {kind} was built true but {why}:\n{}",
            derivation(&good, &sc)
        ));
    }
    if truth_good == Truth::Unknown {
        // Nowhere defined or ill-conditioned at every point tried.
        t.skipped += 1;
        return Ok(());
    }
    // Nearly half the pairs are perturbed into false ones, checked false by the
    // evaluation (a perturbation that happens to keep the pair true is tried again).
    let mut pair = good;
    let mut expected_true = true;
    let mut evidence = String::new();
    if rng.chance(0.45) {
        for _ in 0..8 {
            let (rhs, what) = perturb(&mut rng, &pair.rhs);
            let bad = Pair {
                rhs,
                ..pair.clone()
            };
            if let Truth::Differ(why) = truth(&bad, &sc, &mut rng)? {
                pair = Pair {
                    kind: pair.kind,
                    ..bad
                };
                expected_true = false;
                evidence = format!("{what}; {why}");
                break;
            }
        }
        if expected_true {
            t.skipped += 1;
            return Ok(());
        }
    }
    let text = derivation(&pair, &sc);
    let v = verdict(&text);
    t.total += 1;
    let entry = t.kinds.entry(kind).or_default();
    if expected_true {
        t.true_pairs += 1;
        entry.0 += 1;
        match &v {
            Verdict::Verified => t.verified_true += 1,
            Verdict::Refuted => t.wrong.push(format!(
                "pair {i} ({kind}) is true by construction but was refuted:\n{text}"
            )),
            Verdict::Undecided(code) => {
                t.undecided_true += 1;
                if code == "E0903 verification" {
                    t.caught.push(format!("pair {i} ({kind}, true):\n{text}"));
                }
                if std::env::var_os("DIFFERENTIAL_VERBOSE").is_some() {
                    eprintln!(
                        "undecided {kind} {code}: {}",
                        text.lines().last().unwrap_or("")
                    );
                }
                entry.1 += 1;
                if entry.2.as_ref().is_none_or(|e| e.len() > text.len()) {
                    entry.2 = Some(text.clone());
                }
                *t.codes.entry(code.clone()).or_default() += 1;
            }
        }
    } else {
        t.false_pairs += 1;
        match &v {
            Verdict::Refuted => t.refuted_false += 1,
            Verdict::Verified => t.wrong.push(format!(
                "pair {i} ({kind}) is false ({evidence}) but was verified:\n{text}"
            )),
            Verdict::Undecided(code) => {
                t.undecided_false += 1;
                if code == "E0903 verification" {
                    t.caught
                        .push(format!("pair {i} ({kind}, {evidence}):\n{text}"));
                }
                *t.codes.entry(format!("{code} (false pair)")).or_default() += 1;
            }
        }
    }
    Ok(())
}

fn seed() -> u64 {
    std::env::var("DIFFERENTIAL_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0x5EED_D1FF)
}

/// The pairs `0..n`, on two threads.
fn run(n: u64) -> Tally {
    let seed = seed();
    let parts: Vec<Tally> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..2u64)
            .map(|w| {
                scope.spawn(move || {
                    let mut t = Tally::default();
                    for i in (w..n).step_by(2) {
                        if let Err(e) = run_one(i, seed, &mut t) {
                            panic!("test bug (seed {seed}): {e}");
                        }
                    }
                    t
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("worker"))
            .collect()
    });
    let mut t = Tally::default();
    for p in parts {
        t.total += p.total;
        t.true_pairs += p.true_pairs;
        t.verified_true += p.verified_true;
        t.undecided_true += p.undecided_true;
        t.false_pairs += p.false_pairs;
        t.refuted_false += p.refuted_false;
        t.undecided_false += p.undecided_false;
        t.skipped += p.skipped;
        t.wrong.extend(p.wrong);
        t.caught.extend(p.caught);
        for (k, (a, b, ex)) in p.kinds {
            let e = t.kinds.entry(k).or_default();
            e.0 += a;
            e.1 += b;
            if e.2
                .as_ref()
                .is_none_or(|x| ex.as_ref().is_some_and(|y| y.len() < x.len()))
            {
                e.2 = ex.or(e.2.take());
            }
        }
        for (c, k) in p.codes {
            *t.codes.entry(c).or_default() += k;
        }
    }
    t
}

#[test]
fn random_pairs_agree_with_the_independent_evaluation() {
    let n = u64::from(crate::cases(2_500));
    let t = run(n);
    eprintln!(
        "differential: {} pairs checked ({} skipped: undefined or ill-conditioned everywhere tried)",
        t.total, t.skipped
    );
    eprintln!(
        "  true by construction: {} — verified {}, undecided {}",
        t.true_pairs, t.verified_true, t.undecided_true
    );
    eprintln!(
        "  false (perturbed):    {} — refuted {}, undecided {}",
        t.false_pairs, t.refuted_false, t.undecided_false
    );
    eprintln!("  wrong verdicts: {}", t.wrong.len());
    for (k, (all, und, ex)) in &t.kinds {
        eprintln!("  {k:<10} true {all:>4}, undecided {und:>3}");
        if let Some(ex) = ex {
            eprintln!("      smallest undecided:\n{}", indent(ex));
        }
    }
    eprintln!("  undecided by code: {:?}", t.codes);
    assert!(
        t.wrong.is_empty(),
        "wrong verdicts:\n{}",
        t.wrong.join("\n")
    );
    assert!(
        t.caught.is_empty(),
        "the exact engine verified these, but the guard found the sides differ (E0903):\n{}",
        t.caught.join("\n")
    );
    assert!(t.total >= 2_000 || n < 2_500, "only {} pairs", t.total);
    // The target of issue #14: fewer than 1 in 50 true pairs undecided. Measured at the
    // default seed: 0.2% (3 of 1,292; it was 5.0% before squarefree parts, merged abs,
    // roots and logarithms, and exact eighths of pi). The kinds that were undecided are
    // `kinds_once_undecided_are_decided_…` below.
    assert!(
        t.undecided_true * 50 < t.true_pairs,
        "undecided on {} of {} true pairs",
        t.undecided_true,
        t.true_pairs
    );
}

fn indent(s: &str) -> String {
    s.lines().map(|l| format!("        {l}\n")).collect()
}

#[test]
fn the_printer_and_the_evaluators_agree_on_precedence() {
    // `-x^2` is −(x²); a quotient times a symbol is parenthesised; odd roots of negatives.
    let e = mul(div(s("a"), n(2)), neg(pow(s("x"), 2)));
    assert_eq!(e.print(), "(a/2) (-x^2)");
    let pt: HashMap<String, f64> = [("a".to_string(), 3.0), ("x".to_string(), -2.0)]
        .into_iter()
        .collect();
    let parsed = parse_expr(&e.print(), &ParseOptions::default()).unwrap();
    assert_eq!(value(&parsed, &e, &pt), Ok(Some(-6.0)));
    let cube = powq(s("x"), 1, 3);
    assert!((cube.val(&pt).unwrap() + 2f64.cbrt()).abs() < 1e-12);
}

/// True identities of the kinds that once kept the differential test above 1 in 50
/// undecided (E0302), each in its smallest form, with a false neighbour of each below.
const ONCE_UNDECIDED: &[(&str, &str)] = &[
    // ln of a power or a root of a positive sum (a product of positive symbols works).
    ("symbols a > 0", "ln((a + 1)^2) = 2 ln(a + 1)"),
    ("symbols x", "ln((x + 1)^2) = 2 ln(abs(x + 1))"),
    // Odd roots of odd powers of sums (of a symbol: verified).
    ("symbols y", "((y - 1)^3)^(1/3) = y - 1"),
    // A fourth root of a square.
    ("symbols x", "(x^2)^(1/4) = sqrt(sqrt(x^2))"),
    // Roots of quotients and products of positive sums.
    ("symbols x", "sqrt(1/exp(x)) = 1/sqrt(exp(x))"),
    (
        "symbols x",
        "sqrt((x^2 + 1) (x^2 + 2)) = sqrt(x^2 + 1) sqrt(x^2 + 2)",
    ),
    (
        "symbols b > 0\nsymbols c > 0",
        "sqrt((c + b)^2 (b + 1)) = (c + b) sqrt(b + 1)",
    ),
    // Ranges: sqrt of tan² and of 1/cos² (abs(tan(beta)) = tan(beta) is verified).
    ("symbols 0 < beta < pi/2", "sqrt(tan(beta)^2) = tan(beta)"),
    (
        "symbols 0 < beta < pi/2",
        "sqrt(1 + tan(beta)^2) = 1/cos(beta)",
    ),
    // abs of a power of a sum.
    ("symbols x", "abs((x + 1)^3) = abs(x + 1)^3"),
    // Half angles of an angle with a multiple of pi in it.
    (
        "symbols beta",
        "sin(beta + pi/4) = 2 sin((beta + pi/4)/2) cos((beta + pi/4)/2)",
    ),
    // abs and roots of products that only a factorisation splits; logarithms of them.
    ("symbols x", "abs(x^2 - 4) = abs(x - 2) abs(x + 2)"),
    (
        "symbols a c > 0",
        "ln((a + 1) (5 c + a)) = ln(a + 1) + ln(5 c + a)",
    ),
    ("symbols x", "sqrt(2) 2^(1/4) = 8^(1/4)"),
    (
        "symbols x",
        "sqrt(x^2 + 1) (x^2 + 1)^(1/3) = (x^2 + 1)^(5/6)",
    ),
    ("symbols y", "ln(cos(y)^2) = 2 ln(abs(cos(y)))"),
];

/// False neighbours of [`ONCE_UNDECIDED`], one each, in the same order: what the new
/// rules must not verify. Some are false only where both sides are defined, some only
/// where one side is (declared signs missing): none may be verified.
const FALSE_NEIGHBOURS: &[(&str, &str)] = &[
    ("symbols a > 0", "ln((a + 1)^2) = 3 ln(a + 1)"),
    ("symbols x", "ln((x + 1)^2) = 2 ln(x + 1)"),
    ("symbols y", "((y - 1)^3)^(1/3) = 1 - y"),
    ("symbols x", "(x^2)^(1/4) = sqrt(x)"),
    ("symbols x", "sqrt(1/exp(x)) = sqrt(exp(x))"),
    (
        "symbols x",
        "sqrt((x^2 + 1) (x^2 + 2)) = sqrt(x^2 + 1) sqrt(x^2 + 3)",
    ),
    (
        "symbols b > 0\nsymbols c > 0",
        "sqrt((c + b)^2 (b + 1)) = (c - b) sqrt(b + 1)",
    ),
    ("symbols beta", "sqrt(tan(beta)^2) = tan(beta)"),
    ("symbols beta", "sqrt(1 + tan(beta)^2) = 1/cos(beta)"),
    ("symbols x", "abs((x + 1)^3) = (x + 1)^3"),
    (
        "symbols beta",
        "sin(beta + pi/4) = 2 sin((beta + pi/4)/2) cos((beta - pi/4)/2)",
    ),
    ("symbols x", "abs(x^2 - 4) = (x - 2) abs(x + 2)"),
    (
        "symbols a c",
        "ln((a + 1) (5 c + a)) = ln(a + 1) + ln(5 c + a)",
    ),
    ("symbols x", "sqrt(2) 2^(1/4) = 4^(1/4)"),
    (
        "symbols x",
        "sqrt(x^2 + 1) (x^2 + 1)^(1/3) = (x^2 + 1)^(2/3)",
    ),
    ("symbols y", "ln(cos(y)^2) = 2 ln(cos(y))"),
];

#[test]
fn kinds_once_undecided_are_decided_and_their_false_neighbours_are_not() {
    assert_eq!(ONCE_UNDECIDED.len(), FALSE_NEIGHBOURS.len());
    for (decls, claim) in ONCE_UNDECIDED {
        let text = format!("{decls}\nclaim {claim}\n");
        assert_eq!(verdict(&text), Verdict::Verified, "{text}");
    }
    for (decls, claim) in FALSE_NEIGHBOURS {
        let text = format!("{decls}\nclaim {claim}\n");
        assert_ne!(verdict(&text), Verdict::Verified, "{text}");
    }
}

#[test]
fn refutations_with_tiny_values_stand() {
    // At the counterexample both sides are ≈ 1e-26: the guard's check of the
    // counterexample once took them for equal (an absolute tolerance) and withdrew the
    // refutation as E0903. Likewise sides that differ by 1e-9 of their size.
    let text = "symbols y > 0\nclaim exp(-30 y) = 2 exp(-30 y)\n";
    assert_eq!(verdict(text), Verdict::Refuted, "{text}");
    let text = "symbols y > 0\nclaim 1/(y^8) = 1/(y^8 + 1)\n";
    assert_eq!(verdict(text), Verdict::Refuted, "{text}");
    // The first point found (y = 1/1000) makes the sides differ by 10⁻²⁴ of their size,
    // beyond what the guard's floating point can confirm: the search goes on to a
    // point where they differ plainly (it was withdrawn as E0903, so undecided).
    let text = "symbols a > 0\nsymbols c\nsymbols y > 0\nclaim a/(3 y^6) + ln(sqrt((c^2 + 3) (y^2 + 2))) = a/(3 y^6) + ln((c^2 + 3) (2 - y^2))/2\n";
    assert_eq!(verdict(text), Verdict::Refuted, "{text}");
}

#[test]
fn logarithms_of_roots_and_exponentials_of_fractional_logarithms_are_decided() {
    for (decls, claim) in [
        ("symbols a > 0", "ln(sqrt(a)) = ln(a)/2"),
        ("symbols a > 0", "ln(a^(1/3)) = ln(a)/3"),
        ("symbols a b > 0", "ln(sqrt(a b)) = ln(a)/2 + ln(b)/2"),
        ("symbols a > 0", "exp(ln(sqrt(a))) = sqrt(a)"),
        ("symbols x", "exp(ln(x)/2) = sqrt(x)"),
        ("symbols x", "exp(3 ln(x)/2) = x sqrt(x)"),
    ] {
        let text = format!("{decls}\nclaim {claim}\n");
        assert_eq!(verdict(&text), Verdict::Verified, "{text}");
    }
    // And a false neighbour is still refuted.
    let text = "symbols a > 0\nclaim ln(sqrt(a)) = ln(a)/3\n";
    assert_eq!(verdict(text), Verdict::Refuted, "{text}");
}
