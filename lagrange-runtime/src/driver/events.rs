//! The hook every driver calls after an accepted step: the events'
//! values at its end, and, where one changed sign, the crossing located on
//! the step's interpolant and acted on (see [`events`](crate::events)).
//!
//! Nothing here runs for a run without events: each entry point returns at
//! once, so such runs take the same steps, evaluations and samples as
//! before events existed.

use nalgebra::RealField;

use super::record::{Evaluate, Recorder, finite_state};
use super::run::Segment;
use crate::error::{IntegrationError, NonFiniteValue};
use crate::events::{Events, Hermite, RunData, Watch, evaluate_into, first_crossing};
use crate::trajectory::EventRecord;
use crate::trajectory::State;

impl<'a, S: RealField + Copy, const N: usize> Recorder<'a, S, N> {
    /// Watches `events` from now on (nothing to watch if there are none).
    pub(crate) fn watch_events(&mut self, events: &'a Events<'a, S, N>) {
        if !events.is_empty() || events.has_observer() {
            self.watch = Some(Watch::new(events));
        }
    }

    /// A [`Stepper`](crate::stepper::Stepper)'s start of a call: the events of the
    /// previous call forgotten (their room kept).
    pub(crate) fn forget_events(&mut self) {
        self.trajectory.clear_events();
    }

    /// The events of the current call (a stepper's), and the one that
    /// stopped it, if any.
    pub(crate) fn events_so_far(&self) -> (&[EventRecord<S, N>], Option<&EventRecord<S, N>>) {
        (self.trajectory.events(), self.trajectory.stopped())
    }

    /// Whether the observer stopped the current call (a stepper's).
    pub(crate) fn interrupted(&self) -> bool {
        self.trajectory.interrupted().is_some()
    }

    /// Hands the watch over to a new recorder (a stepper's, restarted by
    /// `set_state`).
    pub(crate) fn take_watch(&mut self) -> Option<Watch<'a, S, N>> {
        self.watch.take()
    }

    pub(crate) fn put_watch(&mut self, watch: Option<Watch<'a, S, N>>) {
        self.watch = watch;
    }

    /// The run's data, which the events keep (`()` where they keep none,
    /// or no events are watched).
    pub(crate) fn data(&self) -> &RunData {
        match &self.watch {
            Some(watch) => &*watch.data,
            None => &(),
        }
    }

    /// Whether a reset changed the run's data since the model was last
    /// built from it.
    pub(crate) fn data_changed(&self) -> bool {
        self.watch.as_ref().is_some_and(|watch| watch.changed)
    }

    /// The run's data, taken at its end (`()` in its place).
    pub(crate) fn take_data(&mut self) -> Box<RunData> {
        match &mut self.watch {
            Some(watch) => core::mem::replace(&mut watch.data, Box::new(())),
            None => Box::new(()),
        }
    }

    /// [`data_changed`](Self::data_changed), and it is built anew now.
    pub(crate) fn take_changed(&mut self) -> bool {
        self.watch
            .as_mut()
            .is_some_and(|watch| core::mem::take(&mut watch.changed))
    }

    /// Whether events are watched: the drivers do the extra work events
    /// need (the interpolant of every step) only then.
    pub(crate) fn watching(&self) -> bool {
        self.watch.is_some()
    }

    /// A fixed-step method's step `h`: events closer than a few steps are
    /// beyond it (the Zeno guard's default separation).
    pub(crate) fn resolve_events(&mut self, h: S) {
        if let Some(watch) = &mut self.watch {
            watch.resolution = h;
        }
    }

    /// The step `h`, bounded by the events' [`max_step`](Events::max_step).
    pub(crate) fn bound_step(&self, h: S) -> S {
        match self.watch.as_ref().and_then(|w| w.events.max_step_bound()) {
            Some(max_step) => h.min(max_step),
            None => h,
        }
    }

    /// The events' values at a segment's start.
    pub(crate) fn arm_events(
        &mut self,
        t: S,
        state: &State<S, N>,
    ) -> Result<(), IntegrationError<S, N>> {
        match &mut self.watch {
            Some(watch) => watch.start(t, state, &mut self.stats.event_evals),
            None => Ok(()),
        }
    }

    /// After an accepted step from `t` to `t_new` ending in `end`, with the
    /// method's dense output `interpolant`: `Some` when an event ended the
    /// segment (the samples up to it recorded from `interpolant`).
    ///
    /// The model and the interpolant are taken behind `dyn`: this code, and
    /// the location under it, is compiled once per scalar and size, not once
    /// per model, method and interpolant (it was a fifth of the LLVM IR of
    /// the runtime's test binary).
    pub(crate) fn watch_dense(
        &mut self,
        model: &dyn Evaluate<S, N>,
        (t, t_new): (S, S),
        end: &State<S, N>,
        interpolant: &mut dyn FnMut(S) -> State<S, N>,
    ) -> Result<Option<Segment<S, N>>, IntegrationError<S, N>> {
        if let Some(g_end) = self.crossed_at_end(t_new, end)? {
            if let Some(ended) = self.act(model, (t, t_new), end, g_end, interpolant)? {
                return Ok(Some(ended));
            }
        }
        self.observe(model, t_new, end, interpolant)
    }

    /// [`watch_dense`](Self::watch_dense) for a method without dense
    /// output: the cubic Hermite interpolant of the step from `start` to
    /// `end`. Its slopes need `q̈` at both ends: the end's is evaluated (one
    /// right-hand side per step while events are watched) and kept as the
    /// next step's start, whose own is evaluated only after the state was
    /// changed in between (a reset, a projection, a new segment).
    pub(crate) fn watch_hermite(
        &mut self,
        model: &dyn Evaluate<S, N>,
        (t, start): (S, &State<S, N>),
        (t_new, end): (S, &State<S, N>),
    ) -> Result<Option<Segment<S, N>>, IntegrationError<S, N>> {
        if let Some(g_end) = self.crossed_at_end(t_new, end)? {
            let carried = self.watch.as_mut().and_then(|w| w.slope.take());
            let qddot0 = match carried {
                Some((at, state, qddot)) if at == t && state == *start => qddot,
                _ => self.rhs(model, t, &start.0, &start.1)?,
            };
            let qddot1 = self.rhs(model, t_new, &end.0, &end.1)?;
            if let Some(watch) = &mut self.watch {
                watch.slope = Some((t_new, *end, qddot1));
            }
            let hermite = Hermite::new((t, *start, qddot0), (t_new, *end, qddot1));
            let mut interpolant = |s| hermite.at(s);
            if let Some(ended) = self.act(model, (t, t_new), end, g_end, &mut interpolant)? {
                return Ok(Some(ended));
            }
        }
        // A fixed step ends on every sample time: no sample lies strictly
        // inside it for the observer's stop to interpolate.
        self.observe(model, t_new, end, &mut |_| *end)
    }

    /// The observer, if any, at an accepted step's end `(t_new, end)`: when
    /// it asks to stop, the samples up to `t_new` are recorded (from
    /// `interpolant` inside the step) and the run ends there.
    fn observe(
        &mut self,
        model: &dyn Evaluate<S, N>,
        t_new: S,
        end: &State<S, N>,
        interpolant: &mut dyn FnMut(S) -> State<S, N>,
    ) -> Result<Option<Segment<S, N>>, IntegrationError<S, N>> {
        let Some(watch) = &self.watch else {
            return Ok(None);
        };
        if !watch.events.observe_stop(t_new, end) {
            return Ok(None);
        }
        while let Some(ts) = self.pending().filter(|&ts| ts <= t_new) {
            if ts < t_new {
                let (q, qdot) = interpolant(ts);
                self.record_dense(model, ts, q, qdot)?;
            } else {
                self.record(ts, end.0, end.1);
            }
        }
        self.trajectory.interrupt(t_new);
        Ok(Some(Segment::Done))
    }

    /// The events' values at a step's end, when the step must be searched
    /// for a crossing: always while there are events, since `g` may cross
    /// zero and come back within the step (found from its rate along the
    /// interpolant, see `first_crossing`). `None` without events.
    fn crossed_at_end(
        &mut self,
        t_new: S,
        end: &State<S, N>,
    ) -> Result<Option<Vec<S>>, IntegrationError<S, N>> {
        let Some(watch) = &mut self.watch else {
            return Ok(None);
        };
        if watch.events.is_empty() {
            return Ok(None);
        }
        let (q, qdot) = *end;
        if !finite_state(&q, &qdot) {
            let value = NonFiniteValue::State;
            return Err(IntegrationError::NonFiniteState {
                t: t_new,
                q,
                qdot,
                value,
            });
        }
        let mut g = core::mem::take(&mut watch.scratch);
        evaluate_into(
            (watch.events, &*watch.data),
            t_new,
            end,
            &mut g,
            &mut self.stats.event_evals,
        )?;
        Ok(Some(g))
    }

    fn act(
        &mut self,
        model: &dyn Evaluate<S, N>,
        step: (S, S),
        end: &State<S, N>,
        g_end: Vec<S>,
        interpolant: &mut dyn FnMut(S) -> State<S, N>,
    ) -> Result<Option<Segment<S, N>>, IntegrationError<S, N>> {
        let Some(mut watch) = self.watch.take() else {
            return Ok(None);
        };
        let acted = self.act_on(&mut watch, model, step, end, g_end, interpolant);
        self.watch = Some(watch);
        acted
    }

    /// Every crossing on the step in turn: recorded ones in passing, until
    /// one that stops or resets ends the segment.
    fn act_on(
        &mut self,
        watch: &mut Watch<'a, S, N>,
        model: &dyn Evaluate<S, N>,
        (t, t_new): (S, S),
        end: &State<S, N>,
        g_end: Vec<S>,
        interpolant: &mut dyn FnMut(S) -> State<S, N>,
    ) -> Result<Option<Segment<S, N>>, IntegrationError<S, N>> {
        let events = watch.events;
        let list = events.list();
        // The interpolant at the step's end is the end state itself, which
        // `g_end` was computed from.
        let mut state_at = |s: S| if s == t_new { *end } else { interpolant(s) };
        let (mut from, mut g_from) = (t, core::mem::take(&mut watch.g));
        loop {
            let tolerance = events.tolerance_at(t_new);
            let evaluations = &mut self.stats.event_evals;
            let start = (from, g_from.as_slice());
            let found = first_crossing(
                (events, &*watch.data),
                start,
                (t_new, &g_end),
                tolerance,
                &mut state_at,
                evaluations,
            )?;
            let Some(crossing) = found else {
                // The values become the next step's start; the old ones'
                // room the next step's scratch.
                watch.g = g_end;
                watch.scratch = g_from;
                return Ok(None);
            };
            let at = crossing.t;
            let interrupts = crossing.events.iter().any(|&i| !list[i].records_only());
            if interrupts {
                while let Some(ts) = self.pending().filter(|&ts| ts <= at) {
                    let (q, qdot) = state_at(ts);
                    self.record_dense(model, ts, q, qdot)?;
                }
            }
            let (q, qdot) = crossing.state;
            let (q, qdot) = self.project_sample(model, at, q, qdot)?;
            let min_separation = events.separation_at(at, watch.resolution);
            if let Some(run) = watch.guard.check(at, min_separation) {
                return Err(IntegrationError::Zeno {
                    t: at,
                    gaps: run.gaps,
                    gap: run.gap,
                    min_separation,
                    q,
                    qdot,
                });
            }
            let record = |index: usize, after| EventRecord {
                name: list[index].name(),
                index,
                t: at,
                q,
                qdot,
                after,
            };
            if crossing.events.iter().any(|&i| list[i].stops()) {
                for &i in &crossing.events {
                    self.trajectory.push_event(record(i, None), list[i].stops());
                }
                return Ok(Some(Segment::Done));
            }
            if interrupts {
                let mut state = (q, qdot);
                for &i in &crossing.events {
                    let Some(reset) = list[i].apply_reset(&mut *watch.data, at, &state) else {
                        continue;
                    };
                    watch.changed |= list[i].changes_data();
                    let (q, qdot) = reset.map_err(|reason| IntegrationError::ResetFailed {
                        event: list[i].name(),
                        t: at,
                        q: state.0,
                        qdot: state.1,
                        reason: Box::new(reason),
                    })?;
                    if !finite_state(&q, &qdot) {
                        let (event, value) = (list[i].name(), NonFiniteValue::EventReset);
                        return Err(IntegrationError::NonFiniteEvent {
                            event,
                            t: at,
                            q,
                            qdot,
                            value,
                        });
                    }
                    state = self.project_sample(model, at, q, qdot)?;
                }
                for &i in &crossing.events {
                    let after = (!list[i].records_only()).then_some(state);
                    self.trajectory.push_event(record(i, after), false);
                }
                return Ok(Some(Segment::Restart { t: at, state }));
            }
            for &i in &crossing.events {
                self.trajectory.push_event(record(i, None), false);
            }
            (from, g_from) = (at, crossing.g);
        }
    }
}
