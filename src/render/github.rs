//! `rigor check --format github`: GitHub Actions workflow commands, which show each
//! diagnostic as an annotation on the pull request.

use crate::check::report::FileReport;
use crate::diag::{Diagnostic, LineIndex, Severity};

/// One workflow command per diagnostic, each on its own line:
/// `::error file=PATH,line=L,col=C,endLine=L2,endColumn=C2,title=CODE::MESSAGE`
/// (`::warning` for warnings, `::notice` for notes). The message is followed by the
/// words under the caret (the hint) and the diagnostic's notes (both sides, the
/// counterexample) on further lines. Escaping follows GitHub's rules: in the
/// message `%`, `\r`, `\n` become `%25`, `%0D`, `%0A`; in properties also `:` and `,`
/// become `%3A` and `%2C`.
pub fn report(r: &FileReport) -> String {
    let idx = LineIndex::new(&r.source);
    r.diagnostics
        .iter()
        .map(|d| command_in(&r.path, &idx, d))
        .collect()
}

/// One workflow command for a diagnostic of the file `path` with text `source`.
pub fn command_for(path: &str, source: &str, d: &Diagnostic) -> String {
    command_in(path, &LineIndex::new(source), d)
}

/// One workflow command for a diagnostic of the file `path`, its text indexed (for many
/// diagnostics of one file).
pub fn command_in(path: &str, idx: &LineIndex<'_>, d: &Diagnostic) -> String {
    let kind = match d.severity {
        Severity::Error => "error",
        Severity::Warning => "warning",
        Severity::Note => "notice",
    };
    let mut props = vec![format!("file={}", escape_property(path))];
    if let Some((span, _)) = &d.primary {
        let (line, col) = idx.line_col(span.start);
        let (end_line, end_col) = idx.line_col(span.end.max(span.start));
        props.push(format!("line={line}"));
        props.push(format!("col={col}"));
        props.push(format!("endLine={end_line}"));
        props.push(format!("endColumn={end_col}"));
    }
    props.push(format!("title={}", escape_property(d.code.as_str())));
    let mut message = d.message.to_string();
    // The words under the caret are the hint ("the left side is 2 × the right side",
    // "a sign error?"): an annotation has no caret, so they follow the headline.
    if let Some((_, label)) = &d.primary {
        if !label.is_empty() {
            message.push('\n');
            message.push_str(label);
        }
    }
    for n in &d.notes {
        message.push('\n');
        message.push_str(&n.to_string());
    }
    format!("::{kind} {}::{}\n", props.join(","), escape_data(&message))
}

/// A message: `%` → `%25`, `\r` → `%0D`, `\n` → `%0A`.
pub fn escape_data(s: &str) -> String {
    s.replace('%', "%25")
        .replace('\r', "%0D")
        .replace('\n', "%0A")
}

/// A property value: as [`escape_data`], and `:` → `%3A`, `,` → `%2C`.
pub fn escape_property(s: &str) -> String {
    escape_data(s).replace(':', "%3A").replace(',', "%2C")
}
