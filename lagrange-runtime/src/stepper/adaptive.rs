//! An explicit embedded pair in a stepper: the adaptive driver's step
//! loop ([`adaptive`](crate::driver::adaptive)), resumable. The step size
//! and the error history are kept from call to call; a step that would
//! cross the call's target is shortened to land on it, and the next call
//! starts again from the step size the control had chosen.

use nalgebra::{RealField, SVector};

use super::sealed::{Run, Work};
use crate::driver::{
    advances, initial_step, Controller, EmbeddedPair, GrowthGuard, Outcome, Segment, Tolerances,
};
use crate::error::IntegrationError;
use crate::model::Lagrangian;

/// How a stepper builds a method's pair from `(q̇, q̈)` at the state.
pub(crate) trait PairOf<S: RealField + Copy, const N: usize> {
    /// The pair.
    type Pair: EmbeddedPair<S, N>;
    /// The pair with its first slope `q̈` at `(q, q̇)`.
    fn pair(&self, qdot: &SVector<S, N>, qddot: &SVector<S, N>) -> Self::Pair;
}

/// An adaptive method's side of a stepper.
pub struct AdaptiveWork<S: RealField + Copy, M: PairOf<S, N>, const N: usize> {
    pub(super) method: M,
    pub(super) control: &'static Controller,
    pub(super) settings: Tolerances<S>,
    /// Built (and rebuilt, when the model or the state changes) from the
    /// slope at the state.
    pub(super) pair: Option<M::Pair>,
    /// The step size the control chose; `None` before the first step.
    pub(super) h: Option<S>,
    pub(super) err_old: S,
    pub(super) rejected_last: bool,
    pub(super) growth: Option<GrowthGuard<S>>,
}

impl<S, M, const N: usize> Work<S, N> for AdaptiveWork<S, M, N>
where
    S: RealField + Copy,
    M: PairOf<S, N>,
{
    fn advance<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        run: &mut Run<'_, S, N>,
        model: &L,
        target: S,
    ) -> Result<(), IntegrationError<S, N>> {
        let c = |x: f64| -> S { nalgebra::convert(x) };
        let control = self.control;
        let Tolerances {
            rtol,
            atol,
            max_steps,
        } = self.settings;
        let gains = control.gains::<S>();

        let mut attempts = 0;
        let mut stage_failure = None;
        loop {
            // A first call, a changed model or state, or a reset: the slope
            // the pair carries is recomputed at the state (the step size is
            // kept, or guessed on the first call).
            if run.stale || self.pair.is_none() {
                let (t, (q, qdot)) = (run.t, run.state());
                let qddot = run.rec.rhs(model, t, &q, &qdot)?;
                if self.h.is_none() {
                    let start = (t, &q, &qdot, &qddot);
                    let h_max = run.rec.bound_step(target - t);
                    let guess =
                        initial_step(&mut run.rec, model, start, h_max, rtol, atol, control.order);
                    self.h = Some(guess);
                }
                self.pair = Some(self.method.pair(&qdot, &qddot));
                self.growth
                    .get_or_insert_with(|| GrowthGuard::new(&q, &qdot));
                run.stale = false;
            }
            let (Some(pair), Some(h), Some(growth)) = (&mut self.pair, self.h, &mut self.growth)
            else {
                unreachable!("built above");
            };
            let mut h = run.rec.bound_step(h);
            let (t, (q, qdot)) = (run.t, run.state());
            if attempts >= max_steps {
                return Err(IntegrationError::TooManySteps {
                    t,
                    max_steps,
                    q,
                    qdot,
                });
            }
            attempts += 1;
            if !advances(t, h) {
                return Err(stage_failure
                    .take()
                    .unwrap_or(IntegrationError::StepSizeUnderflow { t, h, q, qdot }));
            }
            // Land on the target rather than leave a sliver before it.
            let last = t + h * c(control.stretch) >= target;
            let h_try = if last { target - t } else { h };
            let t_new = if last { target } else { t + h_try };
            // The representable step, as in the adaptive driver.
            let h_try = t_new - t;

            let (step, err) =
                match pair.attempt(&mut run.rec, model, (t, t_new, h_try), (&q, &qdot)) {
                    Ok(Outcome::Accepted { step, err }) => (step, err),
                    Ok(Outcome::Rejected { err }) => {
                        run.rec.stats.steps_rejected += 1;
                        self.rejected_last = true;
                        h = gains.after_rejection(h_try, err);
                        self.h = Some(h);
                        continue;
                    }
                    Err(error) => {
                        stage_failure = Some(error);
                        run.rec.stats.steps_rejected += 1;
                        self.rejected_last = true;
                        h = h_try * gains.fac_min;
                        self.h = Some(h);
                        continue;
                    }
                };
            let mut h_new = gains.after_acceptance(h_try, err, self.err_old);
            if self.rejected_last {
                h_new = h_new.min(h_try);
            }
            // A step shortened to land on the target says little about the
            // step the solution allows: keep the one the control had chosen
            // if the shortened step's proposal is smaller.
            if last && h_try < h {
                h_new = h_new.max(h);
            }
            self.err_old = err.max(c(1e-4));
            self.rejected_last = false;
            stage_failure = None;

            let (q_end, qdot_end) = <M::Pair as EmbeddedPair<S, N>>::end(&step);
            let (q_new, qdot_new) = run.rec.control_drift(model, t_new, q_end, qdot_end)?;
            if let Some(steps) = growth.unstable((q, qdot), (&q_new, &qdot_new), h_try) {
                return Err(IntegrationError::Unstable {
                    t: t_new,
                    h: h_try,
                    steps,
                    q: q_new,
                    qdot: qdot_new,
                });
            }
            run.rec.stats.steps_accepted += 1;
            self.h = Some(h_new);
            // The dense output is built from the step's slopes before the
            // pair moves on (its last slope becomes the next step's first).
            let crossed = if run.rec.watching() {
                let dense = pair.dense(h_try, (&q, &qdot), &step);
                let interpolant = |ts: S| M::Pair::dense_at(&dense, (ts - t) / h_try);
                let end = (q_new, qdot_new);
                run.rec.watch_dense(model, (t, t_new), &end, interpolant)?
            } else {
                None
            };
            pair.advance(&step);
            let restarted = matches!(crossed, Some(Segment::Restart { .. }));
            if run.take((t_new, q_new, qdot_new), crossed)? {
                return Ok(());
            }
            // A reset a few ulps before the target: too close to step to,
            // the call ends there with the state after the reset.
            if restarted && !advances(run.t, target - run.t) {
                run.t = target;
            }
            if run.t >= target {
                return Ok(());
            }
        }
    }
}
