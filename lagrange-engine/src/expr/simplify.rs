//! Simplifying constructors: the only way nodes are made.
//!
//! Every node is kept in a canonical form, so equal expressions are one node:
//! - sums are flat, like terms collected (`2x + 3x = 5x`), constants folded,
//!   `c·R·sin²a + c·R·cos²a = c·R`, operands ordered by id;
//! - products are flat, powers of a base collected (`x·x⁻¹ = 1`), one leading
//!   numeric coefficient, operands ordered by id;
//! - integer powers distribute over products (`(a·b)² = a²·b²`) and nest
//!   (`(x²)³ = x⁶`); `0` and `1` identities apply everywhere;
//! - odd functions pull out a negated argument (`sin(-a) = -sin(a)`), even
//!   ones drop it (`cos(b - a) = cos(a - b)`), so both signs share one node.
//!
//! Products are never expanded over sums: that is what keeps large models
//! from swelling.

use super::{ExprId, Func, Node, Pool, SymId};
use std::collections::HashMap;

fn canonical_bits(x: f64) -> u64 {
    // One zero, so `0.0` and `-0.0` are the same node.
    if x == 0.0 {
        0f64.to_bits()
    } else {
        x.to_bits()
    }
}

impl Pool {
    /// A numeric constant (`-0.0` is `0.0`).
    pub fn num(&mut self, x: f64) -> ExprId {
        self.intern(Node::Num(canonical_bits(x)))
    }

    /// A symbol.
    pub fn sym(&mut self, s: SymId) -> ExprId {
        self.intern(Node::Sym(s))
    }

    /// Splits `c * rest` into its numeric coefficient and the rest
    /// (`Pool::ONE` for a constant).
    pub fn split_coeff(&mut self, id: ExprId) -> (f64, ExprId) {
        match self.node(id) {
            Node::Num(bits) => (f64::from_bits(*bits), Pool::ONE),
            Node::Mul(xs) => {
                if let Some(c) = self.as_num(xs[0]) {
                    let rest: Vec<ExprId> = xs[1..].to_vec();
                    let rest = if rest.len() == 1 {
                        rest[0]
                    } else {
                        self.intern(Node::Mul(rest.into_boxed_slice()))
                    };
                    (c, rest)
                } else {
                    (1.0, id)
                }
            }
            _ => (1.0, id),
        }
    }

    pub(super) fn split_pow(&self, id: ExprId) -> (ExprId, ExprId) {
        match self.node(id) {
            Node::Pow(b, e) => (*b, *e),
            _ => (id, Pool::ONE),
        }
    }

    /// `a + b`.
    pub fn add2(&mut self, a: ExprId, b: ExprId) -> ExprId {
        self.add(&[a, b])
    }

    /// `a - b`, as `a + (-1)·b`.
    pub fn sub(&mut self, a: ExprId, b: ExprId) -> ExprId {
        let nb = self.neg(b);
        self.add(&[a, nb])
    }

    /// `-a`, as `(-1)·a`.
    pub fn neg(&mut self, a: ExprId) -> ExprId {
        let m1 = self.num(-1.0);
        self.mul(&[m1, a])
    }

    /// `a · b`.
    pub fn mul2(&mut self, a: ExprId, b: ExprId) -> ExprId {
        self.mul(&[a, b])
    }

    /// `a / b`, as `a · b^-1`.
    pub fn div(&mut self, a: ExprId, b: ExprId) -> ExprId {
        let m1 = self.num(-1.0);
        let inv = self.pow(b, m1);
        self.mul(&[a, inv])
    }

    /// A sum in canonical form.
    pub fn add(&mut self, terms: &[ExprId]) -> ExprId {
        if self.exhausted() {
            return Pool::ZERO;
        }
        let mut constant = 0.0;
        let mut coeffs: Vec<(ExprId, f64)> = Vec::new();
        let mut slot: HashMap<ExprId, usize> = HashMap::new();
        let mut stack: Vec<ExprId> = terms.iter().rev().copied().collect();
        while let Some(t) = stack.pop() {
            self.charge(1);
            if let Node::Add(xs) = self.node(t) {
                stack.extend(xs.iter().rev());
                continue;
            }
            let (c, rest) = self.split_coeff(t);
            if rest == Pool::ONE {
                constant += c;
            } else if let Some(&k) = slot.get(&rest) {
                coeffs[k].1 += c;
            } else {
                slot.insert(rest, coeffs.len());
                coeffs.push((rest, c));
            }
        }
        let freed = self.pythagoras(&mut coeffs, &slot);
        coeffs.retain(|&(_, c)| c != 0.0);
        if !freed.is_empty() {
            // Each pass removes sin² factors, so this recursion ends.
            let mut terms = freed;
            for (rest, c) in coeffs {
                let c = self.num(c);
                terms.push(self.mul2(c, rest));
            }
            let c = self.num(constant);
            terms.push(c);
            return self.add(&terms);
        }
        if constant != 0.0 {
            coeffs.push((Pool::ONE, constant));
        }
        // Ordered by the coefficient-free part, so `a - b` and `b - a` list
        // their terms in the same order and differ only in signs.
        self.charge(coeffs.len() as u64);
        coeffs.sort_by_key(|&(rest, _)| rest);
        let children: Vec<ExprId> = coeffs
            .into_iter()
            .map(|(rest, c)| {
                if rest == Pool::ONE {
                    self.num(c)
                } else if c == 1.0 {
                    rest
                } else {
                    let c = self.num(c);
                    self.mul_raw_coeff(c, rest)
                }
            })
            .collect();
        match children.len() {
            0 => Pool::ZERO,
            1 => children[0],
            _ => self.intern(Node::Add(children.into_boxed_slice())),
        }
    }

    /// `c·R·sin²a + c·R·cos²a → c·R`: the identity that turns the kinetic
    /// energy of a rotating point, `(l cos θ θ̇)² + (l sin θ θ̇)²`, into `l²θ̇²`.
    /// Zeroes each matched pair in `coeffs` and returns the terms that replace
    /// them.
    fn pythagoras(
        &mut self,
        coeffs: &mut [(ExprId, f64)],
        slot: &HashMap<ExprId, usize>,
    ) -> Vec<ExprId> {
        let two = self.num(2.0);
        let mut freed = Vec::new();
        for k in 0..coeffs.len() {
            let (rest, c) = coeffs[k];
            if c == 0.0 {
                continue;
            }
            if self.exhausted() {
                break;
            }
            let factors: Vec<ExprId> = match self.node(rest) {
                Node::Mul(xs) => xs.to_vec(),
                _ => vec![rest],
            };
            self.charge(factors.len() as u64);
            for (pos, &f) in factors.iter().enumerate() {
                let Node::Pow(base, e) = *self.node(f) else {
                    continue;
                };
                if e != two {
                    continue;
                }
                let Node::Func(Func::Sin, arg) = *self.node(base) else {
                    continue;
                };
                // Only look the partner up: never create nodes here.
                let Some(cos) = self.lookup(&Node::Func(Func::Cos, arg)) else {
                    continue;
                };
                let Some(cos2) = self.lookup(&Node::Pow(cos, two)) else {
                    continue;
                };
                self.charge(2 * factors.len() as u64);
                let mut others: Vec<ExprId> = factors.clone();
                others.remove(pos);
                let mut partner_factors = others.clone();
                partner_factors.push(cos2);
                partner_factors.sort();
                let partner = if partner_factors.len() == 1 {
                    Some(partner_factors[0])
                } else {
                    self.lookup(&Node::Mul(partner_factors.into_boxed_slice()))
                };
                let Some(&j) = partner.and_then(|p| slot.get(&p)) else {
                    continue;
                };
                if coeffs[j].1 != c {
                    continue;
                }
                coeffs[k].1 = 0.0;
                coeffs[j].1 = 0.0;
                let cn = self.num(c);
                others.push(cn);
                freed.push(self.mul(&others));
                break;
            }
        }
        freed
    }

    /// `c * rest` where `rest` is already a canonical, coefficient-free term.
    fn mul_raw_coeff(&mut self, c: ExprId, rest: ExprId) -> ExprId {
        let mut xs = vec![c];
        match self.node(rest) {
            Node::Mul(fs) => xs.extend(fs.iter()),
            _ => xs.push(rest),
        }
        self.intern(Node::Mul(xs.into_boxed_slice()))
    }

    /// A product in canonical form.
    pub fn mul(&mut self, factors: &[ExprId]) -> ExprId {
        if self.exhausted() {
            return Pool::ZERO;
        }
        let mut coeff = 1.0;
        let mut powers: Vec<(ExprId, Vec<ExprId>)> = Vec::new();
        let mut slot: HashMap<ExprId, usize> = HashMap::new();
        let mut stack: Vec<ExprId> = factors.iter().rev().copied().collect();
        while let Some(f) = stack.pop() {
            self.charge(1);
            match self.node(f) {
                Node::Mul(xs) => {
                    stack.extend(xs.iter().rev());
                    continue;
                }
                Node::Num(bits) => {
                    coeff *= f64::from_bits(*bits);
                    continue;
                }
                _ => {}
            }
            let (mut base, exp) = self.split_pow(f);
            // A sum gives its content to the product, `0.5·m·(2a·x + 2b·x) =
            // m·x·(a + b)`, under any integer power: `(b − a)⁻¹ = −(a − b)⁻¹`,
            // so that `(a − b)²·(b − a)⁻¹` collects to `−(a − b)` and no
            // removable `0/0` is left where `a = b`. Not under a fractional
            // power, where the sign may not come out (`√(−x) ≠ −√x`).
            if let Some(n) = self
                .as_num(exp)
                .filter(|n| n.fract() == 0.0 && n.abs() < 1e9)
            {
                if let Some((k, common, inner)) = self.content(base) {
                    coeff *= k.powi(n as i32);
                    for c in common {
                        let p = self.pow(c, exp);
                        stack.push(p);
                    }
                    base = inner;
                }
            }
            if let Some(&k) = slot.get(&base) {
                powers[k].1.push(exp);
            } else {
                slot.insert(base, powers.len());
                powers.push((base, vec![exp]));
            }
        }
        if coeff == 0.0 {
            return Pool::ZERO;
        }
        let mut out: Vec<ExprId> = Vec::new();
        for (base, exps) in powers {
            let e = if exps.len() == 1 {
                exps[0]
            } else {
                self.add(&exps)
            };
            let p = self.pow(base, e);
            // Collecting may fold to a constant or a product (e.g. x²·x⁻² = 1).
            match self.node(p) {
                Node::Num(bits) => coeff *= f64::from_bits(*bits),
                Node::Mul(xs) => {
                    for &x in xs.iter() {
                        if let Some(c) = self.as_num(x) {
                            coeff *= c;
                        } else {
                            out.push(x);
                        }
                    }
                }
                _ => out.push(p),
            }
        }
        if coeff == 0.0 {
            return Pool::ZERO;
        }
        self.charge(2 * out.len() as u64);
        out.sort();
        // Two factors with the same base can reappear only if `pow` produced a
        // product; merge them through another pass in that rare case.
        let mut bases: Vec<ExprId> = out.iter().map(|&x| self.split_pow(x).0).collect();
        bases.sort();
        if bases.windows(2).any(|w| w[0] == w[1]) {
            let c = self.num(coeff);
            out.push(c);
            return self.mul(&out);
        }
        if out.is_empty() {
            return self.num(coeff);
        }
        if coeff == 1.0 && out.len() == 1 {
            return out[0];
        }
        if coeff != 1.0 {
            let c = self.num(coeff);
            out.insert(0, c);
        }
        self.intern(Node::Mul(out.into_boxed_slice()))
    }

    /// `base ^ exp` in canonical form.
    pub fn pow(&mut self, base: ExprId, exp: ExprId) -> ExprId {
        if self.exhausted() {
            return Pool::ZERO;
        }
        let e = self.as_num(exp);
        if e == Some(0.0) {
            return Pool::ONE;
        }
        if e == Some(1.0) {
            return base;
        }
        if let (Some(b), Some(e)) = (self.as_num(base), e) {
            let v = if e.fract() == 0.0 && e.abs() < 1e9 {
                b.powi(e as i32)
            } else {
                b.powf(e)
            };
            return self.num(v);
        }
        if base == Pool::ONE {
            return Pool::ONE;
        }
        if base == Pool::ZERO && e.is_some_and(|e| e > 0.0) {
            return Pool::ZERO;
        }
        let integer = e.is_some_and(|e| e.fract() == 0.0);
        match self.node(base).clone() {
            // (x^a)^n = x^(a n) for integer n.
            Node::Pow(b, a) if integer => {
                let an = self.mul2(a, exp);
                self.pow(b, an)
            }
            // (a b)^n = a^n b^n for integer n.
            Node::Mul(xs) if integer => {
                let parts: Vec<ExprId> = xs.iter().map(|&x| self.pow(x, exp)).collect();
                self.mul(&parts)
            }
            _ => self.intern(Node::Pow(base, exp)),
        }
    }

    /// `sqrt(a)`, as `a^0.5`.
    pub fn sqrt(&mut self, a: ExprId) -> ExprId {
        let half = self.num(0.5);
        self.pow(a, half)
    }

    /// Whether `a` is "negative" in the canonical sense: a negative constant,
    /// a product with a negative coefficient, or a sum whose first term is.
    fn is_negated(&self, a: ExprId) -> bool {
        match self.node(a) {
            Node::Num(bits) => f64::from_bits(*bits) < 0.0,
            Node::Mul(xs) => self.as_num(xs[0]).is_some_and(|c| c < 0.0),
            Node::Add(xs) => self.is_negated(xs[0]),
            _ => false,
        }
    }

    /// `f(a)`: folded for a constant, the sign pulled out of an odd or even
    /// function of a negated argument, `exp(ln x)` and `ln(exp x)` cancelled.
    pub fn func(&mut self, f: Func, a: ExprId) -> ExprId {
        if self.exhausted() {
            return Pool::ZERO;
        }
        if let Some(x) = self.as_num(a) {
            return self.num(f.apply(x));
        }
        let odd = matches!(
            f,
            Func::Sin | Func::Tan | Func::Asin | Func::Atan | Func::Sinh | Func::Tanh
        );
        let even = matches!(f, Func::Cos | Func::Cosh);
        if (odd || even) && self.is_negated(a) {
            let pos = self.neg(a);
            let inner = self.func(f, pos);
            return if odd { self.neg(inner) } else { inner };
        }
        match (f, self.node(a)) {
            (Func::Exp, Node::Func(Func::Ln, x)) => *x,
            (Func::Ln, Node::Func(Func::Exp, x)) => *x,
            _ => self.intern(Node::Func(f, a)),
        }
    }

    /// `atan2(y, x)`, folded for constants.
    pub fn atan2(&mut self, y: ExprId, x: ExprId) -> ExprId {
        if let (Some(a), Some(b)) = (self.as_num(y), self.as_num(x)) {
            return self.num(a.atan2(b));
        }
        self.intern(Node::Atan2(y, x))
    }
}
