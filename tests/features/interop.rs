//! A generated model integrated by other ODE crates (features
//! `ode_solvers` and `diffsol`): the chaotic double pendulum through
//! `ode_solvers::Dop853`, diffsol's Tsit45 and BDF, and ours, against the
//! 25-digit reference.

use crate::support::reference::Reference;
use lagrange::prelude::*;

#[test]
fn the_double_pendulum_through_ode_solvers_matches_ours_and_the_reference() {
    use lagrange::interop::ode_solvers::FirstOrder;
    use lagrange::ode_solvers::dop_shared::OutputType;
    let r = Reference::double_pendulum();
    let model = r.double_pendulum_model::<f64>();
    // The reference sample at t = 2 (perturbation growth there ~1e2).
    let sample = r
        .samples
        .iter()
        .find(|s| s.t == 2.0)
        .expect("a sample at t = 2");
    let tol = 1e-12;
    let y0 = lagrange::ode_solvers::Vector4::new(r.q0[0], r.q0[1], r.qdot0[0], r.qdot0[1]);
    // Hairer's DOP853 defaults, sparse output (the state at each accepted
    // step, the last at t = 2).
    let mut theirs = lagrange::ode_solvers::Dop853::from_param(
        FirstOrder::new(&model),
        0.0,
        2.0,
        2.0,
        y0,
        tol,
        tol,
        0.9,
        0.0,
        0.333,
        6.0,
        2.0,
        0.0,
        100_000,
        1000,
        OutputType::Sparse,
    );
    theirs.integrate().unwrap();
    assert_eq!(theirs.x_out().last(), Some(&2.0));
    let y = theirs.y_out().last().unwrap();
    let ours = Dop853::new()
        .rtol(tol)
        .atol(tol)
        .integrate(&model, 0.0, r.q0, r.qdot0, &[2.0])
        .unwrap();
    let end = ours.last().unwrap();
    let theirs_err = (0..2)
        .map(|i| {
            (y[i] - sample.q[i])
                .abs()
                .max((y[2 + i] - sample.qdot[i]).abs())
        })
        .fold(0.0, f64::max);
    let ours_err = (end.q - sample.q)
        .amax()
        .max((end.qdot - sample.qdot).amax());
    println!("t = 2 against the reference: ode_solvers {theirs_err:.1e}, ours {ours_err:.1e}");
    // Both run DOP853 at 1e-12 on the same right-hand side: each global
    // error is bounded by the tolerance times the perturbation growth at
    // t = 2, times the state's scale (up to ~9) and a safety of 100, as in
    // `reference_trajectories.rs`.
    let scale = 1f64.max(sample.q.amax()).max(sample.qdot.amax());
    let bound = 100.0 * tol * sample.growth * scale;
    assert!(
        theirs_err < bound && ours_err < bound,
        "{theirs_err} {ours_err} > {bound}"
    );
}

/// The double pendulum as a diffsol problem (feature `diffsol`): its
/// Tsit45 (explicit) and BDF (implicit, the Jacobian from the generated
/// residual Jacobians) against the 25-digit reference at t = 2, beside ours.
#[test]
fn the_double_pendulum_through_diffsol_matches_the_reference() {
    use lagrange::diffsol::{MatrixCommon, NalgebraLU, OdeSolverMethod};
    use lagrange::interop::diffsol::problem;
    let r = Reference::double_pendulum();
    let model = r.double_pendulum_model::<f64>();
    let sample = r
        .samples
        .iter()
        .find(|s| s.t == 2.0)
        .expect("a sample at t = 2");
    let scale = 1f64.max(sample.q.amax()).max(sample.qdot.amax());
    let error = |y: &[f64]| {
        (0..2)
            .map(|i| {
                (y[i] - sample.q[i])
                    .abs()
                    .max((y[2 + i] - sample.qdot[i]).abs())
            })
            .fold(0.0, f64::max)
    };
    let tol = 1e-10;
    let ode = problem(&model, 0.0, r.q0, r.qdot0, tol, tol).unwrap();
    let (ys, _) = ode.tsit45().unwrap().solve_dense(&[2.0]).unwrap();
    let tsit45 = error(ys.inner().column(0).as_slice());
    let (ys, _) = ode
        .bdf::<NalgebraLU<f64>>()
        .unwrap()
        .solve_dense(&[2.0])
        .unwrap();
    let bdf = error(ys.inner().column(0).as_slice());
    let ours = Dop853::new()
        .rtol(tol)
        .atol(tol)
        .integrate(&model, 0.0, r.q0, r.qdot0, &[2.0])
        .unwrap();
    let end = ours.last().unwrap();
    let ours = (end.q - sample.q)
        .amax()
        .max((end.qdot - sample.qdot).amax());
    println!("t = 2 at {tol:e}: diffsol Tsit45 {tsit45:.1e}, BDF {bdf:.1e}; our Dop853 {ours:.1e}");
    // Each method's global error: its local tolerance times the
    // perturbation growth to t = 2 and the state's scale; Tsit45 and
    // Dop853 hold within 100× that (as in `reference_trajectories.rs`);
    // BDF's variable-order control, 1000×.
    let bound = tol * sample.growth * scale;
    assert!(
        tsit45 < 100.0 * bound && ours < 100.0 * bound,
        "{tsit45} {ours}"
    );
    assert!(bdf < 1000.0 * bound, "{bdf} > {}", 1000.0 * bound);
}
