//! A fixed-step method in a stepper: each call's interval cut into the
//! fewest equal steps no longer than `h`, as the fixed-step driver cuts the
//! intervals between sample times ([`Interval`]).

use nalgebra::{RealField, SVector};

use super::sealed::{Run, Work};
use crate::driver::{advances, finite_state, GrowthGuard, Interval, Recorder, Segment};
use crate::error::{IntegrationError, NonFiniteValue};
use crate::model::Lagrangian;
use crate::trajectory::State;

/// One step of a fixed-step method, as `driver::fixed_step` takes it.
pub(crate) trait FixedStep<S: RealField + Copy, const N: usize> {
    /// One step of size `h` from `(t, q, q̇)`, evaluating through `rec`.
    fn step<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        t: S,
        state: (&SVector<S, N>, &SVector<S, N>),
        h: S,
    ) -> Result<State<S, N>, IntegrationError<S, N>>;

    /// Forgets what the previous step carries into the next (an implicit
    /// method's starting guess), after the state or the model changed.
    fn restart(&mut self) {}
}

/// A fixed-step method's side of a stepper: its step, `h`, the step budget
/// of one call, and the growth guard of the whole run.
pub struct FixedWork<S, F> {
    pub(super) step: F,
    pub(super) h: S,
    pub(super) max_steps: usize,
    /// Built at the first call, from the state then.
    pub(super) growth: Option<GrowthGuard<S>>,
}

impl<S, F, const N: usize> Work<S, N> for FixedWork<S, F>
where
    S: RealField + Copy,
    F: FixedStep<S, N>,
{
    fn advance<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        run: &mut Run<'_, S, N>,
        model: &L,
        target: S,
    ) -> Result<(), IntegrationError<S, N>> {
        // Events closer than a few steps are beyond a fixed step (the Zeno
        // guard's default separation).
        run.rec.resolve_events(self.h);
        // One pass per stretch between resets: after a reset the rest of
        // the call is cut again from the event time.
        while run.t < target {
            let (t, (q, qdot)) = (run.t, run.state());
            let interval = Interval::new(t, target, run.rec.bound_step(self.h));
            if interval.underflows() {
                let h = interval.step;
                return Err(IntegrationError::StepSizeUnderflow { t, h, q, qdot });
            }
            let max_steps = self.max_steps;
            let Some(steps) = interval.steps(max_steps) else {
                return Err(IntegrationError::TooManySteps {
                    t,
                    max_steps,
                    q,
                    qdot,
                });
            };
            let growth = self
                .growth
                .get_or_insert_with(|| GrowthGuard::new(&q, &qdot));
            if run.stale {
                self.step.restart();
                run.stale = false;
            }
            for k in 1..=steps {
                let (t, before) = (run.t, run.state());
                let t_next = interval.time(k, steps);
                let dt = t_next - t;
                let (q, qdot) = self
                    .step
                    .step(&mut run.rec, model, t, (&before.0, &before.1), dt)
                    .and_then(|(q, qdot)| run.rec.control_drift(model, t_next, q, qdot))?;
                // The step's end is not evaluated by the model: check it
                // before it becomes the state.
                if !finite_state(&q, &qdot) {
                    let value = NonFiniteValue::State;
                    return Err(IntegrationError::NonFiniteState {
                        t: t_next,
                        q,
                        qdot,
                        value,
                    });
                }
                if let Some(steps) = growth.unstable(before, (&q, &qdot), dt) {
                    let h = interval.step;
                    let t = t_next;
                    return Err(IntegrationError::Unstable {
                        t,
                        h,
                        steps,
                        q,
                        qdot,
                    });
                }
                run.rec.stats.steps_accepted += 1;
                let crossed = if run.rec.watching() {
                    run.rec
                        .watch_hermite(model, (t, &before), (t_next, &(q, qdot)))?
                } else {
                    None
                };
                let restarted = matches!(crossed, Some(Segment::Restart { .. }));
                if run.take((t_next, q, qdot), crossed)? {
                    return Ok(());
                }
                if restarted {
                    // A reset a few ulps before the target: too close to
                    // step to, the call ends there with the state after it.
                    if !advances(run.t, target - run.t) {
                        run.t = target;
                    }
                    break;
                }
            }
        }
        Ok(())
    }
}
