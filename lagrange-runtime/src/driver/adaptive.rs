//! The adaptive driver of the explicit embedded pairs ([`Dopri5`] and
//! [`Dop853`]): Hairer's step loop with its stabilized step-size control,
//! the step budget, the underflow check, and samples from the continuous
//! extension, so that the methods only supply their stages, error estimate
//! and dense output.
//!
//! [`Dopri5`]: crate::integrators::Dopri5
//! [`Dop853`]: crate::integrators::Dop853

use nalgebra::{RealField, SVector};

use super::growth::GrowthGuard;
use super::record::Recorder;
use super::segments::{segments, Segment};
use super::step_control::{advances, initial_step};
use super::validate::{check_tolerances, invalid};
use crate::error::{IntegrationError, IntegrationResult};
use crate::events::Events;
use crate::model::Lagrangian;
use crate::trajectory::State;

/// A step-size controller's constants, as Hairer's codes set them:
/// `h_new = h · safety · err^(−α) · err_old^β`, the ratio `h_new / h` kept
/// within `[fac_min, fac_max]`, with `α = exponent − β · beta_weight`.
pub(crate) struct Controller {
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
pub(crate) struct Gains<S> {
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

/// The settings every adaptive method has.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Tolerances<S> {
    pub(crate) rtol: S,
    pub(crate) atol: S,
    pub(crate) max_steps: usize,
}

/// How an attempted step ended, short of a model failure.
pub(crate) enum Outcome<S, Step> {
    /// The error estimate `err` exceeds the tolerance.
    Rejected { err: S },
    /// The step passed the error test with estimate `err`.
    Accepted { step: Step, err: S },
}

/// What an explicit embedded Runge–Kutta pair supplies to [`adaptive`]: one
/// value per integration, holding the tableau and the slopes it carries
/// from step to step (first same as last).
pub(crate) trait EmbeddedPair<S: RealField + Copy, const N: usize> {
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

/// Integrates `model` with the pair made by `pair` from `(q̇0, q̈0)`:
/// validation, Hairer's initial step, then attempts until the last sample
/// time, with the step size controlled by `control`. After a reset by an
/// event, a new pair from the new state, and a new initial step
/// ([`segments`]).
///
/// A stage where the model cannot be evaluated rejects the step and retries
/// with `fac_min` of it, so a model that breaks down at `t*` is integrated up
/// to `t*`; if `h` then underflows, that failure is the error reported.
///
/// Accepted steps are watched by the fixed-step driver's growth guard: at
/// everyday tolerances the error control keeps an explicit step within its
/// stability region and the guard never fires, but a tolerance loose enough
/// (`rtol` near 1 or above, or `atol` above the solution's size) accepts
/// steps that blow the solution up, which would otherwise end in a
/// misleading underflow or overflow; it ends in
/// [`Unstable`](IntegrationError::Unstable), as for a fixed step beyond its
/// limit.
#[allow(clippy::too_many_arguments)]
pub(crate) fn adaptive<S, L, P, const N: usize>(
    control: &Controller,
    settings: Tolerances<S>,
    model: &L,
    t0: S,
    q0: SVector<S, N>,
    qdot0: SVector<S, N>,
    times: &[S],
    events: &Events<'_, S, N>,
    pair: impl Fn(&SVector<S, N>, &SVector<S, N>) -> P,
) -> IntegrationResult<S, N>
where
    S: RealField + Copy,
    L: Lagrangian<N, Scalar = S>,
    P: EmbeddedPair<S, N>,
{
    check_tolerances(settings.rtol, settings.atol).map_err(invalid)?;
    segments(model, t0, q0, qdot0, times, events, |rec, t, state| {
        segment(control, settings, rec, model, (t, state), &pair)
    })
}

/// One segment of [`adaptive`]: from `(t0, q0, q̇0)`, with its own first
/// slope and initial step, to the last sample time or to an event that
/// stops the run or resets its state.
fn segment<S, L, P, const N: usize>(
    control: &Controller,
    settings: Tolerances<S>,
    rec: &mut Recorder<'_, S, N>,
    model: &L,
    (t0, (q0, qdot0)): (S, State<S, N>),
    pair: &impl Fn(&SVector<S, N>, &SVector<S, N>) -> P,
) -> Result<Segment<S, N>, IntegrationError<S, N>>
where
    S: RealField + Copy,
    L: Lagrangian<N, Scalar = S>,
    P: EmbeddedPair<S, N>,
{
    let Tolerances {
        rtol,
        atol,
        max_steps,
    } = settings;
    let (Some(_), Some(t_end)) = (rec.pending(), rec.end()) else {
        return Ok(Segment::Done);
    };

    let c = |x: f64| -> S { nalgebra::convert(x) };
    let gains = control.gains::<S>();

    let (mut t, mut q, mut qdot) = (t0, q0, qdot0);
    let qddot = rec.rhs(model, t, &q, &qdot)?;
    let h_max = rec.bound_step(t_end - t0);
    let start = (t, &q, &qdot, &qddot);
    let mut h = initial_step(rec, model, start, h_max, rtol, atol, control.order);
    let mut pair = pair(&qdot, &qddot);

    let mut growth = GrowthGuard::new(&q0, &qdot0);
    let mut err_old = c(1e-4);
    let mut rejected_last = false;
    // The evaluation failure that made us shrink h, reported if h
    // underflows before we get past it.
    let mut stage_failure = None;

    loop {
        let attempts = rec.stats.steps_accepted + rec.stats.steps_rejected;
        if attempts >= max_steps {
            return Err(IntegrationError::TooManySteps {
                t,
                max_steps,
                q,
                qdot,
            });
        }
        if !advances(t, h) {
            return Err(stage_failure
                .take()
                .unwrap_or(IntegrationError::StepSizeUnderflow { t, h, q, qdot }));
        }
        // Stretch a step that would stop just short of the end, so the last
        // step is not a sliver.
        let last = t + h * c(control.stretch) >= t_end;
        if last {
            h = t_end - t;
        }
        let t_new = if last { t_end } else { t + h };
        // The state advances by exactly the time the clock does: `t + h`
        // rounds, so the step taken is the representable `fl(t + h) − t`
        // (else the clock drifts from the state by up to half an ulp of `t`
        // per step, 1e-10 s after 5e5 steps at t ≈ 70).
        h = t_new - t;

        let (step, err) = match pair.attempt(rec, model, (t, t_new, h), (&q, &qdot)) {
            Ok(Outcome::Accepted { step, err }) => (step, err),
            Ok(Outcome::Rejected { err }) => {
                rec.stats.steps_rejected += 1;
                rejected_last = true;
                h = gains.after_rejection(h, err);
                continue;
            }
            Err(error) => {
                stage_failure = Some(error);
                rec.stats.steps_rejected += 1;
                rejected_last = true;
                h *= gains.fac_min;
                continue;
            }
        };

        let mut h_new = gains.after_acceptance(h, err, err_old).min(h_max);
        if rejected_last {
            h_new = h_new.min(h);
        }
        err_old = err.max(c(1e-4));
        rec.stats.steps_accepted += 1;
        rejected_last = false;
        stage_failure = None;

        // A constrained model's end state is projected; the pair keeps its
        // last slope, evaluated before that (see `constraints`).
        let (q_end, qdot_end) = P::end(&step);
        let (q_new, qdot_new) = rec.control_drift(model, t_new, q_end, qdot_end)?;
        if let Some(steps) = growth.unstable((q, qdot), (&q_new, &qdot_new), h) {
            let (t, q, qdot) = (t_new, q_new, qdot_new);
            return Err(IntegrationError::Unstable {
                t,
                h,
                steps,
                q,
                qdot,
            });
        }
        let mut dense = None;
        if rec.watching() {
            let dense = &*dense.get_or_insert_with(|| pair.dense(h, (&q, &qdot), &step));
            let interpolant = |ts: S| P::dense_at(dense, (ts - t) / h);
            let end = (q_new, qdot_new);
            if let Some(end) = rec.watch_dense(model, (t, t_new), &end, interpolant)? {
                return Ok(end);
            }
        }
        while let Some(ts) = rec.pending().filter(|&ts| ts <= t_new) {
            if ts < t_new {
                let dense = dense.get_or_insert_with(|| pair.dense(h, (&q, &qdot), &step));
                let (qs, qdots) = P::dense_at(dense, (ts - t) / h);
                rec.record_dense(model, ts, qs, qdots)?;
            } else {
                rec.record(ts, q_new, qdot_new);
            }
        }
        if last {
            return Ok(Segment::Done);
        }
        (t, q, qdot) = (t_new, q_new, qdot_new);
        pair.advance(&step);
        h = h_new;
    }
}
