//! The symbolic engine behind `lagrangian!`.
//!
//! An ordinary library, so that it is unit-tested and benchmarked without
//! rustc: it takes the macro's tokens and returns the generated items. Two
//! layers. The pipeline, one module per stage:
//!
//! 1. [`parse`]: tokens → [`ast`], with mathematical precedence for `^`;
//! 2. [`model`]: names resolved, `let`s and `dot` expanded, every section
//!    lowered into the expression DAG, one pass per function;
//! 3. [`check`]: the physics (V free of velocities, T quadratic in them, a
//!    regular mass matrix; constraints holonomic, fewer than the
//!    coordinates and independent), each failure a spanned error;
//! 4. [`derive`](mod@derive): `M = ∂²T/∂q̇²` and
//!    `f = ∂L/∂q − (∂²L/∂q̇∂q) q̇ − ∂²L/∂q̇∂t − ∂R/∂q̇ + Q`, and for
//!    constraints `φ = 0` their Jacobian `G` and bias `γ`; for a model
//!    whose `M` and `f` would be formed from the parts of `T` on a tree of
//!    links ([`derive::articulated::looks_first`]), the tree is looked for
//!    first, and where it is found `M` and `f` are never derived;
//! 5. [`emit`]: straight-line, allocation-free Rust for each const and
//!    method listed in [`emit::api`]; [`render`] the same equations as text.
//!    On any error, [`fallback`] emits the error and a stub of the same API,
//!    so one mistake gives one error.
//!
//! Under it, the algebra kernel [`expr`], which knows nothing of models: the
//! hash-consed [`Pool`](expr::Pool) of nodes, built only through its
//! simplifying constructors ([`expr::simplify`]), its derivatives
//! ([`expr::diff`]), numeric evaluation ([`expr::eval`]) and the choice of
//! shared nodes to bind in emitted code ([`expr::cse`]).
//!
//! Where to add things: an output of the generated code is one entry of
//! [`emit::api::METHODS`] plus the code in [`derive`](mod@derive) that computes its
//! expressions; a section of the language is a variant of [`ast::Item`], its
//! parse in [`parse`], and its lowering pass in [`model`]; a check is a
//! function of [`check`] called from [`derive`](fn@derive).
//!
//! Output is deterministic: no step iterates a hash map, and node ids (which
//! order everything) are handed out in a deterministic order.
//!
//! ```
//! let tokens: proc_macro2::TokenStream = r#"
//!     pub struct Pendulum {
//!         coordinates: theta;
//!         parameters: m, l, g;
//!         let y = -l*cos(theta);
//!         kinetic: m/2*l^2*dot(theta)^2;
//!         potential: m*g*y;
//!     }
//! "#.parse().unwrap();
//! let derived = lagrange_engine::derive(tokens).unwrap();
//! // M = m l², f = -m g l sin θ
//! assert_eq!(derived.equations_text(), "M[theta, theta] = m*l^2\nf[theta] = -l*m*g*sin(theta)\n");
//! ```
//!
//! # Limits
//!
//! The engine runs inside rustc on every build, so whatever the input it
//! expands or stops with a spanned error, within seconds, never with a
//! panic, a stack overflow or a wrapped number:
//!
//! - **Nesting.** An expression nests at most
//!   [`MAX_NESTING`](parse::expression::MAX_NESTING) = 128 levels
//!   (parentheses, calls, brackets, sums, unary minuses, exponents, method
//!   calls). Sums and products are flat: `x + x + ... + x` may have any
//!   number of terms.
//! - **Depth.** An expression, counting the `let`s it uses (`let a1 =
//!   sin(a0); let a2 = sin(a1); ...`), is at most [`MAX_DEPTH`](expr::MAX_DEPTH)
//!   = 400 nodes deep, derivatives included. With the nesting limit this
//!   keeps the engine's recursion under about 1.5 MiB of stack in a debug
//!   build, 0.3 MiB optimized; rustc runs a proc macro on a thread of 8 MiB.
//! - **Integers.** Sizes, indices and ranges are 64-bit integer arithmetic,
//!   every operation checked: an overflow is an error on the expression. A
//!   range or an indexed name has at most [`MAX_RANGE`](model::MAX_RANGE) =
//!   10 000 elements.
//! - **Work.** Every stage charges a step counter for what it does (a node
//!   built or looked up, a term of an unrolled sum, a derivative, an entry
//!   of `M`, the code to write), and a model that needs more than
//!   [`DEFAULT_BUDGET`](expr::DEFAULT_BUDGET) = 50 000 000 steps stops with
//!   an error naming the budget. The 20-link chain takes 3 million steps,
//!   the 30-link 8 million, the 60-link 44 million; any model stops within
//!   about 2 s and 400 MB with the engine optimized, as this workspace's
//!   profile builds it. Cargo builds proc macros unoptimized unless told
//!   otherwise, and the engine is then 6 to 10 times slower (about 7 s to
//!   spend the budget). `#[lagrange(budget = N)]` on the struct gives one
//!   model `N` steps instead (at most [`MAX_BUDGET`](ast::MAX_BUDGET)); time
//!   and memory grow in proportion.
//!
//! - **Generated code.** Before writing the functions, the engine
//!   estimates their size ([`emit::charge`]), and a model over
//!   [`DEFAULT_MAX_CODE`](emit::DEFAULT_MAX_CODE) = 4 000 000 bytes (or
//!   its own `#[lagrange(max_code = N)]`) stops with an error saying what
//!   to write instead: rustc's memory grows faster than the code (3.7 MB
//!   of it took 4.7 GB to build, 8.4 MB 17.9 GB).
//!
//! The budget counts steps, not time, so an expansion is the same on every
//! machine: a model expands everywhere or nowhere.

#![deny(missing_docs)]

pub mod ast;
pub mod check;
pub mod derive;
pub mod emit;
pub mod expr;
pub mod fallback;
pub mod model;
pub mod parse;
pub mod render;
pub mod robot;

use proc_macro2::TokenStream;

/// A derived model: the lowered model and its equations of motion.
pub struct Derived {
    /// The lowered model, its pool holding the equations' nodes too.
    pub model: model::Model,
    /// The equations of motion.
    pub equations: derive::Equations,
}

impl Derived {
    /// The generated Rust items.
    pub fn tokens(&self) -> TokenStream {
        let texts = (self.equations_text(), self.equations_latex());
        emit::emit(&self.model, &self.equations, (&texts.0, &texts.1))
    }

    /// The equations as readable text (the generated `EQUATIONS` constant).
    pub fn equations_text(&self) -> String {
        render::render(&self.model, &self.equations)
    }

    /// The equations as LaTeX (the generated `LATEX` constant).
    pub fn equations_latex(&self) -> String {
        render::render_latex(&self.model, &self.equations)
    }

    /// Values of the symbols in the order `t, q, q̇, parameters`. A model
    /// with inputs takes their values after the parameters' in `params`.
    fn values(&self, t: f64, q: &[f64], qdot: &[f64], params: &[f64]) -> Vec<f64> {
        let p = self.model.parameters.len().min(params.len());
        let mut v = vec![t];
        v.extend_from_slice(q);
        v.extend_from_slice(qdot);
        v.extend_from_slice(&params[..p]);
        v.extend(std::iter::repeat_n(0.0, q.len())); // accelerations
        v.extend_from_slice(&params[p..]); // inputs
        assert_eq!(
            v.len(),
            self.model.symbols.count(),
            "wrong number of values"
        );
        v
    }

    /// Evaluates `∂f/∂u` numerically (row-major, `N × K`), for tests;
    /// `params` holds the parameters, then the inputs. Empty for a model
    /// without inputs.
    pub fn eval_input_jacobian(
        &self,
        t: f64,
        q: &[f64],
        qdot: &[f64],
        params: &[f64],
    ) -> Vec<Vec<f64>> {
        let Some(rows) = &self.equations.input_jacobian else {
            return Vec::new();
        };
        rows.iter()
            .map(|row| self.eval(row, t, q, qdot, params))
            .collect()
    }

    /// Evaluates `M` numerically (row-major), for tests; empty for a model
    /// solved by the recursion without `M` derived.
    pub fn eval_mass_matrix(&self, t: f64, q: &[f64], params: &[f64]) -> Vec<Vec<f64>> {
        let zeros = vec![0.0; q.len()];
        let v = self.values(t, q, &zeros, params);
        let mut memo = Default::default();
        self.equations
            .mass
            .iter()
            .map(|row| {
                row.iter()
                    .map(|&m| self.model.pool.eval_memo(m, &v, &mut memo))
                    .collect()
            })
            .collect()
    }

    /// Evaluates `f` numerically, for tests; empty for a model solved by
    /// the recursion without `f` derived.
    pub fn eval_forcing(&self, t: f64, q: &[f64], qdot: &[f64], params: &[f64]) -> Vec<f64> {
        let v = self.values(t, q, qdot, params);
        let mut memo = Default::default();
        self.equations
            .forcing
            .iter()
            .map(|&f| self.model.pool.eval_memo(f, &v, &mut memo))
            .collect()
    }

    /// Evaluates `T + V` numerically, for tests.
    pub fn eval_energy(&self, t: f64, q: &[f64], qdot: &[f64], params: &[f64]) -> f64 {
        let v = self.values(t, q, qdot, params);
        self.model.pool.eval(self.equations.energy, &v)
    }

    /// Evaluates any of the equations' expressions numerically (the
    /// constraints' `φ`, `G`, `γ`, ...), for tests.
    pub fn eval(
        &self,
        ids: &[expr::ExprId],
        t: f64,
        q: &[f64],
        qdot: &[f64],
        params: &[f64],
    ) -> Vec<f64> {
        let v = self.values(t, q, qdot, params);
        let mut memo = Default::default();
        ids.iter()
            .map(|&id| self.model.pool.eval_memo(id, &v, &mut memo))
            .collect()
    }

    /// The size of the generated functions in bytes as the engine
    /// estimates it before writing them, what `#[lagrange(max_code = N)]`
    /// is checked against ([`emit::charge`]).
    pub fn estimated_code_bytes(&self) -> u64 {
        let pool = &self.model.pool;
        pool.uncharged(|| emit::charge(&self.model, &self.equations))
    }

    /// Operation counts of `G` and `γ` together, as emitted (with sharing)
    /// and as a tree; `None` for a model without constraints.
    pub fn constraint_op_counts(&self) -> Option<(expr::cse::OpCount, expr::cse::OpCount)> {
        let c = self.equations.constraints.as_ref()?;
        let mut roots: Vec<expr::ExprId> = c.jacobian.iter().flatten().copied().collect();
        roots.extend(&c.bias);
        Some((
            expr::cse::shared_ops(&self.model.pool, &roots),
            expr::cse::tree_ops(&self.model.pool, &roots),
        ))
    }

    /// Operation counts of `M` and `f` as emitted (with sharing) and as a
    /// tree without sharing would need; of the recursion's parts for a
    /// model solved without `M` and `f` derived (their `mass` empty).
    pub fn op_counts(&self) -> (expr::cse::OpCount, expr::cse::OpCount) {
        let n = self.model.dof();
        let mut roots = Vec::new();
        if self.equations.mass.len() != n {
            if let Some(a) = &self.equations.articulated {
                roots.extend(&a.roots);
            }
        }
        for i in 0..self.equations.mass.len() {
            for j in i..n {
                roots.push(self.equations.mass[i][j]);
            }
        }
        roots.extend(&self.equations.forcing);
        (
            expr::cse::shared_ops(&self.model.pool, &roots),
            expr::cse::tree_ops(&self.model.pool, &roots),
        )
    }
}

/// The bodies of the `lagrangian! { .. }` invocations in a token stream
/// (a source file), at any depth: what tools outside rustc hand to
/// [`derive`](fn@derive) or [`expand`] to study the repository's own models.
pub fn invocations(source: TokenStream) -> Vec<TokenStream> {
    fn walk(stream: TokenStream, found: &mut Vec<TokenStream>) {
        use proc_macro2::{Delimiter, TokenTree};
        let tokens: Vec<TokenTree> = stream.into_iter().collect();
        for (i, tt) in tokens.iter().enumerate() {
            if let TokenTree::Group(g) = tt {
                let after_bang = i >= 2
                    && matches!(&tokens[i - 1], TokenTree::Punct(p) if p.as_char() == '!')
                    && matches!(&tokens[i - 2], TokenTree::Ident(id) if id == "lagrangian");
                if after_bang && g.delimiter() == Delimiter::Brace {
                    found.push(g.stream());
                } else {
                    walk(g.stream(), found);
                }
            }
        }
    }
    let mut found = Vec::new();
    walk(source, &mut found);
    found
}

/// Parses, lowers, checks and differentiates a model.
pub fn derive(input: TokenStream) -> syn::Result<Derived> {
    derive_with_budget(input, expr::DEFAULT_BUDGET)
}

/// [`derive`](fn@derive) with a work budget other than the default (for a
/// model without `#[lagrange(budget = N)]`): a model that needs more steps
/// stops with an error naming the budget.
pub fn derive_with_budget(input: TokenStream, budget: u64) -> syn::Result<Derived> {
    let parsed = parse::parse(input)?;
    if let Some(e) = parsed.error {
        return Err(e);
    }
    derive_model(parsed.model, budget)
}

fn derive_model(def: ast::ModelDef, budget: u64) -> syn::Result<Derived> {
    let budget = def.options.budget.unwrap_or(budget);
    // Kept for a second lowering where the tree, looked for first, is not
    // found: the model is then derived from a fresh pool, exactly as before.
    let spare = derive::articulated::may_look_first(&def.options).then(|| def.clone());
    let mut model = lowered_and_checked(def, budget)?;
    if let Some(spare) = spare {
        if derive::articulated::looks_first(&model) {
            let asked = model.options.articulated == Some(true);
            let mut equations = derive::without_mass_matrix(&mut model);
            let r = if model.pool.exhausted() {
                Ok(false)
            } else {
                derive::articulated::first(&mut model, &mut equations)
            };
            // Unasked, a search that ran out of budget is given up like one
            // that did not find the tree: the model is derived as before
            // the search came first, from a fresh pool.
            let found = if asked {
                within_budget(&model, r)?
            } else {
                r? && !model.pool.exhausted()
            };
            if found {
                // Emitting is linear in what it writes: charged now, so that
                // a model within its budget is one whose code is written
                // within it too.
                let size = emit::charge(&model, &equations);
                within_budget(&model, Ok(()))?;
                within_code_limit(&model, size)?;
                return Ok(Derived { model, equations });
            }
            model = lowered_and_checked(spare, budget)?;
        }
    }
    let mut equations = derive::euler_lagrange(&mut model);
    within_budget(&model, Ok(()))?;
    let r = check::inputs::momenta_hold_no_input(&mut model, &equations);
    within_budget(&model, r)?;
    let r = check::mass_matrix_is_regular(&mut model, &mut equations);
    within_budget(&model, r)?;
    let r = check::constraints::constraints_are_independent(&mut model, &equations);
    within_budget(&model, r)?;
    let r = derive::regressor::regressor(&mut model, &mut equations);
    within_budget(&model, r)?;
    // Emitting is linear in what it writes: charged now, so that a model
    // within its budget is one whose code is written within it too.
    let size = emit::charge(&model, &equations);
    within_budget(&model, Ok(()))?;
    // Last, within what is left: unasked, the search gives up rather than
    // spend the budget a model expanded within before it existed; its
    // function's emission is charged there.
    let r = derive::articulated::articulated(&mut model, &mut equations);
    within_budget(&model, r)?;
    within_code_limit(&model, size)?;
    Ok(Derived { model, equations })
}

/// A model lowered into a pool of `budget` steps, and checked before any
/// derivative of `T` is taken.
fn lowered_and_checked(def: ast::ModelDef, budget: u64) -> syn::Result<model::Model> {
    let mut model = model::lower_with_pool(def, expr::Pool::with_budget(budget))?;
    let r = check::constants_are_finite(&mut model);
    within_budget(&model, r)?;
    let r = check::potential_has_no_velocity(&mut model);
    within_budget(&model, r)?;
    let r = check::constraints::constraints_are_admissible(&mut model);
    within_budget(&model, r)?;
    let r = check::contacts::contacts_are_admissible(&mut model);
    within_budget(&model, r)?;
    let r = check::inputs::constraints_hold_no_input(&mut model);
    within_budget(&model, r)?;
    Ok(model)
}

/// The error of a model whose generated code, estimated at `bytes`, is
/// over its limit ([`emit::code_limit_error`]).
fn within_code_limit(model: &model::Model, bytes: u64) -> syn::Result<()> {
    match emit::code_limit_error(model, bytes) {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// A stage's result, or the budget error if the budget ran out during it
/// (its result is then garbage). A stage's own error stands: it was found
/// on nodes built within the budget.
fn within_budget<T>(model: &model::Model, result: syn::Result<T>) -> syn::Result<T> {
    let value = result?;
    model
        .pool
        .check_budget()
        .map_err(|x| model::limit_error(&model.name, x))?;
    Ok(value)
}

/// The macro: tokens in, items out. Never panics on user input; every error
/// is a `compile_error!` on the offending tokens, plus a stub of the model.
/// A URDF's path is relative to the manifest of the crate being compiled
/// (`CARGO_MANIFEST_DIR`, which cargo sets for rustc).
pub fn expand(input: TokenStream) -> TokenStream {
    expand_with(input, None)
}

/// [`expand`], with a URDF's path relative to `manifest_dir` instead of
/// `CARGO_MANIFEST_DIR`: for a tool that expands the models of several
/// crates in one process (the golden test, over the whole repository).
pub fn expand_in(input: TokenStream, manifest_dir: &std::path::Path) -> TokenStream {
    expand_with(input, Some(manifest_dir))
}

fn expand_with(input: TokenStream, manifest_dir: Option<&std::path::Path>) -> TokenStream {
    if robot::is_robot(&input) {
        return robot::expand(input, manifest_dir);
    }
    let parsed = match parse::parse(input) {
        Ok(p) => p,
        Err(e) => return e.to_compile_error(),
    };
    let stub = fallback::Stub::of(&parsed.model);
    if let Some(e) = parsed.error {
        return stub.emit(e);
    }
    match derive_model(parsed.model, expr::DEFAULT_BUDGET) {
        Ok(derived) => derived.tokens(),
        Err(e) => stub.emit(e),
    }
}
