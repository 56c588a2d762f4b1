//! What a run keeps of its events between steps: the events, their values
//! at the current time and the Zeno guard.

use super::guard::ZenoGuard;
use super::locate::evaluate_into;
use super::{Events, RunData};
use crate::error::IntegrationError;
use crate::trajectory::State;
use nalgebra::{RealField, SVector};

/// The state of the watch over a run's events.
pub(crate) struct Watch<'a, S, const N: usize> {
    pub(crate) events: &'a Events<'a, S, N>,
    /// Every event's `g` at the current time: the start of the next step.
    pub(crate) g: Vec<S>,
    /// Room for the values at a step's end, kept so that watching a run
    /// allocates nothing per step.
    pub(crate) scratch: Vec<S>,
    pub(crate) guard: ZenoGuard<S>,
    /// The shortest gap between events the method resolves: its fixed
    /// step, zero for an adaptive method.
    pub(crate) resolution: S,
    /// `q̈` at the end of the last step a Hermite interpolant was built
    /// for, with that time and state: the next step's slope at its start.
    pub(crate) slope: Option<(S, State<S, N>, SVector<S, N>)>,
    /// The run's data, which the events read and their resets change
    /// (`()` where they keep none): the run's own, made at its start.
    pub(crate) data: Box<RunData>,
    /// Whether a reset changed `data` since the model was last built from
    /// it.
    pub(crate) changed: bool,
}

impl<'a, S: RealField + Copy, const N: usize> Watch<'a, S, N> {
    pub(crate) fn new(events: &'a Events<'a, S, N>) -> Self {
        Self {
            events,
            g: Vec::with_capacity(events.len()),
            scratch: Vec::with_capacity(events.len()),
            guard: ZenoGuard::new(),
            resolution: S::zero(),
            slope: None,
            data: events.fresh_data(),
            changed: false,
        }
    }

    /// Arms the events at a start: their values at `(t, q, q̇)`.
    pub(crate) fn start(
        &mut self,
        t: S,
        state: &State<S, N>,
        evaluations: &mut usize,
    ) -> Result<(), IntegrationError<S, N>> {
        evaluate_into(
            (self.events, &*self.data),
            t,
            state,
            &mut self.g,
            evaluations,
        )
    }
}
