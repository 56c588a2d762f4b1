//! What `#[lagrange(jacobians)]` costs at compile time: the N-link chain
//! expanded with and without the exact residual Jacobians (`∂(M q̈ − f)/∂q`
//! and `/∂q̇`, which the implicit methods and `lagrange::analysis` use),
//! median time of `expand` and the size of the emitted code. Why the
//! Jacobians are opt-in rather than generated for every model.
//!
//! `cargo run --release -p lagrange-studies --example jacobian_cost`

#[path = "support/option_cost.rs"]
mod option_cost;

use option_cost::{chain, expand};

fn main() {
    println!(
        "| N | expand (s) | with jacobians (s) | ratio | code (kB) | with jacobians (kB) | ratio |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|");
    for n in [2, 5, 10, 20] {
        let reps = if n >= 20 { 3 } else { 7 };
        let (t0, b0) = expand(&chain(n, None), reps);
        let (t1, b1) = expand(&chain(n, Some("jacobians")), reps);
        println!(
            "| {n} | {:.4} | {:.4} | {:.2} | {:.0} | {:.0} | {:.2} |",
            t0.as_secs_f64(),
            t1.as_secs_f64(),
            t1.as_secs_f64() / t0.as_secs_f64(),
            b0 as f64 / 1e3,
            b1 as f64 / 1e3,
            b1 as f64 / b0 as f64
        );
    }
}
