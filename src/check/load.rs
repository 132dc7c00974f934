//! Reading files and folders, `use` imports (confined to the folder being checked,
//! with cycle detection), and checking files in parallel.

use super::link::Checker;
use super::report::FileReport;
use crate::diag::Diagnostic;
use crate::normal::Rat;
use crate::syntax::{parse_file, ParseOptions};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Duration;

/// Settings of a check run.
#[derive(Clone, Debug)]
pub struct Options {
    /// Parser limits.
    pub parse: ParseOptions,
    /// Wall-clock budget per claim.
    pub timeout: Duration,
    /// Largest file read, in bytes.
    pub max_file_size: u64,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            parse: ParseOptions::default(),
            timeout: Duration::from_secs(10),
            max_file_size: 10_000_000,
        }
    }
}

/// What an imported file offers: the verified claims by label.
#[derive(Clone, Debug, Default)]
pub struct Exports {
    /// Label → the equations `lhs − rhs = 0` of that claim, each with the conditions it
    /// was derived under (divisors nonzero, arguments of `ln` positive, radicands ≥ 0).
    pub claims: HashMap<String, Vec<(Rat, Vec<(Rat, crate::lower::Need)>)>>,
    /// The signs the file declares for its symbols (its claims hold under them).
    pub signs: HashMap<String, crate::normal::Sign>,
    /// The file's unknowns (and `time` symbols): they cannot be instantiated.
    pub unknowns: Vec<String>,
    /// The first input error of the file, if it has one.
    pub error: Option<String>,
}

/// Resolves `use` imports for one top-level file.
pub struct Loader<'o> {
    /// The folder imports must stay inside.
    pub root: PathBuf,
    /// Files being checked, outermost first (for cycles).
    pub stack: Vec<PathBuf>,
    /// Checked imports.
    pub cache: HashMap<PathBuf, Exports>,
    /// Settings.
    pub opts: &'o Options,
}

/// Why an import failed.
pub enum ImportError {
    /// Message for the diagnostic.
    Msg(String),
}

impl Loader<'_> {
    /// The exports of `path` (relative to `from_dir`), checking it if needed.
    pub fn import(&mut self, from_dir: &Path, path: &str) -> Result<Exports, ImportError> {
        let rel = Path::new(path);
        if rel.is_absolute() {
            return Err(ImportError::Msg(format!(
                "`use` takes a path relative to the importing file, not the absolute path \"{path}\""
            )));
        }
        let joined = from_dir.join(rel);
        let canon = joined
            .canonicalize()
            .map_err(|e| ImportError::Msg(format!("cannot read \"{path}\": {e}")))?;
        let root = self
            .root
            .canonicalize()
            .unwrap_or_else(|_| self.root.clone());
        if !canon.starts_with(&root) {
            return Err(ImportError::Msg(format!(
                "\"{path}\" is outside the folder being checked; imports must stay inside it"
            )));
        }
        if let Some(i) = self.stack.iter().position(|p| *p == canon) {
            let chain: Vec<String> = self.stack[i..]
                .iter()
                .chain(std::iter::once(&canon))
                .map(|p| {
                    p.file_name().map_or_else(
                        || p.display().to_string(),
                        |f| f.to_string_lossy().into_owned(),
                    )
                })
                .collect();
            return Err(ImportError::Msg(format!(
                "import cycle: {}",
                chain.join(" → ")
            )));
        }
        if let Some(e) = self.cache.get(&canon) {
            return Ok(e.clone());
        }
        let src = read(&canon, self.opts.max_file_size)
            .map_err(|e| ImportError::Msg(format!("cannot read \"{path}\": {e}")))?;
        self.stack.push(canon.clone());
        let dir = canon.parent().map(Path::to_path_buf).unwrap_or_default();
        let (report, exports) = check_inner(&joined.display().to_string(), &src, &dir, self);
        self.stack.pop();
        let _ = report;
        self.cache.insert(canon, exports.clone());
        Ok(exports)
    }
}

fn read(path: &Path, max: u64) -> Result<String, String> {
    let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if meta.len() > max {
        return Err(format!(
            "the file is {} bytes, more than the limit of {max} (see --max-file-size)",
            meta.len()
        ));
    }
    let bytes = std::fs::read(path).map_err(|e| e.to_string())?;
    String::from_utf8(bytes).map_err(|e| {
        format!(
            "the file is not valid UTF-8 (invalid byte at offset {})",
            e.utf8_error().valid_up_to()
        )
    })
}

fn check_inner(
    path: &str,
    src: &str,
    dir: &Path,
    loader: &mut Loader<'_>,
) -> (FileReport, Exports) {
    let mut report = FileReport {
        path: path.to_string(),
        source: src.to_string(),
        ..FileReport::default()
    };
    let ast = match parse_file(src, &loader.opts.parse) {
        Ok(f) => f,
        Err(e) => {
            report.input_error = true;
            report.diagnostics.push(Diagnostic::error(
                "E0001",
                format!("syntax error: {}", e.message),
                e.span,
                "",
            ));
            return (report, Exports::default());
        }
    };
    let checker = Checker::new(report, dir.to_path_buf(), loader);
    checker.run(ast)
}

/// Checks one source text as if read from `path` (imports resolve next to `path`).
pub fn check_source(path: &Path, src: &str, opts: &Options) -> FileReport {
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let root = if dir.as_os_str().is_empty() {
        PathBuf::from(".")
    } else {
        dir.clone()
    };
    let mut loader = Loader {
        root,
        stack: path.canonicalize().ok().into_iter().collect(),
        cache: HashMap::new(),
        opts,
    };
    check_inner(&path.display().to_string(), src, &dir, &mut loader).0
}

fn collect(path: &Path, out: &mut Vec<(PathBuf, PathBuf)>, root: &Path) -> Result<(), String> {
    let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if meta.is_dir() {
        let mut entries: Vec<PathBuf> = std::fs::read_dir(path)
            .map_err(|e| e.to_string())?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .collect();
        entries.sort();
        for e in entries {
            if e.is_dir() {
                collect(&e, out, root)?;
            } else if e.extension().is_some_and(|x| x == "deriv") {
                out.push((e, root.to_path_buf()));
            }
        }
    } else {
        out.push((path.to_path_buf(), root.to_path_buf()));
    }
    Ok(())
}

fn unreadable(path: &Path, msg: String) -> FileReport {
    FileReport {
        path: path.display().to_string(),
        input_error: true,
        diagnostics: vec![Diagnostic {
            severity: crate::diag::Severity::Error,
            code: "E0002",
            message: format!("cannot read {}: {msg}", path.display()),
            primary: None,
            notes: Vec::new(),
        }],
        ..FileReport::default()
    }
}

/// Checks files and folders (folders: every `.deriv` file inside, recursively), two at a
/// time; the reports come back in a stable order (sorted by path within each argument).
pub fn check_paths(paths: &[PathBuf], opts: &Options) -> Vec<FileReport> {
    let mut jobs: Vec<(PathBuf, PathBuf)> = Vec::new();
    let mut early: Vec<(usize, FileReport)> = Vec::new();
    for p in paths {
        let root = if p.is_dir() {
            p.clone()
        } else {
            p.parent()
                .filter(|d| !d.as_os_str().is_empty())
                .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
        };
        if let Err(e) = collect(p, &mut jobs, &root) {
            early.push((jobs.len(), unreadable(p, e)));
        }
    }
    let results: Mutex<Vec<Option<FileReport>>> = Mutex::new(vec![None; jobs.len()]);
    let next = Mutex::new(0usize);
    let workers = std::thread::available_parallelism()
        .map_or(2, |n| n.get())
        .min(jobs.len().max(1));
    std::thread::scope(|s| {
        for _ in 0..workers {
            s.spawn(|| loop {
                let i = {
                    let mut n = next.lock().unwrap_or_else(|e| e.into_inner());
                    let i = *n;
                    *n += 1;
                    i
                };
                let Some((path, root)) = jobs.get(i) else {
                    break;
                };
                let report = match read(path, opts.max_file_size) {
                    Err(e) => unreadable(path, e),
                    Ok(src) => {
                        let mut loader = Loader {
                            root: root.clone(),
                            stack: path.canonicalize().ok().into_iter().collect(),
                            cache: HashMap::new(),
                            opts,
                        };
                        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
                        check_inner(&path.display().to_string(), &src, &dir, &mut loader).0
                    }
                };
                let mut r = results.lock().unwrap_or_else(|e| e.into_inner());
                if let Some(slot) = r.get_mut(i) {
                    *slot = Some(report);
                }
            });
        }
    });
    let mut out: Vec<FileReport> = Vec::new();
    let results = results.into_inner().unwrap_or_else(|e| e.into_inner());
    let mut early = early.into_iter().peekable();
    for (i, r) in results.into_iter().enumerate() {
        while early.peek().is_some_and(|e| e.0 == i) {
            if let Some(e) = early.next() {
                out.push(e.1);
            }
        }
        if let Some(r) = r {
            out.push(r);
        }
    }
    out.extend(early.map(|e| e.1));
    out
}
