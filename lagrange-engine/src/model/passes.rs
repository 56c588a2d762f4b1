//! The lowering passes, in the order [`lower_with_pool`](super::lower_with_pool)
//! runs them. Each reads the whole item list, so a section may be written in
//! any order except that a `const`, a constant or a `let` may use only the
//! ones above it.

use super::lowering::Lowering;
use super::scope::{Binding, Declared, Role};
use super::vectors::{Value, describe};
use super::{Constraint, Contact, Field, Force, Scalar, Section, Symbols, limit_error};
use crate::ast::{BinOp, ConstraintDef, ContactDef, Expr, Item, ModelDef};
use crate::expr::{ExprId, Pool};
use std::collections::{HashMap, HashSet};
use syn::Ident;

/// What a coordinate or parameter costs the budget, measured as the
/// memory it holds through the stages (about a kilobyte).
const STEPS_PER_SCALAR: u64 = 64;

/// What a name costs the budget: the memory of its entry in the scope.
const STEPS_PER_NAME: u64 = 16;

/// Pass 1: the `const`s, in order; sizes and indices anywhere may use them.
pub(super) fn consts(
    def: &ModelDef,
    declared: &mut Declared,
    cx: &mut Lowering,
) -> syn::Result<()> {
    for item in &def.items {
        if let Item::Const { name, value } = item {
            declared.declare(name, "`const`")?;
            let v = cx.int(value)?;
            cx.names.insert(name.to_string(), Binding::Const(v));
        }
    }
    Ok(())
}

/// The coordinates, parameters and inputs as declared, element by element.
pub(super) struct Declarations {
    pub(super) coordinates: Vec<Scalar>,
    pub(super) parameters: Vec<Scalar>,
    pub(super) fields: Vec<Field>,
    pub(super) inputs: Vec<Scalar>,
    pub(super) input_fields: Vec<Field>,
    /// The indexed names among them, with their ranges.
    arrays: Vec<(String, Binding)>,
}

/// Pass 2: every name declared once; the coordinates and parameters, which
/// may be listed anywhere, with their sizes.
pub(super) fn declarations(
    def: &ModelDef,
    declared: &mut Declared,
    cx: &Lowering,
) -> syn::Result<Declarations> {
    let mut out = Declarations {
        coordinates: Vec::new(),
        parameters: Vec::new(),
        fields: Vec::new(),
        inputs: Vec::new(),
        input_fields: Vec::new(),
        arrays: Vec::new(),
    };
    for item in &def.items {
        match item {
            Item::Coordinates { names, .. }
            | Item::Parameters { names, .. }
            | Item::Inputs { names, .. } => {
                let (role, what) = match item {
                    Item::Coordinates { .. } => (Role::Coordinate, "coordinate"),
                    Item::Inputs { .. } => (Role::Input, "input"),
                    _ => (Role::Parameter, "parameter"),
                };
                for d in names {
                    declared.declare(&d.name, what)?;
                    let len = match &d.len {
                        None => None,
                        Some(e) => Some(cx.length(e)?),
                    };
                    // Each element is a scalar of the model, with a name, a
                    // symbol and a local in every generated function.
                    cx.pool.charge(STEPS_PER_SCALAR * len.unwrap_or(1) as u64);
                    cx.pool
                        .check_budget()
                        .map_err(|x| limit_error(&def.name, x))?;
                    let scalars = match role {
                        Role::Coordinate => &mut out.coordinates,
                        Role::Input => &mut out.inputs,
                        _ => &mut out.parameters,
                    };
                    match len {
                        None => scalars.push(Scalar {
                            name: d.name.clone(),
                            index: None,
                        }),
                        Some(len) => {
                            out.arrays.push((
                                d.name.to_string(),
                                Binding::Array {
                                    lo: 0,
                                    hi: len as i64,
                                    role,
                                },
                            ));
                            scalars.extend((0..len).map(|k| Scalar {
                                name: d.name.clone(),
                                index: Some(k),
                            }));
                        }
                    }
                    let field = Field {
                        name: d.name.clone(),
                        len,
                        domain: d.domain,
                    };
                    match role {
                        Role::Parameter => out.fields.push(field),
                        Role::Input => out.input_fields.push(field),
                        _ => {}
                    }
                }
            }
            Item::Constants { entries, .. } => {
                for (n, _) in entries {
                    declared.declare(n, "constant")?;
                }
            }
            Item::Let { name, .. } => declared.declare(name, "`let`")?,
            Item::Constraints { entries, .. } => {
                for e in entries {
                    declared.declare(&e.name, "constraint")?;
                }
            }
            Item::Contacts { entries, .. } => {
                for e in entries {
                    declared.declare(&e.name, "contact")?;
                }
            }
            _ => {}
        }
    }
    if out.coordinates.is_empty() {
        return Err(syn::Error::new(
            def.name.span(),
            format!(
                "model `{}` has no `coordinates:` section: list its generalized coordinates, e.g. `coordinates: x, theta;`",
                def.name
            ),
        ));
    }
    Ok(out)
}

/// Pass 3: a symbol for `t` and for each coordinate, parameter and input,
/// bound to its name (`x`, `theta[2]`); the indexed names bound to their
/// ranges.
pub(super) fn bind_symbols(def: &ModelDef, decls: &mut Declarations, cx: &mut Lowering) -> Symbols {
    let symbols = Symbols::new(
        decls.coordinates.len(),
        decls.parameters.len(),
        decls.inputs.len(),
    );
    cx.symbols = symbols.clone();
    cx.names.insert("t".into(), Binding::Symbol(symbols.time));
    for (i, c) in decls.coordinates.iter().enumerate() {
        cx.names
            .insert(c.to_string(), Binding::Symbol(symbols.coordinates[i]));
    }
    for (k, p) in decls.parameters.iter().enumerate() {
        cx.names
            .insert(p.to_string(), Binding::Symbol(symbols.parameters[k]));
    }
    for (k, u) in decls.inputs.iter().enumerate() {
        cx.names
            .insert(u.to_string(), Binding::Symbol(symbols.inputs[k]));
    }
    cx.names.extend(std::mem::take(&mut decls.arrays));
    cx.pending_lets = def
        .items
        .iter()
        .filter_map(|i| match i {
            Item::Let { name, .. } => Some(name.to_string()),
            _ => None,
        })
        .collect();
    symbols
}

/// Pass 4: the `constants:`, in order; each must fold to a number.
pub(super) fn constants(def: &ModelDef, cx: &mut Lowering) -> syn::Result<()> {
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
    Ok(())
}

/// Pass 5: the `let`s, in order; each may use the ones above it, and an
/// element of an indexed `let` the elements before it.
pub(super) fn lets(def: &ModelDef, cx: &mut Lowering) -> syn::Result<Vec<(String, ExprId)>> {
    let mut values = Vec::new();
    for item in &def.items {
        if let Item::Let { name, index, value } = item {
            match index {
                None => match cx.lower_value(value)? {
                    Value::Scalar(id) => {
                        cx.names.insert(name.to_string(), Binding::Let(id));
                        values.push((name.to_string(), id));
                    }
                    // A vector is bound as an indexed `let`: `r[0]` is its
                    // first component, `r` written bare the vector.
                    Value::Vector(components) => {
                        cx.names.insert(
                            name.to_string(),
                            Binding::Array {
                                lo: 0,
                                hi: components.len() as i64,
                                role: Role::Vector,
                            },
                        );
                        for (k, id) in components.into_iter().enumerate() {
                            cx.pool.charge(STEPS_PER_NAME);
                            let element = format!("{name}[{k}]");
                            cx.names.insert(element.clone(), Binding::Let(id));
                            values.push((element, id));
                        }
                    }
                },
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
                        // Each element is a name kept to the end.
                        cx.pool.charge(STEPS_PER_NAME);
                        cx.env.push((range.var.to_string(), k));
                        let id = cx.lower_value(value).and_then(|v| match v {
                            Value::Scalar(id) => Ok(id),
                            v => Err(value.range().error(format!(
                                "an indexed `let` holds one number per index, and this is {}: \
                                 write `let {name}[{var} in ..] = ...` of one component, or \
                                 `let {name} = vector(...)` for one vector",
                                describe(&v),
                                var = range.var
                            ))),
                        });
                        cx.env.pop();
                        let (element, id) = (format!("{name}[{k}]"), id?);
                        cx.names.insert(element.clone(), Binding::Let(id));
                        values.push((element, id));
                    }
                }
            }
            cx.pending_lets.remove(&name.to_string());
        }
    }
    Ok(values)
}

/// The energies and forces of a model.
pub(super) struct Sections {
    pub(super) kinetic: Section,
    pub(super) potential: Section,
    pub(super) dissipation: Option<Section>,
    pub(super) forces: Vec<Force>,
    pub(super) constraint_defs: Vec<ConstraintDef>,
    pub(super) constraints: Vec<Constraint>,
    pub(super) contact_defs: Vec<ContactDef>,
    pub(super) contacts: Vec<Contact>,
}

/// Pass 6: the sections, in order; a section written twice is the sum of
/// both. `kinetic:` and `potential:` are required.
pub(super) fn sections(items: Vec<Item>, name: &Ident, cx: &mut Lowering) -> syn::Result<Sections> {
    let mut kinetic = None;
    let mut potential = None;
    let mut dissipation = None;
    let mut forces: Vec<Force> = Vec::new();
    let mut targets: HashSet<String> = HashSet::new();
    let mut constraint_defs = Vec::new();
    let mut constraints = Vec::new();
    let mut contact_defs = Vec::new();
    let mut contacts = Vec::new();
    for item in items {
        match item {
            Item::Kinetic { keyword, value } => add_to(&mut kinetic, cx, keyword, value)?,
            Item::Potential { keyword, value } => add_to(&mut potential, cx, keyword, value)?,
            Item::Dissipation { keyword, value } => add_to(&mut dissipation, cx, keyword, value)?,
            Item::Forces { entries, .. } => {
                for (target, value) in entries {
                    forces.extend(force(&mut targets, cx, target, value)?);
                }
            }
            Item::Constraints { entries, .. } => {
                for def in entries {
                    constraints.extend(constraint(cx, &def, constraint_defs.len())?);
                    constraint_defs.push(def);
                }
            }
            Item::Contacts { entries, .. } => {
                for def in entries {
                    contacts.push(contact(cx, &def, contact_defs.len())?);
                    contact_defs.push(def);
                }
            }
            _ => {}
        }
    }
    let missing = |what: &str, example: &str| {
        syn::Error::new(
            name.span(),
            format!("model `{name}` has no `{what}:` section: {example}"),
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
    Ok(Sections {
        kinetic,
        potential,
        dissipation,
        forces,
        constraint_defs,
        constraints,
        contact_defs,
        contacts,
    })
}

/// The keys of a contact's law.
const CONTACT_KEYS: &str =
    "`restitution`, `friction`, `static_friction`, `kinetic_friction`, `slip` or `normal`";

/// The contact of one entry `name: lhs >= rhs { law }` or `name: { normal:
/// F, .. }` (the `entry`-th).
fn contact(cx: &mut Lowering, def: &ContactDef, entry: usize) -> syn::Result<Contact> {
    let lhs = cx.lower(&def.lhs)?;
    let rhs = cx.lower(&def.rhs)?;
    let gap = if !def.has_gap {
        Pool::ZERO
    } else if def.at_least {
        cx.pool.sub(lhs, rhs)
    } else {
        cx.pool.sub(rhs, lhs)
    };
    let mut law: HashMap<String, ExprId> = HashMap::new();
    let mut fields = Vec::with_capacity(def.fields.len());
    let mut second_slip = None;
    for (key, value) in &def.fields {
        let name = key.to_string();
        if !matches!(
            name.as_str(),
            "restitution" | "friction" | "static_friction" | "kinetic_friction" | "slip" | "normal"
        ) {
            return Err(syn::Error::new(
                key.span(),
                format!(
                    "unknown entry `{name}` in contact `{}`'s law: expected {CONTACT_KEYS}",
                    def.name
                ),
            ));
        }
        let both = name == "friction"
            && (law.contains_key("static_friction") || law.contains_key("kinetic_friction"));
        let one = name.ends_with("_friction") && law.contains_key("friction");
        if law.contains_key(&name) || both || one {
            return Err(syn::Error::new(
                key.span(),
                format!(
                    "contact `{}` gives `{name}` twice: `friction: mu` sets the static and the kinetic \
                     coefficient at once, `static_friction:` and `kinetic_friction:` each",
                    def.name
                ),
            ));
        }
        if def.has_gap && name == "normal" {
            return Err(syn::Error::new(
                key.span(),
                format!(
                    "contact `{}` has a gap, so its normal force is the reaction that keeps the gap \
                     non-negative: `normal:` gives the force of a contact written without a gap, \
                     friction against a given load (`brake: {{ normal: F, friction: mu, slip: \
                     r*dot(theta) }}`)",
                    def.name
                ),
            ));
        }
        if !def.has_gap && name == "restitution" {
            return Err(syn::Error::new(
                key.span(),
                format!(
                    "contact `{}` has no gap, so it has no impacts and no restitution: drop \
                     `restitution:` (or write the gap, as in `{}: y >= 0 {{ restitution: e }}`)",
                    def.name, def.name
                ),
            ));
        }
        if name == "slip" {
            // A number, or a vector of two components: the slip in the
            // plane of the surface, with friction isotropic in it.
            match cx.lower_value(value)? {
                Value::Scalar(id) => {
                    fields.push(id);
                    law.insert(name, id);
                }
                Value::Vector(components) if components.len() == 2 => {
                    fields.push(components[0]);
                    law.insert(name, components[0]);
                    second_slip = Some(components[1]);
                }
                Value::Vector(components) => {
                    return Err(value.range().error(format!(
                        "contact `{}`'s slip is a vector of {} components: a slip is a number (the \
                         contact point's velocity along one direction of the surface) or a vector of \
                         two (its velocity along two orthogonal unit tangents, friction isotropic in \
                         their plane), as in `slip: vector(dot(p[0]), dot(p[2]))`",
                        def.name,
                        components.len()
                    )));
                }
            }
            continue;
        }
        let lowered = cx.lower(value)?;
        fields.push(lowered);
        law.insert(name, lowered);
    }
    if !def.has_gap && !law.contains_key("normal") {
        return Err(syn::Error::new(
            def.name.span(),
            format!(
                "contact `{}` has no gap: write its gap (`{}: y >= 0 {{ .. }}`), or give the normal \
                 force its friction acts against (`{}: {{ normal: F, friction: mu, slip: dot(x) }}`)",
                def.name, def.name, def.name
            ),
        ));
    }
    let (static_friction, kinetic_friction) = match (
        law.get("friction"),
        law.get("static_friction"),
        law.get("kinetic_friction"),
    ) {
        (Some(&mu), _, _) => (mu, mu),
        (None, Some(&s), Some(&k)) => (s, k),
        (None, None, None) => (Pool::ZERO, Pool::ZERO),
        (None, _, _) => {
            let key = def
                .fields
                .iter()
                .find(|(k, _)| k.to_string().ends_with("_friction"))
                .map(|(k, _)| k.span())
                .unwrap_or_else(|| def.name.span());
            return Err(syn::Error::new(
                key,
                format!(
                    "contact `{}` gives one friction coefficient: give both `static_friction:` and \
                     `kinetic_friction:`, or `friction:` for one coefficient of both",
                    def.name
                ),
            ));
        }
    };
    Ok(Contact {
        label: def.name.to_string(),
        entry,
        sides: (lhs, rhs),
        fields,
        gap,
        slip: law.get("slip").copied(),
        second_slip,
        restitution: law.get("restitution").copied().unwrap_or(Pool::ZERO),
        static_friction,
        kinetic_friction,
        normal: law.get("normal").copied(),
    })
}

/// The constraints of one entry `name: lhs = rhs` (the `def`-th), `φ = lhs
/// − rhs`: one, or one per index of `name[i in a..b]`.
fn constraint(
    cx: &mut Lowering,
    def: &ConstraintDef,
    entry: usize,
) -> syn::Result<Vec<Constraint>> {
    let lower = |cx: &mut Lowering, index: Option<i64>| -> syn::Result<Constraint> {
        let lhs = cx.lower(&def.lhs)?;
        let rhs = match &def.rhs {
            None => None,
            Some(rhs) => Some(cx.lower(rhs)?),
        };
        let value = match rhs {
            None => lhs,
            Some(rhs) => cx.pool.sub(lhs, rhs),
        };
        let label = match index {
            None => def.name.to_string(),
            Some(k) => format!("{}[{k}]", def.name),
        };
        Ok(Constraint {
            label,
            entry,
            index,
            lhs,
            rhs,
            value,
        })
    };
    let Some(range) = &def.index else {
        return Ok(vec![lower(cx, None)?]);
    };
    let (lo, hi) = cx.range(range)?;
    let mut out = Vec::new();
    for k in lo..hi {
        // Each element is a name kept to the end, like an indexed `let`'s.
        cx.pool.charge(STEPS_PER_NAME);
        cx.env.push((range.var.to_string(), k));
        let c = lower(cx, Some(k));
        cx.env.pop();
        out.push(c?);
    }
    Ok(out)
}

/// One entry `target = value` of `forces:`; `targets`, those before it. A
/// vector force along a vector position (`r = vector(fx, fy, fz)`, `r` a
/// `let` of a vector) is one force along each component.
fn force(
    targets: &mut HashSet<String>,
    cx: &mut Lowering,
    target: Expr,
    value: Expr,
) -> syn::Result<Vec<Force>> {
    let vector_target = match &target {
        Expr::Name(n) => match cx.names.get(&n.to_string()) {
            Some(&Binding::Array { lo, hi, .. }) if hi > lo => Some((n.clone(), lo, hi)),
            _ => None,
        },
        _ => None,
    };
    let Some((base, lo, hi)) = vector_target else {
        return Ok(vec![one_force(targets, cx, target, value)?]);
    };
    let components = match cx.lower_value(&value)? {
        Value::Vector(c) if c.len() as i64 == hi - lo => c,
        // A number along an indexed name: the error of `one_force`.
        Value::Scalar(_) => return Ok(vec![one_force(targets, cx, target, value)?]),
        v => return Err(value.range().error(format!(
            "a force along `{base}`, which has {} components, is a vector of as many; this is {}",
            hi - lo,
            describe(&v)
        ))),
    };
    let mut out = Vec::with_capacity(components.len());
    for (k, id) in (lo..hi).zip(components) {
        let element = Expr::Index {
            base: base.clone(),
            index: Box::new(Expr::Num {
                value: k as f64,
                span: base.span(),
            }),
            range: target.range(),
        };
        let (label, position) = cx.force_target(&element, true)?;
        if !targets.insert(label.clone()) {
            return Err(target.range().error(format!(
                "a second force on `{label}`: write the sum of the forces in one entry"
            )));
        }
        out.push(Force {
            label,
            target: element,
            ast: value.clone(),
            position,
            value: id,
        });
    }
    if !out.iter().any(|f| {
        cx.symbols
            .coordinates
            .iter()
            .any(|&q| cx.pool.depends_on(f.position, q))
    }) {
        return Err(target.range().error(format!(
            "force along `{base}`, which depends on no coordinate (so the force does no virtual work): \
             a force acts along a position, a `let` of the coordinates"
        )));
    }
    Ok(out)
}

/// One scalar force `target = value`.
fn one_force(
    targets: &mut HashSet<String>,
    cx: &mut Lowering,
    target: Expr,
    value: Expr,
) -> syn::Result<Force> {
    let (label, position) = cx.force_target(&target, false)?;
    if !targets.insert(label.clone()) {
        return Err(target.range().error(format!(
            "a second force on `{label}`: write the sum of the forces in one entry"
        )));
    }
    let id = cx.lower(&value)?;
    Ok(Force {
        label,
        target,
        ast: value,
        position,
        value: id,
    })
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
            ast: first.ast.then(BinOp::Add, ast),
            keyword: first.keyword,
        },
    });
    Ok(())
}

/// What the stub of a model with an error knows of its shape.
pub struct Shape {
    /// The number of coordinates.
    pub dof: usize,
    /// The parameter fields.
    pub fields: Vec<Field>,
    /// The input fields.
    pub inputs: Vec<Field>,
    /// The number of holonomic constraints.
    pub constraints: usize,
    /// The number of contacts.
    pub contacts: usize,
    /// The `let` values, an indexed `let` counting its elements.
    pub lets: usize,
}

/// For the stub of a model with an error: its number of coordinates, its
/// parameter and input fields and its number of constraints, counted as
/// lowering will count them once the error is fixed (a duplicated name or
/// `t` is the error, not an extra one; a size or range that cannot be
/// evaluated counts as one).
pub fn declared_shape(def: &ModelDef) -> Shape {
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
    let mut seen: HashSet<String> = HashSet::from(["t".to_string()]);
    let mut dof = 0;
    let mut fields = Vec::new();
    let mut inputs = Vec::new();
    let mut constraints = 0usize;
    let mut contacts = 0usize;
    let mut lets = 0usize;
    let mut seen_lets: HashSet<String> = HashSet::new();
    // The `let`s of vectors so far, with their lengths.
    let mut vectors: HashMap<String, usize> = HashMap::new();
    // Apart from the other names: a constraint named like a coordinate is
    // the error, and the coordinate still counts.
    let mut seen_constraints: HashSet<String> = HashSet::new();
    let mut field_names: HashSet<String> = HashSet::new();
    for item in &def.items {
        if let Item::Let { name, index, value } = item {
            if seen_lets.insert(name.to_string()) {
                let n = match index {
                    None => written_length(value, &vectors),
                    Some(range) => cx.range(range).map_or(1, |(lo, hi)| (hi - lo) as usize),
                };
                if index.is_none() && n != 1 {
                    vectors.insert(name.to_string(), n);
                }
                lets += n;
            }
            continue;
        }
        if let Item::Contacts { entries, .. } = item {
            for e in entries {
                if seen_constraints.insert(e.name.to_string()) {
                    contacts += 1;
                }
            }
            continue;
        }
        if let Item::Constraints { entries, .. } = item {
            for e in entries {
                if !seen_constraints.insert(e.name.to_string()) {
                    continue;
                }
                constraints += match &e.index {
                    None => 1,
                    Some(range) => cx.range(range).map_or(1, |(lo, hi)| (hi - lo) as usize),
                };
            }
            continue;
        }
        let (Item::Coordinates { names, .. }
        | Item::Parameters { names, .. }
        | Item::Inputs { names, .. }) = item
        else {
            continue;
        };
        for d in names {
            // An input clashes only with another field: an input named
            // like a coordinate is still the input the code using it means.
            let fresh = match item {
                Item::Inputs { .. } => field_names.insert(d.name.to_string()),
                Item::Parameters { .. } => {
                    field_names.insert(d.name.to_string());
                    seen.insert(d.name.to_string())
                }
                _ => seen.insert(d.name.to_string()),
            };
            if !fresh {
                continue;
            }
            let len = d.len.as_ref().map(|e| cx.length(e).unwrap_or(1));
            let field = Field {
                name: d.name.clone(),
                len,
                domain: d.domain,
            };
            match item {
                Item::Coordinates { .. } => dof += len.unwrap_or(1),
                Item::Inputs { .. } => inputs.push(field),
                _ => fields.push(field),
            }
        }
    }
    Shape {
        dof,
        fields,
        inputs,
        constraints,
        contacts,
        lets,
    }
}

/// The number of components of a `let`'s value as written, for the stub's
/// count: a vector's where the text shows it (`vector(..)`, a vector
/// function, a vector `let` before it, and sums, differences and multiples
/// of these), else 1.
fn written_length(e: &Expr, vectors: &HashMap<String, usize>) -> usize {
    match e {
        Expr::Call { func, args, .. } => match func.to_string().as_str() {
            "vector" => args.len().max(1),
            "cross" | "rotate" | "rotate_x" | "rotate_y" | "rotate_z" | "body_rates"
            | "space_rates" => 3,
            "dot" => args.first().map_or(1, |a| written_length(a, vectors)),
            _ => 1,
        },
        Expr::Name(name) => vectors.get(&name.to_string()).copied().unwrap_or(1),
        Expr::Neg { inner, .. } => written_length(inner, vectors),
        Expr::Chain { first, rest, .. } => std::iter::once(&**first)
            .chain(rest.iter().map(|(_, x)| x))
            .map(|x| written_length(x, vectors))
            .max()
            .unwrap_or(1),
        _ => 1,
    }
}
