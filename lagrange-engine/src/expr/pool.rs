//! The arena: one copy of each node, cheap ids, a dependency set per node,
//! and the work budget that bounds what the engine does with a model.

use super::{ExprId, Node, SymId};
use std::cell::Cell;
use std::collections::HashMap;

/// A limit of the engine that a model ran into.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Exceeded {
    /// The work budget, in steps (see [`Pool::charge`]).
    Budget(u64),
    /// An expression deeper than [`MAX_DEPTH`] nodes.
    Depth,
}

/// The arena. Cheap ids, one copy of each node, a dependency set per node.
pub struct Pool {
    nodes: Vec<Node>,
    deps: Vec<Box<[u64]>>,
    /// Per node: its depth (a leaf is 0), and whether it holds a
    /// non-finite constant.
    depth: Vec<u32>,
    non_finite: Vec<bool>,
    index: HashMap<Node, ExprId>,
    pub(super) diff_memo: HashMap<(ExprId, SymId), ExprId>,
    pub(super) content_memo: HashMap<ExprId, Option<(f64, Vec<ExprId>, ExprId)>>,
    budget: u64,
    spent: Cell<u64>,
    too_deep: bool,
}

/// The default work budget, in steps: far above what a textbook model needs
/// (the 30-link chain of the scaling benchmark takes about a sixth of it,
/// the 60-link chain most of it), low enough that any model stops within a
/// few seconds and a few hundred MB, on one core, with the engine built
/// optimized (a step is some 20 to 60 ns of work and at most about 10 bytes
/// kept). Raised per model with `#[lagrange(budget = N)]`.
pub const DEFAULT_BUDGET: u64 = 50_000_000;

/// The deepest an expression may nest, counted in nodes (a number or a
/// symbol is 0, `sin(x)` 1). Differentiation, simplification, emission and
/// rendering recurse on it: at this depth they take at most about 1.1 MiB
/// of stack in a debug build of the engine (opt-level 0), 0.25 MiB
/// optimized; rustc runs a proc macro on a thread of 8 MiB. Sums and
/// products are single nodes, so `x + x + ... + x` is 2 deep at any length;
/// depth comes from nested functions and powers, directly or through `let`s.
pub const MAX_DEPTH: u32 = 400;

/// The work done by a point in time ([`Pool::mark`]).
#[derive(Clone, Copy, Debug)]
pub struct Mark {
    spent: u64,
    too_deep: bool,
}

impl Default for Pool {
    fn default() -> Self {
        Self::with_budget(DEFAULT_BUDGET)
    }
}

impl Pool {
    /// A pool that may do `budget` steps of work.
    pub fn with_budget(budget: u64) -> Self {
        let mut pool = Pool {
            nodes: Vec::new(),
            deps: Vec::new(),
            depth: Vec::new(),
            non_finite: Vec::new(),
            index: HashMap::new(),
            diff_memo: HashMap::new(),
            content_memo: HashMap::new(),
            budget: u64::MAX,
            spent: Cell::new(0),
            too_deep: false,
        };
        // Ids 0 and 1 are always zero and one, whatever the budget.
        pool.intern(Node::Num(0f64.to_bits()));
        pool.intern(Node::Num(1f64.to_bits()));
        pool.budget = budget;
        pool.spent.set(0);
        pool
    }

    /// The constant `0`, always node 0.
    pub const ZERO: ExprId = ExprId(0);
    /// The constant `1`, always node 1.
    pub const ONE: ExprId = ExprId(1);

    /// The node behind an id.
    pub fn node(&self, id: ExprId) -> &Node {
        &self.nodes[id.index()]
    }

    /// The number of nodes interned so far.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the pool holds no node (never once built: `ZERO` and `ONE` are always there).
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Counts `steps` units of work against the budget. A step is about
    /// the cost of interning a small node: every stage of the engine charges
    /// for what it does (a node built or looked up, a term of an unrolled
    /// sum, a derivative taken, a function's code emitted...), so that the
    /// budget bounds the time and the memory of any model.
    pub fn charge(&self, steps: u64) {
        self.spent.set(self.spent.get().saturating_add(steps));
    }

    /// The steps spent so far.
    pub fn spent(&self) -> u64 {
        self.spent.get()
    }

    /// Where the work stands, for [`Pool::rewind`].
    pub fn mark(&self) -> Mark {
        Mark {
            spent: self.spent.get(),
            too_deep: self.too_deep,
        }
    }

    /// Forgets the work since `mark` (the steps and a node grown too deep):
    /// for a search that may give up without costing the model its budget.
    /// The nodes it made stay, unused; what it could make is bounded by the
    /// budget it had, as any stage's.
    pub fn rewind(&mut self, mark: Mark) {
        self.spent.set(mark.spent);
        self.too_deep = mark.too_deep;
    }

    /// `f`'s result, the steps it charges forgotten: a measurement taken
    /// after the expansion, which must not find the budget spent.
    pub fn uncharged<R>(&self, f: impl FnOnce() -> R) -> R {
        let before = self.spent.replace(0);
        let result = f();
        self.spent.set(before);
        result
    }

    /// Whether the budget is spent or a node grew too deep: from then on
    /// every new node is zero and every loop stops, so the result is
    /// garbage, but reached quickly, and [`Pool::check_budget`] says why.
    pub fn exhausted(&self) -> bool {
        self.too_deep || self.spent.get() > self.budget
    }

    /// `Err` once the pool is [`exhausted`](Pool::exhausted); the model
    /// stops there.
    pub fn check_budget(&self) -> Result<(), Exceeded> {
        if self.too_deep {
            Err(Exceeded::Depth)
        } else if self.spent.get() > self.budget {
            Err(Exceeded::Budget(self.budget))
        } else {
            Ok(())
        }
    }

    /// The node's id if it already exists (never creates one).
    pub(super) fn lookup(&self, node: &Node) -> Option<ExprId> {
        self.charge(1 + node_size(node));
        self.index.get(node).copied()
    }

    pub(super) fn intern(&mut self, node: Node) -> ExprId {
        // Hashing and comparing cost the node's size.
        self.charge(1 + node_size(&node));
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        if self.exhausted() {
            return Pool::ZERO;
        }
        let children = node_children(&node);
        let depth = 1 + children
            .iter()
            .map(|c| self.depth[c.index()])
            .max()
            .unwrap_or(0);
        let depth = if children.is_empty() { 0 } else { depth };
        if depth > MAX_DEPTH {
            self.too_deep = true;
            return Pool::ZERO;
        }
        let non_finite = match node {
            Node::Num(bits) => !f64::from_bits(bits).is_finite(),
            _ => children.iter().any(|c| self.non_finite[c.index()]),
        };
        let deps = self.deps_of(&node);
        // The allocations, the copies kept (the node twice, its dependency
        // set; about 8 bytes a step) and the union of the children's sets.
        let union: usize = children.iter().map(|c| self.deps[c.index()].len()).sum();
        self.charge(8 + node_size(&node) + deps.len() as u64 + union as u64 / 8);
        let id = ExprId(self.nodes.len() as u32);
        self.nodes.push(node.clone());
        self.deps.push(deps);
        self.depth.push(depth);
        self.non_finite.push(non_finite);
        self.index.insert(node, id);
        id
    }

    /// The depth of a node: 0 for a number or a symbol, one more than its
    /// deepest operand otherwise.
    pub fn depth(&self, id: ExprId) -> u32 {
        self.depth[id.index()]
    }

    /// Whether a non-finite constant (a division by zero, `ln(0)`...) is
    /// part of `id`.
    pub fn has_non_finite(&self, id: ExprId) -> bool {
        self.non_finite[id.index()]
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

    /// The symbols `id` depends on (structurally), in increasing order; as
    /// long to read as its dependency set, which its creation paid for.
    pub fn dependencies(&self, id: ExprId) -> impl Iterator<Item = SymId> + '_ {
        self.charge(1 + self.deps[id.index()].len() as u64);
        self.deps[id.index()]
            .iter()
            .enumerate()
            .flat_map(|(w, &bits)| {
                // The set bits only, lowest first.
                std::iter::successors((bits != 0).then_some(bits), |&b| {
                    let rest = b & (b - 1);
                    (rest != 0).then_some(rest)
                })
                .map(move |b| SymId((64 * w) as u32 + b.trailing_zeros()))
            })
    }

    /// A set of symbols, for [`Pool::depends_on_any`].
    pub fn symbol_set(syms: &[SymId]) -> Box<[u64]> {
        let words = syms
            .iter()
            .map(|s| s.0 as usize / 64 + 1)
            .max()
            .unwrap_or(0);
        let mut bits = vec![0u64; words];
        for s in syms {
            bits[s.0 as usize / 64] |= 1 << (s.0 % 64);
        }
        bits.into_boxed_slice()
    }

    /// Whether `id` depends on any symbol of `set` (from [`Pool::symbol_set`]).
    pub fn depends_on_any(&self, id: ExprId, set: &[u64]) -> bool {
        self.deps[id.index()]
            .iter()
            .zip(set)
            .any(|(a, b)| a & b != 0)
    }

    /// The constant value of a `Num` node.
    pub fn as_num(&self, id: ExprId) -> Option<f64> {
        match self.nodes[id.index()] {
            Node::Num(bits) => Some(f64::from_bits(bits)),
            _ => None,
        }
    }

    /// Nodes reachable from `roots`, children before parents, each once, in a
    /// deterministic order (depth-first, operands in canonical order).
    pub fn post_order(&self, roots: &[ExprId]) -> Vec<ExprId> {
        self.charge(1 + self.nodes.len() as u64 / 64);
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
            self.charge(node_size(self.node(id)));
            stack.push((id, true));
            for child in self.children(id).into_iter().rev() {
                if !seen[child.index()] {
                    stack.push((child, false));
                }
            }
        }
        order
    }

    /// The operands of a node (none for a number or a symbol).
    pub fn children(&self, id: ExprId) -> Vec<ExprId> {
        node_children(self.node(id))
    }
}

/// The operands of a node.
fn node_children(node: &Node) -> Vec<ExprId> {
    match node {
        Node::Num(_) | Node::Sym(_) => Vec::new(),
        Node::Add(xs) | Node::Mul(xs) => xs.to_vec(),
        Node::Pow(a, b) | Node::Atan2(a, b) => vec![*a, *b],
        Node::Func(_, a) => vec![*a],
    }
}

/// 1 plus the number of operands.
fn node_size(node: &Node) -> u64 {
    match node {
        Node::Num(_) | Node::Sym(_) => 1,
        Node::Add(xs) | Node::Mul(xs) => 1 + xs.len() as u64,
        Node::Pow(..) | Node::Atan2(..) => 3,
        Node::Func(..) => 2,
    }
}
