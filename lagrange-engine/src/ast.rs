//! The model as written: what `parse` produces and `model` lowers.
//! Every node keeps the spans of its first and last tokens, so an error can
//! underline exactly the user's text.

use proc_macro2::{Span, TokenStream};
use quote::ToTokens;
use syn::{Attribute, Ident, Visibility};

/// A source range: first and last token. `syn::Error::new_spanned` on it
/// underlines the whole range on stable Rust.
#[derive(Clone, Copy, Debug)]
pub struct SpanRange {
    /// The span of the first token.
    pub start: Span,
    /// The span of the last token.
    pub end: Span,
}

impl SpanRange {
    /// The range of one token.
    pub fn single(span: Span) -> Self {
        SpanRange {
            start: span,
            end: span,
        }
    }

    /// From the start of `self` to the end of `other`.
    pub fn to(self, other: SpanRange) -> Self {
        SpanRange {
            start: self.start,
            end: other.end,
        }
    }

    /// An error underlining this range.
    pub fn error(self, message: impl std::fmt::Display) -> syn::Error {
        syn::Error::new_spanned(self, message)
    }
}

impl ToTokens for SpanRange {
    fn to_tokens(&self, tokens: &mut TokenStream) {
        let mut a = proc_macro2::Punct::new('<', proc_macro2::Spacing::Alone);
        a.set_span(self.start);
        let mut b = proc_macro2::Punct::new('>', proc_macro2::Spacing::Alone);
        b.set_span(self.end);
        tokens.extend([
            proc_macro2::TokenTree::Punct(a),
            proc_macro2::TokenTree::Punct(b),
        ]);
    }
}

/// `lagrangian! { #[attrs] vis struct Name { items } }`.
#[derive(Clone)]
pub struct ModelDef {
    /// The user's attributes (docs, derives), passed through to the struct.
    pub attrs: Vec<Attribute>,
    /// Options from `#[lagrange(...)]`, which is consumed, not passed on.
    pub options: Options,
    /// The struct's visibility, given to the generated struct.
    pub vis: Visibility,
    /// The struct's name, the name of the generated model type.
    pub name: Ident,
    /// The sections of the body, in the order written.
    pub items: Vec<Item>,
}

/// What a model asks the macro to generate beyond the defaults.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// `#[lagrange(jacobians)]`: exact Jacobians of the residual
    /// `M q̈ − f` for implicit integrators.
    pub jacobians: bool,
    /// `#[lagrange(budget = N)]`: the engine's work budget for this model,
    /// in steps, instead of [`DEFAULT_BUDGET`](crate::expr::DEFAULT_BUDGET).
    pub budget: Option<u64>,
    /// `#[lagrange(serde)]`: the struct derives serde's `Serialize` and
    /// `Deserialize` (through `lagrange::serde`, the facade's `serde`
    /// feature), its control inputs skipped (read back unset).
    pub serde: bool,
    /// `#[lagrange(parameter_derivatives)]`: `∂M/∂p`, `∂f/∂p` and the
    /// residual's `∂(M q̈ − f)/∂p`, one column per parameter scalar.
    pub parameter_derivatives: bool,
    /// `#[lagrange(regressor(m1, c1, ..))]`: the parameters (fields, an
    /// indexed one with all its scalars) in which `M q̈ − f` is to be
    /// written as `Y(t, q, q̇, q̈) π + (terms free of them)`, `π` their
    /// products that occur, grouped into base parameters.
    pub regressor: Option<Vec<Ident>>,
    /// `#[lagrange(articulated)]`: the masses of `T` must hang on a tree of
    /// increments, at any size, or the model is an error (and `M` and `f`
    /// are formed from the parts at any size, not from
    /// [`FORMED_FROM`](crate::derive::articulated::FORMED_FROM) on);
    /// `#[lagrange(articulated = false)]`: the dense solve, whatever the
    /// model. Neither (`None`): looked for from
    /// [`FROM_COORDINATES`](crate::derive::articulated::FROM_COORDINATES)
    /// coordinates on.
    pub articulated: Option<bool>,
    /// `#[lagrange(max_code = N)]`: the most bytes of generated code this
    /// model may expand to, instead of
    /// [`DEFAULT_MAX_CODE`](crate::emit::DEFAULT_MAX_CODE).
    pub max_code: Option<u64>,
}

/// The largest budget `#[lagrange(budget = N)]` may ask for: the time and
/// memory of an expansion grow in proportion to the budget, and node ids
/// must stay 32-bit.
pub const MAX_BUDGET: u64 = 4_000_000_000;

/// A declared name, scalar or indexed: `x` or `theta[N]`.
#[derive(Clone)]
pub struct Decl {
    /// The declared name.
    pub name: Ident,
    /// The length expression of `name[len]`, evaluated against the `const`s.
    pub len: Option<Expr>,
    /// A parameter's domain (`m > 0`, `e in [0, 1]`), for every element
    /// of an indexed one.
    pub domain: Option<Domain>,
}

/// The values a parameter may take: an interval whose ends are each open
/// or closed, infinite where there is no bound (then open). Its ends are
/// number literals, the lower below the upper (checked by the parser).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Domain {
    /// The lower end, `-∞` where there is none.
    pub lower: f64,
    /// Whether the lower end is inside (`>=`, `[`).
    pub lower_closed: bool,
    /// The upper end, `+∞` where there is none.
    pub upper: f64,
    /// Whether the upper end is inside (`<=`, `]`).
    pub upper_closed: bool,
}

impl Domain {
    /// The domain as the language writes it, after the name: `> 0`,
    /// `in [0, 1]`.
    pub fn written(&self) -> String {
        match (self.lower.is_finite(), self.upper.is_finite()) {
            (true, false) => format!(
                "{} {}",
                if self.lower_closed { ">=" } else { ">" },
                self.lower
            ),
            (false, true) => format!(
                "{} {}",
                if self.upper_closed { "<=" } else { "<" },
                self.upper
            ),
            _ => format!(
                "in {}{}, {}{}",
                if self.lower_closed { '[' } else { '(' },
                self.lower,
                self.upper,
                if self.upper_closed { ']' } else { ')' }
            ),
        }
    }
}

/// `var in lo..hi` or `var in lo..=hi`.
#[derive(Clone, Debug)]
pub struct IndexRange {
    /// The index variable.
    pub var: Ident,
    /// The first index.
    pub lo: Box<Expr>,
    /// The bound of the range: the last index if `inclusive`, else one past it.
    pub hi: Box<Expr>,
    /// Whether the range is `lo..=hi` rather than `lo..hi`.
    pub inclusive: bool,
    /// The tokens of the whole range, for errors.
    pub range: SpanRange,
}

/// One section of a model's body, as written.
#[derive(Clone)]
pub enum Item {
    /// `const N = 6;`: a compile-time integer, for sizes and indices.
    Const {
        /// The constant's name.
        name: Ident,
        /// Its value, an integer expression.
        value: Expr,
    },
    /// `coordinates: a, b, theta[N];`: the generalized coordinates, in the order of `q`.
    Coordinates {
        /// The `coordinates` keyword, for errors.
        keyword: Ident,
        /// The declared coordinates.
        names: Vec<Decl>,
    },
    /// `parameters: m, l[N];`: runtime parameters, fields of the struct and arguments of `new`.
    Parameters {
        /// The `parameters` keyword, for errors.
        keyword: Ident,
        /// The declared parameters.
        names: Vec<Decl>,
    },
    /// `inputs: force, tau[N];`: control inputs, declared like parameters
    /// but set during a run (by a controller) rather than at construction.
    Inputs {
        /// The `inputs` keyword, for errors.
        keyword: Ident,
        /// The declared inputs.
        names: Vec<Decl>,
    },
    /// `constants: g = 9.81;`: values folded into the generated code.
    Constants {
        /// The `constants` keyword, for errors.
        keyword: Ident,
        /// Each constant's name and value.
        entries: Vec<(Ident, Expr)>,
    },
    /// `let x = expr;` or `let x[i in 0..N] = expr;`: an intermediate quantity.
    Let {
        /// The name of the `let`.
        name: Ident,
        /// `let x[i in 0..N] = ...`
        index: Option<IndexRange>,
        /// Its defining expression (in terms of the index variable, if indexed).
        value: Expr,
    },
    /// `kinetic: expr;`: (a term of) the kinetic energy T.
    Kinetic {
        /// The `kinetic` keyword, for errors.
        keyword: Ident,
        /// The energy expression.
        value: Expr,
    },
    /// `potential: expr;`: (a term of) the potential energy V.
    Potential {
        /// The `potential` keyword, for errors.
        keyword: Ident,
        /// The energy expression.
        value: Expr,
    },
    /// `dissipation: expr;`: (a term of) the Rayleigh dissipation function R.
    Dissipation {
        /// The `dissipation` keyword, for errors.
        keyword: Ident,
        /// The dissipation expression.
        value: Expr,
    },
    /// Targets are names (`x`) or elements (`x[N-1]`): a coordinate or a
    /// `let` position.
    Forces {
        /// The `forces` keyword, for errors.
        keyword: Ident,
        /// Each force's target and its value: `target = value`.
        entries: Vec<(Expr, Expr)>,
    },
    /// `constraints: rod: x^2 + y^2 = l^2, link[i in 0..N]: ...;`.
    Constraints {
        /// The `constraints` keyword, for errors.
        keyword: Ident,
        /// The constraints, in the order written.
        entries: Vec<ConstraintDef>,
    },
    /// `contacts: floor: y >= 0 { restitution: e }, ...;`.
    Contacts {
        /// The `contacts` keyword, for errors.
        keyword: Ident,
        /// The contacts, in the order written.
        entries: Vec<ContactDef>,
    },
}

/// One entry of `contacts:`: `name: lhs >= rhs` (the gap `lhs − rhs`) or
/// `name: lhs <= rhs` (the gap `rhs − lhs`), then optionally its law in
/// braces, `{ restitution: e, friction: mu, slip: dot(x) }`.
#[derive(Clone)]
pub struct ContactDef {
    /// The contact's name.
    pub name: Ident,
    /// The left-hand side.
    pub lhs: Expr,
    /// `>=` (`true`) or `<=` (`false`).
    pub at_least: bool,
    /// The right-hand side.
    pub rhs: Expr,
    /// Whether the entry has a gap; without one (`name: { normal: F, .. }`,
    /// friction against a given normal force) both sides are the number 0
    /// at the name.
    pub has_gap: bool,
    /// The law's entries, `key: value`, in the order written.
    pub fields: Vec<(Ident, Expr)>,
}

impl ContactDef {
    /// From the name to the end of the inequality.
    pub fn range(&self) -> SpanRange {
        SpanRange::single(self.name.span()).to(self.rhs.range())
    }
}

/// One entry of `constraints:`: `name: lhs` (meaning `lhs = 0`) or
/// `name: lhs = rhs`, or an indexed family `name[i in a..b]: ...`, one
/// constraint per index.
#[derive(Clone)]
pub struct ConstraintDef {
    /// The constraint's name (the family's name, for an indexed entry).
    pub name: Ident,
    /// The index range of an indexed family, `name[i in a..b]`.
    pub index: Option<IndexRange>,
    /// The left-hand side, or the whole constraint `lhs = 0`.
    pub lhs: Expr,
    /// The right-hand side, if written as `lhs = rhs`.
    pub rhs: Option<Expr>,
}

impl ConstraintDef {
    /// From the name to the end of the last expression.
    pub fn range(&self) -> SpanRange {
        let end = self.rhs.as_ref().unwrap_or(&self.lhs).range();
        SpanRange::single(self.name.span()).to(end)
    }
}

/// An operator of a [`Expr::Chain`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    /// `+`.
    Add,
    /// `-`.
    Sub,
    /// `*`.
    Mul,
    /// `/`.
    Div,
}

/// An expression as written, before lowering into the expression DAG.
#[derive(Clone, Debug)]
pub enum Expr {
    /// A number literal.
    Num {
        /// Its value.
        value: f64,
        /// The literal's span.
        span: Span,
    },
    /// A name: a coordinate, parameter, input, constant, `const`, `let`, index variable or `t`.
    Name(Ident),
    /// `-inner`.
    Neg {
        /// From the `-` to the end of `inner`.
        range: SpanRange,
        /// The negated operand.
        inner: Box<Expr>,
    },
    /// `a + b - c` or `a * b / c`: operands combined left to right, as
    /// `((a + b) - c)`. Kept flat, so that a sum of many terms nests no
    /// deeper than its terms. `rest` is not empty; its operators are all
    /// additive or all multiplicative.
    Chain {
        /// The first operand.
        first: Box<Expr>,
        /// The other operands, each with the operator before it.
        rest: Vec<(BinOp, Expr)>,
        /// The tokens of the whole chain.
        range: SpanRange,
    },
    /// `base ^ exponent`.
    Power {
        /// The base.
        base: Box<Expr>,
        /// The exponent.
        exponent: Box<Expr>,
        /// The tokens of the whole power.
        range: SpanRange,
    },
    /// `f(a, b)` and the method form `a.f(b)` alike; `dot(e)` too.
    Call {
        /// The function's name (`sin`, `sqrt`, `dot`, ...).
        func: Ident,
        /// The tokens of the whole call.
        range: SpanRange,
        /// The arguments; in the method form, the receiver first.
        args: Vec<Expr>,
    },
    /// `x[i - 1]`: an element of an indexed coordinate, parameter or `let`.
    Index {
        /// The indexed name.
        base: Ident,
        /// The index, an integer expression.
        index: Box<Expr>,
        /// The tokens of the whole element.
        range: SpanRange,
    },
    /// `sum(j in a..b, body)`, unrolled at compile time.
    Sum {
        /// The index variable and its range.
        index: IndexRange,
        /// The summand, in terms of the index variable.
        body: Box<Expr>,
        /// The tokens of the whole sum.
        range: SpanRange,
    },
}

impl Expr {
    /// The tokens the expression was parsed from, for errors.
    pub fn range(&self) -> SpanRange {
        match self {
            Expr::Num { span, .. } => SpanRange::single(*span),
            Expr::Name(id) => SpanRange::single(id.span()),
            Expr::Neg { range, .. }
            | Expr::Chain { range, .. }
            | Expr::Power { range, .. }
            | Expr::Call { range, .. }
            | Expr::Index { range, .. }
            | Expr::Sum { range, .. } => *range,
        }
    }

    /// Direct real-valued subexpressions, left to right (an index is an
    /// integer, not one of them; a sum's body is, under its index; a
    /// chain's are all its operands).
    pub fn children(&self) -> Vec<&Expr> {
        match self {
            Expr::Num { .. } | Expr::Name(_) | Expr::Index { .. } => Vec::new(),
            Expr::Sum { body, .. } => vec![body],
            Expr::Neg { inner, .. } => vec![inner],
            Expr::Chain { first, rest, .. } => std::iter::once(&**first)
                .chain(rest.iter().map(|(_, x)| x))
                .collect(),
            Expr::Power { base, exponent, .. } => vec![base, exponent],
            Expr::Call { args, .. } => args.iter().collect(),
        }
    }

    /// `self + other` (or `self - other`...), flat: appended to `self` if it
    /// is a chain of the same kind.
    pub fn then(self, op: BinOp, other: Expr) -> Expr {
        let additive = |op: BinOp| matches!(op, BinOp::Add | BinOp::Sub);
        match self {
            Expr::Chain {
                first,
                mut rest,
                range,
            } if additive(rest[0].0) == additive(op) => {
                let range = range.to(other.range());
                rest.push((op, other));
                Expr::Chain { first, rest, range }
            }
            lhs => Expr::Chain {
                range: lhs.range().to(other.range()),
                first: Box::new(lhs),
                rest: vec![(op, other)],
            },
        }
    }
}
