//! Lagrange's equations, symbolically.
//!
//! With `L = T - V`, `p_i = ∂T/∂q̇_i` (V holds no velocity, see `check`):
//!
//! ```text
//! M_ij = ∂p_i/∂q̇_j
//! f_i  = ∂L/∂q_i − Σ_j (∂p_i/∂q_j) q̇_j − ∂p_i/∂t − ∂R/∂q̇_i + Q_i
//! Q_i  = Σ_forces F · ∂p/∂q_i     (virtual work of F along the position p)
//! ```
//!
//! so that `M q̈ = f`. `M` is never inverted symbolically: the runtime solves.
//! When `T` is quadratic in `q̇` (`M` free of `q̇`), `f` is computed from
//! the derivatives of `M` instead (Christoffel symbols, `forcing`), which
//! is the same function without the terms that cancel.
//! On request, the Jacobians of the residual `r = M q̈ − f` with respect to
//! `q` and `q̇`, for the Newton iterations of implicit integrators.
//!
//! A model with holonomic constraints `φ(t, q) = 0` also gets what the
//! runtime's saddle-point system `M q̈ + Gᵀλ = f, G q̈ = −γ` needs:
//!
//! ```text
//! G   = ∂φ/∂q                               (C × N)
//! φ̇   = G q̇ + ∂φ/∂t
//! γ   = Σ_j ∂φ̇/∂q_j q̇_j + ∂φ̇/∂t              so that  φ̈ = G q̈ + γ
//! ```
//!
//! `γ` is the total time derivative of `φ̇` with `q̇` held: `∂φ̇/∂q̇ = G` is
//! the part that multiplies `q̈`. Rheonomic constraints (`x = a sin(ω t)`)
//! need nothing more: their `∂/∂t` terms are in `φ̇` and `γ`.
//!
//! A model with control inputs `u` (`inputs:`) also gets `∂f/∂u` (N × K),
//! how the forcing responds to each input: what a controller designer
//! linearizes. The inputs are symbols like the parameters; the checks keep
//! them out of the momenta and the constraints, the only places where their
//! time derivatives would be needed.
//!
//! A model that asks (`#[lagrange(parameter_derivatives)]`) also gets the
//! derivatives by each parameter scalar `p_k` (P of them, an indexed
//! parameter `m[N]` being N): `∂M/∂p_k` (P matrices N × N), `∂f/∂p`
//! (N × P) and the residual's `∂r/∂p = (∂M/∂p) q̈ − ∂f/∂p` (N × P), what
//! forward sensitivities and parameter fits need; a constrained model also
//! `∂φ/∂p`, `∂φ̇/∂p` and `∂(G q̈ + γ)/∂p` (each C × P). The parameters are
//! symbols of the same pool, so these share their subexpressions with `M`
//! and `f`.

use crate::expr::{ExprId, Pool};
use crate::model::{Model, Symbols};

pub mod articulated;
mod forcing;
pub mod regressor;

/// A matrix of expressions, row-major.
pub type ExprMatrix = Vec<Vec<ExprId>>;

/// The derived equations of motion.
pub struct Equations {
    /// `M`, full and symmetric: `mass[i][j]` and `mass[j][i]` are one node.
    pub mass: ExprMatrix,
    /// `f`, the right-hand side of `M q̈ = f`.
    pub forcing: Vec<ExprId>,
    /// `T + V`.
    pub energy: ExprId,
    /// `p = ∂L/∂q̇`.
    pub momenta: Vec<ExprId>,
    /// `∂L/∂q`.
    pub lagrangian_gradient: Vec<ExprId>,
    /// `Q − ∂R/∂q̇`.
    pub nonconservative: Vec<ExprId>,
    /// `(∂r/∂q, ∂r/∂q̇)` of `r = M q̈ − f`, row-major, if the model asked.
    pub jacobians: Option<(ExprMatrix, ExprMatrix)>,
    /// The constraints' terms, for a constrained model only.
    pub constraints: Option<ConstraintEquations>,
    /// The contacts' terms, for a model with contacts only.
    pub contacts: Option<ContactEquations>,
    /// `∂f/∂u`, `N × K` row-major, for a model with inputs only.
    pub input_jacobian: Option<ExprMatrix>,
    /// The derivatives by the parameters, if the model asked.
    pub parameter_derivatives: Option<ParameterDerivatives>,
    /// The regressor, if the model asked (filled in after the checks).
    pub regressor: Option<regressor::Regressor>,
    /// The masses of `T` on a tree of increments, where the model has that
    /// form (found last, `articulated`): the runtime then solves in `O(N)`.
    pub articulated: Option<articulated::Articulated>,
}

/// The derivatives of the equations by each parameter scalar `p_k`, in
/// the order of the model's parameters (P of them).
pub struct ParameterDerivatives {
    /// `∂M/∂p_k`, one full symmetric `N × N` matrix per parameter.
    pub mass: Vec<ExprMatrix>,
    /// `∂f/∂p`, `N × P` row-major.
    pub forcing: ExprMatrix,
    /// `∂r/∂p` of the residual `r = M q̈ − f`, `N × P` row-major.
    pub residual: ExprMatrix,
    /// A constrained model's `∂φ/∂p`, `∂φ̇/∂p` and `∂(G q̈ + γ)/∂p`, each
    /// `C × P` row-major (`φ` is zero for a velocity constraint, so is its
    /// row of `∂φ/∂p`).
    pub constraints: Option<[ExprMatrix; 3]>,
}

/// What the contacts contribute, each in the order written: the gaps'
/// terms as a holonomic constraint's (`g`, `G`, `ġ`, `γ`), the slip
/// velocities' as a velocity constraint's (`T` in the rows of `G`, `v_t`
/// in the velocities, `γ_t` in the biases; zero rows for a frictionless
/// contact), and each law's restitution, static and kinetic friction.
pub struct ContactEquations {
    /// The gaps' terms.
    pub gaps: ConstraintEquations,
    /// The slip velocities' terms (a slip vector's first components).
    pub slips: ConstraintEquations,
    /// The second components' of the slip vectors (zero rows for a slip
    /// along one direction), where some contact's slip is a vector.
    pub second_slips: Option<ConstraintEquations>,
    /// `[e, μ_s, μ_k, N]` per contact, `N` its given normal force (zero
    /// where it has none).
    pub laws: Vec<[ExprId; 4]>,
}

/// What the constraints contribute, each vector in the order of `φ`:
/// holonomic ones `φ(t, q) = 0` and velocity constraints
/// `A(t, q) q̇ + b(t, q) = 0` (Lagrange–d'Alembert), whose rows are
/// marked in `velocity_rows`.
pub struct ConstraintEquations {
    /// `φ`; zero for a velocity constraint, which has no position level.
    pub values: Vec<ExprId>,
    /// `G = ∂φ/∂q`, `C × N`, row-major; `A = ∂φ/∂q̇` for a velocity
    /// constraint.
    pub jacobian: ExprMatrix,
    /// `∂φ/∂t` (zero for scleronomic constraints).
    pub time: Vec<ExprId>,
    /// `φ̇ = G q̇ + ∂φ/∂t`; for a velocity constraint its residual
    /// `A q̇ + b` itself.
    pub velocities: Vec<ExprId>,
    /// Which rows are velocity constraints.
    pub velocity_rows: Vec<bool>,
    /// `γ`, with `φ̈ = G q̈ + γ`.
    pub bias: Vec<ExprId>,
    /// `M` is singular by itself and regular on the velocities the
    /// constraints allow (a unit quaternion's rates): set by
    /// [`mass_matrix_is_regular`](crate::check::mass_matrix_is_regular),
    /// and the runtime then solves with `M + k GᵀG`.
    pub mass_regular_on_constraints_only: bool,
}

/// Derives the equations of motion of a lowered model (adding their nodes
/// to its pool); within the model's budget, else garbage that the caller
/// reports as the budget error.
#[allow(clippy::needless_range_loop)] // (i, j) index M, symmetric: the clearest form
pub fn euler_lagrange(model: &mut Model) -> Equations {
    let n = model.dof();
    let s = model.symbols.clone();
    let t_kin = model.kinetic.value;
    let v_pot = model.potential.value;
    let dissipation = model.dissipation.as_ref().map(|d| d.value);
    let forces: Vec<(ExprId, ExprId)> =
        model.forces.iter().map(|f| (f.position, f.value)).collect();
    let want_jacobians = model.options.jacobians;
    let want_parameters = model.options.parameter_derivatives;
    let phi: Vec<ExprId> = model.constraints.iter().map(|c| c.value).collect();
    let gaps: Vec<ExprId> = model.contacts.iter().map(|c| c.gap).collect();
    let slips: Vec<ExprId> = model
        .contacts
        .iter()
        .map(|c| c.slip.unwrap_or(Pool::ZERO))
        .collect();
    let second_slips: Vec<ExprId> = model
        .contacts
        .iter()
        .map(|c| c.second_slip.unwrap_or(Pool::ZERO))
        .collect();
    let laws: Vec<[ExprId; 4]> = model
        .contacts
        .iter()
        .map(|c| {
            [
                c.restitution,
                c.static_friction,
                c.kinetic_friction,
                c.normal.unwrap_or(Pool::ZERO),
            ]
        })
        .collect();
    let pool = &mut model.pool;

    // The matrices alone hold n² entries each: paid for before they are
    // made. A pool exhausted here or below yields garbage, quickly, which
    // the caller reports as the budget error.
    let square = (n as u64).saturating_mul(n as u64);
    pool.charge(square.saturating_mul(if want_jacobians { 3 } else { 1 }));
    if pool.exhausted() {
        return Equations::exhausted();
    }

    let lagrangian = pool.sub(t_kin, v_pot);
    let momenta: Vec<ExprId> = s.velocities.iter().map(|&v| pool.diff(t_kin, v)).collect();

    let mut mass = vec![vec![Pool::ZERO; n]; n];
    for i in 0..n {
        if pool.exhausted() {
            return Equations::exhausted();
        }
        for j in i..n {
            let m = pool.diff(momenta[i], s.velocities[j]);
            let m = pool.factored(m);
            mass[i][j] = m;
            mass[j][i] = m;
        }
    }

    let lagrangian_gradient: Vec<ExprId> = s
        .coordinates
        .iter()
        .map(|&q| pool.diff(lagrangian, q))
        .collect();
    let Some(nonconservative) = nonconservative(pool, &s, dissipation, &forces) else {
        return Equations::exhausted();
    };
    // The momenta and T, to be taken at rest together (one traversal).
    let mut with_t = momenta.clone();
    with_t.push(t_kin);
    let conservative = forcing::conservative_forcing(pool, &s, &mass, &with_t, v_pot);
    let mut forcing = Vec::with_capacity(n);
    if let Some(f) = conservative {
        for (i, fi) in f.into_iter().enumerate() {
            let fi = pool.add2(fi, nonconservative[i]);
            forcing.push(pool.factored(fi));
        }
    }
    for i in forcing.len()..n {
        if pool.exhausted() {
            return Equations::exhausted();
        }
        let mut terms = vec![lagrangian_gradient[i], nonconservative[i]];
        for j in 0..n {
            if pool.depends_on(momenta[i], s.coordinates[j]) {
                let d = pool.diff(momenta[i], s.coordinates[j]);
                let v = pool.sym(s.velocities[j]);
                let dv = pool.mul2(d, v);
                terms.push(pool.neg(dv));
            }
        }
        let dt = pool.diff(momenta[i], s.time);
        terms.push(pool.neg(dt));
        let fi = pool.add(&terms);
        forcing.push(pool.factored(fi));
    }
    let energy = pool.add2(t_kin, v_pot);
    let jacobians = want_jacobians.then(|| {
        // r_i = Σ_j M_ij q̈_j − f_i, differentiated symbolically: the same
        // DAG, so the Jacobians share their subexpressions with M and f.
        let residual: Vec<ExprId> = (0..n)
            .map(|i| {
                let mut terms: Vec<ExprId> = (0..n)
                    .map(|j| {
                        let a = pool.sym(s.accelerations[j]);
                        pool.mul2(mass[i][j], a)
                    })
                    .collect();
                terms.push(pool.neg(forcing[i]));
                pool.add(&terms)
            })
            .collect();
        let block = |pool: &mut crate::expr::Pool, by: &[crate::expr::SymId]| -> ExprMatrix {
            residual
                .iter()
                .map(|&r| by.iter().map(|&x| pool.diff(r, x)).collect())
                .collect()
        };
        (block(pool, &s.coordinates), block(pool, &s.velocities))
    });
    let input_jacobian = if s.inputs.is_empty() {
        None
    } else {
        // N × K entries, paid for before they are made like M's.
        pool.charge((n as u64).saturating_mul(s.inputs.len() as u64));
        let rows = forcing
            .iter()
            .map(|&f| {
                s.inputs
                    .iter()
                    .map(|&u| {
                        let d = pool.diff(f, u);
                        pool.factored(d)
                    })
                    .collect()
            })
            .collect();
        Some(rows)
    };
    let constraints = if phi.is_empty() {
        None
    } else {
        match holonomic(pool, &s, phi) {
            Some(c) => Some(c),
            None => return Equations::exhausted(),
        }
    };
    // A contact's gap has the terms of a holonomic constraint, its slip
    // velocity those of a velocity constraint (a contact without friction
    // has a slip of zero: zero rows).
    let contacts = if gaps.is_empty() {
        None
    } else {
        let vectors = model.contacts.iter().any(|c| c.second_slip.is_some());
        match (
            holonomic(pool, &s, gaps),
            holonomic(pool, &s, slips),
            vectors.then(|| holonomic(pool, &s, second_slips)),
        ) {
            (Some(gaps), Some(slips), None) => Some(ContactEquations {
                gaps,
                slips,
                second_slips: None,
                laws,
            }),
            (Some(gaps), Some(slips), Some(Some(second_slips))) => Some(ContactEquations {
                gaps,
                slips,
                second_slips: Some(second_slips),
                laws,
            }),
            _ => return Equations::exhausted(),
        }
    };
    let parameter_derivatives = if want_parameters {
        match by_parameters(pool, &s, &mass, &forcing, constraints.as_ref()) {
            Some(d) => Some(d),
            None => return Equations::exhausted(),
        }
    } else {
        None
    };
    Equations {
        mass,
        forcing,
        energy,
        momenta,
        lagrangian_gradient,
        nonconservative,
        jacobians,
        constraints,
        contacts,
        input_jacobian,
        parameter_derivatives,
        regressor: None,
        articulated: None,
    }
}

/// `Q − ∂R/∂q̇`, coordinate by coordinate; `None` if the budget ran out.
fn nonconservative(
    pool: &mut Pool,
    s: &Symbols,
    dissipation: Option<ExprId>,
    forces: &[(ExprId, ExprId)],
) -> Option<Vec<ExprId>> {
    let n = s.coordinates.len();
    let mut nonconservative = Vec::with_capacity(n);
    for i in 0..n {
        if pool.exhausted() {
            return None;
        }
        let mut terms = Vec::new();
        if let Some(r) = dissipation {
            let dr = pool.diff(r, s.velocities[i]);
            terms.push(pool.neg(dr));
        }
        // Virtual work: a force F along the position p does F·∂p/∂q_i.
        pool.charge(forces.len() as u64);
        for &(position, force) in forces {
            if pool.depends_on(position, s.coordinates[i]) {
                let dp = pool.diff(position, s.coordinates[i]);
                terms.push(pool.mul2(force, dp));
            }
        }
        nonconservative.push(pool.add(&terms));
    }
    Some(nonconservative)
}

/// The equations of a model whose `M q̈ = f` the runtime's recursion
/// solves from the parts of `T` on a tree of links
/// ([`articulated::first`]), without `M` and `f`: `T + V`, the momenta,
/// `∂L/∂q` and `Q − ∂R/∂q̇`, derived as [`euler_lagrange`] derives them,
/// `mass` and `forcing` left empty (their generated functions are formed
/// from the parts at run time). Within the model's budget, else garbage
/// that the caller reports as the budget error.
pub fn without_mass_matrix(model: &mut Model) -> Equations {
    let s = model.symbols.clone();
    let t_kin = model.kinetic.value;
    let v_pot = model.potential.value;
    let dissipation = model.dissipation.as_ref().map(|d| d.value);
    let forces: Vec<(ExprId, ExprId)> =
        model.forces.iter().map(|f| (f.position, f.value)).collect();
    let pool = &mut model.pool;
    let lagrangian = pool.sub(t_kin, v_pot);
    let momenta: Vec<ExprId> = s.velocities.iter().map(|&v| pool.diff(t_kin, v)).collect();
    let lagrangian_gradient: Vec<ExprId> = s
        .coordinates
        .iter()
        .map(|&q| pool.diff(lagrangian, q))
        .collect();
    let Some(nonconservative) = nonconservative(pool, &s, dissipation, &forces) else {
        return Equations::exhausted();
    };
    let energy = pool.add2(t_kin, v_pot);
    Equations {
        energy,
        momenta,
        lagrangian_gradient,
        nonconservative,
        ..Equations::exhausted()
    }
}

/// `G`, `φ_t`, `φ̇` and `γ` of the constraints `phi`; `None` if the budget
/// ran out on the way.
fn holonomic(pool: &mut Pool, s: &Symbols, phi: Vec<ExprId>) -> Option<ConstraintEquations> {
    // C × N entries of G, and as many terms of φ̇ and γ each: paid for
    // before they are made, like the n² of M.
    let (c, n) = (phi.len() as u64, s.coordinates.len() as u64);
    pool.charge(c.saturating_mul(n).saturating_mul(3));
    let mut out = ConstraintEquations {
        jacobian: Vec::with_capacity(phi.len()),
        time: Vec::with_capacity(phi.len()),
        velocities: Vec::with_capacity(phi.len()),
        bias: Vec::with_capacity(phi.len()),
        velocity_rows: Vec::with_capacity(phi.len()),
        values: phi,
        mass_regular_on_constraints_only: false,
    };
    for k in 0..out.values.len() {
        if pool.exhausted() {
            return None;
        }
        let p = out.values[k];
        // A velocity constraint `A(t, q) q̇ + b(t, q)` (linear, as checked):
        // its row of G is `A = ∂φ/∂q̇`, its velocity residual φ itself, and
        // `γ = ∂φ/∂q q̇ + ∂φ/∂t` (the q̇ in φ held, as Ȧ q̇ + ḃ). It has no
        // position-level value: zero, which no projection moves.
        let velocity_constraint = s.velocities.iter().any(|&v| pool.depends_on(p, v));
        let with_respect_to = if velocity_constraint {
            &s.velocities
        } else {
            &s.coordinates
        };
        let row = with_respect_to
            .iter()
            .map(|&q| {
                let d = pool.diff(p, q);
                pool.factored(d)
            })
            .collect();
        out.jacobian.push(row);
        out.time.push(pool.diff(p, s.time));
        let velocity = if velocity_constraint {
            p
        } else {
            pool.total_time_derivative(p, &s.coordinates, &s.velocities, s.time)
        };
        let bias = pool.total_time_derivative(velocity, &s.coordinates, &s.velocities, s.time);
        out.velocities.push(pool.factored(velocity));
        out.bias.push(pool.factored(bias));
        out.velocity_rows.push(velocity_constraint);
        if velocity_constraint {
            out.values[k] = Pool::ZERO;
        }
    }
    (!pool.exhausted()).then_some(out)
}

/// `∂M/∂p_k`, `∂f/∂p` and `∂r/∂p` for every parameter scalar; `None` if
/// the budget ran out on the way.
#[allow(clippy::needless_range_loop)] // (i, j) index M, symmetric: the clearest form
fn by_parameters(
    pool: &mut Pool,
    s: &Symbols,
    mass: &ExprMatrix,
    forcing: &[ExprId],
    constraints: Option<&ConstraintEquations>,
) -> Option<ParameterDerivatives> {
    let n = forcing.len();
    let p = s.parameters.len();
    // P matrices and two N × P ones, paid for before they are made.
    let square = (n as u64).saturating_mul(n as u64);
    pool.charge(square.saturating_add(2 * n as u64).saturating_mul(p as u64));
    let mut by_mass = Vec::with_capacity(p);
    for &pk in &s.parameters {
        if pool.exhausted() {
            return None;
        }
        let mut dm = vec![vec![Pool::ZERO; n]; n];
        for i in 0..n {
            for j in i..n {
                let d = pool.diff(mass[i][j], pk);
                let d = pool.factored(d);
                dm[i][j] = d;
                dm[j][i] = d;
            }
        }
        by_mass.push(dm);
    }
    let mut by_forcing = vec![Vec::with_capacity(p); n];
    let mut by_residual = vec![Vec::with_capacity(p); n];
    for (k, &pk) in s.parameters.iter().enumerate() {
        if pool.exhausted() {
            return None;
        }
        for i in 0..n {
            let df = pool.diff(forcing[i], pk);
            let df = pool.factored(df);
            // (∂M/∂p_k q̈)_i − ∂f_i/∂p_k
            let mut terms: Vec<ExprId> = (0..n)
                .map(|j| {
                    let a = pool.sym(s.accelerations[j]);
                    pool.mul2(by_mass[k][i][j], a)
                })
                .collect();
            terms.push(pool.neg(df));
            let dr = pool.add(&terms);
            by_forcing[i].push(df);
            by_residual[i].push(dr);
        }
    }
    let constraints = constraints.map(|c| {
        // G q̈ + γ, the constraints at the level of accelerations.
        let acceleration: Vec<ExprId> = c
            .jacobian
            .iter()
            .zip(&c.bias)
            .map(|(row, &gamma)| {
                let mut terms: Vec<ExprId> = row
                    .iter()
                    .zip(&s.accelerations)
                    .map(|(&g, &a)| {
                        let a = pool.sym(a);
                        pool.mul2(g, a)
                    })
                    .collect();
                terms.push(gamma);
                pool.add(&terms)
            })
            .collect();
        pool.charge((3 * acceleration.len() as u64).saturating_mul(p as u64));
        let mut by = |rows: &[ExprId]| -> ExprMatrix {
            rows.iter()
                .map(|&r| {
                    s.parameters
                        .iter()
                        .map(|&pk| {
                            let d = pool.diff(r, pk);
                            pool.factored(d)
                        })
                        .collect()
                })
                .collect()
        };
        [by(&c.values), by(&c.velocities), by(&acceleration)]
    });
    (!pool.exhausted()).then_some(ParameterDerivatives {
        mass: by_mass,
        forcing: by_forcing,
        residual: by_residual,
        constraints,
    })
}

impl Equations {
    /// What a derivation that ran out of budget returns: nothing to read.
    fn exhausted() -> Self {
        Equations {
            mass: Vec::new(),
            forcing: Vec::new(),
            energy: Pool::ZERO,
            momenta: Vec::new(),
            lagrangian_gradient: Vec::new(),
            nonconservative: Vec::new(),
            jacobians: None,
            constraints: None,
            contacts: None,
            input_jacobian: None,
            parameter_derivatives: None,
            regressor: None,
            articulated: None,
        }
    }
}
