//! The performance workloads of `../shared/bench/WORKLOADS.md`, checked for correctness
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
