//! Symbolic differentiation, memoized per (node, symbol) and short-cut by the
//! dependency sets: the derivative of a node that does not mention the symbol
//! is zero without a visit, which is what keeps chains of many links cheap.

use super::{ExprId, Func, Node, Pool, SymId};

impl Pool {
    /// `∂e/∂s`, simplified.
    pub fn diff(&mut self, e: ExprId, s: SymId) -> ExprId {
        if !self.depends_on(e, s) || self.exhausted() {
            return Pool::ZERO;
        }
        self.charge(1);
        if let Some(&d) = self.diff_memo.get(&(e, s)) {
            return d;
        }
        let d = match self.node(e).clone() {
            Node::Num(_) => Pool::ZERO,
            Node::Sym(x) => {
                if x == s {
                    Pool::ONE
                } else {
                    Pool::ZERO
                }
            }
            Node::Add(xs) => {
                let ds: Vec<ExprId> = xs.iter().map(|&x| self.diff(x, s)).collect();
                self.add(&ds)
            }
            Node::Mul(xs) => {
                // Product rule, skipping factors that do not depend on s.
                let mut terms = Vec::new();
                for k in 0..xs.len() {
                    if !self.depends_on(xs[k], s) {
                        continue;
                    }
                    let dk = self.diff(xs[k], s);
                    self.charge(1 + xs.len() as u64 / 8);
                    let mut factors: Vec<ExprId> = xs.to_vec();
                    factors[k] = dk;
                    terms.push(self.mul(&factors));
                }
                self.add(&terms)
            }
            Node::Pow(b, p) => {
                if !self.depends_on(p, s) {
                    // d(b^p) = p b^(p-1) db
                    let one = Pool::ONE;
                    let pm1 = self.sub(p, one);
                    let bp = self.pow(b, pm1);
                    let db = self.diff(b, s);
                    self.mul(&[p, bp, db])
                } else {
                    // d(b^p) = b^p (dp ln b + p db / b)
                    let dp = self.diff(p, s);
                    let db = self.diff(b, s);
                    let lnb = self.func(Func::Ln, b);
                    let t1 = self.mul2(dp, lnb);
                    let t2 = self.div(db, b);
                    let t2 = self.mul2(p, t2);
                    let sum = self.add2(t1, t2);
                    self.mul2(e, sum)
                }
            }
            Node::Func(f, a) => {
                let da = self.diff(a, s);
                let outer = self.func_derivative(f, a, e);
                self.mul2(outer, da)
            }
            Node::Atan2(y, x) => {
                // d atan2(y, x) = (x dy - y dx) / (x² + y²)
                let dy = self.diff(y, s);
                let dx = self.diff(x, s);
                let a = self.mul2(x, dy);
                let b = self.mul2(y, dx);
                let num = self.sub(a, b);
                let two = self.num(2.0);
                let x2 = self.pow(x, two);
                let y2 = self.pow(y, two);
                let den = self.add2(x2, y2);
                self.div(num, den)
            }
        };
        self.diff_memo.insert((e, s), d);
        d
    }

    /// `f'(a)`, given `fa = f(a)` for the functions whose derivative reuses it.
    fn func_derivative(&mut self, f: Func, a: ExprId, fa: ExprId) -> ExprId {
        let one = Pool::ONE;
        let two = self.num(2.0);
        match f {
            Func::Sin => self.func(Func::Cos, a),
            Func::Cos => {
                let s = self.func(Func::Sin, a);
                self.neg(s)
            }
            Func::Tan => {
                // 1 + tan²
                let t2 = self.pow(fa, two);
                self.add2(one, t2)
            }
            Func::Asin | Func::Acos => {
                // ±1/sqrt(1 - a²)
                let a2 = self.pow(a, two);
                let r = self.sub(one, a2);
                let mhalf = self.num(-0.5);
                let inv = self.pow(r, mhalf);
                if f == Func::Asin { inv } else { self.neg(inv) }
            }
            Func::Atan => {
                let a2 = self.pow(a, two);
                let d = self.add2(one, a2);
                self.div(one, d)
            }
            Func::Sinh => self.func(Func::Cosh, a),
            Func::Cosh => self.func(Func::Sinh, a),
            Func::Tanh => {
                let t2 = self.pow(fa, two);
                self.sub(one, t2)
            }
            Func::Exp => fa,
            Func::Ln => self.div(one, a),
        }
    }

    /// The total time derivative `Σ ∂e/∂q_i · q̇_i + ∂e/∂t`.
    pub fn total_time_derivative(
        &mut self,
        e: ExprId,
        coords: &[SymId],
        velocities: &[SymId],
        time: SymId,
    ) -> ExprId {
        let mut terms = Vec::with_capacity(coords.len() + 1);
        for (&q, &v) in coords.iter().zip(velocities) {
            if self.depends_on(e, q) {
                let d = self.diff(e, q);
                let v = self.sym(v);
                terms.push(self.mul2(d, v));
            }
        }
        terms.push(self.diff(e, time));
        self.add(&terms)
    }
}
