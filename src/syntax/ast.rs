//! The syntax tree of expressions and derivation files, every node with its source span.

use num_rational::BigRational;
use std::fmt;

/// A byte range `start..end` into the source text the node was parsed from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default, PartialOrd, Ord)]
pub struct Span {
    /// First byte of the node.
    pub start: usize,
    /// One past the last byte of the node.
    pub end: usize,
}

impl Span {
    /// The span `start..end`.
    pub fn new(start: usize, end: usize) -> Span {
        Span { start, end }
    }

    /// The smallest span covering both.
    pub fn to(self, other: Span) -> Span {
        Span::new(self.start.min(other.start), self.end.max(other.end))
    }
}

/// A built-in function of the expression language (FORMAT.md §1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Func {
    /// `sqrt(a)`, also `√(a)`.
    Sqrt,
    /// `sin(a)`.
    Sin,
    /// `cos(a)`.
    Cos,
    /// `tan(a)`.
    Tan,
    /// `exp(a)`.
    Exp,
    /// `ln(a)`.
    Ln,
    /// `abs(a)`.
    Abs,
    /// `int(f, x, a, b)`, `int(f, x)`, `int(f, B)`, `int(f, dm)`.
    Int,
    /// `diff(f, x)`, `diff(f, x, n)`.
    Diff,
    /// `eval(F, x, a, b)`.
    Eval,
    /// `subs(f, x, v)`.
    Subs,
}

impl Func {
    /// The function's name as written.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sqrt => "sqrt",
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Exp => "exp",
            Func::Ln => "ln",
            Func::Abs => "abs",
            Func::Int => "int",
            Func::Diff => "diff",
            Func::Eval => "eval",
            Func::Subs => "subs",
        }
    }

    /// The function called `name`, if there is one.
    pub fn from_name(name: &str) -> Option<Func> {
        Some(match name {
            "sqrt" => Func::Sqrt,
            "sin" => Func::Sin,
            "cos" => Func::Cos,
            "tan" => Func::Tan,
            "exp" => Func::Exp,
            "ln" => Func::Ln,
            "abs" => Func::Abs,
            "int" => Func::Int,
            "diff" => Func::Diff,
            "eval" => Func::Eval,
            "subs" => Func::Subs,
            _ => return None,
        })
    }
}

/// A binary arithmetic operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`, `·`, `×` or juxtaposition.
    Mul,
    /// `/`
    Div,
    /// `^` (also `²`, `³`).
    Pow,
}

/// An expression node.
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    /// What the node is.
    pub kind: ExprKind,
    /// Where it was written.
    pub span: Span,
    /// How LaTeX notation gave the node, where the checker's reading of it depends on
    /// the declarations (rigor's own syntax always gives [`Reading::AsWritten`]).
    pub reading: Reading,
}

/// Where a node read from LaTeX came from, when that matters to its meaning.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Reading {
    /// The node means what its kind says.
    #[default]
    AsWritten,
    /// `exp(x)` read from `e^{x}`: a power of the symbol `e` when `e` is declared.
    EulerE,
    /// `diff(f, x)` read from Leibniz notation (`\frac{d}{dx}(…)`): the writer means a
    /// quantity that varies with `x`, so an operand that, as declared, does not vary
    /// with `x` is refused rather than differentiated to zero.
    Leibniz,
}

/// The kinds of expression node.
#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    /// An exact number: `12`, `0.71` (= 71/100), `1.5e-3`.
    Num(BigRational),
    /// A symbol. The name is ASCII: Greek letters written in Unicode are stored
    /// by their names (`β` → `beta`), and time-derivative primes are kept at the
    /// end of the name (`x''`).
    Sym(String),
    /// The constant π (`pi` or `π`).
    Pi,
    /// Unary minus.
    Neg(Box<Expr>),
    /// A binary operation.
    Bin(BinOp, Box<Expr>, Box<Expr>),
    /// A call of a built-in function, arguments in order as written.
    Call(Func, Vec<Expr>),
}

impl Expr {
    /// A node.
    pub fn new(kind: ExprKind, span: Span) -> Expr {
        Expr {
            kind,
            span,
            reading: Reading::AsWritten,
        }
    }

    /// The node, marked as read from LaTeX notation in the way `reading` says.
    pub fn read_as(mut self, reading: Reading) -> Expr {
        self.reading = reading;
        self
    }

    /// Whether this node or any node below it satisfies `f`.
    pub fn any(&self, f: &dyn Fn(&Expr) -> bool) -> bool {
        f(self)
            || match &self.kind {
                ExprKind::Num(_) | ExprKind::Sym(_) | ExprKind::Pi => false,
                ExprKind::Neg(a) => a.any(f),
                ExprKind::Bin(_, a, b) => a.any(f) || b.any(f),
                ExprKind::Call(_, args) => args.iter().any(|a| a.any(f)),
            }
    }
}

/// A relation operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RelOp {
    /// `=`
    Eq,
    /// `!=`
    Ne,
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
    /// `~=`: approximately equal (FORMAT.md §3).
    Approx,
}

impl RelOp {
    /// The operator as written.
    pub fn as_str(self) -> &'static str {
        match self {
            RelOp::Eq => "=",
            RelOp::Ne => "!=",
            RelOp::Lt => "<",
            RelOp::Le => "<=",
            RelOp::Gt => ">",
            RelOp::Ge => ">=",
            RelOp::Approx => "~=",
        }
    }
}

impl fmt::Display for RelOp {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A label in square brackets, `[Fx]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Label {
    /// The name between the brackets.
    pub name: String,
    /// The span of the whole `[…]`.
    pub span: Span,
}

/// The justification written after `by`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum By {
    /// `by [Fx], [MG]`: the link may use only these facts.
    Labels(Vec<Label>),
    /// `by some words`: rendered in worked solutions, no effect on checking.
    Text(String),
}

/// One link of a chain: `= expr by …`.
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    /// The relation between the previous expression and this one.
    pub op: RelOp,
    /// The right-hand side.
    pub rhs: Expr,
    /// The justification, if any.
    pub by: Option<(By, Span)>,
    /// `by [eom], [shm] comparing coefficients of theta`: the `time` symbol whose
    /// coefficients the cited facts are compared in (`by` then holds the labels).
    pub compare: Option<Name>,
    /// The span from the operator to the end of the link.
    pub span: Span,
}

/// `lhs op rhs op rhs …`: a relation or a chain of them.
#[derive(Clone, Debug, PartialEq)]
pub struct Chain {
    /// The first expression.
    pub first: Expr,
    /// The links, at least one.
    pub links: Vec<Link>,
}

impl Chain {
    /// Its expressions in order: the first, then each link's right side.
    pub fn exprs(&self) -> impl Iterator<Item = &Expr> {
        std::iter::once(&self.first).chain(self.links.iter().map(|l| &l.rhs))
    }
}

/// The sign declared for symbols in a `symbols` statement.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SignDecl {
    /// No sign: any real.
    Any,
    /// `> 0`
    Positive,
    /// `>= 0`
    Nonnegative,
    /// `!= 0`
    Nonzero,
}

/// A name with its span.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Name {
    /// The name (ASCII, Greek letters spelt out).
    pub name: String,
    /// Where it was written.
    pub span: Span,
}

/// `x from a to b` in a body's region.
#[derive(Clone, Debug, PartialEq)]
pub struct Range {
    /// The coordinate.
    pub var: Name,
    /// Lower bound.
    pub from: Expr,
    /// Upper bound.
    pub to: Expr,
}

/// The definition of a body.
#[derive(Clone, Debug, PartialEq)]
pub enum BodyDef {
    /// `dm = <expr>, x from a to b, …` (outermost coordinate first).
    Concrete {
        /// The mass element, including the differentials (`m/L dy`).
        dm: Expr,
        /// The region, outermost coordinate first.
        ranges: Vec<Range>,
    },
    /// `mass m, coordinates x y, centred`.
    Abstract {
        /// The total mass.
        mass: Expr,
        /// The coordinates.
        coords: Vec<Name>,
        /// Whether the origin is the centre of mass.
        centred: bool,
    },
}

/// `with d = L/2` of a `use`, or one substitution of `where`.
#[derive(Clone, Debug, PartialEq)]
pub struct Assign {
    /// The symbol replaced.
    pub name: Name,
    /// Its replacement.
    pub value: Expr,
}

/// A unit expression of a `units` statement: kept as written (dimensions are a separate issue).
#[derive(Clone, Debug, PartialEq)]
pub struct UnitDecl {
    /// The symbol.
    pub name: Name,
    /// The unit text as written, e.g. `m/s^2`.
    pub unit: String,
    /// Where the unit was written.
    pub unit_span: Span,
}

/// A statement of a derivation file.
#[derive(Clone, Debug, PartialEq)]
pub enum StmtKind {
    /// `symbols m L g > 0`
    Symbols {
        /// The symbols declared.
        names: Vec<Name>,
        /// Their sign.
        sign: SignDecl,
    },
    /// `time x theta`
    Time {
        /// The time-dependent symbols.
        names: Vec<Name>,
    },
    /// `unknowns F N`
    Unknowns {
        /// The unknowns.
        names: Vec<Name>,
    },
    /// `symbols 0 < beta < pi/2`: symbols in an interval.
    Range {
        /// The symbols declared.
        names: Vec<Name>,
        /// The lower bound.
        lo: Expr,
        /// Whether the lower bound is excluded (`<`) rather than included (`<=`).
        lo_strict: bool,
        /// The upper bound.
        hi: Expr,
        /// Whether the upper bound is excluded.
        hi_strict: bool,
    },
    /// `small theta` or `small theta to order 2`.
    Small {
        /// The small quantities.
        names: Vec<Name>,
        /// The order kept (1 unless `to order n`).
        order: u32,
    },
    /// `result [xdd], [N]`: the derivation's results.
    Result {
        /// The labels named.
        labels: Vec<Label>,
    },
    /// `units m: kg, L: m`
    Units {
        /// The declarations.
        decls: Vec<UnitDecl>,
    },
    /// `body rod: …`
    Body {
        /// The body's name.
        name: Name,
        /// Its definition.
        def: BodyDef,
    },
    /// `let I_G = …`
    Let {
        /// The name defined.
        name: Name,
        /// Its value.
        value: Expr,
    },
    /// `given [label] chain`
    Given {
        /// The optional label.
        label: Option<Label>,
        /// The fact (usually a single equation).
        chain: Chain,
    },
    /// `constraint [label] chain`
    Constraint {
        /// The optional label.
        label: Option<Label>,
        /// The constraint.
        chain: Chain,
    },
    /// `claim [label] chain … where …`
    Claim {
        /// The optional label.
        label: Option<Label>,
        /// The chain to check.
        chain: Chain,
        /// Substitutions of `where`.
        where_: Vec<Assign>,
    },
    /// `use [IO] from "rod.deriv" with d = L/2`
    Use {
        /// The labels imported.
        labels: Vec<Label>,
        /// The path as written (relative to the importing file).
        path: String,
        /// Where the path was written.
        path_span: Span,
        /// Instantiations.
        with: Vec<Assign>,
    },
}

/// A statement with its span (the whole statement, continuation lines included).
#[derive(Clone, Debug, PartialEq)]
pub struct Stmt {
    /// The statement.
    pub kind: StmtKind,
    /// Where it was written.
    pub span: Span,
}

/// A piece of prose: plain text or `$…$` math.
#[derive(Clone, Debug, PartialEq)]
pub enum ProsePart {
    /// Text, as written.
    Text(String),
    /// `$…$`, parsed as an expression or relation chain.
    Math(Chain),
    /// `$…$` that holds a lone expression rather than a relation.
    MathExpr(Expr),
}

/// One item of a derivation file, in order.
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    /// `# Title` (level 1) or `## Section` (level 2), `### …` (level 3).
    Heading {
        /// Number of `#`.
        level: usize,
        /// The text.
        text: String,
        /// Where it was written.
        span: Span,
    },
    /// A `>` line (consecutive `>` lines are separate items; renderers join them).
    Prose {
        /// The parts of the line.
        parts: Vec<ProsePart>,
        /// Where it was written.
        span: Span,
    },
    /// A statement.
    Stmt(Stmt),
}

/// A parsed derivation file.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct File {
    /// Headings, prose and statements in order. Comments and blank lines are dropped.
    pub items: Vec<Item>,
}
