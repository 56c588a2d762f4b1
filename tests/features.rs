//! The optional features' tests, one binary built only with all of them
//! (`required-features` in Cargo.toml), so that the plain `cargo test`
//! builds none of their dependencies: `cargo test --all-features --test
//! features` (CI runs it).
//!
//! - `export`: features `csv` and `serde`: trajectories written as CSV and
//!   read back; failures, trajectories and `#[lagrange(serde)]` models
//!   through JSON.
//! - `interop`: features `ode_solvers` and `diffsol`: the double pendulum
//!   through those crates' solvers against the 25-digit reference.

#[path = "support/mod.rs"]
mod support;

#[path = "features/export.rs"]
mod export;
#[path = "features/interop.rs"]
mod interop;
