//! AST → model: names resolved to symbols, `let`s and `dot` expanded, every
//! section lowered into the expression DAG. Errors here are about the text
//! (unknown or duplicated names, misplaced sections); the physics is checked
//! in [`check`](crate::check).
//!
//! Lowering runs six passes over the items (`passes.rs`), each a function:
//! the `const`s; the declarations (every name once, the coordinates and
//! parameters with their sizes); the symbols; the `constants:`; the `let`s;
//! the sections. An expression is lowered by `lowering.rs`, with the index
//! arithmetic of [`index`], the function table of [`functions`] and the
//! names of `scope.rs`; `locate.rs` finds the tokens behind a node for the
//! checks' errors.

pub mod functions;
pub mod index;
mod locate;
mod lowering;
mod passes;
mod scope;
pub mod symbols;
mod vectors;

pub use functions::FUNCTIONS;
pub use index::MAX_RANGE;
pub use passes::{Shape, declared_shape};
pub use symbols::{SymKind, Symbols};

use crate::ast::MAX_BUDGET;
use crate::ast::{Expr, ModelDef, SpanRange};
use crate::expr::{Exceeded, ExprId, MAX_DEPTH, Pool};
use lowering::Lowering;
use scope::{Binding, Declared};
use std::collections::HashMap;
use syn::{Attribute, Ident, Visibility};

/// A section's expression with the tokens it came from. A section written
/// more than once is their sum: `ast` is then the `+` of the parts.
pub struct Section {
    /// The section's keyword, for errors.
    pub keyword: Ident,
    /// The section as written (the sum of its parts).
    pub ast: Expr,
    /// The section lowered.
    pub value: ExprId,
}

/// One scalar of the model: a name, or one element of an indexed name.
#[derive(Clone, Debug)]
pub struct Scalar {
    /// The declared name.
    pub name: Ident,
    /// The element's index, for an element of an indexed name.
    pub index: Option<usize>,
}

impl Scalar {
    /// The span of the name, for errors.
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
    /// The field's name.
    pub name: Ident,
    /// The array length of an indexed parameter, `None` for a scalar.
    pub len: Option<usize>,
    /// A parameter's declared domain, for every element of an indexed one.
    pub domain: Option<crate::ast::Domain>,
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
    /// The target as written.
    pub target: Expr,
    /// The force as written.
    pub ast: Expr,
    /// The target lowered: the position the force acts along.
    pub position: ExprId,
    /// The force lowered.
    pub value: ExprId,
}

/// A holonomic constraint `φ(t, q) = 0`: an entry of `constraints:`, or
/// one element of an indexed entry.
pub struct Constraint {
    /// As `EQUATIONS` and `CONSTRAINTS` name it: `rod`, `link[2]`.
    pub label: String,
    /// Which entry of [`Model::constraint_defs`] it comes from.
    pub entry: usize,
    /// The value of the entry's index variable, for an indexed entry.
    pub index: Option<i64>,
    /// The sides as lowered, for the checks to tell which is at fault.
    pub lhs: ExprId,
    /// The right-hand side, if written as `lhs = rhs`.
    pub rhs: Option<ExprId>,
    /// `φ = lhs − rhs`.
    pub value: ExprId,
}

/// A unilateral contact, an entry of `contacts:`: its gap `g(t, q) ≥ 0`,
/// the slip velocity friction acts against, and its law's coefficients
/// (each a constant of the parameters).
pub struct Contact {
    /// As `CONTACTS` names it.
    pub label: String,
    /// Which entry of [`Model::contact_defs`] it comes from.
    pub entry: usize,
    /// The sides as lowered, for the checks to tell which is at fault.
    pub sides: (ExprId, ExprId),
    /// The law's entries as lowered, in the order written.
    pub fields: Vec<ExprId>,
    /// The gap, `lhs − rhs` for `>=`, `rhs − lhs` for `<=`.
    pub gap: ExprId,
    /// The slip velocity, if written (`slip:`); its first component where
    /// it is a vector.
    pub slip: Option<ExprId>,
    /// The second component of a slip vector (`slip: vector(u, v)`): the
    /// contact point's velocity along a second tangent of the surface,
    /// friction isotropic in the plane of the two.
    pub second_slip: Option<ExprId>,
    /// The coefficient of restitution (`restitution:`, zero by default).
    pub restitution: ExprId,
    /// The static friction coefficient (zero without friction).
    pub static_friction: ExprId,
    /// The kinetic friction coefficient (zero without friction).
    pub kinetic_friction: ExprId,
    /// The given normal force (`normal:`) of a contact without a gap.
    pub normal: Option<ExprId>,
}

/// The lowered model.
pub struct Model {
    /// The user's attributes, passed through to the struct.
    pub attrs: Vec<Attribute>,
    /// The options of `#[lagrange(...)]`.
    pub options: crate::ast::Options,
    /// The struct's visibility.
    pub vis: Visibility,
    /// The struct's name.
    pub name: Ident,
    /// The generalized coordinates, one scalar each, in the order of `q`.
    pub coordinates: Vec<Scalar>,
    /// The parameters, one scalar each, in the order of the symbols.
    pub parameters: Vec<Scalar>,
    /// The parameters as struct fields, in declaration order.
    pub fields: Vec<Field>,
    /// The control inputs, one scalar each, in the order of `u` and of
    /// their symbols; empty for a model without `inputs:`.
    pub inputs: Vec<Scalar>,
    /// The inputs as struct fields (after the parameters' fields), in
    /// declaration order.
    pub input_fields: Vec<Field>,
    /// What each symbol id stands for.
    pub symbols: Symbols,
    /// The kinetic energy T.
    pub kinetic: Section,
    /// The potential energy V.
    pub potential: Section,
    /// The Rayleigh dissipation function R, if the model has one.
    pub dissipation: Option<Section>,
    /// The non-conservative forces, in the order written.
    pub forces: Vec<Force>,
    /// The `constraints:` entries as written, for the checks' errors.
    pub constraint_defs: Vec<crate::ast::ConstraintDef>,
    /// The holonomic constraints, in the order of `φ`; empty for a model
    /// in minimal coordinates.
    pub constraints: Vec<Constraint>,
    /// The `contacts:` entries as written, for the checks' errors.
    pub contact_defs: Vec<crate::ast::ContactDef>,
    /// The unilateral contacts, in the order written; empty for a model
    /// without `contacts:`.
    pub contacts: Vec<Contact>,
    /// Every `let` value by name, in declaration order (an indexed `let`
    /// as `x[0]`, `x[1]`, …): what the generated `lets` returns.
    pub lets: Vec<(String, ExprId)>,
    /// The expression DAG holding every lowered expression.
    pub pool: Pool,
    /// Every name as lowering left it, so that `locate` can lower a piece
    /// of a section again.
    scope: HashMap<String, Binding>,
}

/// Lowers a parsed model, pass by pass. The first error met is returned.
pub fn lower_with_pool(def: ModelDef, pool: Pool) -> syn::Result<Model> {
    let mut declared = Declared::default();
    let mut cx = Lowering::new(pool, &def.name);
    passes::consts(&def, &mut declared, &mut cx)?;
    let mut decls = passes::declarations(&def, &mut declared, &cx)?;
    let symbols = passes::bind_symbols(&def, &mut decls, &mut cx);
    passes::constants(&def, &mut cx)?;
    let lets = passes::lets(&def, &mut cx)?;
    let sections = passes::sections(def.items, &def.name, &mut cx)?;
    cx.pool
        .check_budget()
        .map_err(|x| limit_error(&def.name, x))?;
    Ok(Model {
        attrs: def.attrs,
        options: def.options,
        vis: def.vis,
        name: def.name,
        coordinates: decls.coordinates,
        parameters: decls.parameters,
        fields: decls.fields,
        inputs: decls.inputs,
        input_fields: decls.input_fields,
        symbols,
        kinetic: sections.kinetic,
        potential: sections.potential,
        dissipation: sections.dissipation,
        forces: sections.forces,
        constraint_defs: sections.constraint_defs,
        constraints: sections.constraints,
        contact_defs: sections.contact_defs,
        contacts: sections.contacts,
        lets,
        pool: cx.pool,
        scope: cx.names,
    })
}

/// The error of a model that ran into a limit of the engine (its work
/// budget, or the depth of its expressions), on the model's name.
pub fn limit_error(name: &Ident, exceeded: Exceeded) -> syn::Error {
    let message = match exceeded {
        Exceeded::Budget(budget) => format!(
            "the expansion of `{name}` exceeds the engine's work budget of {budget} steps: the model is too large \
             to derive symbolically in reasonable time and memory (simplify it, or split it); if it really needs \
             more, raise the budget with `#[lagrange(budget = {})]` on the struct",
            budget.saturating_mul(4).min(MAX_BUDGET)
        ),
        Exceeded::Depth => format!(
            "the derivation of `{name}` nests expressions more than {MAX_DEPTH} levels deep: write the model with \
             fewer nested `let`s and functions"
        ),
    };
    syn::Error::new(name.span(), message)
}

impl Model {
    /// The number of coordinates (degrees of freedom), `N`.
    pub fn dof(&self) -> usize {
        self.coordinates.len()
    }

    /// The entry a constraint comes from, and the index variable bound as
    /// it was when the constraint was lowered (for [`Model::locate_in`]).
    pub fn constraint_def(
        &self,
        c: &Constraint,
    ) -> (&crate::ast::ConstraintDef, Vec<(String, i64)>) {
        let def = &self.constraint_defs[c.entry];
        let env = match (&def.index, c.index) {
            (Some(range), Some(k)) => vec![(range.var.to_string(), k)],
            _ => Vec::new(),
        };
        (def, env)
    }
}

impl Section {
    /// From the section's keyword to the end of its expression.
    pub fn keyword_and_value(&self) -> SpanRange {
        SpanRange::single(self.keyword.span()).to(self.ast.range())
    }
}
