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
/// The loop itself ([`Course::walk`]) is written once for a run and for
/// the SIMD lanes of an [`Ensemble`](crate::ensemble::Ensemble)
/// ([`Track`]: what differs between them, the state and what is done with
/// a step's end). For a run it sees the method's step and the model only
/// behind a `dyn` ([`Stepping`], [`Evaluate`]): it is compiled once per
/// scalar and size, not once per model and method. Only the step, where
/// the model is evaluated, keeps both types.
pub struct FixedWalk<S, F> {
    pub(crate) step: F,
    course: Course<S>,
    growth: Option<GrowthGuard<S>>,
}

/// The fixed-step loop's own state between calls: the step asked for,
/// and the budget.
pub(crate) struct Course<S> {
    h: S,
    max_steps: usize,
    /// `h` bounded by the events' `max_step`, for the current segment.
    bounded: S,
}

impl<S: RealField + Copy> Course<S> {
    /// The loop's state before a method's first step.
    pub(crate) fn new(h: S, max_steps: usize) -> Self {
        Self {
            h,
            max_steps,
            bounded: h,
        }
    }
}

impl<S: RealField + Copy, F> FixedWalk<S, F> {
    pub(crate) fn new(step: F, h: S, max_steps: usize) -> Self {
        Self {
            step,
            course: Course::new(h, max_steps),
            growth: None,
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
        walk_run(
            &mut self.course,
            &mut self.growth,
            run,
            model,
            &mut bound,
            target,
        )
    }
}

/// The loop over one run, compiled once per scalar and size.
fn walk_run<S: RealField + Copy, const N: usize>(
    course: &mut Course<S>,
    growth: &mut Option<GrowthGuard<S>>,
    run: &mut Run<'_, S, N>,
    model: &dyn Evaluate<S, N>,
    stepping: &mut dyn Stepping<S, N>,
    target: S,
) -> Result<Advanced, IntegrationError<S, N>> {
    let zeros = (SVector::zeros(), SVector::zeros());
    let mut track = OneRun {
        run,
        model,
        stepping,
        growth,
        before: zeros,
        end: zeros,
    };
    course.walk(&mut track, target)
}

/// What the fixed-step loop walks: one run (its state, samples and
/// events, [`OneRun`]) or the SIMD lanes of an
/// [`Ensemble`](crate::ensemble::Ensemble). The loop ([`Course::walk`])
/// cuts each interval to the next stop into steps, keeps the budget and
/// hands the steps' ends on; the track steps, judges and keeps the state.
pub(crate) trait Track<S: RealField + Copy> {
    /// What ends a walk in failure.
    type Error;

    /// The time of the state.
    fn t(&self) -> S;

    /// What must be built anew before the next step.
    fn fresh(&self) -> Fresh;

    /// A fresh start (see [`fresh`](Track::fresh)), after which `fresh`
    /// is [`Fresh::No`]: the events armed, what the method carries from
    /// step to step forgotten; for a new segment, the growth guard anew
    /// and the step `h` bounded by the events' `max_step`, which it
    /// returns.
    fn begin(&mut self, fresh: Fresh, h: S) -> Result<Option<S>, Self::Error>;

    /// The next stop: the next sample time before `target`, or `target`.
    fn next_stop(&self, target: S) -> S;

    /// The error of an interval whose steps are too short to move `t`.
    fn underflow(&self, h: S) -> Self::Error;

    /// The error of a call that spent its step budget, at the state.
    fn too_many_steps(&self, max_steps: usize) -> Self::Error;

    /// The steps taken in the current call: what the budget counts.
    fn steps_this_call(&self) -> usize;

    /// One step from the state at `t` to `t_next = t + dt`, its end kept
    /// (and, for a run, checked finite: the model does not evaluate it).
    fn step(&mut self, t: S, dt: S, t_next: S) -> Result<(), Self::Error>;

    /// Counts a step taken.
    fn count(&mut self);

    /// The growth guard's judgement of the step (`h` the interval's step,
    /// which an error reports, `dt` its length).
    fn judge(&mut self, t_next: S, h_dt: (S, S)) -> Result<(), Self::Error>;

    /// Moves to the end of the step: its events, then the state.
    /// [`Flow::Restarted`]`(true)` has left the state at `target`.
    fn take(&mut self, times: (S, S), target: S) -> Result<Flow, Self::Error>;

    /// The samples due where the last step of an interval landed.
    fn landed(&mut self);
}

impl<S: RealField + Copy> Course<S> {
    /// Advances `track` to `target`, or to an event that stops it, each
    /// interval between stops in the fewest equal steps no longer than
    /// `h`. On error the track holds the end of the last step that
    /// succeeded.
    #[inline(always)]
    pub(crate) fn walk<T: Track<S>>(
        &mut self,
        track: &mut T,
        target: S,
    ) -> Result<Advanced, T::Error> {
        let max_steps = self.max_steps;
        loop {
            let fresh = track.fresh();
            if fresh != Fresh::No {
                if let Some(bounded) = track.begin(fresh, self.h)? {
                    self.bounded = bounded;
                }
            }
            if track.t() >= target {
                return Ok(Advanced::Reached);
            }
            let interval = Interval::new(track.t(), track.next_stop(target), self.bounded);
            if interval.underflows() {
                return Err(track.underflow(interval.step));
            }
            let Some(steps) = interval.steps(max_steps) else {
                return Err(track.too_many_steps(max_steps));
            };
            let mut restarted = false;
            for k in 1..=steps {
                if track.steps_this_call() >= max_steps {
                    return Err(track.too_many_steps(max_steps));
                }
                let t = track.t();
                let t_next = interval.time(k, steps);
                let dt = t_next - t;
                track.step(t, dt, t_next)?;
                track.count();
                track.judge(t_next, (interval.step, dt))?;
                match track.take((t, t_next), target)? {
                    Flow::Go => {}
                    Flow::Stopped => return Ok(Advanced::Stopped),
                    Flow::Rebuild => return Ok(Advanced::Rebuild),
                    Flow::Restarted(true) => return Ok(Advanced::Reached),
                    Flow::Restarted(false) => {
                        restarted = true;
                        break;
                    }
                }
            }
            if !restarted {
                track.landed();
            }
        }
    }
}

/// One run as the fixed-step loop walks it: its state, samples and
/// events, the model and the step behind a `dyn`, its growth guard (kept
/// between calls by the walker), and the step's start and end.
struct OneRun<'r, 'a, S: RealField + Copy, const N: usize> {
    run: &'r mut Run<'a, S, N>,
    model: &'r dyn Evaluate<S, N>,
    stepping: &'r mut dyn Stepping<S, N>,
    growth: &'r mut Option<GrowthGuard<S>>,
    /// The state the step starts from.
    before: State<S, N>,
    /// Its end.
    end: State<S, N>,
}

impl<S: RealField + Copy, const N: usize> Track<S> for OneRun<'_, '_, S, N> {
    type Error = IntegrationError<S, N>;

    #[inline(always)]
    fn t(&self) -> S {
        self.run.t
    }

    #[inline(always)]
    fn fresh(&self) -> Fresh {
        self.run.fresh
    }

    #[inline(always)]
    fn begin(&mut self, fresh: Fresh, h: S) -> Result<Option<S>, Self::Error> {
        let run = &mut *self.run;
        run.arm()?;
        let bounded = if fresh == Fresh::Segment {
            // Events closer than a few steps are beyond a fixed step (the
            // Zeno guard's default separation).
            let bounded = run.rec.bound_step(h);
            run.rec.resolve_events(bounded);
            *self.growth = Some(GrowthGuard::new(&run.q, &run.qdot));
            Some(bounded)
        } else {
            None
        };
        self.stepping.restart();
        run.fresh = Fresh::No;
        Ok(bounded)
    }

    #[inline(always)]
    fn next_stop(&self, target: S) -> S {
        self.run
            .rec
            .pending()
            .filter(|&ts| ts < target)
            .unwrap_or(target)
    }

    fn underflow(&self, h: S) -> Self::Error {
        let (t, (q, qdot)) = (self.run.t, self.run.state());
        IntegrationError::StepSizeUnderflow { t, h, q, qdot }
    }

    fn too_many_steps(&self, max_steps: usize) -> Self::Error {
        let (t, (q, qdot)) = (self.run.t, self.run.state());
        IntegrationError::TooManySteps {
            t,
            max_steps,
            q,
            qdot,
        }
    }

    #[inline(always)]
    fn steps_this_call(&self) -> usize {
        self.run.steps_this_call().0
    }

    #[inline(always)]
    fn step(&mut self, t: S, dt: S, t_next: S) -> Result<(), Self::Error> {
        self.before = self.run.state();
        let (q0, qdot0) = &self.before;
        let (q, qdot) = self
            .stepping
            .step(&mut self.run.rec, t, (q0, qdot0), dt, t_next)?;
        // The step's end is not evaluated by the model: check it before it
        // becomes the state.
        if !finite_state(&q, &qdot) {
            let value = NonFiniteValue::State;
            return Err(IntegrationError::NonFiniteState {
                t: t_next,
                q,
                qdot,
                value,
            });
        }
        self.end = (q, qdot);
        Ok(())
    }

    #[inline(always)]
    fn count(&mut self) {
        self.run.rec.stats.steps_accepted += 1;
    }

    #[inline(always)]
    fn judge(&mut self, t_next: S, (h, dt): (S, S)) -> Result<(), Self::Error> {
        if self.growth.is_none() {
            *self.growth = Some(GrowthGuard::new(&self.before.0, &self.before.1));
        }
        let Some(growth) = self.growth.as_mut() else {
            unreachable!("set above");
        };
        let (q, qdot) = &self.end;
        match growth.unstable(self.before, (q, qdot), dt) {
            Some(steps) => Err(IntegrationError::Unstable {
                t: t_next,
                h,
                steps,
                q: *q,
                qdot: *qdot,
            }),
            None => Ok(()),
        }
    }

    #[inline(always)]
    fn take(&mut self, (t, t_next): (S, S), target: S) -> Result<Flow, Self::Error> {
        let run = &mut *self.run;
        let crossed = if run.rec.watching() {
            run.rec
                .watch_hermite(self.model, (t, &self.before), (t_next, &self.end))?
        } else {
            None
        };
        let flow = run.take((t_next, self.end.0, self.end.1), crossed, target);
        if let Flow::Restarted(true) = flow {
            run.t = target;
        }
        Ok(flow)
    }

    #[inline(always)]
    fn landed(&mut self) {
        self.run.record_landed();
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
