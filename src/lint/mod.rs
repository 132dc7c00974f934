//! `rigor lint`: the chains of equations inside lecture notes (Markdown with `$$…$$`,
//! LaTeX with `\[…\]`, `$$…$$`, `equation`, `align` and their starred forms). Each chain
//! is checked through the one checker entry, as a claim of a derivation made from the
//! document: its symbols declared as reals (or as the document's `rigor:` comments
//! say), a chain whose left side is a lone new symbol defining it for later chains.

use crate::diag::{Code, Mistake};
mod cache;
mod carry;
mod display;
mod extract;
mod later;
mod mass;
mod partial;
mod premises;
mod queue;
mod reader;
mod reason;
mod sound;
mod values;

use crate::check::{FileReport, Options, Status};
use crate::diag::{Diagnostic, LineIndex};
use crate::syntax::ast::{Chain, Expr, ExprKind, Func, Reading, Span};
use cache::Checked;
pub use extract::{pieces, DocKind, Piece};
use foldhash::{HashSet, HashSetExt};
use later::{later_is_a_mistake, later_link, later_links, later_needs, Later};
use partial::{conditions, once, report_all};
pub use queue::{lint_all, Document};
pub use reason::Reason;

/// The verdict on one chain.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Every link holds.
    Verified,
    /// A link is false.
    Failed,
    /// It depends on something the document defines in prose, or rigor cannot read it.
    NeedsContext,
    /// It states what a new symbol stands for (`I_G = \frac{mL^2}{12}`, the symbol used
    /// nowhere before): a definition, taken as the notes give it and not checked.
    Defined,
}

/// One chain of a document and what became of it.
#[derive(Clone, Debug)]
pub struct ChainReport {
    /// Where the chain is in the document.
    pub span: Span,
    /// The verdict.
    pub verdict: Verdict,
    /// For a failure or a need of context: why (diagnostics with document spans).
    pub diagnostics: Vec<Diagnostic>,
    /// For a verified chain: what its links assume that the declared signs do not show
    /// (`b F m != 0`), each once.
    pub assuming: Vec<String>,
    /// The new symbol a chain's first link defines (`I_G`), as rigor names it.
    pub defines: Option<String>,
    /// For a chain that needs context: why.
    pub reason: Option<Reason>,
    /// The `rigor:` comment that would make it checkable, where rigor knows it.
    pub comment: Option<String>,
    /// For a verified chain: the lines of the document whose relations its links were
    /// verified from (the premises it rests on), in order.
    pub from: Vec<usize>,
    /// For a verified chain: the definitions of earlier sections it used, each as
    /// written (`I_G = \frac{m L^2}{12}`) with its line.
    pub using: Vec<(String, usize)>,
}

impl ChainReport {
    /// A chain with its verdict and diagnostics, and nothing assumed, defined, cited or
    /// suggested (the other fields are set where they are known).
    pub fn new(span: Span, verdict: Verdict, diagnostics: Vec<Diagnostic>) -> ChainReport {
        ChainReport {
            span,
            verdict,
            diagnostics,
            assuming: Vec::new(),
            defines: None,
            reason: None,
            comment: None,
            from: Vec::new(),
            using: Vec::new(),
        }
    }

    /// The chain turned into one that needs context for `reason`, with `message` as its
    /// one diagnostic, where its first diagnostic was (else at the chain).
    pub(crate) fn needs_context(&mut self, reason: Reason, message: String) {
        let at = self
            .diagnostics
            .first()
            .and_then(|d| d.primary.as_ref())
            .map_or(self.span, |(s, _)| *s);
        self.verdict = Verdict::NeedsContext;
        self.reason = Some(reason);
        self.diagnostics = vec![Diagnostic::error(Code::NotVerified, message, at, "")];
    }
}

/// Everything found in one document.
#[derive(Clone, Debug, Default)]
pub struct LintReport {
    /// The document's name.
    pub path: String,
    /// Its text.
    pub source: String,
    /// Each chain, in document order.
    pub chains: Vec<ChainReport>,
}

impl LintReport {
    /// How many chains have this verdict.
    pub fn count(&self, v: &Verdict) -> usize {
        self.chains.iter().filter(|c| &c.verdict == v).count()
    }
}

/// Where a claim of the derivation came from: pieces of the document's text copied
/// into it, as (offset there, offset in the document, length).
type Part = Vec<(usize, usize, usize)>;

/// A chain's place in the derivation made from the document.
struct Placed {
    /// The claim of its first link (none for a definition of a new symbol).
    first: Option<Part>,
    /// The claim of the links after the first, if any.
    rest: Option<Part>,
    /// The statement that takes the first link as stated (a `given` or a `let`).
    stated: Option<Part>,
    /// The links after the first.
    later: Vec<Later>,
    /// Where the whole chain is in the document.
    span: Span,
    /// Where the first link ends, and where its right side starts.
    first_link: Span,
    /// Whether the first link states a relation for a lone symbol (a definition or a
    /// law the notes take from elsewhere).
    states: bool,
    /// Whether every symbol of the first link is one the document declared (in a
    /// `rigor:` comment) or defined: then a first link that does not hold is a mistake,
    /// not a relation taken from elsewhere.
    firm: bool,
    /// The new symbol the first link defines, if it does.
    defines: Option<String>,
    /// Whether it is a premise the notes impose (written before an implication arrow).
    imposed: bool,
    /// Its approximations that may not fail (`premises::loose_approximations`), each
    /// with the comment that would make it checkable.
    loose: Vec<premises::Loose>,
    /// Whether a part of it could not be written into the derivation (then it is not
    /// checked).
    unwritten: bool,
    /// The names of its symbols.
    symbols: Vec<String>,
    /// Whether its first link, stated, is not taken as a premise: with what was stated
    /// before it, it could hold only where one of its sides is zero (`sound::unfit`).
    contradicts: bool,
    /// The statements that take its later links as stated.
    givens: Vec<Part>,
    /// Its first expression as the notes write it (`v`).
    head: String,
}

/// What the notes derive under one heading.
#[derive(Default)]
struct Scope {
    /// The document's `rigor:` statements before the scope.
    directives: String,
    /// The names they declare.
    names: HashSet<String>,
    /// The scope's own `rigor:` statements (with the names they declare) and chains.
    items: Vec<Item>,
    /// Where the chains start that are statements of the prose (an inline relation of
    /// one link): reported only when they hold, fail or define a symbol.
    quiet: HashSet<usize>,
    /// The definitions of earlier sections (`I_G = \frac{m L^2}{12}`), each a chain of
    /// one link: in scope here unless the scope states its symbol again.
    carried: Vec<Chain>,
    /// The values the section's prose gives lone symbols (`where $r = A$`): the symbol,
    /// and the relation as a `let` comment writes it (`r = A`, or `$$ r = \frac{L}{2} $$`).
    values: Vec<(String, String)>,
}

enum Item {
    Directive(String, Vec<String>),
    Chain(Chain),
    /// A chain written before an implication arrow: a premise the notes impose.
    Imposed(Chain),
}

/// The derivation made from a scope, as it is written.
struct Build<'a> {
    /// The derivation.
    deriv: String,
    /// Its chains.
    placed: Vec<Placed>,
    /// Names declared in the derivation.
    declared: HashSet<String>,
    /// Names the document itself declared or defined (not those the linter assumed).
    known: HashSet<String>,
    /// Names the scope's chains have used so far.
    seen: HashSet<String>,
    /// Names the scope writes with a derivative somewhere: functions of time.
    time: &'a HashSet<String>,
    /// Names the linter declares with `unknowns`: the facts determine them.
    solve: &'a HashSet<String>,
    /// What this run has read and checked.
    cache: &'a Checked,
    /// Whether the chain being placed is a premise the notes impose.
    imposing: bool,
    /// Where the links start (document offsets) whose relations are not taken as
    /// stated: they contradict what was stated before them, or they are mistakes
    /// (`sound::unfit`).
    skip: &'a HashSet<usize>,
    /// With a set: only the chains starting there keep the claim of a first link that
    /// a given states again (`Scope::build_with`).
    keep: Option<&'a HashSet<usize>>,
    /// The definitions of earlier sections written into this derivation: name, the
    /// definition as the notes write it, and where it starts in the document.
    carried: Vec<(String, String, usize)>,
    /// Whether the definitions of earlier sections are written in.
    carry: bool,
}

impl Scope {
    /// A new scope under the document's `rigor:` statements so far.
    fn under(directives: &str, names: &HashSet<String>) -> Scope {
        Scope {
            directives: directives.to_string(),
            names: names.clone(),
            items: Vec::new(),
            quiet: HashSet::new(),
            carried: Vec::new(),
            values: Vec::new(),
        }
    }

    /// The derivation made from the scope.
    fn build<'a>(
        &self,
        doc: &str,
        sets: (&'a HashSet<String>, &'a HashSet<String>, &'a HashSet<usize>),
        cache: &'a Checked,
        carry: bool,
    ) -> Build<'a> {
        self.build_with(doc, sets, (cache, carry), (None, None))
    }

    /// The derivation made from the scope, with `extra` (a `rigor:` statement and the
    /// names it declares) after the document's statements; with `keep`, only the chains
    /// starting there keep the claim of a first link that a given states again (the
    /// others' verdicts are not wanted: the given brings the same relation).
    fn build_with<'a>(
        &self,
        doc: &str,
        (time, solve, skip): (&'a HashSet<String>, &'a HashSet<String>, &'a HashSet<usize>),
        (cache, carry): (&'a Checked, bool),
        (extra, keep): (Option<&Extra>, Option<&'a HashSet<usize>>),
    ) -> Build<'a> {
        let mut b = Build {
            deriv: self.directives.clone(),
            placed: Vec::new(),
            declared: self.names.clone(),
            known: self.names.clone(),
            seen: HashSet::new(),
            time,
            solve,
            cache,
            imposing: false,
            skip,
            keep,
            carried: Vec::new(),
            carry,
        };
        if let Some((text, names)) = extra {
            b.deriv.push_str(text);
            b.deriv.push('\n');
            b.declared.extend(names.iter().cloned());
            b.known.extend(names.iter().cloned());
        }
        if b.carry {
            carry::place_carried(self, doc, &mut b);
        }
        for item in &self.items {
            match item {
                Item::Directive(text, names) => {
                    b.deriv.push_str(text);
                    b.deriv.push('\n');
                    b.declared.extend(names.iter().cloned());
                    b.known.extend(names.iter().cloned());
                }
                Item::Chain(chain) => place(chain, doc, &mut b),
                Item::Imposed(chain) => {
                    b.imposing = true;
                    place(chain, doc, &mut b);
                    b.imposing = false;
                }
            }
        }
        b
    }

    /// Checks the scope and gives each chain its verdict (`close_with`); then, when it
    /// has results of earlier sections and chains that need context, checks it again
    /// with those results written in (`carry.rs`): a chain not verified without them
    /// that is verified with them, and one that needs context without them and fails
    /// with them, takes that verdict. A chain that holds as the section writes it (a
    /// letter reused: `I_G` of another body, used as any) keeps its own.
    fn close(
        &self,
        (name, doc): (&str, &LineIndex<'_>),
        (opts, cache): (&Options, &Checked),
        out: &mut Vec<ChainReport>,
    ) {
        let mut base = Vec::new();
        self.close_with((name, doc), (opts, cache), false, &mut base);
        let open = |r: &ChainReport| matches!(r.verdict, Verdict::NeedsContext | Verdict::Failed);
        if self.carried.is_empty() || !base.iter().any(open) {
            out.extend(base);
            return;
        }
        let mut with = Vec::new();
        self.close_with((name, doc), (opts, cache), true, &mut with);
        carry::settle(base, &with, out);
    }

    /// Checks the scope's derivation and gives each chain its verdict. A name the
    /// linter assumed (no `rigor:` comment declares it) that the facts determine is
    /// then declared with `unknowns` and the scope checked again: in notes, letters are
    /// not declared as given quantities, so `N` found from `N - m g cos(beta) = 0` is
    /// solved for, not held fixed.
    fn close_with(
        &self,
        (name, doc): (&str, &LineIndex<'_>),
        (opts, cache): (&Options, &Checked),
        carry: bool,
        out: &mut Vec<ChainReport>,
    ) {
        let mut time = HashSet::new();
        for item in &self.items {
            if let Item::Chain(c) | Item::Imposed(c) = item {
                let mut names = Vec::new();
                free(&c.first, &mut Vec::new(), &mut names);
                for l in &c.links {
                    free(&l.rhs, &mut Vec::new(), &mut names);
                }
                time.extend(
                    names
                        .iter()
                        .filter(|n| n.ends_with('\''))
                        .map(|n| n.trim_end_matches('\'').to_string()),
                );
                for e in c.exprs() {
                    changing(e, &mut time);
                }
            }
        }
        let mut solve = HashSet::new();
        let mut skip = HashSet::new();
        // While names to solve for may still be found, a check stops at the first one:
        // the scope is checked again with it, so the rest would be checked for nothing.
        let mut finding = 0;
        let finder = Options {
            stop_at_determined_given: true,
            ..opts.clone()
        };
        let mut round = 0;
        while round < ROUNDS {
            let b = self.build(doc.text(), (&time, &solve, &skip), cache, carry);
            if b.placed.is_empty() {
                return;
            }
            let finds = finding < FINDING;
            let checked = cache.report(name, &b.deriv, if finds { &finder } else { opts });
            let more: Vec<String> = checked
                .diagnostics
                .iter()
                .filter_map(|d| match &d.mistake {
                    Some(Mistake::DeclaredGiven(name)) => Some(name.clone()),
                    _ => None,
                })
                .filter(|n| !b.known.contains(n) && !solve.contains(n))
                .collect();
            if finds && !more.is_empty() {
                solve.extend(more);
                finding += 1;
                continue;
            }
            if finds && checked.names_determined_given() {
                // It stopped at a name already solved for: check it all.
                finding = FINDING;
                continue;
            }
            round += 1;
            // Stated relations become premises only when they fit together: one that
            // contradicts those before it, or a mistake, is taken back and the scope
            // checked again without it (two slips must not make a third line follow).
            let unfit: Vec<usize> = sound::unfit(&checked, &b, (name, doc.text()), opts)
                .into_iter()
                .filter(|k| !skip.contains(k))
                .collect();
            if !unfit.is_empty() {
                if round < ROUNDS {
                    skip.extend(unfit);
                    continue;
                }
                // Out of rounds: nothing is verified from the facts in scope.
                sound::distrust(&b, &checked, (name, doc), (opts, cache), out);
                return;
            }
            let start = out.len();
            report_all(&b, &checked, (name, doc), (opts, cache), out);
            let sets = (&time, &solve, &skip);
            values::suggest(
                self,
                (&b, sets),
                (name, doc.text()),
                (opts, cache),
                &mut out[start..],
            );
            return;
        }
    }
}

/// A `rigor:` statement written into a scope's derivation, with the names it declares.
type Extra = (String, Vec<String>);

/// The sets a scope's derivation is built with: names written with a derivative, names
/// to solve for, links not taken as stated.
type Sets<'a> = (&'a HashSet<String>, &'a HashSet<String>, &'a HashSet<usize>);

/// How many times a scope is checked at most without the stated relations that do not
/// fit.
const ROUNDS: usize = 6;

/// How many times at most a scope is checked again with names the facts determine
/// declared as unknowns (each such check stops at the first name it finds).
const FINDING: usize = 4;

/// Checks the chains of `doc`. Each heading starts a new scope: notes reuse letters
/// from one section to the next (R a radius, then a reaction), so what one section
/// defines or states is not a fact of the next; `rigor:` statements hold throughout.
pub fn lint(name: &str, doc: &str, kind: DocKind, opts: &Options) -> LintReport {
    let doc = Document {
        name: name.to_string(),
        text: doc.to_string(),
        kind,
    };
    lint_all(std::slice::from_ref(&doc), opts)
        .pop()
        .unwrap_or_default()
}

/// A diagnostic about the derivation made from the document, with the lines it cites
/// (lines of that derivation) turned into the lines of the document they came from. A
/// line of the `rigor:` statements is not a line of the notes: a fact on one is not
/// cited.
fn document_lines(d: &mut Diagnostic, deriv: &str, placed: &[Placed], doc: &LineIndex<'_>) {
    let doc_line = |n: usize| doc_line(n, deriv, placed, doc);
    d.message = d.message.renumber(&doc_line);
    d.notes = d.notes.iter().map(|n| n.renumber(&doc_line)).collect();
}

/// The line of the document that line `n` of the derivation came from, if it came
/// from the notes (not from a `rigor:` statement or a declaration).
fn doc_line(n: usize, deriv: &str, placed: &[Placed], doc: &LineIndex<'_>) -> Option<usize> {
    let line_start = deriv
        .split_inclusive('\n')
        .take(n.checked_sub(1)?)
        .map(str::len)
        .sum::<usize>();
    let line_end = line_start + deriv.get(line_start..)?.find('\n').unwrap_or(0);
    let at = placed
        .iter()
        .flat_map(|p| {
            p.first
                .iter()
                .chain(p.rest.iter())
                .chain(p.stated.iter())
                .chain(p.givens.iter())
        })
        .flatten()
        .find(|(at, _, _)| *at >= line_start && *at <= line_end)?
        .1;
    Some(doc.line_col(at).0)
}

/// Writes a chain into the derivation: its new symbols declared, then as a `let` (a
/// lone new symbol on the left) and a claim of the rest, or as a claim.
fn place(chain: &Chain, doc: &str, b: &mut Build<'_>) {
    let Build {
        deriv,
        placed,
        declared,
        known,
        seen,
        time,
        solve,
        cache,
        imposing,
        skip,
        keep,
        ..
    } = b;
    let mut names = first_link_names(chain);
    let is_known = |n: &String| known.contains(n.trim_end_matches('\'')) || n == "t";
    let firm = !*imposing && names.iter().all(is_known);
    let loose = premises::loose_approximations(chain, deriv);
    let constraint = is_constraint(&names, time);
    let mut later = later_links(chain, &mut names, seen, &is_known);
    for l in &mut later {
        l.skipped = skip.contains(&l.span.start);
    }
    seen.extend(names.iter().map(|n| n.trim_end_matches('\'').to_string()));
    let chain_names = names.clone();
    let defines = new_symbol(chain, declared, time);
    declare(names, defines.as_ref(), deriv, declared, (time, solve));
    let text = |s: Span| flat(doc, s);
    let last = chain.links.last().map_or(chain.first.span, |l| l.span);
    let chain_span = chain.first.span.to(last);
    let Some(link0) = chain.links.first() else {
        return;
    };
    let write = |kw: &str, pieces: &[Span], deriv: &mut String| {
        write_statement(kw, pieces, (doc, cache), deriv)
    };
    let rest_span = chain
        .links
        .get(1)
        .map(|l| Span::new(l.span.start, last.end));
    let first_link = [
        chain.first.span,
        Span::new(link0.span.start, link0.span.end),
    ];
    let stated;
    let (first, states) = match &defines {
        Some(s) => {
            declared.insert(s.clone());
            known.insert(s.clone());
            let stmt = format!(
                "let $$ {} = {} $$\n",
                text(chain.first.span),
                text(link0.rhs.span)
            );
            if cache.parses(&stmt) {
                stated = Some(vec![(deriv.len() + 7, chain.first.span.start, 0)]);
                deriv.push_str(&stmt);
                (None, true)
            } else {
                declared.remove(s);
                stated = None;
                (None, false)
            }
        }
        None => {
            // Checked as a claim; then, holding or not, taken as what the notes state —
            // unless every symbol is one the document declared: then it is a step, a
            // fact once verified, and a mistake (never a fact) if not.
            let start = chain.first.span.start;
            let restated = (!firm || constraint) && !skip.contains(&start);
            let wanted = keep.is_none_or(|k| k.contains(&start));
            let claim = (!restated || constraint || wanted)
                .then(|| write("claim", &first_link, deriv))
                .flatten();
            let kw = if constraint { "constraint" } else { "given" };
            stated = restated.then(|| write(kw, &first_link, deriv)).flatten();
            (claim, lone(&chain.first))
        }
    };
    let rest = rest_span.and_then(|r| write("claim", &[link0.rhs.span, r], deriv));
    // A part that does not read as rigor's own statement is not checked: the chain
    // needs context, never verified by what was left out.
    let unwritten = (first.is_none() && !states) || (rest_span.is_some() && rest.is_none());
    // Then each later link is taken as stated too, as the first is: one that does not
    // follow states something new (`m y'' = 0`), which later chains may use.
    let mut givens = Vec::new();
    for ((prev, l), later) in chain
        .links
        .iter()
        .zip(chain.links.iter().skip(1))
        .zip(&later)
    {
        if !later.firm && !skip.contains(&later.span.start) {
            givens.extend(write("given", &[prev.rhs.span, l.span], deriv));
        }
    }
    let defined = (first.is_none() && states).then_some(defines).flatten();
    let contradicts = first.is_some() && skip.contains(&chain.first.span.start);
    placed.push(Placed {
        first,
        rest,
        stated,
        later,
        span: chain_span,
        first_link: Span::new(link0.rhs.span.start, link0.span.end),
        states,
        firm,
        defines: defined,
        imposed: *imposing,
        loose,
        unwritten,
        symbols: chain_names,
        contradicts,
        givens,
        head: text(chain.first.span).trim().to_string(),
    });
}

/// Whether `e` is a lone symbol or a power of one (`\omega^2 = \frac{g}{L}` states what
/// `\omega` is, as `T = 2\pi/\omega` states `T`).
fn lone(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Sym(_) => true,
        ExprKind::Bin(crate::syntax::ast::BinOp::Pow, base, exp) => {
            matches!(base.kind, ExprKind::Sym(_)) && matches!(exp.kind, ExprKind::Num(_))
        }
        _ => false,
    }
}

/// The text of `s` in the document on one line: a link may run over several rows of a
/// display.
fn flat(doc: &str, s: Span) -> String {
    doc.get(s.start..s.end)
        .unwrap_or("")
        .replace(['\n', '\r'], " ")
}

/// Writes `kw $$ pieces $$` into the derivation when it reads, and where each piece
/// came from.
fn write_statement(
    kw: &str,
    pieces: &[Span],
    (doc, cache): (&str, &Checked),
    deriv: &mut String,
) -> Option<Part> {
    let mut stmt = format!("{kw} $$ ");
    for p in pieces {
        stmt.push_str(&flat(doc, *p));
        stmt.push(' ');
    }
    stmt.push_str("$$\n");
    if !cache.parses(&stmt) {
        return None;
    }
    let mut part = Vec::new();
    let mut at = deriv.len() + kw.len() + 4;
    for p in pieces {
        part.push((at, p.start, p.end - p.start));
        at += p.end - p.start + 1;
    }
    deriv.push_str(&stmt);
    Some(part)
}

/// The lone new symbol a chain's first link defines: not declared, not a derivative,
/// and not written with a derivative elsewhere (a function of time: a relation for it
/// is a constraint or a law, never a `let`).
fn new_symbol(chain: &Chain, declared: &HashSet<String>, time: &HashSet<String>) -> Option<String> {
    match &chain.first.kind {
        ExprKind::Sym(n)
            if !declared.contains(n.trim_end_matches('\''))
                && !n.ends_with('\'')
                && !time.contains(n) =>
        {
            Some(n.clone())
        }
        _ => None,
    }
}

/// The free names of a chain's first link.
fn first_link_names(chain: &Chain) -> Vec<String> {
    let mut names = Vec::new();
    free(&chain.first, &mut Vec::new(), &mut names);
    if let Some(l) = chain.links.first() {
        free(&l.rhs, &mut Vec::new(), &mut names);
    }
    names
}

/// A relation between positions of two or more moving things (`x = -theta R`) is a
/// constraint: it holds at every instant, so its derivatives do too. Anything else
/// stated (a law with accelerations, a value at release) holds at the instant only.
fn is_constraint(names: &[String], time: &HashSet<String>) -> bool {
    let bases: HashSet<&str> = names.iter().map(|n| n.trim_end_matches('\'')).collect();
    !names.iter().any(|n| n.ends_with('\''))
        && bases.iter().filter(|n| time.contains(**n)).count() >= 2
}

/// Declares the chain's new symbols: `time` for those the scope writes with a
/// derivative, `unknowns` for those the facts determine, `symbols` for the rest.
fn declare(
    names: Vec<String>,
    defines: Option<&String>,
    deriv: &mut String,
    declared: &mut HashSet<String>,
    (time, solve): (&HashSet<String>, &HashSet<String>),
) {
    let mut kinds: [(&str, Vec<String>); 3] = [
        ("symbols", Vec::new()),
        ("unknowns", Vec::new()),
        ("time", Vec::new()),
    ];
    for n in names {
        let base = n.trim_end_matches('\'').to_string();
        if declared.contains(&base) || Some(&base) == defines || base == "t" || base == "dm" {
            continue;
        }
        declared.insert(base.clone());
        let k = if time.contains(&base) {
            2
        } else if solve.contains(&base) {
            1
        } else {
            0
        };
        kinds[k].1.push(base);
    }
    for (kw, list) in kinds {
        if !list.is_empty() {
            // Room for ` > 0` (`premises::positive`), so offsets stay as they are.
            let room = if kw == "symbols" { premises::ROOM } else { "" };
            deriv.push_str(&format!("{kw} {}{room}\n", list.join(" ")));
        }
    }
}

/// The names inside a derivative with respect to time written in Leibniz notation
/// (`\frac{d}{dt}(m v)`): written with a derivative, so functions of time, as `x` is
/// when the notes write `\dot x` or `\frac{dx}{dt}`.
fn changing(e: &Expr, out: &mut HashSet<String>) {
    let by_time =
        |args: &[Expr]| matches!(args.get(1).map(|a| &a.kind), Some(ExprKind::Sym(v)) if v == "t");
    match &e.kind {
        ExprKind::Call(Func::Diff, args) if e.reading == Reading::Leibniz && by_time(args) => {
            let mut names = Vec::new();
            if let Some(f) = args.first() {
                free(f, &mut vec!["t".to_string()], &mut names);
            }
            out.extend(names.iter().map(|n| n.trim_end_matches('\'').to_string()));
        }
        ExprKind::Sym(_) | ExprKind::Num(_) | ExprKind::Pi => {}
        ExprKind::Neg(a) => changing(a, out),
        ExprKind::Bin(_, a, b) => {
            changing(a, out);
            changing(b, out);
        }
        ExprKind::Call(_, args) => args.iter().for_each(|a| changing(a, out)),
    }
}

/// Free symbol names of a tree (bound variables of `int`, `diff`, `subs`, `eval` left out).
fn free(e: &Expr, bound: &mut Vec<String>, out: &mut Vec<String>) {
    match &e.kind {
        ExprKind::Sym(n) if !bound.contains(n) => {
            if !out.contains(n) {
                out.push(n.clone());
            }
        }
        ExprKind::Sym(_) | ExprKind::Num(_) | ExprKind::Pi => {}
        ExprKind::Neg(a) => free(a, bound, out),
        ExprKind::Bin(_, a, b) => {
            free(a, bound, out);
            free(b, bound, out);
        }
        ExprKind::Call(f, args) => {
            let var = match (f, args.get(1).map(|a| &a.kind)) {
                (Func::Int | Func::Diff | Func::Subs | Func::Eval, Some(ExprKind::Sym(v))) => {
                    Some(v.clone())
                }
                _ => None,
            };
            for (i, a) in args.iter().enumerate() {
                if i == 1 && var.is_some() {
                    continue;
                }
                if i == 0 {
                    bound.extend(var.clone());
                    free(a, bound, out);
                    if var.is_some() {
                        bound.pop();
                    }
                } else {
                    free(a, bound, out);
                }
            }
        }
    }
}

/// The verdict on a placed chain, with its diagnostics moved to document positions.
/// The statuses and diagnostics (in document positions) of one claim part.
fn part_outcome(checked: &FileReport, part: &Part, whole: Span) -> (Vec<Status>, Vec<Diagnostic>) {
    // Each end of a span mapped on its own: a link's span runs across two pieces.
    let pos = |x: usize| {
        part.iter()
            .find(|(at, _, len)| x >= *at && x <= at + len)
            .map(|(at, doc, _)| x - at + doc)
    };
    let diagnostics = checked
        .diagnostics
        .iter()
        .filter(|d| {
            d.primary
                .as_ref()
                .is_some_and(|(s, _)| pos(s.start).is_some())
        })
        .cloned()
        .map(|mut d| {
            if let Some((s, _)) = d.primary.as_mut() {
                let start = pos(s.start).unwrap_or(whole.start);
                *s = Span::new(start, pos(s.end).unwrap_or(whole.end).max(start));
            }
            d
        })
        .collect();
    let first = part.first().map_or(0, |s| s.0);
    let statuses = checked
        .claims
        .iter()
        .filter(|c| c.span.start <= first && c.span.end > first)
        .flat_map(|c| c.links.iter().map(|l| l.status.clone()))
        .collect();
    (statuses, diagnostics)
}

/// Whether `d` shows its relation false (or its units inconsistent), rather than not
/// shown: in a chain whose first link states a relation, that is a mistake.
fn refuted(d: &Diagnostic) -> bool {
    matches!(
        d.code,
        Code::Refuted | Code::Inequality | Code::Approximation | Code::DivisionByZero | Code::Units
    )
}

/// The report of a chain that could not be written as a derivation.
fn unwritten(p: &Placed) -> ChainReport {
    let why = Diagnostic::error(
        Code::NotVerified,
        "needs context: rigor reads this chain but cannot write it as a derivation, so it is not checked",
        p.span,
        "",
    );
    ChainReport::new(p.span, Verdict::NeedsContext, vec![why])
}

/// The verdict on a placed chain, and for one that needs context, why.
fn verdict(checked: &FileReport, p: &Placed) -> ChainReport {
    let mut report = verdict_on(checked, p);
    premises::beyond_order(&mut report, &p.loose);
    if report.verdict == Verdict::NeedsContext && report.reason.is_none() {
        let reason = reason::of(checked, p, &report.diagnostics);
        if reason == Reason::Approximation {
            report.comment = premises::small_comment(&p.loose, &report.diagnostics);
        }
        report.reason = Some(reason);
    }
    report
}

/// The verdict on a placed chain: its later links must follow (else it failed); its
/// first link must hold on its own, or state a relation for a lone symbol.
fn verdict_on(checked: &FileReport, p: &Placed) -> ChainReport {
    if p.unwritten {
        return unwritten(p);
    }
    let holds = |s: &[Status]| !s.is_empty() && s.iter().all(Status::is_verified);
    let (first_statuses, mut first_diags) = match &p.first {
        Some(part) => part_outcome(checked, part, p.span),
        None => (Vec::new(), Vec::new()),
    };
    premises::loosen(&mut first_diags, &p.loose);
    let first_ok = p.first.is_none() || holds(&first_statuses);
    let rest = p.rest.as_ref().map(|part| {
        let (s, mut d) = part_outcome(checked, part, p.span);
        premises::loosen(&mut d, &p.loose);
        (s, d)
    });
    if p.firm && !p.states && first_diags.iter().any(refuted) {
        return ChainReport::new(p.span, Verdict::Failed, first_diags);
    }
    // A verified chain says what its links assume (a division the signs do not show safe).
    let mut assuming = conditions(&first_statuses);
    assuming.extend(rest.iter().flat_map(|(s, _)| conditions(s)));
    let report = |verdict, diagnostics| ChainReport {
        assuming: if verdict == Verdict::Verified {
            once(assuming.clone())
        } else {
            Vec::new()
        },
        defines: p.defines.clone(),
        ..ChainReport::new(p.span, verdict, diagnostics)
    };
    if let Some((s, mut d)) = rest {
        later::imposed_or_false(p, &mut d);
        if d.iter().any(refuted) {
            let mistake = |x: &Diagnostic| {
                later_is_a_mistake(p, x) || later_link(p, x).is_some_and(|l| l.skipped)
            };
            if d.iter().any(|x| refuted(x) && mistake(x)) {
                return report(Verdict::Failed, d);
            }
            for x in d.iter_mut().filter(|x| refuted(x)) {
                x.message = later_needs(p, x).into();
                x.code = Code::NotVerified;
                x.mistake = None;
            }
            first_diags.extend(d);
            return report(Verdict::NeedsContext, first_diags);
        }
        if holds(&s) && (first_ok || p.states) {
            return report(Verdict::Verified, Vec::new());
        }
        // A later link that brings in a symbol nothing before it defines (`= k_G^2`)
        // needs that definition, whatever the facts it was tried with relate.
        for x in &mut d {
            if later_link(p, x).is_some_and(|l| !l.fresh.is_empty()) {
                x.message = later_needs(p, x).into();
            }
        }
        first_diags.extend(d);
    } else if p.first.is_none() && p.states {
        // Only a definition, nothing checked.
        return report(Verdict::Defined, Vec::new());
    } else if first_ok {
        return report(Verdict::Verified, Vec::new());
    }
    // What the first link needs is context, not a mistake: notes state relations that
    // hold by definitions and laws given in prose.
    for d in &mut first_diags {
        if refuted(d) {
            d.code = Code::NotVerified;
            d.mistake = None;
            d.message = if p.imposed {
                premises::IMPOSED.into()
            } else if p.contradicts {
                sound::CONTRADICTS.into()
            } else {
                "needs context: this relation does not hold for every value of its symbols; the document must define or give it".into()
            };
        }
    }
    if first_diags.is_empty() {
        first_diags.push(Diagnostic::error(
            Code::NotVerified,
            "needs context: this chain uses something the document defines elsewhere",
            p.span,
            "",
        ));
    }
    report(Verdict::NeedsContext, first_diags)
}
