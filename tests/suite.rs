//! The facade's tests, one binary (one link, and the models and methods
//! they share compiled once): `extremes` (numerical stability at the
//! extremes, STABILITY.md's scenarios), `models` (what `lagrangian!`
//! generates), `trajectories` (every integrator on derived models, the
//! 25-digit references, the fingerprints), `docs` (the figures quoted in
//! several files agree with their source). `cargo test --test suite --
//! extremes::kepler::` runs one group.

mod support;

mod docs;
mod extremes;
mod models;
mod trajectories;
