//! The examples (`examples/`) and benchmarks (`benches/`) of lagrange,
//! in a crate of their own so that the heavy dependencies they need stay
//! out of the library's tests. Nothing to import: run them.
//!
//! ```text
//! cargo run --release -p lagrange-studies --example four_bar
//! cargo bench -p lagrange-studies --bench frame
//! ```
