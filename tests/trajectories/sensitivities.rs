//! Forward sensitivities (`lagrange::sensitivity`) against dual numbers:
//! num-dual's `Dual64` carried through the model and the same integrator,
//! one direction at a time, on the damped double pendulum and the 5-link
//! chain of `tests/models/parameter_derivatives.rs` (each with its exact
//! Jacobians and parameter derivatives).
//!
//! With a fixed step the two are the same numbers by two roads: an
//! explicit Runge–Kutta step applied to the model and its variational
//! equations is the derivative of the step applied to the model, so RK4 on
//! the `Sensitivity` model and RK4 in dual numbers differ by rounding
//! alone. The adaptive and implicit methods choose their own steps; they
//! are held to a converged reference instead.

use crate::models::parameter_derivatives::{ChainOfFive, DampedDoublePendulum, FromScalars};
use lagrange::nalgebra::{SMatrix, SVector};
use lagrange::prelude::*;
use lagrange::sensitivity::{Direction, Sensitivity, SensitivityError, coordinates};
use lagrange::{Dop853, ParameterDerivatives, Radau5, Rk4};
use num_dual::Dual64;

/// `∂q/∂d` at each of `times`, column by direction, by RK4 in dual
/// numbers with step `h`, written out here (an independent road to the
/// runtime's RK4; the runtime's fixed-step driver rounds its step counts
/// with `ceil`, which dual numbers refuse): for each direction a run whose
/// parameters and initial state carry the unit derivative along it.
fn by_dual_numbers<M, const N: usize, const P: usize, const D: usize>(
    parameters: &[f64; P],
    directions: &[Direction; D],
    (q0, v0): (SVector<f64, N>, SVector<f64, N>),
    h: f64,
    times: &[f64],
) -> Vec<SMatrix<f64, N, D>>
where
    M: Lagrangian<N, Scalar = Dual64> + FromScalars<Dual64>,
{
    let mut out = vec![SMatrix::<f64, N, D>::zeros(); times.len()];
    for (j, d) in directions.iter().enumerate() {
        let seed = |hit: bool| if hit { 1.0 } else { 0.0 };
        let p: Vec<Dual64> = (0..P)
            .map(|k| Dual64::new(parameters[k], seed(*d == Direction::Parameter(k))))
            .collect();
        let q = SVector::<Dual64, N>::from_fn(|i, _| {
            Dual64::new(q0[i], seed(*d == Direction::Position(i)))
        });
        let v = SVector::<Dual64, N>::from_fn(|i, _| {
            Dual64::new(v0[i], seed(*d == Direction::Velocity(i)))
        });
        let model = M::from_scalars(&p);
        let (mut q, mut v, mut t) = (q, v, 0.0);
        for (i, &stop) in times.iter().enumerate() {
            // As the runtime's fixed-step driver: the interval to the next
            // sample cut into the fewest equal steps no longer than `h`.
            let n = ((stop - t) / h).ceil() as usize;
            let step = Dual64::from((stop - t) / n as f64);
            for _ in 0..n {
                (q, v) = rk4_step(&model, q, v, step);
            }
            t = stop;
            out[i].set_column(j, &q.map(|x| x.eps));
        }
    }
    out
}

/// One classical Runge–Kutta step of `q̈ = M⁻¹ f` (autonomous: `t` is
/// not read by these models), in dual numbers.
fn rk4_step<M, const N: usize>(
    model: &M,
    q: SVector<Dual64, N>,
    v: SVector<Dual64, N>,
    h: Dual64,
) -> (SVector<Dual64, N>, SVector<Dual64, N>)
where
    M: Lagrangian<N, Scalar = Dual64>,
{
    let t = Dual64::from(0.0);
    let a = |q: &SVector<Dual64, N>, v: &SVector<Dual64, N>| {
        let (m, f) = model.mass_matrix_and_forcing(t, q, v);
        lagrange::linalg::mass::solve_mass_matrix(&m, &f).expect("M is regular")
    };
    let half = h * 0.5;
    let (k1q, k1v) = (v, a(&q, &v));
    let (q2, v2) = (q + k1q * half, v + k1v * half);
    let (k2q, k2v) = (v2, a(&q2, &v2));
    let (q3, v3) = (q + k2q * half, v + k2v * half);
    let (k3q, k3v) = (v3, a(&q3, &v3));
    let (q4, v4) = (q + k3q * h, v + k3v * h);
    let (k4q, k4v) = (v4, a(&q4, &v4));
    let (sixth, two) = (h / 6.0, Dual64::from(2.0));
    (
        q + (k1q + k2q * two + k3q * two + k4q) * sixth,
        v + (k1v + k2v * two + k3v * two + k4v) * sixth,
    )
}

/// The same sensitivities from the `Sensitivity` model run by `method`.
fn by_sensitivity<L, I, const N: usize, const P: usize, const D: usize, const NA: usize>(
    model: L,
    directions: [Direction; D],
    (q0, v0): (SVector<f64, N>, SVector<f64, N>),
    method: &I,
    times: &[f64],
) -> (Vec<SMatrix<f64, N, D>>, Vec<SVector<f64, N>>)
where
    L: ParameterDerivatives<N, P, Scalar = f64> + lagrange::sensitivity::Augmented<D, NA>,
    I: Integrator<f64>,
{
    let sensitivity = Sensitivity::<L, N, P, D, NA>::new(model, directions).unwrap();
    let (x0, w0) = sensitivity.initial_state(&q0, &v0);
    let run = method
        .integrate(&sensitivity, 0.0, x0, w0, times)
        .expect("the sensitivity run succeeds");
    (
        run.positions()
            .iter()
            .map(|x| sensitivity.sensitivities(x))
            .collect(),
        run.positions()
            .iter()
            .map(|x| sensitivity.state(x))
            .collect(),
    )
}

/// The largest difference between two runs of sensitivities, relative to
/// the largest sensitivity of the reference, and that largest one.
fn worst<const N: usize, const D: usize>(
    got: &[SMatrix<f64, N, D>],
    reference: &[SMatrix<f64, N, D>],
) -> (f64, f64) {
    let scale = reference.iter().map(|s| s.amax()).fold(0.0, f64::max);
    let diff = got
        .iter()
        .zip(reference)
        .map(|(a, b)| (a - b).amax())
        .fold(0.0, f64::max);
    (diff / scale, scale)
}

const PENDULUM: [f64; 7] = [1.0, 0.8, 1.1, 0.9, 9.81, 0.3, 0.2];

fn pendulum_directions() -> [Direction; 7] {
    let named = |n| Direction::parameter::<DampedDoublePendulum, 2, 7>(n).unwrap();
    [
        named("m2"),
        named("l1"),
        named("l2"),
        named("c1"),
        named("c2"),
        Direction::Position(0),
        Direction::Velocity(1),
    ]
}

fn pendulum_start() -> (SVector<f64, 2>, SVector<f64, 2>) {
    (SVector::from([1.0, -0.5]), SVector::from([0.0, 0.3]))
}

const CHAIN_M: [f64; 5] = [1.0, 1.2, 0.8, 1.5, 0.9];
const CHAIN_L: [f64; 5] = [1.0, 0.7, 1.3, 0.6, 1.1];

fn chain_parameters() -> [f64; 10] {
    std::array::from_fn(|k| if k < 5 { CHAIN_M[k] } else { CHAIN_L[k - 5] })
}

fn chain_directions() -> [Direction; 4] {
    let named = |n| Direction::parameter::<ChainOfFive, 5, 10>(n).unwrap();
    [
        named("m[2]"),
        named("l[0]"),
        named("l[4]"),
        Direction::Position(3),
    ]
}

fn chain_start() -> (SVector<f64, 5>, SVector<f64, 5>) {
    (SVector::from([0.5; 5]), SVector::zeros())
}

fn sample_times() -> Vec<f64> {
    (1..=20).map(|i| 0.1 * i as f64).collect()
}

/// RK4, h = 1e-3 over 2 s. Both roads evaluate the same exact derivatives
/// of the same 2000 steps in different orders of operations: each step
/// adds rounding of a few ulps of the sensitivities, which later steps
/// carry with the growth of perturbations (the sensitivities to the
/// initial state measure it: up to about 30 here), so some 2000 · 30 ·
/// 1e-16 ≈ 1e-11 of the largest sensitivity (measured: 3e-12 for the
/// pendulum, 2e-11 for the chain). 1e-10 bounds it; a missing or wrong term
/// of the variational equations moves the sensitivities at O(1).
const FIXED_STEP_BOUND: f64 = 1e-10;

/// The sensitivity model run by RK4 against the dual numbers over the
/// same steps (h = 1e-3, 2 s), held to [`FIXED_STEP_BOUND`].
fn rk4_equals_dual_numbers<const N: usize, const P: usize, const D: usize, const NA: usize, M, L>(
    parameters: &[f64; P],
    directions: [Direction; D],
    start: (SVector<f64, N>, SVector<f64, N>),
) where
    M: Lagrangian<N, Scalar = Dual64> + FromScalars<Dual64>,
    L: ParameterDerivatives<N, P, Scalar = f64>
        + FromScalars<f64>
        + lagrange::sensitivity::Augmented<D, NA>,
{
    let (times, h) = (sample_times(), 1e-3);
    let dual = by_dual_numbers::<M, N, P, D>(parameters, &directions, start, h, &times);
    let (ours, _) = by_sensitivity::<_, _, N, P, D, NA>(
        L::from_scalars(parameters),
        directions,
        start,
        &Rk4::new(h),
        &times,
    );
    let (relative, scale) = worst(&ours, &dual);
    assert!(
        relative < FIXED_STEP_BOUND && scale > 0.1,
        "{relative:e} of {scale}"
    );
}

#[test]
fn rk4_sensitivities_of_the_double_pendulum_equal_dual_numbers_to_rounding() {
    rk4_equals_dual_numbers::<2, 7, 7, 16, DampedDoublePendulum<Dual64>, DampedDoublePendulum>(
        &PENDULUM,
        pendulum_directions(),
        pendulum_start(),
    );
}

#[test]
fn rk4_sensitivities_of_the_chain_equal_dual_numbers_to_rounding() {
    rk4_equals_dual_numbers::<5, 10, 4, { coordinates(5, 4) }, ChainOfFive<Dual64>, ChainOfFive>(
        &chain_parameters(),
        chain_directions(),
        chain_start(),
    );
}

/// Dop853 (tolerance 1e-12) and Radau5 (1e-10, its Jacobians of the whole
/// augmented state by differences) against the dual numbers' RK4 at
/// h = 5e-4, whose own error is estimated from h = 1e-3 (Richardson: the
/// difference over 15 for a fourth-order method). Each adaptive method is
/// held to 100 times its tolerance plus that estimate: the global error of
/// a tolerance-controlled run is a modest multiple of its tolerance over
/// 2 s of a damped motion (the same factor `tests/trajectories` allows
/// the state), and the sensitivities are in its error control.
#[test]
fn adaptive_and_implicit_sensitivities_converge_to_the_dual_reference() {
    let times = sample_times();
    let coarse = by_dual_numbers::<DampedDoublePendulum<Dual64>, 2, 7, 7>(
        &PENDULUM,
        &pendulum_directions(),
        pendulum_start(),
        1e-3,
        &times,
    );
    let fine = by_dual_numbers::<DampedDoublePendulum<Dual64>, 2, 7, 7>(
        &PENDULUM,
        &pendulum_directions(),
        pendulum_start(),
        5e-4,
        &times,
    );
    let (richardson, _) = worst(&coarse, &fine);
    let richardson = richardson / 15.0;
    for (name, tol, ours) in [
        (
            "dop853",
            1e-12,
            by_sensitivity::<_, _, 2, 7, 7, 16>(
                DampedDoublePendulum::from_scalars(&PENDULUM),
                pendulum_directions(),
                pendulum_start(),
                &Dop853::new().rtol(1e-12).atol(1e-12),
                &times,
            )
            .0,
        ),
        (
            "radau5",
            1e-10,
            by_sensitivity::<_, _, 2, 7, 7, 16>(
                DampedDoublePendulum::from_scalars(&PENDULUM),
                pendulum_directions(),
                pendulum_start(),
                &Radau5::new().rtol(1e-10).atol(1e-10),
                &times,
            )
            .0,
        ),
    ] {
        let (relative, _) = worst(&ours, &fine);
        assert!(
            relative < 100.0 * tol + 2.0 * richardson,
            "{name}: {relative:e} (RK4's own error {richardson:e})"
        );
    }
}

/// The sensitivity model's own state is the model's trajectory: the same
/// `q` as a run of the model alone, to the tolerance of the run (the
/// sensitivities share its error control, so the steps differ).
#[test]
fn the_state_part_is_the_models_trajectory() {
    let times = sample_times();
    let model = DampedDoublePendulum::from_scalars(&PENDULUM);
    let (q0, v0) = pendulum_start();
    let alone = Rk4::new(1e-3)
        .integrate(&model, 0.0, q0, v0, &times)
        .unwrap();
    let (_, states) = by_sensitivity::<_, _, 2, 7, 7, 16>(
        model,
        pendulum_directions(),
        pendulum_start(),
        &Rk4::new(1e-3),
        &times,
    );
    // The same steps on the same equations: bit for bit.
    assert_eq!(alone.positions(), &states[..]);
}

#[test]
fn bad_directions_and_models_are_refused_with_the_reason() {
    let model = DampedDoublePendulum::from_scalars(&PENDULUM);
    let unknown = Direction::parameter::<DampedDoublePendulum, 2, 7>("m3").unwrap_err();
    assert!(
        unknown.to_string().contains("m1, m2, l1, l2, g, c1, c2"),
        "{unknown}"
    );
    let out = Sensitivity::<_, 2, 7, 1, 4>::new(model, [Direction::Position(2)]).unwrap_err();
    assert!(
        matches!(out, SensitivityError::OutOfRange { limit: 2, .. }),
        "{out}"
    );
    let twice = Sensitivity::<_, 2, 7, 2, 6>::new(
        model,
        [Direction::Parameter(1), Direction::Parameter(1)],
    )
    .unwrap_err();
    assert!(
        matches!(twice, SensitivityError::Repeated { .. }),
        "{twice}"
    );
    let mut broken = model;
    broken.m2 = f64::NAN;
    assert_eq!(
        Sensitivity::<_, 2, 7, 1, 4>::new(broken, [Direction::Position(0)]).unwrap_err(),
        SensitivityError::NonFiniteParameters
    );
    // The variational method needs momenta, which a sensitivity has not.
    let sensitivity = Sensitivity::<_, 2, 7, 1, 4>::new(model, [Direction::Position(0)]).unwrap();
    let (x0, w0) = sensitivity.initial_state(&pendulum_start().0, &pendulum_start().1);
    assert!(
        lagrange::Variational::new(1e-2)
            .integrate(&sensitivity, 0.0, x0, w0, &[0.1])
            .is_err()
    );
}
