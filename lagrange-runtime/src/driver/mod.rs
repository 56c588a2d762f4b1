//! What every method shares, apart from the methods themselves: the run
//! loops that turn steps into a trajectory or a stepper's frames.
//!
//! - `run`: a run between steps ([`Run`](run::Run)), the [`Walk`](run::Walk)
//!   each kind of method implements (one resumable loop per kind), and
//!   `integrate`, one advance through every sample time;
//! - `fixed`: the fixed-step kind, each interval between stops cut into
//!   equal steps no longer than `h`;
//! - `pair`: the embedded pairs' kind, Hairer's step-size control;
//! - `record`: the [`Recorder`] that keeps the samples a run has passed and
//!   counts its work, so a success and a failure hand back the same
//!   trajectory;
//! - `validate`: the checks before the first step (finite start, state,
//!   parameters and sample times; step sizes and tolerances);
//! - `growth`: the guard that stops a run beyond its stability limit
//!   before the state overflows;
//! - `step_control`: the adaptive methods' default tolerance, initial step
//!   guess and underflow check;
//! - `newton`: the noise floor of the implicit methods' Newton iterations;
//! - `events`: the hook the loops call after every accepted step, where
//!   events are located on the step's interpolant and acted on.
//!
//! (The implicit adaptive kind and the variational kind are their methods'
//! own: `integrators/radau5/walk.rs`, `integrators/variational/walk.rs`.)

mod events;
pub(crate) mod fixed;
mod growth;
mod newton;
pub(crate) mod pair;
mod record;
pub(crate) mod run;
mod step_control;
mod validate;

pub(crate) use fixed::Interval;
pub(crate) use growth::{GrowthGuard, measure};
pub(crate) use newton::newton_noise_floor;
pub(crate) use record::{Recorder, finite_state};
pub(crate) use step_control::{FirstStep, advances, default_tolerance};
pub(crate) use validate::{check_step_size, check_tolerances, finite_start, invalid};
