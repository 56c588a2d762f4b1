//! Large trees of links through the engine (issue 50): the comb (a chain
//! of 20 links with a branch of two on every fourth, 30 coordinates), a
//! binary tree of 64 links (the complete tree of depth 6 and one more
//! link) and the 100-link chain, each found to be masses on a tree of
//! links before `M` and `f` would be derived, and solved by the recursion
//! without them. For each: the engine's expansion time outside rustc
//! (`lagrange_engine::expand`, median of 5), the work budget spent, the
//! generated code's size, of which `EQUATIONS` and `LATEX`, and the
//! estimate the limit on generated code is checked against; then the comb
//! derived whole (`articulated = false` with a raised budget), which the
//! limit refuses.
//!
//! `cargo run --release -p lagrange-studies --example large_trees`
//!
//! The models are the engine's test problems
//! (`lagrange-engine/tests/engine/problems.rs`), defined once.

#[allow(dead_code)]
#[path = "../../lagrange-engine/tests/engine/problems.rs"]
mod problems;

use std::time::{Duration, Instant};

/// The median of `runs` expansions of `source`, and the last expansion.
fn expand(source: &str, runs: usize) -> (Duration, String) {
    let mut times = Vec::with_capacity(runs);
    let mut code = String::new();
    for _ in 0..runs {
        let tokens: proc_macro2::TokenStream = source.parse().expect("the model lexes");
        let start = Instant::now();
        let expanded = lagrange_engine::expand(tokens);
        times.push(start.elapsed());
        code = expanded.to_string();
    }
    times.sort();
    (times[runs / 2], code)
}

fn main() {
    println!(
        "| model | N | expand (s) | steps | code (KB) | EQUATIONS + LATEX (KB) | estimated functions (KB) |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    for (name, source) in [
        ("comb", problems::comb("")),
        ("binary tree of 64", problems::binary_tree_64("")),
        ("chain of 100", problems::indexed_chain(100)),
    ] {
        let (time, code) = expand(&source, 5);
        assert!(!code.contains("compile_error"), "{name} did not expand");
        let derived = lagrange_engine::derive(source.parse().unwrap()).expect("derives");
        let n = derived.model.dof();
        let text = derived.equations_text().len() + derived.equations_latex().len();
        println!(
            "| {name} | {n} | {:.3} | {} | {} | {} | {} |",
            time.as_secs_f64(),
            derived.model.pool.spent(),
            code.len() / 1000,
            text / 1000,
            derived.estimated_code_bytes() / 1000,
        );
    }
    let dense = problems::comb("#[lagrange(articulated = false, budget = 100000000)]");
    let start = Instant::now();
    let refused = lagrange_engine::derive(dense.parse().unwrap());
    let time = start.elapsed();
    match refused {
        Ok(_) => println!("\nThe comb derived whole expanded: the limit did not hold."),
        Err(e) => println!(
            "\nThe comb derived whole (`articulated = false, budget = 100000000`), refused in {:.2} s:\n{e}",
            time.as_secs_f64()
        ),
    }
}
