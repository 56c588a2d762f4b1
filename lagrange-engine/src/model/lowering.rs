//! Expressions → DAG nodes: names resolved, indices evaluated, sums
//! unrolled, every node built through the pool's simplifying constructors.

use super::functions::FUNCTIONS;
use super::scope::{Binding, Role};
use super::vectors::{Value, describe};
use super::{SymKind, Symbols, limit_error};
use crate::ast::{BinOp, Expr};
use crate::expr::{Exceeded, ExprId, MAX_DEPTH, Pool};
use std::collections::{HashMap, HashSet};
use syn::Ident;

/// The state of lowering: the pool, the names bound so far, the index
/// variables in scope.
pub(super) struct Lowering {
    pub(super) pool: Pool,
    pub(super) symbols: Symbols,
    pub(super) names: HashMap<String, Binding>,
    /// The `let`s not lowered yet, to tell "used before its `let`" from
    /// "unknown".
    pub(super) pending_lets: HashSet<String>,
    /// The index variables in scope, innermost last.
    pub(super) env: Vec<(String, i64)>,
    /// The model's name, for the budget error.
    pub(super) model: Ident,
}

impl Lowering {
    /// A lowering with no names yet: the `const`s come first.
    pub(super) fn new(pool: Pool, model: &Ident) -> Self {
        Lowering {
            pool,
            symbols: Symbols::new(0, 0, 0),
            names: HashMap::new(),
            pending_lets: HashSet::new(),
            env: Vec::new(),
            model: model.clone(),
        }
    }

    /// The node of `e`. Stops at the first error, or once the pool is
    /// exhausted: a node too deep is an error on the smallest expression
    /// that built it.
    pub(super) fn lower(&mut self, e: &Expr) -> syn::Result<ExprId> {
        if let Expr::Name(name) = e {
            if let Some(error) = self.array_written_bare(name) {
                return Err(error);
            }
        }
        match self.lower_value(e)? {
            Value::Scalar(id) => Ok(id),
            v => Err(self.bare_array_in(e).unwrap_or_else(|| {
                e.range().error(format!(
                    "this is {} where a number is needed: take one component (`r[0]`), \
                 or `inner(a, b)` or `norm(r)`",
                    describe(&v)
                ))
            })),
        }
    }

    /// The error of the first indexed name written bare in `e`, if any:
    /// where a vector stands where a number is needed, the name that made
    /// it a vector is most often the mistake (`dot(theta)^2` for
    /// `dot(theta[i])^2`), unless it is a `let` of a vector.
    pub(super) fn bare_array_in(&self, e: &Expr) -> Option<syn::Error> {
        if let Expr::Name(name) = e {
            // A `let` of a vector is meant as one: the operation is the
            // mistake, and its own error says which.
            if let Some(Binding::Array {
                role: Role::Vector, ..
            }) = self.names.get(&name.to_string())
            {
                return None;
            }
            return self.array_written_bare(name);
        }
        e.children().into_iter().find_map(|c| self.bare_array_in(c))
    }

    /// The value of `e`, a number or a vector (`vectors.rs`).
    pub(super) fn lower_value(&mut self, e: &Expr) -> syn::Result<Value> {
        // Names are strings to look up: a lowering costs a few steps.
        self.pool.charge(2);
        let id = self.lower_node(e)?;
        match self.pool.check_budget() {
            Ok(()) => Ok(id),
            Err(Exceeded::Depth) => Err(e.range().error(format!(
                "this expression nests more than {MAX_DEPTH} levels deep, counting the `let`s it uses: \
                 write the model with fewer nested `let`s and functions"
            ))),
            Err(x) => Err(limit_error(&self.model, x)),
        }
    }

    fn lower_node(&mut self, e: &Expr) -> syn::Result<Value> {
        let scalar = Value::Scalar;
        Ok(match e {
            Expr::Num { value, .. } => scalar(self.pool.num(*value)),
            Expr::Name(name) => {
                let s = name.to_string();
                if let Some(&(_, k)) = self.env.iter().rev().find(|(v, _)| *v == s) {
                    return Ok(scalar(self.pool.num(k as f64)));
                }
                match self.names.get(&s) {
                    Some(Binding::Symbol(s)) => scalar(self.pool.sym(*s)),
                    Some(Binding::Let(id)) => scalar(*id),
                    Some(Binding::Const(v)) => scalar(self.pool.num(*v as f64)),
                    // An indexed name written bare is the vector of its
                    // elements, once they are all defined.
                    Some(&Binding::Array { lo, hi, .. }) if hi > lo => {
                        let mut components = Vec::new();
                        for k in lo..hi {
                            match self.names.get(&format!("{s}[{k}]")) {
                                Some(Binding::Symbol(x)) => components.push(self.pool.sym(*x)),
                                Some(Binding::Let(id)) => components.push(*id),
                                _ => return Err(self.array_written_bare(name).expect("an array")),
                            }
                        }
                        Value::Vector(components)
                    }
                    Some(Binding::Array { .. }) => {
                        return Err(self.array_written_bare(name).expect("an array"));
                    }
                    None => return Err(self.unknown_name(name)),
                }
            }
            Expr::Index { base, index, .. } => match self.element(base, index)?.1 {
                Binding::Symbol(s) => scalar(self.pool.sym(s)),
                Binding::Let(id) => scalar(id),
                _ => unreachable!("elements are symbols or lets"),
            },
            Expr::Sum { index, body, .. } => {
                let (lo, hi) = self.range(index)?;
                let mut terms = Vec::new();
                for k in lo..hi {
                    self.env.push((index.var.to_string(), k));
                    let term = self.lower_value(body);
                    self.env.pop();
                    terms.push(term?);
                }
                match terms.first() {
                    Some(Value::Vector(first)) => {
                        let n = first.len();
                        let mut columns = vec![Vec::with_capacity(terms.len()); n];
                        for t in &terms {
                            match t {
                                Value::Vector(c) if c.len() == n => {
                                    for (column, &x) in columns.iter_mut().zip(c) {
                                        column.push(x);
                                    }
                                }
                                t => {
                                    return Err(self.bare_array_in(body).unwrap_or_else(|| body.range().error(format!(
                                        "the terms of this sum are {} and {}: a sum adds numbers, or vectors of one length",
                                        describe(&terms[0]),
                                        describe(t)
                                    ))))
                                }
                            }
                        }
                        Value::Vector(columns.iter().map(|c| self.pool.add(c)).collect())
                    }
                    _ => {
                        let mut scalars = Vec::with_capacity(terms.len());
                        for t in &terms {
                            match t {
                                Value::Scalar(x) => scalars.push(*x),
                                t => {
                                    return Err(self.bare_array_in(body).unwrap_or_else(|| body.range().error(format!(
                                        "the terms of this sum are {} and {}: a sum adds numbers, or vectors of one length",
                                        describe(&terms[0]),
                                        describe(t)
                                    ))))
                                }
                            }
                        }
                        scalar(self.pool.add(&scalars))
                    }
                }
            }
            Expr::Neg { inner, .. } => match self.lower_value(inner)? {
                Value::Scalar(x) => scalar(self.pool.neg(x)),
                Value::Vector(c) => Value::Vector(c.iter().map(|&x| self.pool.neg(x)).collect()),
            },
            Expr::Chain { first, rest, .. } => {
                let mut acc = self.lower_value(first)?;
                for (op, x) in rest {
                    let b = self.lower_value(x)?;
                    acc = self
                        .combine_values(*op, acc, b, first.range().to(x.range()))
                        .map_err(|error| self.bare_array_in(e).unwrap_or(error))?;
                }
                acc
            }
            Expr::Power { base, exponent, .. } => {
                let a = match self.lower_value(base)? {
                    Value::Scalar(a) => a,
                    v => {
                        return Err(self.bare_array_in(base).unwrap_or_else(|| {
                            base.range().error(format!(
                                "a power of {}: |r|² is `inner(r, r)`, |r| is `norm(r)`",
                                describe(&v)
                            ))
                        }));
                    }
                };
                let b = self.lower(exponent)?;
                scalar(self.pool.pow(a, b))
            }
            Expr::Call { func, range, args } => self.lower_call(func, *range, args)?,
        })
    }

    /// The error of an indexed name written bare where a number is needed
    /// (or whose elements are not all defined yet); `None` where `name` is
    /// not an indexed name.
    fn array_written_bare(&self, name: &Ident) -> Option<syn::Error> {
        let s = name.to_string();
        if self.env.iter().any(|(v, _)| *v == s) {
            return None;
        }
        match self.names.get(&s) {
            Some(Binding::Array { lo, hi, role }) => {
                let role = match role {
                    Role::Coordinate => "an indexed coordinate",
                    Role::Parameter => "an indexed parameter",
                    Role::Input => "an indexed input",
                    Role::Let => "an indexed `let`",
                    Role::Vector => {
                        return Some(syn::Error::new(
                            name.span(),
                            format!(
                                "`{s}` is a vector ({}) where a number is needed: write one component, \
                                 e.g. `{s}[{lo}]`, or a number made of it, `inner({s}, {s})` or `norm({s})`",
                                elements(&s, *lo, *hi)
                            ),
                        ));
                    }
                };
                let message = if hi > lo {
                    let example = match self.env.last() {
                        None => format!("`{s}[{lo}]`"),
                        Some((var, _)) => format!("`{s}[{var}]`"),
                    };
                    format!(
                        "`{s}` is {role} ({}): write one element, e.g. {example}",
                        elements(&s, *lo, *hi)
                    )
                } else {
                    format!("`{s}` is {role} with no elements (its range `{lo}..{hi}` is empty)")
                };
                Some(syn::Error::new(name.span(), message))
            }
            _ => None,
        }
    }

    /// `a op b`, one step of a chain.
    pub(super) fn combine(&mut self, op: BinOp, a: ExprId, b: ExprId) -> ExprId {
        match op {
            BinOp::Add => self.pool.add2(a, b),
            BinOp::Sub => self.pool.sub(a, b),
            BinOp::Mul => self.pool.mul2(a, b),
            BinOp::Div => self.pool.div(a, b),
        }
    }

    /// The index of `base[index]`, checked against its range, and the
    /// element's binding.
    pub(super) fn element(&self, base: &Ident, index: &Expr) -> syn::Result<(i64, Binding)> {
        let s = base.to_string();
        let (lo, hi) = match self.names.get(&s) {
            Some(Binding::Array { lo, hi, .. }) => (*lo, *hi),
            Some(Binding::Const(_)) => {
                return Err(syn::Error::new(
                    base.span(),
                    format!("`{s}` is a `const`, not indexed: write `{s}`"),
                ));
            }
            Some(_) => {
                return Err(syn::Error::new(
                    base.span(),
                    format!("`{s}` is not indexed: write `{s}` (declare `{s}[N]` to index it)"),
                ));
            }
            None => return Err(self.unknown_name(base)),
        };
        let k = self.int(index)?;
        if k < lo || k >= hi {
            let has = if hi > lo {
                format!("has elements {}", elements(&s, lo, hi))
            } else {
                format!("has no elements (its range `{lo}..{hi}` is empty)")
            };
            return Err(index
                .range()
                .error(format!("index {k} is out of range: `{s}` {has}")));
        }
        match self.names.get(&format!("{s}[{k}]")) {
            Some(b) => Ok((k, *b)),
            // An indexed `let` using its own later elements.
            None => Err(index.range().error(format!(
                "`{s}[{k}]` is used before it is defined: an element of a `let` may only use the elements before it"
            ))),
        }
    }

    /// The force target `x` or `x[k]`: its label and its position. A
    /// component of a vector target (`constant_allowed`) may be constant
    /// (the z of a planar motion): the force along it does no work.
    pub(super) fn force_target(
        &mut self,
        target: &Expr,
        constant_allowed: bool,
    ) -> syn::Result<(String, ExprId)> {
        let (label, binding) = match target {
            Expr::Name(name) => {
                let s = name.to_string();
                match self.names.get(&s) {
                    Some(b) => (s, *b),
                    None => return Err(self.unknown_name(name)),
                }
            }
            Expr::Index { base, index, .. } => {
                let (k, b) = self.element(base, index)?;
                (format!("{base}[{k}]"), b)
            }
            _ => unreachable!("the parser reads force targets as names or elements"),
        };
        let not_a_position = |what: &str| {
            target.range().error(format!(
                "force on `{label}`, which is {what}: a force acts on a coordinate or along a position \
                 (a `let` of the coordinates), e.g. `x = F` or `x[N-1] = F`"
            ))
        };
        let position =
            match binding {
                Binding::Symbol(s) if s == self.symbols.time => return Err(not_a_position("time")),
                Binding::Symbol(s) => match self.symbols.kind(s) {
                    SymKind::Coordinate(_) => self.pool.sym(s),
                    SymKind::Input(_) => return Err(not_a_position("an input")),
                    _ => return Err(not_a_position("a parameter")),
                },
                Binding::Const(_) => return Err(not_a_position("a `const`")),
                Binding::Array { .. } => return Err(target.range().error(format!(
                    "`{label}` is indexed: apply the force to one element, e.g. `{label}[0] = F`"
                ))),
                Binding::Let(id) => id,
            };
        let s = &self.symbols;
        if s.velocities
            .iter()
            .any(|&v| self.pool.depends_on(position, v))
        {
            return Err(not_a_position("not a position (it holds a velocity)"));
        }
        if !constant_allowed
            && !s
                .coordinates
                .iter()
                .any(|&q| self.pool.depends_on(position, q))
        {
            return Err(not_a_position(
                "a constant or a parameter (it depends on no coordinate, so the force does no virtual work)",
            ));
        }
        Ok((label, position))
    }

    pub(super) fn unknown_name(&self, name: &Ident) -> syn::Error {
        let s = name.to_string();
        let msg = if self.pending_lets.contains(&s) {
            format!("`{s}` is used before its `let`: a `let` may only use the ones above it")
        } else if FUNCTIONS.iter().any(|(f, _)| *f == s) || s == "sum" {
            format!("`{s}` is a function: call it, e.g. `{s}(x)` or `x.{s}()`")
        } else {
            format!(
                "unknown name `{s}`: not a coordinate, a parameter, a constant, a `let` or `t` (declare parameters with `parameters: {s};`)"
            )
        };
        syn::Error::new(name.span(), msg)
    }
}

/// "`x[lo]` to `x[hi - 1]`", of a non-empty range (`hi > lo`, so `hi - 1`
/// cannot overflow).
fn elements(name: &str, lo: i64, hi: i64) -> String {
    format!("`{name}[{lo}]` to `{name}[{}]`", hi - 1)
}
