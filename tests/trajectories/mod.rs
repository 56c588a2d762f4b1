//! Trajectories of derived models: every integrator's order, tolerance and
//! energy behaviour, and the 25-digit references of `tests/data/`.

mod articulated;
mod bicycle;
mod constrained;
mod contact;
mod ensemble;
mod events;
mod fingerprints;
mod heavy_top;
mod identification;
mod integrator_suite;
mod reference_trajectories;
mod rigid_body;
mod rolling;
mod sensitivities;
