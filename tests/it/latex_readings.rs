//! Regression tests for issue 27, item 4: LaTeX in a derivation's `$$ … $$` means
//! what a physicist means. Every case the issue lists: the false ones must not verify
//! (refused or failed, never verified), the true ones must verify.

use rigor::check::{check_source, MemoryResolver};

/// Checks `text` as a derivation: (every claim verified, bad input, the diagnostics).
fn check(text: &str) -> (bool, bool, String) {
    let r = check_source(
        "case.deriv",
        text,
        &crate::no_budget(),
        &MemoryResolver::new(),
    );
    let diags: String = r
        .diagnostics
        .iter()
        .map(|d| rigor::diag::render(d, "case.deriv", &r.source))
        .collect();
    (r.ok(), r.input_error, diags)
}

fn verifies(text: &str) {
    let (ok, _, diags) = check(text);
    assert!(ok, "should verify:\n{text}\n{diags}");
}

fn does_not_verify(text: &str) {
    let (ok, _, diags) = check(text);
    assert!(!ok, "must not verify:\n{text}");
    assert!(!diags.is_empty(), "a diagnostic says why:\n{text}");
}

/// Refused as input (exit status 2), with `needle` in the diagnostics.
fn refused(text: &str, needle: &str) {
    let (ok, input, diags) = check(text);
    assert!(!ok && input, "must be refused as input:\n{text}\n{diags}");
    assert!(diags.contains(needle), "{needle:?} in:\n{diags}");
}

#[test]
fn leibniz_notation_is_never_a_quotient_of_products() {
    refused(
        "symbols d x t\nclaim $$ \\frac{dx}{dt} = \\frac{x}{t} $$\n",
        "time x",
    );
    refused(
        "symbols d x t\nclaim $$ \\frac{\\mathrm{d}x}{\\mathrm{d}t} = \\frac{x}{t} $$\n",
        "time x",
    );
    // Undeclared x: the hint still says to declare it a function of time.
    refused(
        "symbols t\nclaim $$ \\frac{dx}{dt} = \\frac{x}{t} $$\n",
        "time x",
    );
    refused(
        "symbols d F m v t > 0\ngiven [n] $$ F = m\\frac{dv}{dt} $$\nclaim $$ F t = m v $$ by [n]\n",
        "time v",
    );
    does_not_verify(
        "time v\nsymbols d F m > 0\ngiven [n] $$ F = m\\frac{dv}{dt} $$\nclaim $$ F t = m v $$ by [n]\n",
    );
    // With `d` and `Delta` declared (a diameter, a discriminant), the notation still
    // means a derivative and increments: these verified as products before.
    does_not_verify(
        "time x\nsymbols Delta Delta_x Delta_t > 0\nclaim $$ \\frac{\\Delta x}{\\Delta t} = \\frac{x}{t} $$\n",
    );
    refused(
        "symbols Delta x t\nclaim $$ \\frac{\\Delta x}{\\Delta t} = \\frac{x}{t} $$\n",
        "undeclared symbol `Delta_x`",
    );
    refused(
        "symbols d m v t\nclaim $$ \\frac{d}{dt}(m v) = \\frac{m v}{t} $$\n",
        "does not change with time",
    );
    refused(
        "symbols d x y\nclaim $$ \\frac{dy}{dx} = \\frac{y}{x} $$\n",
        "does not depend on x",
    );
    refused(
        "symbols d m x\nclaim $$ \\frac{dm}{dx} = \\frac{m}{x} $$\n",
        "of `m`, which as declared does not depend on x",
    );
}

#[test]
fn leibniz_notation_of_time_symbols_verifies() {
    verifies("time theta\nclaim $$ \\dot\\theta = \\frac{d\\theta}{dt} $$\n");
    verifies("time x\nclaim $$ \\ddot x = \\frac{d^2x}{dt^2} = \\frac{\\mathrm{d}^2x}{\\mathrm{d}t^2} $$\n");
    verifies("time x\nclaim $$ \\frac{d}{dt}(x^3) = 3x^2\\dot x $$\n");
    verifies("symbols a x\nclaim $$ \\frac{d}{dx}(a x^3) = 3 a x^2 $$\n");
    // A diameter d stays a quotient.
    verifies("symbols d > 0\nclaim $$ \\frac{d}{2} + \\frac{d}{2} = d $$\n");
}

#[test]
fn a_declared_e_is_the_symbol() {
    verifies("symbols e > 0\nclaim $$ e^2 = e \\cdot e $$\n");
    does_not_verify("symbols e > 0\nclaim $$ \\ln e^2 = 2 $$\n");
    verifies("symbols e\nclaim e^2 = e * e\n");
    does_not_verify("symbols e > 0\nclaim ln(e^2) = 2\n");
    // Undeclared, e^{x} is Euler's number to the x.
    verifies("symbols x\nclaim $$ \\ln e^{x} = x $$\n");
    verifies("symbols x\nclaim $$ e^{x} = \\exp(x) $$\n");
}

#[test]
fn a_function_takes_the_factors_after_it() {
    does_not_verify("symbols A omega t > 0\nclaim $$ A \\cos\\omega t = A t \\cos\\omega $$\n");
    verifies("symbols A omega t\nclaim $$ A \\cos\\omega t = A \\cos(\\omega t) $$\n");
    verifies("symbols theta\nclaim $$ \\sin\\theta\\cos\\theta = \\frac{1}{2}\\sin 2\\theta $$\n");
    verifies("symbols x\nclaim $$ \\sin x^2 = \\sin(x^2) $$\n");
}

#[test]
fn times_between_vectors_is_refused_never_failed() {
    refused(
        "symbols omega r\nclaim $$ \\omega \\times r = - r \\times \\omega $$\n",
        "cross product",
    );
    refused(
        "symbols omega r\nclaim $$ \\omega \\times r = \\omega r $$\n",
        "cross product",
    );
    verifies("claim $$ 3 \\times 10^{4} = 30000 $$\n");
    verifies("symbols m\nclaim $$ 2 \\times m = m + m $$\n");
}
