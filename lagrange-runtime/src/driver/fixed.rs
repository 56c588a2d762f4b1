//! The fixed-step driver: how every fixed-step method lands on the sample
//! times, counts its steps against the budget and is watched for growth,
//! so that the methods only differ in their step.

use nalgebra::{RealField, SVector};

use super::growth::GrowthGuard;
use super::record::{finite_state, Recorder};
use super::segments::{segments, Segment};
use super::validate::{check_step_size, invalid};
use crate::error::{IntegrationError, IntegrationResult, NonFiniteValue};
use crate::events::Events;
use crate::model::Lagrangian;
use crate::trajectory::State;

/// The loop every fixed-step method shares, so that they all land on the
/// sample times the same way and only differ in `step`.
///
/// Sample times are hit exactly, not interpolated: each interval between
/// consecutive sample times is cut into the fewest equal steps no longer than
/// `h` ([`Interval`]). `step(rec, model, t, q, q̇, h)` advances one step,
/// evaluating the model through `rec` so that its work is counted; its error
/// ends the integration with the samples so far. Every step counts against
/// `max_steps`. A constrained model's state is brought back onto its
/// constraints after each step ([`Recorder::control_drift`]). After a reset
/// by an event the loop starts again from the event ([`segments`]).
#[allow(clippy::too_many_arguments)]
pub(crate) fn fixed_step<S, L, const N: usize, F>(
    model: &L,
    h: S,
    max_steps: usize,
    t0: S,
    q0: SVector<S, N>,
    qdot0: SVector<S, N>,
    times: &[S],
    events: &Events<'_, S, N>,
    mut step: F,
) -> IntegrationResult<S, N>
where
    S: RealField + Copy,
    L: Lagrangian<N, Scalar = S>,
    F: FnMut(
        &mut Recorder<'_, S, N>,
        &L,
        S,
        &SVector<S, N>,
        &SVector<S, N>,
        S,
    ) -> Result<State<S, N>, IntegrationError<S, N>>,
{
    check_step_size(h).map_err(invalid)?;
    segments(model, t0, q0, qdot0, times, events, |rec, t, state| {
        fixed_segment(rec, model, (h, max_steps), (t, state), &mut step)
    })
}

/// One segment of [`fixed_step`]: from `(t0, q0, q̇0)` to the last sample
/// time, or to an event that stops the run or resets its state. A method
/// whose step keeps a workspace (the implicit Runge–Kutta methods) makes a
/// fresh one per segment, so nothing of the motion before a reset carries
/// over.
pub(crate) fn fixed_segment<S, L, const N: usize, F>(
    rec: &mut Recorder<'_, S, N>,
    model: &L,
    (h, max_steps): (S, usize),
    (t0, (q0, qdot0)): (S, State<S, N>),
    step: &mut F,
) -> Result<Segment<S, N>, IntegrationError<S, N>>
where
    S: RealField + Copy,
    L: Lagrangian<N, Scalar = S>,
    F: FnMut(
        &mut Recorder<'_, S, N>,
        &L,
        S,
        &SVector<S, N>,
        &SVector<S, N>,
        S,
    ) -> Result<State<S, N>, IntegrationError<S, N>>,
{
    let h = rec.bound_step(h);
    rec.resolve_events(h);
    let (mut t, mut q, mut qdot) = (t0, q0, qdot0);
    let mut growth = GrowthGuard::new(&q0, &qdot0);

    while let Some(target) = rec.pending() {
        let interval = Interval::new(t, target, h);
        if interval.underflows() {
            let h = interval.step;
            return Err(IntegrationError::StepSizeUnderflow { t, h, q, qdot });
        }
        let Some(steps) = interval.steps(max_steps) else {
            return Err(IntegrationError::TooManySteps {
                t,
                max_steps,
                q,
                qdot,
            });
        };
        for k in 1..=steps {
            if rec.stats.steps_accepted >= max_steps {
                return Err(IntegrationError::TooManySteps {
                    t,
                    max_steps,
                    q,
                    qdot,
                });
            }
            let t_next = interval.time(k, steps);
            let (before, dt) = ((q, qdot), t_next - t);
            (q, qdot) = step(rec, model, t, &q, &qdot, dt)
                .and_then(|(q, qdot)| rec.control_drift(model, t_next, q, qdot))?;
            let t_before = t;
            t = t_next;
            rec.stats.steps_accepted += 1;
            if let Some(steps) = growth.unstable(before, (&q, &qdot), dt) {
                return Err(IntegrationError::Unstable {
                    t,
                    h: interval.step,
                    steps,
                    q,
                    qdot,
                });
            }
            if let Some(end) = rec.watch_hermite(model, (t_before, &before), (t, &(q, qdot)))? {
                return Ok(end);
            }
        }
        // The last step's state is not evaluated by the model, so check it
        // here rather than record a NaN.
        if !finite_state(&q, &qdot) {
            let value = NonFiniteValue::State;
            return Err(IntegrationError::NonFiniteState { t, q, qdot, value });
        }
        while rec.pending() == Some(target) {
            rec.record(target, q, qdot);
        }
    }
    Ok(Segment::Done)
}

/// The interval from `start` to the next sample time `target`, cut into
/// equal steps of length `step`, no longer than the `h` asked for (see
/// [`steps_to_cover`]). Never longer: an interval that would need more
/// steps than the budget allows is refused whole ([`Interval::steps`]), not
/// covered in fewer, longer steps.
pub(crate) struct Interval<S> {
    start: S,
    target: S,
    /// The number of steps, at least 1; infinite if `span / h` overflows.
    count: S,
    /// Their length, `(target − start) / count`: `h` itself, to rounding,
    /// when `count` is infinite.
    pub(crate) step: S,
}

impl<S: RealField + Copy> Interval<S> {
    pub(crate) fn new(start: S, target: S, h: S) -> Self {
        let count = steps_to_cover(start, target, h);
        let step = if count.is_finite() {
            (target - start) / count
        } else {
            h
        };
        Self {
            start,
            target,
            count,
            step,
        }
    }

    /// Whether the step is too small to move `t` at all.
    pub(crate) fn underflows(&self) -> bool {
        self.start + self.step == self.start
    }

    /// The number of steps, if the whole budget `max_steps` could cover it.
    /// `None` means the interval alone needs more steps than the budget:
    /// the run must stop with
    /// [`TooManySteps`](crate::error::IntegrationError::TooManySteps) before its
    /// first step, rather than spend the budget on a run that cannot reach
    /// the sample (or, as a saturating count would, stretch the step).
    pub(crate) fn steps(&self, max_steps: usize) -> Option<usize> {
        let budget = nalgebra::convert::<f64, S>(max_steps as f64);
        if self.count <= budget {
            let count: f64 = nalgebra::try_convert(self.count)?;
            Some((count as usize).min(max_steps))
        } else {
            None
        }
    }

    /// The time at the end of step `k` of `steps`, from the interval start,
    /// so rounding does not accumulate in `t` and the last step lands on the
    /// target.
    pub(crate) fn time(&self, k: usize, steps: usize) -> S {
        if k == steps {
            self.target
        } else {
            self.start + self.step * nalgebra::convert::<f64, S>(k as f64)
        }
    }
}

/// The fewest equal steps no longer than `h` that cover `[start, target]`,
/// forgiving the rounding of the sample times themselves: a span of exactly
/// `10 h` in decimal takes 10 steps, not 11, and samples `i h` apart by one
/// step still take one step each late in a run, where `i h` carries rounding
/// of a few ulps of `t` (at `t = 100`, ~1e-14 — far more than an ulp of `h`).
/// A step may so exceed `h` by `8 ε (|t| + span)`, which no method notices,
/// and never by more than `h / 8`: where `h` is within a few ulps of `t`
/// (`t = 1e20`, `h = 1`), forgiving 8 ulps would merge all the steps into
/// one giant one, where the callers should see that `h` no longer advances
/// `t`. A whole number in `S`, at least 1; `+∞` when `span / h` overflows.
fn steps_to_cover<S: RealField + Copy>(start: S, target: S, h: S) -> S {
    let span = target - start;
    let eight_ulps = nalgebra::convert::<f64, S>(8.0) * S::default_epsilon();
    let forgiven = (eight_ulps * (span + start.abs().max(target.abs())))
        .min(h / nalgebra::convert::<f64, S>(8.0));
    // A span of zero never reaches here; a span below what is forgiven
    // still takes one step.
    ((span - forgiven) / h).ceil().max(S::one())
}
