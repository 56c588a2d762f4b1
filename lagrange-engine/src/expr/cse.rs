//! Common subexpression elimination. The DAG already shares every repeated
//! subexpression (hash-consing); what is left is to decide, for one emitted
//! function, which nodes get a `let` (those used more than once, and the
//! bases of powers that are expanded into products) and in which order.

use super::{ExprId, Node, Pool};

/// What one emitted function computes, and how.
pub struct Schedule {
    /// Every node the roots need, children first.
    pub order: Vec<ExprId>,
    /// Uses of each node (indexed by node id) within this function.
    pub uses: Vec<u32>,
    /// Whether each node (indexed by id) is bound to a `let`.
    pub bound: Vec<bool>,
}

/// Small integer exponents are emitted as repeated products (`x * x`), which
/// needs their base as a name.
pub fn expands_to_product(exponent: f64) -> bool {
    matches!(exponent, 2.0 | 3.0 | -2.0 | -3.0)
}

pub fn schedule(pool: &Pool, roots: &[ExprId]) -> Schedule {
    let order = pool.post_order(roots);
    let mut uses = vec![0u32; pool.len()];
    let mut bound = vec![false; pool.len()];
    for &id in &order {
        for child in pool.children(id) {
            uses[child.index()] += 1;
        }
        if let Node::Pow(base, e) = pool.node(id) {
            if pool.as_num(*e).is_some_and(expands_to_product) {
                bound[base.index()] = true;
            }
        }
    }
    for r in roots {
        uses[r.index()] += 1;
    }
    for &id in &order {
        let leaf = matches!(pool.node(id), Node::Num(_) | Node::Sym(_));
        if leaf {
            bound[id.index()] = false;
        } else if uses[id.index()] > 1 {
            bound[id.index()] = true;
        }
    }
    Schedule { order, uses, bound }
}

/// Operation counts of emitted code, for benchmarks and tests: what the
/// straight-line code performs with sharing, and what a tree (no sharing at
/// all) would perform.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCount {
    /// Additions, subtractions, multiplications, divisions.
    pub arithmetic: u64,
    /// Calls of elementary functions, `sqrt` and `powi`/`powf`.
    pub calls: u64,
}

impl OpCount {
    pub fn total(self) -> u64 {
        self.arithmetic + self.calls
    }
}

fn node_ops(pool: &Pool, id: ExprId) -> OpCount {
    match pool.node(id) {
        Node::Num(_) | Node::Sym(_) => OpCount::default(),
        Node::Add(xs) => {
            // Non-unit coefficients cost a multiplication each.
            let scaled = xs
                .iter()
                .filter(|&&x| match pool.node(x) {
                    Node::Mul(fs) => pool.as_num(fs[0]).is_some_and(|c| c.abs() != 1.0),
                    _ => false,
                })
                .count() as u64;
            OpCount {
                arithmetic: xs.len() as u64 - 1 + scaled,
                calls: 0,
            }
        }
        Node::Mul(xs) => OpCount {
            arithmetic: xs.len() as u64 - 1,
            calls: 0,
        },
        Node::Pow(_, e) => match pool.as_num(*e) {
            Some(2.0) | Some(-1.0) => OpCount {
                arithmetic: 1,
                calls: 0,
            },
            Some(3.0) | Some(-2.0) => OpCount {
                arithmetic: 2,
                calls: 0,
            },
            Some(-3.0) => OpCount {
                arithmetic: 3,
                calls: 0,
            },
            _ => OpCount {
                arithmetic: 0,
                calls: 1,
            },
        },
        Node::Func(..) | Node::Atan2(..) => OpCount {
            arithmetic: 0,
            calls: 1,
        },
    }
}

/// Operations performed by code that evaluates each reachable node once.
pub fn shared_ops(pool: &Pool, roots: &[ExprId]) -> OpCount {
    let mut total = OpCount::default();
    for id in pool.post_order(roots) {
        let c = node_ops(pool, id);
        total.arithmetic += c.arithmetic;
        total.calls += c.calls;
    }
    total
}

/// Operations a tree without any sharing would perform (saturating: trees of
/// large models are astronomically large, which is the point).
pub fn tree_ops(pool: &Pool, roots: &[ExprId]) -> OpCount {
    let order = pool.post_order(roots);
    let mut cost: Vec<OpCount> = vec![OpCount::default(); pool.len()];
    for &id in &order {
        let mut c = node_ops(pool, id);
        for child in pool.children(id) {
            let cc = cost[child.index()];
            c.arithmetic = c.arithmetic.saturating_add(cc.arithmetic);
            c.calls = c.calls.saturating_add(cc.calls);
        }
        cost[id.index()] = c;
    }
    let mut total = OpCount::default();
    for r in roots {
        let c = cost[r.index()];
        total.arithmetic = total.arithmetic.saturating_add(c.arithmetic);
        total.calls = total.calls.saturating_add(c.calls);
    }
    total
}
