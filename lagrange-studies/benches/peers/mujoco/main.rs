//! The Rust side of `benches/mujoco.rs`: the models of `models.rs` (written
//! by the bench from `chain.rs.in` and `tree.rs.in`, with `cases`, which
//! calls `reference` or `time` on each) on the `Stepper`, released from rest
//! with the first hinge at 0.5 rad, to T = 2 s.
//!
//! - `reference`: for each model the final state by Dop853 at 1e-13, and
//!   the final-state error of RK4 and symplectic Euler at each step of
//!   `--hs`: one JSON object.
//! - `time`: ns per step of RK4 and symplectic Euler at h = 1e-3 (one run of
//!   2000 steps each; the bench repeats and interleaves): one JSON object.

use std::time::Instant;

use lagrange::nalgebra::SVector;
use lagrange::prelude::*;

mod models;
use models::cases;

const T: f64 = 2.0;
const TIMED_STEP: f64 = 1e-3;

/// The start: every absolute angle 0.5 rad for the chain (absolute
/// coordinates), the first hinge 0.5 rad and the rest 0 for the tree
/// (relative ones): the same configuration as MuJoCo's.
fn start<const N: usize>(absolute: bool) -> SVector<f64, N> {
    SVector::from_fn(|i, _| if absolute || i == 0 { 0.5 } else { 0.0 })
}

fn run_to_end<L, M, const N: usize>(
    model: &L,
    method: M,
    h: f64,
    q0: SVector<f64, N>,
) -> (f64, SVector<f64, N>, SVector<f64, N>)
where
    L: Lagrangian<N, Scalar = f64> + Clone,
    M: StepMethod<f64>,
{
    let steps = (T / h).round() as usize;
    let mut s =
        Stepper::new(model.clone(), method, 0.0, q0, SVector::zeros()).expect("a valid start");
    let clock = Instant::now();
    for k in 1..=steps {
        s.advance_to(k as f64 * h).expect("the chain integrates");
    }
    let ns = clock.elapsed().as_nanos() as f64 / steps as f64;
    (ns, *s.q(), *s.qdot())
}

fn list<const N: usize>(x: &SVector<f64, N>) -> String {
    x.iter()
        .map(|a| format!("{a:.17e}"))
        .collect::<Vec<_>>()
        .join(",")
}

fn error<const N: usize>(
    q: &SVector<f64, N>,
    v: &SVector<f64, N>,
    rq: &SVector<f64, N>,
    rv: &SVector<f64, N>,
) -> f64 {
    (q - rq).amax().max((v - rv).amax())
}

fn reference<L, const N: usize>(name: &str, model: L, absolute: bool, hs: &[f64]) -> String
where
    L: Lagrangian<N, Scalar = f64> + Clone,
{
    let q0 = start::<N>(absolute);
    let end = Dop853::new()
        .rtol(1e-13)
        .atol(1e-13)
        .max_steps(10_000_000)
        .integrate(&model, 0.0, q0, SVector::zeros(), &[T])
        .expect("the reference integrates");
    let last = end.last().expect("one sample");
    let (rq, rv) = (last.q, last.qdot);
    let mut rows = Vec::new();
    for &h in hs {
        let (_, q, v) = run_to_end(&model, Rk4::new(h), h, q0);
        rows.push(format!(
            "{{\"method\":\"RK4\",\"h\":{h},\"error\":{:.3e}}}",
            error(&q, &v, &rq, &rv)
        ));
        let (_, q, v) = run_to_end(&model, SymplecticEuler::new(h), h, q0);
        rows.push(format!(
            "{{\"method\":\"SymplecticEuler\",\"h\":{h},\"error\":{:.3e}}}",
            error(&q, &v, &rq, &rv)
        ));
    }
    format!(
        "\"{name}\":{{\"n\":{N},\"absolute\":{absolute},\"q_ref\":[{}],\"qdot_ref\":[{}],\"ours\":[{}]}}",
        list(&rq),
        list(&rv),
        rows.join(",")
    )
}

fn time<L, const N: usize>(name: &str, model: L, absolute: bool) -> String
where
    L: Lagrangian<N, Scalar = f64> + Clone,
{
    let q0 = start::<N>(absolute);
    let h = TIMED_STEP;
    let (rk4, _, _) = run_to_end(&model, Rk4::new(h), h, q0);
    let (euler, _, _) = run_to_end(&model, SymplecticEuler::new(h), h, q0);
    format!("\"{name}\":{{\"RK4\":{rk4:.1},\"SymplecticEuler\":{euler:.1}}}")
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mode = args.first().map(String::as_str).unwrap_or("time");
    let hs: Vec<f64> = match args.iter().position(|a| a == "--hs") {
        Some(i) => args[i + 1]
            .split(',')
            .map(|h| h.parse().expect("a step"))
            .collect(),
        None => vec![1e-2, 1e-3],
    };
    let parts = match mode {
        "reference" => cases(true, &hs),
        "time" => cases(false, &hs),
        other => panic!("unknown mode {other}: reference or time"),
    };
    println!("{{\"T\":{T},\"h_timed\":{TIMED_STEP},{}}}", parts.join(","));
}
