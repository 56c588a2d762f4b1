//! Getting results out of Rust: a trajectory as CSV (feature `csv`).
//!
//! Column names come from the model: `t`, then its coordinates as written
//! (`theta1`, `theta2`), their velocities (`theta1_dot`, …), the total
//! energy `energy`, for a model with constraints the multiplier of each
//! constraint by its name (`lambda_rod`, …), and for a run with events an
//! `event` column naming the event of each event row.

#[cfg(feature = "csv")]
mod csv;

#[cfg(feature = "csv")]
pub use self::csv::{CsvError, write_csv};
