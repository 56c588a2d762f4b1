//! The runtime's integrators, one module per method or concern, on
//! hand-written models (`tests/models`) and the shared problems of
//! `lagrange::models`: `cargo test -p lagrange-runtime --test integrators --
//! radau5::` runs one module.

#[path = "../models/mod.rs"]
mod models;

mod allocations;
mod analysis;
mod clock;
mod constraints;
mod contact;
mod dop853;
mod euler_methods;
mod events;
mod failures;
mod harmonic_oscillator;
mod implicit_accuracy;
mod implicit_geometry;
mod instability;
mod newton_failures;
mod properties;
mod radau5;
mod stepper;
mod variational;
