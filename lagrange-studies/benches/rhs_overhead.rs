//! What an adaptive integrator adds to each right-hand side: the time of a
//! Dop853 run, and of a Dopri5 run, divided by its evaluations, against one
//! evaluation alone (`lagrange::dynamics::acceleration`: the generated `M + f`
//! and the solve), on the double pendulum and a 10-link chain. Issue 14's
//! target: at most 1.3× the evaluation.
//!
//! One evaluation is timed two ways. "Independent": calls on 64 fixed
//! states, which the processor overlaps (the throughput, issue 14's
//! measure). "Chained": each call's state moved by the acceleration the
//! previous one returned (symplectic Euler, 1 ms steps, 64 in a row), so
//! each waits for the last, as the stages of an explicit Runge–Kutta step
//! do (the latency, with the two multiply-adds of the update in it). Each
//! is timed inlined and through a call, and the faster kept.
//!
//! The ratios are fragile: the same `M + f` loop has timed 13.0 and 16.4 ns
//! in two builds that differ only elsewhere (code placement), and they
//! depend on the machine (1.94 on one whose evaluation took half as long),
//! so compare the integrators' own times across builds, and ratios only
//! within one (BENCHMARKS.md, "What an adaptive step adds").
//!
//! `cargo bench -p lagrange-studies --bench rhs_overhead` (under `cargo test` it only says so).
//! Each timing's best of 15, taken in interleaved rounds in one process (a
//! slow spell of a shared machine then slows every measure, not one); a
//! quick table, not criterion's statistics.

use lagrange::dynamics::acceleration;
use lagrange::lagrangian;
use lagrange::models::DoublePendulum;
use lagrange::nalgebra::SVector;
use lagrange::prelude::*;
use std::hint::black_box;
use std::time::Instant;

lagrangian! {
    /// The scaling chain at N = 10, solved with its dense `M` (what this
    /// bench measures, and BENCHMARKS.md's figures; `benches/articulated.rs`
    /// times the recursion the chain gets by default).
    #[lagrange(articulated = false)]
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

/// The time of one run of `f`, in ns, divided by `per`.
fn ns_per(per: usize, f: &mut impl FnMut()) -> f64 {
    let start = Instant::now();
    f();
    start.elapsed().as_secs_f64() * 1e9 / per as f64
}

/// Each timing's best over `rounds` rounds, each round running every timing
/// once, in turn: a slow spell of the shared machine (one has slowed a
/// loop by a fifth within one run of this bench) then falls on all of them
/// alike rather than on one measure alone.
fn best_interleaved<const K: usize>(
    rounds: usize,
    mut timings: [&mut dyn FnMut() -> f64; K],
) -> [f64; K] {
    let mut best = [f64::INFINITY; K];
    for _ in 0..rounds {
        for (best, timing) in best.iter_mut().zip(timings.iter_mut()) {
            *best = best.min(timing());
        }
    }
    best
}

/// `q̈` at `t = 0`, `acceleration` inlined where this is.
#[inline(always)]
fn inlined<L: Lagrangian<N, Scalar = f64>, const N: usize>(
    model: &L,
    q: &SVector<f64, N>,
    v: &SVector<f64, N>,
) -> SVector<f64, N> {
    acceleration(model, 0.0, q, v).unwrap()
}

/// The same through a call.
#[inline(never)]
fn called<L: Lagrangian<N, Scalar = f64>, const N: usize>(
    model: &L,
    q: &SVector<f64, N>,
    v: &SVector<f64, N>,
) -> SVector<f64, N> {
    inlined(model, q, v)
}

/// `eval` on 64 fixed states in turn, `calls` times: ns per call.
fn independent<'a, L: Lagrangian<N, Scalar = f64>, const N: usize>(
    model: &'a L,
    states: &'a [(SVector<f64, N>, SVector<f64, N>)],
    calls: usize,
    eval: impl Fn(&L, &SVector<f64, N>, &SVector<f64, N>) -> SVector<f64, N> + 'a,
) -> impl FnMut() -> f64 + 'a {
    move || {
        ns_per(calls, &mut || {
            for k in 0..calls {
                let (q, v) = &states[k & 63];
                black_box(eval(model, black_box(q), v));
            }
        })
    }
}

/// Chains of 64 symplectic Euler steps of 1 ms from each state in turn
/// (short enough to stay near the states), each step's `eval` waiting for
/// the last: ns per call.
fn chained<'a, L: Lagrangian<N, Scalar = f64>, const N: usize>(
    model: &'a L,
    states: &'a [(SVector<f64, N>, SVector<f64, N>)],
    calls: usize,
    eval: impl Fn(&L, &SVector<f64, N>, &SVector<f64, N>) -> SVector<f64, N> + 'a,
) -> impl FnMut() -> f64 + 'a {
    move || {
        ns_per(calls, &mut || {
            for block in 0..calls / 64 {
                let (mut q, mut v) = states[block & 63];
                for _ in 0..64 {
                    let a = eval(model, &q, &v);
                    v += a * 1e-3;
                    q += v * 1e-3;
                }
                black_box((q, v));
            }
        })
    }
}

/// A model's rows: M + f, one right-hand side (independent and chained),
/// and the time per evaluation of a Dop853 run and of a Dopri5 run.
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
    // About a millisecond per timing of the evaluation.
    let calls = (2_000_000 / (N * N)).max(6400);
    let mut mf = || {
        ns_per(calls, &mut || {
            for k in 0..calls {
                let (q, v) = &states[k & 63];
                black_box(model.mass_matrix_and_forcing(0.0, black_box(q), v));
            }
        })
    };
    // `acceleration` inlined into the loop, and called through a function
    // that is never inlined: the faster of the two is the evaluation's cost
    // (the integrators inline it, which spares them a round trip through
    // memory; a loop of nothing else may schedule the call better).
    let (mut independent_inlined, mut independent_called) = (
        independent(model, &states, calls, inlined),
        independent(model, &states, calls, called),
    );
    let (mut chained_inlined, mut chained_called) = (
        chained(model, &states, calls, inlined),
        chained(model, &states, calls, called),
    );
    // The adaptive methods, each to `t_end` keeping only the final state.
    let start = (q0, t_end);
    let (dop853, dopri5) = (
        Dop853::new().rtol(tol).atol(tol),
        Dopri5::new().rtol(tol).atol(tol),
    );
    let (mut dop853, dop853_evals) = per_evaluation(&dop853, model, start);
    let (mut dopri5, dopri5_evals) = per_evaluation(&dopri5, model, start);
    let [
        mf,
        independent_inlined,
        independent_called,
        chained_inlined,
        chained_called,
        dop853,
        dopri5,
    ] = best_interleaved(
        15,
        [
            &mut mf,
            &mut independent_inlined,
            &mut independent_called,
            &mut chained_inlined,
            &mut chained_called,
            &mut dop853,
            &mut dopri5,
        ],
    );
    let rhs = independent_inlined.min(independent_called);
    let chained = chained_inlined.min(chained_called);
    for (method, evals, per_eval) in [
        ("Dop853", dop853_evals, dop853),
        ("Dopri5", dopri5_evals, dopri5),
    ] {
        println!(
            "| {name} | {method} | {evals} | {mf:.1} | {rhs:.1} | {chained:.1} | {per_eval:.1} | {:.2} | {:.2} |",
            per_eval / rhs,
            per_eval / chained
        );
    }
}

/// Runs of `method` from `q0` at rest to `t_end`, keeping only the final
/// state: a timing of one run, in ns per evaluation, and the evaluations.
fn per_evaluation<'a, M: Integrator<f64>, L: Lagrangian<N, Scalar = f64>, const N: usize>(
    method: &'a M,
    model: &'a L,
    (q0, t_end): (SVector<f64, N>, f64),
) -> (impl FnMut() -> f64 + 'a, usize) {
    let run = move || {
        method
            .integrate(model, 0.0, q0, SVector::zeros(), &[t_end])
            .unwrap()
    };
    let evals = run().stats().rhs_evals;
    let timing = move || {
        ns_per(evals, &mut || {
            black_box(run());
        })
    };
    (timing, evals)
}

fn main() {
    if !std::env::args().any(|a| a == "--bench") {
        println!("rhs_overhead: run with `cargo bench -p lagrange-studies --bench rhs_overhead`");
        return;
    }
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("load average at the start: {}", load.trim());
    println!();
    println!("Both methods at rtol = atol = 1e-10.");
    println!();
    println!(
        "| model | method | evaluations | M + f (ns) | M + f + solve, independent (ns) | M + f + solve, chained (ns) | method per evaluation (ns) | per evaluation / independent | per evaluation / chained |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|");
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
