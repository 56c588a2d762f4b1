//! Setting symbols to zero: what the kinetic energy and the momenta are at
//! rest (`q̇ = 0`), the parts of `T` that are not quadratic in `q̇`.

use super::{ExprId, Node, Pool, SymId};
use std::collections::HashMap;

impl Pool {
    /// Each of `exprs` with every symbol of `syms` replaced by zero,
    /// simplified. A result that holds a non-finite constant (`1/q̇` at
    /// rest) is the caller's to refuse.
    pub fn at_zero(&mut self, exprs: &[ExprId], syms: &[SymId]) -> Vec<ExprId> {
        let set = Pool::symbol_set(syms);
        let mut memo = HashMap::new();
        exprs
            .iter()
            .map(|&e| self.at_zero_memo(e, &set, &mut memo))
            .collect()
    }

    fn at_zero_memo(
        &mut self,
        e: ExprId,
        set: &[u64],
        memo: &mut HashMap<ExprId, ExprId>,
    ) -> ExprId {
        self.charge(1 + set.len() as u64 / 8);
        if self.exhausted() || !self.depends_on_any(e, set) {
            return e;
        }
        if let Some(&z) = memo.get(&e) {
            return z;
        }
        let z = match self.node(e).clone() {
            Node::Num(_) => e,
            Node::Sym(_) => Pool::ZERO, // in `set`, or it would not depend on it
            Node::Add(xs) => {
                let ys: Vec<ExprId> = xs
                    .iter()
                    .map(|&x| self.at_zero_memo(x, set, memo))
                    .collect();
                self.add(&ys)
            }
            Node::Mul(xs) => {
                let ys: Vec<ExprId> = xs
                    .iter()
                    .map(|&x| self.at_zero_memo(x, set, memo))
                    .collect();
                self.mul(&ys)
            }
            Node::Pow(b, p) => {
                let b = self.at_zero_memo(b, set, memo);
                let p = self.at_zero_memo(p, set, memo);
                self.pow(b, p)
            }
            Node::Func(f, a) => {
                let a = self.at_zero_memo(a, set, memo);
                self.func(f, a)
            }
            Node::Atan2(y, x) => {
                let y = self.at_zero_memo(y, set, memo);
                let x = self.at_zero_memo(x, set, memo);
                self.atan2(y, x)
            }
        };
        memo.insert(e, z);
        z
    }
}
