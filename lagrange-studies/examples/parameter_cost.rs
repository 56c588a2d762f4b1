//! What `#[lagrange(parameter_derivatives)]` costs, on the N-link chain of
//! point masses (`m[N]`, `l[N]`: P = 2N parameter scalars) at N = 2, 5, 10
//! and 20. At compile time: the engine's expansion with and without the
//! option (median time of `expand`, size of the emitted code). At run
//! time: `∂f/∂p` (N × P), the residual's `∂r/∂p` (N × P) and `∂M/∂p` (P
//! matrices N × N) against `f` alone, ns per call (median of 7 batches);
//! and one right-hand side of the chain with its forward sensitivities to
//! all P parameters (`lagrange::sensitivity`, `N (1 + P)` coordinates,
//! with the exact Jacobians) against `q̈` alone.
//!
//! `cargo run --release -p lagrange-studies --example parameter_cost`

#[path = "support/option_cost.rs"]
mod option_cost;

use lagrange::nalgebra::SVector;
use lagrange::prelude::*;
use option_cost::{chain, expand};
use std::hint::black_box;
use std::time::Instant;

macro_rules! chain_model {
    ($name:ident, $n:literal) => {
        lagrangian! {
            #[lagrange(jacobians, parameter_derivatives)]
            pub struct $name {
                const N = $n;
                coordinates: theta[N];
                parameters: m[N], l[N];
                constants: g = 9.81;
                let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
                let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
                kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
                potential: sum(i in 0..N, m[i]*g*y[i]);
            }
        }
    };
}

chain_model!(Chain2, 2);
chain_model!(Chain5, 5);
chain_model!(Chain10, 10);
chain_model!(Chain20, 20);

/// Median ns per call of `f` over 7 batches.
fn ns(mut f: impl FnMut()) -> f64 {
    let calls = 2_000;
    let mut times: Vec<f64> = (0..7)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..calls {
                f();
            }
            start.elapsed().as_secs_f64() * 1e9 / calls as f64
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[3]
}

macro_rules! run_time {
    ($name:ident, $n:literal) => {{
        let model = $name::new([1.0; $n], [0.5; $n]);
        let q = SVector::<f64, $n>::from_fn(|i, _| 0.4 * (0.7 * i as f64).sin());
        let v = SVector::<f64, $n>::from_fn(|i, _| 0.5 * (1.3 * i as f64).cos());
        let a = SVector::<f64, $n>::from_fn(|i, _| 0.3 * (0.9 * i as f64).sin());
        let m = black_box(model);
        let f = ns(|| {
            black_box(m.forcing(0.0, black_box(&q), black_box(&v)));
        });
        let df = ns(|| {
            black_box(m.forcing_parameter_jacobian(0.0, black_box(&q), black_box(&v)));
        });
        let dr = ns(|| {
            black_box(m.residual_parameter_jacobian(
                0.0,
                black_box(&q),
                black_box(&v),
                black_box(&a),
            ));
        });
        let dm = ns(|| {
            black_box(m.mass_matrix_parameter_derivatives(0.0, black_box(&q)));
        });
        (f, df, dr, dm)
    }};
}

/// ns per right-hand side of the chain alone, and with its sensitivities
/// to all its `P` parameters (`NA = N (1 + P)` coordinates).
macro_rules! sensitivity_time {
    ($name:ident, $n:literal, $p:literal, $na:literal) => {{
        use lagrange::dynamics::acceleration;
        use lagrange::sensitivity::{Direction, Sensitivity};
        let model = $name::new([1.0; $n], [0.5; $n]);
        let directions: [Direction; $p] = std::array::from_fn(Direction::Parameter);
        let sensitivity = Sensitivity::<_, $n, $p, $p, $na>::new(model, directions).unwrap();
        let q = SVector::<f64, $n>::from_fn(|i, _| 0.4 * (0.7 * i as f64).sin());
        let v = SVector::<f64, $n>::from_fn(|i, _| 0.5 * (1.3 * i as f64).cos());
        let (mut x, mut w) = sensitivity.initial_state(&q, &v);
        for k in $n..$na {
            x[k] = 0.1 * (0.3 * k as f64).sin();
            w[k] = 0.1 * (0.7 * k as f64).cos();
        }
        let m = black_box(model);
        let alone = ns(|| {
            black_box(acceleration(&m, 0.0, black_box(&q), black_box(&v)).unwrap());
        });
        let s = black_box(sensitivity);
        let with = ns(|| {
            black_box(acceleration(&s, 0.0, black_box(&x), black_box(&w)).unwrap());
        });
        (alone, with)
    }};
}

fn main() {
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("load average at the start: {}", load.trim());
    println!();
    println!("Compile time: the engine's expansion (median), and the emitted code.");
    println!();
    println!(
        "| N | P | expand (s) | with the option (s) | ratio | code (kB) | with the option (kB) | ratio |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|");
    for n in [2, 5, 10, 20] {
        let reps = if n >= 20 { 3 } else { 7 };
        let (t0, b0) = expand(&chain(n, None), reps);
        let (t1, b1) = expand(&chain(n, Some("parameter_derivatives")), reps);
        println!(
            "| {n} | {} | {:.4} | {:.4} | {:.2} | {:.0} | {:.0} | {:.2} |",
            2 * n,
            t0.as_secs_f64(),
            t1.as_secs_f64(),
            t1.as_secs_f64() / t0.as_secs_f64(),
            b0 as f64 / 1e3,
            b1 as f64 / 1e3,
            b1 as f64 / b0 as f64
        );
    }
    println!();
    println!("Run time: ns per call, and each against `f` alone.");
    println!();
    println!("| N | P | f | ∂f/∂p | ratio | ∂r/∂p | ratio | ∂M/∂p | ratio |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let rows = [
        (2, run_time!(Chain2, 2)),
        (5, run_time!(Chain5, 5)),
        (10, run_time!(Chain10, 10)),
        (20, run_time!(Chain20, 20)),
    ];
    for (n, (f, df, dr, dm)) in rows {
        println!(
            "| {n} | {} | {f:.1} | {df:.1} | {:.1} | {dr:.1} | {:.1} | {dm:.1} | {:.1} |",
            2 * n,
            df / f,
            dr / f,
            dm / f
        );
    }
    println!();
    println!(
        "One right-hand side with the sensitivities to all P parameters, ns, against `q̈` alone;"
    );
    println!("the last column per sensitivity (the ratio over P).");
    println!();
    println!("| N | P | q̈ | with sensitivities | ratio | ratio / P |");
    println!("|---:|---:|---:|---:|---:|---:|");
    let rows = [
        (2, sensitivity_time!(Chain2, 2, 4, 10)),
        (5, sensitivity_time!(Chain5, 5, 10, 55)),
        (10, sensitivity_time!(Chain10, 10, 20, 210)),
        (20, sensitivity_time!(Chain20, 20, 40, 820)),
    ];
    for (n, (alone, with)) in rows {
        let p = 2 * n;
        println!(
            "| {n} | {p} | {alone:.1} | {with:.1} | {:.1} | {:.2} |",
            with / alone,
            with / alone / p as f64
        );
    }
}
