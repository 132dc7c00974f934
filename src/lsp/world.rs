//! The server's world around the one checker entry: the documents the editor has open,
//! a [`Resolver`] that serves them from memory and every other file from disk (imports
//! resolve from the document's own folder and stay inside it, as on the command line),
//! and a clock that a newer version of a document can stop: [`check`] runs on a thread
//! of its own, and once its [`Cancel`] is tripped every claim's deadline has passed.

use crate::check::{check_source, FileReport, ImportError, Options, Resolver, Source};
use crate::files::FsResolver;
use crate::lint::{DocKind, LintReport};
use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

/// What a document is, from its name: a derivation, or notes that `rigor lint` reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A `.deriv` file (or anything not recognised as notes).
    Derivation,
    /// Markdown or LaTeX notes.
    Notes(DocKind),
}

impl Kind {
    /// The kind of a document called `name`.
    pub fn of(name: &str) -> Kind {
        let lower = name.to_ascii_lowercase();
        if [".md", ".markdown", ".tex"]
            .iter()
            .any(|e| lower.ends_with(e))
        {
            Kind::Notes(DocKind::of(name))
        } else {
            Kind::Derivation
        }
    }
}

/// What a check found.
#[derive(Clone, Debug)]
pub enum Outcome {
    /// A derivation's report.
    Derivation(Box<FileReport>),
    /// Notes' report.
    Notes(LintReport),
}

/// The texts of the open documents, by path (see [`key`]).
pub type Open = HashMap<PathBuf, Arc<String>>;

/// The name a path is known by: the canonical path where the file exists, else the path
/// with `.` and `..` taken out, so that an import of an open document finds it.
pub fn key(path: &Path) -> PathBuf {
    if let Ok(p) = path.canonicalize() {
        return p;
    }
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                out.pop();
            }
            other => out.push(other),
        }
    }
    out
}

/// Imports of one document: open documents from memory, other files from disk, all
/// inside `root` (the document's folder); none for a document that is not a file.
pub struct Overlay<'a> {
    /// The open documents.
    pub open: &'a Open,
    /// The folder imports must stay inside, if the document is a file.
    pub root: Option<PathBuf>,
    /// Largest file read, in bytes.
    pub max_file_size: u64,
}

impl Resolver for Overlay<'_> {
    fn resolve(&self, importer: &str, path: &str) -> Result<Source, ImportError> {
        let Some(root) = &self.root else {
            return Err(ImportError::NotFound {
                path: path.into(),
                reason: Some(
                    "the document is not a file, so it has no folder to import from".into(),
                ),
            });
        };
        if Path::new(path).is_absolute() {
            return Err(ImportError::Absolute { path: path.into() });
        }
        let from = Path::new(importer).parent().unwrap_or(Path::new(""));
        let wanted = key(&from.join(path));
        if let Some(text) = self.open.get(&wanted) {
            if !wanted.starts_with(key(root)) {
                return Err(ImportError::OutsideRoot { path: path.into() });
            }
            return Ok(Source {
                id: wanted.display().to_string(),
                display: wanted
                    .file_name()
                    .map_or_else(String::new, |f| f.to_string_lossy().into_owned()),
                text: text.to_string(),
            });
        }
        let disk = FsResolver {
            root: root.clone(),
            max_file_size: self.max_file_size,
        };
        disk.resolve(importer, path)
    }

    fn identify(&self, name: &str) -> String {
        key(Path::new(name)).display().to_string()
    }
}

/// A flag that stops a check: tripped when a newer version of its document arrives.
pub type Cancel = Arc<AtomicBool>;

thread_local! {
    /// The flag of the check running on this thread, and how often the clock has been
    /// read since it was tripped.
    static RUNNING: RefCell<Option<(Cancel, u64)>> = const { RefCell::new(None) };
}

/// A leap larger than any budget: once the check is cancelled, every read of the clock
/// is this much later than the one before, so every deadline, old or new, has passed
/// at its next look.
const LEAP: Duration = Duration::from_secs(1_000_000_000);

/// The clock of a check that can be cancelled: the system's, until this thread's flag
/// is tripped.
fn cancellable() -> Duration {
    let now = crate::clock::system().map_or(Duration::ZERO, |c| c());
    RUNNING.with(|r| match &mut *r.borrow_mut() {
        Some((flag, reads)) if flag.load(Ordering::Relaxed) => {
            *reads = reads.saturating_add(1);
            let leaps = u32::try_from(*reads).unwrap_or(u32::MAX);
            now.saturating_add(LEAP.saturating_mul(leaps))
        }
        _ => now,
    })
}

/// Clears this thread's flag when the check returns (or unwinds).
struct Running;

impl Drop for Running {
    fn drop(&mut self) {
        RUNNING.with(|r| *r.borrow_mut() = None);
    }
}

/// The options of a check in the editor: the server's, on a clock `cancel` stops.
fn options(base: &Options) -> Options {
    Options {
        clock: Some(cancellable),
        ..base.clone()
    }
}

/// Checks the document `path` (its text `text`) as what it is, with the options `base`
/// (their clock replaced), imports from `open` and the disk; `cancel` stops it early
/// (its outcome is then of no use).
pub fn check(
    path: &str,
    text: &str,
    kind: Kind,
    (open, cancel): (&Open, &Cancel),
    base: &Options,
) -> Outcome {
    RUNNING.with(|r| *r.borrow_mut() = Some((cancel.clone(), 0)));
    let _running = Running;
    let opts = options(base);
    match kind {
        Kind::Notes(k) => Outcome::Notes(crate::lint::lint(path, text, k, &opts)),
        Kind::Derivation => {
            let p = Path::new(path);
            let root = p
                .is_absolute()
                .then(|| p.parent().map(Path::to_path_buf))
                .flatten();
            let resolver = Overlay {
                open,
                root,
                max_file_size: opts.max_file_size,
            };
            Outcome::Derivation(Box::new(check_source(path, text, &opts, &resolver)))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tripped_flag_passes_every_deadline_old_and_new() {
        let cancel: Cancel = Arc::new(AtomicBool::new(false));
        RUNNING.with(|r| *r.borrow_mut() = Some((cancel.clone(), 0)));
        let _running = Running;
        let clock = Some(cancellable as crate::clock::Clock);
        let before = crate::clock::Deadline::after(Duration::from_secs(10), clock).unwrap();
        assert!(!before.passed());
        cancel.store(true, Ordering::Relaxed);
        assert!(before.passed());
        let after = crate::clock::Deadline::after(Duration::from_secs(10), clock).unwrap();
        assert!(after.passed());
        assert_eq!(after.remaining(), Duration::ZERO);
    }

    #[test]
    fn imports_come_from_open_documents_first() {
        let dir = std::env::temp_dir().join(format!("rigor-lsp-world-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let lib = dir.join("lib.deriv");
        std::fs::write(&lib, "symbols a > 0\nclaim [A] a = a\n").unwrap();
        let mut open = Open::new();
        open.insert(
            key(&lib),
            Arc::new("symbols a > 0\nclaim [B] 2 a = a + a\n".into()),
        );
        let main = dir.join("main.deriv");
        let text = "symbols a > 0\nuse [B] from \"lib.deriv\"\nclaim a + a = 2 a by [B]\n";
        let cancel: Cancel = Arc::new(AtomicBool::new(false));
        let name = main.display().to_string();
        let base = Options::default();
        let out = check(&name, text, Kind::Derivation, (&open, &cancel), &base);
        let Outcome::Derivation(r) = out else {
            panic!("a derivation")
        };
        assert!(r.ok(), "{:?}", r.diagnostics);
        // Without the open document, the file on disk has no [B].
        let out = check(
            &name,
            text,
            Kind::Derivation,
            (&Open::new(), &cancel),
            &base,
        );
        let Outcome::Derivation(r) = out else {
            panic!("a derivation")
        };
        assert!(!r.ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
