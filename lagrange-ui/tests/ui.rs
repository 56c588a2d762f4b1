//! Every mistake `lagrangian!` catches at compile time gives exactly one
//! error, on the user's tokens, saying the problem in physics terms: each
//! case of `tests/ui/` (one file per mistake) compiled by rustc through
//! trybuild against the `.stderr` beside it. Here rather than in the
//! facade so that trybuild's scratch project builds only `lagrange` and
//! this crate's dependencies (about 40 s from a fresh target on 2 cores),
//! not the facade's dev-dependencies.
//!
//! `lagrange-engine/tests/engine/ui_messages.rs` checks the same messages and
//! spans without rustc, in a second, from the engine alone, in every
//! `cargo test`. This run through rustc (about 35 s more: trybuild builds
//! its own copy of `lagrange`) is left to CI: this crate is not a default
//! member of the workspace, and CI runs it over the default members'
//! features, `cargo test --workspace --exclude lagrange-studies --test ui`.

#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*.rs");
}
