//! A document read piece by piece into the scopes `lint` checks: each heading starts a
//! scope; `rigor:` comments hold from where they stand to the end; each display is
//! cleaned (`display.rs`) and its relations read as chains. Two readings of how notes
//! are written live here: inline relations in prose (`$a_t = \ddot\theta r$`) are
//! checked in a scope of their own beside the displays', so a relation read from a
//! sentence is never a premise of a display's step (one of a single link is a statement
//! of the prose — a condition, a value — and is reported only when it holds, fails or
//! defines a symbol; maths in a sentence that rigor cannot read is prose to it); and a
//! lone symbol given a second, different number under one heading (`a = 5`, later
//! `a = 1`) starts a fresh scope, as the author's reuse of the letter means. An author's `\theta \ll 1` declares `theta`
//! small, as `<!-- rigor: small theta -->` does.

use super::{display, extract, mass, ChainReport, Checked, Item, Piece, Scope, Verdict};
use crate::check::Options;
use crate::diag::{Code, Diagnostic};
use crate::syntax::ast::{Chain, Expr, ExprKind, RelOp, Span};
use crate::syntax::latex::{parse_latex_chain, parse_latex_expr, parse_latex_links};
use crate::syntax::print::source;
use crate::syntax::ParseOptions;
use foldhash::{HashMap, HashMapExt, HashSet, HashSetExt};

/// The state of a document read so far.
pub(super) struct Reader<'a> {
    /// The document, its displays cleaned (offsets kept): what derivations are made of.
    pub(super) cleaned: String,
    /// The scopes closed so far.
    pub(super) scopes: Vec<Scope>,
    /// The displays' scope under the current heading, and the inline relations' one.
    scope: Scope,
    prose: Scope,
    /// The document's `rigor:` statements so far, and the names they declare.
    directives: String,
    names: HashSet<String>,
    /// The last expression of the previous display chain: a display starting with `=`
    /// goes on from it.
    last: Option<Expr>,
    /// The lone symbols the current display scope gave a value, with that value.
    values: HashMap<String, String>,
    /// The definitions of the sections closed so far (`carry.rs`).
    carried: Vec<Chain>,
    doc: &'a str,
    popts: ParseOptions,
    opts: &'a Options,
    cache: &'a Checked,
}

impl<'a> Reader<'a> {
    pub(super) fn new(doc: &'a str, opts: &'a Options, cache: &'a Checked) -> Reader<'a> {
        Reader {
            cleaned: doc.to_string(),
            scopes: Vec::new(),
            scope: Scope::default(),
            prose: Scope::default(),
            directives: String::new(),
            names: HashSet::new(),
            last: None,
            values: HashMap::new(),
            carried: Vec::new(),
            doc,
            popts: ParseOptions {
                max_depth: opts.parse.max_depth,
            },
            opts,
            cache,
        }
    }

    /// Reads one piece; chains reported without a check (unreadable ones) go to `out`.
    pub(super) fn piece(&mut self, piece: Piece, out: &mut Vec<ChainReport>) {
        match piece {
            Piece::Heading => self.heading(),
            // `<!-- rigor: ## Sliding -->`: a heading the notes do not show.
            Piece::Directive(text) if text.starts_with('#') => self.heading(),
            Piece::Directive(text) => self.directive(text),
            Piece::Math {
                text,
                start,
                inline,
            } => self.math(&text, start, inline, out),
        }
    }

    /// The scopes, all closed.
    pub(super) fn finish(mut self) -> (Vec<Scope>, String) {
        self.heading();
        (self.scopes, self.cleaned)
    }

    fn heading(&mut self) {
        super::carry::left_by(&self.scope, &mut self.carried);
        self.fresh_scope();
        let prose = Scope::under(&self.directives, &self.names);
        self.scopes.push(std::mem::replace(&mut self.prose, prose));
        self.last = None;
    }

    /// A new scope for the displays (the inline relations' scope goes on).
    fn fresh_scope(&mut self) {
        let mut scope = Scope::under(&self.directives, &self.names);
        scope.carried = self.carried.clone();
        self.scopes.push(std::mem::replace(&mut self.scope, scope));
        self.values.clear();
    }

    fn directive(&mut self, text: String) {
        let text = super::values::declaring(&text, &self.names).unwrap_or(text);
        // `small theta` marks a symbol declared elsewhere: declared here when it is not.
        let text = match text.strip_prefix("small ") {
            Some(rest) => {
                let new: Vec<&str> = rest
                    .split_whitespace()
                    .take_while(|w| *w != "to")
                    .filter(|w| !self.names.contains(*w))
                    .collect();
                if new.is_empty() {
                    text
                } else {
                    format!("symbols {}\n{text}", new.join(" "))
                }
            }
            None => text,
        };
        if !self.cache.parses(&text) {
            return;
        }
        let words: Vec<String> = text
            .split_whitespace()
            .map(|w| {
                w.trim_matches(|c: char| !c.is_alphanumeric() && c != '_')
                    .to_string()
            })
            .collect();
        self.names.extend(words.iter().cloned());
        self.directives.push_str(&text);
        self.directives.push('\n');
        self.scope
            .items
            .push(Item::Directive(text.clone(), words.clone()));
        self.prose.items.push(Item::Directive(text, words));
    }

    fn math(&mut self, text: &str, start: usize, inline: bool, out: &mut Vec<ChainReport>) {
        // The display as the reader sees it, markup blanked, offsets kept; derivations
        // are made from the document with its displays so cleaned.
        let text = display::clean(text);
        if self.doc.get(start..start + text.len()).is_some() {
            self.cleaned.replace_range(start..start + text.len(), &text);
        }
        for name in small_quantities(&text, &self.popts) {
            if !self
                .directives
                .lines()
                .any(|l| l == format!("small {name}"))
            {
                self.directive(format!("small {name}"));
            }
        }
        for (rel, at, premise) in extract::relations(&text) {
            let at = start + at;
            let prev = if inline { None } else { self.last.as_ref() };
            let (unread, parsed) = read(rel, at, prev, &self.popts);
            // Maths in a sentence that rigor cannot read is prose to it, not a chain.
            if !inline {
                out.extend(unread);
            }
            let Some(chain) = parsed else {
                if !inline {
                    self.last = None;
                }
                continue;
            };
            if !inline {
                self.last = chain.links.last().map(|l| l.rhs.clone());
                self.redefinition(&chain);
            }
            let body = self
                .directives
                .lines()
                .any(|l| l.trim_start().starts_with("body"));
            let (prose, rest) = if body {
                (Vec::new(), Some(chain))
            } else {
                mass::over_prose_mass(chain, (self.opts, self.cache))
            };
            if inline {
                out.extend(
                    prose
                        .into_iter()
                        .filter(|c| c.verdict != Verdict::NeedsContext),
                );
                if let Some(c) = &rest {
                    // A value the prose gives a lone symbol, wherever in the section:
                    // the comment that would make a chain checkable, where it does.
                    if let (ExprKind::Sym(n), [l]) = (&c.first.kind, c.links.as_slice()) {
                        if l.op == RelOp::Eq {
                            let plain = source(&l.rhs);
                            let value = if plain.contains('(') {
                                format!("$$ {n} = {} $$", self.flat(l.rhs.span))
                            } else {
                                format!("{n} = {plain}")
                            };
                            self.scope.values.push((n.clone(), value));
                        }
                    }
                    // `$\mu = 0$`, `$h = 2$`: a case or a value the sentence sets.
                    let value = matches!(c.first.kind, ExprKind::Sym(_))
                        && c.links.iter().all(|l| !has_symbols(&l.rhs));
                    if c.links.len() == 1 && value {
                        continue;
                    }
                    // `$x = -\theta R$`, `$I_G = \frac12 m R^2$`: what a sentence says a
                    // symbol stands for, the displays after it may use (stated, never a
                    // step: with a lone symbol on the left it cannot fail).
                    let defining = matches!(c.first.kind, ExprKind::Sym(_))
                        && c.links.len() == 1
                        && c.links[0].op == RelOp::Eq;
                    if defining {
                        self.scope.quiet.insert(c.first.span.start);
                        self.scope.items.extend(rest.map(Item::Chain));
                        continue;
                    }
                    if c.links.len() == 1 {
                        self.prose.quiet.insert(c.first.span.start);
                    }
                }
                self.prose.items.extend(rest.map(Item::Chain));
            } else {
                out.extend(prose);
                let item = if premise { Item::Imposed } else { Item::Chain };
                self.scope.items.extend(rest.map(item));
            }
        }
    }

    /// The document's text in `s`, on one line.
    fn flat(&self, s: Span) -> String {
        super::flat(&self.cleaned, s).trim().to_string()
    }

    /// A lone symbol given a value different from the one it was given before under
    /// this heading is the letter reused: the chains after it are a scope of their own.
    fn redefinition(&mut self, chain: &Chain) {
        let ExprKind::Sym(n) = &chain.first.kind else {
            return;
        };
        let Some(link) = chain.links.first().filter(|l| l.op == RelOp::Eq) else {
            return;
        };
        // Only a number for a number: two symbolic values are usually two true relations
        // (`\ddot x = -\ddot\theta R`, then the result for `\ddot x`).
        if self.names.contains(n) || has_symbols(&link.rhs) {
            return;
        }
        let value = source(&link.rhs);
        if self.values.get(n).is_some_and(|v| *v != value) {
            self.fresh_scope();
        }
        self.values.insert(n.clone(), value);
    }
}

/// Reads one relation of a display (`prev`: the last expression before it, which a
/// relation that starts with `=` goes on from). What cannot be read is reported as
/// needing context; after a mass element with limits (`\int_0^R r^2\,dm`), the part
/// from the next `=` on is read on its own.
fn read(
    rel: &str,
    at: usize,
    prev: Option<&Expr>,
    popts: &ParseOptions,
) -> (Vec<ChainReport>, Option<Chain>) {
    let continues = display::starts_with_relation(rel);
    let parsed = match (prev, continues) {
        (Some(prev), true) => parse_latex_links(rel, at, popts).map(|links| Chain {
            first: prev.clone(),
            links,
        }),
        _ => parse_latex_chain(rel, at, popts),
    };
    let e = match parsed {
        Ok(chain) => return (Vec::new(), Some(chain)),
        Err(e) => e,
    };
    let unread = |span: Span, message: String| ChainReport {
        reason: Some(super::Reason::Unread),
        ..ChainReport::new(
            span,
            Verdict::NeedsContext,
            vec![Diagnostic::error(Code::Syntax, message, span, "")],
        )
    };
    let after = e.span.end.saturating_sub(at);
    match extract::equals_after(rel, after) {
        Some(eq) if e.kind == crate::syntax::error::SyntaxErrorKind::MassElementWithLimits => {
            let mut out = vec![unread(Span::new(at, at + eq), e.message)];
            let (more, chain) = read(&rel[eq + 1..], at + eq + 1, None, popts);
            out.extend(more);
            (out, chain)
        }
        _ => (vec![unread(e.span, e.message)], None),
    }
}

fn has_symbols(e: &Expr) -> bool {
    e.any(&|n| matches!(n.kind, ExprKind::Sym(_)))
}

/// The symbols an author declares small in the maths itself: `\theta \ll 1`.
fn small_quantities(text: &str, popts: &ParseOptions) -> Vec<String> {
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(k) = text[from..].find("\\ll").map(|k| k + from) {
        from = k + 3;
        let after = text[from..].trim_start();
        let one = after
            .strip_prefix('1')
            .is_some_and(|r| !r.starts_with(|c: char| c.is_ascii_digit() || c == '.'));
        if !one || text[from..].starts_with(|c: char| c.is_ascii_alphabetic()) {
            continue;
        }
        // The quantity: what stands before `\ll`, back to a separator.
        let begin = text[..k]
            .rfind([',', ';', display::SEP as char, '$', '('])
            .map_or(0, |b| b + 1);
        let lhs = &text[begin..k];
        let Ok(e) = parse_latex_expr(lhs, 0, popts) else {
            continue;
        };
        let e = match &e.kind {
            ExprKind::Call(crate::syntax::ast::Func::Abs, args) if args.len() == 1 => &args[0],
            _ => &e,
        };
        if let ExprKind::Sym(n) = &e.kind {
            if !n.contains('\'') && !out.contains(n) {
                out.push(n.clone());
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_author_declares_a_quantity_small_with_ll() {
        let p = ParseOptions::default();
        assert_eq!(small_quantities(r"\theta \ll 1", &p), ["theta"]);
        assert_eq!(small_quantities(r"x = 2, \quad |\phi| \ll 1", &p), ["phi"]);
        assert!(small_quantities(r"\theta \ll 10", &p).is_empty());
        assert!(small_quantities(r"a \ll L", &p).is_empty());
    }
}
