//! The test problems of the work–precision study, each with its reference.

use lagrange::models::DoublePendulum;
use lagrange::nalgebra::{SMatrix, SVector, Vector2, Vector3};
use lagrange::prelude::*;

lagrangian! {
    /// A unit-mass body around a unit central mass (μ = 1), Cartesian.
    #[lagrange(jacobians)]
    pub struct Kepler {
        coordinates: x, y;
        parameters: mu;
        kinetic: (dot(x)^2 + dot(y)^2)/2;
        potential: -mu/sqrt(x^2 + y^2);
    }
}

lagrangian! {
    /// Three unit masses in a row between walls; the middle spring is
    /// `stiff` times harder than the others, and damped.
    #[lagrange(jacobians)]
    pub struct StiffChain {
        coordinates: x1, x2, x3;
        parameters: k, stiff, c;
        kinetic: (dot(x1)^2 + dot(x2)^2 + dot(x3)^2)/2;
        potential: k/2*x1^2 + stiff*k/2*(x2 - x1)^2 + k/2*(x3 - x2)^2 + k/2*x3^2;
        dissipation: c/2*(dot(x2) - dot(x1))^2;
    }
}

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

fn reference_number(v: &serde_json::Value) -> f64 {
    match v {
        serde_json::Value::String(s) => s.parse().unwrap(),
        v => v.as_f64().unwrap(),
    }
}

fn halvings(h0: f64, count: usize) -> Vec<f64> {
    (0..count).map(|k| h0 / 2f64.powi(k as i32)).collect()
}

/// The chaotic double pendulum to t = 2 (perturbation growth 13: any
/// float64 run can reach ~1e-15), against the 25-digit reference.
pub fn double_pendulum() -> Problem<DoublePendulum, 2> {
    let json: serde_json::Value =
        serde_json::from_str(include_str!("../../tests/data/double_pendulum.json")).unwrap();
    let sample = json["samples"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| reference_number(&s["t"]) == 2.0)
        .unwrap();
    let v2 = |v: &serde_json::Value| Vector2::new(reference_number(&v[0]), reference_number(&v[1]));
    let e0 = reference_number(&json["energy0"]);
    let times: Vec<f64> = (1..=40).map(|k| 0.05 * k as f64).collect();
    Problem {
        name: "double_pendulum",
        model: DoublePendulum::new(1.0, 1.0, 1.0, 1.0, 9.81),
        q0: v2(&json["q0"]),
        qdot0: v2(&json["dq0"]),
        energies: vec![e0; times.len()],
        times,
        final_state: (v2(&sample["q"]), v2(&sample["dq"])),
        steps: halvings(0.05, 10),
    }
}

/// Kepler, eccentricity 0.9, 100 periods from pericentre: the orbit is
/// periodic, so the exact final state is the initial one.
pub fn kepler() -> Problem<Kepler, 2> {
    let e: f64 = 0.9;
    let period = 2.0 * std::f64::consts::PI;
    let q0 = Vector2::new(1.0 - e, 0.0);
    let qdot0 = Vector2::new(0.0, ((1.0 + e) / (1.0 - e)).sqrt());
    let energy = -0.5; // −μ / 2a with a = 1
                       // 20 samples per orbit: the energy error of a symplectic method oscillates
                       // along the orbit, and one sample per orbit would see only one phase.
    let times: Vec<f64> = (1..=2000).map(|k| period * k as f64 / 20.0).collect();
    Problem {
        name: "kepler_e0.9",
        model: Kepler::new(1.0),
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
    let (k, stiff, c) = (1.0, 1e6, 20.0);
    let model = StiffChain::new(k, stiff, c);
    let q0 = Vector3::new(0.1, 0.1, -0.05); // the stiff spring starts relaxed
    let qdot0 = Vector3::zeros();
    let mut a = SMatrix::<f64, 6, 6>::zeros();
    let stiffness = SMatrix::<f64, 3, 3>::new(
        k + stiff * k,
        -stiff * k,
        0.0,
        -stiff * k,
        stiff * k + k,
        -k,
        0.0,
        -k,
        2.0 * k,
    );
    let damping = SMatrix::<f64, 3, 3>::new(c, -c, 0.0, -c, c, 0.0, 0.0, 0.0, 0.0);
    a.fixed_view_mut::<3, 3>(0, 3)
        .copy_from(&SMatrix::<f64, 3, 3>::identity());
    a.fixed_view_mut::<3, 3>(3, 0).copy_from(&(-stiffness));
    a.fixed_view_mut::<3, 3>(3, 3).copy_from(&(-damping));
    let mut y0 = SVector::<f64, 6>::zeros();
    y0.fixed_rows_mut::<3>(0).copy_from(&q0);
    let times: Vec<f64> = (1..=20).map(|k| 0.5 * k as f64).collect();
    let states: Vec<SVector<f64, 6>> = times.iter().map(|&t| (a * t).exp() * y0).collect();
    let split = |y: &SVector<f64, 6>| {
        (
            y.fixed_rows::<3>(0).into_owned(),
            y.fixed_rows::<3>(3).into_owned(),
        )
    };
    let energies = states
        .iter()
        .map(|y| {
            let (q, v) = split(y);
            model.energy(0.0, &q, &v)
        })
        .collect();
    Problem {
        name: "stiff_chain_1e6",
        model,
        q0,
        qdot0,
        final_state: split(states.last().unwrap()),
        energies,
        times,
        steps: halvings(0.02, 9),
    }
}
