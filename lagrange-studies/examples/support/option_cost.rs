//! What an opt-in `#[lagrange(..)]` option costs the engine: the N-link
//! chain of `scaling/chain.rs` expanded with and without it. Shared by
//! `jacobian_cost` and `parameter_cost`.

#[allow(dead_code)]
#[path = "../scaling/chain.rs"]
mod chain;

use chain::Form;
use proc_macro2::TokenStream;
use std::time::{Duration, Instant};

/// The `n`-link chain, written with `#[lagrange(option)]` if one is given;
/// with its `M` and `f` generated (`articulated = false`), as the options
/// were first measured on.
pub fn chain(n: usize, option: Option<&str>) -> TokenStream {
    let attribute = option.map_or(String::new(), |o| format!("#[lagrange({o})]"));
    format!("{attribute} {}", chain::model_body(n, Form::Indexed, false))
        .parse()
        .expect("the chain lexes")
}

/// Median expansion time over `reps` runs, and the emitted code's size.
pub fn expand(tokens: &TokenStream, reps: usize) -> (Duration, usize) {
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
