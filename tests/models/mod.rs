//! What `lagrangian!` generates: the derived equations of textbook models
//! against closed forms, the indexed language, the derivatives beyond `M`
//! and `f`, the README's generated code, and the compile errors of
//! `tests/ui` (one per mistake).

#[path = "../support/mod.rs"]
mod support;

mod compile_errors;
mod constrained_models;
mod generated_derivatives;
mod indexed_models;
mod inputs;
mod latex;
mod layers;
mod linearization;
mod more_models;
mod named_lets;
mod readme;
mod textbook_models;
mod trigonometry;
