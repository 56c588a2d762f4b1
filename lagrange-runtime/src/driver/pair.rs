//! The embedded-pair kind ([`Bs3`], [`Dopri5`], [`Tsit5`] and [`Dop853`]):
//! Hairer's step loop with its stabilized step-size control (its rules,
//! [`StepControl`], also step the
//! [`AdaptiveEnsemble`](crate::ensemble::AdaptiveEnsemble)), the step
//! budget, the underflow check, and samples from the continuous extension,
//! resumable, so that the methods only supply their stages, error estimate
//! and dense output.
//!
//! [`Bs3`]: crate::integrators::Bs3
//! [`Dopri5`]: crate::integrators::Dopri5
//! [`Tsit5`]: crate::integrators::Tsit5
//! [`Dop853`]: crate::integrators::Dop853

use nalgebra::{RealField, SVector};

use super::growth::GrowthGuard;
use super::record::{Evaluate, Recorder};
use super::run::{Advanced, Flow, Fresh, Run, Walk};
use super::step_control::{FirstStep, advances, initial_step};
use crate::error::IntegrationError;
use crate::model::Lagrangian;
use crate::trajectory::State;

/// A step-size controller's constants, as Hairer's codes set them:
/// `h_new = h · safety · err^(−α) · err_old^β`, the ratio `h_new / h` kept
/// within `[fac_min, fac_max]`, with `α = exponent − β · beta_weight`.
pub struct Controller {
    pub(crate) safety: f64,
    /// Smallest step-size ratio `h_new / h`.
    pub(crate) fac_min: f64,
    /// Largest step-size ratio `h_new / h`.
    pub(crate) fac_max: f64,
    /// Lund stabilization (the "I" weight on the previous error).
    pub(crate) beta: f64,
    /// `1 / (q + 1)` for an error estimate of order `q`.
    pub(crate) exponent: f64,
    /// How much of `β` is taken off the exponent.
    pub(crate) beta_weight: f64,
    /// The order the initial step guess assumes.
    pub(crate) order: u8,
    /// How much longer than `h` a last step may be stretched to land on the
    /// end, so that it is not a sliver (Hairer's 1.01).
    pub(crate) stretch: f64,
}

impl Controller {
    /// The constants in the scalar `S`, for one run (or one stepper).
    pub(crate) fn gains<S: RealField + Copy>(&self) -> Gains<S> {
        let c = |x: f64| -> S { nalgebra::convert(x) };
        let beta = c(self.beta);
        Gains {
            safety: c(self.safety),
            fac_min: c(self.fac_min),
            fac_max: c(self.fac_max),
            alpha: c(self.exponent) - beta * c(self.beta_weight),
            beta,
        }
    }
}

/// A [`Controller`] in the scalar of a run: the step-size rule the
/// adaptive driver and a [`Stepper`](crate::stepper::Stepper) share.
pub struct Gains<S> {
    safety: S,
    /// Smallest step-size ratio, also the cut after a failed evaluation.
    pub(crate) fac_min: S,
    fac_max: S,
    alpha: S,
    beta: S,
}

impl<S: RealField + Copy> Gains<S> {
    /// The step after `h` was rejected with error `err` (above 1).
    pub(crate) fn after_rejection(&self, h: S, err: S) -> S {
        h / (err.powf(self.alpha) / self.safety).min(S::one() / self.fac_min)
    }

    /// The step after `h` was accepted with error `err`, the previous
    /// accepted step's being `err_old`:
    /// `h · safety · err^(−α) · err_old^β`, its ratio to `h` bounded.
    pub(crate) fn after_acceptance(&self, h: S, err: S, err_old: S) -> S {
        // Without stabilization (`β = 0`, DOP853) the old error's factor is
        // exactly 1: the library call that would compute it is skipped.
        let stabilization = if self.beta == S::zero() {
            S::one()
        } else {
            err_old.powf(self.beta)
        };
        let shrink = err.powf(self.alpha) / stabilization / self.safety;
        let fac = shrink
            .min(S::one() / self.fac_min)
            .max(S::one() / self.fac_max);
        h / fac
    }
}

/// The step-size rules of the explicit pairs, for a run and a
/// [`Stepper`](crate::stepper::Stepper) ([`PairWalk`]) and for the
/// [`AdaptiveEnsemble`](crate::ensemble::AdaptiveEnsemble)'s one step of
/// all lanes alike: which step to attempt, landing on a target, and the
/// next step after an attempt. The callers check the budget and whether
/// the step still moves `t` ([`advances`]) first.
pub(crate) struct StepControl<S> {
    gains: Gains<S>,
    /// The controller's [`stretch`](Controller::stretch).
    stretch: S,
    /// The step size the control chose; `None` before the first guess.
    pub(crate) h: Option<S>,
    err_old: S,
    rejected_last: bool,
}

/// A step to attempt, as [`StepControl::attempt`] proposes it.
#[derive(Clone, Copy)]
pub(crate) struct Attempt<S> {
    /// Where it ends: the target, or `t + h` rounded.
    pub(crate) t_new: S,
    /// Its size, `t_new − t` exactly.
    pub(crate) h: S,
    /// Whether it lands on the target.
    pub(crate) last: bool,
    /// The step the control proposed, before it was cut or stretched to
    /// land.
    proposed: S,
}

impl<S: RealField + Copy> StepControl<S> {
    pub(crate) fn new(control: &Controller) -> Self {
        Self {
            gains: control.gains(),
            stretch: nalgebra::convert(control.stretch),
            h: None,
            err_old: nalgebra::convert(1e-4),
            rejected_last: false,
        }
    }

    /// A new segment (a start, or a reset by an event): no error history.
    pub(crate) fn restart(&mut self) {
        self.err_old = nalgebra::convert(1e-4);
        self.rejected_last = false;
    }

    /// The attempt of the step `h` from `t` towards `target`. A step that
    /// would stop just short of the target is stretched to land on it
    /// (Hairer's 1 %), one beyond it cut. The state advances by exactly
    /// the time the clock does: `t + h` rounds, so the step taken is the
    /// representable `fl(t + h) − t` (else the clock drifts from the state
    /// by up to half an ulp of `t` per step, 1e-10 s after 5e5 steps at
    /// `t ≈ 70`).
    #[inline]
    pub(crate) fn attempt(&self, t: S, h: S, target: S) -> Attempt<S> {
        let last = t + h * self.stretch >= target;
        let t_new = if last { target } else { t + h };
        Attempt {
            t_new,
            h: t_new - t,
            last,
            proposed: h,
        }
    }

    /// After `attempt` was rejected with error `err` (above 1).
    pub(crate) fn reject(&mut self, attempt: &Attempt<S>, err: S) {
        self.rejected_last = true;
        self.h = Some(self.gains.after_rejection(attempt.h, err));
    }

    /// After a stage of `attempt` could not be evaluated: `fac_min` of it.
    pub(crate) fn fail(&mut self, attempt: &Attempt<S>) {
        self.rejected_last = true;
        self.h = Some(attempt.h * self.gains.fac_min);
    }

    /// After `attempt` was accepted with error `err`: the next step, which
    /// the caller sets once the step's end is taken. No growth right after
    /// a rejection; a step shortened to land on the target says little of
    /// the step the solution allows, so the next is not shorter than the
    /// one proposed.
    #[inline]
    pub(crate) fn accept(&mut self, attempt: &Attempt<S>, err: S) -> S {
        let mut h_new = self.gains.after_acceptance(attempt.h, err, self.err_old);
        if self.rejected_last {
            h_new = h_new.min(attempt.h);
        }
        if attempt.last && attempt.h < attempt.proposed {
            h_new = h_new.max(attempt.proposed);
        }
        self.err_old = err.max(nalgebra::convert(1e-4));
        self.rejected_last = false;
        h_new
    }
}

/// The settings every adaptive method has.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerances<S> {
    pub(crate) rtol: S,
    pub(crate) atol: S,
    pub(crate) max_steps: usize,
}

/// How an attempted step ended, short of a model failure.
pub enum Outcome<S, Step> {
    /// The error estimate `err` exceeds the tolerance.
    Rejected { err: S },
    /// The step passed the error test with estimate `err`.
    Accepted { step: Step, err: S },
}

/// What an explicit embedded Runge–Kutta pair supplies to [`adaptive`]: one
/// value per integration, holding the tableau and the slopes it carries
/// from step to step (first same as last).
pub trait EmbeddedPair<S: RealField + Copy, const N: usize> {
    /// An accepted step: the new state and what the dense output needs.
    type Step;
    /// The continuous extension on one accepted step.
    type Dense;

    /// Attempts a step of size `h` from `(t, q, q̇)` to `t_new`. A failing
    /// evaluation, or an overflow in the error estimate, is an error, which
    /// rejects the step. `rec` tells whether a sample lies inside the step.
    fn attempt<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        times: (S, S, S),
        state: (&SVector<S, N>, &SVector<S, N>),
    ) -> Result<Outcome<S, Self::Step>, IntegrationError<S, N>>;

    /// The state at the end of an accepted step.
    fn end(step: &Self::Step) -> State<S, N>;

    /// The continuous extension of an accepted step of size `h` from
    /// `(q, q̇)`; built only when a sample lies strictly inside it.
    fn dense(
        &self,
        h: S,
        state: (&SVector<S, N>, &SVector<S, N>),
        step: &Self::Step,
    ) -> Self::Dense;

    /// The continuous extension at `t + θ h`.
    fn dense_at(dense: &Self::Dense, theta: S) -> State<S, N>;

    /// Moves on to the end of an accepted step: its last slope is the next
    /// step's first.
    fn advance(&mut self, step: &Self::Step);
}

/// An embedded pair by its settings: what [`PairWalk`] builds a pair from.
pub trait Embedded<S: RealField + Copy, const N: usize> {
    /// The pair, holding the tableau and the slopes carried between steps.
    type Pair: EmbeddedPair<S, N>;
    /// The step-size controller's constants.
    const CONTROL: Controller;
    /// The tolerances and the step budget.
    fn tolerances(&self) -> Tolerances<S>;
    /// The pair from `(q̇, q̈)` at a start.
    fn pair(&self, qdot: &SVector<S, N>, qddot: &SVector<S, N>) -> Self::Pair;
}

/// The embedded pairs' loop, resumable, around a method `M`'s pair.
///
/// At a segment's start (the run's, or after a reset by an event): the
/// first slope, Hairer's initial step guess from it (bounded by the
/// target and the events' `max_step`), a growth guard. Then attempts until
/// the target: a step that would stop just short of it is stretched to land
/// on it (Hairer's 1 %), samples in between come from the continuous
/// extension, so sampling never changes the steps. A stage where the model
/// cannot be evaluated rejects the step and retries with `fac_min` of it,
/// so a model that breaks down at `t*` is integrated up to `t*`; if `h`
/// then underflows, that failure is the error reported.
///
/// Accepted steps are watched by the growth guard: at everyday tolerances
/// the error control keeps an explicit step within its stability region
/// and the guard never fires, but a tolerance loose enough (`rtol` near 1
/// or above, or `atol` above the solution's size) accepts steps that blow
/// the solution up, which would otherwise end in a misleading underflow or
/// overflow; it ends in [`Unstable`](IntegrationError::Unstable), as for a
/// fixed step beyond its limit.
///
/// Between calls (a stepper's frames) the step size, the error history
/// and the pair's carried slope are kept. A step shortened to land on a
/// frame's end says little about the step the solution allows: the next
/// one is not shorter than the control had chosen before it.
///
/// The loop itself ([`Course::walk`]) is written once for a run and for
/// the SIMD lanes of the [`AdaptiveEnsemble`](crate::ensemble::AdaptiveEnsemble)
/// ([`Track`]: what differs between them, the state and what is done with
/// a step's end). For a run it sees the pair and the model only behind a
/// `dyn` ([`Pairing`], [`Evaluate`]): it is compiled once per scalar and
/// size, not once per model and method. Only the pair's attempts, where
/// the model is evaluated, keep both types.
pub struct PairWalk<S, M: Embedded<S, N>, const N: usize>
where
    S: RealField + Copy,
{
    method: M,
    pair: Option<M::Pair>,
    course: Course<S>,
    growth: Option<GrowthGuard<S>>,
}

/// The embedded pairs' loop's own state between calls: the step-size
/// rules and the step they chose, the tolerances and the step budget.
pub(crate) struct Course<S> {
    pub(crate) control: StepControl<S>,
    settings: Tolerances<S>,
    /// The controller's [`order`](Controller::order).
    order: u8,
}

impl<S: RealField + Copy> Course<S> {
    /// The loop's state before a method's first step.
    pub(crate) fn new(control: &Controller, settings: Tolerances<S>) -> Self {
        Self {
            control: StepControl::new(control),
            settings,
            order: control.order,
        }
    }
}

impl<S: RealField + Copy, M: Embedded<S, N>, const N: usize> PairWalk<S, M, N> {
    pub(crate) fn new(method: M) -> Self {
        Self {
            course: Course::new(&M::CONTROL, method.tolerances()),
            growth: None,
            method,
            pair: None,
        }
    }
}

/// A method's pair bound to the model it steps, as the loop calls it: the
/// accepted step and its continuous extension are kept here between the
/// loop's calls.
trait Pairing<S: RealField + Copy, const N: usize> {
    /// The pair anew from `(q̇, q̈)` at a start ([`Embedded::pair`]).
    fn start(&mut self, qdot: &SVector<S, N>, qddot: &SVector<S, N>);

    /// [`EmbeddedPair::attempt`], keeping an accepted step; `None` where
    /// it failed, its error kept for [`failure`](Pairing::failure) (the
    /// outcome alone, a few words, comes back in registers).
    fn attempt(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        times: (S, S, S),
        state: (&SVector<S, N>, &SVector<S, N>),
    ) -> Option<Outcome<S, ()>>;

    /// The error of the last attempt that failed.
    fn failure(&mut self) -> IntegrationError<S, N>;

    /// The state at the end of the accepted step.
    fn end(&self) -> State<S, N>;

    /// The accepted step's continuous extension at `θ`, built on first use
    /// from the step of size `h` from `state`.
    fn dense_at(&mut self, h: S, state: (&SVector<S, N>, &SVector<S, N>), theta: S) -> State<S, N>;

    /// Moves the pair on past the accepted step ([`EmbeddedPair::advance`]).
    fn advance(&mut self);
}

struct Bound<'a, S, M, L, const N: usize>
where
    S: RealField + Copy,
    M: Embedded<S, N>,
{
    method: &'a M,
    pair: &'a mut Option<M::Pair>,
    model: &'a L,
    step: Option<<M::Pair as EmbeddedPair<S, N>>::Step>,
    dense: Option<<M::Pair as EmbeddedPair<S, N>>::Dense>,
    failure: Option<IntegrationError<S, N>>,
}

impl<S, M, L, const N: usize> Bound<'_, S, M, L, N>
where
    S: RealField + Copy,
    M: Embedded<S, N>,
{
    fn pair(&mut self) -> &mut M::Pair {
        self.pair
            .as_mut()
            .expect("the pair is built at every start")
    }

    fn step(&self) -> &<M::Pair as EmbeddedPair<S, N>>::Step {
        self.step.as_ref().expect("read after an accepted step")
    }
}

impl<S, M, L, const N: usize> Pairing<S, N> for Bound<'_, S, M, L, N>
where
    S: RealField + Copy,
    M: Embedded<S, N>,
    L: Lagrangian<N, Scalar = S>,
{
    fn start(&mut self, qdot: &SVector<S, N>, qddot: &SVector<S, N>) {
        *self.pair = Some(self.method.pair(qdot, qddot));
    }

    fn attempt(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        times: (S, S, S),
        state: (&SVector<S, N>, &SVector<S, N>),
    ) -> Option<Outcome<S, ()>> {
        let model = self.model;
        Some(match self.pair().attempt(rec, model, times, state) {
            Ok(Outcome::Rejected { err }) => Outcome::Rejected { err },
            Ok(Outcome::Accepted { step, err }) => {
                self.step = Some(step);
                self.dense = None;
                Outcome::Accepted { step: (), err }
            }
            Err(error) => {
                self.failure = Some(error);
                return None;
            }
        })
    }

    fn failure(&mut self) -> IntegrationError<S, N> {
        self.failure.take().expect("read after a failed attempt")
    }

    fn end(&self) -> State<S, N> {
        M::Pair::end(self.step())
    }

    fn dense_at(&mut self, h: S, state: (&SVector<S, N>, &SVector<S, N>), theta: S) -> State<S, N> {
        if self.dense.is_none() {
            let pair = self
                .pair
                .as_ref()
                .expect("the pair is built at every start");
            self.dense = Some(pair.dense(h, state, self.step()));
        }
        let dense = self.dense.as_ref().expect("built above");
        M::Pair::dense_at(dense, theta)
    }

    fn advance(&mut self) {
        // The step is read where it lies, not taken out of its `Option`:
        // a move of a Dop853 step is eight vectors.
        let step = self.step.as_ref().expect("advanced after an accepted step");
        self.pair
            .as_mut()
            .expect("the pair is built at every start")
            .advance(step);
        self.step = None;
        self.dense = None;
    }
}

impl<S, M, const N: usize> Walk<S, N> for PairWalk<S, M, N>
where
    S: RealField + Copy,
    M: Embedded<S, N>,
{
    fn advance<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        run: &mut Run<'_, S, N>,
        model: &L,
        target: S,
    ) -> Result<Advanced, IntegrationError<S, N>> {
        let mut bound = Bound {
            method: &self.method,
            pair: &mut self.pair,
            model,
            step: None,
            dense: None,
            failure: None,
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
    pairing: &mut dyn Pairing<S, N>,
    target: S,
) -> Result<Advanced, IntegrationError<S, N>> {
    let zeros = (SVector::zeros(), SVector::zeros());
    let mut track = OneRun {
        run,
        model,
        pairing,
        growth,
        at: zeros,
        end: zeros,
    };
    course.walk(&mut track, target)
}

/// A fresh start's outcome, as [`Track::begin`] reports it.
pub(crate) struct Begun<S> {
    /// Hairer's first step, where the loop asked for one.
    pub(crate) h: Option<S>,
    /// Whether the step control's error history starts anew (a new
    /// segment, or a run without a growth guard yet).
    pub(crate) restart: bool,
}

/// What the embedded pairs' loop walks: one run (its state, samples and
/// events, [`OneRun`]) or the SIMD lanes of an
/// [`AdaptiveEnsemble`](crate::ensemble::AdaptiveEnsemble). The loop
/// ([`Course::walk`]) decides every step: the budget, the underflow rule,
/// the attempt, its rejection, retry or acceptance, and the next step
/// size; the track evaluates and keeps the state.
pub(crate) trait Track<S: RealField + Copy> {
    /// What ends a walk in failure.
    type Error;

    /// The time of the state.
    fn t(&self) -> S;

    /// What must be built anew before the next step.
    fn fresh(&self) -> Fresh;

    /// A fresh start (see [`fresh`](Track::fresh)), after which
    /// `fresh` is [`Fresh::No`]: the pair's first slope at the state, the
    /// growth guard anew for a new segment, and where `first` asks,
    /// Hairer's first step towards `target`.
    fn begin(
        &mut self,
        fresh: Fresh,
        first: Option<FirstStep<S>>,
        target: S,
    ) -> Result<Begun<S>, Self::Error>;

    /// `h` bounded by the events' `max_step`.
    fn bound_step(&self, h: S) -> S;

    /// The steps attempted (accepted or rejected) in the current call:
    /// what the step budget counts.
    fn attempts_this_call(&self) -> usize;

    /// The error of a call that spent its step budget, at the state.
    fn too_many_steps(&self, max_steps: usize) -> Self::Error;

    /// The error of a step `h` too short to move `t`, at the state.
    fn underflow(&self, h: S) -> Self::Error;

    /// Attempts the step `(t, t_new, h)` from the state: its error
    /// estimate, or the failure of a stage (which the loop retries
    /// shorter, and reports if the step underflows before getting past it).
    fn attempt(&mut self, times: (S, S, S)) -> Result<Outcome<S, ()>, Self::Error>;

    /// Counts an attempt, accepted or rejected.
    fn count(&mut self, accepted: bool);

    /// The end of the accepted attempt: a constrained model's state
    /// projected, and the growth guard's judgement of the step.
    fn end(&mut self, times: (S, S, S)) -> Result<(), Self::Error>;

    /// Moves to the end of the accepted step: the events and the samples
    /// inside it, then the state. [`Flow::Restarted`]`(true)` has left the
    /// state at `target`.
    fn take(&mut self, times: (S, S, S), target: S) -> Result<Flow, Self::Error>;
}

impl<S: RealField + Copy> Course<S> {
    /// Advances `track` to `target`, or to an event that stops it. On
    /// error the track holds the end of the last step that succeeded.
    ///
    /// At a fresh start (the run's, after a reset by an event, or a change
    /// by the caller): the first slope, Hairer's first step if none was
    /// chosen or a segment begins. Then attempts until the target: a step
    /// whose stage fails is retried with `fac_min` of it, and if `h` then
    /// underflows, that failure is the error reported.
    #[inline(always)]
    pub(crate) fn walk<T: Track<S>>(
        &mut self,
        track: &mut T,
        target: S,
    ) -> Result<Advanced, T::Error> {
        let Tolerances {
            rtol,
            atol,
            max_steps,
        } = self.settings;
        // The evaluation failure that made us shrink h, reported if h
        // underflows before we get past it.
        let mut stage_failure = None;
        loop {
            let t = track.t();
            if t >= target {
                return Ok(Advanced::Reached);
            }
            let fresh = track.fresh();
            if fresh != Fresh::No {
                let guess = fresh == Fresh::Segment || self.control.h.is_none();
                let order = self.order;
                let first = guess.then_some(FirstStep { rtol, atol, order });
                let begun = track.begin(fresh, first, target)?;
                if let Some(h) = begun.h {
                    self.control.h = Some(h);
                }
                if begun.restart {
                    self.control.restart();
                }
            }
            let Some(h) = self.control.h else {
                unreachable!("chosen at the start");
            };
            let h = track.bound_step(h);
            if track.attempts_this_call() >= max_steps {
                return Err(track.too_many_steps(max_steps));
            }
            if !advances(t, h) {
                return Err(stage_failure.take().unwrap_or_else(|| track.underflow(h)));
            }
            let step = self.control.attempt(t, h, target);
            let times = (t, step.t_new, step.h);
            let err = match track.attempt(times) {
                Ok(Outcome::Accepted { step: (), err }) => err,
                Ok(Outcome::Rejected { err }) => {
                    track.count(false);
                    self.control.reject(&step, err);
                    continue;
                }
                Err(failure) => {
                    stage_failure = Some(failure);
                    track.count(false);
                    self.control.fail(&step);
                    continue;
                }
            };
            let h_new = self.control.accept(&step, err);
            stage_failure = None;
            track.count(true);
            track.end(times)?;
            self.control.h = Some(h_new);
            match track.take(times, target)? {
                Flow::Go | Flow::Restarted(false) => {}
                Flow::Stopped => return Ok(Advanced::Stopped),
                Flow::Rebuild => return Ok(Advanced::Rebuild),
                Flow::Restarted(true) => return Ok(Advanced::Reached),
            }
        }
    }
}

/// One run as the pair loop walks it: its state, samples and events, the
/// model and the pair behind a `dyn`, its growth guard (kept between
/// calls by the walker), and the attempted step's start and end.
struct OneRun<'r, 'a, S: RealField + Copy, const N: usize> {
    run: &'r mut Run<'a, S, N>,
    model: &'r dyn Evaluate<S, N>,
    pairing: &'r mut dyn Pairing<S, N>,
    growth: &'r mut Option<GrowthGuard<S>>,
    /// The state the attempted step starts from.
    at: State<S, N>,
    /// The accepted step's end, its drift controlled.
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
    fn begin(
        &mut self,
        fresh: Fresh,
        first: Option<FirstStep<S>>,
        target: S,
    ) -> Result<Begun<S>, Self::Error> {
        let run = &mut *self.run;
        run.arm()?;
        let (t, (q, qdot)) = (run.t, run.state());
        let qddot = run.rec.rhs(self.model, t, &q, &qdot)?;
        let h = first.map(|first| {
            let start = (t, &q, &qdot, &qddot);
            let h_max = run.rec.bound_step(target - t);
            initial_step(&mut run.rec, self.model, start, h_max, &first)
        });
        let restart = fresh == Fresh::Segment || self.growth.is_none();
        if restart {
            *self.growth = Some(GrowthGuard::new(&q, &qdot));
        }
        self.pairing.start(&qdot, &qddot);
        run.fresh = Fresh::No;
        Ok(Begun { h, restart })
    }

    #[inline(always)]
    fn bound_step(&self, h: S) -> S {
        self.run.rec.bound_step(h)
    }

    #[inline(always)]
    fn attempts_this_call(&self) -> usize {
        self.run.steps_this_call().1
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

    fn underflow(&self, h: S) -> Self::Error {
        let (t, (q, qdot)) = (self.run.t, self.run.state());
        IntegrationError::StepSizeUnderflow { t, h, q, qdot }
    }

    #[inline(always)]
    fn attempt(&mut self, times: (S, S, S)) -> Result<Outcome<S, ()>, Self::Error> {
        self.at = self.run.state();
        let (q, qdot) = &self.at;
        match self.pairing.attempt(&mut self.run.rec, times, (q, qdot)) {
            Some(outcome) => Ok(outcome),
            None => Err(self.pairing.failure()),
        }
    }

    #[inline(always)]
    fn count(&mut self, accepted: bool) {
        let stats = &mut self.run.rec.stats;
        if accepted {
            stats.steps_accepted += 1;
        } else {
            stats.steps_rejected += 1;
        }
    }

    #[inline(always)]
    fn end(&mut self, (_, t_new, h): (S, S, S)) -> Result<(), Self::Error> {
        // A constrained model's end state is projected; the pair keeps
        // its last slope, evaluated before that (see `constraints`).
        let (q_end, qdot_end) = self.pairing.end();
        let (q_new, qdot_new) = self
            .run
            .rec
            .control_drift(self.model, t_new, q_end, qdot_end)?;
        let Some(growth) = self.growth else {
            unreachable!("built at the start");
        };
        if let Some(steps) = growth.unstable(self.at, (&q_new, &qdot_new), h) {
            return Err(IntegrationError::Unstable {
                t: t_new,
                h,
                steps,
                q: q_new,
                qdot: qdot_new,
            });
        }
        self.end = (q_new, qdot_new);
        Ok(())
    }

    #[inline(always)]
    fn take(&mut self, (t, t_new, h): (S, S, S), target: S) -> Result<Flow, Self::Error> {
        let (run, model, pairing) = (&mut *self.run, self.model, &mut *self.pairing);
        let ((q, qdot), end) = (&self.at, &self.end);
        // The dense output is built from the step's slopes before the
        // pair moves on (its last slope becomes the next step's first),
        // only when a sample or an event needs it.
        let crossed = if run.rec.watching() {
            let mut interpolant = |ts: S| pairing.dense_at(h, (q, qdot), (ts - t) / h);
            run.rec
                .watch_dense(model, (t, t_new), end, &mut interpolant)?
        } else {
            None
        };
        if crossed.is_none() {
            while let Some(ts) = run.rec.pending().filter(|&ts| ts <= t_new) {
                if ts < t_new {
                    let (qs, qdots) = pairing.dense_at(h, (q, qdot), (ts - t) / h);
                    run.rec.record_dense(model, ts, qs, qdots)?;
                } else {
                    run.rec.record(ts, end.0, end.1);
                }
            }
        }
        pairing.advance();
        let flow = run.take((t_new, end.0, end.1), crossed, target);
        if let Flow::Restarted(true) = flow {
            run.t = target;
        }
        Ok(flow)
    }
}
