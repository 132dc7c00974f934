//! A standalone LaTeX worked solution (`rigor latex`) that compiles with pdflatex.
//!
//! The preamble uses only packages of a minimal TeX installation (`amsmath`,
//! `amssymb`, `geometry`, `inputenc`). The font encoding stays the default OT1 —
//! T1 would need the Latin Modern or cm-super fonts — so `<`, `>` and `|` in text
//! are written as `\textless` and friends. Every user-written text is escaped and
//! every formula comes from [`super::expr`], so any input gives a document that
//! compiles.

use super::solution::{build_with, Block, Inline, Problem};
use super::steps::Work;
use super::text::{latex_lines, latex_text};
use super::Detail;
use crate::check::report::FileReport;

const PREAMBLE: &str = "\\documentclass[11pt]{article}
\\usepackage[utf8]{inputenc}
\\usepackage{amsmath}
\\usepackage{amssymb}
\\usepackage[margin=2.5cm]{geometry}
\\setlength{\\parindent}{0pt}
\\setlength{\\parskip}{0.6em}
";

/// The worked solution of a checked file as a standalone LaTeX document.
///
/// Claims are `align*` environments, one link per line with its justification;
/// links that did not verify carry their verdict in bold (`[does not hold]`, `[not
/// verified]`, `[not checked]`) and the checker's message follows the claim; in the
/// closing "Results", only a verified result is boxed. A file that could not be read
/// gives a short document listing its diagnostics.
pub fn document(report: &FileReport) -> String {
    document_with(report, Detail::Written)
}

/// [`document`], with the work the file skipped filled in when `detail` is
/// [`Detail::Steps`]: each filled-in piece is a quotation headed *Working*, after the
/// statement it belongs to.
pub fn document_with(report: &FileReport, detail: Detail) -> String {
    let solution = build_with(report, detail);
    let mut out = String::from(PREAMBLE);
    out.push_str(&format!(
        "\\title{{{}}}\n\\author{{}}\n\\date{{}}\n\\begin{{document}}\n\\maketitle\n",
        inlines(&super::solution::rich(&solution.title))
    ));
    for block in &solution.blocks {
        out.push('\n');
        block_latex(block, false, &mut out);
    }
    out.push_str("\n\\end{document}\n");
    out
}

/// Several checked files as one book: a title page, a table of contents, and one
/// numbered section per file in the order given. Equations are numbered by section
/// (`3.2`), and a `use` of another file of the book refers to its section and
/// equations.
pub fn book(reports: &[FileReport], title: &str) -> String {
    book_with(reports, title, Detail::Written)
}

/// [`book`], with the work the files skipped filled in when `detail` is
/// [`Detail::Steps`].
pub fn book_with(reports: &[FileReport], title: &str, detail: Detail) -> String {
    let files = super::solution::book_numbers(reports);
    let mut out = String::from(PREAMBLE);
    out.push_str(&format!(
        "\\title{{{}}}\n\\author{{}}\n\\date{{}}\n\\begin{{document}}\n\\maketitle\n\\thispagestyle{{empty}}\n\\tableofcontents\n\\clearpage\n",
        inlines(&super::solution::rich(title))
    ));
    for (k, report) in reports.iter().enumerate() {
        let place = super::solution::Place {
            section: k + 1,
            files: &files,
        };
        let solution = super::solution::build_in(report, &place, detail);
        let heading = inlines(&super::solution::rich(&solution.title));
        out.push_str(&format!("\n\\section{{{heading}}}\n"));
        for block in &solution.blocks {
            out.push('\n');
            block_latex(block, true, &mut out);
        }
    }
    out.push_str("\n\\end{document}\n");
    out
}

/// Escaped text, with `<`, `>` and `|` spelled out for the OT1 encoding.
fn text(s: &str) -> String {
    latex_text(s)
        // Two apostrophes would be a closing quote: keep them apart (`theta''`).
        .replace("''", "'{}'")
        .replace('<', "\\textless{}")
        .replace('>', "\\textgreater{}")
        .replace('|', "\\textbar{}")
}

/// Inline parts in running LaTeX text.
fn inlines(parts: &[Inline]) -> String {
    let mut out = String::new();
    for part in parts {
        match part {
            Inline::Text(t) => out.push_str(&text(t)),
            Inline::Strong(t) => out.push_str(&format!("\\textbf{{{}}}", text(t))),
            Inline::Code(t) => out.push_str(&format!("\\texttt{{{}}}", text(t))),
            Inline::Math(m) => out.push_str(&format!("${m}$")),
        }
    }
    out
}

/// One block; in a book (`in_book`) each file is a section, so headings go one down.
fn block_latex(block: &Block, in_book: bool, out: &mut String) {
    match block {
        Block::Heading(level, t) => {
            let cmd = match level + usize::from(in_book) {
                0..=2 => "section",
                3 => "subsection",
                4 => "subsubsection",
                _ => "paragraph",
            };
            out.push_str(&format!(
                "\\{cmd}*{{{}}}\n",
                inlines(&super::solution::rich(t))
            ));
        }
        Block::Paragraph(parts) => {
            for part in parts {
                match part {
                    Inline::Text(t) => out.push_str(&text(t)),
                    Inline::Strong(t) => out.push_str(&format!("\\textbf{{{}}}", text(t))),
                    Inline::Code(t) => out.push_str(&format!("\\texttt{{{}}}", text(t))),
                    Inline::Math(m) => out.push_str(&format!("${m}$")),
                }
            }
            out.push_str("\n\\par\n");
        }
        Block::Display {
            prefix,
            math,
            note,
            tag,
        } => {
            if let Some(p) = prefix {
                out.push_str(&format!("\\textit{{{}}}\n", text(p)));
            }
            out.push_str("\\begin{equation*}\n");
            out.push_str(math);
            if let Some(n) = note {
                out.push_str(&format!(" \\qquad\\text{{({})}}", text(n)));
            }
            if let Some(t) = tag {
                out.push_str(&format!(" \\tag{{{}}}", text(t)));
            }
            out.push_str("\n\\end{equation*}\n");
        }
        Block::Claim { rows, tag } => {
            out.push_str("\\begin{align*}\n");
            for (k, row) in rows.iter().enumerate() {
                super::solution::row_math(text, row, out);
                if k == 0 {
                    if let Some(t) = tag {
                        out.push_str(&format!(" \\tag{{{}}}", text(t)));
                    }
                }
                if k + 1 < rows.len() {
                    out.push_str(" \\\\");
                }
                out.push('\n');
            }
            out.push_str("\\end{align*}\n");
        }
        Block::Problems(problems) => {
            out.push_str("\\begin{quote}\\small\n");
            for p in problems {
                problem_latex(p, out);
            }
            out.push_str("\\end{quote}\n");
        }
        Block::Listing(listing) => {
            for l in listing {
                out.push_str(&latex_lines(l));
                out.push_str("\\medskip\n");
            }
        }
        Block::Working(work) => working_latex(work, out),
    }
}

/// Filled-in work: a quotation headed *Working*, each piece a sentence and an
/// `align*` of its lines.
fn working_latex(work: &[Work], out: &mut String) {
    out.push_str("\\begin{quote}\n\\textit{Working.}\n");
    for (k, w) in work.iter().enumerate() {
        if k > 0 {
            out.push_str("\\par\n");
        }
        out.push_str(&inlines(&w.lead));
        out.push('\n');
        if w.lines.is_empty() {
            continue;
        }
        out.push_str("\\begin{align*}\n");
        out.push_str(&w.rows(text));
        out.push_str("\\end{align*}\n");
    }
    out.push_str("\\end{quote}\n");
}

fn problem_latex(p: &Problem, out: &mut String) {
    let mut head = capitalise(p.kind.words());
    if let Some(line) = p.line {
        head.push_str(&format!(" (line {line})"));
    }
    out.push_str(&format!(
        "\\textbf{{{}:}} {}\\par\n",
        text(&head),
        text(&p.message)
    ));
    for n in &p.notes {
        let note = inlines(&super::solution::note_inlines(n));
        out.push_str(&format!("\\hspace*{{1em}}{note}\\par\n"));
    }
}

/// `not verified` → `Not verified`.
fn capitalise(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_uppercase().chain(c).collect(),
        None => String::new(),
    }
}
