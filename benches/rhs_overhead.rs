//! What an adaptive integrator adds to each right-hand side: the time of a
//! Dop853 run divided by its evaluations, against one evaluation alone
//! (`lagrange::solve::acceleration`: the generated `M + f` and the solve),
//! on the double pendulum and a 10-link chain. Issue 14's target: at most
//! 1.3× the evaluation.
//!
//! One evaluation is timed two ways. "Independent": calls on 64 fixed
//! states, which the processor overlaps (the throughput, issue 14's
//! measure). "Chained": each call's state moved by the acceleration the
//! previous one returned (symplectic Euler, 1 ms steps, 64 in a row), so
//! each waits for the last, as the stages of an explicit Runge–Kutta step
//! do (the latency, with the two multiply-adds of the update in it).
//!
//! `cargo bench --bench rhs_overhead` (under `cargo test` it only says so).
//! Best of several repetitions each, one process; a quick table, not
//! criterion's statistics.

use lagrange::lagrangian;
use lagrange::models::DoublePendulum;
use lagrange::nalgebra::SVector;
use lagrange::prelude::*;
use lagrange::solve::acceleration;
use std::hint::black_box;
use std::time::Instant;

lagrangian! {
    /// The scaling chain at N = 10.
    pub struct Chain10 {
        const N = 10;
        coordinates: theta[N];
        parameters: m[N], l[N];
        constants: g = 9.81;
        let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
        let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
        kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
        potential: sum(i in 0..N, m[i]*g*y[i]);
    }
}

/// Best time of `reps` runs of `f`, in ns, divided by `per`.
fn best_ns(reps: usize, per: usize, mut f: impl FnMut()) -> f64 {
    (0..reps)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64() * 1e9 / per as f64
        })
        .fold(f64::INFINITY, f64::min)
}

/// One row: M + f, one right-hand side, and a Dop853 run's time per evaluation.
fn row<L: Lagrangian<N, Scalar = f64>, const N: usize>(
    name: &str,
    model: &L,
    q0: SVector<f64, N>,
    t_end: f64,
    tol: f64,
) {
    let states: Vec<(SVector<f64, N>, SVector<f64, N>)> = (0..64)
        .map(|k| {
            let q = SVector::from_fn(|i, _| 0.3 + 0.9 * (1.7 * i as f64 + k as f64).sin());
            let v = SVector::from_fn(|i, _| 0.5 * (1.3 * i as f64 - 0.7 * k as f64).cos());
            (q, v)
        })
        .collect();
    let calls = 200_000;
    let mf = best_ns(7, calls, || {
        for k in 0..calls {
            let (q, v) = &states[k & 63];
            black_box(model.mass_matrix_and_forcing(0.0, black_box(q), v));
        }
    });
    let rhs = best_ns(7, calls, || {
        for k in 0..calls {
            let (q, v) = &states[k & 63];
            black_box(acceleration(model, 0.0, black_box(q), v).unwrap());
        }
    });
    // Chains of 64 symplectic Euler steps of 1 ms from each state in turn:
    // short enough to stay near the states above.
    let chained = best_ns(7, calls, || {
        for block in 0..calls / 64 {
            let (mut q, mut v) = states[block & 63];
            for _ in 0..64 {
                let a = acceleration(model, 0.0, &q, &v).unwrap();
                v += a * 1e-3;
                q += v * 1e-3;
            }
            black_box((q, v));
        }
    });
    let method = Dop853::new().rtol(tol).atol(tol);
    let run = || {
        method
            .integrate(model, 0.0, q0, SVector::zeros(), &[t_end])
            .unwrap()
    };
    let evals = run().stats().rhs_evals;
    let per_eval = best_ns(7, evals, || {
        black_box(run());
    });
    println!(
        "| {name} | {tol:.0e} | {evals} | {mf:.1} | {rhs:.1} | {chained:.1} | {per_eval:.1} | {:.2} | {:.2} |",
        per_eval / rhs,
        per_eval / chained
    );
}

fn main() {
    if !std::env::args().any(|a| a == "--bench") {
        println!("rhs_overhead: run with `cargo bench --bench rhs_overhead`");
        return;
    }
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("load average at the start: {}", load.trim());
    println!();
    println!("| model | Dop853 tol | evaluations | M + f (ns) | M + f + solve, independent (ns) | M + f + solve, chained (ns) | Dop853 per evaluation (ns) | per evaluation / independent | per evaluation / chained |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    let dp = DoublePendulum::unit();
    row(
        "double pendulum",
        &dp,
        SVector::from([2.0, 2.5]),
        10.0,
        1e-10,
    );
    let m: [f64; 10] = core::array::from_fn(|i| 1.0 + 0.1 * i as f64);
    let l: [f64; 10] = core::array::from_fn(|i| 1.0 - 0.05 * i as f64);
    let chain = Chain10::new(m, l);
    row(
        "10-link chain",
        &chain,
        SVector::from_fn(|i, _| 0.3 + 0.05 * i as f64),
        5.0,
        1e-10,
    );
}
