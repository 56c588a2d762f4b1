//! Numeric evaluation of an expression, for tests and for compile-time checks
//! (the rank of the mass matrix at a generic state); emitted code never calls
//! it.

use super::{ExprId, Node, Pool};
use std::collections::HashMap;

impl Pool {
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
        let v = match self.node(id) {
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
}
