//! The seed double pendulum (1, 1, 1, 1, 9.81, from (2, 2.5) at rest)
//! integrated to t = 10 with one sample at the end, by Dop853 and Dopri5
//! at 1e-8, 1e-10 and 1e-12: each run's best of `ROUNDS` (argument 1,
//! default 20), one line a run (method, tolerance, evaluations, best ms).
//! With `METHOD TOL` as arguments, that run once (for cachegrind).

use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;
use std::hint::black_box;
use std::time::Instant;

lagrangian! {
    pub struct DoublePendulum {
        coordinates: theta1, theta2;
        parameters: m1, m2, l1, l2, g;
        let x1 = l1*sin(theta1);
        let y1 = -l1*cos(theta1);
        let x2 = x1 + l2*sin(theta2);
        let y2 = y1 - l2*cos(theta2);
        kinetic: m1/2*(dot(x1)^2 + dot(y1)^2) + m2/2*(dot(x2)^2 + dot(y2)^2);
        potential: m1*g*y1 + m2*g*y2;
    }
}

/// One run: its evaluations.
fn run(method: &str, tol: f64) -> usize {
    let model = DoublePendulum::new(1.0, 1.0, 1.0, 1.0, 9.81);
    let (q0, v0) = (Vector2::new(2.0, 2.5), Vector2::zeros());
    let end = [10.0];
    let run = match method {
        "dop853" => {
            Dop853::new()
                .rtol(tol)
                .atol(tol)
                .integrate(black_box(&model), 0.0, q0, v0, &end)
        }
        _ => Dopri5::new()
            .rtol(tol)
            .atol(tol)
            .integrate(black_box(&model), 0.0, q0, v0, &end),
    };
    run.expect("the seed problem integrates").stats().rhs_evals
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() > 2 {
        let tol = args[2].parse().expect("a tolerance");
        println!("{}", run(&args[1], tol));
        return;
    }
    let rounds: usize = args.get(1).map_or(20, |r| r.parse().expect("rounds"));
    for method in ["dop853", "dopri5"] {
        for tol in [1e-8, 1e-10, 1e-12] {
            let mut best = f64::INFINITY;
            let mut evals = 0;
            for _ in 0..rounds {
                let start = Instant::now();
                evals = run(method, tol);
                best = best.min(start.elapsed().as_secs_f64() * 1e3);
            }
            println!("{method} {tol:e}\t{evals}\t{best:.4}");
        }
    }
}
