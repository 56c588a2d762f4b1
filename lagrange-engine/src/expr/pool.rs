//! The arena: one copy of each node, cheap ids, a dependency set per node,
//! and the node budget that bounds a derivation.

use super::{ExprId, Node, SymId};
use std::collections::HashMap;

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
    pub(super) diff_memo: HashMap<(ExprId, SymId), ExprId>,
    pub(super) content_memo: HashMap<ExprId, Option<(f64, Vec<ExprId>, ExprId)>>,
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
    pub(super) fn lookup(&self, node: &Node) -> Option<ExprId> {
        self.index.get(node).copied()
    }

    pub(super) fn intern(&mut self, node: Node) -> ExprId {
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
