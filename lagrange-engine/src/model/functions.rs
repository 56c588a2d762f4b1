//! The functions a model may call, and their lowering.

use super::lowering::Lowering;
use super::vectors::{VECTOR_FUNCTIONS, Value, describe};
use crate::ast::{Expr, SpanRange};
use crate::expr::{ExprId, Func};
use syn::Ident;

/// The functions the DSL knows, with their arity.
pub const FUNCTIONS: &[(&str, usize)] = &[
    ("sin", 1),
    ("cos", 1),
    ("tan", 1),
    ("asin", 1),
    ("acos", 1),
    ("atan", 1),
    ("atan2", 2),
    ("sinh", 1),
    ("cosh", 1),
    ("tanh", 1),
    ("exp", 1),
    ("ln", 1),
    ("sqrt", 1),
    ("powi", 2),
    ("powf", 2),
    ("dot", 1),
    // Vectors (`vectors.rs`); `vector` takes any number of components.
    ("vector", 0),
    ("cross", 2),
    ("inner", 2),
    ("norm", 1),
    ("rotate", 2),
    ("rotate_x", 2),
    ("rotate_y", 2),
    ("rotate_z", 2),
    ("body_rates", 1),
    ("space_rates", 1),
];

fn function_list() -> String {
    FUNCTIONS
        .iter()
        .map(|(f, _)| format!("`{f}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

impl Lowering {
    /// `f(args)`: the arity checked, the arguments lowered, `dot` the total
    /// time derivative (of each component, for a vector), the vector
    /// functions by `vectors.rs`.
    pub(super) fn lower_call(
        &mut self,
        func: &Ident,
        range: SpanRange,
        args: &[Expr],
    ) -> syn::Result<Value> {
        let name = func.to_string();
        let Some(&(_, arity)) = FUNCTIONS.iter().find(|(f, _)| *f == name) else {
            return Err(syn::Error::new(
                func.span(),
                format!(
                    "unknown function `{name}`: the model may use {}",
                    function_list()
                ),
            ));
        };
        if name == "vector" {
            if args.is_empty() {
                return Err(
                    range.error("`vector` takes its components, at least one: `vector(x, y, z)`")
                );
            }
        } else if args.len() != arity {
            let plural = if arity == 1 { "" } else { "s" };
            return Err(range.error(format!(
                "`{name}` takes {arity} argument{plural}, found {}",
                args.len()
            )));
        }
        let values = args
            .iter()
            .map(|a| self.lower_value(a))
            .collect::<syn::Result<Vec<_>>>()?;
        if VECTOR_FUNCTIONS.contains(&name.as_str()) {
            return self.lower_vector_call(&name, range, args, values);
        }
        if name == "dot" {
            return Ok(match &values[0] {
                Value::Scalar(x) => Value::Scalar(self.time_derivative(*x, range)?),
                Value::Vector(c) => Value::Vector(
                    c.iter()
                        .map(|&x| self.time_derivative(x, range))
                        .collect::<syn::Result<_>>()?,
                ),
            });
        }
        let mut xs = Vec::with_capacity(values.len());
        for (v, a) in values.iter().zip(args) {
            match v {
                Value::Scalar(x) => xs.push(*x),
                v => {
                    return Err(self.bare_array_in(a).unwrap_or_else(|| {
                        a.range().error(format!(
                        "`{name}` takes a number; this is {}: apply it to one component (`r[0]`), \
                             or to `norm(r)` or `inner(a, b)`",
                        describe(v)
                    ))
                    }));
                }
            }
        }
        let p = &mut self.pool;
        Ok(Value::Scalar(match name.as_str() {
            "sqrt" => p.sqrt(xs[0]),
            "atan2" => p.atan2(xs[0], xs[1]),
            "powi" | "powf" => p.pow(xs[0], xs[1]),
            f => {
                let func = match f {
                    "sin" => Func::Sin,
                    "cos" => Func::Cos,
                    "tan" => Func::Tan,
                    "asin" => Func::Asin,
                    "acos" => Func::Acos,
                    "atan" => Func::Atan,
                    "sinh" => Func::Sinh,
                    "cosh" => Func::Cosh,
                    "tanh" => Func::Tanh,
                    "exp" => Func::Exp,
                    "ln" => Func::Ln,
                    _ => unreachable!("every name in FUNCTIONS is handled"),
                };
                p.func(func, xs[0])
            }
        }))
    }

    /// `dot(x)` of a scalar node: the total time derivative, refused where
    /// `x` already holds a velocity or an input.
    pub(super) fn time_derivative(&mut self, x: ExprId, range: SpanRange) -> syn::Result<ExprId> {
        let p = &mut self.pool;
        if self.symbols.velocities.iter().any(|&v| p.depends_on(x, v)) {
            return Err(range.error(
                "`dot` of an expression that already holds a velocity: the model is written in positions and velocities, accelerations are not allowed",
            ));
        }
        // An input is set from outside at each instant and has no
        // time derivative the model could know: `dot` would silently
        // take it as constant.
        if let Some(&u) = self.symbols.inputs.iter().find(|&&u| p.depends_on(x, u)) {
            let name = self
                .names
                .iter()
                .find(|(_, b)| matches!(b, super::scope::Binding::Symbol(s) if *s == u))
                .map_or_else(String::new, |(n, _)| n.clone());
            return Err(range.error(format!(
                "`dot` of an expression that holds the input `{name}`: an input is set from outside at each \
                 instant and has no time derivative the model could know; use inputs in forces, \
                 potentials and `let`s, not under `dot`"
            )));
        }
        let s = &self.symbols;
        Ok(p.total_time_derivative(x, &s.coordinates, &s.velocities, s.time))
    }
}
