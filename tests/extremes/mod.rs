//! Numerical stability at the extremes: the scenarios of STABILITY.md, one
//! module per group. Each test's doc comment states the expected behaviour
//! and why; the figures STABILITY.md quotes are what they print:
//!
//! ```sh
//! cargo test --release --test suite -- extremes:: --nocapture            # every group
//! cargo test --release --test suite -- extremes::kepler:: --nocapture   # one group
//! cargo test --release --test suite -- extremes:: --ignored --nocapture  # the long runs
//! ```

mod chaos;
mod f32;
mod kepler;
mod long_runs;
mod mass_ratio;
pub(crate) mod nonfinite;
mod order;
mod reversibility;
mod separatrix;
mod singularity;
mod steps;
mod stiff;
