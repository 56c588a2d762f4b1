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
            hi.saturating_add(1)
        } else {
            hi
        };
        if hi.saturating_sub(lo) > MAX_RANGE {
            return Err(r.range.error(format!(
                "this range has {} elements, more than the limit of {MAX_RANGE}: sums and indexed names are unrolled at compile time",
                hi.saturating_sub(lo)
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
    /// index variables.
    pub(super) fn int(&self, e: &Expr) -> syn::Result<i64> {
        let overflow = || e.range().error("index arithmetic overflows");
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
            Expr::Neg { inner, .. } => self.int(inner)?.checked_neg().ok_or_else(overflow),
            Expr::Binary { op, lhs, rhs, .. } => {
                let (a, b) = (self.int(lhs)?, self.int(rhs)?);
                match op {
                    BinOp::Add => a.checked_add(b).ok_or_else(overflow),
                    BinOp::Sub => a.checked_sub(b).ok_or_else(overflow),
                    BinOp::Mul => a.checked_mul(b).ok_or_else(overflow),
                    BinOp::Div if b != 0 && a % b == 0 => Ok(a / b),
                    BinOp::Div => Err(e.range().error(format!(
                        "{a}/{b} is not an integer: index arithmetic is exact"
                    ))),
                    BinOp::Pow => Err(e
                        .range()
                        .error("index arithmetic has `+`, `-`, `*` and exact `/`, not `^`")),
                }
            }
            _ => Err(e.range().error(
                "an index or a size must be integer arithmetic on integers, `const`s and index variables",
            )),
        }
    }
}
