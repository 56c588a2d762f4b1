//! Numeric evaluation of an expression, for tests and for compile-time checks
//! (the rank of the mass matrix at a generic state); emitted code never calls
//! it.

use super::{ExprId, Node, Pool};
use std::collections::HashMap;

impl Pool {
    /// Evaluates `id` with `values[s]` for each symbol `s`.
    pub fn eval(&self, id: ExprId, values: &[f64]) -> f64 {
        let mut memo: HashMap<ExprId, f64> = HashMap::new();
        self.eval_memo(id, values, &mut memo)
    }

    /// [`Pool::eval`], reusing and extending `memo` (the values of nodes
    /// already evaluated at `values`). A loop, not a recursion: an
    /// expression's depth does not reach the stack.
    pub fn eval_memo(&self, id: ExprId, values: &[f64], memo: &mut HashMap<ExprId, f64>) -> f64 {
        let mut stack = vec![(id, false)];
        while let Some((x, operands_done)) = stack.pop() {
            if memo.contains_key(&x) {
                continue;
            }
            if !operands_done {
                stack.push((x, true));
                stack.extend(
                    self.children(x)
                        .into_iter()
                        .filter(|c| !memo.contains_key(c))
                        .map(|c| (c, false)),
                );
                continue;
            }
            let v = |c: &ExprId| memo[c];
            let value = match self.node(x) {
                Node::Num(bits) => f64::from_bits(*bits),
                Node::Sym(s) => values[s.0 as usize],
                Node::Add(xs) => xs.iter().map(v).sum(),
                Node::Mul(xs) => xs.iter().map(v).product(),
                Node::Pow(a, b) => {
                    let (base, exp) = (v(a), v(b));
                    if exp.fract() == 0.0 && exp.abs() < 1e9 {
                        base.powi(exp as i32)
                    } else {
                        base.powf(exp)
                    }
                }
                Node::Func(f, a) => f.apply(v(a)),
                Node::Atan2(y, x) => v(y).atan2(v(x)),
            };
            memo.insert(x, value);
        }
        memo[&id]
    }
}
