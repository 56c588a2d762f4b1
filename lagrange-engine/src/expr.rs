//! The expression DAG: every distinct node exists once (hash-consing), so a
//! subexpression that appears in M, f and the energies is one node, and common
//! subexpression elimination is a matter of counting uses at emission time.
//!
//! Nodes are only ever built through the simplifying constructors in
//! [`simplify`](crate::simplify), which keep them in a canonical form; this
//! module holds the storage, the symbol-dependency sets and numeric evaluation.

use std::collections::HashMap;

/// A node of the [`Pool`]. Ids are handed out in creation order, which is
/// deterministic, so ordering by id gives deterministic output.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub struct ExprId(u32);

impl ExprId {
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
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sinh,
    Cosh,
    Tanh,
    Exp,
    Ln,
}

impl Func {
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
    Sym(SymId),
    Add(Box<[ExprId]>),
    Mul(Box<[ExprId]>),
    Pow(ExprId, ExprId),
    Func(Func, ExprId),
    /// `atan2(y, x)`.
    Atan2(ExprId, ExprId),
}

/// Raised when a derivation grows past the pool's node budget.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BudgetExceeded {
    pub budget: usize,
}

/// The arena. Cheap ids, one copy of each node, a dependency set per node.
pub struct Pool {
    nodes: Vec<Node>,
    deps: Vec<Box<[u64]>>,
    index: HashMap<Node, ExprId>,
    pub(crate) diff_memo: HashMap<(ExprId, SymId), ExprId>,
    pub(crate) content_memo: HashMap<ExprId, Option<(f64, Vec<ExprId>, ExprId)>>,
    budget: usize,
    exceeded: bool,
}

/// The default node budget: far above what any textbook model needs (the
/// 20-link chain uses a small fraction of it), low enough that a runaway
/// derivation stops in well under a minute and a few hundred MB.
pub const DEFAULT_NODE_BUDGET: usize = 2_000_000;

impl Default for Pool {
    fn default() -> Self {
        Self::with_budget(DEFAULT_NODE_BUDGET)
    }
}

impl Pool {
    pub fn with_budget(budget: usize) -> Self {
        let mut pool = Pool {
            nodes: Vec::new(),
            deps: Vec::new(),
            index: HashMap::new(),
            diff_memo: HashMap::new(),
            content_memo: HashMap::new(),
            budget,
            exceeded: false,
        };
        // Ids 0 and 1 are always zero and one.
        pool.intern(Node::Num(0f64.to_bits()));
        pool.intern(Node::Num(1f64.to_bits()));
        pool
    }

    pub const ZERO: ExprId = ExprId(0);
    pub const ONE: ExprId = ExprId(1);

    pub fn node(&self, id: ExprId) -> &Node {
        &self.nodes[id.index()]
    }

    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// `Err` once the pool has grown past its budget; the model stops there.
    pub fn check_budget(&self) -> Result<(), BudgetExceeded> {
        if self.exceeded {
            Err(BudgetExceeded {
                budget: self.budget,
            })
        } else {
            Ok(())
        }
    }

    /// The node's id if it already exists (never creates one).
    pub(crate) fn lookup(&self, node: &Node) -> Option<ExprId> {
        self.index.get(node).copied()
    }

    pub(crate) fn intern(&mut self, node: Node) -> ExprId {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        if self.nodes.len() >= self.budget {
            // Past the budget every new node collapses to zero: the result is
            // garbage, but bounded, and `check_budget` reports it.
            self.exceeded = true;
            return Pool::ZERO;
        }
        let deps = self.deps_of(&node);
        let id = ExprId(self.nodes.len() as u32);
        self.nodes.push(node.clone());
        self.deps.push(deps);
        self.index.insert(node, id);
        id
    }

    fn deps_of(&self, node: &Node) -> Box<[u64]> {
        let mut bits: Vec<u64> = Vec::new();
        let mut union = |other: &[u64]| {
            if bits.len() < other.len() {
                bits.resize(other.len(), 0);
            }
            for (b, o) in bits.iter_mut().zip(other) {
                *b |= o;
            }
        };
        match node {
            Node::Num(_) => {}
            Node::Sym(s) => {
                let word = s.0 as usize / 64;
                let mut own = vec![0u64; word + 1];
                own[word] |= 1 << (s.0 % 64);
                union(&own);
            }
            Node::Add(xs) | Node::Mul(xs) => {
                for x in xs.iter() {
                    union(&self.deps[x.index()]);
                }
            }
            Node::Pow(a, b) | Node::Atan2(a, b) => {
                union(&self.deps[a.index()]);
                union(&self.deps[b.index()]);
            }
            Node::Func(_, a) => union(&self.deps[a.index()]),
        }
        bits.into_boxed_slice()
    }

    /// Whether `id` depends on symbol `s` (structurally).
    pub fn depends_on(&self, id: ExprId, s: SymId) -> bool {
        let word = s.0 as usize / 64;
        self.deps[id.index()]
            .get(word)
            .is_some_and(|w| w & (1 << (s.0 % 64)) != 0)
    }

    /// The constant value of a `Num` node.
    pub fn as_num(&self, id: ExprId) -> Option<f64> {
        match self.nodes[id.index()] {
            Node::Num(bits) => Some(f64::from_bits(bits)),
            _ => None,
        }
    }

    /// Evaluates `id` with `values[s]` for each symbol `s`. Used by tests and
    /// by compile-time checks; emitted code never calls it.
    pub fn eval(&self, id: ExprId, values: &[f64]) -> f64 {
        let mut memo: HashMap<ExprId, f64> = HashMap::new();
        self.eval_memo(id, values, &mut memo)
    }

    pub fn eval_memo(&self, id: ExprId, values: &[f64], memo: &mut HashMap<ExprId, f64>) -> f64 {
        if let Some(&v) = memo.get(&id) {
            return v;
        }
        let v = match &self.nodes[id.index()] {
            Node::Num(bits) => f64::from_bits(*bits),
            Node::Sym(s) => values[s.0 as usize],
            Node::Add(xs) => xs.iter().map(|&x| self.eval_memo(x, values, memo)).sum(),
            Node::Mul(xs) => xs
                .iter()
                .map(|&x| self.eval_memo(x, values, memo))
                .product(),
            Node::Pow(a, b) => {
                let base = self.eval_memo(*a, values, memo);
                let exp = self.eval_memo(*b, values, memo);
                if exp.fract() == 0.0 && exp.abs() < 1e9 {
                    base.powi(exp as i32)
                } else {
                    base.powf(exp)
                }
            }
            Node::Func(f, a) => f.apply(self.eval_memo(*a, values, memo)),
            Node::Atan2(y, x) => {
                let y = self.eval_memo(*y, values, memo);
                y.atan2(self.eval_memo(*x, values, memo))
            }
        };
        memo.insert(id, v);
        v
    }

    /// Nodes reachable from `roots`, children before parents, each once, in a
    /// deterministic order (depth-first, operands in canonical order).
    pub fn post_order(&self, roots: &[ExprId]) -> Vec<ExprId> {
        let mut seen = vec![false; self.nodes.len()];
        let mut order = Vec::new();
        let mut stack: Vec<(ExprId, bool)> = roots.iter().rev().map(|&r| (r, false)).collect();
        while let Some((id, expanded)) = stack.pop() {
            if expanded {
                order.push(id);
                continue;
            }
            if seen[id.index()] {
                continue;
            }
            seen[id.index()] = true;
            stack.push((id, true));
            for child in self.children(id).into_iter().rev() {
                if !seen[child.index()] {
                    stack.push((child, false));
                }
            }
        }
        order
    }

    pub fn children(&self, id: ExprId) -> Vec<ExprId> {
        match &self.nodes[id.index()] {
            Node::Num(_) | Node::Sym(_) => Vec::new(),
            Node::Add(xs) | Node::Mul(xs) => xs.to_vec(),
            Node::Pow(a, b) | Node::Atan2(a, b) => vec![*a, *b],
            Node::Func(_, a) => vec![*a],
        }
    }
}
