//! The fixed-step kind: how every fixed-step method lands on the sample
//! times (or a stepper's frame times), counts its steps against the
//! budget and is watched for growth, so that the methods only differ in
//! their step.

use nalgebra::{RealField, SVector};

use super::growth::GrowthGuard;
use super::record::{Evaluate, Recorder, finite_state};
use super::run::{Advanced, Flow, Fresh, Run, Walk};
use crate::error::{IntegrationError, NonFiniteValue};
use crate::model::Lagrangian;
use crate::trajectory::State;

/// One step of a fixed-step method.
pub trait FixedStep<S: RealField + Copy, const N: usize> {
    /// One step of size `h` from `(t, q, q̇)`, evaluating the model through
    /// `rec` so that its work is counted.
    fn step<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        t: S,
        state: (&SVector<S, N>, &SVector<S, N>),
        h: S,
    ) -> Result<State<S, N>, IntegrationError<S, N>>;

    /// Forgets what the previous step carries into the next (an implicit
    /// method's starting guess): after a reset, or a change of the model
    /// or the state.
    fn restart(&mut self) {}
}

/// The fixed-step loop, resumable, around a method's [`FixedStep`].
///
/// Sample times are hit exactly, not interpolated: each interval between
/// consecutive stops (the sample times, the target) is cut into the fewest
/// equal steps no longer than `h` ([`Interval`]). Every step counts
/// against `max_steps` (per call). A constrained model's state is brought
/// back onto its constraints after each step
/// ([`Recorder::control_drift`]).
///
/// The loop itself ([`Course::advance`]) sees the method's step and the
/// model only behind a `dyn` ([`Stepping`], [`Evaluate`]): it is compiled
/// once per scalar and size, not once per model and method. Only the
/// step, where the model is evaluated, keeps both types.
pub struct FixedWalk<S, F> {
    pub(crate) step: F,
    course: Course<S>,
}

/// The fixed-step loop's own state between calls.
struct Course<S> {
    h: S,
    max_steps: usize,
    /// `h` bounded by the events' `max_step`, for the current segment.
    bounded: S,
    growth: Option<GrowthGuard<S>>,
}

impl<S: RealField + Copy, F> FixedWalk<S, F> {
    pub(crate) fn new(step: F, h: S, max_steps: usize) -> Self {
        Self {
            step,
            course: Course {
                h,
                max_steps,
                bounded: h,
                growth: None,
            },
        }
    }
}

/// A method's step bound to the model it steps, as the loop calls it.
trait Stepping<S: RealField + Copy, const N: usize> {
    /// [`FixedStep::step`] from `t` to `t_next = t + h`, then the drift
    /// control at its end.
    fn step(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        t: S,
        state: (&SVector<S, N>, &SVector<S, N>),
        h: S,
        t_next: S,
    ) -> Result<State<S, N>, IntegrationError<S, N>>;

    /// [`FixedStep::restart`].
    fn restart(&mut self);
}

struct Bound<'a, F, L> {
    step: &'a mut F,
    model: &'a L,
}

impl<S, F, L, const N: usize> Stepping<S, N> for Bound<'_, F, L>
where
    S: RealField + Copy,
    F: FixedStep<S, N>,
    L: Lagrangian<N, Scalar = S>,
{
    fn step(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        t: S,
        state: (&SVector<S, N>, &SVector<S, N>),
        h: S,
        t_next: S,
    ) -> Result<State<S, N>, IntegrationError<S, N>> {
        self.step
            .step(rec, self.model, t, state, h)
            .and_then(|(q, qdot)| rec.control_drift(self.model, t_next, q, qdot))
    }

    fn restart(&mut self) {
        self.step.restart();
    }
}

impl<S, F, const N: usize> Walk<S, N> for FixedWalk<S, F>
where
    S: RealField + Copy,
    F: FixedStep<S, N>,
{
    fn advance<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        run: &mut Run<'_, S, N>,
        model: &L,
        target: S,
    ) -> Result<Advanced, IntegrationError<S, N>> {
        let mut bound = Bound {
            step: &mut self.step,
            model,
        };
        self.course.advance(run, model, &mut bound, target)
    }
}

impl<S: RealField + Copy> Course<S> {
    fn advance<const N: usize>(
        &mut self,
        run: &mut Run<'_, S, N>,
        model: &dyn Evaluate<S, N>,
        stepping: &mut dyn Stepping<S, N>,
        target: S,
    ) -> Result<Advanced, IntegrationError<S, N>> {
        let max_steps = self.max_steps;
        loop {
            if run.fresh != Fresh::No {
                if run.fresh == Fresh::Segment {
                    run.arm()?;
                    // Events closer than a few steps are beyond a fixed
                    // step (the Zeno guard's default separation).
                    self.bounded = run.rec.bound_step(self.h);
                    run.rec.resolve_events(self.bounded);
                    self.growth = Some(GrowthGuard::new(&run.q, &run.qdot));
                } else {
                    run.arm()?;
                }
                stepping.restart();
                run.fresh = Fresh::No;
            }
            if run.t >= target {
                return Ok(Advanced::Reached);
            }
            // The next stop: a sample time, or the target.
            let stop = run
                .rec
                .pending()
                .filter(|&ts| ts < target)
                .unwrap_or(target);
            let (t, (q, qdot)) = (run.t, run.state());
            let interval = Interval::new(t, stop, self.bounded);
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
            let growth = self
                .growth
                .get_or_insert_with(|| GrowthGuard::new(&q, &qdot));
            let mut restarted = false;
            for k in 1..=steps {
                let (t, before) = (run.t, run.state());
                if run.steps_this_call().0 >= max_steps {
                    let (q, qdot) = before;
                    return Err(IntegrationError::TooManySteps {
                        t,
                        max_steps,
                        q,
                        qdot,
                    });
                }
                let t_next = interval.time(k, steps);
                let dt = t_next - t;
                let (q, qdot) =
                    stepping.step(&mut run.rec, t, (&before.0, &before.1), dt, t_next)?;
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
                run.rec.stats.steps_accepted += 1;
                if let Some(steps) = growth.unstable(before, (&q, &qdot), dt) {
                    return Err(IntegrationError::Unstable {
                        t: t_next,
                        h: interval.step,
                        steps,
                        q,
                        qdot,
                    });
                }
                let crossed = if run.rec.watching() {
                    run.rec
                        .watch_hermite(model, (t, &before), (t_next, &(q, qdot)))?
                } else {
                    None
                };
                match run.take((t_next, q, qdot), crossed, target) {
                    Flow::Go => {}
                    Flow::Stopped => return Ok(Advanced::Stopped),
                    Flow::Rebuild => return Ok(Advanced::Rebuild),
                    Flow::Restarted(at_target) => {
                        if at_target {
                            run.t = target;
                            return Ok(Advanced::Reached);
                        }
                        restarted = true;
                        break;
                    }
                }
            }
            if !restarted {
                run.record_landed();
            }
        }
    }
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
