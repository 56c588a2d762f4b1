//! The checks of `inputs:`. A control input is a value set from outside at
//! each instant, with no time derivative the model could know. Lagrange's
//! equations differentiate the momenta `p = ∂T/∂q̇` and the constraints'
//! `φ` in time, so an input in either would need `u̇` (and `ü`), which
//! the derivation would silently take as zero: both are compile errors.
//! (`dot` of an input is refused where it is lowered.) Inputs are welcome
//! everywhere else: forces above all, the potential, dissipation, `let`s,
//! and the velocity-free part of `T`.

use super::constraints::locate_side;
use crate::derive::Equations;
use crate::expr::{ExprId, Pool, SymId};
use crate::model::Model;

/// The first input `id` depends on, if any.
fn input_in(pool: &Pool, inputs: &[SymId], id: ExprId) -> Option<usize> {
    inputs.iter().position(|&u| pool.depends_on(id, u))
}

/// No constraint may depend on an input: `φ̇` and `γ` would need `u̇`, `ü`.
pub fn constraints_hold_no_input(model: &mut Model) -> syn::Result<()> {
    let inputs = model.symbols.inputs.clone();
    for k in 0..model.constraints.len() {
        let value = model.constraints[k].value;
        let Some(i) = input_in(&model.pool, &inputs, value) else {
            continue;
        };
        let u = inputs[i];
        let label = model.constraints[k].label.clone();
        let range = locate_side(model, k, &|pool: &mut Pool, id| pool.depends_on(id, u));
        return Err(range.error(format!(
            "constraint `{label}` depends on the input `{}`: the constraint's velocity and acceleration \
             would need the input's time derivatives, which an input set from outside does not have \
             (a prescribed motion is written in `t`)",
            model.inputs[i]
        )));
    }
    Ok(())
}

/// No momentum `p_i = ∂T/∂q̇_i` may depend on an input: `d/dt p` would need
/// `u̇`. (So `M = ∂p/∂q̇` is free of inputs too, which lets the runtime
/// evaluate `M(t, q)` without a controller.)
pub fn momenta_hold_no_input(model: &mut Model, eq: &Equations) -> syn::Result<()> {
    let inputs = model.symbols.inputs.clone();
    let velocities = model.symbols.velocities.clone();
    for (i, &p) in eq.momenta.iter().enumerate() {
        let Some(k) = input_in(&model.pool, &inputs, p) else {
            continue;
        };
        let (u, v) = (inputs[k], velocities[i]);
        let ast = model.kinetic.ast.clone();
        let range = model.locate(&ast, &|pool: &mut Pool, id: ExprId| {
            let d = pool.diff(id, v);
            pool.depends_on(d, u)
        });
        return Err(range.error(format!(
            "the momentum ∂T/∂dot({}) depends on the input `{}`: Lagrange's equations differentiate it in \
             time, which would need the input's time derivative, and an input set from outside has none \
             (inputs act through forces, the potential or the velocity-free part of T)",
            model.coordinates[i], model.inputs[k]
        )));
    }
    Ok(())
}
