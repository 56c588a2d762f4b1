//! Prints the code `lagrangian!` generates for the N-link chain of
//! `lagrange-studies/benches/peers/chain_codegen_c.py`, for that script to count its
//! operations: the items pretty-printed, then the engine's own operation
//! counts and its derive + emit time.
//!
//! ```sh
//! cargo run --release -p lagrange-engine --example peers_chain -- 10
//! ```

use std::time::Instant;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .expect("usage: peers_chain N");
    // The model of lagrange-studies/examples/scaling (indexed form) and of
    // the script, with its generated `M` and `f` (from 18 coordinates the
    // chain would otherwise have them formed from its links' parts).
    let source = format!(
        "#[lagrange(articulated = false)]
pub struct Chain {{
    const N = {n};
    coordinates: theta[N];
    parameters: m[N], l[N];
    constants: g = 9.81;
    let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
    let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
    kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
    potential: sum(i in 0..N, m[i]*g*y[i]);
}}"
    );
    let tokens: proc_macro2::TokenStream = source.parse().expect("the chain lexes");
    let start = Instant::now();
    let derived = lagrange_engine::derive(tokens).expect("the chain derives");
    let items = derived.tokens();
    let seconds = start.elapsed().as_secs_f64();
    let file: syn::File = syn::parse2(items).expect("the generated items parse");
    println!("{}", prettyplease::unparse(&file));
    let pool = &derived.model.pool;
    let mass: Vec<_> = (0..n)
        .flat_map(|i| (i..n).map(move |j| (i, j)))
        .map(|(i, j)| derived.equations.mass[i][j])
        .collect();
    let m = lagrange_engine::expr::cse::shared_ops(pool, &mass).total();
    let f = lagrange_engine::expr::cse::shared_ops(pool, &derived.equations.forcing).total();
    let (shared, _) = derived.op_counts();
    println!("// engine_shared_ops {m} {f} {}", shared.total());
    println!("// derive_emit_s {seconds:.6}");
}
