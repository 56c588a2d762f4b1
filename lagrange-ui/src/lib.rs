//! The compile errors of `lagrangian!` through rustc: `tests/ui/` holds
//! one case per mistake and the `.stderr` rustc prints for it, and
//! `tests/ui.rs` compiles them with trybuild (this crate is not a default
//! member, so `cargo test` leaves it out; CI runs it: `cargo test
//! --workspace --exclude lagrange-studies --test ui`). Nothing is exported.
