//! The worked solution as Markdown (`rigor markdown`): headings, prose with `$…$`
//! math, displayed formulas in `$$…$$` blocks (claims as `aligned`), and failures
//! as block quotes. The math is the same LaTeX as in [`super::latex`]; text inside
//! `\text{…}` and `\tag{…}` is made safe for MathJax and KaTeX.

use super::solution::{build_with, Block, Inline, Problem};
use super::steps::Work;
use super::text::{block_safe, markdown_inline, markdown_message, markdown_text, mathjax_text};
use super::Detail;
use crate::check::report::FileReport;

/// The worked solution of a checked file as Markdown.
///
/// Links that did not verify carry their verdict (`\textbf{[does not hold]}`,
/// `[not verified]`, `[not checked]`), and after the claim each diagnostic follows as
/// `> **does not hold** (line N): message`; in the closing "Results", only a verified
/// result is boxed.
pub fn document(report: &FileReport) -> String {
    document_with(report, Detail::Written)
}

/// [`document`], with the work the file skipped filled in when `detail` is
/// [`Detail::Steps`]: each filled-in piece is a block quote headed *Working*, after the
/// statement it belongs to.
pub fn document_with(report: &FileReport, detail: Detail) -> String {
    let solution = build_with(report, detail);
    let mut out = format!("# {}\n", inlines(&super::solution::rich(&solution.title)));
    for block in &solution.blocks {
        out.push('\n');
        block_markdown(block, false, &mut out);
    }
    out
}

/// The worked solution as a section of another document (`rigor mark`'s feedback):
/// no title, every heading one level further down.
pub fn section(report: &FileReport) -> String {
    let solution = build_with(report, Detail::Written);
    let mut out = String::new();
    for block in &solution.blocks {
        if !out.is_empty() {
            out.push('\n');
        }
        block_markdown(block, true, &mut out);
    }
    out
}

/// Several checked files as one document: the title, a numbered list of contents, and
/// one numbered section per file (`## 3. Title`), equations numbered by section (`3.2`)
/// and a `use` of another file of the book a reference to its section and equations.
pub fn book(reports: &[FileReport], title: &str) -> String {
    book_with(reports, title, Detail::Written)
}

/// [`book`], with the work the files skipped filled in when `detail` is
/// [`Detail::Steps`].
pub fn book_with(reports: &[FileReport], title: &str, detail: Detail) -> String {
    let files = super::solution::book_numbers(reports);
    let solutions: Vec<_> = reports
        .iter()
        .enumerate()
        .map(|(k, r)| {
            let place = super::solution::Place {
                section: k + 1,
                files: &files,
            };
            super::solution::build_in(r, &place, detail)
        })
        .collect();
    let mut out = format!("# {}\n\n", inlines(&super::solution::rich(title)));
    for (k, s) in solutions.iter().enumerate() {
        out.push_str(&format!(
            "{}. {}\n",
            k + 1,
            inlines(&super::solution::rich(&s.title))
        ));
    }
    for (k, s) in solutions.iter().enumerate() {
        out.push_str(&format!(
            "\n## {}. {}\n",
            k + 1,
            inlines(&super::solution::rich(&s.title))
        ));
        for block in &s.blocks {
            out.push('\n');
            block_markdown(block, true, &mut out);
        }
    }
    out
}

/// Inline parts in a Markdown line.
fn inlines(parts: &[Inline]) -> String {
    let mut line = String::new();
    for part in parts {
        match part {
            Inline::Text(t) if line.is_empty() => line.push_str(&markdown_text(t)),
            Inline::Text(t) => line.push_str(&markdown_inline(t)),
            Inline::Strong(t) => line.push_str(&format!("**{}**", markdown_inline(t))),
            Inline::Code(t) => line.push_str(&code(t)),
            Inline::Math(m) => line.push_str(&format!("${m}$")),
        }
    }
    line
}

/// One block; in a book (`in_book`) each file is a section, so headings go one down.
fn block_markdown(block: &Block, in_book: bool, out: &mut String) {
    match block {
        Block::Heading(level, t) => {
            let level = (*level + usize::from(in_book)).clamp(2 + usize::from(in_book), 6);
            out.push_str(&format!(
                "{} {}\n",
                "#".repeat(level),
                inlines(&super::solution::rich(t))
            ));
        }
        Block::Paragraph(parts) => {
            let mut line = String::new();
            for part in parts {
                match part {
                    Inline::Text(t) if line.is_empty() => line.push_str(&markdown_text(t)),
                    Inline::Text(t) => line.push_str(&markdown_inline(t)),
                    Inline::Strong(t) => line.push_str(&format!("**{}**", markdown_inline(t))),
                    Inline::Code(t) => line.push_str(&code(t)),
                    Inline::Math(m) => line.push_str(&format!("${m}$")),
                }
            }
            out.push_str(&line);
            out.push('\n');
        }
        Block::Display { prefix, .. } => {
            if let Some(p) = prefix {
                out.push_str(&format!("*{}*\n\n", markdown_inline(p)));
            }
            out.push_str(&format!(
                "$$\n{}\n$$\n",
                display_latex(block, false).unwrap_or_default()
            ));
        }
        Block::Claim { .. } => {
            out.push_str(&format!(
                "$$\n{}\n$$\n",
                display_latex(block, false).unwrap_or_default()
            ));
        }
        Block::Problems(problems) => {
            for (k, p) in problems.iter().enumerate() {
                if k > 0 {
                    out.push('\n');
                }
                problem_markdown(p, out);
            }
        }
        Block::Listing(listing) => {
            out.push_str("```text\n");
            for l in listing {
                out.push_str(&l.replace("```", "'''"));
                if !l.ends_with('\n') {
                    out.push('\n');
                }
            }
            out.push_str("```\n");
        }
        Block::Working(work) => {
            for (k, w) in work.iter().enumerate() {
                let head = if k == 0 { "*Working.* " } else { "" };
                if k > 0 {
                    out.push_str(">\n");
                }
                out.push_str(&format!("> {head}{}\n", block_safe(inlines(&w.lead))));
                if let Some(math) = work_latex(w) {
                    out.push_str(">\n> $$\n");
                    for line in math.lines() {
                        out.push_str(&format!("> {line}\n"));
                    }
                    out.push_str("> $$\n");
                }
            }
        }
    }
}

/// The lines of a piece of filled-in work as an `aligned` environment (`None` without
/// lines); text inside is safe for MathJax and KaTeX.
pub(crate) fn work_latex(w: &Work) -> Option<String> {
    if w.lines.is_empty() {
        return None;
    }
    let mut out = String::from("\\begin{aligned}\n");
    out.push_str(&w.rows(mathjax_text));
    out.push_str("\\end{aligned}");
    Some(out)
}

/// The LaTeX of a displayed formula or claim (what goes between `$$` and `$$`), with
/// its note and equation number; text inside is safe for MathJax and KaTeX. The number
/// is a `\tag` with `tags` (KaTeX in the playground sets it at the margin), otherwise
/// `\qquad (n)` after the formula, which every Markdown renderer draws (GitHub's does
/// not number with `\tag`). `None` for other blocks.
pub(crate) fn display_latex(block: &Block, tags: bool) -> Option<String> {
    let number = |t: &str| {
        if tags {
            format!(" \\tag{{{}}}", mathjax_text(t))
        } else {
            format!(" \\qquad\\text{{({})}}", mathjax_text(t))
        }
    };
    let mut out = String::new();
    match block {
        Block::Display {
            math, note, tag, ..
        } => {
            out.push_str(math);
            if let Some(n) = note {
                out.push_str(&format!(" \\qquad\\text{{({})}}", mathjax_text(n)));
            }
            if let Some(t) = tag {
                out.push_str(&number(t));
            }
        }
        Block::Claim { rows, tag } => {
            out.push_str("\\begin{aligned}\n");
            for (k, row) in rows.iter().enumerate() {
                super::solution::row_math(mathjax_text, false, row, &mut out);
                if k + 1 < rows.len() {
                    out.push_str(" \\\\");
                }
                out.push('\n');
            }
            out.push_str("\\end{aligned}");
            if let Some(t) = tag {
                out.push_str(&number(t));
            }
        }
        _ => return None,
    }
    Some(out)
}

/// `` `text` ``, with a fence longer than any run of backticks inside.
fn code(t: &str) -> String {
    let t = t.replace(['\n', '\r'], " ");
    let mut longest = 0;
    let mut run = 0;
    for c in t.chars() {
        run = if c == '`' { run + 1 } else { 0 };
        longest = longest.max(run);
    }
    let fence = "`".repeat(longest + 1);
    let pad = if t.starts_with('`') || t.ends_with('`') {
        " "
    } else {
        ""
    };
    format!("{fence}{pad}{t}{pad}{fence}")
}

/// `> **not verified** (line N): message`, notes on further quoted lines.
fn problem_markdown(p: &Problem, out: &mut String) {
    out.push_str(&format!("> **{}**", p.kind.words()));
    if let Some(line) = p.line {
        out.push_str(&format!(" (line {line})"));
    }
    out.push_str(&format!(": {}\n", markdown_message(&p.message)));
    for n in &p.notes {
        let note = block_safe(inlines(&super::solution::note_inlines(n)));
        out.push_str(&format!(">\n> {note}\n"));
    }
}
