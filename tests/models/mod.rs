//! What `lagrangian!` generates: the derived equations of textbook models
//! against closed forms, the indexed language, the derivatives beyond `M`
//! and `f`, the README's generated code. (The compile errors are the
//! macro crate's UI tests, `lagrange-ui/tests/ui.rs`.)

mod constrained_models;
mod generated_derivatives;
mod indexed_models;
mod inputs;
mod latex;
mod layers;
mod linearization;
mod more_models;
mod named_lets;
mod physics_names;
mod readme;
mod textbook_models;
mod trigonometry;
mod vectors;
