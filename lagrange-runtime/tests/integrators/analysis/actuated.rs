//! `B = [[0], [M⁻¹ ∂f/∂u]]` of an actuated model, with `A` at the inputs
//! given.

use lagrange_runtime::Actuated;
use lagrange_runtime::analysis::{Derivatives, equilibrium, linearize_with_inputs};
use lagrange_runtime::nalgebra::Vector1;

use super::models::PushedSpring;

/// `m ẍ = −k x − c ẋ + u cos x`: at `(x, ẋ, u)`,
/// `∂ẍ/∂x = (−k − u sin x) / m`, `∂ẍ/∂ẋ = −c / m`, `∂ẍ/∂u = cos x / m`.
/// Exact model Jacobians and one division: to rounding.
#[test]
fn pushed_spring_input_matrix_is_the_transmitted_force_over_the_mass() {
    let model = PushedSpring {
        m: 2.0,
        k: 8.0,
        c: 0.5,
        u: 0.0,
    };
    let (x, v, u) = (0.7, -1.2, 3.0);
    let lin = linearize_with_inputs(
        &model,
        0.0,
        &Vector1::new(x),
        &Vector1::new(v),
        &Vector1::new(u),
    )
    .unwrap();
    let close = |a: f64, b: f64| (a - b).abs() < 1e-15 * b.abs().max(1.0);
    assert_eq!(lin.state.derivatives, Derivatives::Exact);
    assert!(close(
        lin.state.qddot[0],
        (-8.0 * x - 0.5 * v + u * x.cos()) / 2.0
    ));
    assert!(close(
        lin.state.dqddot_dq[(0, 0)],
        (-8.0 - u * x.sin()) / 2.0
    ));
    assert!(close(lin.state.dqddot_dqdot[(0, 0)], -0.25));
    assert!(close(lin.dqddot_du[(0, 0)], x.cos() / 2.0));
    let b = lin.input_matrix();
    assert_eq!((b.nrows(), b.ncols()), (2, 1));
    assert_eq!(b[(0, 0)], 0.0);
    assert_eq!(b[(1, 0)], lin.dqddot_du[(0, 0)]);
    // The inputs were set on a copy.
    assert_eq!(model.inputs()[0], 0.0);
}

/// Equilibria are searched at the inputs the model holds: a push `u`
/// moves the rest point to `k x = u cos x`.
#[test]
fn pushed_spring_rests_where_the_spring_balances_the_push() {
    let model = PushedSpring {
        m: 2.0,
        k: 8.0,
        c: 0.5,
        u: 4.0,
    };
    let x = equilibrium(&model, 0.0, &Vector1::new(0.0)).unwrap().q[0];
    // Newton to rounding on a function of slope ≈ 10: residual a few ε·4.
    assert!((8.0 * x - 4.0 * x.cos()).abs() < 1e-14, "{x}");
}
