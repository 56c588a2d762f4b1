//! Side by side with an established Rust ODE crate, `ode_solvers`, on the
//! same generated right-hand side (both call `lagrange::dynamics::acceleration`
//! on the derived double pendulum), the same problem (the chaotic double
//! pendulum from rest at (2, 2.5), to t = 2, against the 25-digit reference)
//! and the same tolerances: the error reached, the evaluations and the time.
//!
//! `cargo bench -p lagrange-studies --bench vs_ode_solvers`

/// The tests' reader of `tests/data/*.json`; the benchmark needs part of it.
#[allow(dead_code)]
#[path = "../../tests/support/reference.rs"]
mod reference;

use criterion::{Criterion, criterion_group, criterion_main};
use lagrange::dynamics::acceleration;
use lagrange::models::DoublePendulum;
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;
use reference::Reference;
use std::hint::black_box;

type State = ode_solvers::Vector4<f64>;

/// The double pendulum as a first-order system for `ode_solvers`.
struct FirstOrder(DoublePendulum);

impl ode_solvers::System<f64, State> for FirstOrder {
    fn system(&self, t: f64, y: &State, dy: &mut State) {
        let q = Vector2::new(y[0], y[1]);
        let v = Vector2::new(y[2], y[3]);
        let a = acceleration(&self.0, t, &q, &v).expect("regular mass matrix");
        *dy = State::new(v[0], v[1], a[0], a[1]);
    }
}

const T_END: f64 = 2.0;

fn model() -> DoublePendulum {
    DoublePendulum::unit()
}

fn ours<I: Integrator<f64>>(method: I) -> (State, usize) {
    let t = method
        .integrate(
            &model(),
            0.0,
            Vector2::new(2.0, 2.5),
            Vector2::zeros(),
            &[T_END],
        )
        .unwrap();
    let s = t.last().unwrap();
    (
        State::new(s.q[0], s.q[1], s.qdot[0], s.qdot[1]),
        t.stats().rhs_evals,
    )
}

fn ours_dopri5(tol: f64) -> (State, usize) {
    ours(Dopri5::new().rtol(tol).atol(tol))
}

fn ours_dop853(tol: f64) -> (State, usize) {
    ours(Dop853::new().rtol(tol).atol(tol))
}

/// Their DOP853 with its defaults (Hairer's), sparse output as for Dopri5.
fn theirs_dop853(tol: f64) -> (State, usize) {
    let y0 = State::new(2.0, 2.5, 0.0, 0.0);
    let mut stepper = ode_solvers::Dop853::from_param(
        FirstOrder(model()),
        0.0,
        T_END,
        T_END,
        y0,
        tol,
        tol,
        0.9,
        0.0,
        0.333,
        6.0,
        T_END,
        0.0,
        100_000,
        1000,
        ode_solvers::dop_shared::OutputType::Sparse,
    );
    let stats = stepper.integrate().unwrap();
    assert_eq!(*stepper.x_out().last().unwrap(), T_END);
    (*stepper.y_out().last().unwrap(), stats.num_eval as usize)
}

fn theirs(tol: f64) -> (State, usize) {
    let y0 = State::new(2.0, 2.5, 0.0, 0.0);
    // Their defaults (Hairer's: safety 0.9, beta 0.04, facmin 0.2, facmax
    // 10, initial step estimated), with sparse output: the state after every
    // accepted step, the last of which ends at T_END. (Their dense output at
    // exactly x_end returned a wrong state in our trials; interior dense
    // output points were right.)
    let mut stepper = ode_solvers::Dopri5::from_param(
        FirstOrder(model()),
        0.0,
        T_END,
        T_END,
        y0,
        tol,
        tol,
        0.9,
        0.04,
        0.2,
        10.0,
        T_END,
        0.0,
        100_000,
        1000,
        ode_solvers::dop_shared::OutputType::Sparse,
    );
    let stats = stepper.integrate().unwrap();
    assert_eq!(*stepper.x_out().last().unwrap(), T_END);
    (*stepper.y_out().last().unwrap(), stats.num_eval as usize)
}

/// The largest difference from the reference at `T_END`
/// (`tests/data/double_pendulum.json`).
fn error(y: &State) -> f64 {
    let reference = Reference::double_pendulum();
    let s = reference.samples.iter().find(|s| s.t == T_END).unwrap();
    let exact = [s.q[0], s.q[1], s.qdot[0], s.qdot[1]];
    (0..4).map(|i| (y[i] - exact[i]).abs()).fold(0.0, f64::max)
}

fn bench(c: &mut Criterion) {
    type Run = fn(f64) -> (State, usize);
    let pairs: [(&str, Run, Run); 2] = [
        ("dopri5", ours_dopri5, theirs),
        ("dop853", ours_dop853, theirs_dop853),
    ];
    for (name, mine, other) in pairs {
        println!("\n{name} on the double pendulum to t = 2, same tolerance rtol = atol:");
        println!(
            "{:>8} {:>14} {:>10} {:>14} {:>10}",
            "tol", "lagrange error", "evals", "ode_solvers", "evals"
        );
        for tol in [1e-6, 1e-8, 1e-10, 1e-12] {
            let (a, na) = mine(tol);
            let (b, nb) = other(tol);
            println!(
                "{tol:>8.0e} {:>14.2e} {na:>10} {:>14.2e} {nb:>10}",
                error(&a),
                error(&b)
            );
        }
        let mut group = c.benchmark_group(format!("{name}_double_pendulum_t2"));
        for tol in [1e-8, 1e-12] {
            group.bench_function(format!("lagrange_tol_{tol:.0e}"), |b| {
                b.iter(|| mine(black_box(tol)))
            });
            group.bench_function(format!("ode_solvers_tol_{tol:.0e}"), |b| {
                b.iter(|| other(black_box(tol)))
            });
        }
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
