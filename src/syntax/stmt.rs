//! Statements of a derivation file (FORMAT.md §2): one parser per keyword, each over the
//! statement's region (its first line and continuation lines) with absolute spans.

use super::ast::{BodyDef, Chain, Label, Name, Range, SignDecl, Stmt, StmtKind, UnitDecl};
use super::chain::{assignments, by_clause, chain_or_expr, label, label_list, name, ChainRules};
use super::error::{failure, failure_of_kind, PResult, SyntaxError};
use super::expr::expr;
use super::lex::{end, expected, hspace, ident, keyword, number, punct, token_len, ws, Cx};
use num_traits::Zero;

/// The words that start a statement.
pub(crate) const KEYWORDS: [&str; 12] = [
    "symbols",
    "small",
    "result",
    "time",
    "unknowns",
    "units",
    "body",
    "let",
    "given",
    "constraint",
    "claim",
    "use",
];

/// Parses the statement in `region`, a subslice of `cx.base` that starts with its keyword.
pub(crate) fn statement<'a>(cx: &Cx<'a>, region: &'a str) -> Result<Stmt, SyntaxError> {
    stmt(cx, region).map(|(_, s)| s).map_err(|e| cx.error(e))
}

/// `stmt = keyword …`: dispatches on the keyword; the span ends at the last token.
fn stmt<'a>(cx: &Cx<'a>, region: &'a str) -> PResult<'a, Stmt> {
    let (i, kw) = match ident(region) {
        Ok((i, id)) if KEYWORDS.contains(&id.raw) => (i, id.raw),
        _ => return expected(cx, region, "a statement keyword"),
    };
    let (rest, kind) = match kw {
        "symbols" => symbols(cx, i)?,
        "time" => names(cx, i, "time", false).map(|(r, names)| (r, StmtKind::Time { names }))?,
        "unknowns" => {
            names(cx, i, "unknowns", true).map(|(r, names)| (r, StmtKind::Unknowns { names }))?
        }
        "units" => units(cx, i)?,
        "small" => small(cx, i)?,
        "result" => {
            let (r, labels) = label_list(cx, i)?;
            end(cx, r, "`,` and the next label, or the end of the statement")?;
            (r, StmtKind::Result { labels })
        }
        "body" => body(cx, i)?,
        "let" => let_(cx, i)?,
        "use" => use_(cx, i)?,
        _ => fact(cx, i, kw)?,
    };
    Ok((
        rest,
        Stmt {
            kind,
            span: cx.span(region, rest),
        },
    ))
}

/// `names = name ([","] name)*` after `symbols`, `time` or `unknowns` (the `kw`); in
/// `small`, the word `to` ends the list.
fn names<'a>(cx: &Cx<'a>, i: &'a str, kw: &str, primes: bool) -> PResult<'a, Vec<Name>> {
    let (mut i, first) = name(cx, i, &format!("a symbol name after `{kw}`"), primes)?;
    let mut names = vec![first];
    loop {
        let next = punct(cx, i, ",").map_or(i, |(_, rest)| rest);
        let stop = kw == "small" && keyword(cx, next, "to").is_some();
        if ident(ws(cx, next)).is_err() || stop {
            return Ok((i, names));
        }
        let (rest, n) = name(cx, next, "a symbol name", primes)?;
        names.push(n);
        i = rest;
    }
}

/// `symbols = "symbols" names [sign] | "symbols" expr less names less expr`.
fn symbols<'a>(cx: &Cx<'a>, i: &'a str) -> PResult<'a, StmtKind> {
    if let Some(r) = range(cx, i) {
        return r;
    }
    let (i, names) = names(cx, i, "symbols", false)?;
    let (i, sign) = sign(cx, i)?;
    end(
        cx,
        i,
        "a symbol name, a sign (`> 0`, `>= 0`, `!= 0`) or the end of the statement",
    )?;
    Ok((i, StmtKind::Symbols { names, sign }))
}

/// `<` (strict) or `<=`, `≤`.
fn less<'a>(cx: &Cx<'a>, i: &'a str) -> Option<(bool, &'a str)> {
    for (op, strict) in [("<=", false), ("≤", false), ("<", true)] {
        if let Some((_, rest)) = punct(cx, i, op) {
            return Some((strict, rest));
        }
    }
    None
}

/// `range = expr less names less expr` after `symbols`; `None` when the statement does
/// not start like one (then it is a list of names).
fn range<'a>(cx: &Cx<'a>, i: &'a str) -> Option<PResult<'a, StmtKind>> {
    let (r, lo) = expr(cx, i, "symbols").ok()?;
    let (lo_strict, r) = less(cx, r)?;
    // `symbols m < 0` is not a range (and negative signs are not declared this way).
    ident(ws(cx, r)).ok()?;
    Some((|| {
        let (r, names) = names(cx, r, "a bound and `<`", false)?;
        let Some((hi_strict, r)) = less(cx, r) else {
            return expected(
                cx,
                r,
                "`<` or `<=` and the upper bound, as in `0 < beta < pi/2`",
            );
        };
        let (r, hi) = expr(cx, r, "<")?;
        end(cx, r, "the end of the statement after the upper bound")?;
        Ok((
            r,
            StmtKind::Range {
                names,
                lo,
                lo_strict,
                hi,
                hi_strict,
            },
        ))
    })())
}

/// `small = "small" names ["to" "order" n]`.
fn small<'a>(cx: &Cx<'a>, i: &'a str) -> PResult<'a, StmtKind> {
    let (i, names) = names(cx, i, "small", false)?;
    let Some((_, r)) = keyword(cx, i, "to") else {
        end(cx, i, "a name, `to order n` or the end of the statement")?;
        return Ok((i, StmtKind::Small { names, order: 1 }));
    };
    let Some((_, r)) = keyword(cx, r, "order") else {
        return expected(cx, r, "`order` after `to`, as in `small theta to order 2`");
    };
    let at = ws(cx, r);
    let order = match number(at) {
        Ok((rest, n)) if n.is_integer() => {
            match num_traits::ToPrimitive::to_u32(&n.to_integer()).filter(|k| (1..=4).contains(k)) {
                Some(k) => (rest, k),
                None => return expected(cx, at, "an order from 1 to 4 after `to order`"),
            }
        }
        _ => return expected(cx, at, "an order from 1 to 4 after `to order`"),
    };
    end(cx, order.0, "the end of the statement after the order")?;
    Ok((
        order.0,
        StmtKind::Small {
            names,
            order: order.1,
        },
    ))
}

/// `sign = (">" | ">=" | "≥" | "!=" | "≠") "0"`, or nothing.
fn sign<'a>(cx: &Cx<'a>, i: &'a str) -> PResult<'a, SignDecl> {
    let signs = [
        (">=", SignDecl::Nonnegative),
        ("≥", SignDecl::Nonnegative),
        ("!=", SignDecl::Nonzero),
        ("≠", SignDecl::Nonzero),
        (">", SignDecl::Positive),
    ];
    let Some((op, sign, rest)) = signs
        .iter()
        .find_map(|&(op, s)| punct(cx, i, op).map(|(_, r)| (op, s, r)))
    else {
        return Ok((i, SignDecl::Any));
    };
    let at = ws(cx, rest);
    match number(at) {
        Ok((rest, n)) if n.is_zero() => Ok((rest, sign)),
        _ => expected(
            cx,
            rest,
            &format!("`0` after `{op}`: signs are `> 0`, `>= 0` or `!= 0`"),
        ),
    }
}

/// `units = "units" name ":" unit ("," name ":" unit)*`, a unit being raw text up to the
/// next `, name:`, a comment or the end of the line.
fn units<'a>(cx: &Cx<'a>, i: &'a str) -> PResult<'a, StmtKind> {
    let mut decls = Vec::new();
    let mut what = "a symbol name after `units`";
    let mut i = i;
    loop {
        let (rest, n) = name(cx, i, what, false)?;
        let Some((_, rest)) = punct(cx, rest, ":") else {
            return expected(
                cx,
                rest,
                &format!("`:` after `{}`, as in `units m: kg`", n.name),
            );
        };
        let at = hspace(rest);
        let unit = at.get(..unit_len(cx, at)).unwrap_or("").trim_end();
        if unit.is_empty() {
            return expected(
                cx,
                at,
                &format!("a unit after `{}:`, such as `kg` or `m/s^2`", n.name),
            );
        }
        let after = at.get(unit.len()..).unwrap_or("");
        decls.push(UnitDecl {
            name: n,
            unit: unit.to_string(),
            unit_span: cx.span(at, after),
        });
        match punct(cx, after, ",") {
            Some((_, next)) => (i, what) = (next, "a symbol name after `,`"),
            None => {
                end(
                    cx,
                    after,
                    "`,` and the next `name: unit`, or the end of the statement",
                )?;
                return Ok((after, StmtKind::Units { decls }));
            }
        }
    }
}

/// The length of the unit text at the start of `at`.
fn unit_len(cx: &Cx<'_>, at: &str) -> usize {
    for (k, c) in at.char_indices() {
        let next_decl = || {
            let rest = at.get(k.saturating_add(1)..).unwrap_or("");
            matches!(ident(ws(cx, rest)), Ok((r, _)) if punct(cx, r, ":").is_some())
        };
        if c == '\n' || (cx.comments && c == '%') || (c == ',' && next_decl()) {
            return k;
        }
    }
    at.len()
}

/// `body = "body" name ":" (concrete | abstract)`.
fn body<'a>(cx: &Cx<'a>, i: &'a str) -> PResult<'a, StmtKind> {
    let (rest, name) = name(cx, i, "a body name after `body`", false)?;
    let Some((_, rest)) = punct(cx, rest, ":") else {
        return expected(cx, rest, "`:` after the body name");
    };
    let (rest, def) = if let Some((_, r)) = keyword(cx, rest, "dm") {
        concrete(cx, r)?
    } else if let Some((_, r)) = keyword(cx, rest, "mass") {
        abstract_(cx, r)?
    } else {
        return expected(
            cx,
            rest,
            &format!("`dm = …` or `mass …` after `body {}:`", name.name),
        );
    };
    Ok((rest, StmtKind::Body { name, def }))
}

/// `concrete = "dm" "=" expr ("," name "from" expr "to" expr)+`, after `dm`.
fn concrete<'a>(cx: &Cx<'a>, i: &'a str) -> PResult<'a, BodyDef> {
    let Some((_, i)) = punct(cx, i, "=") else {
        return expected(cx, i, "`=` after `dm`");
    };
    let (mut i, dm) = expr(cx, i, "=")?;
    let mut ranges = Vec::new();
    while let Some((_, rest)) = punct(cx, i, ",") {
        let (rest, var) = name(
            cx,
            rest,
            "a coordinate after `,`, as in `y from -L/2 to L/2`",
            false,
        )?;
        let Some((_, rest)) = keyword(cx, rest, "from") else {
            return expected(
                cx,
                rest,
                &format!("`from` after the coordinate `{}`", var.name),
            );
        };
        let (rest, from) = expr(cx, rest, "from")?;
        let Some((_, rest)) = keyword(cx, rest, "to") else {
            return expected(
                cx,
                rest,
                &format!("an operator or `to` in the range of `{}`", var.name),
            );
        };
        let (rest, to) = expr(cx, rest, "to")?;
        ranges.push(Range { var, from, to });
        i = rest;
    }
    if ranges.is_empty() {
        let what = "an operator, or `,` and the range of a coordinate as in `dm = m/L dy, y from -L/2 to L/2`";
        return expected(cx, i, what);
    }
    end(
        cx,
        i,
        "an operator, `,` and another coordinate range, or the end of the statement",
    )?;
    Ok((i, BodyDef::Concrete { dm, ranges }))
}

/// `abstract = "mass" expr "," "coordinates" name+ ["," ("centred" | "centered")]`, after `mass`.
fn abstract_<'a>(cx: &Cx<'a>, i: &'a str) -> PResult<'a, BodyDef> {
    let (i, mass) = expr(cx, i, "mass")?;
    let Some((_, i)) = punct(cx, i, ",") else {
        return expected(cx, i, "an operator, or `, coordinates …` after the mass");
    };
    let Some((_, i)) = keyword(cx, i, "coordinates") else {
        return expected(
            cx,
            i,
            "`coordinates` and the body's coordinates, as in `coordinates x y`",
        );
    };
    let (mut i, first) = name(cx, i, "a coordinate name after `coordinates`", false)?;
    let mut coords = vec![first];
    while ident(ws(cx, i)).is_ok() {
        let (rest, c) = name(cx, i, "a coordinate name", false)?;
        coords.push(c);
        i = rest;
    }
    let mut centred = false;
    if let Some((_, rest)) = punct(cx, i, ",") {
        let Some((_, rest)) =
            keyword(cx, rest, "centred").or_else(|| keyword(cx, rest, "centered"))
        else {
            return expected(cx, rest, "`centred` after `,`");
        };
        (i, centred) = (rest, true);
    }
    end(
        cx,
        i,
        "a coordinate name, `, centred` or the end of the statement",
    )?;
    Ok((
        i,
        BodyDef::Abstract {
            mass,
            coords,
            centred,
        },
    ))
}

/// `let = "let" name "=" expr`.
fn let_<'a>(cx: &Cx<'a>, i: &'a str) -> PResult<'a, StmtKind> {
    if let Some(r) = latex_chain(cx, i) {
        let (rest, chain) = r?;
        let at = ws(cx, i);
        let (crate::syntax::ast::ExprKind::Sym(n), [link]) =
            (&chain.first.kind, chain.links.as_slice())
        else {
            return failure(
                at,
                2,
                "`let $$ name = … $$` defines one name by one equation",
            );
        };
        if link.op != crate::syntax::ast::RelOp::Eq {
            return failure(
                at,
                2,
                "`let $$ name = … $$` defines one name by one equation",
            );
        }
        end(cx, rest, "the end of the statement after `$$`")?;
        let name = Name {
            name: n.clone(),
            span: chain.first.span,
        };
        return Ok((
            rest,
            StmtKind::Let {
                name,
                value: link.rhs.clone(),
            },
        ));
    }
    let (i, name) = name(cx, i, "a name after `let`", false)?;
    let Some((_, i)) = punct(cx, i, "=").filter(|(at, _)| !at.starts_with("==")) else {
        return expected(cx, i, &format!("`=` after `let {}`", name.name));
    };
    let (i, value) = expr(cx, i, "=")?;
    end(cx, i, "an operator or the end of the statement")?;
    Ok((i, StmtKind::Let { name, value }))
}

/// `$$ latex $$`: a relation in LaTeX (FORMAT.md §1, "LaTeX math"); `None` when the
/// statement does not continue with `$$`.
fn latex_chain<'a>(cx: &Cx<'a>, i: &'a str) -> Option<PResult<'a, Chain>> {
    let at = ws(cx, i);
    let inside = at.strip_prefix("$$")?;
    let Some(k) = inside.find("$$") else {
        return Some(failure(at, 2, "`$$` without the closing `$$` on its line"));
    };
    let math = inside.get(..k).unwrap_or("");
    let rest = inside.get(k + 2..).unwrap_or("");
    let opts = super::error::ParseOptions {
        max_depth: cx.max_depth,
    };
    Some(
        match super::latex::parse_latex_chain(math, cx.pos(inside), &opts) {
            Ok(chain) => Ok((rest, chain)),
            Err(e) => {
                let off = e.span.start.saturating_sub(cx.pos(inside));
                let at = inside.get(off..).unwrap_or(inside);
                failure_of_kind(
                    at,
                    e.span.end.saturating_sub(e.span.start),
                    e.kind,
                    e.message,
                )
            }
        },
    )
}

/// `fact = ("given" | "constraint" | "claim") [label] chain`, and for a claim
/// `["where" assignments]`.
fn fact<'a>(cx: &Cx<'a>, i: &'a str, kw: &'a str) -> PResult<'a, StmtKind> {
    let (i, label) = match label(cx, i) {
        Ok((rest, l)) => (rest, Some(l)),
        Err(nom::Err::Error(_)) => (i, None),
        Err(e) => return Err(e),
    };
    let after = label
        .as_ref()
        .and_then(|l| cx.base.get(l.span.start..l.span.end))
        .unwrap_or(kw);
    let claim = kw == "claim";
    let rules = ChainRules {
        after,
        by: true,
        where_: claim,
    };
    let (i, (first, links)) = match latex_chain(cx, i) {
        Some(r) => {
            let (i, mut chain) = r?;
            // `$$ … $$ by [Fx]`: the justification of the last link.
            let i = match keyword(cx, i, "by") {
                Some((by_at, after_by)) => {
                    let (rest, (by, span, compare)) = by_clause(cx, by_at, after_by, rules)?;
                    if let Some(last) = chain.links.last_mut() {
                        last.span = last.span.to(span);
                        last.by = Some((by, span));
                        last.compare = compare;
                    }
                    rest
                }
                None => i,
            };
            (i, (chain.first, chain.links))
        }
        None => chain_or_expr(cx, i, rules)?,
    };
    if links.is_empty() {
        return expected(
            cx,
            i,
            "an operator or a relation (`=`, `!=`, `<`, `<=`, `>`, `>=`, `~=`)",
        );
    }
    let chain = Chain { first, links };
    if !claim {
        end(
            cx,
            i,
            "an operator, a relation, `by` or the end of the statement",
        )?;
        return Ok((i, given_or_constraint(kw, label, chain)));
    }
    let (i, where_) = match keyword(cx, i, "where") {
        Some((_, rest)) => assignments(cx, rest, "where")?,
        None => (i, Vec::new()),
    };
    let mut chain = chain;
    // `… where I_G = m R^2/2 by [acc]`: both clauses are "at the end of a claim", so
    // the justification may also follow the substitutions; it belongs to the last link.
    let i = match keyword(cx, i, "by").filter(|_| !where_.is_empty()) {
        Some((by_at, after_by)) => {
            let Some(last) = chain.links.last_mut() else {
                return expected(cx, i, "the end of the statement");
            };
            if last.by.is_some() {
                let message = "this link already has a justification (`by`) before `where`";
                return failure(by_at, 2, message);
            }
            let rules = ChainRules {
                after: "where",
                by: true,
                where_: false,
            };
            let (rest, (by, by_span, compare)) = by_clause(cx, by_at, after_by, rules)?;
            last.by = Some((by, by_span));
            last.compare = compare;
            rest
        }
        None => i,
    };
    let wanted = if where_.is_empty() {
        "an operator, a relation, `by`, `where` or the end of the statement"
    } else {
        "an operator, `,` and another substitution, or the end of the statement"
    };
    end(cx, i, wanted)?;
    Ok((
        i,
        StmtKind::Claim {
            label,
            chain,
            where_,
        },
    ))
}

/// The node of a `given` or a `constraint`.
fn given_or_constraint(kw: &str, label: Option<Label>, chain: Chain) -> StmtKind {
    if kw == "constraint" {
        StmtKind::Constraint { label, chain }
    } else {
        StmtKind::Given { label, chain }
    }
}

/// `use = "use" labels "from" string ["with" assignments]`.
fn use_<'a>(cx: &Cx<'a>, i: &'a str) -> PResult<'a, StmtKind> {
    let (i, labels) = match label_list(cx, i) {
        Err(nom::Err::Error(_)) => return expected(cx, i, "a label such as `[IO]` after `use`"),
        other => other?,
    };
    let Some((_, i)) = keyword(cx, i, "from") else {
        return expected(cx, i, "`,` and another label, or `from \"file.deriv\"`");
    };
    let (i, (path, path_span)) = string(cx, i)?;
    let (i, with) = match keyword(cx, i, "with") {
        Some((_, rest)) => assignments(cx, rest, "with")?,
        None => (i, Vec::new()),
    };
    let wanted = if with.is_empty() {
        "`with` or the end of the statement"
    } else {
        "an operator, `,` and another substitution, or the end of the statement"
    };
    end(cx, i, wanted)?;
    Ok((
        i,
        StmtKind::Use {
            labels,
            path,
            path_span,
            with,
        },
    ))
}

/// `string = '"' [^"\n]+ '"'`: the path of a `use`, with the span of the quoted text.
fn string<'a>(cx: &Cx<'a>, i: &'a str) -> PResult<'a, (String, super::ast::Span)> {
    let at = ws(cx, i);
    let Some(inner) = at.strip_prefix('"') else {
        return expected(
            cx,
            i,
            "a quoted path after `from`, as in `from \"rod.deriv\"`",
        );
    };
    let len = inner.find(['"', '\n']).unwrap_or(inner.len());
    let path = inner.get(..len).unwrap_or("");
    let Some(rest) = inner.get(len..).and_then(|r| r.strip_prefix('"')) else {
        return failure(at, 1, "unclosed `\"`");
    };
    if path.trim().is_empty() {
        return failure(
            at,
            token_len(at).saturating_add(1),
            "expected a file path between the quotes",
        );
    }
    Ok((rest, (path.to_string(), cx.span(at, rest))))
}
