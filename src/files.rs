//! The file system, for the command line, tests and benchmarks: a [`Resolver`] that
//! reads imports beside the importing file (never outside the folder being checked),
//! and the walk over files and folders, one file per core at a time. The checker itself
//! ([`crate::check_source`]) never touches the file system.

use crate::check::{check_source, FileReport, ImportError, Options, Resolver, Source};
use crate::diag::Code;
use crate::diag::Diagnostic;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Reads imports from disk: relative to the importing file, inside `root`.
#[derive(Clone, Debug)]
pub struct FsResolver {
    /// The folder imports must stay inside.
    pub root: PathBuf,
    /// Largest file read, in bytes.
    pub max_file_size: u64,
}

impl Resolver for FsResolver {
    fn resolve(&self, importer: &str, path: &str) -> Result<Source, ImportError> {
        let rel = Path::new(path);
        if rel.is_absolute() {
            return Err(ImportError::Absolute { path: path.into() });
        }
        let from_dir = Path::new(importer).parent().unwrap_or(Path::new(""));
        let joined = from_dir.join(rel);
        let canon = joined
            .canonicalize()
            .map_err(|e| ReadError::Io(e).import(path))?;
        let root = self
            .root
            .canonicalize()
            .unwrap_or_else(|_| self.root.clone());
        if !canon.starts_with(&root) {
            return Err(ImportError::OutsideRoot { path: path.into() });
        }
        let text = read_text(&canon, self.max_file_size).map_err(|e| e.import(path))?;
        Ok(Source {
            display: canon.file_name().map_or_else(
                || canon.display().to_string(),
                |f| f.to_string_lossy().into_owned(),
            ),
            id: canon.display().to_string(),
            text,
        })
    }

    fn identify(&self, name: &str) -> String {
        Path::new(name)
            .canonicalize()
            .map_or_else(|_| name.to_string(), |p| p.display().to_string())
    }
}

/// Why a file could not be read.
#[derive(Debug)]
pub enum ReadError {
    /// Larger than the largest file read.
    TooLarge {
        /// Its size, in bytes.
        size: u64,
        /// The limit, in bytes.
        max: u64,
    },
    /// Not UTF-8.
    NotUtf8 {
        /// The offset of the first invalid byte.
        offset: usize,
    },
    /// The system could not read it.
    Io(std::io::Error),
    /// Anything else, said.
    Other(String),
}

impl ReadError {
    /// The error of a `use` of `path` that found this.
    fn import(self, path: &str) -> ImportError {
        let path = path.to_string();
        match self {
            ReadError::TooLarge { size, max } => ImportError::TooLarge { path, size, max },
            ReadError::NotUtf8 { offset } => ImportError::NotUtf8 { path, offset },
            ReadError::Io(e) if e.kind() == std::io::ErrorKind::NotFound => ImportError::NotFound {
                path,
                reason: Some(e.to_string()),
            },
            ReadError::Io(e) => ImportError::Unreadable {
                path,
                reason: e.to_string(),
            },
            ReadError::Other(reason) => ImportError::Unreadable { path, reason },
        }
    }
}

impl std::fmt::Display for ReadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ReadError::TooLarge { size, max } => {
                write!(f, "the file is {size} bytes, more than the limit of {max}")
            }
            ReadError::NotUtf8 { offset } => write!(
                f,
                "the file is not valid UTF-8 (invalid byte at offset {offset})"
            ),
            ReadError::Io(e) => e.fmt(f),
            ReadError::Other(why) => f.write_str(why),
        }
    }
}

/// The text of `path`, at most `max` bytes of UTF-8.
fn read_text(path: &Path, max: u64) -> Result<String, ReadError> {
    let meta = std::fs::metadata(path).map_err(ReadError::Io)?;
    if meta.len() > max {
        return Err(ReadError::TooLarge {
            size: meta.len(),
            max,
        });
    }
    let bytes = std::fs::read(path).map_err(ReadError::Io)?;
    String::from_utf8(bytes).map_err(|e| ReadError::NotUtf8 {
        offset: e.utf8_error().valid_up_to(),
    })
}

/// The text of `path`, at most `max` bytes of UTF-8.
pub fn read(path: &Path, max: u64) -> Result<String, ReadError> {
    read_text(path, max)
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

fn unreadable(path: &Path, e: ReadError) -> FileReport {
    let reached = match e {
        ReadError::TooLarge { max, .. } => Some(crate::diag::Reached::FileSize(max)),
        _ => None,
    };
    FileReport {
        path: path.display().to_string(),
        input_error: true,
        diagnostics: vec![Diagnostic {
            severity: crate::diag::Severity::Error,
            code: Code::Unreadable,
            message: format!("cannot read {}: {e}", path.display()).into(),
            primary: None,
            notes: Vec::new(),
            mistake: None,
            reached,
        }],
        ..FileReport::default()
    }
}

/// Checks one file read from disk; its imports must stay inside `root`.
pub fn check_file(path: &Path, root: &Path, opts: &Options) -> FileReport {
    match read(path, opts.max_file_size) {
        Err(e) => unreadable(path, e),
        Ok(src) => {
            let resolver = FsResolver {
                root: root.to_path_buf(),
                max_file_size: opts.max_file_size,
            };
            check_source(&path.display().to_string(), &src, opts, &resolver)
        }
    }
}

/// Every `.deriv` file of the files and folders given, each with the folder its imports
/// must stay inside; an error names a path that cannot be read or holds none.
pub fn collect_all(paths: &[PathBuf]) -> Result<Vec<(PathBuf, PathBuf)>, String> {
    let mut jobs = Vec::new();
    for p in paths {
        let root = if p.is_dir() {
            p.clone()
        } else {
            p.parent()
                .filter(|d| !d.as_os_str().is_empty())
                .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
        };
        let before = jobs.len();
        collect(p, &mut jobs, &root).map_err(|e| format!("cannot read {}: {e}", p.display()))?;
        if jobs.len() == before {
            return Err(format!("{}: no `.deriv` file in it", p.display()));
        }
    }
    Ok(jobs)
}

/// `f` on every item, one worker per core (as many as `available_parallelism` allows:
/// `taskset` or a container's CPU limit lowers it), two without that information; results
/// in order. Workers take the next item from a shared counter as they finish one, so a
/// slow item holds up one worker only, never a fixed share of the rest.
pub fn parallel<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let results: Mutex<Vec<Option<R>>> = Mutex::new((0..items.len()).map(|_| None).collect());
    let next = AtomicUsize::new(0);
    let workers = std::thread::available_parallelism()
        .map_or(2, |n| n.get())
        .min(items.len().max(1));
    std::thread::scope(|s| {
        for _ in 0..workers {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some(item) = items.get(i) else {
                    break;
                };
                let r = f(item);
                let mut all = lock(&results);
                if let Some(slot) = all.get_mut(i) {
                    *slot = Some(r);
                }
            });
        }
    });
    results
        .into_inner()
        .unwrap_or_else(|e| e.into_inner())
        .into_iter()
        .flatten()
        .collect()
}

/// Work in two stages on every core, from one queue. Each item is first prepared
/// (`prepare`, the items with the largest `size` first), which gives it parts, each with
/// a weight; then each part is done (`part`), the heaviest ready part first. A worker
/// prepares while any item is left, so no core waits for the others to finish
/// preparing, and a heavy part starts as soon as it is known. `finish` is called with
/// an item once its last part is done, on the thread that did that part (never for an
/// item without parts). Returns each item prepared, with its parts' results in their
/// order (`None` only for an item whose preparation did not return).
pub fn staged<T: Sync, P: Send + Sync, R: Send>(
    items: &[T],
    size: impl Fn(&T) -> usize,
    prepare: impl Fn(&T) -> (P, Vec<usize>) + Sync,
    part: impl Fn(&P, usize) -> R + Sync,
    finish: impl Fn(&P) + Sync,
) -> Vec<Option<(P, Vec<R>)>> {
    let mut unprepared: Vec<usize> = (0..items.len()).collect();
    // Stable: among items of one size the earlier is prepared first (popped last-first).
    unprepared.sort_by_key(|&i| std::cmp::Reverse(size(&items[i])));
    unprepared.reverse();
    let queue = Queue {
        state: Mutex::new(Stages {
            unprepared,
            preparing: 0,
            ready: std::collections::BinaryHeap::new(),
        }),
        changed: std::sync::Condvar::new(),
    };
    let prepared: Vec<std::sync::OnceLock<P>> =
        items.iter().map(|_| std::sync::OnceLock::new()).collect();
    let left: Vec<AtomicUsize> = items.iter().map(|_| AtomicUsize::new(0)).collect();
    let results: Mutex<Vec<Vec<Option<R>>>> =
        Mutex::new(items.iter().map(|_| Vec::new()).collect());
    let workers = std::thread::available_parallelism().map_or(2, |n| n.get());
    std::thread::scope(|s| {
        for _ in 0..workers {
            s.spawn(|| {
                while let Some(task) = queue.next() {
                    match task {
                        Task::Prepare(i) => {
                            let _preparing = Preparing(&queue);
                            let (p, weights) = prepare(&items[i]);
                            left[i].store(weights.len(), Ordering::Release);
                            lock(&results)[i] = weights.iter().map(|_| None).collect();
                            prepared[i].get_or_init(|| p);
                            let mut state = lock(&queue.state);
                            for (k, w) in weights.into_iter().enumerate() {
                                state
                                    .ready
                                    .push((w, std::cmp::Reverse(i), std::cmp::Reverse(k)));
                            }
                        }
                        Task::Part(i, k) => {
                            let Some(p) = prepared[i].get() else {
                                continue;
                            };
                            let r = part(p, k);
                            if let Some(slot) = lock(&results)[i].get_mut(k) {
                                *slot = Some(r);
                            }
                            if left[i].fetch_sub(1, Ordering::AcqRel) == 1 {
                                finish(p);
                            }
                        }
                    }
                }
            });
        }
    });
    let results = results.into_inner().unwrap_or_else(|e| e.into_inner());
    prepared
        .into_iter()
        .zip(results)
        .map(|(p, rs)| Some((p.into_inner()?, rs.into_iter().flatten().collect())))
        .collect()
}

/// [`staged`]'s queue: the work left, and a signal when an item has been prepared.
struct Queue {
    state: Mutex<Stages>,
    changed: std::sync::Condvar,
}

struct Stages {
    /// The items not yet prepared, the next last.
    unprepared: Vec<usize>,
    /// How many items are being prepared.
    preparing: usize,
    /// The parts ready: weight, then item and part (the earlier first among equals).
    ready:
        std::collections::BinaryHeap<(usize, std::cmp::Reverse<usize>, std::cmp::Reverse<usize>)>,
}

enum Task {
    Prepare(usize),
    Part(usize, usize),
}

impl Queue {
    /// The next task: an item to prepare while any is left, else the heaviest ready
    /// part; waits while items being prepared may bring more; `None` when all is done.
    fn next(&self) -> Option<Task> {
        let mut state = lock(&self.state);
        loop {
            if let Some(i) = state.unprepared.pop() {
                state.preparing += 1;
                return Some(Task::Prepare(i));
            }
            if let Some((_, std::cmp::Reverse(i), std::cmp::Reverse(k))) = state.ready.pop() {
                return Some(Task::Part(i, k));
            }
            if state.preparing == 0 {
                return None;
            }
            state = self.changed.wait(state).unwrap_or_else(|e| e.into_inner());
        }
    }
}

/// An item being prepared, given back even if preparing it panics, so that no worker
/// waits for it for ever.
struct Preparing<'q>(&'q Queue);

impl Drop for Preparing<'_> {
    fn drop(&mut self) {
        lock(&self.0.state).preparing -= 1;
        self.0.changed.notify_all();
    }
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// [`parallel`] over files, the largest started first (a long file started last would
/// leave the other cores idle while it finishes); results in the order of `jobs`.
fn largest_first<R: Send>(
    jobs: &[(PathBuf, PathBuf)],
    f: impl Fn(&(PathBuf, PathBuf)) -> R + Sync,
) -> Vec<R> {
    let mut order: Vec<(u64, usize)> = jobs
        .iter()
        .enumerate()
        .map(|(i, (path, _))| (std::fs::metadata(path).map_or(0, |m| m.len()), i))
        .collect();
    // Largest first; equal sizes in the order given.
    order.sort_by_key(|&(size, i)| (std::cmp::Reverse(size), i));
    let results = parallel(&order, |&(_, i)| jobs.get(i).map(&f));
    let mut slots: Vec<Option<R>> = (0..jobs.len()).map(|_| None).collect();
    for ((_, i), r) in order.into_iter().zip(results) {
        if let Some(slot) = slots.get_mut(i) {
            *slot = r;
        }
    }
    slots.into_iter().flatten().collect()
}

/// The reports of a folder's files in the order of its `ORDER` file (one path per
/// line, relative to the folder; blank lines and `#` comments ignored), the files it
/// does not list after them in path order; without `ORDER`, in path order. A listed
/// file that does not exist, or one listed twice, is an error.
pub fn in_book_order(dir: &Path, mut reports: Vec<FileReport>) -> Result<Vec<FileReport>, String> {
    reports.sort_by(|a, b| a.path.cmp(&b.path));
    let order_file = dir.join("ORDER");
    if !order_file.is_file() {
        return Ok(reports);
    }
    let text = read(&order_file, 1_000_000).map_err(|e| e.to_string())?;
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let name = line.split('#').next().unwrap_or("").trim();
        if name.is_empty() {
            continue;
        }
        let want = dir.join(name);
        let Some(i) = reports.iter().position(|r| Path::new(&r.path) == want) else {
            let twice = out.iter().any(|r: &FileReport| Path::new(&r.path) == want);
            return Err(format!(
                "{}:{}: `{name}` {}",
                order_file.display(),
                n + 1,
                if twice {
                    "is listed twice"
                } else {
                    "is not a `.deriv` file of the folder"
                }
            ));
        };
        out.push(reports.remove(i));
    }
    out.extend(reports);
    Ok(out)
}

/// Checks files and folders (folders: every `.deriv` file inside, recursively), one per
/// core at a time; the reports come back in a stable order (sorted by path within each
/// argument).
/// A file's imports must stay inside the folder given (or the file's own folder).
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
        let before = jobs.len();
        match collect(p, &mut jobs, &root) {
            Err(e) => early.push((jobs.len(), unreadable(p, ReadError::Other(e)))),
            // A folder with no derivation in it is a mistyped path, not a pass.
            Ok(()) if jobs.len() == before => {
                let e = ReadError::Other("no `.deriv` file in it".into());
                early.push((jobs.len(), unreadable(p, e)))
            }
            Ok(()) => {}
        }
    }
    let results = largest_first(&jobs, |(path, root)| check_file(path, root, opts));
    let mut out: Vec<FileReport> = Vec::new();
    let mut early = early.into_iter().peekable();
    for (i, r) in results.into_iter().enumerate() {
        while early.peek().is_some_and(|e| e.0 == i) {
            if let Some(e) = early.next() {
                out.push(e.1);
            }
        }
        out.push(r);
    }
    out.extend(early.map(|e| e.1));
    out
}

#[cfg(test)]
mod tests {
    use super::staged;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// Every part done once, the results in the parts' order whatever order they ran
    /// in, and `finish` once per item with parts, after all of them.
    #[test]
    fn staged_does_every_part_once_and_finishes_each_item_last() {
        let items: Vec<usize> = vec![3, 0, 7, 1, 12, 5];
        let done: Vec<AtomicUsize> = items.iter().map(|_| AtomicUsize::new(0)).collect();
        let finished: Vec<AtomicUsize> = items.iter().map(|_| AtomicUsize::new(0)).collect();
        let out = staged(
            &items,
            |&n| n,
            |&n| {
                let i = items.iter().position(|&m| m == n).unwrap_or(0);
                // Weights that do not follow the parts' order.
                (i, (0..n).map(|k| (k * 7) % 5).collect())
            },
            |&i, k| {
                done[i].fetch_add(1, Ordering::SeqCst);
                (i, k * k)
            },
            |&i| {
                assert_eq!(done[i].load(Ordering::SeqCst), items[i], "item {i}");
                finished[i].fetch_add(1, Ordering::SeqCst);
            },
        );
        assert_eq!(out.len(), items.len());
        for (i, (r, &n)) in out.iter().zip(&items).enumerate() {
            let Some((p, parts)) = r else {
                panic!("item {i} not prepared");
            };
            assert_eq!(*p, i);
            let want: Vec<(usize, usize)> = (0..n).map(|k| (i, k * k)).collect();
            assert_eq!(parts, &want, "item {i}");
            assert_eq!(done[i].load(Ordering::SeqCst), n);
            assert_eq!(
                finished[i].load(Ordering::SeqCst),
                usize::from(n > 0),
                "item {i}"
            );
        }
        let none: Vec<Option<(usize, Vec<usize>)>> =
            staged(&[] as &[usize], |_| 0, |_| (0, vec![]), |_, k| k, |_| {});
        assert!(none.is_empty());
    }
}
