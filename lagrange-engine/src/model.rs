//! AST → model: names resolved to symbols, `let`s and `dot` expanded, every
//! section lowered into the expression DAG. Errors here are about the text
//! (unknown or duplicated names, misplaced sections); the physics is checked
//! in [`check`](crate::check).

use crate::ast::{BinOp, Expr, IndexRange, Item, ModelDef, SpanRange};
use crate::expr::{ExprId, Func, Pool, SymId};
use std::collections::HashMap;
use syn::{Attribute, Ident, Visibility};

/// What a symbol id stands for. Symbol ids are dense: `t`, then the
/// coordinates, then the velocities, then the parameters, so a numeric state
/// is one slice in that order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SymKind {
    Time,
    Coordinate(usize),
    Velocity(usize),
    Parameter(usize),
    /// Only in the residual `M q̈ − f` of the Jacobians.
    Acceleration(usize),
}

/// The symbols of a model.
#[derive(Clone, Debug)]
pub struct Symbols {
    pub time: SymId,
    pub coordinates: Vec<SymId>,
    pub velocities: Vec<SymId>,
    pub parameters: Vec<SymId>,
    pub accelerations: Vec<SymId>,
}

impl Symbols {
    fn new(n: usize, p: usize) -> Self {
        let id = |k: usize| SymId(k as u32);
        Symbols {
            time: id(0),
            coordinates: (0..n).map(|i| id(1 + i)).collect(),
            velocities: (0..n).map(|i| id(1 + n + i)).collect(),
            parameters: (0..p).map(|k| id(1 + 2 * n + k)).collect(),
            accelerations: (0..n).map(|i| id(1 + 2 * n + p + i)).collect(),
        }
    }

    pub fn count(&self) -> usize {
        1 + 3 * self.coordinates.len() + self.parameters.len()
    }

    pub fn kind(&self, s: SymId) -> SymKind {
        let n = self.coordinates.len();
        let k = s.0 as usize;
        if k == 0 {
            SymKind::Time
        } else if k <= n {
            SymKind::Coordinate(k - 1)
        } else if k <= 2 * n {
            SymKind::Velocity(k - 1 - n)
        } else if k <= 2 * n + self.parameters.len() {
            SymKind::Parameter(k - 1 - 2 * n)
        } else {
            SymKind::Acceleration(k - 1 - 2 * n - self.parameters.len())
        }
    }
}

/// A section's expression with the tokens it came from. A section written
/// more than once is their sum: `ast` is then the `+` of the parts.
pub struct Section {
    pub keyword: Ident,
    pub ast: Expr,
    pub value: ExprId,
}

/// One scalar of the model: a name, or one element of an indexed name.
#[derive(Clone, Debug)]
pub struct Scalar {
    pub name: Ident,
    pub index: Option<usize>,
}

impl Scalar {
    pub fn span(&self) -> proc_macro2::Span {
        self.name.span()
    }
}

impl std::fmt::Display for Scalar {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.index {
            None => write!(f, "{}", self.name),
            Some(k) => write!(f, "{}[{k}]", self.name),
        }
    }
}

/// A runtime parameter as the struct holds it: `m: S` or `m: [S; len]`.
#[derive(Clone, Debug)]
pub struct Field {
    pub name: Ident,
    pub len: Option<usize>,
}

impl Field {
    /// The field's type: `S` or `[S; len]`.
    pub fn rust_type(&self) -> proc_macro2::TokenStream {
        match self.len {
            None => quote::quote!(S),
            Some(len) => {
                let len = proc_macro2::Literal::usize_unsuffixed(len);
                quote::quote!([S; #len])
            }
        }
    }
}

/// A force: `value` acts along the position `position` (a coordinate or a
/// `let`), contributing `value · ∂position/∂q_i` to each `Q_i`.
pub struct Force {
    /// The target as resolved: `x`, `theta[0]`.
    pub label: String,
    pub target: Expr,
    pub ast: Expr,
    pub position: ExprId,
    pub value: ExprId,
}

/// The lowered model.
pub struct Model {
    pub attrs: Vec<Attribute>,
    pub options: crate::ast::Options,
    pub vis: Visibility,
    pub name: Ident,
    pub coordinates: Vec<Scalar>,
    /// The parameters, one scalar each, in the order of the symbols.
    pub parameters: Vec<Scalar>,
    /// The parameters as struct fields, in declaration order.
    pub fields: Vec<Field>,
    pub symbols: Symbols,
    pub kinetic: Section,
    pub potential: Section,
    pub dissipation: Option<Section>,
    pub forces: Vec<Force>,
    pub pool: Pool,
    scope: HashMap<String, Binding>,
}

#[derive(Clone, Copy, Debug)]
enum Binding {
    Symbol(SymId),
    Let(ExprId),
    /// A `const` (a compile-time integer).
    Const(i64),
    /// An indexed name; its elements are bound as `name[k]`, `k` in `lo..hi`.
    Array {
        lo: i64,
        hi: i64,
        role: Role,
    },
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
    Coordinate,
    Parameter,
    Let,
}

/// The most elements an index range or an indexed name may have: sums are
/// unrolled at compile time, and a size this large is a typo, not a model.
pub const MAX_RANGE: i64 = 10_000;

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

/// Lowers a parsed model. The first error met is returned.
pub fn lower_with_pool(def: ModelDef, pool: Pool) -> syn::Result<Model> {
    let mut declared: HashMap<String, &str> = HashMap::new();
    let mut declare = |name: &Ident, what: &'static str| -> syn::Result<()> {
        if name == "t" {
            return Err(syn::Error::new(
                name.span(),
                format!("`t` is time and is reserved: choose another name for this {what}"),
            ));
        }
        if let Some(first) = declared.get(&name.to_string()) {
            let roles = if *first == what {
                format!(" as a {what}")
            } else {
                format!(", as a {first} and as a {what}")
            };
            return Err(syn::Error::new(
                name.span(),
                format!(
                    "`{name}` is declared twice{roles}: each coordinate, parameter, constant and `let` needs its own name"
                ),
            ));
        }
        declared.insert(name.to_string(), what);
        Ok(())
    };

    // `const`s first, in order: sizes and indices anywhere may use them.
    let mut cx = Lowering::new(pool, &def.name);
    for item in &def.items {
        if let Item::Const { name, value } = item {
            declare(name, "`const`")?;
            let v = cx.int(value)?;
            cx.names.insert(name.to_string(), Binding::Const(v));
        }
    }

    // Declarations next: coordinates and parameters may be listed anywhere.
    let mut coordinates: Vec<Scalar> = Vec::new();
    let mut parameters: Vec<Scalar> = Vec::new();
    let mut fields: Vec<Field> = Vec::new();
    let mut arrays: Vec<(String, Binding)> = Vec::new();
    for item in &def.items {
        match item {
            Item::Coordinates { names, .. } | Item::Parameters { names, .. } => {
                let (role, what, out) = match item {
                    Item::Coordinates { .. } => (Role::Coordinate, "coordinate", &mut coordinates),
                    _ => (Role::Parameter, "parameter", &mut parameters),
                };
                for d in names {
                    declare(&d.name, what)?;
                    let len = match &d.len {
                        None => None,
                        Some(e) => Some(cx.length(e)?),
                    };
                    match len {
                        None => out.push(Scalar {
                            name: d.name.clone(),
                            index: None,
                        }),
                        Some(len) => {
                            arrays.push((
                                d.name.to_string(),
                                Binding::Array {
                                    lo: 0,
                                    hi: len as i64,
                                    role,
                                },
                            ));
                            out.extend((0..len).map(|k| Scalar {
                                name: d.name.clone(),
                                index: Some(k),
                            }));
                        }
                    }
                    if role == Role::Parameter {
                        fields.push(Field {
                            name: d.name.clone(),
                            len,
                        });
                    }
                }
            }
            Item::Constants { entries, .. } => {
                for (n, _) in entries {
                    declare(n, "constant")?;
                }
            }
            Item::Let { name, .. } => declare(name, "`let`")?,
            _ => {}
        }
    }
    if coordinates.is_empty() {
        return Err(syn::Error::new(
            def.name.span(),
            format!(
                "model `{}` has no `coordinates:` section: list its generalized coordinates, e.g. `coordinates: x, theta;`",
                def.name
            ),
        ));
    }

    let symbols = Symbols::new(coordinates.len(), parameters.len());
    cx.symbols = symbols.clone();
    cx.names.insert("t".into(), Binding::Symbol(symbols.time));
    for (i, c) in coordinates.iter().enumerate() {
        cx.names
            .insert(c.to_string(), Binding::Symbol(symbols.coordinates[i]));
    }
    for (k, p) in parameters.iter().enumerate() {
        cx.names
            .insert(p.to_string(), Binding::Symbol(symbols.parameters[k]));
    }
    cx.names.extend(arrays);
    cx.pending_lets = def
        .items
        .iter()
        .filter_map(|i| match i {
            Item::Let { name, .. } => Some(name.to_string()),
            _ => None,
        })
        .collect();

    // Constants, in order: each must fold to a number.
    for item in &def.items {
        if let Item::Constants { entries, .. } = item {
            for (name, value) in entries {
                let id = cx.lower(value)?;
                if cx.pool.as_num(id).is_none() {
                    return Err(value.range().error(format!(
                        "constant `{name}` is not a number: a constant may use numbers, `const`s and the constants before it \
                         (declare values that change at run time with `parameters: {name};`)"
                    )));
                }
                cx.names.insert(name.to_string(), Binding::Let(id));
            }
        }
    }

    // `let`s, in order: each may use the ones above it.
    for item in &def.items {
        if let Item::Let { name, index, value } = item {
            match index {
                None => {
                    let id = cx.lower(value)?;
                    cx.names.insert(name.to_string(), Binding::Let(id));
                }
                Some(range) => {
                    let (lo, hi) = cx.range(range)?;
                    cx.names.insert(
                        name.to_string(),
                        Binding::Array {
                            lo,
                            hi,
                            role: Role::Let,
                        },
                    );
                    for k in lo..hi {
                        cx.env.push((range.var.to_string(), k));
                        let id = cx.lower(value);
                        cx.env.pop();
                        cx.names.insert(format!("{name}[{k}]"), Binding::Let(id?));
                    }
                }
            }
            cx.pending_lets.retain(|n| n != &name.to_string());
        }
    }

    let mut kinetic = None;
    let mut potential = None;
    let mut dissipation = None;
    let mut forces: Vec<Force> = Vec::new();
    for item in def.items {
        match item {
            Item::Kinetic { keyword, value } => add_to(&mut kinetic, &mut cx, keyword, value)?,
            Item::Potential { keyword, value } => add_to(&mut potential, &mut cx, keyword, value)?,
            Item::Dissipation { keyword, value } => {
                add_to(&mut dissipation, &mut cx, keyword, value)?
            }
            Item::Forces { entries, .. } => {
                for (target, value) in entries {
                    let (label, position) = cx.force_target(&target)?;
                    if forces.iter().any(|f| f.label == label) {
                        return Err(target.range().error(format!(
                            "a second force on `{label}`: write the sum of the forces in one entry"
                        )));
                    }
                    let id = cx.lower(&value)?;
                    forces.push(Force {
                        label,
                        target,
                        ast: value,
                        position,
                        value: id,
                    });
                }
            }
            _ => {}
        }
    }
    let missing = |what: &str, example: &str| {
        syn::Error::new(
            def.name.span(),
            format!("model `{}` has no `{what}:` section: {example}", def.name),
        )
    };
    let kinetic = kinetic.ok_or_else(|| {
        missing(
            "kinetic",
            "write its kinetic energy T, e.g. `kinetic: m/2*dot(x)^2;`",
        )
    })?;
    let potential = potential.ok_or_else(|| {
        missing(
            "potential",
            "write its potential energy V, e.g. `potential: m*g*y;` (or `potential: 0;`)",
        )
    })?;
    cx.pool
        .check_budget()
        .map_err(|b| budget_error(&def.name, b.budget))?;

    Ok(Model {
        attrs: def.attrs,
        options: def.options,
        vis: def.vis,
        name: def.name,
        coordinates,
        parameters,
        fields,
        symbols,
        kinetic,
        potential,
        dissipation,
        forces,
        pool: cx.pool,
        scope: cx.names,
    })
}

/// For the stub of a model with an error: its number of coordinates and
/// its parameter fields, counted as lowering will count them once the error
/// is fixed (a duplicated name or `t` is the error, not an extra one; a size
/// that cannot be evaluated counts as one).
pub fn declared_shape(def: &ModelDef) -> (usize, Vec<Field>) {
    let mut cx = Lowering::new(Pool::default(), &def.name);
    for item in &def.items {
        if let Item::Const { name, value } = item {
            if let Ok(v) = cx.int(value) {
                cx.names
                    .entry(name.to_string())
                    .or_insert(Binding::Const(v));
            }
        }
    }
    let mut seen: Vec<String> = vec!["t".into()];
    let mut dof = 0;
    let mut fields = Vec::new();
    for item in &def.items {
        let (Item::Coordinates { names, .. } | Item::Parameters { names, .. }) = item else {
            continue;
        };
        for d in names {
            if seen.contains(&d.name.to_string()) {
                continue;
            }
            seen.push(d.name.to_string());
            let len = d.len.as_ref().map(|e| cx.length(e).unwrap_or(1));
            if matches!(item, Item::Coordinates { .. }) {
                dof += len.unwrap_or(1);
            } else {
                fields.push(Field {
                    name: d.name.clone(),
                    len,
                });
            }
        }
    }
    (dof, fields)
}

pub fn budget_error(name: &Ident, budget: usize) -> syn::Error {
    syn::Error::new(
        name.span(),
        format!(
            "the derivation of `{name}` exceeds the size budget of {budget} expression nodes: \
             the model is too large to derive symbolically (simplify the positions, or split the model)"
        ),
    )
}

/// Lowers a section; a section written again adds to the first.
fn add_to(
    slot: &mut Option<Section>,
    cx: &mut Lowering,
    keyword: Ident,
    ast: Expr,
) -> syn::Result<()> {
    let value = cx.lower(&ast)?;
    *slot = Some(match slot.take() {
        None => Section {
            keyword,
            ast,
            value,
        },
        Some(first) => Section {
            value: cx.pool.add2(first.value, value),
            ast: Expr::Binary {
                op: BinOp::Add,
                range: first.ast.range().to(ast.range()),
                lhs: Box::new(first.ast),
                rhs: Box::new(ast),
            },
            keyword: first.keyword,
        },
    });
    Ok(())
}

struct Lowering {
    pool: Pool,
    symbols: Symbols,
    names: HashMap<String, Binding>,
    pending_lets: Vec<String>,
    /// The index variables in scope, innermost last.
    env: Vec<(String, i64)>,
    model: Ident,
}

impl Lowering {
    /// A lowering with no names yet: the `const`s come first.
    fn new(pool: Pool, model: &Ident) -> Self {
        Lowering {
            pool,
            symbols: Symbols::new(0, 0),
            names: HashMap::new(),
            pending_lets: Vec::new(),
            env: Vec::new(),
            model: model.clone(),
        }
    }

    fn lower(&mut self, e: &Expr) -> syn::Result<ExprId> {
        Ok(match e {
            Expr::Num { value, .. } => self.pool.num(*value),
            Expr::Name(name) => {
                let s = name.to_string();
                if let Some(&(_, k)) = self.env.iter().rev().find(|(v, _)| *v == s) {
                    return Ok(self.pool.num(k as f64));
                }
                match self.names.get(&s) {
                    Some(Binding::Symbol(s)) => self.pool.sym(*s),
                    Some(Binding::Let(id)) => *id,
                    Some(Binding::Const(v)) => self.pool.num(*v as f64),
                    Some(Binding::Array { lo, hi, role }) => {
                        let role = match role {
                            Role::Coordinate => "an indexed coordinate",
                            Role::Parameter => "an indexed parameter",
                            Role::Let => "an indexed `let`",
                        };
                        let example = if self.env.is_empty() {
                            format!("`{s}[{lo}]`")
                        } else {
                            format!("`{s}[{}]`", self.env[self.env.len() - 1].0)
                        };
                        return Err(syn::Error::new(
                            name.span(),
                            format!(
                                "`{s}` is {role} (`{s}[{lo}]` to `{s}[{}]`): write one element, e.g. {example}",
                                hi - 1
                            ),
                        ));
                    }
                    None => return Err(self.unknown_name(name)),
                }
            }
            Expr::Index { base, index, .. } => match self.element(base, index)?.1 {
                Binding::Symbol(s) => self.pool.sym(s),
                Binding::Let(id) => id,
                _ => unreachable!("elements are symbols or lets"),
            },
            Expr::Sum { index, body, .. } => {
                let (lo, hi) = self.range(index)?;
                let mut terms = Vec::new();
                for k in lo..hi {
                    self.env.push((index.var.to_string(), k));
                    let term = self.lower(body);
                    self.env.pop();
                    terms.push(term?);
                    self.pool
                        .check_budget()
                        .map_err(|b| budget_error(&self.model, b.budget))?;
                }
                self.pool.add(&terms)
            }
            Expr::Neg { inner, .. } => {
                let x = self.lower(inner)?;
                self.pool.neg(x)
            }
            Expr::Binary { op, lhs, rhs, .. } => {
                let a = self.lower(lhs)?;
                let b = self.lower(rhs)?;
                match op {
                    BinOp::Add => self.pool.add2(a, b),
                    BinOp::Sub => self.pool.sub(a, b),
                    BinOp::Mul => self.pool.mul2(a, b),
                    BinOp::Div => self.pool.div(a, b),
                    BinOp::Pow => self.pool.pow(a, b),
                }
            }
            Expr::Call { func, range, args } => self.lower_call(func, *range, args)?,
        })
    }

    /// The index of `base[index]`, checked against its range, and the
    /// element's binding.
    fn element(&self, base: &Ident, index: &Expr) -> syn::Result<(i64, Binding)> {
        let s = base.to_string();
        let (lo, hi) = match self.names.get(&s) {
            Some(Binding::Array { lo, hi, .. }) => (*lo, *hi),
            Some(Binding::Const(_)) => {
                return Err(syn::Error::new(
                    base.span(),
                    format!("`{s}` is a `const`, not indexed: write `{s}`"),
                ))
            }
            Some(_) => {
                return Err(syn::Error::new(
                    base.span(),
                    format!("`{s}` is not indexed: write `{s}` (declare `{s}[N]` to index it)"),
                ))
            }
            None => return Err(self.unknown_name(base)),
        };
        let k = self.int(index)?;
        if k < lo || k >= hi {
            return Err(index.range().error(format!(
                "index {k} is out of range: `{s}` has elements `{s}[{lo}]` to `{s}[{}]`",
                hi - 1
            )));
        }
        match self.names.get(&format!("{s}[{k}]")) {
            Some(b) => Ok((k, *b)),
            // An indexed `let` using its own later elements.
            None => Err(index.range().error(format!(
                "`{s}[{k}]` is used before it is defined: an element of a `let` may only use the elements before it"
            ))),
        }
    }

    /// The force target `x` or `x[k]`: its label and its position.
    fn force_target(&mut self, target: &Expr) -> syn::Result<(String, ExprId)> {
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
        let position = match binding {
            Binding::Symbol(s) if s == self.symbols.time => return Err(not_a_position("time")),
            Binding::Symbol(s) => match self.symbols.kind(s) {
                SymKind::Coordinate(_) => self.pool.sym(s),
                _ => return Err(not_a_position("a parameter")),
            },
            Binding::Const(_) => return Err(not_a_position("a `const`")),
            Binding::Array { .. } => {
                return Err(target.range().error(format!(
                    "`{label}` is indexed: apply the force to one element, e.g. `{label}[0] = F`"
                )))
            }
            Binding::Let(id) => id,
        };
        let s = &self.symbols;
        if s.velocities
            .iter()
            .any(|&v| self.pool.depends_on(position, v))
        {
            return Err(not_a_position("not a position (it holds a velocity)"));
        }
        if !s
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

    /// `lo..hi` (or `lo..=hi`) as a half-open integer range.
    fn range(&self, r: &IndexRange) -> syn::Result<(i64, i64)> {
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
    fn length(&self, e: &Expr) -> syn::Result<usize> {
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
    fn int(&self, e: &Expr) -> syn::Result<i64> {
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

    fn unknown_name(&self, name: &Ident) -> syn::Error {
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

    fn lower_call(&mut self, func: &Ident, range: SpanRange, args: &[Expr]) -> syn::Result<ExprId> {
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
                if let Some(v) = self
                    .symbols
                    .velocities
                    .iter()
                    .position(|&v| p.depends_on(xs[0], v))
                {
                    let _ = v;
                    return Err(range.error(
                        "`dot` of an expression that already holds a velocity: the model is written in positions and velocities, accelerations are not allowed",
                    ));
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

impl Model {
    /// Re-lowers `e` (a subexpression of a section, under the index values
    /// `env`) to find its node; the pool returns the existing nodes, so this
    /// is cheap and side-effect free.
    fn lower_sub(&mut self, e: &Expr, env: &[(String, i64)]) -> Option<ExprId> {
        let mut cx = self.lowering(env);
        let id = cx.lower(e).ok();
        self.pool = cx.pool;
        id
    }

    fn lowering(&mut self, env: &[(String, i64)]) -> Lowering {
        Lowering {
            pool: std::mem::take(&mut self.pool),
            symbols: self.symbols.clone(),
            names: self.scope.clone(),
            pending_lets: Vec::new(),
            env: env.to_vec(),
            model: self.name.clone(),
        }
    }

    /// The node of a whole section's expression.
    pub fn lower_section(&mut self, e: &Expr) -> Option<ExprId> {
        self.lower_sub(e, &[])
    }

    /// The smallest piece of `e` that is `bad`, descending from `e` (assumed
    /// bad) into its leftmost bad operand: the token to underline. Inside a
    /// sum, into the first term that is bad.
    pub fn locate(&mut self, e: &Expr, bad: &dyn Fn(&mut Pool, ExprId) -> bool) -> SpanRange {
        self.locate_in(e, &mut Vec::new(), bad)
    }

    fn locate_in(
        &mut self,
        e: &Expr,
        env: &mut Vec<(String, i64)>,
        bad: &dyn Fn(&mut Pool, ExprId) -> bool,
    ) -> SpanRange {
        if let Expr::Sum { index, body, .. } = e {
            let cx = self.lowering(env);
            let range = cx.range(index);
            self.pool = cx.pool;
            if let Ok((lo, hi)) = range {
                for k in lo..hi {
                    env.push((index.var.to_string(), k));
                    if let Some(id) = self.lower_sub(body, env) {
                        if bad(&mut self.pool, id) {
                            let r = self.locate_in(body, env, bad);
                            env.pop();
                            return r;
                        }
                    }
                    env.pop();
                }
            }
            return e.range();
        }
        for child in e.children() {
            if let Some(id) = self.lower_sub(child, env) {
                if bad(&mut self.pool, id) {
                    return self.locate_in(child, env, bad);
                }
            }
        }
        e.range()
    }

    pub fn dof(&self) -> usize {
        self.coordinates.len()
    }
}

impl Section {
    /// From the section's keyword to the end of its expression.
    pub fn keyword_and_value(&self) -> SpanRange {
        SpanRange::single(self.keyword.span()).to(self.ast.range())
    }
}
