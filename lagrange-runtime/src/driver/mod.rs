//! What every method shares, apart from the methods themselves: the driver
//! that turns one step into a trajectory.
//!
//! - `record`: the [`Recorder`] that keeps the samples a run has passed and
//!   counts its work, so a success and a failure hand back the same
//!   trajectory;
//! - `validate`: the checks before the first step (finite start, state,
//!   parameters and sample times; step sizes and tolerances);
//! - `fixed`: the fixed-step loop, which cuts each interval between sample
//!   times into equal steps no longer than `h`;
//! - `growth`: the guard that stops a fixed-step run beyond its stability
//!   limit before the state overflows;
//! - `adaptive`: the step loop of the explicit embedded pairs;
//! - `step_control`: the adaptive methods' default tolerance, initial step
//!   guess and underflow check;
//! - `newton`: the noise floor of the implicit methods' Newton iterations;
//! - `segments`: a run as segments between the events that reset or stop
//!   it, each one a method's loop;
//! - `events`: the hook the loops call after every accepted step, where
//!   events are located on the step's interpolant and acted on.

mod adaptive;
mod events;
mod fixed;
mod growth;
mod newton;
mod record;
mod segments;
mod step_control;
mod validate;

pub(crate) use adaptive::{adaptive, Controller, EmbeddedPair, Outcome, Tolerances};
pub(crate) use fixed::{fixed_segment, fixed_step, Interval};
pub(crate) use growth::GrowthGuard;
pub(crate) use newton::newton_noise_floor;
pub(crate) use record::{finite_state, Recorder};
pub(crate) use segments::{segments, Segment};
pub(crate) use step_control::{advances, default_tolerance, initial_step};
pub(crate) use validate::{check_step_size, check_tolerances, invalid};
