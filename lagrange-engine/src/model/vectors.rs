//! Vectors: 3D kinematics written as a textbook writes it. A vector is a
//! list of scalar nodes, lowered component by component: `vector(a, b, c)`,
//! an indexed name written bare (`theta`, `r` of `let r[i in 0..3]`), and a
//! `let` of a vector (`let r = vector(..)`, bound like an indexed `let`, so
//! `r[0]` is its first component). `+`, `-`, a product or quotient with a
//! number and `dot` act on each component; the functions below are the
//! rest. Nothing of this reaches the DAG: it holds the components only.

use super::lowering::Lowering;
use crate::ast::{Expr, SpanRange};
use crate::expr::ExprId;

/// A lowered expression: a number, or a vector of numbers.
#[derive(Clone, Debug)]
pub(super) enum Value {
    Scalar(ExprId),
    Vector(Vec<ExprId>),
}

/// The functions of vectors, with their arity (`vector` takes any number of
/// components, at least one). Each is in [`FUNCTIONS`](super::FUNCTIONS)
/// too, for the list an unknown function's error gives.
pub const VECTOR_FUNCTIONS: &[&str] = &[
    "vector",
    "cross",
    "inner",
    "norm",
    "rotate",
    "rotate_x",
    "rotate_y",
    "rotate_z",
    "body_rates",
    "space_rates",
];

/// "a number" or "a vector of 3 components", for errors.
pub(super) fn describe(v: &Value) -> String {
    match v {
        Value::Scalar(_) => "a number".to_string(),
        Value::Vector(c) => format!("a vector of {} components", c.len()),
    }
}

impl Lowering {
    /// The vector functions, their arguments lowered: `name` is one of
    /// [`VECTOR_FUNCTIONS`], its arity already checked.
    pub(super) fn lower_vector_call(
        &mut self,
        name: &str,
        range: SpanRange,
        args: &[Expr],
        values: Vec<Value>,
    ) -> syn::Result<Value> {
        Ok(match name {
            "vector" => {
                let mut out = Vec::with_capacity(values.len());
                for (v, a) in values.into_iter().zip(args) {
                    match v {
                        Value::Scalar(x) => out.push(x),
                        v => {
                            return Err(a.range().error(format!(
                                "a component of `vector` is {}: each component is a number",
                                describe(&v)
                            )));
                        }
                    }
                }
                Value::Vector(out)
            }
            "inner" => {
                let (a, b) = same_length(name, args, values)?;
                let p = &mut self.pool;
                let terms: Vec<ExprId> = a.iter().zip(&b).map(|(&x, &y)| p.mul2(x, y)).collect();
                Value::Scalar(p.add(&terms))
            }
            "norm" => {
                let a = vector_arg(name, &args[0], &values[0], None, "its argument")?;
                let p = &mut self.pool;
                let squares: Vec<ExprId> = a.iter().map(|&x| p.mul2(x, x)).collect();
                let sum = p.add(&squares);
                Value::Scalar(p.sqrt(sum))
            }
            "cross" => {
                let a = vector_arg(name, &args[0], &values[0], Some(3), "its first argument")?;
                let b = vector_arg(name, &args[1], &values[1], Some(3), "its second argument")?;
                Value::Vector(self.cross(&a, &b))
            }
            "rotate" => {
                let q = quaternion_arg(name, &args[0], &values[0])?;
                let v = vector_arg(name, &args[1], &values[1], Some(3), "the vector it rotates")?;
                // v + 2w (u × v) + 2 u × (u × v), u = (x, y, z): the rotation
                // of a unit quaternion (a constraint keeps |q| = 1).
                let u = [q[1], q[2], q[3]];
                let uv = self.cross(&u, &v);
                let uuv = self.cross(&u, &uv);
                let p = &mut self.pool;
                let two = p.num(2.0);
                let two_w = p.mul2(two, q[0]);
                Value::Vector(
                    (0..3)
                        .map(|i| {
                            let a = p.mul2(two_w, uv[i]);
                            let b = p.mul2(two, uuv[i]);
                            p.add(&[v[i], a, b])
                        })
                        .collect(),
                )
            }
            "rotate_x" | "rotate_y" | "rotate_z" => {
                let Value::Scalar(angle) = values[0] else {
                    return Err(args[0].range().error(format!(
                        "`{name}` takes the angle first, a number; it is {}",
                        describe(&values[0])
                    )));
                };
                let v = vector_arg(name, &args[1], &values[1], Some(3), "the vector it rotates")?;
                // The right-handed rotation by `angle` about the axis: the
                // other two components (i, j) turn, i towards j.
                let (i, j) = match name {
                    "rotate_x" => (1, 2),
                    "rotate_y" => (2, 0),
                    _ => (0, 1),
                };
                let p = &mut self.pool;
                let c = p.func(crate::expr::Func::Cos, angle);
                let s = p.func(crate::expr::Func::Sin, angle);
                let mut out = v.clone();
                let (ci, si) = (p.mul2(c, v[i]), p.mul2(s, v[i]));
                let (cj, sj) = (p.mul2(c, v[j]), p.mul2(s, v[j]));
                out[i] = p.sub(ci, sj);
                out[j] = p.add2(si, cj);
                Value::Vector(out)
            }
            "body_rates" | "space_rates" => {
                let q = quaternion_arg(name, &args[0], &values[0])?;
                let qd = q
                    .iter()
                    .map(|&x| self.time_derivative(x, range))
                    .collect::<syn::Result<Vec<_>>>()?;
                // 2 Im(q̄ q̇) = 2 (w u̇ − ẇ u − u × u̇) in the body,
                // 2 Im(q̇ q̄) = 2 (w u̇ − ẇ u + u × u̇) in space.
                let (u, ud) = ([q[1], q[2], q[3]], [qd[1], qd[2], qd[3]]);
                let uxud = self.cross(&u, &ud);
                let p = &mut self.pool;
                let two = p.num(2.0);
                Value::Vector(
                    (0..3)
                        .map(|i| {
                            let a = p.mul2(q[0], ud[i]);
                            let b = p.mul2(qd[0], u[i]);
                            let ab = p.sub(a, b);
                            let sum = if name == "body_rates" {
                                p.sub(ab, uxud[i])
                            } else {
                                p.add2(ab, uxud[i])
                            };
                            p.mul2(two, sum)
                        })
                        .collect(),
                )
            }
            _ => unreachable!("every name in VECTOR_FUNCTIONS is handled"),
        })
    }

    /// a × b of two vectors of 3 components.
    fn cross(&mut self, a: &[ExprId], b: &[ExprId]) -> Vec<ExprId> {
        let p = &mut self.pool;
        (0..3)
            .map(|i| {
                let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                let x = p.mul2(a[j], b[k]);
                let y = p.mul2(a[k], b[j]);
                p.sub(x, y)
            })
            .collect()
    }

    /// `a op b` of two values: component by component for vectors of one
    /// length, a vector times or over a number; an error on `range` (the
    /// operation's operands) for anything else.
    pub(super) fn combine_values(
        &mut self,
        op: crate::ast::BinOp,
        a: Value,
        b: Value,
        range: SpanRange,
    ) -> syn::Result<Value> {
        use crate::ast::BinOp;
        Ok(match (a, b) {
            (Value::Scalar(x), Value::Scalar(y)) => Value::Scalar(self.combine(op, x, y)),
            (Value::Vector(x), Value::Vector(y)) if matches!(op, BinOp::Add | BinOp::Sub) => {
                if x.len() != y.len() {
                    return Err(range.error(format!(
                        "{} vectors of {} and {} components: a sum or difference of vectors takes two of one length",
                        if op == BinOp::Add { "adds" } else { "subtracts" },
                        x.len(),
                        y.len()
                    )));
                }
                Value::Vector(x.iter().zip(&y).map(|(&a, &b)| self.combine(op, a, b)).collect())
            }
            (Value::Vector(_), Value::Vector(_)) => {
                return Err(range.error(if op == BinOp::Mul {
                    "a product of two vectors: write `inner(a, b)` for the scalar product or `cross(a, b)` for the vector product"
                } else {
                    "a quotient of two vectors: a vector may be divided by a number only"
                }))
            }
            (Value::Scalar(s), Value::Vector(v)) if op == BinOp::Mul => {
                Value::Vector(v.iter().map(|&x| self.combine(op, s, x)).collect())
            }
            (Value::Vector(v), Value::Scalar(s)) if matches!(op, BinOp::Mul | BinOp::Div) => {
                Value::Vector(v.iter().map(|&x| self.combine(op, x, s)).collect())
            }
            (a, b) => {
                let verb = match op {
                    BinOp::Add => "adds",
                    BinOp::Sub => "subtracts",
                    BinOp::Mul => "multiplies",
                    BinOp::Div => "divides",
                };
                return Err(range.error(format!(
                    "this {verb} {} and {}: a vector adds to or subtracts from a vector of its length, \
                     and is multiplied or divided by a number",
                    describe(&a),
                    describe(&b)
                )));
            }
        })
    }
}

/// The components of argument `arg` of `name`, a vector (of `len`
/// components, where given); `what` names the argument for the error.
fn vector_arg(
    name: &str,
    arg: &Expr,
    value: &Value,
    len: Option<usize>,
    what: &str,
) -> syn::Result<Vec<ExprId>> {
    match (value, len) {
        (Value::Vector(c), Some(n)) if c.len() == n => Ok(c.clone()),
        (Value::Vector(c), None) => Ok(c.clone()),
        (v, Some(n)) => Err(arg.range().error(format!(
            "`{name}` takes a vector of {n} components as {what}; this is {}",
            describe(v)
        ))),
        (v, None) => Err(arg
            .range()
            .error(format!("`{name}` takes a vector; this is {}", describe(v)))),
    }
}

/// The quaternion `(w, x, y, z)` that `name` takes first.
fn quaternion_arg(name: &str, arg: &Expr, value: &Value) -> syn::Result<Vec<ExprId>> {
    vector_arg(name, arg, value, Some(4), "the quaternion `(w, x, y, z)`")
}

/// The two arguments of `name`, vectors of one length.
fn same_length(
    name: &str,
    args: &[Expr],
    mut values: Vec<Value>,
) -> syn::Result<(Vec<ExprId>, Vec<ExprId>)> {
    let b = values.pop().expect("two arguments");
    let a = values.pop().expect("two arguments");
    let a = vector_arg(name, &args[0], &a, None, "its first argument")?;
    let b = vector_arg(
        name,
        &args[1],
        &b,
        Some(a.len()),
        "its second argument, as long as its first",
    )?;
    Ok((a, b))
}
