//! The one entry of the checker: [`check_source`] checks a derivation given as text and
//! returns its [`FileReport`]. It is pure: it reads no file and no clock of its own and
//! starts no thread. `use … from "f.deriv"` goes through a [`Resolver`] the caller passes
//! in (the command line reads files beside the importing one, tests and the browser keep
//! them in memory), like typst's `World`.

use super::report::FileReport;
use super::walk::Checker;
use crate::diag::Code;
use crate::diag::{Diagnostic, Reached};
use crate::lower::Condition;
use crate::normal::Rat;
use crate::syntax::ast::Span;
use crate::syntax::{parse_file, ParseOptions};
use foldhash::{HashMap, HashMapExt};
use std::fmt;
use std::time::Duration;

/// Settings of a check run.
#[derive(Clone, Debug)]
pub struct Options {
    /// Parser limits.
    pub parse: ParseOptions,
    /// The engine's size limits (terms, digits), installed on the checking thread for
    /// the whole check.
    pub limits: crate::normal::limits::Limits,
    /// Wall-clock budget per claim (only where there is a clock).
    pub timeout: Duration,
    /// Wall-clock budget for all the claims of one file (`rigor mark` gives each
    /// submission one): once spent, the file's remaining claims are undecided.
    pub file_budget: Option<Duration>,
    /// Largest file read, in bytes (by resolvers that read files).
    pub max_file_size: u64,
    /// The clock the time budget is measured on; `None`: no budget.
    pub clock: Option<crate::clock::Clock>,
    /// For rigor's own tests of its guard only: every right side normalises to the left
    /// side, as a broken engine might, so that only the guard stands between a false
    /// step and "verified".
    #[doc(hidden)]
    pub corrupt_for_tests: bool,
    /// Stop at the first statement whose failure names a quantity declared with
    /// `symbols` that the facts determine (`Mistake::DeclaredGiven`): the statements after
    /// it are not checked. For a caller that checks the text again with that quantity
    /// declared an unknown (`rigor lint`), the rest would be checked for nothing.
    pub stop_at_determined_given: bool,
    /// Only the verdicts are wanted: a failing `=` link is reported "not verified"
    /// without the search for a counterexample or the naming of the mistake (for a
    /// caller that asks only whether links hold, as `rigor lint` does when it tests
    /// whether a stated relation forces its sides to zero). Nothing more is verified.
    pub verdicts_only: bool,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            parse: ParseOptions::default(),
            limits: crate::normal::limits::Limits::DEFAULT,
            timeout: Duration::from_secs(10),
            file_budget: None,
            max_file_size: 10_000_000,
            clock: crate::clock::system(),
            corrupt_for_tests: false,
            stop_at_determined_given: false,
            verdicts_only: false,
        }
    }
}

/// A file an import resolves to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Source {
    /// A name that identifies the file (equal names: the same file), used for cycles,
    /// for the cache, and as the importer of the file's own imports.
    pub id: String,
    /// How messages name it (`rod.deriv`).
    pub display: String,
    /// Its text.
    pub text: String,
}

/// Why the file a `use` names cannot be had (after typst's `FileError`). Each holds the
/// path as written in the `use`; [`Display`](fmt::Display) is the message shown at it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ImportError {
    /// An absolute path: `use` takes paths relative to the importing file.
    Absolute {
        /// The path as written.
        path: String,
    },
    /// A path that leaves the folder being checked.
    OutsideRoot {
        /// The path as written.
        path: String,
    },
    /// No file at the path.
    NotFound {
        /// The path as written.
        path: String,
        /// What the system said, if a file system was asked.
        reason: Option<String>,
    },
    /// A file larger than the largest file read ([`Options::max_file_size`]).
    TooLarge {
        /// The path as written.
        path: String,
        /// Its size, in bytes.
        size: u64,
        /// The limit, in bytes.
        max: u64,
    },
    /// A file that is not UTF-8 text.
    NotUtf8 {
        /// The path as written.
        path: String,
        /// The offset of the first invalid byte.
        offset: usize,
    },
    /// A file the world does not let this file import (a submission marked by a tutor
    /// may import only the course library).
    NotAllowed {
        /// The path as written.
        path: String,
    },
    /// A file that exists but cannot be read (permissions, a folder, …).
    Unreadable {
        /// The path as written.
        path: String,
        /// What the system said.
        reason: String,
    },
}

impl fmt::Display for ImportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ImportError::Absolute { path } => write!(
                f,
                "`use` takes a path relative to the importing file, not the absolute path \"{path}\""
            ),
            ImportError::OutsideRoot { path } => write!(
                f,
                "\"{path}\" is outside the folder being checked; imports must stay inside it"
            ),
            ImportError::NotFound { path, reason } => write!(
                f,
                "cannot read \"{path}\": {}",
                reason.as_deref().unwrap_or("no such file")
            ),
            ImportError::TooLarge { path, size, max } => write!(
                f,
                "cannot read \"{path}\": the file is {size} bytes, more than the limit of {max}"
            ),
            ImportError::NotUtf8 { path, offset } => write!(
                f,
                "cannot read \"{path}\": the file is not valid UTF-8 (invalid byte at offset {offset})"
            ),
            ImportError::NotAllowed { path } => write!(
                f,
                "\"{path}\" may not be imported here: a submission may import only the course library its tutor allows"
            ),
            ImportError::Unreadable { path, reason } => {
                write!(f, "cannot read \"{path}\": {reason}")
            }
        }
    }
}

impl std::error::Error for ImportError {}

/// Where imports come from: the world, passed in.
pub trait Resolver {
    /// The file that `path`, written in a `use` of the file `importer` (an [`Source::id`],
    /// or the name given to [`check_source`]), refers to, or why there is none (shown at
    /// the path).
    fn resolve(&self, importer: &str, path: &str) -> Result<Source, ImportError>;

    /// The id of the top-level file called `name` (for cycle detection).
    fn identify(&self, name: &str) -> String {
        name.to_string()
    }
}

/// Imports from files held in memory, by name; paths are relative to the importing
/// file's name (`a/b.deriv` importing `../c.deriv` reads `c.deriv`). Nothing may leave
/// the root.
#[derive(Clone, Debug, Default)]
pub struct MemoryResolver {
    files: HashMap<String, String>,
}

impl MemoryResolver {
    /// No files.
    pub fn new() -> MemoryResolver {
        MemoryResolver::default()
    }

    /// Adds (or replaces) the file `name`.
    pub fn insert(&mut self, name: &str, text: &str) {
        self.files
            .insert(normalise(name).unwrap_or_default(), text.to_string());
    }
}

/// `a/./b/../c` → `a/c`; `None` when it climbs above the root or is absolute.
pub(crate) fn normalise(path: &str) -> Option<String> {
    if path.starts_with('/') {
        return None;
    }
    let mut parts: Vec<&str> = Vec::new();
    for p in path.split('/') {
        match p {
            "" | "." => {}
            ".." => {
                parts.pop()?;
            }
            p => parts.push(p),
        }
    }
    Some(parts.join("/"))
}

impl Resolver for MemoryResolver {
    fn resolve(&self, importer: &str, path: &str) -> Result<Source, ImportError> {
        if path.starts_with('/') {
            return Err(ImportError::Absolute { path: path.into() });
        }
        let dir = importer.rsplit_once('/').map_or("", |(d, _)| d);
        let joined = if dir.is_empty() {
            path.to_string()
        } else {
            format!("{dir}/{path}")
        };
        let id =
            normalise(&joined).ok_or_else(|| ImportError::OutsideRoot { path: path.into() })?;
        let text = self.files.get(&id).ok_or_else(|| ImportError::NotFound {
            path: path.into(),
            reason: None,
        })?;
        Ok(Source {
            display: id.rsplit('/').next().unwrap_or(&id).to_string(),
            id,
            text: text.clone(),
        })
    }

    fn identify(&self, name: &str) -> String {
        normalise(name).unwrap_or_else(|| name.to_string())
    }
}

/// What an imported file offers: the verified claims by label.
#[derive(Clone, Debug, Default)]
pub struct Exports {
    /// Label → the equations `lhs − rhs = 0` of that claim, each with the conditions it
    /// was derived under (divisors nonzero, arguments of `ln` positive, radicands ≥ 0).
    pub claims: HashMap<String, Vec<(Rat, Vec<Condition>)>>,
    /// The signs the file declares for its symbols (its claims hold under them).
    pub signs: HashMap<String, crate::normal::Sign>,
    /// The file's unknowns (and `time` symbols): they cannot be instantiated.
    pub unknowns: Vec<String>,
    /// Its `let` definitions, name → value as written: `use` imports claims, and names
    /// a definition as what it is.
    pub lets: HashMap<String, String>,
    /// The units the file declares, name → unit: `use … with` must give each symbol a
    /// value in its unit.
    pub units: HashMap<String, crate::units::Dim>,
    /// The first input error of the file, if it has one.
    pub error: Option<String>,
}

/// Resolves `use` imports for one top-level file: cycles, a cache, the settings.
pub struct Loader<'o> {
    resolver: &'o dyn Resolver,
    /// Files being checked, outermost first (for cycles): id and display name.
    stack: Vec<(String, String)>,
    cache: HashMap<String, Exports>,
    /// Settings.
    pub opts: &'o Options,
}

impl Loader<'_> {
    /// The exports of `path`, written in the file `importer`, checking it if needed.
    pub fn import(&mut self, importer: &str, path: &str) -> Result<Exports, Diagnostic> {
        let failed = |m: String| Diagnostic::error(Code::ImportFailed, m, Span::new(0, 0), "");
        let src = self.resolver.resolve(importer, path).map_err(|e| {
            let d = failed(e.to_string());
            match e {
                ImportError::TooLarge { max, .. } => d.reached(Reached::FileSize(max)),
                _ => d,
            }
        })?;
        if let Some(i) = self.stack.iter().position(|(id, _)| *id == src.id) {
            let chain: Vec<&str> = self.stack[i..]
                .iter()
                .map(|(_, d)| d.as_str())
                .chain(std::iter::once(src.display.as_str()))
                .collect();
            return Err(failed(format!("import cycle: {}", chain.join(" → "))));
        }
        if let Some(e) = self.cache.get(&src.id) {
            return Ok(e.clone());
        }
        self.stack.push((src.id.clone(), src.display.clone()));
        let (_, exports) = check_in(&src.id, &src.text, self);
        self.stack.pop();
        self.cache.insert(src.id, exports.clone());
        Ok(exports)
    }
}

/// Checks one file's text with `loader` for its imports.
fn check_in(name: &str, src: &str, loader: &mut Loader<'_>) -> (FileReport, Exports) {
    // A UTF-8 byte-order mark (as some Windows editors write) is not part of the text.
    let src = src.strip_prefix('\u{feff}').unwrap_or(src);
    let mut report = FileReport {
        path: name.to_string(),
        source: src.to_string(),
        ..FileReport::default()
    };
    let ast = match parse_file(src, &loader.opts.parse) {
        Ok(f) => f,
        Err(e) => {
            report.input_error = true;
            report.diagnostics.push(Diagnostic::error(
                Code::Syntax,
                format!("syntax error: {}", e.message),
                e.span,
                "",
            ));
            return (report, Exports::default());
        }
    };
    Checker::new(report, name.to_string(), loader).run(ast)
}

/// Checks the derivation `text`, called `name` (imports resolve relative to it through
/// `resolver`): every statement and link, as data. Never fails and never panics: bad
/// input is reported in the [`FileReport`].
pub fn check_source(
    name: &str,
    text: &str,
    options: &Options,
    resolver: &dyn Resolver,
) -> FileReport {
    // This thread's limits are the options' until the check returns (or unwinds); its
    // time budgets are the options' too (each claim installs its own deadline), not a
    // deadline the caller may have set.
    let _limits = crate::normal::limits::install(options.limits);
    let _deadline = crate::normal::limits::until(None);
    let display = name.rsplit(['/', '\\']).next().unwrap_or(name).to_string();
    let mut loader = Loader {
        resolver,
        stack: vec![(resolver.identify(name), display)],
        cache: HashMap::new(),
        opts: options,
    };
    let budget = options
        .file_budget
        .and_then(|b| crate::clock::Deadline::after(b, options.clock));
    let mut report = check_in(name, text, &mut loader).0;
    // Several failed steps: the first may explain the rest (one mistake, one error).
    // Checking again spends what is left of the file's budget, if it has one.
    let left = budget.map(|d| d.remaining());
    if report.failed() >= 2 && left.is_none_or(|l| !l.is_zero()) {
        if let Ok(ast) = parse_file(&report.source, &options.parse) {
            let recheck = |changed: &str| {
                let again = Options {
                    file_budget: budget.map(|d| d.remaining()),
                    ..options.clone()
                };
                let mut loader = Loader {
                    resolver,
                    stack: loader.stack[..1].to_vec(),
                    cache: HashMap::new(),
                    opts: &again,
                };
                check_in(name, changed, &mut loader).0
            };
            super::roots::one_mistake(&mut report, &ast, &recheck);
        }
    }
    report
}
