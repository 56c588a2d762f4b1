//! A run as segments between events: every method integrates from a start
//! until its last sample or until an event stops it or resets its state;
//! after a reset it starts again, from the event time and the new state,
//! with the same recorder (so samples, events and work accumulate).
//!
//! Without events there is one segment, the whole run, and nothing else
//! changes: the methods' loops are the segments.

use nalgebra::{RealField, SVector};

use super::record::Recorder;
use super::step_control::advances;
use super::validate::invalid;
use crate::error::{IntegrationError, IntegrationResult};
use crate::events::Events;
use crate::model::Lagrangian;
use crate::trajectory::State;

/// How a segment ended, short of an error.
pub(crate) enum Segment<S, const N: usize> {
    /// At the last sample time, or at an event that stops the run.
    Done,
    /// At an event that reset the state: restart from `(t, state)`.
    Restart { t: S, state: State<S, N> },
}

/// Validates the events' settings and the call, starts the recorder, then
/// runs `segment(rec, t, (q, q̇))` from the start and from every reset.
///
/// After a reset at `t*`, a sample time too close to step to from `t*`
/// (`t_s − t*` at most `10 ε |t*|`, see `advances`) takes the state after
/// the reset. An [`InvalidInput`](crate::error::InvalidInput) met before the first
/// step (a model that lacks what the method needs) is reported with an
/// empty trajectory, as every invalid input is.
#[allow(clippy::type_complexity)]
pub(crate) fn segments<'a, S, L, const N: usize>(
    model: &L,
    t0: S,
    q0: SVector<S, N>,
    qdot0: SVector<S, N>,
    times: &'a [S],
    events: &'a Events<'a, S, N>,
    mut segment: impl FnMut(
        &mut Recorder<'a, S, N>,
        S,
        State<S, N>,
    ) -> Result<Segment<S, N>, IntegrationError<S, N>>,
) -> IntegrationResult<S, N>
where
    S: RealField + Copy,
    L: Lagrangian<N, Scalar = S>,
{
    events.validate().map_err(invalid)?;
    let (mut rec, mut state) = Recorder::start(model, t0, &q0, &qdot0, times)?;
    rec.watch_events(events);
    let (mut t, mut first) = (t0, true);
    loop {
        let ended = rec
            .arm_events(t, &state)
            .and_then(|()| segment(&mut rec, t, state));
        match ended {
            Ok(Segment::Done) => return Ok(rec.finish()),
            Ok(Segment::Restart {
                t: at,
                state: after,
            }) => {
                (t, state, first) = (at, after, false);
                while let Some(ts) = rec.pending().filter(|&ts| !advances(t, ts - t)) {
                    rec.record(ts, state.0, state.1);
                }
            }
            Err(IntegrationError::InvalidInput(error))
                if first && rec.stats.steps_accepted == 0 =>
            {
                return Err(invalid(error));
            }
            Err(error) => return Err(rec.fail(error)),
        }
    }
}
