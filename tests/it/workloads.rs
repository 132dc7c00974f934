//! The performance workloads of `bench/WORKLOADS.md`, checked for correctness
//! (their speed is measured by `benches/`, never by a test).

use rigor::lower::{lower, Env};
use rigor::normal::atom::sym;
use rigor::normal::Rat;
use rigor::syntax::{parse_expr, ParseOptions};
use sha2::{Digest, Sha256};

fn normal(text: &str) -> Rat {
    let e = parse_expr(text, &ParseOptions::default()).expect("parses");
    lower(&e, &Env::default()).expect("lowers")
}

/// The canonical serialisation of WORKLOADS.md: `i j k p/q` per term, sorted by exponents.
fn w2_sha(r: &Rat) -> (usize, String) {
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
    (
        r.num().len(),
        format!("{:x}", Sha256::digest(text.as_bytes())),
    )
}

#[test]
fn w2_matches_the_expected_outputs() {
    let expected = [
        (
            2,
            10,
            "771f96d072fd026b740093716f87669daf51e17e04af5c1403416aac318c1a2b",
            19,
            "79f91b6b0956f69eb89c5aa5f3fbcb930354e173168781e58dfae3ab441977ac",
        ),
        (
            4,
            35,
            "1c101dd8057c2ae8d70e859bfd36b78269348fe51b27eed62e42769504ccb35a",
            60,
            "510d06f3c45cbdbea718f6253430a51e7d8f6320c56cb889c7e25cbfc0b13ee6",
        ),
        (
            8,
            165,
            "39100f2b6d3eb78662a11fd853c2f5e6fc95c03e9f609a28e03243c0e77a9ea3",
            246,
            "72af4d1757f3277ab19a4ba851d6313e2a30924521f6dc90d5875c46db2dcb8c",
        ),
    ];
    for (n, mass_terms, mass_sha, ixx_terms, ixx_sha) in expected {
        let mass = normal(&format!(
            "int(int(int((1+x+y+z)^{n}, x, 0, a), y, 0, b), z, 0, c)"
        ));
        let ixx = normal(&format!(
            "int(int(int((1+x+y+z)^{n} (y^2 + z^2), x, 0, a), y, 0, b), z, 0, c)"
        ));
        assert_eq!(
            w2_sha(&mass),
            (mass_terms, mass_sha.to_string()),
            "mass, n = {n}"
        );
        assert_eq!(
            w2_sha(&ixx),
            (ixx_terms, ixx_sha.to_string()),
            "I_xx, n = {n}"
        );
    }
}

/// A W3 system of WORKLOADS.md: the matrix and right-hand side.
fn w3_system(kind: &str, n: usize) -> (Vec<Vec<Rat>>, Vec<Rat>) {
    let v = |name: String| Rat::atom(sym(&name));
    let q = |p: i64, d: i64| Rat::int(p).div(&Rat::int(d)).expect("nonzero");
    let mut a = vec![vec![Rat::zero(); n]; n];
    let mut b = Vec::with_capacity(n);
    for i in 1..=n {
        for j in 1..=n {
            a[i - 1][j - 1] = match kind {
                "chain" => {
                    let (k0, first) = if i == j {
                        (i, q(1, 3))
                    } else {
                        (i.max(j), q(1, 2))
                    };
                    let mut mu = v(format!("m{k0}")).mul(&first).expect("product");
                    for k in k0 + 1..=n {
                        mu = mu.add(&v(format!("m{k}"))).expect("sum");
                    }
                    mu.mul(
                        &v(format!("l{i}"))
                            .mul(&v(format!("l{j}")))
                            .expect("product"),
                    )
                    .expect("product")
                }
                "tri" if i == j => v(format!("k{i}"))
                    .add(&v(format!("k{}", i + 1)))
                    .and_then(|s| s.sub(&v("w".into()).powi(2)?.mul(&v(format!("m{i}")))?))
                    .expect("entry"),
                "tri" if i.abs_diff(j) == 1 => v(format!("k{}", i.max(j))).neg(),
                "tri" => Rat::zero(),
                _ => v(format!("a{i}_{j}")),
            };
        }
        b.push(v(match kind {
            "chain" => format!("Q{i}"),
            "tri" => format!("f{i}"),
            _ => format!("b{i}"),
        }));
    }
    (a, b)
}

/// The value of a W3 symbol at the check point of WORKLOADS.md.
fn w3_point(kind: &str, name: &str) -> Rat {
    let split = name
        .find(|c: char| c.is_ascii_digit())
        .unwrap_or(name.len());
    let (head, tail) = name.split_at(split);
    let idx = |s: &str| s.parse::<i64>().expect("index");
    match (kind, head) {
        ("chain", "l") => Rat::int(idx(tail) + 1),
        ("tri", "w") => Rat::int(1).div(&Rat::int(2)).expect("half"),
        ("dense", "a") => {
            let (i, j) = tail.split_once('_').expect("a{i}_{j}");
            Rat::int(1)
                .div(&Rat::int(idx(i) + idx(j) - 1))
                .expect("Hilbert")
        }
        _ => Rat::int(idx(tail)),
    }
}

#[test]
fn w3_solutions_are_canonical_and_right() {
    use rigor::normal::subst::Subst;
    use rigor::normal::{atom, Assumptions};
    // (kind, n, x_1 at the point, Σ x_i at the point, numerator terms, largest denominator).
    let expected = [
        ("chain", 2, "-3/10", "1/3", 5, 2),
        ("chain", 3, "-3/94", "107/564", 19, 4),
        ("chain", 4, "-48/515", "3271/30900", 58, 8),
        ("chain", 5, "-2721/34730", "68551/1041900", 158, 16),
        ("tri", 2, "68/67", "128/67", 8, 8),
        ("tri", 3, "1988/883", "5804/883", 39, 21),
        ("tri", 4, "1828/347", "14863/694", 154, 55),
        ("tri", 5, "16012/713", "84436/713", 544, 144),
        ("dense", 2, "-8", "10", 4, 2),
        ("dense", 3, "27", "45", 18, 6),
        ("dense", 4, "-64", "136", 96, 24),
    ];
    let signs = Assumptions::new();
    for (kind, n, x1, sum, num_terms, den_terms) in expected {
        let (a, b) = w3_system(kind, n);
        let x = rigor::solve::solve(&a, &b).expect("nonsingular");
        let map = |id| atom::sym_name(id).map(|s| w3_point(kind, &s));
        let at = |r: &Rat| {
            Subst::new(&map, &signs)
                .rat(r)
                .expect("defined at the point")
        };
        let mut total = Rat::zero();
        for xi in &x {
            total = total.add(&at(xi)).expect("sum");
        }
        assert_eq!(at(&x[0]), normal(x1), "{kind} {n}: x_1");
        assert_eq!(total, normal(sum), "{kind} {n}: Σ x_i");
        let nums: usize = x.iter().map(|r| r.num().len()).sum();
        let dens = x.iter().map(|r| r.den().len()).max().unwrap_or(0);
        assert_eq!((nums, dens), (num_terms, den_terms), "{kind} {n}: sizes");
        // Canonical: each x_i in lowest terms (gcd 1) with a monic denominator.
        for xi in &x {
            let again = xi.num().clone();
            let r = Rat::new(again, xi.den().clone()).expect("nonzero denominator");
            assert_eq!(&r, xi, "{kind} {n}: not reduced");
        }
    }
}

#[test]
fn linear_solver_edge_cases() {
    use rigor::solve::{solve, LinearError};
    let s = |t: &str| normal(t);
    // Singular: the second row is twice the first.
    let a = vec![vec![s("a"), s("b")], vec![s("2 a"), s("2 b")]];
    assert_eq!(solve(&a, &[s("1"), s("2")]), Err(LinearError::Singular));
    // One unknown, a rational-function coefficient.
    let x = solve(&[vec![s("m/(2 L)")]], &[s("F")]).expect("regular");
    assert_eq!(x, vec![s("2 F L/m")]);
    // No unknowns at all, and a shape mismatch.
    assert_eq!(solve(&[], &[]), Ok(Vec::new()));
    assert_eq!(solve(&[vec![s("1")]], &[]), Err(LinearError::Shape));
    // A zero in the leading position needs a row swap (and its sign).
    let a = vec![vec![s("0"), s("k")], vec![s("m"), s("c")]];
    let x = solve(&a, &[s("p"), s("q")]).expect("regular");
    assert_eq!(x, vec![s("(q k - c p)/(m k)"), s("p/k")]);
}
