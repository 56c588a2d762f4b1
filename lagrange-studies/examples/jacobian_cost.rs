//! What `#[lagrange(jacobians)]` costs at compile time: the N-link chain
//! expanded with and without the exact residual Jacobians (`∂(M q̈ − f)/∂q`
//! and `/∂q̇`, which the implicit methods and `lagrange::analysis` use),
//! median time of `expand` and the size of the emitted code. Why the
//! Jacobians are opt-in rather than generated for every model.
//!
//! `cargo run --release -p lagrange-studies --example jacobian_cost`

#[allow(dead_code)]
#[path = "scaling/chain.rs"]
mod chain;

use chain::Form;
use proc_macro2::TokenStream;
use std::time::{Duration, Instant};

/// The `n`-link chain of `lagrange-studies/examples/scaling`, with or without the attribute.
fn chain(n: usize, jacobians: bool) -> TokenStream {
    let attribute = if jacobians {
        "#[lagrange(jacobians)]"
    } else {
        ""
    };
    format!("{attribute} {}", chain::model_body(n, Form::Indexed))
        .parse()
        .expect("the chain lexes")
}

/// Median expansion time over `reps` runs, and the emitted code's size.
fn expand(tokens: &TokenStream, reps: usize) -> (Duration, usize) {
    let mut times = Vec::new();
    let mut bytes = 0;
    for _ in 0..reps {
        let start = Instant::now();
        let out = lagrange_engine::expand(tokens.clone());
        times.push(start.elapsed());
        bytes = out.to_string().len();
    }
    times.sort();
    (times[reps / 2], bytes)
}

fn main() {
    println!(
        "| N | expand (s) | with jacobians (s) | ratio | code (kB) | with jacobians (kB) | ratio |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|");
    for n in [2, 5, 10, 20] {
        let reps = if n >= 20 { 3 } else { 7 };
        let (t0, b0) = expand(&chain(n, false), reps);
        let (t1, b1) = expand(&chain(n, true), reps);
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
