//! Compile-time integer arithmetic: sizes (`theta[N]`), indices (`x[i-1]`)
//! and ranges (`i in 0..N`), on integers, `const`s and index variables.

use super::lowering::Lowering;
use super::scope::Binding;
use crate::ast::{BinOp, Expr, IndexRange};

/// The most elements an index range or an indexed name may have: sums are
/// unrolled at compile time, and a size this large is a typo, not a model.
pub const MAX_RANGE: i64 = 10_000;

impl Lowering {
    /// `lo..hi` (or `lo..=hi`) as a half-open integer range.
    pub(super) fn range(&self, r: &IndexRange) -> syn::Result<(i64, i64)> {
        let lo = self.int(&r.lo)?;
        let hi = self.int(&r.hi)?;
        let hi = if r.inclusive {
            hi.checked_add(1).ok_or_else(|| {
                r.hi.range()
                    .error(format!("index arithmetic overflows: {hi} + 1 (the end of `..=`) is not a 64-bit integer"))
            })?
        } else {
            hi
        };
        // In i128, where the difference of two i64 cannot overflow.
        let count = i128::from(hi) - i128::from(lo);
        if count > i128::from(MAX_RANGE) {
            return Err(r.range.error(format!(
                "this range has {count} elements, more than the limit of {MAX_RANGE}: sums and indexed names are unrolled at compile time"
            )));
        }
        Ok((lo, hi.max(lo)))
    }

    /// The length of `name[len]`.
    pub(super) fn length(&self, e: &Expr) -> syn::Result<usize> {
        let n = self.int(e)?;
        if n < 1 {
            return Err(e.range().error(format!(
                "length {n}: an indexed name needs at least one element"
            )));
        }
        if n > MAX_RANGE {
            return Err(e.range().error(format!(
                "length {n} is more than the limit of {MAX_RANGE}: every element is unrolled at compile time"
            )));
        }
        Ok(n as usize)
    }

    /// An index or a size: integer arithmetic on integers, `const`s and
    /// index variables, in 64-bit integers, every step checked.
    pub(super) fn int(&self, e: &Expr) -> syn::Result<i64> {
        match e {
            Expr::Num { value, .. } => {
                if value.fract() != 0.0 {
                    Err(e.range().error(format!(
                        "`{value}` is not an integer: indices and sizes are integers"
                    )))
                } else if value.abs() > i32::MAX as f64 {
                    Err(e.range().error(format!(
                        "`{value}` is too large for an index or a size"
                    )))
                } else {
                    Ok(*value as i64)
                }
            }
            Expr::Name(name) => {
                let s = name.to_string();
                if let Some(&(_, k)) = self.env.iter().rev().find(|(v, _)| *v == s) {
                    return Ok(k);
                }
                match self.names.get(&s) {
                    Some(Binding::Const(v)) => Ok(*v),
                    Some(_) => Err(syn::Error::new(
                        name.span(),
                        format!(
                            "`{s}` is not a compile-time integer: indices and sizes use integers, `const`s and index variables"
                        ),
                    )),
                    None => Err(syn::Error::new(
                        name.span(),
                        format!(
                            "unknown name `{s}` in an index: declare it with `const {s} = ...;` or bind it in a range (`{s} in 0..N`)"
                        ),
                    )),
                }
            }
            Expr::Neg { inner, .. } => {
                let a = self.int(inner)?;
                a.checked_neg().ok_or_else(|| overflows(e, format!("-({a})")))
            }
            Expr::Chain { first, rest, .. } => {
                let mut a = self.int(first)?;
                for (op, x) in rest {
                    let b = self.int(x)?;
                    // The step's own text: from the chain's start to `x`.
                    let step = first.range().to(x.range());
                    a = match op {
                        BinOp::Add => a.checked_add(b).ok_or((a, "+", b)),
                        BinOp::Sub => a.checked_sub(b).ok_or((a, "-", b)),
                        BinOp::Mul => a.checked_mul(b).ok_or((a, "*", b)),
                        BinOp::Div if b == 0 || a.checked_rem(b).is_some_and(|r| r != 0) => {
                            return Err(step.error(format!(
                                "{a}/{b} is not an integer: index arithmetic is exact"
                            )))
                        }
                        BinOp::Div => a.checked_div(b).ok_or((a, "/", b)),
                    }
                    .map_err(|(a, op, b)| {
                        step.error(format!(
                            "index arithmetic overflows: {a} {op} {b} is not a 64-bit integer"
                        ))
                    })?;
                }
                Ok(a)
            }
            Expr::Power { .. } => Err(e
                .range()
                .error("index arithmetic has `+`, `-`, `*` and exact `/`, not `^`")),
            _ => Err(e.range().error(
                "an index or a size must be integer arithmetic on integers, `const`s and index variables",
            )),
        }
    }
}

fn overflows(e: &Expr, what: String) -> syn::Error {
    e.range().error(format!(
        "index arithmetic overflows: {what} is not a 64-bit integer"
    ))
}
