//! Atoms, the indeterminates of the normal form, interned process-wide.
//!
//! An atom is a symbol, `pi`, or a function of a normal form (`sqrt`, `sin`, …).
//! Interning gives every distinct atom one [`AtomId`]; since the arguments are
//! themselves canonical, equal atoms get equal ids.

use super::poly::Poly;
use super::rat::Rat;
use foldhash::HashMap;
use std::cmp::Ordering;
use std::sync::{Arc, LazyLock, OnceLock, RwLock};

/// The interned id of an atom. Ids order monomials inside one process only;
/// printers order by [`cmp_atoms`], which depends on content alone.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct AtomId(u32);

impl AtomId {
    /// The largest id (a bound for packing, never interned).
    pub const MAX: AtomId = AtomId(u32::MAX);

    /// The id as a number (the order atoms were interned in).
    pub fn index(self) -> u32 {
        self.0
    }

    /// The id numbered `i`: for the packed monomials, which store ids as numbers, and
    /// for tests of polynomial arithmetic, whose atoms need no meaning. An id not
    /// interned names no atom (`atom::get` of it reads as the symbol `?`).
    pub fn from_index(i: u32) -> AtomId {
        AtomId(i)
    }
}

/// An indeterminate of the normal form.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Atom {
    /// A symbol (`m`, `I_G`, `x''`).
    Sym(String),
    /// π.
    Pi,
    /// `sqrt(p)`, with `p` a polynomial holding no square factor rigor could see. Reduction: `s² = p`.
    Sqrt(Poly),
    /// The principal `n`-th root of `p`, `n ≥ 3`. Reduction: `rⁿ = p`.
    Root(Poly, u32),
    /// `abs(p)`, `p` of unknown sign, primitive with positive leading coefficient. Reduction: `A² = p²`.
    Abs(Poly),
    /// `sin(u)`.
    Sin(Rat),
    /// `cos(u)`. Reduction: `c² = 1 − sin(u)²`.
    Cos(Rat),
    /// `exp(u)`; products of exponentials merge into one.
    Exp(Rat),
    /// `ln(u)`.
    Ln(Rat),
    /// `b^e` with a symbolic exponent and a base of unknown sign.
    Pow(Rat, Rat),
    /// A sum kept as one factor so that its large powers are not expanded
    /// (`power::keep`): its value is `p`, a primitive polynomial of
    /// two or more terms with a positive leading coefficient and no monomial factor.
    Factor(Poly),
    /// `∫ x₁^e₁ ⋯ xₙ^eₙ dm` over the abstract body named: every coordinate with its exponent.
    Moment(String, Vec<(String, u32)>),
    /// A `time` symbol or one of its derivatives (`x'`) at an instant: `subs(x', t, T)`,
    /// written x′(T). The instant is never the bare time variable `t` (that is `x'` itself).
    At(String, Rat),
}

/// What reduction rule, if any, an atom carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rule {
    /// No rule: an independent indeterminate.
    Free,
    /// `a^n = value`: powers at or above `n` reduce.
    Power(u32),
    /// An exponential: products merge.
    Exp,
}

struct Entry {
    atom: Arc<Atom>,
    rule: Rule,
    depth: u32,
}

/// The ids of the atoms interned so far; the lock also serialises interning.
#[derive(Default)]
struct Table {
    map: HashMap<Arc<Atom>, AtomId>,
    len: u32,
}

static TABLE: LazyLock<RwLock<Table>> = LazyLock::new(|| RwLock::new(Table::default()));

/// The entries by id, read without a lock (lookups by id are the hot path of every
/// computation, on every thread at once). Entries are written once, while interning
/// holds the table's write lock, and never change or move: segment `k` holds the
/// `SEGMENT << k` ids from `SEGMENT·(2^k − 1)` on, allocated when its first id is.
static ENTRIES: [OnceLock<Box<[OnceLock<Entry>]>>; SEGMENTS] =
    [const { OnceLock::new() }; SEGMENTS];

/// Ids in the first segment.
const SEGMENT: usize = 64;
/// Segments: enough for every `u32` id.
const SEGMENTS: usize = 27;

/// The segment and the place in it of `id`.
fn slot(id: AtomId) -> (usize, usize) {
    let id = id.0 as usize;
    let j = id / SEGMENT + 1;
    let k = (usize::BITS - 1 - j.leading_zeros()) as usize;
    (k, id - SEGMENT * ((1 << k) - 1))
}

/// The entry of `id`, if it was interned.
fn entry(id: AtomId) -> Option<&'static Entry> {
    let (k, i) = slot(id);
    ENTRIES.get(k)?.get()?.get(i)?.get()
}

fn rule_of(a: &Atom) -> Rule {
    match a {
        Atom::Sqrt(_) | Atom::Abs(_) | Atom::Cos(_) => Rule::Power(2),
        Atom::Root(_, n) => Rule::Power(*n),
        Atom::Exp(_) => Rule::Exp,
        _ => Rule::Free,
    }
}

fn depth_of(a: &Atom) -> u32 {
    let of_poly = |p: &Poly| {
        p.atoms()
            .iter()
            .filter_map(|id| entry(*id).map(|e| e.depth))
            .max()
            .unwrap_or(0)
    };
    let of_rat = |r: &Rat| of_poly(r.num()).max(of_poly(r.den()));
    1 + match a {
        Atom::Sym(_) | Atom::Pi | Atom::Moment(..) => 0,
        Atom::Sqrt(p) | Atom::Root(p, _) | Atom::Abs(p) | Atom::Factor(p) => of_poly(p),
        Atom::Sin(u) | Atom::Cos(u) | Atom::Exp(u) | Atom::Ln(u) => of_rat(u),
        Atom::Pow(b, e) => of_rat(b).max(of_rat(e)),
        Atom::At(_, u) => of_rat(u),
    }
}

/// The id of `a`, interning it if new.
pub fn intern(a: Atom) -> AtomId {
    {
        let t = TABLE.read().unwrap_or_else(|e| e.into_inner());
        if let Some(id) = t.map.get(&a) {
            return *id;
        }
    }
    let mut t = TABLE.write().unwrap_or_else(|e| e.into_inner());
    if let Some(id) = t.map.get(&a) {
        return *id;
    }
    let id = AtomId(t.len);
    let depth = depth_of(&a);
    let rule = rule_of(&a);
    let atom = Arc::new(a);
    // Every `u32` id has a slot (memory runs out long before the ids do).
    let (k, i) = slot(id);
    if let Some(segment) = ENTRIES.get(k) {
        let segment = segment.get_or_init(|| (0..SEGMENT << k).map(|_| OnceLock::new()).collect());
        if let Some(e) = segment.get(i) {
            let _ = e.set(Entry {
                atom: atom.clone(),
                rule,
                depth,
            });
        }
    }
    t.map.insert(atom, id);
    t.len += 1;
    id
}

/// The symbol named `name`.
pub fn sym(name: &str) -> AtomId {
    // Symbols are looked up by name over and over (every evaluation point names its
    // symbols). Ids never change, so each thread remembers the ones it has seen and
    // leaves the shared table's lock, and a copy of the name, to the first lookup.
    thread_local! {
        static SEEN: std::cell::RefCell<HashMap<String, AtomId>> = Default::default();
    }
    SEEN.with(|seen| {
        if let Some(id) = seen.borrow().get(name) {
            return *id;
        }
        let id = intern(Atom::Sym(name.to_string()));
        seen.borrow_mut().insert(name.to_string(), id);
        id
    })
}

/// The `time` symbol (or derivative) `name` at the instant `u`: `x'` itself when `u` is
/// the time variable `t`.
pub fn at(name: &str, u: &Rat) -> AtomId {
    if u.num().len() == 1 && u.den().is_one() {
        if let [(m, q)] = u.num().terms() {
            if num_traits::One::is_one(q) && m.pairs() == [(sym("t"), 1)] {
                return sym(name);
            }
        }
    }
    intern(Atom::At(name.to_string(), u.clone()))
}

/// The atom with id `id`, lent for the whole process (entries never change or move).
/// Ids only come from [`intern`], so the lookup cannot fail; an unknown id (a bug) reads
/// as the symbol `?`.
pub fn get(id: AtomId) -> &'static Atom {
    static UNKNOWN: LazyLock<Atom> = LazyLock::new(|| Atom::Sym("?".into()));
    entry(id).map_or(&*UNKNOWN, |e| &*e.atom)
}

/// The reduction rule of each atom in `ids`.
pub fn rules(ids: &[AtomId]) -> Vec<Rule> {
    ids.iter()
        .map(|id| entry(*id).map_or(Rule::Free, |e| e.rule))
        .collect()
}

/// The nesting depth of an atom (symbols 1).
pub fn depth(id: AtomId) -> u32 {
    entry(id).map_or(0, |e| e.depth)
}

/// The symbol's name, if `id` is a symbol.
pub fn sym_name(id: AtomId) -> Option<String> {
    sym_str(id).map(str::to_string)
}

/// The symbol's name, if `id` is a symbol, without a copy.
pub fn sym_str(id: AtomId) -> Option<&'static str> {
    match entry(id).map(|e| &*e.atom) {
        Some(Atom::Sym(s)) => Some(s),
        _ => None,
    }
}

/// Whether `id` is π.
pub fn is_pi(id: AtomId) -> bool {
    matches!(entry(id).map(|e| &*e.atom), Some(Atom::Pi))
}

fn kind_rank(a: &Atom) -> u8 {
    match a {
        Atom::Sym(_) => 0,
        Atom::Moment(..) => 1,
        Atom::Pi => 2,
        Atom::Pow(..) => 3,
        Atom::Sqrt(_) => 4,
        Atom::Root(..) => 5,
        Atom::Abs(_) => 6,
        Atom::Sin(_) => 7,
        Atom::Cos(_) => 8,
        Atom::Exp(_) => 9,
        Atom::Ln(_) => 10,
        Atom::At(..) => 11,
        Atom::Factor(_) => 12,
    }
}

/// A total order of atoms by content alone, the same in every run: printers use it.
pub fn cmp_atoms(a: AtomId, b: AtomId) -> Ordering {
    if a == b {
        return Ordering::Equal;
    }
    let (x, y) = (get(a), get(b));
    kind_rank(x).cmp(&kind_rank(y)).then_with(|| match (x, y) {
        (Atom::Sym(p), Atom::Sym(q)) => caseless(p, q).then_with(|| p.cmp(q)),
        (Atom::Moment(b1, e1), Atom::Moment(b2, e2)) => b1.cmp(b2).then_with(|| e1.cmp(e2)),
        _ => {
            let (p, q) = (super::print::atom_plain(x), super::print::atom_plain(y));
            p.len().cmp(&q.len()).then_with(|| p.cmp(&q))
        }
    })
}

/// `p.to_lowercase().cmp(&q.to_lowercase())`, without building the two strings when both
/// names are ASCII (nearly every name; sorting atoms compares names often).
fn caseless(p: &str, q: &str) -> Ordering {
    if p.is_ascii() && q.is_ascii() {
        p.bytes()
            .map(|b| b.to_ascii_lowercase())
            .cmp(q.bytes().map(|b| b.to_ascii_lowercase()))
    } else {
        p.to_lowercase().cmp(&q.to_lowercase())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_symbol_has_one_id_however_it_is_looked_up() {
        let names = ["sym_test_a", "sym_test_b", "sym_test_a'"];
        let first: Vec<AtomId> = names.iter().map(|n| sym(n)).collect();
        for (n, id) in names.iter().zip(&first) {
            assert_eq!(sym(n), *id, "{n} again");
            assert_eq!(intern(Atom::Sym(n.to_string())), *id, "{n} interned");
            assert_eq!(sym_str(*id), Some(*n));
        }
        assert!(first[0] != first[1] && first[0] != first[2]);
    }

    #[test]
    fn names_compare_as_their_lower_case_forms() {
        // ASCII names take the short path; Greek ones (a final capital sigma lowers to ς,
        // not σ, in a whole string) the long one. Both must agree with lower-casing.
        let names = [
            "a", "A", "ab", "aB", "Ab", "a_1", "A_1", "a1", "Z", "z", "_", "theta", "Theta", "x_G",
            "x_g", "", "ΣF", "Σ", "AΣ", "aσ", "aς", "ω", "Ω", "é", "E",
        ];
        for p in names {
            for q in names {
                assert_eq!(
                    caseless(p, q),
                    p.to_lowercase().cmp(&q.to_lowercase()),
                    "{p:?} against {q:?}"
                );
            }
        }
    }

    #[test]
    fn slots_number_every_id_once_in_order() {
        let mut next = (0, 0);
        for id in 0..100_000u32 {
            let (k, i) = slot(AtomId(id));
            assert!(i < SEGMENT << k, "{id}");
            if (k, i) != next {
                assert_eq!((k, i, next.1), (next.0 + 1, 0, SEGMENT << next.0), "{id}");
            }
            next = (k, i + 1);
        }
        assert!(slot(AtomId::MAX).0 < SEGMENTS);
    }

    #[test]
    fn interned_atoms_read_back_from_every_thread() {
        let ids: Vec<AtomId> = (0..300).map(|k| sym(&format!("slot_test_{k}"))).collect();
        std::thread::scope(|s| {
            for _ in 0..2 {
                s.spawn(|| {
                    for (k, id) in ids.iter().enumerate() {
                        assert_eq!(sym_name(*id), Some(format!("slot_test_{k}")));
                        assert_eq!(depth(*id), 1);
                    }
                });
            }
        });
    }
}
