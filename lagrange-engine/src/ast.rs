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
    pub start: Span,
    pub end: Span,
}

impl SpanRange {
    pub fn single(span: Span) -> Self {
        SpanRange {
            start: span,
            end: span,
        }
    }

    pub fn to(self, other: SpanRange) -> Self {
        SpanRange {
            start: self.start,
            end: other.end,
        }
    }

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
pub struct ModelDef {
    /// The user's attributes (docs, derives), passed through to the struct.
    pub attrs: Vec<Attribute>,
    /// Options from `#[lagrange(...)]`, which is consumed, not passed on.
    pub options: Options,
    pub vis: Visibility,
    pub name: Ident,
    pub items: Vec<Item>,
}

/// What a model asks the macro to generate beyond the defaults.
#[derive(Clone, Copy, Debug, Default)]
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
}

/// The largest budget `#[lagrange(budget = N)]` may ask for: the time and
/// memory of an expansion grow in proportion to the budget, and node ids
/// must stay 32-bit.
pub const MAX_BUDGET: u64 = 4_000_000_000;

/// A declared name, scalar or indexed: `x` or `theta[N]`.
pub struct Decl {
    pub name: Ident,
    /// The length expression of `name[len]`, evaluated against the `const`s.
    pub len: Option<Expr>,
}

/// `var in lo..hi` or `var in lo..=hi`.
#[derive(Clone, Debug)]
pub struct IndexRange {
    pub var: Ident,
    pub lo: Box<Expr>,
    pub hi: Box<Expr>,
    pub inclusive: bool,
    pub range: SpanRange,
}

pub enum Item {
    /// `const N = 6;`: a compile-time integer, for sizes and indices.
    Const {
        name: Ident,
        value: Expr,
    },
    Coordinates {
        keyword: Ident,
        names: Vec<Decl>,
    },
    Parameters {
        keyword: Ident,
        names: Vec<Decl>,
    },
    /// `inputs: force, tau[N];`: control inputs, declared like parameters
    /// but set during a run (by a controller) rather than at construction.
    Inputs {
        keyword: Ident,
        names: Vec<Decl>,
    },
    /// `constants: g = 9.81;`: values folded into the generated code.
    Constants {
        keyword: Ident,
        entries: Vec<(Ident, Expr)>,
    },
    Let {
        name: Ident,
        /// `let x[i in 0..N] = ...`
        index: Option<IndexRange>,
        value: Expr,
    },
    Kinetic {
        keyword: Ident,
        value: Expr,
    },
    Potential {
        keyword: Ident,
        value: Expr,
    },
    Dissipation {
        keyword: Ident,
        value: Expr,
    },
    /// Targets are names (`x`) or elements (`x[N-1]`): a coordinate or a
    /// `let` position.
    Forces {
        keyword: Ident,
        entries: Vec<(Expr, Expr)>,
    },
    /// `constraints: rod: x^2 + y^2 = l^2, link[i in 0..N]: ...;`.
    Constraints {
        keyword: Ident,
        entries: Vec<ConstraintDef>,
    },
}

/// One entry of `constraints:`: `name: lhs` (meaning `lhs = 0`) or
/// `name: lhs = rhs`, or an indexed family `name[i in a..b]: ...`, one
/// constraint per index.
pub struct ConstraintDef {
    pub name: Ident,
    pub index: Option<IndexRange>,
    pub lhs: Expr,
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
    Add,
    Sub,
    Mul,
    Div,
}

#[derive(Clone, Debug)]
pub enum Expr {
    Num {
        value: f64,
        span: Span,
    },
    Name(Ident),
    Neg {
        range: SpanRange,
        inner: Box<Expr>,
    },
    /// `a + b - c` or `a * b / c`: operands combined left to right, as
    /// `((a + b) - c)`. Kept flat, so that a sum of many terms nests no
    /// deeper than its terms. `rest` is not empty; its operators are all
    /// additive or all multiplicative.
    Chain {
        first: Box<Expr>,
        rest: Vec<(BinOp, Expr)>,
        range: SpanRange,
    },
    /// `base ^ exponent`.
    Power {
        base: Box<Expr>,
        exponent: Box<Expr>,
        range: SpanRange,
    },
    /// `f(a, b)` and the method form `a.f(b)` alike; `dot(e)` too.
    Call {
        func: Ident,
        range: SpanRange,
        args: Vec<Expr>,
    },
    /// `x[i - 1]`: an element of an indexed coordinate, parameter or `let`.
    Index {
        base: Ident,
        index: Box<Expr>,
        range: SpanRange,
    },
    /// `sum(j in a..b, body)`, unrolled at compile time.
    Sum {
        index: IndexRange,
        body: Box<Expr>,
        range: SpanRange,
    },
}

impl Expr {
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
