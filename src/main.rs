//! The `rigor` command line: parses arguments, runs a command, maps results to exit statuses.

use clap::{Parser, Subcommand, ValueEnum};
use std::process::ExitCode;

mod cli;

#[cfg(not(target_arch = "wasm32"))]
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// rigor: an exact derivation and proof checker for engineering dynamics.
#[derive(Parser)]
#[command(name = "rigor", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Largest number of terms any intermediate polynomial may have.
    #[arg(long, global = true, default_value_t = rigor::normal::limits::Limits::DEFAULT.max_terms)]
    max_terms: usize,
    /// Deepest nesting of parentheses and calls accepted.
    #[arg(long, global = true, default_value_t = 200)]
    max_depth: usize,
    /// Largest number of decimal digits a power may produce.
    #[arg(long, global = true, default_value_t = rigor::normal::limits::Limits::DEFAULT.max_digits)]
    max_digits: u64,
    /// Wall-clock budget, in seconds, per claim (`check`) or per command (`simplify`, `equiv`);
    /// 0: no budget.
    #[arg(long, global = true, default_value_t = 10.0)]
    timeout: f64,
}

/// Output format of `check`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// Diagnostics like the Rust compiler's.
    Human,
    /// One JSON object per file.
    Json,
    /// GitHub Actions workflow-command annotations.
    Github,
}

/// Output format of `mark`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum MarkFormat {
    /// Lines per submission.
    Human,
    /// The gradebook CSV.
    Csv,
    /// One JSON object per submission.
    Json,
}

#[derive(Subcommand)]
enum Command {
    /// Check derivation files and folders (default: derivations/).
    Check {
        /// Files or folders.
        paths: Vec<std::path::PathBuf>,
        /// Output format.
        #[arg(long, value_enum, default_value_t = Format::Human)]
        format: Format,
        /// Print how every verified link was justified.
        #[arg(long, short)]
        verbose: bool,
        /// Largest file accepted, in bytes.
        #[arg(long, default_value_t = 10_000_000)]
        max_file_size: u64,
    },
    /// Print the normal form of an expression.
    Simplify {
        /// The expression.
        #[arg(allow_hyphen_values = true)]
        expr: String,
        /// A sign assumption, e.g. "R > 0" or "x y >= 0" (repeatable).
        #[arg(long)]
        assume: Vec<String>,
        /// A body, as in a `body` statement: "rod: dm = m/L dy, y from -L/2 to L/2" (repeatable).
        #[arg(long)]
        body: Vec<String>,
        /// Print LaTeX instead of rigor's syntax.
        #[arg(long)]
        latex: bool,
        /// Units of the symbols, as in a `units` statement ("m: kg, L: m"): the expression's
        /// unit is printed too, and an inconsistent one is an error.
        #[arg(long)]
        units: Option<String>,
    },
    /// Decide whether two expressions are equal.
    Equiv {
        /// Left side.
        #[arg(allow_hyphen_values = true)]
        a: String,
        /// Right side.
        #[arg(allow_hyphen_values = true)]
        b: String,
        /// A sign assumption (repeatable).
        #[arg(long)]
        assume: Vec<String>,
        /// A body (repeatable).
        #[arg(long)]
        body: Vec<String>,
        /// Units of the symbols ("m: kg, L: m"): sides in different units are not equal.
        #[arg(long)]
        units: Option<String>,
    },
    /// Write a derivation as a standalone LaTeX worked solution.
    Latex {
        /// The derivation file, or a folder: one book of all its files (in the order of
        /// its `ORDER` file, if it has one).
        file: std::path::PathBuf,
        /// Output file (default: standard output).
        #[arg(short)]
        o: Option<std::path::PathBuf>,
        /// The title of a book (default: "Worked solutions").
        #[arg(long)]
        title: Option<String>,
        /// Fill in the work the file skipped (integrals evaluated, unknowns solved),
        /// from the checker's own computation.
        #[arg(long)]
        steps: bool,
    },
    /// Check the chains of equations inside Markdown (`$$…$$`) and LaTeX documents.
    Lint {
        /// The documents (`.md`, `.tex`).
        #[arg(required = true)]
        docs: Vec<std::path::PathBuf>,
        /// Output format.
        #[arg(long, value_enum, default_value_t = Format::Human)]
        format: Format,
    },
    /// Mark students' derivation files against a reference.
    Mark {
        /// The reference derivation.
        #[arg(long)]
        reference: std::path::PathBuf,
        /// Submissions: files or folders.
        #[arg(required = true)]
        submissions: Vec<std::path::PathBuf>,
        /// Print the class summary table.
        #[arg(long)]
        summary: bool,
        /// Write one Markdown feedback file per submission into this folder.
        #[arg(long)]
        feedback: Option<std::path::PathBuf>,
        /// Show the reference's working in the feedback files.
        #[arg(long)]
        reveal: bool,
        /// Output format.
        #[arg(long, value_enum, default_value_t = MarkFormat::Human)]
        format: MarkFormat,
        /// A folder a submission's `use` may import from (a course library; repeatable).
        /// Without it a submission may import nothing.
        #[arg(long)]
        allow_use: Vec<std::path::PathBuf>,
        /// Time budget of one submission, in seconds: once spent, its remaining steps
        /// are undecided (the row says so), and the rest of the class is unaffected; 0: no
        /// budget.
        #[arg(long, default_value_t = 30.0)]
        budget: f64,
    },
    /// Serve editors: the Language Server Protocol over standard input and output
    /// (diagnostics as you type, hovers, go to definition, the outline, quick fixes).
    Lsp,
    /// Write a derivation as a Markdown worked solution.
    Markdown {
        /// The derivation file, or a folder: one book of all its files (in the order of
        /// its `ORDER` file, if it has one).
        file: std::path::PathBuf,
        /// Output file (default: standard output).
        #[arg(short)]
        o: Option<std::path::PathBuf>,
        /// The title of a book (default: "Worked solutions").
        #[arg(long)]
        title: Option<String>,
        /// Fill in the work the file skipped (integrals evaluated, unknowns solved),
        /// from the checker's own computation.
        #[arg(long)]
        steps: bool,
    },
}

/// What `--steps` asks of a worked solution.
fn detail(steps: bool) -> rigor::render::Detail {
    if steps {
        rigor::render::Detail::Steps
    } else {
        rigor::render::Detail::Written
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    // The size limits of this thread, for the whole command: `simplify`, `equiv` and the
    // worked solutions' steps compute here, and the commands that check files pass them
    // on in their `Options` (`limits::current()`) to the checking threads.
    let _limits = rigor::normal::limits::install(rigor::normal::limits::Limits {
        max_terms: cli.max_terms,
        max_digits: cli.max_digits,
    });
    let opts = rigor::syntax::ParseOptions {
        max_depth: cli.max_depth,
    };
    let timeout = seconds(cli.timeout, 10.0);
    // The work outside `check_source` (`simplify`, `equiv`, the worked solutions' steps)
    // has one budget; `check_source` times each claim with the `Options` it is given.
    let _deadline = rigor::normal::limits::until(
        if matches!(cli.command, Command::Check { .. } | Command::Lsp) {
            None
        } else {
            rigor::clock::Deadline::after(timeout, rigor::clock::system())
        },
    );
    let code = match cli.command {
        Command::Simplify {
            expr,
            assume,
            body,
            latex,
            units,
        } => cli::simplify(&expr, &assume, &body, (latex, units.as_deref()), &opts),
        Command::Equiv {
            a,
            b,
            assume,
            body,
            units,
        } => cli::equiv((&a, &b), &assume, &body, units.as_deref(), &opts),
        Command::Check {
            paths,
            format,
            verbose,
            max_file_size,
        } => cli::check(&paths, format, verbose, timeout, max_file_size, &opts),
        Command::Latex {
            file,
            o,
            title,
            steps,
        } => cli::document(
            &file,
            &cli::DocumentArgs {
                out: o.as_deref(),
                title: title.as_deref(),
                latex: true,
                detail: detail(steps),
            },
            &opts,
        ),
        Command::Markdown {
            file,
            o,
            title,
            steps,
        } => cli::document(
            &file,
            &cli::DocumentArgs {
                out: o.as_deref(),
                title: title.as_deref(),
                latex: false,
                detail: detail(steps),
            },
            &opts,
        ),
        Command::Lsp => match rigor::lsp::run(rigor::Options {
            parse: opts,
            limits: rigor::normal::limits::current(),
            timeout,
            ..rigor::Options::default()
        }) {
            Ok(()) => 0,
            Err(e) => {
                eprintln!("error: rigor lsp: {e}");
                1
            }
        },
        Command::Lint { docs, format } => cli::lint(&docs, format, timeout, &opts),
        Command::Mark {
            reference,
            submissions,
            summary,
            feedback,
            reveal,
            format,
            allow_use,
            budget,
        } => cli::mark(
            (&reference, &submissions),
            &cli::MarkReports {
                summary,
                feedback: feedback.as_deref(),
                reveal,
                allow_use: &allow_use,
            },
            format,
            (timeout, seconds(budget, 30.0)),
            &opts,
        ),
    };
    ExitCode::from(code)
}

/// A duration given in seconds on the command line (`default` when it is not a
/// positive number).
fn seconds(given: f64, default: f64) -> std::time::Duration {
    if given == 0.0 {
        // `--timeout 0`: no budget (a deadline that never passes).
        return std::time::Duration::MAX;
    }
    let s = if given.is_finite() && given > 0.0 {
        given
    } else {
        default
    };
    std::time::Duration::from_secs_f64(s.min(1e6))
}
