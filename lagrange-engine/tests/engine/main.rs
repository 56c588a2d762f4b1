//! The engine's tests, one binary (one link, the dev-dependencies compiled
//! once): the engine outside rustc, from tokens to items.
//!
//! `cargo test -p lagrange-engine --test engine -- golden::` runs one group.

mod articulated;
mod codegen;
mod constraints;
mod golden;
mod hardening;
mod inputs;
mod kernel;
mod parameters;
mod parsing;
mod problems;
mod readme;
mod tables;
mod ui_messages;
mod urdf;
