//! The compile errors of `lagrangian!` through rustc: `tests/ui/` holds
//! one case per mistake and the `.stderr` rustc prints for it, and
//! `tests/ui.rs` compiles them with trybuild (ignored by `cargo test`;
//! CI runs it: `cargo test --test ui -- --ignored`). Nothing is exported.
