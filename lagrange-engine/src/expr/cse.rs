//! Common subexpression elimination. The DAG already shares every repeated
//! subexpression (hash-consing); what is left is to decide, for one emitted
//! function, which nodes get a `let` (those used more than once, and the
//! bases of powers that are expanded into products) and in which order.
//!
//! Uses are counted on the code as it is written, not on the DAG: a sum
//! writes each product term after the first as one multiply-add with the
//! running total (`fma(a * b, c, total)`, fused where the target has FMA),
//! so such a term's factors are used, not the product itself, which then
//! needs no `let` of its own unless something else uses it whole. The
//! choice depends only on the node, never on what else the function holds,
//! so an expression rounds the same in every function that computes it.
//! A sine and a cosine of the same argument are one lane of the runtime's
//! sine-and-cosine kernel ([`Trig`]), counted as one call.

use super::{ExprId, Func, Node, Pool};
use std::collections::BTreeMap;

/// What one emitted function computes, and how.
pub struct Schedule {
    /// Every node the roots need, children first (some, used only as fused
    /// terms, are never written: their `uses` is 0).
    pub order: Vec<ExprId>,
    /// Uses of each node (indexed by node id) within this function, as
    /// written.
    pub uses: Vec<u32>,
    /// Whether each node (indexed by id) is bound to a `let`.
    pub bound: Vec<bool>,
    /// Every argument of a sine or cosine the function writes, in the order
    /// of the arguments' ids: each is one lane of the runtime's kernel, which
    /// computes both, and the written ones are bound.
    pub trig: Vec<Trig>,
}

/// The sine and the cosine of one argument, as far as a function writes them.
pub struct Trig {
    /// The argument.
    pub arg: ExprId,
    /// `sin(arg)`, if written.
    pub sin: Option<ExprId>,
    /// `cos(arg)`, if written.
    pub cos: Option<ExprId>,
}

/// Small integer exponents are emitted as repeated products (`x * x`), which
/// needs their base as a name.
pub fn expands_to_product(exponent: f64) -> bool {
    matches!(exponent, 2.0 | 3.0 | -2.0 | -3.0)
}

/// A term of a sum written as a multiply-add with the terms before it:
/// `Some((c, factors))` for a product `c * f1 * ... * fk` of at least two
/// operands (`|c| != 1` or `k >= 2`) with no divisor. The first term of a
/// sum is never fused (there is nothing to add it to).
pub fn fused_term(pool: &Pool, term: ExprId) -> Option<(f64, &[ExprId])> {
    let Node::Mul(xs) = pool.node(term) else {
        return None;
    };
    let (c, factors) = match pool.as_num(xs[0]) {
        Some(c) => (c, &xs[1..]),
        None => (1.0, &xs[..]),
    };
    let divisor = factors.iter().any(|&f| match pool.node(f) {
        Node::Pow(_, e) => pool.as_num(*e).is_some_and(|v| v < 0.0),
        _ => false,
    });
    let operands = factors.len() + usize::from(c.abs() != 1.0);
    (!factors.is_empty() && operands >= 2 && !divisor).then_some((c, factors))
}

/// The operands of `id` as its code is written: a sum's fused terms
/// contribute their factors.
fn written_children(pool: &Pool, id: ExprId, out: &mut Vec<ExprId>) {
    out.clear();
    match pool.node(id) {
        Node::Add(xs) => {
            out.push(xs[0]);
            for &x in &xs[1..] {
                match fused_term(pool, x) {
                    Some((_, factors)) => out.extend_from_slice(factors),
                    None => out.push(x),
                }
            }
        }
        _ => out.extend(pool.children(id)),
    }
}

/// Which nodes the code for `roots` names, counting uses as written (sums
/// fused, see [`fused_term`]).
pub fn schedule(pool: &Pool, roots: &[ExprId]) -> Schedule {
    let order = pool.post_order(roots);
    let mut uses = vec![0u32; pool.len()];
    let mut bound = vec![false; pool.len()];
    for r in roots {
        uses[r.index()] += 1;
    }
    // Parents before children: a node's uses are final when it is reached,
    // and a node that is written nowhere passes nothing on.
    let mut children = Vec::new();
    for &id in order.iter().rev() {
        if uses[id.index()] == 0 {
            continue;
        }
        written_children(pool, id, &mut children);
        for child in &children {
            uses[child.index()] += 1;
        }
        if let Node::Pow(base, e) = pool.node(id) {
            if pool.as_num(*e).is_some_and(expands_to_product) {
                bound[base.index()] = true;
            }
        }
    }
    for &id in &order {
        let leaf = matches!(pool.node(id), Node::Num(_) | Node::Sym(_));
        if leaf {
            bound[id.index()] = false;
        } else if uses[id.index()] > 1 {
            bound[id.index()] = true;
        }
    }
    // Sines and cosines by argument, whose id orders them.
    let mut by_argument: BTreeMap<ExprId, (Option<ExprId>, Option<ExprId>)> = BTreeMap::new();
    for &id in &order {
        if uses[id.index()] == 0 {
            continue;
        }
        match pool.node(id) {
            Node::Func(Func::Sin, a) => by_argument.entry(*a).or_default().0 = Some(id),
            Node::Func(Func::Cos, a) => by_argument.entry(*a).or_default().1 = Some(id),
            _ => {}
        }
    }
    let trig: Vec<Trig> = by_argument
        .into_iter()
        .map(|(arg, (sin, cos))| Trig { arg, sin, cos })
        .collect();
    for t in &trig {
        for id in t.sin.iter().chain(&t.cos) {
            bound[id.index()] = true;
        }
    }
    Schedule {
        order,
        uses,
        bound,
        trig,
    }
}

/// Uses of each node counted on the DAG (every operand of every reachable
/// node), for the equations as text, which writes sums as they are.
pub fn dag_uses(pool: &Pool, roots: &[ExprId]) -> (Vec<ExprId>, Vec<u32>) {
    let order = pool.post_order(roots);
    let mut uses = vec![0u32; pool.len()];
    for &id in &order {
        for child in pool.children(id) {
            uses[child.index()] += 1;
        }
    }
    for r in roots {
        uses[r.index()] += 1;
    }
    (order, uses)
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
    /// All operations, arithmetic and calls.
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
        // A coefficient -1 is a sign, written as a subtraction or a minus.
        Node::Mul(xs) => OpCount {
            arithmetic: xs.len() as u64 - 1 - u64::from(pool.as_num(xs[0]) == Some(-1.0)),
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

/// Operations performed by the emitted code, which evaluates each written
/// node once: a fused term of a sum costs its product and one addition
/// (a multiply-add counts as two operations, as it does in C's text).
pub fn shared_ops(pool: &Pool, roots: &[ExprId]) -> OpCount {
    let sched = schedule(pool, roots);
    let mut total = OpCount::default();
    for &id in &sched.order {
        if sched.uses[id.index()] == 0 {
            continue;
        }
        let c = written_ops(pool, id);
        total.arithmetic += c.arithmetic;
        total.calls += c.calls;
    }
    // A sine and a cosine of one argument are one call.
    total.calls -= sched
        .trig
        .iter()
        .filter(|t| t.sin.is_some() && t.cos.is_some())
        .count() as u64;
    total
}

/// [`node_ops`] of a node as written: a sum's fused terms add their
/// products' multiplications.
fn written_ops(pool: &Pool, id: ExprId) -> OpCount {
    let Node::Add(xs) = pool.node(id) else {
        return node_ops(pool, id);
    };
    let mut c = OpCount {
        arithmetic: xs.len() as u64 - 1,
        calls: 0,
    };
    for (k, &x) in xs.iter().enumerate() {
        let fused = if k == 0 { None } else { fused_term(pool, x) };
        if let Some((coef, factors)) = fused {
            c.arithmetic += factors.len() as u64 - 1 + u64::from(coef.abs() != 1.0);
        }
    }
    c
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
