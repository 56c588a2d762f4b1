//! Finding the user's tokens behind a node, for the checks' errors: a
//! subexpression is lowered again (the pool returns the nodes it already
//! holds) and the search descends into the smallest piece that is at fault.

use super::lowering::Lowering;
use super::Model;
use crate::ast::{Expr, SpanRange};
use crate::expr::{ExprId, Pool};

impl Model {
    /// Re-lowers `e` (a subexpression of a section, under the index values
    /// `env`) to find its node; the pool returns the existing nodes, so this
    /// is cheap and side-effect free.
    fn lower_sub(&mut self, e: &Expr, env: &[(String, i64)]) -> Option<ExprId> {
        let mut cx = self.lowering(env);
        let id = cx.lower(e).ok();
        self.pool = cx.pool;
        id
    }

    fn lowering(&mut self, env: &[(String, i64)]) -> Lowering {
        Lowering {
            pool: std::mem::take(&mut self.pool),
            symbols: self.symbols.clone(),
            names: self.scope.clone(),
            pending_lets: Vec::new(),
            env: env.to_vec(),
            model: self.name.clone(),
        }
    }

    /// The node of a whole section's expression.
    pub fn lower_section(&mut self, e: &Expr) -> Option<ExprId> {
        self.lower_sub(e, &[])
    }

    /// The smallest piece of `e` that is `bad`, descending from `e` (assumed
    /// bad) into its leftmost bad operand: the token to underline. Inside a
    /// sum, into the first term that is bad.
    pub fn locate(&mut self, e: &Expr, bad: &dyn Fn(&mut Pool, ExprId) -> bool) -> SpanRange {
        self.locate_in(e, &mut Vec::new(), bad)
    }

    fn locate_in(
        &mut self,
        e: &Expr,
        env: &mut Vec<(String, i64)>,
        bad: &dyn Fn(&mut Pool, ExprId) -> bool,
    ) -> SpanRange {
        if let Expr::Sum { index, body, .. } = e {
            let cx = self.lowering(env);
            let range = cx.range(index);
            self.pool = cx.pool;
            if let Ok((lo, hi)) = range {
                for k in lo..hi {
                    env.push((index.var.to_string(), k));
                    if let Some(id) = self.lower_sub(body, env) {
                        if bad(&mut self.pool, id) {
                            let r = self.locate_in(body, env, bad);
                            env.pop();
                            return r;
                        }
                    }
                    env.pop();
                }
            }
            return e.range();
        }
        for child in e.children() {
            if let Some(id) = self.lower_sub(child, env) {
                if bad(&mut self.pool, id) {
                    return self.locate_in(child, env, bad);
                }
            }
        }
        e.range()
    }
}
