//! Displays read once per process: `rigor lint` checks a note's derivation again and
//! again (with a value, with a relation left out), and every check reads the same
//! displays. Each text is read at offset 0 and its spans moved to where it is given;
//! only the spans depend on the offset.

use super::super::ast::{Chain, Expr, ExprKind, Span};
use super::super::error::{ParseOptions, SyntaxError};

/// `read_chain(text)` at offset 0, remembered by text and nesting limit, with its spans (or
/// its error's span) moved `base` bytes on.
pub(super) fn remembered(
    text: &str,
    base: usize,
    opts: &ParseOptions,
    read_chain: fn(&str, &ParseOptions) -> Result<Chain, SyntaxError>,
) -> Result<Chain, SyntaxError> {
    type Memo = std::collections::HashMap<(String, usize), Result<Chain, SyntaxError>>;
    static MEMO: std::sync::Mutex<Option<Memo>> = std::sync::Mutex::new(None);
    const KEEP: usize = 4096;
    let lock = || MEMO.lock().unwrap_or_else(|e| e.into_inner());
    let key = (text.to_string(), opts.max_depth);
    let known = lock().as_ref().and_then(|m| m.get(&key).cloned());
    let read = known.unwrap_or_else(|| {
        let read = read_chain(text, opts);
        let mut memo = lock();
        let memo = memo.get_or_insert_with(Memo::new);
        if memo.len() >= KEEP {
            memo.clear();
        }
        memo.insert(key, read.clone());
        read
    });
    match read {
        Ok(mut chain) => {
            shift_expr(&mut chain.first, base);
            for l in &mut chain.links {
                l.span = shift(l.span, base);
                shift_expr(&mut l.rhs, base);
            }
            Ok(chain)
        }
        Err(mut e) => {
            e.span = shift(e.span, base);
            Err(e)
        }
    }
}

fn shift(s: Span, by: usize) -> Span {
    Span::new(s.start + by, s.end + by)
}

/// `e` with every span moved `by` bytes on.
fn shift_expr(e: &mut Expr, by: usize) {
    e.span = shift(e.span, by);
    match &mut e.kind {
        ExprKind::Num(_) | ExprKind::Sym(_) | ExprKind::Pi => {}
        ExprKind::Neg(a) => shift_expr(a, by),
        ExprKind::Bin(_, a, b) => {
            shift_expr(a, by);
            shift_expr(b, by);
        }
        ExprKind::Call(_, args) => args.iter_mut().for_each(|a| shift_expr(a, by)),
    }
}
