//! Finding the user's tokens behind a node, for the checks' errors: a
//! subexpression is lowered again (the pool returns the nodes it already
//! holds) and the search descends into the smallest piece that is at fault.

use super::Model;
use super::lowering::Lowering;
use crate::ast::{Expr, SpanRange};
use crate::expr::{ExprId, Pool};

impl Model {
    /// A lowering over the model's names, borrowing its pool and scope;
    /// [`Model::restore`] gives them back.
    fn lowering(&mut self) -> Lowering {
        Lowering {
            pool: std::mem::take(&mut self.pool),
            symbols: self.symbols.clone(),
            names: std::mem::take(&mut self.scope),
            pending_lets: Default::default(),
            env: Vec::new(),
            model: self.name.clone(),
        }
    }

    fn restore(&mut self, cx: Lowering) {
        self.pool = cx.pool;
        self.scope = cx.names;
    }

    /// The smallest piece of `e` that is `bad`, descending from `e` (assumed
    /// bad) into its leftmost bad operand: the token to underline. Inside a
    /// sum, into the first term that is bad; inside a chain `a + b + c`,
    /// into `a + b` or `c`, as if it were written `(a + b) + c`. A search
    /// that runs out of budget stops where it is.
    pub fn locate(&mut self, e: &Expr, bad: &dyn Fn(&mut Pool, ExprId) -> bool) -> SpanRange {
        self.locate_in(e, &[], bad)
    }

    /// [`Model::locate`] in an expression under index variables (the body
    /// of an indexed constraint): `env`, their values.
    pub fn locate_in(
        &mut self,
        e: &Expr,
        env: &[(String, i64)],
        bad: &dyn Fn(&mut Pool, ExprId) -> bool,
    ) -> SpanRange {
        let mut cx = self.lowering();
        cx.env = env.to_vec();
        let range = descend(&mut cx, e, bad);
        self.restore(cx);
        range
    }
}

/// A piece of an expression: a whole node, or the first `len` (≥ 2)
/// operands of a chain.
#[derive(Clone, Copy)]
enum Piece<'a> {
    Whole(&'a Expr),
    Prefix(&'a Expr, usize),
}

impl<'a> Piece<'a> {
    /// A chain is its longest prefix.
    fn of(e: &'a Expr) -> Self {
        match e {
            Expr::Chain { rest, .. } => Piece::Prefix(e, rest.len() + 1),
            _ => Piece::Whole(e),
        }
    }

    fn range(self) -> SpanRange {
        match self {
            Piece::Whole(e) => e.range(),
            Piece::Prefix(chain, len) => {
                let (first, rest) = operands(chain);
                first.range().to(rest[len - 2].1.range())
            }
        }
    }
}

fn operands(chain: &Expr) -> (&Expr, &[(crate::ast::BinOp, Expr)]) {
    match chain {
        Expr::Chain { first, rest, .. } => (first, rest),
        _ => unreachable!("prefixes are of chains"),
    }
}

/// The nodes of a chain's prefixes, `ids[k]` of its first `k + 1`
/// operands, computed once per chain.
struct Prefixes<'a> {
    chain: Option<&'a Expr>,
    ids: Vec<Option<ExprId>>,
}

impl<'a> Prefixes<'a> {
    fn of(&mut self, cx: &mut Lowering, chain: &'a Expr) -> &[Option<ExprId>] {
        if !self.chain.is_some_and(|c| std::ptr::eq(c, chain)) {
            let (first, rest) = operands(chain);
            let mut acc = cx.lower(first).ok();
            self.ids = vec![acc];
            for (op, x) in rest {
                acc = match (acc, cx.lower(x)) {
                    (Some(a), Ok(b)) => Some(cx.combine(*op, a, b)),
                    _ => None,
                };
                self.ids.push(acc);
            }
            self.chain = Some(chain);
        }
        &self.ids
    }
}

/// The descent of [`Model::locate`], a loop: the search goes one way down,
/// and a long chain is as deep as it is long.
fn descend(cx: &mut Lowering, e: &Expr, bad: &dyn Fn(&mut Pool, ExprId) -> bool) -> SpanRange {
    let mut piece = Piece::of(e);
    let mut prefixes = Prefixes {
        chain: None,
        ids: Vec::new(),
    };
    loop {
        if cx.pool.check_budget().is_err() {
            return piece.range();
        }
        let is_bad =
            |cx: &mut Lowering, id: Option<ExprId>| id.is_some_and(|id| bad(&mut cx.pool, id));
        let next = match piece {
            Piece::Whole(Expr::Sum { index, body, .. }) => {
                let Ok((lo, hi)) = cx.range(index) else {
                    return piece.range();
                };
                // Into the first bad term, keeping its index in scope.
                let mut found = None;
                for k in lo..hi {
                    cx.env.push((index.var.to_string(), k));
                    let id = cx.lower(body).ok();
                    if is_bad(cx, id) {
                        found = Some(Piece::of(body));
                        break;
                    }
                    cx.env.pop();
                    if cx.pool.check_budget().is_err() {
                        break;
                    }
                }
                found
            }
            Piece::Whole(e) => {
                let mut found = None;
                for child in e.children() {
                    let id = cx.lower(child).ok();
                    if is_bad(cx, id) {
                        found = Some(Piece::of(child));
                        break;
                    }
                }
                found
            }
            Piece::Prefix(chain, len) => {
                let left = prefixes.of(cx, chain)[len - 2];
                let (first, rest) = operands(chain);
                let right = &rest[len - 2].1;
                if is_bad(cx, left) {
                    Some(if len == 2 {
                        Piece::of(first)
                    } else {
                        Piece::Prefix(chain, len - 1)
                    })
                } else {
                    let id = cx.lower(right).ok();
                    is_bad(cx, id).then(|| Piece::of(right))
                }
            }
        };
        match next {
            Some(p) => piece = p,
            None => return piece.range(),
        }
    }
}
