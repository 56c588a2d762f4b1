//! Trajectories of derived models: every integrator's order, tolerance and
//! energy behaviour, and the 25-digit references of `tests/data/`.

#[path = "../support/mod.rs"]
mod support;

mod constrained;
mod events;
mod integrator_suite;
mod reference_trajectories;
