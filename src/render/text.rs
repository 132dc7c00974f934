//! Escaping of user-written text for LaTeX text mode, for Markdown, and for the
//! `\text{…}` and `\tag{…}` of math that Markdown viewers (MathJax, KaTeX) render.

/// The LaTeX (text mode, T1 encoding) of a character outside printable ASCII that
/// we know how to write, or `None`.
fn unicode_latex(c: char) -> Option<&'static str> {
    Some(match c {
        'α' => "\\ensuremath{\\alpha}",
        'β' => "\\ensuremath{\\beta}",
        'γ' => "\\ensuremath{\\gamma}",
        'δ' => "\\ensuremath{\\delta}",
        'ε' => "\\ensuremath{\\varepsilon}",
        'ζ' => "\\ensuremath{\\zeta}",
        'η' => "\\ensuremath{\\eta}",
        'θ' => "\\ensuremath{\\theta}",
        'ι' => "\\ensuremath{\\iota}",
        'κ' => "\\ensuremath{\\kappa}",
        'λ' => "\\ensuremath{\\lambda}",
        'μ' | 'µ' => "\\ensuremath{\\mu}",
        'ν' => "\\ensuremath{\\nu}",
        'ξ' => "\\ensuremath{\\xi}",
        'π' => "\\ensuremath{\\pi}",
        'ρ' => "\\ensuremath{\\rho}",
        'σ' => "\\ensuremath{\\sigma}",
        'τ' => "\\ensuremath{\\tau}",
        'φ' => "\\ensuremath{\\varphi}",
        'χ' => "\\ensuremath{\\chi}",
        'ψ' => "\\ensuremath{\\psi}",
        'ω' => "\\ensuremath{\\omega}",
        'Γ' => "\\ensuremath{\\Gamma}",
        'Δ' => "\\ensuremath{\\Delta}",
        'Θ' => "\\ensuremath{\\Theta}",
        'Λ' => "\\ensuremath{\\Lambda}",
        'Π' => "\\ensuremath{\\Pi}",
        'Σ' => "\\ensuremath{\\Sigma}",
        'Φ' => "\\ensuremath{\\Phi}",
        'Ψ' => "\\ensuremath{\\Psi}",
        'Ω' => "\\ensuremath{\\Omega}",
        '≈' => "\\ensuremath{\\approx}",
        '≤' => "\\ensuremath{\\leq}",
        '≥' => "\\ensuremath{\\geq}",
        '≠' => "\\ensuremath{\\neq}",
        '±' => "\\ensuremath{\\pm}",
        '×' => "\\ensuremath{\\times}",
        '·' => "\\ensuremath{\\cdot}",
        '−' => "\\ensuremath{-}",
        '√' => "\\ensuremath{\\surd}",
        '∫' => "\\ensuremath{\\int}",
        '∞' => "\\ensuremath{\\infty}",
        '→' => "\\ensuremath{\\to}",
        '⇒' => "\\ensuremath{\\Rightarrow}",
        '°' => "\\ensuremath{^\\circ}",
        '²' => "\\textsuperscript{2}",
        '³' => "\\textsuperscript{3}",
        '½' => "\\ensuremath{\\tfrac{1}{2}}",
        '–' => "--",
        '—' => "---",
        '‘' => "`",
        '’' => "'",
        '“' => "``",
        '”' => "''",
        '…' => "\\ldots{}",
        '\u{a0}' => "~",
        '§' => "\\S{}",
        '©' => "\\copyright{}",
        'ß' => "\\ss{}",
        'æ' => "\\ae{}",
        'Æ' => "\\AE{}",
        'ø' => "\\o{}",
        'Ø' => "\\O{}",
        'å' => "\\aa{}",
        'Å' => "\\AA{}",
        'œ' => "\\oe{}",
        'Œ' => "\\OE{}",
        _ => return None,
    })
}

/// The accent command and base letter of an accented Latin letter (`é` → `\'`, `e`).
fn accented(c: char) -> Option<(&'static str, char)> {
    const TABLE: &[(&str, &str, &str)] = &[
        ("\\`", "àèìòùÀÈÌÒÙ", "aeiouAEIOU"),
        ("\\'", "áéíóúýÁÉÍÓÚÝćńśźĆŃŚŹ", "aeiouyAEIOUYcnszCNSZ"),
        ("\\^", "âêîôûÂÊÎÔÛ", "aeiouAEIOU"),
        ("\\\"", "äëïöüÿÄËÏÖÜŸ", "aeiouyAEIOUY"),
        ("\\~", "ãñõÃÑÕ", "anoANO"),
        ("\\c", "çÇşŞ", "cCsS"),
        ("\\v", "čšžřěČŠŽŘĚ", "cszreCSZRE"),
    ];
    for (cmd, from, to) in TABLE {
        if let Some(k) = from.chars().position(|x| x == c) {
            return to.chars().nth(k).map(|b| (*cmd, b));
        }
    }
    None
}

/// User text escaped for LaTeX text mode (inside a paragraph, `\text{…}`, `\tag{…}`
/// or a heading). Special characters become commands, known Unicode characters their
/// LaTeX equivalents, and any other non-ASCII character `?`, so the output always
/// compiles with pdflatex and never opens or closes a group.
pub(crate) fn latex_text(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 8);
    let mut prev = ' ';
    for c in s.chars() {
        match c {
            '"' if prev.is_whitespace() || "([{".contains(prev) => out.push_str("``"),
            '"' => out.push_str("''"),
            '\\' => out.push_str("\\textbackslash{}"),
            '{' => out.push_str("\\{"),
            '}' => out.push_str("\\}"),
            '$' | '&' | '%' | '#' | '_' => {
                out.push('\\');
                out.push(c);
            }
            '~' => out.push_str("\\textasciitilde{}"),
            '^' => out.push_str("\\textasciicircum{}"),
            '\t' | '\n' | '\r' => out.push(' '),
            c if c.is_ascii_control() => {}
            c if c.is_ascii() => out.push(c),
            c => {
                if let Some(t) = unicode_latex(c) {
                    out.push_str(t);
                } else if let Some((cmd, base)) = accented(c) {
                    out.push_str(cmd);
                    out.push('{');
                    out.push(base);
                    out.push('}');
                } else {
                    out.push('?');
                }
            }
        }
        prev = c;
    }
    out
}

/// Lines of preformatted text (a rendered diagnostic) for LaTeX: escaped, in a
/// typewriter font, spaces kept, one `\par` per line.
pub(crate) fn latex_lines(s: &str) -> String {
    let mut out = String::from("{\\small\\ttfamily\\raggedright\n");
    for line in s.lines() {
        out.push_str("\\noindent\\mbox{}");
        // Spaces keep their width (carets stay under what they point at) but a line too
        // long for the page may break after one, or inside a long run without spaces.
        for (k, word) in line.split(' ').enumerate() {
            if k > 0 {
                out.push_str("~\\allowbreak{}");
            }
            let chars: Vec<char> = word.chars().collect();
            for (j, piece) in chars.chunks(40).enumerate() {
                if j > 0 {
                    out.push_str("\\allowbreak{}");
                }
                out.push_str(&latex_text(&piece.iter().collect::<String>()));
            }
        }
        out.push_str("\\par\n");
    }
    out.push_str("}\n");
    out
}

/// User text for inside a Markdown paragraph: characters that Markdown or its math
/// extension would interpret (`\ * _ $ < > [ ] | \``) are backslash-escaped.
pub(crate) fn markdown_inline(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 8);
    for c in s.chars() {
        match c {
            '\\' | '*' | '_' | '$' | '<' | '>' | '[' | ']' | '`' | '|' => {
                out.push('\\');
                out.push(c);
            }
            '\t' | '\n' | '\r' => out.push(' '),
            c if c.is_control() => {}
            c => out.push(c),
        }
    }
    out
}

/// User text that starts a Markdown paragraph or heading: [`markdown_inline`], made
/// [`block_safe`].
pub(crate) fn markdown_text(s: &str) -> String {
    block_safe(markdown_inline(s))
}

/// Escaped Markdown text that cannot start a block: a leading `#`, `-`, `+`, `=`, `~`
/// or `>` gets a backslash, and in `12.` or `12)` the `.` or `)` does.
pub(crate) fn block_safe(mut s: String) -> String {
    if s.starts_with(['#', '-', '+', '=', '~', '>']) {
        s.insert(0, '\\');
    } else {
        let digits = s.len() - s.trim_start_matches(|c: char| c.is_ascii_digit()).len();
        if digits > 0 && s.get(digits..).is_some_and(|r| r.starts_with(['.', ')'])) {
            s.insert(digits, '\\');
        }
    }
    s
}

/// A message that may hold `code spans`, for inside a Markdown paragraph: text outside
/// backticks is escaped as [`markdown_inline`], code spans are kept (when the
/// backticks pair up). Every backtick that does not open or close one of those spans
/// is escaped, and each span is one backtick on each side of text without backticks,
/// so a Markdown renderer pairs them exactly as here: in `` ```<img …>` `` a renderer
/// would see no span (a run of three does not close with one) and keep the tag live.
pub(crate) fn markdown_message(s: &str) -> String {
    if s.matches('`').count() % 2 == 1 {
        return markdown_inline(s);
    }
    let mut out = String::new();
    for (k, piece) in s.split('`').enumerate() {
        if k % 2 == 0 {
            out.push_str(&markdown_inline(piece));
        } else if piece.is_empty() {
            out.push_str("\\`\\`");
        } else {
            out.push('`');
            out.push_str(&piece.replace(['\n', '\r'], " "));
            out.push('`');
        }
    }
    out
}

/// User text for the `\text{…}` or `\tag{…}` of math rendered by MathJax or KaTeX,
/// which show the inside of `\text` literally: braces, `$`, `\` and `%` (a comment
/// in TeX input) are replaced by harmless look-alikes, as are `^` and `_` (an error in
/// KaTeX's text mode), `&` (an alignment tab inside `aligned`), and `<`, `>` and `` ` ``:
/// a Markdown renderer sees the math as text first, and CommonMark keeps `<img …>` in
/// it as live HTML, and a backtick would open a code span across the math (a backslash
/// would not survive to the math renderer).
pub(crate) fn mathjax_text(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '{' => out.push('('),
            '}' => out.push(')'),
            '\\' => out.push('/'),
            '$' => out.push('S'),
            '%' => out.push_str(" percent"),
            '#' => out.push_str("No."),
            '^' => out.push('\u{2c6}'),
            '_' => out.push('\u{2cd}'),
            '&' => out.push_str("and"),
            '`' => out.push('\u{2018}'),
            '<' => out.push('\u{2039}'),
            '>' => out.push('\u{203a}'),
            '\t' | '\n' | '\r' => out.push(' '),
            c if c.is_control() => {}
            c => out.push(c),
        }
    }
    out
}
