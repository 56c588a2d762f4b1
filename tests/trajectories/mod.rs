//! Trajectories of derived models: every integrator's order, tolerance and
//! energy behaviour, and the 25-digit references of `tests/data/`.

#[path = "../support/mod.rs"]
mod support;

mod constrained;
mod ensemble;
mod events;
#[cfg(feature = "csv")]
mod export;
mod fingerprints;
mod integrator_suite;
#[cfg(any(feature = "ode_solvers", feature = "diffsol"))]
mod interop;
mod reference_trajectories;
