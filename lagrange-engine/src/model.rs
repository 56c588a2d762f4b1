//! AST → model: names resolved to symbols, `let`s and `dot` expanded, every
//! section lowered into the expression DAG. Errors here are about the text
//! (unknown or duplicated names, misplaced sections); the physics is checked
//! in [`check`](crate::check).

use crate::ast::{BinOp, Expr, Item, ModelDef, SpanRange};
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

/// A section's expression with the tokens it came from.
pub struct Section {
    pub keyword: Ident,
    pub ast: Expr,
    pub value: ExprId,
}

/// The lowered model.
pub struct Model {
    pub attrs: Vec<Attribute>,
    pub options: crate::ast::Options,
    pub vis: Visibility,
    pub name: Ident,
    pub coordinates: Vec<Ident>,
    pub parameters: Vec<Ident>,
    pub symbols: Symbols,
    pub kinetic: Section,
    pub potential: Section,
    pub dissipation: Option<Section>,
    /// The generalized force on each coordinate, if any.
    pub forces: Vec<Option<(Ident, Expr, ExprId)>>,
    pub pool: Pool,
    lets: HashMap<String, ExprId>,
}

#[derive(Clone, Copy)]
enum Binding {
    Symbol(SymId),
    Let(ExprId),
}

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
    let mut coordinates: Vec<Ident> = Vec::new();
    let mut parameters: Vec<Ident> = Vec::new();
    let mut declared: HashMap<String, &str> = HashMap::new();
    let mut coordinates_keyword = None;

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
                    "`{name}` is declared twice{roles}: each coordinate, parameter and `let` needs its own name"
                ),
            ));
        }
        declared.insert(name.to_string(), what);
        Ok(())
    };

    // Declarations first: coordinates and parameters may be listed anywhere.
    for item in &def.items {
        match item {
            Item::Coordinates { keyword, names } => {
                coordinates_keyword.get_or_insert_with(|| keyword.clone());
                for n in names {
                    declare(n, "coordinate")?;
                    coordinates.push(n.clone());
                }
            }
            Item::Parameters { names, .. } => {
                for n in names {
                    declare(n, "parameter")?;
                    parameters.push(n.clone());
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
    let mut names: HashMap<String, Binding> = HashMap::new();
    names.insert("t".into(), Binding::Symbol(symbols.time));
    for (i, c) in coordinates.iter().enumerate() {
        names.insert(c.to_string(), Binding::Symbol(symbols.coordinates[i]));
    }
    for (k, p) in parameters.iter().enumerate() {
        names.insert(p.to_string(), Binding::Symbol(symbols.parameters[k]));
    }
    let mut cx = Lowering {
        pool,
        symbols: symbols.clone(),
        names,
        pending_lets: def
            .items
            .iter()
            .filter_map(|i| match i {
                Item::Let { name, .. } => Some(name.to_string()),
                _ => None,
            })
            .collect(),
    };

    let mut lets = HashMap::new();
    for item in &def.items {
        if let Item::Let { name, value } = item {
            let id = cx.lower(value)?;
            cx.pending_lets.retain(|n| n != &name.to_string());
            cx.names.insert(name.to_string(), Binding::Let(id));
            lets.insert(name.to_string(), id);
        }
    }

    let mut kinetic = None;
    let mut potential = None;
    let mut dissipation = None;
    let mut forces: Vec<Option<(Ident, Expr, ExprId)>> = vec![None; coordinates.len()];
    for item in def.items {
        match item {
            Item::Kinetic { keyword, value } => {
                set_once(&mut kinetic, &mut cx, keyword, value)?;
            }
            Item::Potential { keyword, value } => {
                set_once(&mut potential, &mut cx, keyword, value)?;
            }
            Item::Dissipation { keyword, value } => {
                set_once(&mut dissipation, &mut cx, keyword, value)?;
            }
            Item::Forces { entries, .. } => {
                for (target, value) in entries {
                    let Some(i) = coordinates.iter().position(|c| *c == target) else {
                        let what = match cx.names.get(&target.to_string()) {
                            Some(Binding::Let(_)) => "a `let` quantity",
                            Some(Binding::Symbol(s)) if *s == symbols.time => "time",
                            Some(Binding::Symbol(_)) => "a parameter",
                            None => "not declared",
                        };
                        return Err(syn::Error::new(
                            target.span(),
                            format!(
                                "force on `{target}`, which is not a coordinate ({what}): generalized forces act on coordinates, one of {}",
                                list(&coordinates)
                            ),
                        ));
                    };
                    if forces[i].is_some() {
                        return Err(syn::Error::new(
                            target.span(),
                            format!("a second force on `{target}`: write the sum of the forces in one entry"),
                        ));
                    }
                    let id = cx.lower(&value)?;
                    forces[i] = Some((target, value, id));
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
        symbols,
        kinetic,
        potential,
        dissipation,
        forces,
        pool: cx.pool,
        lets,
    })
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

fn list(names: &[Ident]) -> String {
    names
        .iter()
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

fn set_once(
    slot: &mut Option<Section>,
    cx: &mut Lowering,
    keyword: Ident,
    ast: Expr,
) -> syn::Result<()> {
    if slot.is_some() {
        return Err(syn::Error::new(
            keyword.span(),
            format!("a second `{keyword}:` section: a model has one, write the sum in it"),
        ));
    }
    let value = cx.lower(&ast)?;
    *slot = Some(Section {
        keyword,
        ast,
        value,
    });
    Ok(())
}

struct Lowering {
    pool: Pool,
    symbols: Symbols,
    names: HashMap<String, Binding>,
    pending_lets: Vec<String>,
}

impl Lowering {
    fn lower(&mut self, e: &Expr) -> syn::Result<ExprId> {
        Ok(match e {
            Expr::Num { value, .. } => self.pool.num(*value),
            Expr::Name(name) => match self.names.get(&name.to_string()) {
                Some(Binding::Symbol(s)) => self.pool.sym(*s),
                Some(Binding::Let(id)) => *id,
                None => return Err(self.unknown_name(name)),
            },
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

    fn unknown_name(&self, name: &Ident) -> syn::Error {
        let s = name.to_string();
        let msg = if self.pending_lets.contains(&s) {
            format!("`{s}` is used before its `let`: a `let` may only use the ones above it")
        } else if FUNCTIONS.iter().any(|(f, _)| *f == s) {
            format!("`{s}` is a function: call it, e.g. `{s}(x)` or `x.{s}()`")
        } else {
            format!(
                "unknown name `{s}`: not a coordinate, a parameter, a `let` or `t` (declare parameters with `parameters: {s};`)"
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
    /// Re-lowers `e` (a subexpression of a section) to find its node; the
    /// pool returns the existing nodes, so this is cheap and side-effect free.
    fn lower_sub(&mut self, e: &Expr) -> Option<ExprId> {
        let mut names: HashMap<String, Binding> = HashMap::new();
        names.insert("t".into(), Binding::Symbol(self.symbols.time));
        for (i, c) in self.coordinates.iter().enumerate() {
            names.insert(c.to_string(), Binding::Symbol(self.symbols.coordinates[i]));
        }
        for (k, p) in self.parameters.iter().enumerate() {
            names.insert(p.to_string(), Binding::Symbol(self.symbols.parameters[k]));
        }
        for (n, &id) in &self.lets {
            names.insert(n.clone(), Binding::Let(id));
        }
        let mut cx = Lowering {
            pool: std::mem::take(&mut self.pool),
            symbols: self.symbols.clone(),
            names,
            pending_lets: Vec::new(),
        };
        let id = cx.lower(e).ok();
        self.pool = cx.pool;
        id
    }

    /// The node of a whole section's expression.
    pub fn lower_section(&mut self, e: &Expr) -> Option<ExprId> {
        self.lower_sub(e)
    }

    /// The smallest piece of `e` that is `bad`, descending from `e` (assumed
    /// bad) into its leftmost bad operand: the token to underline.
    pub fn locate(&mut self, e: &Expr, bad: &dyn Fn(&mut Pool, ExprId) -> bool) -> SpanRange {
        for child in e.children() {
            if let Some(id) = self.lower_sub(child) {
                if bad(&mut self.pool, id) {
                    return self.locate(child, bad);
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
