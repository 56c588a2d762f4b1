//! The content of a sum: the numeric factor and the powers that every term
//! shares, pulled out so that products hold only primitive sums and an
//! entry of `M` is one product instead of a sum of many.

use super::{ExprId, Node, Pool};

impl Pool {
    /// `id` with the content of a sum pulled out, `Σ k·c·t_i = k·c·Σ t_i`:
    /// for a result that is evaluated, not added to further (an entry of
    /// `M`). Sums stay expanded inside the derivation so that terms can
    /// cancel; an entry `M_ab = Σ_{i ≥ b} m_i·l_a·l_b·P_ab` of a chain is
    /// then one product with the tail `Σ_{i ≥ b} m_i`, shared by every entry
    /// with the same tail, instead of a sum of N − b products.
    pub fn factored(&mut self, id: ExprId) -> ExprId {
        if self.exhausted() {
            return Pool::ZERO;
        }
        match self.content(id) {
            None => id,
            Some((k, common, inner)) => {
                let mut factors = vec![self.num(k)];
                factors.extend(common);
                factors.push(inner);
                self.mul(&factors)
            }
        }
    }

    /// The content of a sum: `sum = k · c1^e1 ⋯ · s`, where the `c` are the
    /// factors every term shares, `k` the shared coefficient magnitude (if all
    /// are equal) times the first term's sign, and `s` the primitive part.
    /// `None` if there is nothing to pull out. Memoized per sum.
    ///
    /// Products hold only primitive sums, so `-m·(a·x − b·x)` and
    /// `m·x·(b − a)` are one node and cancel in an enclosing sum.
    pub(super) fn content(&mut self, id: ExprId) -> Option<(f64, Vec<ExprId>, ExprId)> {
        let Node::Add(xs) = self.node(id) else {
            return None;
        };
        if let Some(c) = self.content_memo.get(&id) {
            return c.clone();
        }
        if self.exhausted() {
            return None;
        }
        let xs = xs.to_vec();
        let parts: Vec<(f64, ExprId)> = xs.iter().map(|&x| self.split_coeff(x)).collect();
        let sign = parts[0].0.signum();
        let mag = parts[0].0.abs();
        let k = if parts.iter().all(|(c, _)| c.abs() == mag) {
            sign * mag
        } else {
            sign
        };
        // Bases every term holds, with the smallest positive numeric exponent.
        let factor_lists: Vec<Vec<(ExprId, ExprId)>> = parts
            .iter()
            .map(|&(_, rest)| {
                let fs = match self.node(rest) {
                    Node::Mul(fs) => fs.to_vec(),
                    _ if rest == Pool::ONE => Vec::new(),
                    _ => vec![rest],
                };
                fs.into_iter().map(|f| self.split_pow(f)).collect()
            })
            .collect();
        self.charge(factor_lists.iter().map(|fs| 1 + fs.len() as u64).sum());
        let mut common: Vec<(ExprId, f64)> = Vec::new();
        for &(base, e) in &factor_lists[0] {
            if self.exhausted() {
                return None;
            }
            let Some(mut min) = self.as_num(e).filter(|&v| v > 0.0) else {
                continue;
            };
            // Looked for in every other term: comparisons of ids, 16 a step.
            let mut compared = 0u64;
            let everywhere = factor_lists[1..].iter().all(|fs| {
                fs.iter().any(|&(b, e2)| {
                    compared += 1;
                    b == base
                        && self.as_num(e2).is_some_and(|v| {
                            min = min.min(v);
                            v > 0.0
                        })
                })
            });
            self.charge(compared / 16);
            if everywhere {
                common.push((base, min));
            }
        }
        let result = if k == 1.0 && common.is_empty() {
            None
        } else {
            let common: Vec<ExprId> = common
                .into_iter()
                .map(|(b, e)| {
                    let e = self.num(e);
                    self.pow(b, e)
                })
                .collect();
            let inv_k = self.num(1.0 / k);
            let mut divisor: Vec<ExprId> = vec![inv_k];
            for &c in &common {
                let m1 = self.num(-1.0);
                divisor.push(self.pow(c, m1));
            }
            let terms: Vec<ExprId> = xs
                .iter()
                .map(|&x| {
                    let mut fs = divisor.clone();
                    fs.push(x);
                    self.mul(&fs)
                })
                .collect();
            Some((k, common, self.add(&terms)))
        };
        self.content_memo.insert(id, result.clone());
        result
    }
}
