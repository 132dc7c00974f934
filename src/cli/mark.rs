//! `rigor mark` on the file system: the class walked without following links (a link is
//! a row that says why), the reference and a file met twice never marked, imports that
//! reach only the folders the tutor allows (`--allow-use`), and the reports written.

use rigor::check::{ImportError, Options, Resolver, Source};
use rigor::files::FsResolver;
use rigor::mark::{Expected, Row};
use rigor::syntax::ParseOptions;
use std::path::{Path, PathBuf};

/// What the tutor asked for besides the class: the summary table, feedback files (and
/// whether they show the reference), and the folders a submission may import from.
pub struct Reports<'a> {
    /// Print the Markdown summary table instead of lines per submission.
    pub summary: bool,
    /// Write one feedback file per submission into this folder.
    pub feedback: Option<&'a Path>,
    /// Show the reference's working in the feedback files.
    pub reveal: bool,
    /// The folders a submission's `use` may reach (a course library).
    pub allow_use: &'a [PathBuf],
}

/// One entry of the class: a file to mark, or one that is not marked, and why.
enum Entry {
    Mark(PathBuf),
    Skip(PathBuf, String),
}

/// Imports of a submission: only files inside the allowed folders (never the
/// reference), found relative to the importing file as `check` finds them.
struct ClassResolver {
    allowed: Vec<FsResolver>,
    reference: Option<PathBuf>,
}

impl Resolver for ClassResolver {
    fn resolve(&self, importer: &str, path: &str) -> Result<Source, ImportError> {
        let refused = || ImportError::NotAllowed { path: path.into() };
        for r in &self.allowed {
            match r.resolve(importer, path) {
                Err(ImportError::OutsideRoot { .. }) => continue,
                Ok(s)
                    if self
                        .reference
                        .as_ref()
                        .is_some_and(|p| p.display().to_string() == s.id) =>
                {
                    return Err(refused())
                }
                other => return other,
            }
        }
        Err(refused())
    }

    fn identify(&self, name: &str) -> String {
        Path::new(name)
            .canonicalize()
            .map_or_else(|_| name.to_string(), |p| p.display().to_string())
    }
}

/// The entries of one folder, links not followed: a link named `*.deriv`, or one to a
/// folder, is a row that says why it was not marked.
fn walk(dir: &Path, out: &mut Vec<Entry>) -> Result<(), String> {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| format!("cannot read {}: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    entries.sort();
    for e in entries {
        let Ok(meta) = std::fs::symlink_metadata(&e) else {
            continue;
        };
        let deriv = e.extension().is_some_and(|x| x == "deriv");
        if meta.file_type().is_symlink() {
            if deriv || e.is_dir() {
                out.push(Entry::Skip(
                    e,
                    "it is a symbolic link, and marking does not follow links".into(),
                ));
            }
        } else if meta.is_dir() {
            walk(&e, out)?;
        } else if deriv {
            out.push(Entry::Mark(e));
        }
    }
    Ok(())
}

/// The identity of a file: its device and inode where there are such (so a hard link
/// is the same file), else its canonical path.
fn identity(p: &Path) -> Option<String> {
    let canon = p.canonicalize().ok()?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        let m = std::fs::metadata(&canon).ok()?;
        Some(format!("{}:{}", m.dev(), m.ino()))
    }
    #[cfg(not(unix))]
    {
        Some(canon.display().to_string())
    }
}

/// The class: every `.deriv` file under the paths given (a path given on the command
/// line is the tutor's, and followed even if it is a link; links inside are not), the
/// reference and files met before set aside with the reason.
fn class(paths: &[PathBuf], reference: &Path) -> Result<Vec<Entry>, String> {
    let mut found = Vec::new();
    for p in paths {
        let before = found.len();
        if p.is_dir() {
            walk(p, &mut found)?;
        } else if p.exists() {
            found.push(Entry::Mark(p.clone()));
        } else {
            return Err(format!(
                "cannot read {}: no such file or folder",
                p.display()
            ));
        }
        if found.len() == before {
            return Err(format!("{}: no `.deriv` file in it", p.display()));
        }
    }
    let reference = identity(reference);
    let mut seen: Vec<(String, PathBuf)> = Vec::new();
    Ok(found
        .into_iter()
        .map(|e| {
            let Entry::Mark(p) = e else { return e };
            let Some(id) = identity(&p) else {
                return Entry::Mark(p);
            };
            if Some(&id) == reference.as_ref() {
                return Entry::Skip(p, "it is the reference, which is never marked".into());
            }
            if let Some((_, first)) = seen.iter().find(|(i, _)| *i == id) {
                let why = format!("it is the same file as {}, marked once", first.display());
                return Entry::Skip(p, why);
            }
            seen.push((id, p.clone()));
            Entry::Mark(p)
        })
        .collect())
}

/// `rigor mark`: exit 0 when the class was marked (whatever the marks), 2 for a bad
/// reference or bad options.
pub fn mark(
    (reference, submissions): (&Path, &[PathBuf]),
    reports: &Reports<'_>,
    format: crate::MarkFormat,
    (timeout, budget): (std::time::Duration, std::time::Duration),
    opts: &ParseOptions,
) -> u8 {
    let options = Options {
        parse: *opts,
        // The limits `main` installed on this thread, for the checking threads too.
        limits: rigor::normal::limits::current(),
        timeout,
        ..Options::default()
    };
    // Each submission gets its own budget; the reference is checked without one.
    let sub_options = Options {
        file_budget: Some(budget),
        ..options.clone()
    };
    let ref_dir = reference
        .parent()
        .map_or_else(|| Path::new(".").to_path_buf(), Path::to_path_buf);
    let ref_report = rigor::files::check_file(reference, &ref_dir, &options);
    if !ref_report.ok() {
        errln!(
            "error: the reference {} does not verify:",
            reference.display()
        );
        err!("{}", rigor::render::human::report(&ref_report, false));
        return 2;
    }
    for d in reports.allow_use {
        if !d.is_dir() {
            errln!("error: --allow-use {}: not a folder", d.display());
            return 2;
        }
    }
    let expected = rigor::mark::expected(&ref_report);
    let entries = match class(submissions, reference) {
        Ok(f) => f,
        Err(e) => {
            errln!("error: {e}");
            return 2;
        }
    };
    let ref_resolver = FsResolver {
        root: ref_dir.clone(),
        max_file_size: options.max_file_size,
    };
    let sub_resolver = ClassResolver {
        allowed: reports
            .allow_use
            .iter()
            .map(|d| FsResolver {
                root: d.clone(),
                max_file_size: options.max_file_size,
            })
            .collect(),
        reference: reference.canonicalize().ok(),
    };
    let memo = rigor::mark::Memo::default();
    let rows = rigor::files::parallel(&entries, |e| match e {
        Entry::Skip(p, why) => {
            rigor::mark::unreadable(&p.display().to_string(), why.clone(), &expected)
        }
        Entry::Mark(p) => mark_one(
            p,
            (&ref_report, &expected),
            &sub_options,
            (&ref_resolver, &sub_resolver),
            &memo,
        ),
    });
    print_rows(&rows, reports.summary, format);
    match reports.feedback {
        Some(dir) => write_feedback(dir, &rows, reports.reveal.then_some(&ref_report)),
        None => 0,
    }
}

/// One submission read and marked.
fn mark_one(
    path: &Path,
    (reference, expected): (&rigor::FileReport, &[Expected]),
    options: &Options,
    resolvers: (&dyn Resolver, &dyn Resolver),
    memo: &rigor::mark::Memo,
) -> Row {
    let name = path.display().to_string();
    match rigor::files::read(path, options.max_file_size) {
        Err(e) => rigor::mark::unreadable(&name, super::read_error(&e), expected),
        Ok(text) => rigor::mark::mark(
            reference,
            expected,
            (&name, &text),
            options,
            resolvers,
            memo,
        ),
    }
}

fn print_rows(rows: &[Row], summary: bool, format: crate::MarkFormat) {
    match format {
        crate::MarkFormat::Csv => out!("{}", rigor::render::mark::csv(rows)),
        crate::MarkFormat::Json => out!("{}", rigor::render::mark::json(rows)),
        crate::MarkFormat::Human if summary => out!("{}", rigor::render::mark::summary(rows)),
        crate::MarkFormat::Human => out!("{}", rigor::render::mark::human(rows)),
    }
}

/// One Markdown feedback file per row, named by its position and its file's stem.
fn write_feedback(dir: &Path, rows: &[Row], reveal: Option<&rigor::check::FileReport>) -> u8 {
    if let Err(e) = std::fs::create_dir_all(dir) {
        errln!("error: cannot create {}: {e}", dir.display());
        return 2;
    }
    for (k, r) in rows.iter().enumerate() {
        let stem: String = Path::new(&r.file)
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default()
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        let path = dir.join(format!("{k:03}-{stem}.md"));
        if let Err(e) = std::fs::write(&path, rigor::render::mark::feedback(r, reveal)) {
            errln!("error: cannot write {}: {e}", path.display());
            return 2;
        }
    }
    0
}
