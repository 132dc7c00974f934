#!/usr/bin/env python3
"""Side-by-side timing of rigor, SymPy, SymEngine and python-flint on the workloads of
bench/WORKLOADS.md (W1-W4), following its protocol:

* one fresh process per cell (workload, variant, size); the process first runs the
  series' smallest size once (untimed), then the cell once (t0); t0 < 5 s: warm-up,
  then k = clamp(floor(20 s / t0), 3, 7) timed runs; t0 >= 5 s: t0 counts, plus 2 more
  runs if t0 < 15 s, 1 more if t0 < 30 s; median and best are reported;
* SymPy's cache is cleared and gc.collect() runs before every run;
* a run longer than 60 s is killed (TIMEOUT) and larger sizes of the series are not run;
  a size is skipped when t2*(n/n2)^p from the two previous sizes predicts > 180 s;
* 10 GB address-space limit per child; peak RSS per cell from wait4();
* every result is checked against expected.json / WORKLOADS.md and the tools are
  cross-checked against each other.

Usage:  python3 bench/compare.py [--quick] [--only W2,W3.chain,...] [--json out.json]

It creates bench/.venv (pip install -r bench/requirements.txt) on first use and re-runs
itself inside it; rigor is built with `cargo build --release --benches` and driven through
the `cell` benchmark binary (benches/cell.rs).
"""
import argparse
import gc
import glob
import hashlib
import json
import math
import os
import platform
import re
import resource
import select
import statistics
import subprocess
import sys
import time
from fractions import Fraction

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
VENV = os.path.join(HERE, ".venv")
VPY = os.path.join(VENV, "bin", "python")
BENCH_DIR = os.environ.get("RIGOR_BENCH_DIR", os.path.join(REPO, "bench"))
RUN_CAP = 60.0
PREDICT_CAP = 180.0
MEM_LIMIT = 10 * 1024**3
W4_SHA = "f30449ef2a285e294981f8ac9020f14a36e4d2811636ad00de5c6dc47f6c0f9f"


# ======================================================================================
# Workload implementations (run inside child processes, in the venv)
# ======================================================================================

def clear_caches():
    if "sympy" in sys.modules:
        from sympy.core.cache import clear_cache
        clear_cache()
    gc.collect()


def frac_str(q):
    q = Fraction(q)
    return f"{q.numerator}/{q.denominator}"


def w2_serial(d):
    """d: {(i,j,k): Fraction} -> fingerprint of WORKLOADS.md."""
    lines = sorted((k, f"{k[0]} {k[1]} {k[2]} {frac_str(v)}\n") for k, v in d.items() if v != 0)
    text = "".join(l for _, l in lines)
    return {"terms": len(lines), "at_1_1_1": frac_str(sum(Fraction(v) for v in d.values())),
            "sha256": hashlib.sha256(text.encode()).hexdigest()}


# ---------------------------------------------------------------------------- W1 ------

W1_IDS = ["a.rod_IG", "a.rod_IO", "b.disk_IG", "b.disk_IG_area", "c.parallel_axis",
          "d.roll_xdd", "d.roll_thdd", "d.roll_F", "d.friction_ratio", "e.trap_thdd",
          "e.trap_R", "f.perc_ygdd", "f.perc_thdd", "f.perc_ab", "g.sphere_m",
          "g.sphere_I_raw", "g.sphere_I", "h.box_Ixx", "h.box_Iyy", "h.box_Izz",
          "h.box_Ixy", "h.box_Ixz", "h.box_Iyz"]


def w1_fp(results):
    failed = [i for i, ok in results if not ok]
    return {"checks": len(results), "passed": len(results) - len(failed), "failed": failed}


def w1_sympy():
    import sympy as sp
    m, L, R, g, IG, rho, a, b, c = sp.symbols("m L R g I_G rho a b c", positive=True)
    beta, x, y, z, r, F, xdd, thdd, Rr, ygdd, Jx, Jy, bb = sp.symbols(
        "beta x y z r F xdd thdd R_r ygdd Jx Jy b_", real=True)
    sin, cos, tan, pi, S = sp.sin, sp.cos, sp.tan, sp.pi, sp.S

    def run():
        out = []
        chk = lambda i, got, exp: out.append((i, sp.simplify(got - exp) == 0))
        IGr = sp.integrate(y**2 * (m / L), (y, -L / 2, L / 2))
        chk("a.rod_IG", IGr, m * L**2 / 12)
        chk("a.rod_IO", IGr + m * (L / 2)**2, m * L**2 / 3)
        chk("b.disk_IG", sp.integrate(r**2 * (2 * m / R**2) * r, (r, 0, R)), m * R**2 / 2)
        chk("b.disk_IG_area", sp.integrate(r**2 * (m * 2 * pi * r / (pi * R**2)), (r, 0, R)), m * R**2 / 2)
        P = sp.Poly(sp.expand((x + a)**2 + (y + b)**2), x, y)
        M = {(0, 0): m, (1, 0): 0, (0, 1): 0, (2, 0): Jx, (0, 2): Jy}
        got = sum(cf * M[mon] for mon, cf in P.terms())
        chk("c.parallel_axis", got, Jx + Jy + m * (a**2 + b**2))
        (sF, sx, st), = sp.linsolve([F - m * g * sin(beta) - m * xdd, F * R - IG * thdd, xdd + thdd * R], [F, xdd, thdd])
        chk("d.roll_xdd", sx, -g * sin(beta) / (1 + IG / (m * R**2)))
        chk("d.roll_thdd", st, g * sin(beta) * m * R / (m * R**2 + IG))
        chk("d.roll_F", sF, m * g * sin(beta) * IG / (m * R**2 + IG))
        chk("d.friction_ratio", sF / (m * g * cos(beta)), tan(beta) / (1 + m * R**2 / IG))
        (et, eR), = sp.linsolve([-m * g * L / 2 - (m * L**2 / 3) * thdd, Rr - m * g - m * (thdd * L / 2)], [thdd, Rr])
        chk("e.trap_thdd", et, -3 * g / (2 * L))
        chk("e.trap_R", eR, m * g / 4)
        sol = sp.solve([F - m * ygdd, -F * a - IG * thdd, ygdd + thdd * bb], [ygdd, thdd, bb], dict=True)[0]
        chk("f.perc_ygdd", sol[ygdd], F / m)
        chk("f.perc_thdd", sol[thdd], -F * a / IG)
        chk("f.perc_ab", a * sol[bb], IG / m)
        sm = sp.integrate(rho * pi * (R**2 - z**2), (z, -R, R))
        chk("g.sphere_m", sm, S(4) / 3 * pi * rho * R**3)
        sI = sp.integrate(S(1) / 2 * rho * pi * (R**2 - z**2) * (R**2 - z**2), (z, -R, R))
        chk("g.sphere_I_raw", sI, S(8) / 15 * pi * rho * R**5)
        rv = sp.solve(sp.Eq(m, sm), rho)[0]
        chk("g.sphere_I", sI.subs(rho, rv), S(2) / 5 * m * R**2)
        rb = m / (a * b * c)
        box = lambda f: sp.integrate(f, (x, -a / 2, a / 2), (y, -b / 2, b / 2), (z, -c / 2, c / 2))
        chk("h.box_Ixx", box(rb * (y**2 + z**2)), m * (b**2 + c**2) / 12)
        chk("h.box_Iyy", box(rb * (x**2 + z**2)), m * (a**2 + c**2) / 12)
        chk("h.box_Izz", box(rb * (x**2 + y**2)), m * (a**2 + b**2) / 12)
        chk("h.box_Ixy", box(-rb * x * y), 0)
        chk("h.box_Ixz", box(-rb * x * z), 0)
        chk("h.box_Iyz", box(-rb * y * z), 0)
        return out
    return run, w1_fp


def w1_symengine():
    import symengine as se
    (m, L, R, g, IG, rho, a, b, c, beta, x, y, z, r, F, xdd, thdd, Rr, ygdd, Jx, Jy) = se.symbols(
        "m L R g I_G rho a b c beta x y z r F xdd thdd R_r ygdd Jx Jy")
    sin, cos, pi, I = se.sin, se.cos, se.pi, se.Integer

    def integ(f, v, lo, hi):
        terms = []
        for mono, k in se.expand(f).as_coefficients_dict().items():
            p = mono.as_powers_dict().get(v, 0)
            terms.append(k * mono * v / (p + 1))
        Fv = se.Add(*terms)
        return se.expand(Fv.subs(v, hi) - Fv.subs(v, lo))

    def run():
        out = []

        def chk(i, got, exp):
            num, _ = se.expand(got - exp).as_numer_denom()
            out.append((i, se.expand(num) == 0))
        IGr = integ(y**2 * (m / L), y, -L / 2, L / 2)
        chk("a.rod_IG", IGr, m * L**2 / 12)
        chk("a.rod_IO", IGr + m * (L / 2)**2, m * L**2 / 3)
        chk("b.disk_IG", integ(r**2 * (2 * m / R**2) * r, r, 0, R), m * R**2 / 2)
        chk("b.disk_IG_area", integ(r**2 * (m * 2 * pi * r / (pi * R**2)), r, 0, R), m * R**2 / 2)
        M = {(0, 0): m, (1, 0): 0, (0, 1): 0, (2, 0): Jx, (0, 2): Jy}
        got = I(0)
        for mono, k in se.expand((x + a)**2 + (y + b)**2).as_coefficients_dict().items():
            pd = mono.as_powers_dict()
            i, j = pd.get(x, 0), pd.get(y, 0)
            got += k * (mono / (x**i * y**j)) * M[(int(i), int(j))]
        chk("c.parallel_axis", got, Jx + Jy + m * (a**2 + b**2))
        sF, sx, st = se.linsolve([F - m * g * sin(beta) - m * xdd, F * R - IG * thdd, xdd + thdd * R], [F, xdd, thdd])
        chk("d.roll_xdd", sx, -g * sin(beta) / (1 + IG / (m * R**2)))
        chk("d.roll_thdd", st, g * sin(beta) * m * R / (m * R**2 + IG))
        chk("d.roll_F", sF, m * g * sin(beta) * IG / (m * R**2 + IG))
        tanb = sin(beta) / cos(beta)
        chk("d.friction_ratio", sF / (m * g * cos(beta)), tanb / (1 + m * R**2 / IG))
        et, eR = se.linsolve([-m * g * L / 2 - (m * L**2 / 3) * thdd, Rr - m * g - m * (thdd * L / 2)], [thdd, Rr])
        chk("e.trap_thdd", et, -3 * g / (2 * L))
        chk("e.trap_R", eR, m * g / 4)
        fy, ft = se.linsolve([F - m * ygdd, -F * a - IG * thdd], [ygdd, thdd])
        bsol = -fy / ft
        chk("f.perc_ygdd", fy, F / m)
        chk("f.perc_thdd", ft, -F * a / IG)
        chk("f.perc_ab", a * bsol, IG / m)
        sm = integ(rho * pi * (R**2 - z**2), z, -R, R)
        chk("g.sphere_m", sm, I(4) / 3 * pi * rho * R**3)
        sI = integ(I(1) / 2 * rho * pi * (R**2 - z**2) * (R**2 - z**2), z, -R, R)
        chk("g.sphere_I_raw", sI, I(8) / 15 * pi * rho * R**5)
        rv = m / se.expand(sm / rho)
        chk("g.sphere_I", sI.subs(rho, rv), I(2) / 5 * m * R**2)
        rb = m / (a * b * c)
        box = lambda f: integ(integ(integ(f, x, -a / 2, a / 2), y, -b / 2, b / 2), z, -c / 2, c / 2)
        chk("h.box_Ixx", box(rb * (y**2 + z**2)), m * (b**2 + c**2) / 12)
        chk("h.box_Iyy", box(rb * (x**2 + z**2)), m * (a**2 + c**2) / 12)
        chk("h.box_Izz", box(rb * (x**2 + y**2)), m * (a**2 + b**2) / 12)
        chk("h.box_Ixy", box(-rb * x * y), I(0))
        chk("h.box_Ixz", box(-rb * x * z), I(0))
        chk("h.box_Iyz", box(-rb * y * z), I(0))
        return out
    return run, w1_fp


class RF:
    """A small rational-function layer over fmpq_mpoly: gcd-reduced, monic denominator."""
    __slots__ = ("n", "d")

    def __init__(self, n, d=None, reduce=True):
        if d is None:
            d = n.context().from_dict({(0,) * n.context().nvars(): 1})
        if reduce and not d.is_constant():
            gg = n.gcd(d)
            if not gg.is_one():
                n, d = n / gg, d / gg
        lc = d.leading_coefficient()
        if lc != 1:
            n, d = n / lc, d / lc
        self.n, self.d = n, d

    def __add__(s, o):
        o = s._c(o)
        return RF(s.n * o.d + o.n * s.d, s.d * o.d)

    __radd__ = __add__

    def __sub__(s, o):
        o = s._c(o)
        return RF(s.n * o.d - o.n * s.d, s.d * o.d)

    def __rsub__(s, o):
        return s._c(o) - s

    def __mul__(s, o):
        o = s._c(o)
        return RF(s.n * o.n, s.d * o.d)

    __rmul__ = __mul__

    def __truediv__(s, o):
        o = s._c(o)
        if o.n.is_zero():
            raise ZeroDivisionError
        return RF(s.n * o.d, s.d * o.n)

    def __rtruediv__(s, o):
        return s._c(o) / s

    def __neg__(s):
        return RF(-s.n, s.d, False)

    def __pow__(s, k):
        return RF(s.n**k, s.d**k, False)

    def _c(s, o):
        if isinstance(o, RF):
            return o
        return RF(s.n.context().from_dict({(0,) * s.n.context().nvars(): 1}) * o)

    def is_zero(s):
        return s.n.is_zero()


def w1_flint():
    import flint
    names = ["m", "L", "R", "g", "I_G", "sb", "cb", "Jx", "Jy", "a", "b", "c", "rho", "pi",
             "x", "y", "z", "r", "F", "xdd", "thdd", "R_r", "ygdd"]
    ctx = flint.fmpq_mpoly_ctx.get(tuple(names), "lex")
    G = dict(zip(names, ctx.gens()))
    V = {k: RF(v) for k, v in G.items()}
    m, L, R, g, IG, sb, cb, Jx, Jy, a, b, c, rho, pi, x, y, z, r, F, xdd, thdd, Rr, ygdd = (V[k] for k in names)
    Q = flint.fmpq
    idx = {k: i for i, k in enumerate(names)}
    gens = list(ctx.gens())

    def integ(f, v, lo, hi):
        # f = num/den with den free of v; lo, hi polynomial (den 1)
        Fn = f.n.integral(v)
        args_hi = list(gens)
        args_hi[idx[v]] = hi.n
        args_lo = list(gens)
        args_lo[idx[v]] = lo.n
        return RF(Fn.compose(*args_hi) - Fn.compose(*args_lo), f.d)

    def linsolve(eqs, unk):
        # rows: coefficients by derivative (linear equations), Gaussian elimination over RF
        n = len(unk)
        A = []
        for e in eqs:
            row = [RF(e.n.derivative(u), e.d) for u in unk]
            z0 = e.n.subs({u: 0 for u in unk})
            row.append(-RF(z0, e.d))
            A.append(row)
        for k in range(n):
            p = next(i for i in range(k, n) if not A[i][k].is_zero())
            A[k], A[p] = A[p], A[k]
            for i in range(n):
                if i != k and not A[i][k].is_zero():
                    f = A[i][k] / A[k][k]
                    A[i] = [A[i][j] - f * A[k][j] for j in range(n + 1)]
        return [A[i][n] / A[i][i] for i in range(n)]

    def run():
        out = []
        chk = lambda i, got, exp: out.append((i, (got - exp).is_zero()))
        IGr = integ(y**2 * (m / L), "y", -L * Q(1, 2), L * Q(1, 2))
        chk("a.rod_IG", IGr, m * L**2 * Q(1, 12))
        chk("a.rod_IO", IGr + m * (L * Q(1, 2))**2, m * L**2 * Q(1, 3))
        zero = V["x"] * 0
        chk("b.disk_IG", integ(r**2 * (2 * m / R**2) * r, "r", zero, R), m * R**2 * Q(1, 2))
        chk("b.disk_IG_area", integ(r**2 * (m * 2 * pi * r / (pi * R**2)), "r", zero, R), m * R**2 * Q(1, 2))
        M = {(0, 0): m, (1, 0): zero, (0, 1): zero, (2, 0): Jx, (0, 2): Jy}
        sq = ((x + a)**2 + (y + b)**2).n
        got = zero
        ix, iy = idx["x"], idx["y"]
        for mon, k in sq.terms():
            e = list(mon)
            i, j = e[ix], e[iy]
            e[ix] = e[iy] = 0
            got = got + RF(ctx.from_dict({tuple(e): k})) * M[(i, j)]
        chk("c.parallel_axis", got, Jx + Jy + m * (a**2 + b**2))
        sF, sx, st = linsolve([F - m * g * sb - m * xdd, F * R - IG * thdd, xdd + thdd * R], ["F", "xdd", "thdd"])
        chk("d.roll_xdd", sx, -g * sb / (1 + IG / (m * R**2)))
        chk("d.roll_thdd", st, g * sb * m * R / (m * R**2 + IG))
        chk("d.roll_F", sF, m * g * sb * IG / (m * R**2 + IG))
        chk("d.friction_ratio", sF / (m * g * cb), (sb / cb) / (1 + m * R**2 / IG))
        et, eR = linsolve([-m * g * L * Q(1, 2) - (m * L**2 * Q(1, 3)) * thdd, Rr - m * g - m * (thdd * L * Q(1, 2))], ["thdd", "R_r"])
        chk("e.trap_thdd", et, -3 * g / (2 * L))
        chk("e.trap_R", eR, m * g * Q(1, 4))
        fy, ft = linsolve([F - m * ygdd, -F * a - IG * thdd], ["ygdd", "thdd"])
        chk("f.perc_ygdd", fy, F / m)
        chk("f.perc_thdd", ft, -F * a / IG)
        chk("f.perc_ab", a * (-fy / ft), IG / m)
        sm = integ(rho * pi * (R**2 - z**2), "z", -R, R)
        chk("g.sphere_m", sm, pi * rho * R**3 * Q(4, 3))
        sI = integ(rho * pi * (R**2 - z**2) * (R**2 - z**2) * Q(1, 2), "z", -R, R)
        chk("g.sphere_I_raw", sI, pi * rho * R**5 * Q(8, 15))
        rv = m / (sm / rho)
        sub = list(gens)
        # I is polynomial in rho (degree 1): I = k*rho  ->  k*rv
        chk("g.sphere_I", (sI / rho) * rv, m * R**2 * Q(2, 5))
        rb = m / (a * b * c)
        half = lambda s: (s * Q(1, 2), -s * Q(1, 2))
        def box(f):
            hx, lx = half(a); hy, ly = half(b); hz, lz = half(c)
            return integ(integ(integ(f, "x", lx, hx), "y", ly, hy), "z", lz, hz)
        chk("h.box_Ixx", box(rb * (y**2 + z**2)), m * (b**2 + c**2) * Q(1, 12))
        chk("h.box_Iyy", box(rb * (x**2 + z**2)), m * (a**2 + c**2) * Q(1, 12))
        chk("h.box_Izz", box(rb * (x**2 + y**2)), m * (a**2 + b**2) * Q(1, 12))
        chk("h.box_Ixy", box(-rb * x * y), zero)
        chk("h.box_Ixz", box(-rb * x * z), zero)
        chk("h.box_Iyz", box(-rb * y * z), zero)
        return out
    return run, w1_fp


# ---------------------------------------------------------------------------- W2 ------

def w2_sympy_poly(n):
    import sympy as sp
    x, y, z, a, b, c = sp.symbols("x y z a b c")
    gens = (x, y, z, a, b, c)

    def integ_box(P):
        for v in range(3):
            P = P.integrate(gens[v])
            d = {}
            for mon, k in P.terms():
                e = list(mon)
                e[v + 3] += e[v]
                e[v] = 0
                d[tuple(e)] = d.get(tuple(e), 0) + k
            P = sp.Poly.from_dict(d, *gens, domain=sp.QQ)
        return P

    def run():
        rho = sp.Poly((1 + x + y + z)**n, *gens, domain=sp.QQ)
        mass = integ_box(rho)
        ixx = integ_box(rho * sp.Poly(y**2 + z**2, *gens, domain=sp.QQ))
        return mass, ixx

    def fp(res):
        conv = lambda P: {(mon[3], mon[4], mon[5]): Fraction(int(k.numerator), int(k.denominator)) for mon, k in P.terms()}
        return {"mass": w2_serial(conv(res[0])), "Ixx": w2_serial(conv(res[1]))}
    return run, fp


def w2_symengine(n):
    import symengine as se
    x, y, z, a, b, c = se.symbols("x y z a b c")

    def termwise(e):
        out = []
        for mono, k in e.as_coefficients_dict().items():
            pd = mono.as_powers_dict()
            i, j, l = int(pd.get(x, 0)), int(pd.get(y, 0)), int(pd.get(z, 0))
            out.append(k * a**(i + 1) * b**(j + 1) * c**(l + 1) / ((i + 1) * (j + 1) * (l + 1)))
        return se.Add(*out)

    def run():
        rho = se.expand((1 + x + y + z)**n)
        return termwise(rho), termwise(se.expand(rho * (y**2 + z**2)))

    def fp(res):
        def conv(e):
            d = {}
            for mono, k in e.as_coefficients_dict().items():
                pd = mono.as_powers_dict()
                key = (int(pd.get(a, 0)), int(pd.get(b, 0)), int(pd.get(c, 0)))
                d[key] = d.get(key, 0) + Fraction(str(k))
            return d
        return {"mass": w2_serial(conv(res[0])), "Ixx": w2_serial(conv(res[1]))}
    return run, fp


def w2_flint(n):
    import flint
    ctx = flint.fmpq_mpoly_ctx.get(("x", "y", "z", "a", "b", "c"), "lex")
    x, y, z, a, b, c = ctx.gens()

    def box(P):
        P = P.integral("x").compose(a, y, z, a, b, c)
        P = P.integral("y").compose(x, b, z, a, b, c)
        return P.integral("z").compose(x, y, c, a, b, c)

    def run():
        rho = (1 + x + y + z)**n
        return box(rho), box(rho * (y**2 + z**2))

    def fp(res):
        conv = lambda P: {(e[3], e[4], e[5]): Fraction(int(k.p), int(k.q)) for e, k in P.terms()}
        return {"mass": w2_serial(conv(res[0])), "Ixx": w2_serial(conv(res[1]))}
    return run, fp


# ---------------------------------------------------------------------------- W3 ------

def w3_entries(kind, n):
    """Matrix and rhs as nested python structures over symbol names (Fraction coeffs):
    each entry a dict {tuple(sorted (name, exp)): Fraction}."""
    def mono(*names):
        d = {}
        for s in names:
            d[s] = d.get(s, 0) + 1
        return tuple(sorted(d.items()))
    A = [[{} for _ in range(n)] for _ in range(n)]
    rhs = []
    for i in range(1, n + 1):
        for j in range(1, n + 1):
            e = {}
            if kind == "chain":
                K = i if i == j else max(i, j)
                e[mono(f"l{i}", f"l{j}", f"m{K}")] = Fraction(1, 3) if i == j else Fraction(1, 2)
                for k in range(K + 1, n + 1):
                    e[mono(f"l{i}", f"l{j}", f"m{k}")] = Fraction(1)
            elif kind == "tri":
                if i == j:
                    e[mono(f"k{i}")] = Fraction(1)
                    e[mono(f"k{i + 1}")] = Fraction(1)
                    e[mono("w", "w", f"m{i}")] = Fraction(-1)
                elif abs(i - j) == 1:
                    e[mono(f"k{max(i, j)}")] = Fraction(-1)
            else:
                e[mono(f"a{i}_{j}")] = Fraction(1)
            A[i - 1][j - 1] = e
        rhs.append({mono({"chain": "Q", "tri": "f"}.get(kind, "b") + str(i)): Fraction(1)})
    return A, rhs


def w3_point(kind, name):
    if kind == "chain":
        i = int(name[1:])
        return Fraction(i + 1) if name[0] == "l" else Fraction(i)
    if kind == "tri":
        return Fraction(1, 2) if name == "w" else Fraction(int(name[1:]))
    if name[0] == "a":
        i, j = name[1:].split("_")
        return Fraction(1, int(i) + int(j) - 1)
    return Fraction(int(name[1:]))


def w3_symbols(kind, n):
    if kind == "chain":
        return [f"m{i}" for i in range(1, n + 1)] + [f"l{i}" for i in range(1, n + 1)] + [f"Q{i}" for i in range(1, n + 1)]
    if kind == "tri":
        return [f"k{i}" for i in range(1, n + 2)] + [f"m{i}" for i in range(1, n + 1)] + ["w"] + [f"f{i}" for i in range(1, n + 1)]
    return [f"a{i}_{j}" for i in range(1, n + 1) for j in range(1, n + 1)] + [f"b{i}" for i in range(1, n + 1)]


def w3_sympy_linsolve(kind, n):
    import sympy as sp
    names = w3_symbols(kind, n)
    S = {s: sp.Symbol(s) for s in names}
    Aent, rent = w3_entries(kind, n)
    conv = lambda e: sp.Add(*[sp.Rational(k.numerator, k.denominator) * sp.Mul(*[S[s]**p for s, p in mon]) for mon, k in e.items()])
    A = sp.Matrix([[conv(e) for e in row] for row in Aent])
    b = sp.Matrix([conv(e) for e in rent])
    xs = sp.symbols(f"x1:{n + 1}")

    def run():
        (sol,) = sp.linsolve((A, b), list(xs))
        return list(sol)

    def fp(sol):
        pt = {S[s]: sp.Rational(w3_point(kind, s).numerator, w3_point(kind, s).denominator) for s in names}
        vals = [sp.nsimplify(e.xreplace(pt)) for e in sol]
        return {"values": [frac_str(Fraction(int(v.p), int(v.q))) for v in vals],
                "sum": frac_str(sum(Fraction(int(v.p), int(v.q)) for v in vals))}
    return run, fp


def w3_flint_bareiss(kind, n):
    import flint
    names = w3_symbols(kind, n)
    ctx = flint.fmpq_mpoly_ctx.get(tuple(names), "lex")
    G = dict(zip(names, ctx.gens()))
    one = ctx.from_dict({(0,) * len(names): 1})
    zero = one - one

    def conv(e):
        p = zero
        for mon, k in e.items():
            t = one * flint.fmpq(k.numerator, k.denominator)
            for s, pw in mon:
                t = t * G[s]**pw
            p = p + t
        return p
    Aent, rent = w3_entries(kind, n)
    A0 = [[conv(e) for e in row] + [conv(r)] for row, r in zip(Aent, rent)]

    def run():
        M = [list(r) for r in A0]
        prev = one
        for k in range(n):
            p = min((i for i in range(k, n) if not M[i][k].is_zero()), key=lambda i: len(M[i][k]))
            M[k], M[p] = M[p], M[k]
            for i in range(k + 1, n):
                for j in range(k + 1, n + 1):
                    M[i][j] = (M[k][k] * M[i][j] - M[i][k] * M[k][j]) / prev
                M[i][k] = zero
            prev = M[k][k]
        det = prev
        nums = [zero] * n
        for i in range(n - 1, -1, -1):
            t = M[i][n] * det
            for j in range(i + 1, n):
                t = t - M[i][j] * nums[j]
            nums[i] = t / M[i][i]
        out = []
        for num in nums:
            g = num.gcd(det)
            out.append((num / g, det / g))
        return out

    def fp(sol):
        pt = {s: flint.fmpq(w3_point(kind, s).numerator, w3_point(kind, s).denominator) for s in names}
        def ev(p):
            v = p.subs(pt)
            return Fraction(0) if v.is_zero() else Fraction(int(v.leading_coefficient().p), int(v.leading_coefficient().q))
        vals = [ev(a) / ev(b) for a, b in sol]
        return {"values": [frac_str(v) for v in vals], "sum": frac_str(sum(vals)),
                "num_terms": sum(len(a) for a, _ in sol), "den_terms": max(len(b) for _, b in sol)}
    return run, fp


# ---------------------------------------------------------------------------- W4 ------

TOK = re.compile(r"\s*(\d+|[wxyz]|[-+*/^()])")


def parse_w4(s):
    toks = TOK.findall(s)
    pos = [0]
    peek = lambda: toks[pos[0]] if pos[0] < len(toks) else None

    def take():
        pos[0] += 1
        return toks[pos[0] - 1]

    def expr():
        e = term()
        while peek() in ("+", "-"):
            op = take()
            e = (op, e, term())
        return e

    def term():
        e = unary()
        while peek() in ("*", "/"):
            op = take()
            e = (op, e, unary())
        return e

    def unary():
        if peek() == "-":
            take()
            return ("neg", unary())
        return power()

    def power():
        a = atom()
        if peek() == "^":
            take()
            return ("^", a, int(take()))
        return a

    def atom():
        t = take()
        if t == "(":
            e = expr()
            assert take() == ")"
            return e
        if t.isdigit():
            return ("int", int(t))
        return ("sym", t)
    e = expr()
    assert pos[0] == len(toks), s
    return e


def w4_load(npairs):
    path = os.path.join(BENCH_DIR, "w4_pairs.tsv")
    raw = open(path, "rb").read()
    assert hashlib.sha256(raw).hexdigest() == W4_SHA, "w4_pairs.tsv: wrong SHA-256"
    pairs = []
    for line in raw.decode().splitlines():
        if line.startswith("#") or not line.strip():
            continue
        f = line.split("\t")
        pairs.append((f[1] == "1", parse_w4(f[3]), parse_w4(f[4])))
    return pairs[:npairs]


def build(e, leaf, ops):
    t = e[0]
    if t == "int":
        return leaf(("int", e[1]))
    if t == "sym":
        return leaf(("sym", e[1]))
    if t == "neg":
        return ops["neg"](build(e[1], leaf, ops))
    if t == "^":
        return ops["^"](build(e[1], leaf, ops), e[2])
    return ops[t](build(e[1], leaf, ops), build(e[2], leaf, ops))


PY_OPS = {"+": lambda a, b: a + b, "-": lambda a, b: a - b, "*": lambda a, b: a * b,
          "/": lambda a, b: a / b, "^": lambda a, k: a**k, "neg": lambda a: -a}


def w4_fp_of(pairs):
    def fp(dec):
        return {"pairs": len(dec), "decided_equal": sum(dec), "label_equal": sum(p[0] for p in pairs),
                "mismatches": sum(1 for p, d in zip(pairs, dec) if p[0] != d)}
    return fp


def w4_sympy_cancel(npairs):
    import sympy as sp
    pairs = w4_load(npairs)
    S = {s: sp.Symbol(s) for s in "wxyz"}
    leaf = lambda l: sp.Integer(l[1]) if l[0] == "int" else S[l[1]]

    def run():
        return [sp.cancel(build(a, leaf, PY_OPS) - build(b, leaf, PY_OPS)) == 0 for _, a, b in pairs]
    return run, w4_fp_of(pairs)


def w4_symengine_expand(npairs):
    import symengine as se
    pairs = w4_load(npairs)
    S = {s: se.Symbol(s) for s in "wxyz"}
    leaf = lambda l: se.Integer(l[1]) if l[0] == "int" else S[l[1]]

    def run():
        out = []
        for _, a, b in pairs:
            A, B = build(a, leaf, PY_OPS), build(b, leaf, PY_OPS)
            n1, d1 = A.as_numer_denom()
            n2, d2 = B.as_numer_denom()
            out.append(se.expand(n1 * d2 - n2 * d1) == 0)
        return out
    return run, w4_fp_of(pairs)


def w4_flint_crossmul(npairs):
    import flint
    pairs = w4_load(npairs)
    ctx = flint.fmpq_mpoly_ctx.get(("w", "x", "y", "z"), "lex")
    G = dict(zip("wxyz", ctx.gens()))
    one = ctx.from_dict({(0, 0, 0, 0): 1})

    def leaf(l):
        return (one * l[1], one) if l[0] == "int" else (G[l[1]], one)
    ops = {"+": lambda a, b: (a[0] * b[1] + b[0] * a[1], a[1] * b[1]),
           "-": lambda a, b: (a[0] * b[1] - b[0] * a[1], a[1] * b[1]),
           "*": lambda a, b: (a[0] * b[0], a[1] * b[1]),
           "/": lambda a, b: (a[0] * b[1], a[1] * b[0]),
           "^": lambda a, k: (a[0]**k, a[1]**k),
           "neg": lambda a: (-a[0], a[1])}

    def run():
        out = []
        for _, a, b in pairs:
            (n1, d1), (n2, d2) = build(a, leaf, ops), build(b, leaf, ops)
            out.append((n1 * d2 - n2 * d1).is_zero())
        return out
    return run, w4_fp_of(pairs)


# ------------------------------------------------------------------- registry ---------

VARIANTS = {
    # (workload family, variant): (tool, factory(workload, size) -> (run, fp))
    ("W1", "sympy"): ("sympy", lambda w, n: w1_sympy()),
    ("W1", "symengine"): ("symengine", lambda w, n: w1_symengine()),
    ("W1", "flint"): ("flint", lambda w, n: w1_flint()),
    ("W2", "sympy_poly"): ("sympy", lambda w, n: w2_sympy_poly(n)),
    ("W2", "symengine_expand_termwise"): ("symengine", lambda w, n: w2_symengine(n)),
    ("W2", "flint_mpoly_integral"): ("flint", lambda w, n: w2_flint(n)),
    ("W3", "sympy_linsolve"): ("sympy", lambda w, n: w3_sympy_linsolve(w.split(".")[1], n)),
    ("W3", "flint_bareiss"): ("flint", lambda w, n: w3_flint_bareiss(w.split(".")[1], n)),
    ("W4", "sympy_cancel"): ("sympy", lambda w, n: w4_sympy_cancel(n)),
    ("W4", "symengine_expand"): ("symengine", lambda w, n: w4_symengine_expand(n)),
    ("W4", "flint_crossmul"): ("flint", lambda w, n: w4_flint_crossmul(n)),
}


def smallest(workload, size):
    if workload == "W2":
        return 2
    if workload.startswith("W3."):
        return 2
    return size


def beat(ev, t=None):
    sys.stdout.write(json.dumps({"event": ev, **({"t": t} if t is not None else {})}) + "\n")
    sys.stdout.flush()


def peak_rss_kb():
    """This process's peak resident set (VmHWM; wait4's ru_maxrss would include the
    forking parent's image)."""
    try:
        for line in open("/proc/self/status"):
            if line.startswith("VmHWM:"):
                return int(line.split()[1])
    except OSError:
        pass
    return 0


def child_main(variant, workload, size):
    tool, factory = VARIANTS[(workload.split(".")[0], variant)]
    run, fp = factory(workload, smallest(workload, size))
    clear_caches()
    run()
    run, fp = factory(workload, size)

    def timed():
        clear_caches()
        t = time.perf_counter()
        r = run()
        return time.perf_counter() - t, r
    beat("start")
    t0, r0 = timed()
    beat("end", t0)
    f0 = fp(r0)
    samples = []
    if t0 < 5:
        k = min(7, max(3, int(20 // t0)))
    else:
        samples.append(t0)
        k = 2 if t0 < 15 else (1 if t0 < 30 else 0)
    for _ in range(k):
        beat("start")
        t, r = timed()
        beat("end", t)
        samples.append(t)
    if k:
        assert fp(r) == f0, "fingerprint changed between runs"
    rec = {"workload": workload, "variant": variant, "tool": tool, "size": size, "status": "ok",
           "median": statistics.median(samples), "best": min(samples), "n": len(samples),
           "samples": samples, "fingerprint": f0, "peak_rss_kb": peak_rss_kb()}
    print(json.dumps(rec))


# ======================================================================================
# Driver
# ======================================================================================

def ensure_venv():
    if os.path.abspath(sys.prefix) == os.path.abspath(VENV):
        return
    req = os.path.join(HERE, "requirements.txt")
    stamp = os.path.join(VENV, ".installed")
    if not os.path.exists(VPY):
        print(f"creating {VENV} ...", file=sys.stderr)
        subprocess.check_call([sys.executable, "-m", "venv", VENV])
    if not os.path.exists(stamp) or os.path.getmtime(stamp) < os.path.getmtime(req):
        subprocess.check_call([VPY, "-m", "pip", "install", "-q", "-r", req])
        open(stamp, "w").close()
    os.execv(VPY, [VPY] + sys.argv)


def build_rigor():
    print("building rigor (cargo build --release --benches) ...", file=sys.stderr)
    subprocess.check_call(["cargo", "build", "--release", "--benches", "--bins", "-q"], cwd=REPO)
    # Builds land in target/<host triple>/ (.cargo/config.toml names the host as the target).
    host = re.search(r"^host: (\S+)$", subprocess.check_output(["rustc", "-vV"], text=True), re.M).group(1)
    release = os.path.join(os.environ.get("CARGO_TARGET_DIR") or os.path.join(REPO, "target"), host, "release")
    cands = [p for p in glob.glob(os.path.join(release, "deps", "cell-*"))
             if os.access(p, os.X_OK) and not p.endswith(".d")]
    cell = max(cands, key=os.path.getmtime)
    return cell, os.path.join(release, "rigor")


def limit_child():
    resource.setrlimit(resource.RLIMIT_AS, (MEM_LIMIT, MEM_LIMIT))


def run_cell(cmd):
    """Runs one cell; kills a run longer than RUN_CAP. Returns (record, peak RSS in MB)."""
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, preexec_fn=limit_child, cwd=REPO)
    buf = b""
    started = None
    status = None
    record = None
    fd = p.stdout.fileno()
    while True:
        r, _, _ = select.select([fd], [], [], 0.5)
        if r:
            chunk = os.read(fd, 65536)
            if not chunk:
                break
            buf += chunk
            while b"\n" in buf:
                line, buf = buf.split(b"\n", 1)
                try:
                    o = json.loads(line)
                except ValueError:
                    continue
                if o.get("event") == "start":
                    started = time.monotonic()
                elif o.get("event") == "end":
                    started = None
                elif "workload" in o:
                    record = o
        if started is not None and time.monotonic() - started > RUN_CAP:
            p.kill()
            status = "timeout"
            break
    p.stdout.close()
    _, wstatus, ru = os.wait4(p.pid, 0)
    p.returncode = os.waitstatus_to_exitcode(wstatus)
    err = p.stderr.read().decode(errors="replace")
    p.stderr.close()
    rss = ru.ru_maxrss / 1024.0  # upper bound (includes the forked parent); VmHWM preferred
    if record is not None and record.get("peak_rss_kb"):
        rss = record["peak_rss_kb"] / 1024.0
    if record is None:
        lines = err.strip().splitlines()
        msg = [l for i, l in enumerate(lines) if "panicked" in l or (i and "panicked" in lines[i - 1])]
        msg = msg or lines[-3:] or [f"exit {p.returncode}"]
        if status:
            pass
        elif "Limit(Terms)" in err:
            status = "refused"
            msg = ["rigor's term limit: an intermediate polynomial would exceed 2,000,000 terms"]
        elif "MemoryError" in err or "memory allocation" in err:
            status = "memory"
        else:
            status = "error"
        record = {"status": status, "error": msg}
    return record, rss


# --------------------------------------------------------------------- checking -------

def load_expected():
    exp = json.load(open(os.path.join(BENCH_DIR, "expected.json")))
    # canonical sizes from the W3 table of WORKLOADS.md
    sizes = {}
    for line in open(os.path.join(BENCH_DIR, "WORKLOADS.md")):
        m = re.match(r"\|\s*(chain|tri|dense)\s*\|\s*(\d+)\s*\|[^|]*\|[^|]*\|\s*(\d+)\s*\|\s*(\d+)\s*\|", line)
        if m:
            sizes[(m.group(1), int(m.group(2)))] = (int(m.group(3)), int(m.group(4)))
    return exp, sizes


def check(rec, exp, w3sizes):
    """Returns '' if the fingerprint is right, else a description of the mismatch."""
    w, n, fp = rec["workload"], rec["size"], rec.get("fingerprint") or {}
    if w == "W1":
        return "" if fp.get("checks") == 23 and fp.get("passed") == 23 else f"W1 {fp}"
    if w == "W1.check":
        return "" if fp.get("ok") and fp.get("failed") == 0 else f"check {fp}"
    if w == "W2":
        e = exp["W2"][str(n)]
        bad = []
        for k in ("mass", "Ixx"):
            for f in ("terms", "at_1_1_1", "sha256"):
                if fp.get(k, {}).get(f) != e[k][f]:
                    bad.append(f"{k}.{f}")
        return ",".join(bad)
    if w.startswith("W3."):
        kind = w[3:]
        e = exp["W3"][kind][str(n)]
        bad = []
        if fp.get("values") != e["values"]:
            bad.append("values")
        if fp.get("sum") != e["sum"]:
            bad.append("sum")
        if "num_terms" in fp and (kind, n) in w3sizes:
            if (fp["num_terms"], fp["den_terms"]) != w3sizes[(kind, n)]:
                bad.append(f"terms {fp['num_terms']}/{fp['den_terms']} != {w3sizes[(kind, n)]}")
        return ",".join(bad)
    if w == "W4":
        ok = fp.get("mismatches") == 0 and fp.get("pairs") == n
        if n == 1000:
            ok = ok and fp.get("decided_equal") == 500 and fp.get("label_equal") == 500
        return "" if ok else f"W4 {fp}"
    return "unknown workload"


# ------------------------------------------------------------------------ plan --------

def plan(quick):
    full = {"W2": [2, 4, 8, 12, 16, 20], "W3.chain": list(range(2, 9)), "W3.tri": list(range(2, 9)),
            "W3.dense": list(range(2, 8))}
    small = {"W2": [2, 4, 8], "W3.chain": list(range(2, 7)), "W3.tri": list(range(2, 6)),
             "W3.dense": list(range(2, 6))}
    series = []  # (workload, variant, tool, sizes)
    series.append(("W1", "rigor", "rigor", [1]))
    series.append(("W1.check", "rigor", "rigor", [1]))
    for v in ("sympy", "symengine", "flint"):
        series.append(("W1", v, VARIANTS[("W1", v)][0], [1]))
    series.append(("W2", "rigor", "rigor", full["W2"]))
    for v in ("sympy_poly", "symengine_expand_termwise", "flint_mpoly_integral"):
        tool = VARIANTS[("W2", v)][0]
        series.append(("W2", v, tool, small["W2"] if quick and tool == "sympy" else full["W2"]))
    for kind in ("chain", "tri", "dense"):
        w = f"W3.{kind}"
        series.append((w, "rigor", "rigor", full[w]))
        series.append((w, "flint_bareiss", "flint", full[w]))
        if kind == "chain":
            series.append((w, "sympy_linsolve", "sympy", small[w] if quick else full[w]))
    series.append(("W4", "rigor", "rigor", [1000]))
    series.append(("W4", "sympy_cancel", "sympy", [250] if quick else [1000]))
    series.append(("W4", "symengine_expand", "symengine", [1000]))
    series.append(("W4", "flint_crossmul", "flint", [1000]))
    return series


def fit_exponent(pts):
    pts = [(math.log(n), math.log(t)) for n, t in pts if t > 0]
    if len(pts) < 2:
        return None
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx)**2 for p in pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx if sxx else None


def fmt_t(t):
    if t is None:
        return "-"
    if t < 1e-3:
        return f"{t * 1e6:.0f} µs"
    if t < 1:
        return f"{t * 1e3:.2f} ms"
    return f"{t:.2f} s"


def machine_info():
    cpu = "?"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    vers = {}
    for mod, name in (("sympy", "sympy"), ("symengine", "symengine"), ("flint", "python-flint")):
        try:
            vers[name] = __import__(mod).__version__
        except Exception as e:  # noqa
            vers[name] = f"unavailable ({e})"
    rustc = subprocess.run(["rustc", "--version"], capture_output=True, text=True).stdout.strip()
    return {"date": time.strftime("%Y-%m-%d %H:%M %Z"), "cpu": cpu, "cores": os.cpu_count(),
            "python": platform.python_version(), "rustc": rustc, **vers}


def time_check_cli(rigor_bin, runs):
    ts = []
    for _ in range(runs + 2):
        t = time.perf_counter()
        p = subprocess.run([rigor_bin, "check", "derivations/"], cwd=REPO, stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL)
        ts.append(time.perf_counter() - t)
    ts = ts[2:]  # two warm-up runs (page cache)
    return statistics.median(ts), min(ts), p.returncode


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="small sizes for the slow SymPy variants")
    ap.add_argument("--only", default="", help="comma-separated workload prefixes (W1,W2,W3.chain,...)")
    ap.add_argument("--tools", default="", help="comma-separated tools (rigor,sympy,symengine,flint)")
    ap.add_argument("--json", default=os.path.join(HERE, "results.json"), help="raw records out")
    ap.add_argument("--check-runs", type=int, default=30, help="runs of `rigor check derivations/`")
    ap.add_argument("--child", nargs=3, metavar=("VARIANT", "WORKLOAD", "SIZE"), help=argparse.SUPPRESS)
    ap.add_argument("--render", metavar="JSON", help="print the table of a saved results file and exit")
    args = ap.parse_args()
    if args.render:
        d = json.load(open(args.render))
        m = d["meta"]
        print(f"# {m['date']} | {m['cpu']} | {m['cores']} cores | Python {m['python']} | sympy {m['sympy']} | "
              f"symengine {m['symengine']} | python-flint {m['python-flint']} | {m['rustc']}")
        print_table(d["records"], m, d.get("check_cli"), args.check_runs)
        return
    if args.child:
        child_main(args.child[0], args.child[1], int(args.child[2]))
        return
    ensure_venv()
    cell_bin, rigor_bin = build_rigor()
    exp, w3sizes = load_expected()
    info = machine_info()
    print(f"# {info['date']} | {info['cpu']} | {info['cores']} cores | Python {info['python']} | "
          f"sympy {info['sympy']} | symengine {info['symengine']} | python-flint {info['python-flint']} | {info['rustc']}",
          flush=True)
    only = [s for s in args.only.split(",") if s]
    tools = [s for s in args.tools.split(",") if s]
    records = []
    for workload, variant, tool, sizes in plan(args.quick):
        if only and not any(workload.startswith(o) for o in only):
            continue
        if tools and tool not in tools:
            continue
        done = []  # (n, median) of ok sizes
        stop = None
        for n in sizes:
            rec = {"workload": workload, "variant": variant, "tool": tool, "size": n}
            if stop:
                rec.update(status="skipped", why=stop)
                records.append(rec)
                continue
            if len(done) >= 2:
                (n1, t1), (n2, t2) = done[-2], done[-1]
                p = math.log(max(t2, 1e-9) / max(t1, 1e-9)) / math.log(n2 / n1)
                pred = t2 * (n / n2)**p
                if pred > PREDICT_CAP:
                    stop = f"predicted {pred:.0f} s"
                    rec.update(status="skipped", why=stop)
                    records.append(rec)
                    continue
            if tool == "rigor":
                cmd = [cell_bin, workload, str(n)]
            else:
                cmd = [sys.executable, os.path.abspath(__file__), "--child", variant, workload, str(n)]
            t_start = time.time()
            out, rss = run_cell(cmd)
            rec.update(out)
            rec.update(workload=workload, variant=variant, tool=tool, size=n, rss_mb=rss)
            if rec.get("status") == "ok":
                rec["check"] = check(rec, exp, w3sizes)
                done.append((n, rec["median"]))
            else:
                stop = rec.get("status")
            records.append(rec)
            print(f"  {workload:9} {variant:26} n={n:<5} {rec.get('status'):8} median {fmt_t(rec.get('median')):>10} "
                  f"best {fmt_t(rec.get('best')):>10} rss {rss:7.1f} MB  {'OK' if rec.get('check') == '' else rec.get('check', '')}"
                  f"  ({time.time() - t_start:.0f} s)", file=sys.stderr, flush=True)
    cli = None
    if not only or "check" in only:
        cli = time_check_cli(rigor_bin, args.check_runs)
    json.dump({"meta": info, "records": records, "check_cli": cli}, open(args.json, "w"), indent=1)
    print_table(records, info, cli, args.check_runs)


def print_table(records, info, cli, cli_runs):
    rig = {(r["workload"], r["size"]): r for r in records if r["tool"] == "rigor" and r.get("status") == "ok"}
    # W4 rigor at 250 pairs is not measured separately: compare throughput (pairs/s) instead.
    print()
    print("| workload | n | tool / variant | median | best | runs | peak RSS | result | tool ÷ rigor (median) |")
    print("|---|---|---|---|---|---|---|---|---|")
    order = {"rigor": 0, "sympy": 1, "symengine": 2, "flint": 3}
    keyf = lambda r: (r["workload"], r["size"], order[r["tool"]], r["variant"])
    for r in sorted(records, key=keyf):
        st = r.get("status")
        if st == "ok":
            res = "ok" if r.get("check") == "" else f"**MISMATCH: {r.get('check')}**"
            rr = rig.get((r["workload"], r["size"]))
            ratio = "—" if r["tool"] == "rigor" else (f"{r['median'] / rr['median']:.2f}×" if rr else "")
            if r["workload"] == "W4":
                pps = r["size"] / r["median"]
                rr = rig.get(("W4", 1000))
                ratio = "—" if r["tool"] == "rigor" else (f"{pps and (1000 / rr['median']) / pps:.2f}× (pairs/s)" if rr else "")
                res = f"{res}, {pps:,.0f} pairs/s"
            print(f"| {r['workload']} | {r['size']} | {r['tool']} / {r['variant']} | {fmt_t(r['median'])} | {fmt_t(r['best'])} | "
                  f"{r['n']} | {r['rss_mb']:.0f} MB | {res} | {ratio} |")
        else:
            why = r.get("why") or "; ".join(r.get("error", []))[:80]
            print(f"| {r['workload']} | {r['size']} | {r['tool']} / {r['variant']} | {st} | | | "
                  f"{r.get('rss_mb', 0):.0f} MB | {why} | |")
    if cli:
        print(f"\n`rigor check derivations/` (release binary, process start included, {cli_runs} runs): "
              f"median {fmt_t(cli[0])}, best {fmt_t(cli[1])}, exit code {cli[2]}")
    print("\nFitted scaling exponent p (t ∝ n^p, log-log least squares over the measured sizes):\n")
    print("| series | variant | sizes | p |")
    print("|---|---|---|---|")
    series = {}
    for r in records:
        if r.get("status") == "ok" and (r["workload"] == "W2" or r["workload"].startswith("W3.")):
            series.setdefault((r["workload"], r["tool"], r["variant"]), []).append((r["size"], r["median"]))
    for (w, tool, v), pts in sorted(series.items(), key=lambda kv: (kv[0][0], order[kv[0][1]])):
        p = fit_exponent(pts)
        print(f"| {w} | {tool} / {v} | {min(n for n, _ in pts)}–{max(n for n, _ in pts)} | "
              f"{'-' if p is None else f'{p:.2f}'} |")
    bad = [r for r in records if r.get("status") == "ok" and r.get("check")]
    print("\nCross-check: " + ("all results agree with expected.json / WORKLOADS.md (hence with each other)."
                               if not bad else f"{len(bad)} MISMATCHES: " +
                               "; ".join(f"{r['workload']} n={r['size']} {r['variant']}: {r['check']}" for r in bad)))


if __name__ == "__main__":
    main()
