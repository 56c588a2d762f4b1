//! The functions a model may call, and their lowering.

use super::lowering::Lowering;
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
    /// time derivative.
    pub(super) fn lower_call(
        &mut self,
        func: &Ident,
        range: SpanRange,
        args: &[Expr],
    ) -> syn::Result<ExprId> {
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
        if args.len() != arity {
            let plural = if arity == 1 { "" } else { "s" };
            return Err(range.error(format!(
                "`{name}` takes {arity} argument{plural}, found {}",
                args.len()
            )));
        }
        let xs = args
            .iter()
            .map(|a| self.lower(a))
            .collect::<syn::Result<Vec<_>>>()?;
        let p = &mut self.pool;
        Ok(match name.as_str() {
            "dot" => {
                if self
                    .symbols
                    .velocities
                    .iter()
                    .any(|&v| p.depends_on(xs[0], v))
                {
                    return Err(range.error(
                        "`dot` of an expression that already holds a velocity: the model is written in positions and velocities, accelerations are not allowed",
                    ));
                }
                // An input is set from outside at each instant and has no
                // time derivative the model could know: `dot` would silently
                // take it as constant.
                if let Some(&u) = self
                    .symbols
                    .inputs
                    .iter()
                    .find(|&&u| p.depends_on(xs[0], u))
                {
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
                p.total_time_derivative(xs[0], &s.coordinates, &s.velocities, s.time)
            }
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
        })
    }
}
