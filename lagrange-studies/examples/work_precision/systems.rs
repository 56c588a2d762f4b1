//! The test problems of the work–precision study, each with its reference.

use crate::reference::Reference;
use lagrange::models::{CartesianPendulum, DoublePendulum, Kepler, SliderCrank, StiffChain};
use lagrange::nalgebra::SVector;
use lagrange::prelude::*;

/// A problem: a model, a start, where to sample, and the exact answer.
pub struct Problem<L: Lagrangian<N, Scalar = f64>, const N: usize> {
    pub name: &'static str,
    pub model: L,
    pub q0: SVector<f64, N>,
    pub qdot0: SVector<f64, N>,
    /// Samples: the energy error is the worst over them, the error is taken
    /// at the last one.
    pub times: Vec<f64>,
    pub final_state: (SVector<f64, N>, SVector<f64, N>),
    /// The exact energy at each sample time.
    pub energies: Vec<f64>,
    /// Fixed step sizes to sweep (largest first).
    pub steps: Vec<f64>,
}

fn halvings(h0: f64, count: usize) -> Vec<f64> {
    (0..count).map(|k| h0 / 2f64.powi(k as i32)).collect()
}

/// The chaotic double pendulum to t = 2 (perturbation growth 13: any
/// float64 run can reach ~1e-15), against the 25-digit reference.
pub fn double_pendulum() -> Problem<DoublePendulum, 2> {
    let reference = Reference::double_pendulum();
    let sample = reference.samples.iter().find(|s| s.t == 2.0).unwrap();
    let times: Vec<f64> = (1..=40).map(|k| 0.05 * k as f64).collect();
    Problem {
        name: "double_pendulum",
        model: reference.double_pendulum_model(),
        q0: reference.q0,
        qdot0: reference.qdot0,
        energies: vec![reference.energy0; times.len()],
        times,
        final_state: (sample.q, sample.qdot),
        steps: halvings(0.05, 10),
    }
}

/// Kepler, eccentricity 0.9, 100 periods from pericentre: the orbit is
/// periodic, so the exact final state is the initial one.
pub fn kepler() -> Problem<Kepler, 2> {
    let period = 2.0 * std::f64::consts::PI;
    let model = Kepler::new(1.0);
    let (q0, qdot0) = model.pericentre(0.9);
    let energy = -0.5; // −μ / 2a with a = 1
    // 20 samples per orbit: the energy error of a symplectic method
    // oscillates along the orbit, and one sample per orbit would see only
    // one phase.
    let times: Vec<f64> = (1..=2000).map(|k| period * k as f64 / 20.0).collect();
    Problem {
        name: "kepler_e0.9",
        model,
        q0,
        qdot0,
        energies: vec![energy; times.len()],
        times,
        final_state: (q0, qdot0),
        steps: halvings(period / 100.0, 8),
    }
}

/// The stiff chain (ratio 1e6) over 10 s; exact through the matrix
/// exponential of the linear first-order system.
pub fn stiff_chain() -> Problem<StiffChain, 3> {
    let model = StiffChain::ratio_1e6();
    let (q0, qdot0) = StiffChain::start();
    let times: Vec<f64> = (1..=20).map(|k| 0.5 * k as f64).collect();
    let states: Vec<_> = times.iter().map(|&t| model.exact(t, q0, qdot0)).collect();
    let energies = states
        .iter()
        .map(|(q, v)| model.energy(0.0, q, v))
        .collect();
    Problem {
        name: "stiff_chain_1e6",
        model,
        q0,
        qdot0,
        final_state: *states.last().unwrap(),
        energies,
        times,
        steps: halvings(0.02, 9),
    }
}

/// The pendulum in Cartesian coordinates held by its rod (a constrained
/// model, projection after each step), released from rest at 1 rad, over
/// ten periods; exact through the θ pendulum's elliptic-function solution
/// (`tests/support/elliptic.rs`, ~1e-14).
pub fn cartesian_pendulum() -> Problem<CartesianPendulum, 2> {
    let model: CartesianPendulum = CartesianPendulum::new(1.0, 1.0, 9.81);
    let (theta, quarter) = crate::elliptic::released_from_rest(model.g.sqrt(), 1.0);
    let (q0, qdot0) = model.state(1.0, 0.0);
    let period = 4.0 * quarter;
    let times: Vec<f64> = (1..=200)
        .map(|k| 10.0 * period * k as f64 / 200.0)
        .collect();
    let (angle, rate) = theta(*times.last().unwrap());
    Problem {
        name: "cartesian_pendulum",
        energies: vec![model.energy(0.0, &q0, &qdot0); times.len()],
        final_state: model.state(angle, rate),
        model,
        q0,
        qdot0,
        times,
        steps: halvings(0.02, 9),
    }
}

/// The slider-crank in three coordinates and two loop constraints, 10 s of
/// a crank at 20 rad/s; the reference is the same mechanism in its minimal
/// coordinate (an independent model: no constraint code on its path) by
/// Gauss–Legendre 3 at h = 1e-4 (order 6, (ω h)⁶ ≈ 1e-16: rounding alone,
/// on a crank angle that reaches 200 rad; Dop853 at 1e-14 was 6e-11 off
/// it), with the rod and piston from the closed-form kinematics.
pub fn slider_crank() -> Problem<SliderCrank, 3> {
    let model = SliderCrank::engine();
    let (q0, qdot0) = model.state(0.5, 20.0);
    let times: Vec<f64> = (1..=100).map(|k| 0.1 * k as f64).collect();
    let end = *times.last().unwrap();
    let reference = GaussLegendre::three_stage(1e-4)
        .max_steps(10_000_000)
        .integrate(
            &model.minimal(),
            0.0,
            SVector::<f64, 1>::new(q0[0]),
            SVector::<f64, 1>::new(qdot0[0]),
            &[end],
        )
        .expect("the minimal slider-crank integrates");
    let last = reference.last().unwrap();
    Problem {
        name: "slider_crank",
        energies: vec![model.energy(0.0, &q0, &qdot0); times.len()],
        final_state: model.state(last.q[0], last.qdot[0]),
        model,
        q0,
        qdot0,
        times,
        steps: halvings(0.005, 9),
    }
}
