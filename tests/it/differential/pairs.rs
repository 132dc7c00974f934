//! The pairs: true by construction (an identity applied) or perturbed into false ones.

use super::*;

// ---------------------------------------------------------------- random expressions

/// A number: small integers mostly, some fractions.
fn number(rng: &mut Rng) -> E {
    match rng.below(6) {
        0 => q(rng.int(-5, 5), rng.int(2, 4)),
        1 => n(rng.int(-4, -1)),
        _ => n(rng.int(1, 6)),
    }
}

/// A symbol of the generic set (no angles, no small quantity).
fn symbol(rng: &mut Rng) -> E {
    s(rng.pick(GENERIC))
}

/// A monomial `c s1^k1 s2^k2`.
fn monomial(rng: &mut Rng) -> E {
    let mut fs = Vec::new();
    if rng.chance(0.6) {
        fs.push(number(rng));
    }
    for _ in 0..rng.int(1, 2) {
        let k = rng.int(1, 3);
        fs.push(if k == 1 {
            symbol(rng)
        } else {
            pow(symbol(rng), k)
        });
    }
    product(fs)
}

/// A polynomial of one to `max` monomials, sometimes with a constant term.
fn poly(rng: &mut Rng, max: i64) -> E {
    let mut ts: Vec<E> = (0..rng.int(1, max)).map(|_| monomial(rng)).collect();
    if rng.chance(0.4) {
        ts.push(number(rng));
    }
    sum(ts)
}

/// A random expression of the rational-function kind, with an occasional function of
/// a symbol as an opaque factor.
fn rational_expr(rng: &mut Rng, depth: u32) -> E {
    if depth == 0 {
        return match rng.below(5) {
            0 => number(rng),
            1 => monomial(rng),
            _ => symbol(rng),
        };
    }
    match rng.below(9) {
        0 | 1 => add(rational_expr(rng, depth - 1), rational_expr(rng, depth - 1)),
        2 => sub(rational_expr(rng, depth - 1), rational_expr(rng, depth - 1)),
        3 | 4 => mul(rational_expr(rng, depth - 1), rational_expr(rng, depth - 1)),
        5 => div(rational_expr(rng, depth - 1), poly(rng, 2)),
        6 => pow(rational_expr(rng, depth - 1), rng.int(2, 3)),
        7 => poly(rng, 3),
        _ => {
            let g = rng.pick(&[Fun::Sin, Fun::Cos, Fun::Exp, Fun::Abs]);
            mul(number(rng), f(g, symbol(rng)))
        }
    }
}

/// An expression the declarations make positive.
fn positive(rng: &mut Rng, sc: &Scope) -> E {
    let pos = sc.names(|d| decl_sign(d) == Sg::Pos);
    let base = |rng: &mut Rng| -> E {
        match rng.below(6) {
            0 | 1 => s(rng.pick(&pos)),
            2 => add(pow(symbol(rng), 2), n(rng.int(1, 3))),
            3 => mul(n(rng.int(1, 5)), s(rng.pick(&pos))),
            4 => add(s(rng.pick(&pos)), q(rng.int(1, 3), rng.int(1, 2))),
            _ => exp(symbol(rng)),
        }
    };
    let e = match rng.below(4) {
        0 => mul(base(rng), base(rng)),
        1 => add(base(rng), base(rng)),
        _ => base(rng),
    };
    debug_assert_eq!(e.sign(sc), Sg::Pos);
    e
}

/// An expression the declarations make nonnegative.
fn nonneg(rng: &mut Rng, sc: &Scope) -> E {
    match rng.below(5) {
        0 => pow(rational_expr(rng, 1), 2),
        1 => abs(rational_expr(rng, 1)),
        2 => {
            let nn = sc.names(|d| decl_sign(d).nonneg());
            s(rng.pick(&nn))
        }
        _ => positive(rng, sc),
    }
}

/// An angle: a small combination of angle symbols and generic symbols.
fn angle(rng: &mut Rng) -> E {
    let a = s(rng.pick(ANGLES));
    let x = s(rng.pick(&["x", "y", "beta", "gamma"]));
    match rng.below(8) {
        0 | 1 => a,
        2 => mul(n(rng.int(2, 3)), a),
        3 => add(a, x),
        4 => sub(mul(n(2), a), x),
        5 => div(a, n(2)),
        6 => add(a, mul(q(1, rng.pick(&[3, 4, 6])), E::Pi)),
        _ => mul(s("a"), x),
    }
}

/// Any random expression of the generator (for contexts and mixed pairs).
fn any_expr(rng: &mut Rng, sc: &Scope) -> E {
    match rng.below(5) {
        0 => sin(angle(rng)),
        1 => sqrt(positive(rng, sc)),
        2 => ln(positive(rng, sc)),
        _ => rational_expr(rng, 1),
    }
}

// ---------------------------------------------------------------- identities

/// A pair with its relation and the kind of identity it was built from.
#[derive(Clone, Debug)]
pub(super) struct Pair {
    pub(super) kind: &'static str,
    pub(super) lhs: E,
    pub(super) rhs: E,
    pub(super) approx: bool,
}

fn expand_pair(rng: &mut Rng, _sc: &Scope) -> (E, E) {
    let lhs = match rng.below(4) {
        0 => mul(poly(rng, 2), poly(rng, 2)),
        1 => pow(add(poly(rng, 2), monomial(rng)), rng.int(2, 3)),
        2 => mul(rational_expr(rng, 2), sub(poly(rng, 2), monomial(rng))),
        _ => product(vec![
            poly(rng, 2),
            poly(rng, 1),
            add(symbol(rng), number(rng)),
        ]),
    };
    let rhs = sum(expand(&lhs));
    (lhs, rhs)
}

fn factor_pair(rng: &mut Rng, sc: &Scope) -> (E, E) {
    let (a, b, k) = (rational_expr(rng, 1), rational_expr(rng, 1), monomial(rng));
    let (factored, expanded) = match rng.below(4) {
        0 => (
            mul(sub(a.clone(), b.clone()), add(a.clone(), b.clone())),
            sub(pow(a, 2), pow(b, 2)),
        ),
        1 => (
            mul(k.clone(), add(a.clone(), b.clone())),
            add(mul(k.clone(), a), mul(k, b)),
        ),
        2 => (
            pow(add(a.clone(), b.clone()), 2),
            sum(vec![
                pow(a.clone(), 2),
                mul(mul(n(2), a), b.clone()),
                pow(b, 2),
            ]),
        ),
        _ => {
            let (l, r) = expand_pair(rng, sc);
            (l, r)
        }
    };
    (expanded, factored)
}

fn fraction_pair(rng: &mut Rng, _sc: &Scope) -> (E, E) {
    let (a, c) = (rational_expr(rng, 1), rational_expr(rng, 1));
    let (b, d) = (poly(rng, 2), poly(rng, 2));
    match rng.below(6) {
        0 => (
            add(div(a.clone(), b.clone()), div(c.clone(), d.clone())),
            div(add(mul(a, d.clone()), mul(c, b.clone())), mul(b, d)),
        ),
        1 => (
            sub(div(a.clone(), b.clone()), div(c.clone(), d.clone())),
            div(sub(mul(a, d.clone()), mul(b.clone(), c)), mul(b, d)),
        ),
        2 => (
            mul(div(a.clone(), b.clone()), div(c.clone(), d.clone())),
            div(mul(a, c), mul(b, d)),
        ),
        3 => (
            div(div(a.clone(), b.clone()), div(c.clone(), d.clone())),
            div(mul(a, d), mul(b, c)),
        ),
        4 => (div(mul(a.clone(), d.clone()), mul(b.clone(), d)), div(a, b)),
        _ => (
            add(a.clone(), div(c.clone(), d.clone())),
            div(add(mul(a, d.clone()), c), d),
        ),
    }
}

fn radical_pair(rng: &mut Rng, sc: &Scope) -> (E, E) {
    let (p, r) = (nonneg(rng, sc), nonneg(rng, sc));
    let pos = positive(rng, sc);
    let any = rational_expr(rng, 1);
    match rng.below(15) {
        12 => powers_of_one_base(rng, sc),
        13 | 14 => denested(rng),
        0 => (sqrt(mul(p.clone(), r.clone())), mul(sqrt(p), sqrt(r))),
        1 => (
            sqrt(mul(pow(any.clone(), 2), p.clone())),
            if any.sign(sc).nonneg() {
                mul(any, sqrt(p))
            } else {
                mul(abs(any), sqrt(p))
            },
        ),
        2 => (powq(p.clone(), 1, 4), sqrt(sqrt(p))),
        3 => (powq(p.clone(), 3, 2), mul(p.clone(), sqrt(p))),
        4 => (sqrt(div(p.clone(), pos.clone())), div(sqrt(p), sqrt(pos))),
        5 => (div(n(1), sqrt(pos.clone())), div(sqrt(pos.clone()), pos)),
        6 => (powq(pow(any.clone(), 3), 1, 3), any),
        7 => {
            let other = rational_expr(rng, 1);
            (
                powq(mul(any.clone(), other.clone()), 1, 3),
                mul(powq(any, 1, 3), powq(other, 1, 3)),
            )
        }
        8 => {
            // A symbol whose declared sign settles `sqrt(s^2)`.
            let signed = sc.names(|d| decl_sign(d) != Sg::Any && decl_sign(d) != Sg::NonZero);
            let v = rng.pick(&signed);
            let rhs = match decl_sign(sc.decl(v)) {
                Sg::Neg => neg(s(v)),
                _ => s(v),
            };
            (sqrt(pow(s(v), 2)), rhs)
        }
        9 => {
            let k = rng.int(2, 5);
            (sqrt(mul(n(k * k), p.clone())), mul(n(k), sqrt(p)))
        }
        10 => (
            div(n(1), add(sqrt(pos.clone()), sqrt(p.clone()))),
            div(sub(sqrt(pos.clone()), sqrt(p.clone())), sub(pos, p)),
        ),
        _ => {
            let k = rng.pick(&[2, 3, 5, 6]);
            (sqrt(n(4 * k)), mul(n(2), sqrt(n(k))))
        }
    }
}

/// Rational powers of one base written two ways (issue 31): `b^(i/m) b^(j/k)` against
/// `b^((i k + j m)/(m k))`, for a number or a symbol declared positive.
fn powers_of_one_base(rng: &mut Rng, sc: &Scope) -> (E, E) {
    let pos = sc.names(|d| decl_sign(d) == Sg::Pos);
    let base = if rng.chance(0.5) {
        n(rng.pick(&[2, 3, 5, 6, 10]))
    } else {
        s(rng.pick(&pos))
    };
    let (m, k) = (rng.int(2, 6), rng.int(2, 6));
    let (i, j) = (rng.int(1, m - 1), rng.int(1, 2 * k));
    (
        mul(powq(base.clone(), i, m), powq(base.clone(), j, k)),
        powq(base, i * k + j * m, m * k),
    )
}

/// A nested square root that denests (issue 31): the root of `(a + b sqrt(c))^2` or of
/// `(sqrt(p) + sqrt(q) - sqrt(r))^2` written out, against the positive one of the two.
fn denested(rng: &mut Rng) -> (E, E) {
    let primes = [2, 3, 5, 7, 11, 13];
    if rng.chance(0.5) {
        let (a, b, c) = (rng.int(1, 6), rng.int(1, 4), rng.pick(&primes));
        let minus = rng.chance(0.5);
        let inside = add(
            n(a * a + b * b * c),
            mul(n(if minus { -2 * a * b } else { 2 * a * b }), sqrt(n(c))),
        );
        let root = mul(n(b), sqrt(n(c)));
        let rhs = if !minus {
            add(n(a), root)
        } else if a * a > b * b * c {
            sub(n(a), root)
        } else {
            sub(root, n(a))
        };
        return (sqrt(inside), rhs);
    }
    let (p, q, r) = (rng.pick(&primes), rng.pick(&primes), rng.pick(&primes));
    if p == q || q == r || p == r {
        return (sqrt(n(4 * p)), mul(n(2), sqrt(n(p))));
    }
    // (√p + √q − √r)² = p + q + r + 2√(pq) − 2√(pr) − 2√(qr), positive for r < p + q.
    let inside = sum(vec![
        n(p + q + r),
        mul(n(2), sqrt(n(p * q))),
        mul(n(-2), sqrt(n(p * r))),
        mul(n(-2), sqrt(n(q * r))),
    ]);
    let value = sub(add(sqrt(n(p)), sqrt(n(q))), sqrt(n(r)));
    let positive = (p as f64).sqrt() + (q as f64).sqrt() > (r as f64).sqrt();
    (sqrt(inside), if positive { value } else { neg(value) })
}

fn range_pair(rng: &mut Rng, sc: &mut Scope) -> (E, E) {
    // One angle in a random range that fixes a sign; identities that hold there.
    let name = rng.pick(ANGLES);
    let d = rng.pick(ANGLE_RANGES);
    if let Some(slot) = sc.syms.iter_mut().find(|(m, _)| *m == name) {
        slot.1 = d;
    }
    let Decl::Range(lo, hi, _, _) = d else {
        unreachable!()
    };
    let b = s(name);
    let (sin_pos, sin_neg) = (lo >= 0.0 && hi <= PI, lo >= -PI && hi <= 0.0);
    let (cos_pos, cos_neg) = (lo >= -HALF_PI && hi <= HALF_PI, lo >= HALF_PI && hi <= PI);
    let mut options: Vec<(E, E)> = Vec::new();
    if sin_pos || sin_neg {
        let sin_b = if sin_pos {
            sin(b.clone())
        } else {
            neg(sin(b.clone()))
        };
        options.push((sqrt(pow(sin(b.clone()), 2)), sin_b.clone()));
        options.push((abs(sin(b.clone())), sin_b.clone()));
        options.push((sqrt(sub(n(1), pow(cos(b.clone()), 2))), sin_b));
    }
    if cos_pos || cos_neg {
        let cos_b = if cos_pos {
            cos(b.clone())
        } else {
            neg(cos(b.clone()))
        };
        options.push((abs(cos(b.clone())), cos_b.clone()));
        options.push((sqrt(sub(n(1), pow(sin(b.clone()), 2))), cos_b.clone()));
        options.push((sqrt(add(n(1), pow(tan(b.clone()), 2))), div(n(1), cos_b)));
    }
    if (sin_pos && cos_pos) || (sin_neg && cos_neg) {
        options.push((abs(tan(b.clone())), tan(b.clone())));
        options.push((sqrt(pow(tan(b.clone()), 2)), tan(b.clone())));
    }
    if (sin_neg && cos_pos) || (sin_pos && cos_neg) {
        options.push((abs(tan(b.clone())), neg(tan(b.clone()))));
    }
    options.push((
        sqrt(pow(b.clone(), 2)),
        if lo >= 0.0 {
            b.clone()
        } else if hi <= 0.0 {
            neg(b.clone())
        } else {
            abs(b.clone())
        },
    ));
    let (l, r) = options.swap_remove(rng.below(options.len()));
    let k = rational_expr(rng, 0);
    if rng.chance(0.5) {
        (mul(k.clone(), l), mul(k, r))
    } else {
        (add(l, k.clone()), add(r, k))
    }
}

fn trig_pair(rng: &mut Rng, _sc: &Scope) -> (E, E) {
    let (a, b) = (angle(rng), angle(rng));
    let k = rational_expr(rng, 0);
    match rng.below(18) {
        16 | 17 => pi_multiples(rng, k),
        0 => (
            mul(k.clone(), add(pow(sin(a.clone()), 2), pow(cos(a), 2))),
            k,
        ),
        1 => (pow(cos(a.clone()), 2), sub(n(1), pow(sin(a), 2))),
        2 => (
            sin(mul(n(2), a.clone())),
            mul(mul(n(2), sin(a.clone())), cos(a)),
        ),
        3 => (
            cos(mul(n(2), a.clone())),
            sub(pow(cos(a.clone()), 2), pow(sin(a), 2)),
        ),
        4 => (
            cos(mul(n(2), a.clone())),
            sub(n(1), mul(n(2), pow(sin(a), 2))),
        ),
        5 => (
            sin(add(a.clone(), b.clone())),
            add(mul(sin(a.clone()), cos(b.clone())), mul(cos(a), sin(b))),
        ),
        6 => (
            cos(sub(a.clone(), b.clone())),
            add(mul(cos(a.clone()), cos(b.clone())), mul(sin(a), sin(b))),
        ),
        7 => (tan(a.clone()), div(sin(a.clone()), cos(a))),
        8 => (add(n(1), pow(tan(a.clone()), 2)), div(n(1), pow(cos(a), 2))),
        9 => (sin(sub(E::Pi, a.clone())), sin(a)),
        10 => (cos(add(E::Pi, a.clone())), neg(cos(a))),
        11 => (sin(add(a.clone(), div(E::Pi, n(2)))), cos(a)),
        12 => (
            sin(mul(n(3), a.clone())),
            sub(mul(n(3), sin(a.clone())), mul(n(4), pow(sin(a), 3))),
        ),
        13 => (
            mul(mul(n(2), sin(a.clone())), cos(b.clone())),
            add(sin(add(a.clone(), b.clone())), sin(sub(a, b))),
        ),
        14 => (
            sin(a.clone()),
            mul(mul(n(2), sin(div(a.clone(), n(2)))), cos(div(a, n(2)))),
        ),
        _ => {
            let exact: &[(E, E)] = &[
                (sin(div(E::Pi, n(6))), q(1, 2)),
                (cos(div(E::Pi, n(3))), q(1, 2)),
                (sin(div(E::Pi, n(4))), div(sqrt(n(2)), n(2))),
                (cos(div(E::Pi, n(6))), div(sqrt(n(3)), n(2))),
                (tan(div(E::Pi, n(3))), sqrt(n(3))),
                (sin(mul(q(5, 6), E::Pi)), q(1, 2)),
                (cos(mul(q(3, 4), E::Pi)), neg(div(sqrt(n(2)), n(2)))),
            ];
            let (l, r) = exact[rng.below(exact.len())].clone();
            (mul(k.clone(), l), mul(k, r))
        }
    }
}

/// Sines and cosines at rational multiples of π (issue 31): the symmetries of the
/// circle at any denominator, and exact values at π/5, π/10, π/12, π/24 written as
/// radicals, each times `k`.
fn pi_multiples(rng: &mut Rng, k: E) -> (E, E) {
    let d = rng.pick(&[7, 9, 11, 13, 14, 18]);
    let j = rng.int(1, d - 1);
    let at = |num: i64| mul(q(num, d), E::Pi);
    let r5 = sqrt(n(5));
    let (l, r) = match rng.below(8) {
        // sin(π − x) = sin x, cos(π − x) = −cos x, cos(2π − x) = cos x, sin(π/2 − x) = cos x.
        0 => (sin(at(d - j)), sin(at(j))),
        1 => (cos(at(d - j)), neg(cos(at(j)))),
        2 => (cos(at(2 * d - j)), cos(at(j))),
        3 => (sin(sub(div(E::Pi, n(2)), at(j))), cos(at(j))),
        4 => (cos(div(E::Pi, n(5))), div(add(n(1), r5), n(4))),
        5 => (sin(div(E::Pi, n(10))), div(sub(r5, n(1)), n(4))),
        6 => (
            sin(mul(q(2, 5), E::Pi)),
            div(sqrt(add(n(10), mul(n(2), r5))), n(4)),
        ),
        _ => (
            cos(div(E::Pi, n(24))),
            div(sqrt(add(n(2), sqrt(add(n(2), sqrt(n(3)))))), n(2)),
        ),
    };
    (mul(k.clone(), l), mul(k, r))
}

fn exp_ln_pair(rng: &mut Rng, sc: &Scope) -> (E, E) {
    let (a, b) = (rational_expr(rng, 1), rational_expr(rng, 1));
    let (p, r) = (positive(rng, sc), positive(rng, sc));
    match rng.below(14) {
        0 => (exp(add(a.clone(), b.clone())), mul(exp(a), exp(b))),
        1 => (exp(sub(a.clone(), b.clone())), div(exp(a), exp(b))),
        2 => {
            let k = rng.int(2, 3);
            (exp(mul(n(k), a.clone())), pow(exp(a), k))
        }
        3 => (mul(exp(a.clone()), exp(neg(a))), n(1)),
        4 => (ln(mul(p.clone(), r.clone())), add(ln(p), ln(r))),
        5 => (ln(div(p.clone(), r.clone())), sub(ln(p), ln(r))),
        6 => {
            let k = rng.int(2, 4);
            (ln(pow(p.clone(), k)), mul(n(k), ln(p)))
        }
        7 => (ln(sqrt(p.clone())), div(ln(p), n(2))),
        8 => (ln(pow(a.clone(), 2)), mul(n(2), ln(abs(a)))),
        9 => (ln(pow(s("x"), 2)), mul(n(2), ln(abs(s("x"))))),
        10 => (ln(exp(a.clone())), a),
        11 => (exp(ln(p.clone())), p),
        12 => (exp(mul(n(2), ln(p.clone()))), pow(p, 2)),
        _ => (pow(exp(a.clone()), 2), exp(mul(n(2), a))),
    }
}

fn abs_pair(rng: &mut Rng, sc: &Scope) -> (E, E) {
    let (p, r) = (rational_expr(rng, 1), rational_expr(rng, 1));
    match rng.below(10) {
        0 => (abs(mul(p.clone(), r.clone())), mul(abs(p), abs(r))),
        1 => (abs(div(p.clone(), r.clone())), div(abs(p), abs(r))),
        2 => (pow(abs(p.clone()), 2), pow(p, 2)),
        3 => (abs(neg(p.clone())), abs(p)),
        4 => {
            let nn = nonneg(rng, sc);
            (abs(nn.clone()), nn)
        }
        5 => {
            let pos = positive(rng, sc);
            (abs(neg(pos.clone())), pos)
        }
        6 => (sqrt(pow(p.clone(), 2)), abs(p)),
        7 => (abs(abs(p.clone())), abs(p)),
        8 => (abs(pow(p.clone(), 3)), pow(abs(p), 3)),
        _ => (mul(abs(p.clone()), abs(p.clone())), pow(p, 2)),
    }
}

/// Taylor coefficients of `g(k theta)` (or of `g(a + theta)`) up to order 3.
fn taylor(rng: &mut Rng) -> (E, [E; 4]) {
    let t = s(THETA);
    let k = rng.pick(&[1i64, 1, 2, 3, -1, -2]);
    let kt = if k == 1 { t } else { mul(n(k), t) };
    let one_kt = add(n(1), kt.clone());
    let c = |num: i64, den: i64| {
        let g = gcd(num.abs(), den);
        q(num / g, den / g)
    };
    let a = s("x");
    match rng.below(10) {
        0 => (sin(kt), [n(0), n(k), n(0), c(-k * k * k, 6)]),
        1 => (cos(kt), [n(1), n(0), c(-k * k, 2), n(0)]),
        2 => (tan(kt), [n(0), n(k), n(0), c(k * k * k, 3)]),
        3 => (exp(kt), [n(1), n(k), c(k * k, 2), c(k * k * k, 6)]),
        4 => (ln(one_kt), [n(0), n(k), c(-k * k, 2), c(k * k * k, 3)]),
        5 => (
            sqrt(one_kt),
            [n(1), c(k, 2), c(-k * k, 8), c(k * k * k, 16)],
        ),
        6 => (div(n(1), one_kt), [n(1), n(-k), n(k * k), n(-k * k * k)]),
        7 => (pow(one_kt, 2), [n(1), n(2 * k), n(k * k), n(0)]),
        8 => (
            sin(add(a.clone(), s(THETA))),
            [
                sin(a.clone()),
                cos(a.clone()),
                neg(div(sin(a.clone()), n(2))),
                neg(div(cos(a), n(6))),
            ],
        ),
        _ => (
            cos(add(a.clone(), s(THETA))),
            [
                cos(a.clone()),
                neg(sin(a.clone())),
                neg(div(cos(a.clone()), n(2))),
                div(sin(a), n(6)),
            ],
        ),
    }
}

fn gcd(a: i64, b: i64) -> i64 {
    if b == 0 {
        a.max(1)
    } else {
        gcd(b, a % b)
    }
}

/// `sum_i K_i g_i(theta) ~= sum_i K_i T_i(theta)` with `T_i` the Taylor polynomial of
/// `g_i` to the order kept (and sometimes a harmless higher-order term).
fn small_pair(rng: &mut Rng, sc: &mut Scope) -> (E, E) {
    let order = if rng.chance(0.7) { 1 } else { 2 };
    sc.small = Some(order);
    let mut lhs = Vec::new();
    let mut rhs = Vec::new();
    for _ in 0..rng.int(1, 2) {
        let (g, cs) = taylor(rng);
        let k = if rng.chance(0.5) {
            n(1)
        } else {
            rational_expr(rng, 0)
        };
        let mut poly_terms = Vec::new();
        for (j, c) in cs.iter().enumerate().take(order as usize + 1) {
            if *c == n(0) {
                continue;
            }
            poly_terms.push(match j {
                0 => c.clone(),
                1 => mul(c.clone(), s(THETA)),
                _ => mul(c.clone(), pow(s(THETA), j as i64)),
            });
        }
        if rng.chance(0.2) {
            poly_terms.push(mul(number(rng), pow(s(THETA), i64::from(order) + 1)));
        }
        let t = if poly_terms.is_empty() {
            n(0)
        } else {
            sum(poly_terms)
        };
        if k == n(1) {
            lhs.push(g);
            rhs.push(t);
        } else {
            lhs.push(mul(k.clone(), g));
            rhs.push(mul(k, t));
        }
    }
    if rng.chance(0.3) {
        let extra = rational_expr(rng, 1);
        lhs.push(extra.clone());
        rhs.push(extra);
    }
    (sum(lhs), sum(rhs))
}

/// The kinds of pair, by name.
pub(super) const KINDS: &[&str] = &[
    "expand",
    "factor",
    "fractions",
    "radicals",
    "ranges",
    "trig",
    "exp-ln",
    "abs",
    "small",
    "mixed",
];

/// A true pair of kind `kind`, in a random context.
pub(super) fn true_pair(rng: &mut Rng, kind: &'static str, sc: &mut Scope) -> Pair {
    let (lhs, rhs) = match kind {
        "expand" => expand_pair(rng, sc),
        "factor" => factor_pair(rng, sc),
        "fractions" => fraction_pair(rng, sc),
        "radicals" => radical_pair(rng, sc),
        "ranges" => range_pair(rng, sc),
        "trig" => trig_pair(rng, sc),
        "exp-ln" => exp_ln_pair(rng, sc),
        "abs" => abs_pair(rng, sc),
        "small" => {
            let (l, r) = small_pair(rng, sc);
            return Pair {
                kind,
                lhs: l,
                rhs: r,
                approx: true,
            };
        }
        _ => {
            // Two identities of other kinds at once.
            let mut parts: Vec<Pair> = Vec::new();
            while parts.len() < 2 {
                let k = KINDS[rng.below(KINDS.len() - 2)];
                // One range per pair: a second would redeclare the first's angle.
                if k != "ranges" || parts.iter().all(|p| p.kind != "ranges") {
                    parts.push(true_pair(rng, k, sc));
                }
            }
            let (p, r) = (parts.remove(0), parts.remove(0));
            let (l, rr) = if rng.chance(0.5) {
                (add(p.lhs, r.lhs), add(p.rhs, r.rhs))
            } else {
                (mul(p.lhs, r.lhs), mul(p.rhs, r.rhs))
            };
            return Pair {
                kind,
                lhs: l,
                rhs: rr,
                approx: false,
            };
        }
    };
    // The same random context around both sides.
    let (lhs, rhs) = match rng.below(6) {
        0 => {
            let k = any_expr(rng, sc);
            (add(k.clone(), lhs), add(k, rhs))
        }
        1 => {
            let k = any_expr(rng, sc);
            (mul(k.clone(), lhs), mul(k, rhs))
        }
        2 => {
            let k = positive(rng, sc);
            (div(lhs, k.clone()), div(rhs, k))
        }
        _ => (lhs, rhs),
    };
    Pair {
        kind,
        lhs,
        rhs,
        approx: false,
    }
}

/// One perturbation of `e`: a sign flipped, a factor changed, a term dropped.
pub(super) fn perturb(rng: &mut Rng, e: &E) -> (E, &'static str) {
    let at = rng.below(e.size());
    let how = rng.below(4);
    let g: Box<dyn Fn(&E) -> E> = match how {
        0 => Box::new(|x: &E| negate(x.clone())),
        1 => {
            let k = rng.pick(&[2i64, 3, -2]);
            Box::new(move |x: &E| match x {
                E::Num(a, b) => E::Num(a + b, *b),
                x => mul(n(k), x.clone()),
            })
        }
        2 => {
            let left = rng.chance(0.5);
            Box::new(move |x: &E| match x {
                E::Add(a, b) => (if left { a } else { b }).as_ref().clone(),
                E::Sub(a, b) if left => a.as_ref().clone(),
                E::Sub(_, b) => neg(b.as_ref().clone()),
                x => add(x.clone(), n(1)),
            })
        }
        _ => Box::new(|x: &E| match x {
            E::Pow(a, p, r) => E::Pow(a.clone(), p + 1, *r),
            E::Sym(_) => pow(x.clone(), 2),
            x => add(x.clone(), n(1)),
        }),
    };
    let what = [
        "sign flipped",
        "factor changed",
        "term dropped",
        "power changed",
    ][how];
    let mut k = at;
    (e.map_at(&mut k, &*g), what)
}
