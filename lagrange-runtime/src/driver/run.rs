//! A run, resumable: the state a method advances, its recorder, and the
//! one loop per kind of method that advances it to a time. `integrate` is
//! one such advance to the last sample time, recording the samples on the
//! way from the method's interpolant; a [`Stepper`](crate::stepper::Stepper)
//! is one advance per frame, landing on the frame's time. Both go through
//! the same loop, so a fix to it lands once.
//!
//! The kinds, each a [`Walk`]: fixed steps (`fixed.rs`: the explicit
//! methods and the Gauss collocation methods), embedded pairs (`pair.rs`:
//! Bs3, Dopri5, Tsit5, Dop853), the implicit adaptive method (Radau5,
//! `integrators/radau5/walk.rs`) and the variational step
//! (`integrators/variational/walk.rs`).

use nalgebra::{RealField, SVector};

use super::record::Recorder;
use super::step_control::advances;
use super::validate::invalid;
use crate::error::{IntegrationError, IntegrationResult};
use crate::events::{Events, RunData};
use crate::model::Lagrangian;
use crate::trajectory::State;

/// How the events of an accepted step ended the stretch of run it was in.
pub enum Segment<S, const N: usize> {
    /// At an event that stops the run, or where the observer stopped it.
    Done,
    /// At an event that reset the state: the run goes on from
    /// `(t, state)` as from a new start.
    Restart { t: S, state: State<S, N> },
}

/// What a method must build anew before its next step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fresh {
    /// Nothing: it goes on from its last step.
    No,
    /// Its slopes and its guesses (a first-same-as-last slope, a Newton
    /// starting guess): the caller changed the model or the state of a
    /// [`Stepper`](crate::stepper::Stepper). An adaptive step size is kept.
    Slopes,
    /// Everything, as at a start: the run begins, or an event reset its
    /// state. The step size is guessed again, the growth guard and the
    /// events' values start from this state.
    Segment,
}

/// The state of a run between steps.
pub struct Run<'a, S: RealField + Copy, const N: usize> {
    pub(crate) t: S,
    pub(crate) q: SVector<S, N>,
    pub(crate) qdot: SVector<S, N>,
    /// The samples (none for a stepper), the work counted, the events.
    pub(crate) rec: Recorder<'a, S, N>,
    pub(crate) fresh: Fresh,
    /// The steps accepted and rejected when the caller's call began
    /// (`integrate`'s run, a stepper's frame): the step budget is per
    /// call, however often the walker returns within it to have the model
    /// built anew.
    pub(crate) call_start: (usize, usize),
}

/// How a call to [`Walk::advance`] ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Advanced {
    /// At the target.
    Reached,
    /// Before it, at an event that stops the run or where the observer
    /// stopped it.
    Stopped,
    /// Before it, at an event whose reset changed the run's data (see
    /// `Recorder::data`): the caller builds the model anew from the data
    /// and advances again, in the same call.
    Rebuild,
}

/// What the events of a step did to the run, after [`Run::take`].
pub enum Flow {
    /// Nothing: the run is at the step's end.
    Go,
    /// The run stopped (an event, the observer).
    Stopped,
    /// An event reset the state; `true` when the target is too close to
    /// the reset to step to, which ends the call there.
    Restarted(bool),
    /// An event reset the state and the run's data, short of the target:
    /// the walker returns [`Advanced::Rebuild`].
    Rebuild,
}

/// One kind of method's loop, resumable: the method's work between steps
/// (slopes, step size, workspace) is the walker's, the state the run's.
pub trait Walk<S: RealField + Copy, const N: usize> {
    /// Advances `run` to `target` (later than `run.t`), recording the
    /// samples it passes, or to an event that stops it. On error the run
    /// holds the end of the last step that succeeded.
    fn advance<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        run: &mut Run<'_, S, N>,
        model: &L,
        target: S,
    ) -> Result<Advanced, IntegrationError<S, N>>;
}

impl<'a, S: RealField + Copy, const N: usize> Run<'a, S, N> {
    pub(crate) fn state(&self) -> State<S, N> {
        (self.q, self.qdot)
    }

    /// A call begins: its step budget counts from here.
    pub(crate) fn begin_call(&mut self) {
        self.call_start = (self.rec.stats.steps_accepted, self.rec.stats.steps_rejected);
    }

    /// The steps accepted in the current call, and those attempted
    /// (accepted or rejected): what each kind's budget counts.
    pub(crate) fn steps_this_call(&self) -> (usize, usize) {
        let (now, (accepted, rejected)) = (&self.rec.stats, self.call_start);
        let accepted = now.steps_accepted - accepted;
        let rejected = now.steps_rejected - rejected;
        (accepted, accepted + rejected)
    }

    /// A fresh start's first duty: the events' values at the state (an
    /// event already at zero is not armed).
    pub(crate) fn arm(&mut self) -> Result<(), IntegrationError<S, N>> {
        let state = self.state();
        self.rec.arm_events(self.t, &state)
    }

    /// Moves the run to the end `(t, q, q̇)` of an accepted step whose
    /// events ended as `crossed` says: to the step's end; to a stopping
    /// event's state (or the step's end where the observer stopped it); or
    /// to the state after a reset, recording the samples too close after
    /// it to step to (`t_s − t*` at most `10 ε |t*|`, see `advances`) with
    /// that state, and starting a new segment.
    #[inline]
    pub(crate) fn take(
        &mut self,
        (t, q, qdot): (S, SVector<S, N>, SVector<S, N>),
        crossed: Option<Segment<S, N>>,
        target: S,
    ) -> Flow {
        match crossed {
            None => {
                (self.t, self.q, self.qdot) = (t, q, qdot);
                Flow::Go
            }
            Some(Segment::Done) => {
                (self.t, self.q, self.qdot) = match self.rec.events_so_far().1 {
                    Some(stop) => (stop.t, stop.q, stop.qdot),
                    None => (t, q, qdot),
                };
                self.fresh = Fresh::Slopes;
                Flow::Stopped
            }
            Some(Segment::Restart { t, state }) => {
                (self.t, self.q, self.qdot) = (t, state.0, state.1);
                self.fresh = Fresh::Segment;
                while let Some(ts) = self.rec.pending().filter(|&ts| !advances(t, ts - t)) {
                    self.rec.record(ts, state.0, state.1);
                }
                let at_target = !advances(t, target - t);
                if !at_target && self.rec.data_changed() {
                    Flow::Rebuild
                } else {
                    Flow::Restarted(at_target)
                }
            }
        }
    }

    /// Records every sample due at the run's time (a fixed step lands on
    /// each).
    pub(crate) fn record_landed(&mut self) {
        while self.rec.pending() == Some(self.t) {
            self.rec.record(self.t, self.q, self.qdot);
        }
    }
}

/// `integrate` for any kind: validation and the start (a constrained
/// model's state brought onto its constraints, the samples at `t0`), then
/// one advance of `walker` to the last sample time, recording the samples
/// on the way. An [`InvalidInput`](crate::error::InvalidInput) met before
/// the first step (a model that lacks what the method needs) is reported
/// with an empty trajectory, as every invalid input is.
#[allow(clippy::too_many_arguments)]
pub(crate) fn integrate<S, L, W, const N: usize>(
    walker: W,
    model: &L,
    t0: S,
    q0: SVector<S, N>,
    qdot0: SVector<S, N>,
    times: &[S],
    events: &Events<'_, S, N>,
) -> IntegrationResult<S, N>
where
    S: RealField + Copy,
    L: Lagrangian<N, Scalar = S>,
    W: Walk<S, N>,
{
    let start = (t0, q0, qdot0);
    integrate_segments(walker, model, start, times, events, |_, _| None, None)
}

/// [`integrate`] for events that keep data (`Events::keeping`): each time
/// a reset changes it, `segment` builds the model the run goes on with
/// from the last one and the data. The run's data at its end, or where it
/// failed, is left in `keep` (if given; untouched where the run did not
/// start).
#[allow(clippy::too_many_arguments)]
pub(crate) fn integrate_segments<S, L, W, const N: usize>(
    mut walker: W,
    model: &L,
    (t0, q0, qdot0): (S, SVector<S, N>, SVector<S, N>),
    times: &[S],
    events: &Events<'_, S, N>,
    segment: impl Fn(&L, &RunData) -> Option<L>,
    keep: Option<&mut Box<RunData>>,
) -> IntegrationResult<S, N>
where
    S: RealField + Copy,
    L: Lagrangian<N, Scalar = S>,
    W: Walk<S, N>,
{
    events.validate().map_err(invalid)?;
    let (rec, (q, qdot)) = Recorder::start(model, t0, &q0, &qdot0, times)?;
    let mut run = Run {
        t: t0,
        q,
        qdot,
        call_start: (rec.stats.steps_accepted, rec.stats.steps_rejected),
        rec,
        fresh: Fresh::Segment,
    };
    run.rec.watch_events(events);
    let advanced = match run.rec.end() {
        Some(end) if run.rec.pending().is_some() => {
            let mut rebuilt: Option<L> = None;
            loop {
                let current = rebuilt.as_ref().unwrap_or(model);
                match walker.advance(&mut run, current, end) {
                    Ok(Advanced::Rebuild) => {
                        if run.rec.take_changed() {
                            rebuilt = segment(current, run.rec.data()).or(rebuilt);
                        }
                    }
                    Ok(_) => break Ok(()),
                    Err(error) => break Err(error),
                }
            }
        }
        _ => Ok(()),
    };
    if let Some(keep) = keep {
        *keep = run.rec.take_data();
    }
    match advanced {
        Ok(()) => Ok(run.rec.finish()),
        Err(IntegrationError::InvalidInput(error)) if run.rec.stats.steps_accepted == 0 => {
            Err(invalid(error))
        }
        Err(error) => Err(run.rec.fail(error)),
    }
}
