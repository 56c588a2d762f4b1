//! Times the generated `mass_matrix_and_forcing`; prints `gen_ns <ns>`.

use std::hint::black_box;

fn main() {
    let model = chain::model();
    let (q, qdot) = chain::state(0);
    let ns = chain::time_ns(|| {
        black_box(model.mass_matrix_and_forcing(black_box(0.0), black_box(&q), black_box(&qdot)));
    });
    println!("gen_ns {ns}");
}
