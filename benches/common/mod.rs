//! The workloads of `bench/WORKLOADS.md` (W1–W4) implemented with rigor's
//! library API, shared by the criterion benchmarks (`benches/workloads.rs`) and the
//! one-cell-per-process driver used by `bench/compare.py` (`benches/cell.rs`).
//!
//! Every workload is split into `prepare` (untimed: parsing the input text, building
//! matrices) and `run` (the timed region), and a `fingerprint` (untimed check).
#![allow(dead_code)]

use rigor::decide::{decide, decide_verdict, Verdict};
use rigor::lower::{lower, Env};
use rigor::normal::atom::sym;
use rigor::normal::subst::{subst_atom, Subst};
use rigor::normal::{Assumptions, AtomId, Poly, Rat};
use rigor::syntax::ast::Expr;
use rigor::syntax::{parse_expr, ParseOptions};
use serde_json::{json, Value};
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};

/// The folder holding WORKLOADS.md, `w4_pairs.tsv` and `expected.json`.
pub fn bench_dir() -> PathBuf {
    if let Ok(d) = std::env::var("RIGOR_BENCH_DIR") {
        return PathBuf::from(d);
    }
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    here.join("bench")
}

/// The repository root (for `derivations/`).
pub fn repo_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

pub fn parse(text: &str) -> Expr {
    parse_expr(text, &ParseOptions::default())
        .unwrap_or_else(|e| panic!("parse error in {text:?}: {e:?}"))
}

fn low(e: &Expr) -> Rat {
    lower(e, &Env::default()).unwrap_or_else(|e| panic!("lowering failed: {e}"))
}

fn eq(a: &Rat, b: &Rat) -> bool {
    matches!(decide(a, b, &Assumptions::new()), Verdict::Equal)
}

// ---------------------------------------------------------------------------------------
// W1 — the handout suite (23 checks)
// ---------------------------------------------------------------------------------------

/// The parsed inputs of W1 (parsing is outside the timed region).
pub struct W1 {
    e: std::collections::HashMap<&'static str, Expr>,
}

const W1_EXPRS: &[(&str, &str)] = &[
    ("rod_IG", "int(y^2 (m/L), y, -L/2, L/2)"),
    ("rod_IG_exp", "m L^2/12"),
    ("rod_shift", "m (L/2)^2"),
    ("rod_IO_exp", "m L^2/3"),
    ("disk_IG", "int(r^2 (2 m/R^2) r, r, 0, R)"),
    ("disk_IG_area", "int(r^2 (m 2 pi r/(pi R^2)), r, 0, R)"),
    ("disk_exp", "m R^2/2"),
    ("pa_sq", "(x+a)^2 + (y+b)^2"),
    ("pa_exp", "Jx + Jy + m (a^2 + b^2)"),
    ("d_eq1", "F - m g sin(beta) - m xdd"),
    ("d_eq2", "F R - I_G thdd"),
    ("d_eq3", "xdd + thdd R"),
    ("d_xdd_exp", "-g sin(beta)/(1 + I_G/(m R^2))"),
    ("d_thdd_exp", "g sin(beta) m R/(m R^2 + I_G)"),
    ("d_F_exp", "m g sin(beta) I_G/(m R^2 + I_G)"),
    ("d_N", "m g cos(beta)"),
    ("d_ratio_exp", "tan(beta)/(1 + m R^2/I_G)"),
    ("e_eq1", "-m g L/2 - (m L^2/3) thdd"),
    ("e_eq2", "R_r - m g - m (thdd L/2)"),
    ("e_thdd_exp", "-3 g/(2 L)"),
    ("e_R_exp", "m g/4"),
    ("f_eq1", "F - m ygdd"),
    ("f_eq2", "-F a - I_G thdd"),
    ("f_ygdd_exp", "F/m"),
    ("f_thdd_exp", "-F a/I_G"),
    ("f_ab_exp", "I_G/m"),
    ("g_m", "int(rho pi (R^2 - z^2), z, -R, R)"),
    ("g_m_exp", "4/3 pi rho R^3"),
    ("g_I", "int(1/2 rho pi (R^2 - z^2) (R^2 - z^2), z, -R, R)"),
    ("g_I_exp", "8/15 pi rho R^5"),
    ("g_Im_exp", "2/5 m R^2"),
    (
        "h_xx",
        "int(int(int(m/(a b c) (y^2 + z^2), x, -a/2, a/2), y, -b/2, b/2), z, -c/2, c/2)",
    ),
    (
        "h_yy",
        "int(int(int(m/(a b c) (x^2 + z^2), x, -a/2, a/2), y, -b/2, b/2), z, -c/2, c/2)",
    ),
    (
        "h_zz",
        "int(int(int(m/(a b c) (x^2 + y^2), x, -a/2, a/2), y, -b/2, b/2), z, -c/2, c/2)",
    ),
    (
        "h_xy",
        "int(int(int(-m/(a b c) x y, x, -a/2, a/2), y, -b/2, b/2), z, -c/2, c/2)",
    ),
    (
        "h_xz",
        "int(int(int(-m/(a b c) x z, x, -a/2, a/2), y, -b/2, b/2), z, -c/2, c/2)",
    ),
    (
        "h_yz",
        "int(int(int(-m/(a b c) y z, x, -a/2, a/2), y, -b/2, b/2), z, -c/2, c/2)",
    ),
    ("h_xx_exp", "m (b^2 + c^2)/12"),
    ("h_yy_exp", "m (a^2 + c^2)/12"),
    ("h_zz_exp", "m (a^2 + b^2)/12"),
    ("zero", "0"),
];

pub fn w1_prepare() -> W1 {
    W1 {
        e: W1_EXPRS.iter().map(|(k, t)| (*k, parse(t))).collect(),
    }
}

/// Reads `eq = 0` (linear in `unknowns`) as a matrix row: coefficients and right-hand side.
fn linear_row(eq: &Rat, unknowns: &[AtomId]) -> (Vec<Rat>, Rat) {
    let den = eq.den();
    let mut row = Vec::with_capacity(unknowns.len());
    let mut rest = eq.num().clone();
    for &u in unknowns {
        assert!(!den.contains(u), "equation not polynomial in the unknowns");
        row.push(Rat::new(eq.num().deriv_atom(u), den.clone()).unwrap());
        rest = rest.subst(u, &Poly::zero()).unwrap();
    }
    let rhs = Rat::new(rest.neg(), den.clone()).unwrap();
    (row, rhs)
}

fn solve_eqs(eqs: &[Rat], unknowns: &[AtomId]) -> Vec<Rat> {
    let (a, b): (Vec<Vec<Rat>>, Vec<Rat>) = eqs.iter().map(|e| linear_row(e, unknowns)).unzip();
    rigor::solve::solve(&a, &b).expect("solvable")
}

/// The timed region of W1: every computation and its verification. Returns the ids of
/// the checks that failed (23 checks in all).
pub fn w1_run(w: &W1) -> (usize, Vec<&'static str>) {
    let l = |k: &str| low(&w.e[k]);
    let mut failed = Vec::new();
    let mut n = 0;
    let mut check = |id: &'static str, got: &Rat, exp: &Rat| {
        n += 1;
        if !eq(got, exp) {
            failed.push(id);
        }
    };
    // a
    let rod_ig = l("rod_IG");
    check("a.rod_IG", &rod_ig, &l("rod_IG_exp"));
    let rod_io = rod_ig.add(&l("rod_shift")).unwrap();
    check("a.rod_IO", &rod_io, &l("rod_IO_exp"));
    // b
    let disk_exp = l("disk_exp");
    check("b.disk_IG", &l("disk_IG"), &disk_exp);
    check("b.disk_IG_area", &l("disk_IG_area"), &disk_exp);
    // c: moments M_ij of x^i y^j
    {
        let (x, y) = (sym("x"), sym("y"));
        let sq = l("pa_sq");
        let p = sq.num();
        let moment = |i: u32, j: u32| -> Rat {
            match (i, j) {
                (0, 0) => Rat::atom(sym("m")),
                (1, 0) | (0, 1) => Rat::zero(),
                (2, 0) => Rat::atom(sym("Jx")),
                (0, 2) => Rat::atom(sym("Jy")),
                _ => panic!("unexpected moment {i} {j}"),
            }
        };
        let mut got = Rat::zero();
        for (i, cx) in p.coeffs_in(x) {
            for (j, cxy) in cx.coeffs_in(y) {
                let c = Rat::poly(cxy).unwrap();
                got = got.add(&c.mul(&moment(i, j)).unwrap()).unwrap();
            }
        }
        let got = got
            .div(&Rat::new(sq.den().clone(), Poly::one()).unwrap())
            .unwrap();
        check("c.parallel_axis", &got, &l("pa_exp"));
    }
    // d
    {
        let u = [sym("F"), sym("xdd"), sym("thdd")];
        let s = solve_eqs(&[l("d_eq1"), l("d_eq2"), l("d_eq3")], &u);
        check("d.roll_xdd", &s[1], &l("d_xdd_exp"));
        check("d.roll_thdd", &s[2], &l("d_thdd_exp"));
        check("d.roll_F", &s[0], &l("d_F_exp"));
        let ratio = s[0].div(&l("d_N")).unwrap();
        check("d.friction_ratio", &ratio, &l("d_ratio_exp"));
    }
    // e
    {
        let u = [sym("thdd"), sym("R_r")];
        let s = solve_eqs(&[l("e_eq1"), l("e_eq2")], &u);
        check("e.trap_thdd", &s[0], &l("e_thdd_exp"));
        check("e.trap_R", &s[1], &l("e_R_exp"));
    }
    // f
    {
        let u = [sym("ygdd"), sym("thdd")];
        let s = solve_eqs(&[l("f_eq1"), l("f_eq2")], &u);
        check("f.perc_ygdd", &s[0], &l("f_ygdd_exp"));
        check("f.perc_thdd", &s[1], &l("f_thdd_exp"));
        let b = s[0].div(&s[1]).unwrap().neg();
        let ab = Rat::atom(sym("a")).mul(&b).unwrap();
        check("f.perc_ab", &ab, &l("f_ab_exp"));
    }
    // g
    {
        let m = l("g_m");
        check("g.sphere_m", &m, &l("g_m_exp"));
        let i = l("g_I");
        check("g.sphere_I_raw", &i, &l("g_I_exp"));
        // m = k·rho  =>  rho = m / k
        let rho = sym("rho");
        let k = m.div(&Rat::atom(rho)).unwrap();
        let rho_v = Rat::atom(sym("m")).div(&k).unwrap();
        let im = subst_atom(&i, rho, &rho_v, &Assumptions::new()).unwrap();
        check("g.sphere_I", &im, &l("g_Im_exp"));
    }
    // h
    {
        let zero = l("zero");
        check("h.box_Ixx", &l("h_xx"), &l("h_xx_exp"));
        check("h.box_Iyy", &l("h_yy"), &l("h_yy_exp"));
        check("h.box_Izz", &l("h_zz"), &l("h_zz_exp"));
        check("h.box_Ixy", &l("h_xy"), &zero);
        check("h.box_Ixz", &l("h_xz"), &zero);
        check("h.box_Iyz", &l("h_yz"), &zero);
    }
    (n, failed)
}

pub fn w1_fingerprint(r: &(usize, Vec<&'static str>)) -> Value {
    json!({"checks": r.0, "passed": r.0 - r.1.len(), "failed": r.1})
}

// W1.check: the checker on the repository's handout derivations.

pub fn w1check_run() -> Vec<rigor::check::FileReport> {
    let dir = repo_dir().join("derivations");
    rigor::files::check_paths(&[dir], &rigor::check::Options::default())
}

pub fn w1check_fingerprint(r: &[rigor::check::FileReport]) -> Value {
    let links: usize = r.iter().map(|f| f.links()).sum();
    let verified: usize = r.iter().map(|f| f.verified()).sum();
    let failed: usize = r.iter().map(|f| f.failed()).sum();
    json!({"files": r.len(), "links": links, "verified": verified, "failed": failed,
           "ok": r.iter().all(|f| f.ok())})
}

// ---------------------------------------------------------------------------------------
// W2 — (1+x+y+z)^n over a symbolic box
// ---------------------------------------------------------------------------------------

pub fn w2_prepare(n: u32) -> (Expr, Expr) {
    (
        parse(&format!(
            "int(int(int((1+x+y+z)^{n}, x, 0, a), y, 0, b), z, 0, c)"
        )),
        parse(&format!(
            "int(int(int((1+x+y+z)^{n} (y^2 + z^2), x, 0, a), y, 0, b), z, 0, c)"
        )),
    )
}

pub fn w2_run(p: &(Expr, Expr)) -> (Rat, Rat) {
    (low(&p.0), low(&p.1))
}

/// Term count, value at a=b=c=1 and SHA-256 of the canonical serialisation.
pub fn w2_serial(r: &Rat) -> Value {
    let (a, b, c) = (sym("a"), sym("b"), sym("c"));
    assert!(r.as_poly().is_some(), "W2 results are polynomials");
    let mut lines: Vec<((u32, u32, u32), String)> = r
        .num()
        .terms()
        .iter()
        .map(|(m, q)| {
            let key = (m.exp(a), m.exp(b), m.exp(c));
            (
                key,
                format!(
                    "{} {} {} {}/{}\n",
                    key.0,
                    key.1,
                    key.2,
                    q.numer(),
                    q.denom()
                ),
            )
        })
        .collect();
    lines.sort();
    let text: String = lines.into_iter().map(|l| l.1).collect();
    let at = eval_at(r, &|_| Some(Rat::one()));
    json!({"terms": r.num().len(), "at_1_1_1": at, "sha256": format!("{:x}", Sha256::digest(text.as_bytes()))})
}

pub fn w2_fingerprint(r: &(Rat, Rat)) -> Value {
    json!({"mass": w2_serial(&r.0), "Ixx": w2_serial(&r.1)})
}

/// The exact value of `r` with atoms replaced by constants, as `p/q`.
pub fn eval_at(r: &Rat, map: &dyn Fn(AtomId) -> Option<Rat>) -> String {
    let s = Assumptions::new();
    let v = Subst::new(map, &s).rat(r).expect("evaluates");
    let q = v.as_constant().expect("constant after substitution");
    format!("{}/{}", q.numer(), q.denom())
}

// ---------------------------------------------------------------------------------------
// W3 — symbolic linear solves
// ---------------------------------------------------------------------------------------

fn v(name: String) -> Rat {
    Rat::atom(sym(&name))
}
fn frac(p: i64, q: i64) -> Rat {
    Rat::int(p).div(&Rat::int(q)).unwrap()
}

/// The matrix and right-hand side of a W3 system (untimed).
pub fn w3_prepare(kind: &str, n: usize) -> (Vec<Vec<Rat>>, Vec<Rat>) {
    let mut a = vec![vec![Rat::zero(); n]; n];
    let mut b = Vec::with_capacity(n);
    for i in 1..=n {
        for j in 1..=n {
            a[i - 1][j - 1] = match kind {
                "chain" => {
                    let (k0, first) = if i == j {
                        (i, frac(1, 3))
                    } else {
                        (i.max(j), frac(1, 2))
                    };
                    let mut mu = v(format!("m{k0}")).mul(&first).unwrap();
                    for k in k0 + 1..=n {
                        mu = mu.add(&v(format!("m{k}"))).unwrap();
                    }
                    v(format!("l{i}"))
                        .mul(&v(format!("l{j}")))
                        .unwrap()
                        .mul(&mu)
                        .unwrap()
                }
                "tri" => {
                    if i == j {
                        let w2m = v("w".into())
                            .powi(2)
                            .unwrap()
                            .mul(&v(format!("m{i}")))
                            .unwrap();
                        v(format!("k{i}"))
                            .add(&v(format!("k{}", i + 1)))
                            .unwrap()
                            .sub(&w2m)
                            .unwrap()
                    } else if j == i + 1 || i == j + 1 {
                        v(format!("k{}", i.max(j))).neg()
                    } else {
                        Rat::zero()
                    }
                }
                "dense" => v(format!("a{i}_{j}")),
                _ => panic!("unknown W3 system {kind}"),
            };
        }
        b.push(match kind {
            "chain" => v(format!("Q{i}")),
            "tri" => v(format!("f{i}")),
            _ => v(format!("b{i}")),
        });
    }
    (a, b)
}

pub fn w3_run(p: &(Vec<Vec<Rat>>, Vec<Rat>)) -> Vec<Rat> {
    rigor::solve::solve(&p.0, &p.1).expect("nonsingular")
}

/// The values of the point of WORKLOADS.md for the symbol named `name`.
fn w3_point(kind: &str, name: &str) -> Option<Rat> {
    let idx = |s: &str| s.parse::<i64>().ok();
    match kind {
        "chain" => {
            let (h, t) = name.split_at(1);
            let i = idx(t)?;
            match h {
                "m" | "Q" => Some(Rat::int(i)),
                "l" => Some(Rat::int(i + 1)),
                _ => None,
            }
        }
        "tri" => {
            if name == "w" {
                return Some(frac(1, 2));
            }
            let (h, t) = name.split_at(1);
            let i = idx(t)?;
            matches!(h, "k" | "m" | "f").then(|| Rat::int(i))
        }
        _ => {
            if let Some(rest) = name.strip_prefix('a') {
                let (i, j) = rest.split_once('_')?;
                Some(frac(1, idx(i)? + idx(j)? - 1))
            } else {
                name.strip_prefix('b').and_then(idx).map(Rat::int)
            }
        }
    }
}

pub fn w3_fingerprint(kind: &str, xs: &[Rat]) -> Value {
    let map = |a: AtomId| rigor::normal::atom::sym_name(a).and_then(|s| w3_point(kind, &s));
    let values: Vec<String> = xs.iter().map(|x| eval_at(x, &map)).collect();
    let mut sum = Rat::zero();
    for x in xs {
        sum = sum.add(x).unwrap();
    }
    let num_terms: usize = xs.iter().map(|x| x.num().len()).sum();
    let den_terms = xs.iter().map(|x| x.den().len()).max().unwrap_or(0);
    json!({"values": values, "sum": eval_at(&sum, &map), "num_terms": num_terms, "den_terms": den_terms})
}

// ---------------------------------------------------------------------------------------
// W4 — equivalence-checking throughput
// ---------------------------------------------------------------------------------------

pub const W4_SHA: &str = "f30449ef2a285e294981f8ac9020f14a36e4d2811636ad00de5c6dc47f6c0f9f";

pub struct W4 {
    pub pairs: Vec<(bool, Expr, Expr)>,
}

pub fn w4_prepare() -> W4 {
    let path = bench_dir().join("w4_pairs.tsv");
    let text = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let sha = format!("{:x}", Sha256::digest(&text));
    assert_eq!(sha, W4_SHA, "w4_pairs.tsv has the wrong SHA-256");
    let text = String::from_utf8(text).unwrap();
    let pairs = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split('\t').collect();
            (f[1] == "1", parse(f[3]), parse(f[4]))
        })
        .collect();
    W4 { pairs }
}

/// Timed region: lower both sides and decide (`decide_verdict`: the verdict alone, no
/// counterexample or diagnosis), for every pair. Returns the decisions.
pub fn w4_run(w: &W4) -> Vec<bool> {
    let env = Env::default();
    let s = Assumptions::new();
    w.pairs
        .iter()
        .map(|(_, a, b)| {
            let a = lower(a, &env).expect("lowers");
            let b = lower(b, &env).expect("lowers");
            matches!(decide_verdict(&a, &b, &s), Verdict::Equal)
        })
        .collect()
}

pub fn w4_fingerprint(w: &W4, d: &[bool]) -> Value {
    let decided = d.iter().filter(|x| **x).count();
    let label = w.pairs.iter().filter(|p| p.0).count();
    let mism = w.pairs.iter().zip(d).filter(|(p, x)| p.0 != **x).count();
    json!({"pairs": d.len(), "decided_equal": decided, "label_equal": label, "mismatches": mism})
}
