//! The checks of `constraints:`: each constraint holonomic (a function of
//! `t` and `q`) or linear in the velocities (`A(t, q) q̇ + b(t, q)`), each
//! constraining some coordinate, fewer constraints than coordinates, and
//! none redundant, i.e. the rows of `G` (`∂φ/∂q`, or `A` for a velocity
//! constraint) independent. Redundant constraints make the runtime's
//! saddle-point system singular at every state, the constrained analogue of
//! a singular mass matrix, so they are a compile error like it.

use super::{evaluate, generic_state};
use crate::ast::{Expr, SpanRange};
use crate::derive::Equations;
use crate::expr::{ExprId, Pool};
use crate::model::{Constraint, Model};

/// The tokens of the side of constraint `k` that is `bad`, narrowed to the
/// smallest piece at fault; the whole entry if neither side alone is.
pub(super) fn locate_side(
    model: &mut Model,
    k: usize,
    bad: &dyn Fn(&mut Pool, ExprId) -> bool,
) -> SpanRange {
    let c = &model.constraints[k];
    let (def, env) = model.constraint_def(c);
    let sides: Vec<(Expr, ExprId)> = std::iter::once((def.lhs.clone(), c.lhs))
        .chain(def.rhs.clone().zip(c.rhs))
        .collect();
    let whole = def.range();
    for (ast, id) in sides {
        if bad(&mut model.pool, id) {
            return model.locate_in(&ast, &env, bad);
        }
    }
    whole
}

/// No constraint may fold to an infinite or undefined constant (called by
/// [`super::constants_are_finite`] once the other sections passed).
pub fn constants_are_finite(model: &mut Model) -> syn::Result<()> {
    let Some(k) = (0..model.constraints.len())
        .find(|&k| model.pool.has_non_finite(model.constraints[k].value))
    else {
        return Ok(());
    };
    let range = locate_side(model, k, &|pool: &mut Pool, id| pool.has_non_finite(id));
    Err(range.error(
        "this evaluates to an infinite or undefined constant (a division by zero, or a function outside its domain)",
    ))
}

/// Each constraint is holonomic, `φ(t, q) = 0`, or a velocity constraint
/// linear in the velocities, `A(t, q) q̇ + b(t, q) = 0`; each names some
/// coordinate or velocity; and there are fewer of them than coordinates.
pub fn constraints_are_admissible(model: &mut Model) -> syn::Result<()> {
    let velocities = model.symbols.velocities.clone();
    let coordinates = model.symbols.coordinates.clone();
    for k in 0..model.constraints.len() {
        let c: &Constraint = &model.constraints[k];
        let (label, value) = (c.label.clone(), c.value);
        // Linear in the velocities: no ∂φ/∂q̇_i holds a velocity.
        for (i, &vi) in velocities.iter().enumerate() {
            if !model.pool.depends_on(value, vi) {
                continue;
            }
            let d = model.pool.diff(value, vi);
            let Some(j) = velocities
                .iter()
                .position(|&vj| model.pool.depends_on(d, vj))
            else {
                continue;
            };
            let vj = velocities[j];
            let range = locate_side(model, k, &|pool: &mut Pool, id| {
                let d = pool.diff(id, vi);
                pool.depends_on(d, vj)
            });
            return Err(range.error(format!(
                "constraint `{label}` is not linear in the velocities: ∂φ/∂dot({}) depends on `dot({})`; \
                 `constraints:` takes holonomic constraints φ(t, q) = 0 and velocity constraints linear in the \
                 velocities, A(t, q) q̇ + b(t, q) = 0",
                model.coordinates[i], model.coordinates[j]
            )));
        }
        let names_any = coordinates
            .iter()
            .chain(&velocities)
            .any(|&q| model.pool.depends_on(value, q));
        if !names_any {
            let (def, _) = model.constraint_def(&model.constraints[k]);
            return Err(def.range().error(format!(
                "constraint `{label}` names no coordinate: it constrains nothing (a constraint is an equation \
                 φ(t, q) = 0 that the coordinates must satisfy, or A(t, q) q̇ + b(t, q) = 0 on their velocities)"
            )));
        }
    }
    let (c, n) = (model.constraints.len(), model.dof());
    if c >= n {
        // The constraint that takes the last degree of freedom.
        let last = &model.constraints[n - 1];
        let (def, _) = model.constraint_def(last);
        let most = if n == 1 {
            "a model with 1 coordinate takes none".to_string()
        } else {
            format!("a model with {n} coordinates takes at most {}", n - 1)
        };
        return Err(def.range().error(format!(
            "too many constraints: {c} constraints on {n} coordinates leave no motion (`{}` removes the last \
             degree of freedom); {most}",
            last.label
        )));
    }
    Ok(())
}

/// The rows of `G = ∂φ/∂q` are independent: a constraint whose row is a
/// combination of the rows before it at two generic states is redundant
/// (or contradicts them) at every state, and the runtime's saddle-point
/// system would be singular. Run after derivation, like the mass matrix's
/// rank check, and in the same spirit: numeric, at generic states.
pub fn constraints_are_independent(model: &mut Model, eq: &Equations) -> syn::Result<()> {
    let Some(ce) = &eq.constraints else {
        return Ok(());
    };
    let (c, n) = (ce.values.len() as u64, model.dof() as u64);
    // Evaluating G (C·N entries, a few steps each) and orthogonalizing
    // (C²·N floating-point operations, a step per 8), at two states.
    model.pool.charge(
        c.saturating_mul(n)
            .saturating_mul(c / 8 + 4)
            .saturating_mul(2),
    );
    if model.pool.exhausted() {
        return Ok(());
    }
    let rows: Vec<Vec<Row>> = [1u64, 2]
        .iter()
        .map(|&seed| classify_rows(model, &ce.jacobian, seed))
        .collect();
    let Some(k) = (0..ce.values.len()).find(|&k| rows.iter().all(|r| r[k] != Row::Independent))
    else {
        return Ok(());
    };
    let label = model.constraints[k].label.clone();
    let (def, _) = model.constraint_def(&model.constraints[k]);
    let reason = if rows.iter().all(|r| r[k] == Row::Vanishes) {
        "its gradient ∂φ/∂q vanishes at every state, so it does not constrain the coordinates after all"
            .to_string()
    } else {
        let before: Vec<String> = model.constraints[..k]
            .iter()
            .map(|c| format!("`{}`", c.label))
            .collect();
        format!(
            "at every state its gradient ∂φ/∂q is a combination of the gradients of the constraints before it \
             ({}), so it repeats (or contradicts) them and the constraint forces are not determined; remove it",
            before.join(", ")
        )
    };
    Err(def
        .range()
        .error(format!("constraint `{label}` is redundant: {reason}")))
}

/// What a row of `G` adds to the rows before it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Row {
    Independent,
    /// Zero.
    Vanishes,
    /// A combination of the rows before it.
    Combination,
}

/// What each row of `G` at a generic state adds to the rows before it
/// (Gram–Schmidt, relative to the largest entry); at a state where `G` is
/// not finite, every row counts as independent.
fn classify_rows(model: &Model, g: &[Vec<ExprId>], seed: u64) -> Vec<Row> {
    let values = generic_state(model, seed);
    let rows = evaluate(model, g, &values, &mut std::collections::HashMap::new());
    if rows.iter().flatten().any(|x| !x.is_finite()) {
        return vec![Row::Independent; g.len()];
    }
    let scale = rows.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    let tol = 1e-9 * scale;
    let norm = |r: &[f64]| r.iter().map(|x| x * x).sum::<f64>().sqrt();
    let mut basis: Vec<Vec<f64>> = Vec::new();
    rows.into_iter()
        .map(|mut r| {
            if scale == 0.0 || norm(&r) <= tol {
                return Row::Vanishes;
            }
            // Twice, for a residual accurate to rounding.
            for _ in 0..2 {
                for b in &basis {
                    let p: f64 = r.iter().zip(b).map(|(x, y)| x * y).sum();
                    r.iter_mut().zip(b).for_each(|(x, y)| *x -= p * y);
                }
            }
            let residual = norm(&r);
            if residual <= tol {
                return Row::Combination;
            }
            basis.push(r.iter().map(|x| x / residual).collect());
            Row::Independent
        })
        .collect()
}
