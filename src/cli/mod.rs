//! The commands behind `rigor`'s subcommands; each returns the exit status.

use rigor::diag::Code;
// Output that ignores a closed pipe (`rigor check | head` must not panic).
macro_rules! out {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = write!(std::io::stdout().lock(), $($t)*);
    }};
}
macro_rules! outln {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout().lock(), $($t)*);
    }};
}
macro_rules! err {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = write!(std::io::stderr().lock(), $($t)*);
    }};
}
macro_rules! errln {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr().lock(), $($t)*);
    }};
}

use crate::Format;
use rigor::check::report::FileReport;
use rigor::decide::Verdict;
use rigor::diag::{self, Diagnostic};
use rigor::lower::{build_body, Env, LowerError, Lowerer};
use rigor::normal::print;
use rigor::syntax::ast::{Item, StmtKind};
use rigor::syntax::{parse_expr, parse_file, ParseOptions, SyntaxError};
use std::path::Path;

mod mark;
pub use mark::{mark, Reports as MarkReports};

fn report_syntax(e: &SyntaxError, what: &str, src: &str) {
    let d = Diagnostic::error(
        Code::Syntax,
        format!("syntax error: {}", e.message),
        e.span,
        "here",
    );
    err!("{}", diag::render(&d, what, src));
}

fn report_lower(e: &LowerError, what: &str, src: &str) {
    let code = if e.limit().is_some() {
        Code::SizeLimit
    } else {
        Code::NoValue
    };
    let message = format!("{e}{}", e.limit().map_or("", flag_of));
    let d = Diagnostic::error(code, message, e.span, "");
    err!("{}", diag::render(&d, what, src));
}

/// Adds the flag that raises it to each refusal at one of rigor's limits (the library
/// says the limit, not the flag).
fn name_the_flags(reports: &mut [FileReport]) {
    use rigor::diag::Reached;
    for d in reports.iter_mut().flat_map(|r| r.diagnostics.iter_mut()) {
        let flag = match d.reached {
            Some(Reached::Terms(_)) => " (see --max-terms)",
            Some(Reached::Digits(_)) => " (see --max-digits)",
            Some(Reached::ClaimTime) => " (see --timeout)",
            Some(Reached::FileBudget) => " (see --budget)",
            Some(Reached::FileSize(_)) => " (see --max-file-size)",
            _ => continue,
        };
        d.message.push_str(flag);
    }
}

/// Why a file could not be read, with the flag that raises the size limit when that is
/// why.
pub(crate) fn read_error(e: &rigor::files::ReadError) -> String {
    match e {
        rigor::files::ReadError::TooLarge { .. } => format!("{e} (see --max-file-size)"),
        _ => e.to_string(),
    }
}

/// The flag that sets a limit, as the command line says it after the library's message
/// (which says the limit but not how to change it).
pub fn flag_of(l: rigor::normal::Limit) -> &'static str {
    use rigor::normal::Limit;
    match l {
        Limit::Terms(_) => " (see --max-terms)",
        Limit::Digits(_) => " (see --max-digits)",
        Limit::Time => " (see --timeout)",
        Limit::Exponent | Limit::RootIndex => "",
    }
}

/// The environment of `--assume` and `--body` options: the exact engine's, and the
/// guard's (the declarations and bodies as written).
type OptionsEnv = (Env, rigor::guard::GuardEnv);

/// A name assumed twice, or a bound that uses a name assumed in the same or a later
/// `--assume`, could describe an empty region (`0 < a < b`, `0 < b < a`): refused.
/// `declared[k]` and `bounds[k]` are the names the k-th `--assume` declares and uses.
fn assumed_in_order(
    assume: &[String],
    declared: &[Vec<String>],
    bounds: &[Vec<String>],
) -> Result<(), ()> {
    for (k, names) in declared.iter().enumerate() {
        for n in names {
            let again = declared[k + 1..].iter().any(|l| l.contains(n))
                || names.iter().filter(|m| *m == n).count() > 1;
            if again {
                errln!(
                    "error: `{n}` is assumed twice (in --assume \"{}\")",
                    assume[k]
                );
                return Err(());
            }
            if let Some(j) = (0..=k).find(|&j| bounds[j].contains(n)) {
                errln!(
                    "error: the bounds in --assume \"{}\" use `{n}`, which is assumed in the same or a later --assume: assume `{n}` first",
                    assume[j]
                );
                return Err(());
            }
        }
    }
    Ok(())
}

/// Builds the environment of `--assume` and `--body` options. An `--assume` means what
/// the same text means after `symbols` in a file: signs (`R > 0`) and intervals
/// (`0 < beta < pi/2`, whose bounds may use only symbols no later `--assume` declares).
fn options_env(
    assume: &[String],
    bodies: &[String],
    opts: &ParseOptions,
) -> Result<OptionsEnv, ()> {
    use rigor::guard::Domain;
    let mut env = Env::default();
    let mut genv = rigor::guard::GuardEnv::default();
    // The names each `--assume` declares, and the symbols each one's bounds use.
    let mut declared: Vec<Vec<String>> = Vec::new();
    let mut bounds: Vec<Vec<String>> = Vec::new();
    for a in assume {
        let src = format!("symbols {a}");
        let f = parse_file(&src, opts).map_err(|e| report_syntax(&e, "--assume", &src))?;
        let (mut names_here, mut used_here) = (Vec::new(), Vec::new());
        for item in f.items {
            let Item::Stmt(s) = item else { continue };
            match s.kind {
                StmtKind::Symbols { names, sign } => {
                    for n in names {
                        env.signs.set(
                            rigor::normal::atom::sym(&n.name),
                            rigor::lower::sign_of_decl(sign),
                        );
                        genv.domains.push((n.name.clone(), Domain::Sign(sign)));
                        names_here.push(n.name);
                    }
                }
                StmtKind::Range {
                    names,
                    lo,
                    lo_strict,
                    hi,
                    hi_strict,
                } => {
                    let bound = |e: &rigor::syntax::ast::Expr| -> Result<rigor::normal::Rat, ()> {
                        let mut lw = Lowerer::new(&env);
                        lw.lower(e).map_err(|e| report_lower(&e, "--assume", &src))
                    };
                    let (l, h) = (bound(&lo)?, bound(&hi)?);
                    let (sign, range) = rigor::check::interval(
                        (l.clone(), lo_strict),
                        (h.clone(), hi_strict),
                        &env.signs,
                    )
                    .map_err(|why| {
                        let d = Diagnostic::error(
                            Code::DeclaredTwice,
                            why,
                            lo.span.to(hi.span),
                            "the lower bound must be below the upper bound",
                        );
                        err!("{}", diag::render(&d, "--assume", &src));
                    })?;
                    let mut used = Vec::new();
                    rigor::decide::symbols_in(&l, &mut used);
                    rigor::decide::symbols_in(&h, &mut used);
                    used_here.extend(used.into_iter().filter_map(rigor::normal::atom::sym_name));
                    for n in names {
                        let x = rigor::normal::atom::sym(&n.name);
                        env.signs.set(x, sign);
                        env.signs.set_range(x, Some(range.clone()));
                        genv.domains.push((
                            n.name.clone(),
                            Domain::Range {
                                lo: lo.clone(),
                                lo_strict,
                                hi: hi.clone(),
                                hi_strict,
                            },
                        ));
                        names_here.push(n.name);
                    }
                }
                _ => {}
            }
        }
        declared.push(names_here);
        bounds.push(used_here);
    }
    assumed_in_order(assume, &declared, &bounds)?;
    for b in bodies {
        let src = format!("body {b}");
        let file = match parse_file(&src, opts) {
            Ok(f) => f,
            Err(e) => {
                report_syntax(&e, "--body", &src);
                return Err(());
            }
        };
        for item in file.items {
            if let Item::Stmt(s) = item {
                if let StmtKind::Body { name, def } = s.kind {
                    match build_body(&name.name, &def, &env) {
                        Ok(body) => {
                            env.bodies.insert(name.name.clone(), body);
                            genv.bodies.insert(name.name.clone(), def);
                        }
                        Err(e) => {
                            report_lower(&e, "--body", &src);
                            return Err(());
                        }
                    }
                }
            }
        }
    }
    Ok((env, genv))
}

/// Set when lowering an argument ran out of time: `equiv` is then undecided (3), not bad input.
static TIMED_OUT: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

fn bad_input_or_undecided() -> u8 {
    if TIMED_OUT.load(std::sync::atomic::Ordering::Relaxed) {
        outln!("undecided");
        outln!("  the time budget ran out (see --timeout)");
        3
    } else {
        2
    }
}

type Conditions = Vec<(rigor::normal::Rat, rigor::lower::Need)>;

/// An argument parsed, lowered, and the conditions for it to be defined.
type Lowered = (rigor::syntax::ast::Expr, rigor::normal::Rat, Conditions);

fn lower_arg(text: &str, what: &str, env: &Env, opts: &ParseOptions) -> Result<Lowered, ()> {
    let e = parse_expr(text, opts).map_err(|e| report_syntax(&e, what, text))?;
    let mut lw = Lowerer::new(env);
    let r = lw.lower(&e).map_err(|e| {
        report_lower(&e, what, text);
        if e.timed_out() {
            TIMED_OUT.store(true, std::sync::atomic::Ordering::Relaxed);
        }
    })?;
    let conds = lw.divisors.into_iter().map(|d| (d.value, d.need)).collect();
    Ok((e, r, conds))
}

fn condition_text(c: &(rigor::normal::Rat, rigor::lower::Need)) -> String {
    let op = match c.1 {
        rigor::lower::Need::NonZero => "!=",
        rigor::lower::Need::Positive => ">",
        rigor::lower::Need::NonNegative => ">=",
    };
    format!("{} {op} 0", print::plain(&c.0))
}

/// `rigor simplify`.
pub fn simplify(
    expr: &str,
    assume: &[String],
    bodies: &[String],
    (latex, units): (bool, Option<&str>),
    opts: &ParseOptions,
) -> u8 {
    let Ok((env, _)) = options_env(assume, bodies, opts) else {
        return 2;
    };
    let Ok((_, r, _)) = lower_arg(expr, "<EXPR>", &env, opts) else {
        return 2;
    };
    let dims = match units.map(|u| units_of(&[expr], u, opts)).transpose() {
        Ok(d) => d,
        Err(e) => {
            errln!("error: {e}");
            return 2;
        }
    };
    if latex {
        outln!("{}", print::latex(&r));
    } else {
        outln!("{}", print::plain(&r));
    }
    if let Some(d) = dims.as_ref().and_then(|d| d.first()) {
        outln!("units: {d}");
    }
    0
}

/// The units (as `kg·m²`, or `any` for 0) of each expression, with `units` declared as
/// in a `units` statement; the error says what is missing or inconsistent.
fn units_of(exprs: &[&str], units: &str, opts: &ParseOptions) -> Result<Vec<String>, String> {
    use rigor::units::check::{dim_of, DimV, UnitEnv};
    let file = parse_file(&format!("units {units}"), opts)
        .map_err(|e| format!("in --units: {}", e.message))?;
    let mut map = foldhash::HashMap::default();
    for item in &file.items {
        if let rigor::syntax::ast::Item::Stmt(s) = item {
            if let StmtKind::Units { decls } = &s.kind {
                for d in decls {
                    let u = rigor::units::parse_unit(&d.unit)
                        .map_err(|e| format!("in --units, `{}`: {}", d.unit, e.message))?;
                    map.insert(d.name.name.clone(), u);
                }
            }
        }
    }
    let (defs, bodies, time) = Default::default();
    let env = UnitEnv {
        units: &map,
        defs: &defs,
        bodies: &bodies,
        time: &time,
    };
    let mut out = Vec::new();
    for e in exprs {
        let tree = parse_expr(e, opts).map_err(|x| x.message)?;
        let mut missing = Vec::new();
        let d = dim_of(&tree, &env, &mut missing).map_err(|p| p.message)?;
        if !missing.is_empty() {
            return Err(format!("no unit is given for {}", missing.join(", ")));
        }
        out.push(match d {
            DimV::Any => "any".to_string(),
            DimV::D(d) => d.si().to_string(),
        });
    }
    Ok(out)
}

/// `rigor equiv`.
pub fn equiv(
    (a, b): (&str, &str),
    assume: &[String],
    bodies: &[String],
    units: Option<&str>,
    opts: &ParseOptions,
) -> u8 {
    let Ok((env, genv)) = options_env(assume, bodies, opts) else {
        return 2;
    };
    if let Some(u) = units {
        match units_of(&[a, b], u, opts) {
            Err(e) => {
                errln!("error: {e}");
                return 2;
            }
            Ok(d) => {
                let (x, y) = (&d[0], &d[1]);
                if x != y && x != "any" && y != "any" {
                    outln!("not equal\n  the left side is in {x}, the right side in {y}");
                    return 1;
                }
            }
        }
    }
    let Ok((ea, ra, mut conds)) = lower_arg(a, "<A>", &env, opts) else {
        return bad_input_or_undecided();
    };
    let Ok((eb, rb, cb)) = lower_arg(b, "<B>", &env, opts) else {
        return bad_input_or_undecided();
    };
    conds.extend(cb);
    let verdict = rigor::decide::decide_where(&ra, &rb, &env.signs, &conds);
    // The guard re-checks a counterexample before it is printed: inside every
    // assumption, and the sides as written not equal there.
    let verdict = rigor::decide::guarded(verdict, |values| {
        rigor::guard::counterexample_stands((&ea, &eb), &genv, values)
    });
    match verdict {
        Verdict::Equal => {
            outln!("equal");
            let mut texts: Vec<String> = conds.iter().map(condition_text).collect();
            texts.dedup();
            if !texts.is_empty() {
                outln!("  where both sides are defined: {}", texts.join(", "));
            }
            0
        }
        Verdict::NotEqual {
            difference,
            exact,
            counterexample,
            diagnosis,
        } => {
            outln!("not equal");
            outln!("  left:  {}", print::plain(&ra));
            outln!("  right: {}", print::plain(&rb));
            if let Some(d) = diagnosis {
                outln!("  {d}");
            }
            if exact {
                outln!(
                    "  left − right = {}, a nonzero rational function of independent quantities",
                    print::plain(&difference)
                );
            }
            if let Some(c) = counterexample {
                if c.values.is_empty() {
                    outln!("  the left side is {}, the right side {}", c.lhs, c.rhs);
                } else {
                    outln!(
                        "  counterexample: at {} the left side is {} and the right side {}",
                        c.assignment(),
                        c.lhs,
                        c.rhs
                    );
                }
            }
            1
        }
        Verdict::Undecided { why } => {
            outln!("undecided");
            outln!("  {why}");
            3
        }
    }
}

/// `rigor check`.
pub fn check(
    paths: &[std::path::PathBuf],
    format: Format,
    verbose: bool,
    timeout: std::time::Duration,
    max_file_size: u64,
    opts: &ParseOptions,
) -> u8 {
    let default = [std::path::PathBuf::from("derivations")];
    let paths = if paths.is_empty() {
        &default[..]
    } else {
        paths
    };
    let options = rigor::check::Options {
        parse: *opts,
        // The limits `main` installed on this thread, for the checking threads too.
        limits: rigor::normal::limits::current(),
        timeout,
        max_file_size,
        file_budget: None,
        clock: rigor::clock::system(),
        corrupt_for_tests: false,
        stop_at_determined_given: false,
        verdicts_only: false,
    };
    let mut reports = rigor::files::check_paths(paths, &options);
    name_the_flags(&mut reports);
    match format {
        Format::Human => {
            for r in &reports {
                let text = rigor::render::human::report(r, verbose);
                if !text.is_empty() {
                    if r.ok() {
                        out!("{text}");
                    } else {
                        err!("{text}");
                    }
                }
            }
            out!("{}", rigor::render::human::summary(&reports));
        }
        Format::Json => {
            for r in &reports {
                outln!("{}", rigor::render::json::report(r));
            }
        }
        Format::Github => {
            for r in &reports {
                out!("{}", rigor::render::github::report(r));
            }
        }
    }
    if reports.iter().any(|r| r.input_error) {
        2
    } else if reports.iter().any(|r| !r.ok()) {
        1
    } else {
        0
    }
}

/// How `rigor latex` and `rigor markdown` write a document.
pub struct DocumentArgs<'a> {
    /// Where to write it (standard output when `None`).
    pub out: Option<&'a Path>,
    /// The title of a book (a folder).
    pub title: Option<&'a str>,
    /// LaTeX, else Markdown.
    pub latex: bool,
    /// Whether to fill in the work the files skipped.
    pub detail: rigor::render::Detail,
}

/// `rigor latex` / `rigor markdown`: renders even when a step fails (marked), exit 1 then.
/// A folder gives one book of all its files. With [`Detail::Steps`](rigor::render::Detail)
/// (`--steps`) the work the files skipped is filled in.
pub fn document(file: &Path, args: &DocumentArgs<'_>, opts: &ParseOptions) -> u8 {
    let DocumentArgs {
        out, latex, detail, ..
    } = *args;
    let options = rigor::check::Options {
        parse: *opts,
        // The limits `main` installed on this thread, for the checking threads too.
        limits: rigor::normal::limits::current(),
        ..rigor::check::Options::default()
    };
    let mut reports = rigor::files::check_paths(&[file.to_path_buf()], &options);
    if file.is_dir() {
        return match rigor::files::in_book_order(file, reports) {
            Ok(reports) => book(&reports, args),
            Err(e) => {
                errln!("error: {e}");
                2
            }
        };
    }
    if reports.len() != 1 {
        errln!("error: {} is not one derivation file", file.display());
        return 2;
    }
    let report = reports.remove(0);
    if report.ast.is_none() {
        err!("{}", rigor::render::human::report(&report, false));
        return 2;
    }
    let text = if latex {
        rigor::render::latex::document_with(&report, detail)
    } else {
        rigor::render::markdown::document_with(&report, detail)
    };
    if !write_document(out, &text) {
        return 2;
    }
    if !report.ok() {
        err!("{}", rigor::render::human::report(&report, false));
    }
    if report.input_error {
        2
    } else if report.ok() {
        0
    } else {
        1
    }
}

/// A book of several files (already in order): written like one document; the exit
/// status of the worst file.
fn book(reports: &[FileReport], args: &DocumentArgs<'_>) -> u8 {
    let DocumentArgs {
        out,
        title,
        latex,
        detail,
    } = *args;
    let title = title.unwrap_or("Worked solutions");
    let text = if latex {
        rigor::render::latex::book_with(reports, title, detail)
    } else {
        rigor::render::markdown::book_with(reports, title, detail)
    };
    if !write_document(out, &text) {
        return 2;
    }
    for r in reports.iter().filter(|r| !r.ok()) {
        err!("{}", rigor::render::human::report(r, false));
    }
    if reports.iter().any(|r| r.input_error) {
        2
    } else if reports.iter().all(FileReport::ok) {
        0
    } else {
        1
    }
}

/// Writes a document to `out` (standard output when `None`); false after saying why
/// it could not be written.
fn write_document(out: Option<&Path>, text: &str) -> bool {
    let written = match out {
        None => {
            out!("{text}");
            Ok(())
        }
        Some(path) => write_atomically(path, text),
    };
    if let Err(e) = &written {
        errln!(
            "error: cannot write {}: {e}",
            out.map_or_else(String::new, |p| p.display().to_string())
        );
    }
    written.is_ok()
}

/// Writes to a temporary file beside `path`, then renames it over `path`, so a crash
/// never leaves a half-written document.
fn write_atomically(path: &Path, text: &str) -> std::io::Result<()> {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    let tmp = dir.join(format!(".{name}.rigor-tmp-{}", std::process::id()));
    std::fs::write(&tmp, text)?;
    std::fs::rename(&tmp, path).inspect_err(|_| {
        let _ = std::fs::remove_file(&tmp);
    })
}

/// `rigor lint`: each chain verified, failed or needing context; exit 1 when one failed.
pub fn lint(
    docs: &[std::path::PathBuf],
    format: Format,
    timeout: std::time::Duration,
    opts: &ParseOptions,
) -> u8 {
    use rigor::lint::{DocKind, Verdict};
    let options = rigor::check::Options {
        parse: *opts,
        // The limits `main` installed on this thread, for the checking threads too.
        limits: rigor::normal::limits::current(),
        timeout,
        ..rigor::check::Options::default()
    };
    let mut bad_input = false;
    let mut readable = Vec::new();
    for d in docs {
        let name = d.display().to_string();
        match rigor::files::read(d, options.max_file_size) {
            Ok(text) => readable.push(rigor::lint::Document {
                kind: DocKind::of(&name),
                name,
                text,
            }),
            Err(e) => {
                errln!("error: cannot read {name}: {}", read_error(&e));
                bad_input = true;
            }
        }
    }
    // The scopes of all the documents are checked on every core; reported in order.
    let reports = rigor::lint::lint_all(&readable, &options);
    for r in &reports {
        match format {
            Format::Json => outln!("{}", rigor::render::lint::json(r)),
            Format::Github => out!("{}", rigor::render::lint::github(r)),
            Format::Human => {
                let (out, err) = rigor::render::lint::human(r);
                out!("{out}");
                err!("{err}");
            }
        }
    }
    if format == Format::Human {
        outln!("{}", rigor::render::lint::summary(&reports));
    }
    if bad_input {
        2
    } else if reports.iter().any(|r| r.count(&Verdict::Failed) > 0) {
        1
    } else {
        0
    }
}
