//! The algebra kernel: a hash-consed expression DAG and what is done with
//! it. Every distinct node exists once, so a subexpression that appears in
//! M, f and the energies is one node, and common subexpression elimination is
//! a matter of counting uses at emission time.
//!
//! The kernel knows nothing of models or tokens; the pipeline stages above it
//! (`model`, `check`, `derive`, `emit`, `render`) build and read expressions
//! only through [`Pool`]. One file per concern of `Pool`:
//!
//! - [`pool`]: the storage, hash-consing, dependency sets, the work budget;
//! - [`simplify`]: the simplifying constructors, the only way nodes are made,
//!   which keep every node in a canonical form; [`content`] pulls the common
//!   factors out of a sum;
//! - [`diff`]: differentiation, memoized;
//! - [`eval`]: numeric evaluation, for tests and compile-time checks;
//! - [`substitute`]: symbols set to zero (`T` at rest);
//! - [`cse`]: which shared nodes an emitted function binds to `let`s.

pub mod content;
pub mod cse;
pub mod diff;
pub mod eval;
pub mod pool;
pub mod simplify;
pub mod substitute;

pub use pool::{DEFAULT_BUDGET, Exceeded, MAX_DEPTH, Pool};

/// A node of the [`Pool`]. Ids are handed out in creation order, which is
/// deterministic, so ordering by id gives deterministic output.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub struct ExprId(u32);

impl ExprId {
    /// The id as an index into the pool's nodes.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// A symbol: time, a coordinate, a velocity or a parameter. What each id
/// means is the model's business (see [`crate::model::Symbols`]).
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub struct SymId(pub u32);

/// Elementary functions of one argument.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub enum Func {
    /// `sin`.
    Sin,
    /// `cos`.
    Cos,
    /// `tan`.
    Tan,
    /// `asin`.
    Asin,
    /// `acos`.
    Acos,
    /// `atan`.
    Atan,
    /// `sinh`.
    Sinh,
    /// `cosh`.
    Cosh,
    /// `tanh`.
    Tanh,
    /// `exp`.
    Exp,
    /// `ln`, the natural logarithm.
    Ln,
}

impl Func {
    /// The function's name: as a model writes it, as the rendered equations
    /// show it, and the `f64` method generated code calls.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Asin => "asin",
            Func::Acos => "acos",
            Func::Atan => "atan",
            Func::Sinh => "sinh",
            Func::Cosh => "cosh",
            Func::Tanh => "tanh",
            Func::Exp => "exp",
            Func::Ln => "ln",
        }
    }

    /// The function applied to a number.
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Func::Sin => x.sin(),
            Func::Cos => x.cos(),
            Func::Tan => x.tan(),
            Func::Asin => x.asin(),
            Func::Acos => x.acos(),
            Func::Atan => x.atan(),
            Func::Sinh => x.sinh(),
            Func::Cosh => x.cosh(),
            Func::Tanh => x.tanh(),
            Func::Exp => x.exp(),
            Func::Ln => x.ln(),
        }
    }
}

/// One node. `Add` and `Mul` are n-ary with at least two operands in
/// canonical order (see `simplify`); division is `a * b^-1`, subtraction
/// `a + (-1)*b`, `sqrt(x)` is `x^0.5`.
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
pub enum Node {
    /// A finite or non-finite real constant, stored as canonical bits (no -0.0).
    Num(u64),
    /// A symbol: time, a coordinate, a velocity, a parameter, an acceleration or an input.
    Sym(SymId),
    /// A sum of at least two terms.
    Add(Box<[ExprId]>),
    /// A product of at least two factors, a numeric coefficient (if any) first.
    Mul(Box<[ExprId]>),
    /// `base ^ exponent`.
    Pow(ExprId, ExprId),
    /// An elementary function of one argument.
    Func(Func, ExprId),
    /// `atan2(y, x)`.
    Atan2(ExprId, ExprId),
}
