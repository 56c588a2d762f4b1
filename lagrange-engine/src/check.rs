//! Physics checks, at compile time, each a spanned error that names the
//! problem: a potential that depends on a velocity, a kinetic energy that is
//! not quadratic in the velocities, a coordinate without kinetic energy, a
//! mass matrix that is singular at every state. The constraints' checks are
//! in [`constraints`], the control inputs' in [`inputs`].

pub mod constraints;
pub mod contacts;
pub mod inputs;

use crate::ast::Expr;
use crate::derive::Equations;
use crate::expr::{ExprId, Pool};
use crate::model::{Model, SymKind};

/// No section may fold to an infinite or undefined constant.
pub fn constants_are_finite(model: &mut Model) -> syn::Result<()> {
    let mut sections: Vec<(&Expr, ExprId)> = vec![
        (&model.kinetic.ast, model.kinetic.value),
        (&model.potential.ast, model.potential.value),
    ];
    sections.extend(model.dissipation.as_ref().map(|d| (&d.ast, d.value)));
    sections.extend(model.forces.iter().map(|f| (&f.ast, f.value)));
    let Some(ast) = sections
        .into_iter()
        .find(|&(_, id)| model.pool.has_non_finite(id))
        .map(|(ast, _)| ast.clone())
    else {
        return constraints::constants_are_finite(model);
    };
    let range = model.locate(&ast, &|pool: &mut Pool, id| pool.has_non_finite(id));
    Err(range.error(
        "this evaluates to an infinite or undefined constant (a division by zero, or a function outside its domain)",
    ))
}

/// V must be a function of t and q alone.
pub fn potential_has_no_velocity(model: &mut Model) -> syn::Result<()> {
    let velocities = model.symbols.velocities.clone();
    let v = model.potential.value;
    let Some(i) = velocities.iter().position(|&s| model.pool.depends_on(v, s)) else {
        return Ok(());
    };
    let vel = velocities[i];
    let ast = model.potential.ast.clone();
    let range = model.locate(&ast, &|pool: &mut Pool, id: ExprId| {
        pool.depends_on(id, vel)
    });
    Err(range.error(format!(
        "the potential energy depends on the velocity `dot({})`: V must be a function of the coordinates and `t` only \
         (velocity-dependent forces go in `forces:` or `dissipation:`)",
        model.coordinates[i]
    )))
}

/// M must not depend on velocities, and must not be singular, except where
/// the constraints make up for it: a singular `M` that is regular on the
/// velocities the constraints allow (the null space of `G`), as a unit
/// quaternion's four rates are under `|q| = 1`, is accepted and marked
/// ([`ConstraintEquations::mass_regular_on_constraints_only`]), since the
/// saddle-point system `M q̈ + Gᵀλ = f`, `G q̈ = −γ` is regular there.
///
/// [`ConstraintEquations::mass_regular_on_constraints_only`]: crate::derive::ConstraintEquations::mass_regular_on_constraints_only
pub fn mass_matrix_is_regular(model: &mut Model, eq: &mut Equations) -> syn::Result<()> {
    let n = model.dof();
    let s = model.symbols.clone();
    for i in 0..n {
        for j in i..n {
            let m = eq.mass[i][j];
            // The first velocity `m` holds, read off its dependency set.
            let velocity = model
                .pool
                .dependencies(m)
                .find_map(|x| match model.symbols.kind(x) {
                    SymKind::Velocity(k) => Some(k),
                    _ => None,
                });
            if model.pool.exhausted() {
                return Ok(());
            }
            if let Some(k) = velocity {
                // Underline the smallest term whose ∂²/∂q̇_i∂q̇_j still holds q̇_k.
                let (vi, vj, vk) = (s.velocities[i], s.velocities[j], s.velocities[k]);
                let ast = model.kinetic.ast.clone();
                let range = model.locate(&ast, &|pool: &mut Pool, id: ExprId| {
                    let d = pool.diff(id, vi);
                    let d = pool.diff(d, vj);
                    pool.depends_on(d, vk)
                });
                return Err(range.error(format!(
                    "the kinetic energy is not quadratic in the velocities: ∂²T/∂dot({})∂dot({}) depends on `dot({})`, \
                     so the mass matrix would depend on the velocities",
                    model.coordinates[i], model.coordinates[j], model.coordinates[k]
                )));
            }
        }
    }
    // A coordinate without kinetic energy may still be fixed by the
    // constraints (the numeric check below decides, and counts what is
    // missing where they do not): only an unconstrained model is refused
    // on sight, naming the coordinate.
    if eq.constraints.is_none() {
        no_coordinate_without_kinetic_energy(model, eq)?;
    }
    // Structurally full, but singular everywhere? Try two generic states; an
    // analytic M singular at both is singular identically (or nearly so).
    // Evaluating M (n² entries, a few steps each) and eliminating (n³/3
    // floating-point operations, a few nanoseconds each, a step per 8).
    let n = n as u64;
    model
        .pool
        .charge(n.saturating_mul(n).saturating_mul(n / 24 + 4));
    let n = n as usize;
    if model.pool.exhausted() {
        return Ok(());
    }
    let mut singular_everywhere = true;
    let mut rank = n;
    for seed in [1u64, 2] {
        match numeric_rank(model, eq, seed, None) {
            Some(r) if r < n => rank = r,
            _ => singular_everywhere = false,
        }
    }
    if !singular_everywhere {
        return Ok(());
    }
    let Some(constraints) = &eq.constraints else {
        return Err(model.kinetic.keyword_and_value().error(format!(
            "the mass matrix ∂²T/∂q̇² is singular at every state (rank {rank} of {n}): the kinetic energy \
             sees fewer independent velocity combinations than there are coordinates"
        )));
    };
    // Regular on the null space of G if and only if `M + GᵀG` is regular
    // (M being semi-definite): the same rank test on that sum, charged as
    // much again plus `GᵀG`.
    let c = constraints.values.len() as u64;
    let n64 = n as u64;
    model.pool.charge(
        n64.saturating_mul(n64)
            .saturating_mul(n64 / 24 + c + 4)
            .saturating_mul(2),
    );
    if model.pool.exhausted() {
        return Ok(());
    }
    let g = constraints.jacobian.clone();
    let mut augmented_rank = n;
    let mut regular = false;
    for seed in [1u64, 2] {
        match numeric_rank(model, eq, seed, Some(&g)) {
            Some(r) if r < n => augmented_rank = r,
            _ => regular = true,
        }
    }
    if regular {
        if let Some(constraints) = &mut eq.constraints {
            constraints.mass_regular_on_constraints_only = true;
        }
        return Ok(());
    }
    let free = n - g.len();
    let seen = augmented_rank.saturating_sub(g.len());
    Err(model.kinetic.keyword_and_value().error(format!(
        "the mass matrix ∂²T/∂q̇² is singular at every state (rank {rank} of {n}), and the constraints do not \
         make up for it: of the {free} velocity combinations they allow, the kinetic energy sees only {seen} \
         (M + GᵀG has rank {augmented_rank} of {n}), so the accelerations are not determined"
    )))
}

/// The error on a coordinate whose row of M is zero: no kinetic energy of
/// its own or shared with another.
fn no_coordinate_without_kinetic_energy(model: &Model, eq: &Equations) -> syn::Result<()> {
    let Some(i) = (0..model.dof()).find(|&i| eq.mass[i].iter().all(|&m| m == Pool::ZERO)) else {
        return Ok(());
    };
    let c = &model.coordinates[i];
    Err(syn::Error::new(
        c.span(),
        format!(
            "coordinate `{c}` has no kinetic energy: the mass matrix is singular \
             (T holds no `dot({c})` squared or times another velocity)"
        ),
    ))
}

/// A matrix of expressions (row-major) evaluated at `values`, sharing
/// `memo` with the other evaluations at the same state.
pub(crate) fn evaluate(
    model: &Model,
    rows: &[Vec<ExprId>],
    values: &[f64],
    memo: &mut std::collections::HashMap<ExprId, f64>,
) -> Vec<Vec<f64>> {
    rows.iter()
        .map(|row| {
            row.iter()
                .map(|&x| model.pool.eval_memo(x, values, memo))
                .collect()
        })
        .collect()
}

/// A reproducible pseudo-random generic value in `[lo, hi)`.
fn generic_value(seed: u64, k: usize, lo: f64, hi: f64) -> f64 {
    let mut x = seed
        .wrapping_mul(0x9E37_79B9_7F4A_7C15)
        .wrapping_add((k as u64 + 1).wrapping_mul(0xBF58_476D_1CE4_E5B9));
    x ^= x >> 31;
    x = x.wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^= x >> 29;
    lo + (hi - lo) * ((x >> 11) as f64 / (1u64 << 53) as f64)
}

/// A generic state: a value for every symbol, parameters in `[0.5, 2)`,
/// the rest in `[0.1, 1.3)`.
fn generic_state(model: &Model, seed: u64) -> Vec<f64> {
    (0..model.symbols.count())
        .map(|k| match model.symbols.kind(crate::expr::SymId(k as u32)) {
            SymKind::Parameter(_) => generic_value(seed, k, 0.5, 2.0),
            _ => generic_value(seed, k, 0.1, 1.3),
        })
        .collect()
}

/// The numerical rank of `M`, or of `M + GᵀG` with `g` (`C × N`, row-major),
/// at a generic state; `None` if it is not finite there.
fn numeric_rank(
    model: &Model,
    eq: &Equations,
    seed: u64,
    g: Option<&[Vec<ExprId>]>,
) -> Option<usize> {
    let n = model.dof();
    let values = generic_state(model, seed);
    let mut memo = std::collections::HashMap::new();
    let mut a = evaluate(model, &eq.mass, &values, &mut memo);
    if let Some(g) = g {
        let g = evaluate(model, g, &values, &mut memo);
        // Each row of G scaled to the size of M, so that neither swamps the
        // other in the rank's relative tolerance.
        let m_scale = a.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        let m_scale = if m_scale > 0.0 { m_scale } else { 1.0 };
        for row in &g {
            let norm2: f64 = row.iter().map(|x| x * x).sum();
            if !(norm2 > 0.0 && norm2.is_finite()) {
                continue;
            }
            let k = m_scale / norm2;
            for i in 0..n {
                for j in 0..n {
                    a[i][j] += k * row[i] * row[j];
                }
            }
        }
    }
    if a.iter().flatten().any(|x| !x.is_finite()) {
        return None;
    }
    let scale = a.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    if scale == 0.0 {
        return Some(0);
    }
    let tol = 1e-10 * scale;
    let mut rank = 0;
    let mut row = 0;
    for col in 0..n {
        let pivot = (row..n).max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))?;
        if a[pivot][col].abs() <= tol {
            continue;
        }
        a.swap(row, pivot);
        let (top, below) = a.split_at_mut(row + 1);
        let pivot_row = &top[row];
        for r in below.iter_mut() {
            let factor = r[col] / pivot_row[col];
            for (x, p) in r[col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= factor * p;
            }
        }
        rank += 1;
        row += 1;
        if row == n {
            break;
        }
    }
    Some(rank)
}
