//! What `lagrangian!` generates: the derived equations of textbook models
//! against closed forms, the indexed language, the derivatives beyond `M`
//! and `f` (by the state, and by the parameters against dual numbers).
//! (The compile errors are the UI tests, `lagrange-ui/tests/ui.rs`; the
//! README's generated code is checked by the engine's tests,
//! `lagrange-engine/tests/engine/readme.rs`.)

mod constrained_models;
mod generated_derivatives;
mod indexed_models;
mod inputs;
mod latex;
mod layers;
mod linearization;
mod more_models;
mod named_lets;
pub(crate) mod parameter_derivatives;
mod physics_names;
mod robot_frames;
mod robot_parameters;
mod robots;
mod textbook_models;
mod trigonometry;
mod vectors;
