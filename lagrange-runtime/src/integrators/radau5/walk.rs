//! Radau5's step loop, RADAU5's `RADCOR`, made resumable: the run loop of
//! the implicit adaptive kind, driven by `integrate` to the last sample
//! time and by a [`Stepper`](crate::stepper::Stepper) frame by frame.

use nalgebra::RealField;

use super::newton::Newton;
use super::work::{Work, evaluate, split};
use super::{FAC_L, FAC_R, KEEP_H, MAX_NEWTON, Radau5, SAFETY, THETA_REUSE};
use crate::driver::advances;
use crate::driver::run::{Advanced, Flow, Fresh, Run, Walk};
use crate::error::{IntegrationError, NonFiniteValue};
use crate::model::Lagrangian;

/// Radau5's work between steps: the workspace (allocated once, in
/// [`Radau5Walk::new`]) and RADCOR's loop variables.
pub struct Radau5Walk<S: RealField + Copy, const N: usize> {
    work: Work<S, N>,
    max_steps: usize,
    h: S,
    /// The step size proposed by the last accepted step and whether its
    /// Jacobian may be kept, not yet placed against a target (RADCOR places
    /// it at once against `t_end`; here it waits for the next step, whose
    /// target a stepper's next frame may have moved).
    proposed: Option<(S, bool)>,
    /// `h` bounded by the target and the events' `max_step`, as at the
    /// segment's start.
    h_max: S,
    /// The step ends at the target.
    last: bool,
    /// The previous accepted step, for the Newton starting values.
    h_old: S,
    /// No step accepted yet: Newton starts from zero and a rejection cuts
    /// `h` tenfold.
    first: bool,
    rejected_last: bool,
    /// Whether the Jacobian in use was evaluated at the current state.
    fresh_jacobian: bool,
    need_jacobian: bool,
    need_factors: bool,
    /// `f0` holds `ẏ` at the current state (it is evaluated when the next
    /// step needs it, not after the last step of a run).
    slope: bool,
    faccon: S,
    theta: S,
    /// Step and error of the last accepted step (Gustafsson).
    h_acc: S,
    err_acc: S,
}

impl<S: RealField + Copy, const N: usize> Radau5Walk<S, N> {
    pub(super) fn new(settings: &Radau5<S>) -> Self {
        let zero = S::zero();
        Self {
            work: Work::new(settings),
            max_steps: settings.max_steps,
            h: zero,
            proposed: None,
            h_max: zero,
            last: false,
            h_old: zero,
            first: true,
            rejected_last: false,
            fresh_jacobian: false,
            need_jacobian: true,
            need_factors: true,
            slope: false,
            faccon: S::one(),
            theta: nalgebra::convert(THETA_REUSE),
            h_acc: zero,
            err_acc: nalgebra::convert(1e-2),
        }
    }

    /// RADCOR's end of an accepted step: the proposed `h_new` placed
    /// against `target`, landing on it when it would reach it, else kept
    /// or taken as the Jacobian and the step-size ratio allow.
    fn place(&mut self, t: S, h_new: S, reuse_jacobian: bool, target: S) {
        let c = |x: f64| -> S { nalgebra::convert(x) };
        if t + h_new >= target {
            self.h = target - t;
            self.last = true;
            (self.need_jacobian, self.need_factors) = (!reuse_jacobian, true);
        } else {
            self.last = false;
            let ratio = h_new / self.h;
            let keep_h = ratio >= c(KEEP_H.0) && ratio <= c(KEEP_H.1);
            if !(reuse_jacobian && keep_h) {
                self.h = h_new;
                (self.need_jacobian, self.need_factors) = (!reuse_jacobian, true);
            }
            // A step that would stop a few ulps short of the target (a
            // kept `h` as long as the last frame, from a time that rounds)
            // would leave a sliver no step can take: land on it now.
            let end = t + self.h;
            if end < target && !advances(end, target - end) {
                self.h = target - t;
                self.last = true;
                self.need_factors = true;
            }
        }
    }
}

impl<S: RealField + Copy, const N: usize> Walk<S, N> for Radau5Walk<S, N> {
    fn advance<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        run: &mut Run<'_, S, N>,
        model: &L,
        target: S,
    ) -> Result<Advanced, IntegrationError<S, N>> {
        let c = |x: f64| -> S { nalgebra::convert(x) };
        let (safety, fac_l, fac_r) = (c(SAFETY), c(FAC_L), c(FAC_R));
        let theta_reuse = c(THETA_REUSE);
        // The controller trusts a step less the more Newton iterations it took.
        let cfac = safety * c((1 + 2 * MAX_NEWTON) as f64);
        let half = c(0.5);
        // The evaluation failure that made us shrink h, reported if h
        // underflows before we get past it.
        let mut stage_failure = None;

        loop {
            if run.t >= target {
                return Ok(Advanced::Reached);
            }
            let t = run.t;
            if run.fresh != Fresh::No {
                run.arm()?;
                self.work.load(&run.q, &run.qdot);
                evaluate(&mut run.rec, model, t, &self.work.y, &mut self.work.f0)?;
                self.work.update_scale();
                self.slope = true;
                self.h_max = run.rec.bound_step(target - t);
                let segment = run.fresh == Fresh::Segment || self.h == S::zero();
                if segment {
                    self.h = self.work.initial_step(self.h_max);
                    self.faccon = S::one();
                    self.theta = theta_reuse;
                }
                self.proposed = None;
                self.last = false;
                if t + self.h * c(1.0001) >= target {
                    self.h = target - t;
                    self.last = true;
                }
                if segment {
                    (self.h_acc, self.err_acc) = (self.h, c(1e-2));
                }
                self.h_old = self.h;
                self.first = true;
                self.rejected_last = false;
                self.fresh_jacobian = false;
                (self.need_jacobian, self.need_factors) = (true, true);
                run.fresh = Fresh::No;
            }
            if !self.slope {
                evaluate(&mut run.rec, model, t, &self.work.y, &mut self.work.f0)?;
                self.fresh_jacobian = false;
                self.slope = true;
            }
            if let Some((h_new, reuse)) = self.proposed.take() {
                self.place(t, h_new, reuse, target);
            }

            if run.steps_this_call().1 >= self.max_steps {
                let (q, qdot) = split(&self.work.y);
                let max_steps = self.max_steps;
                return Err(IntegrationError::TooManySteps {
                    t,
                    max_steps,
                    q,
                    qdot,
                });
            }
            let h = self.h;
            if !advances(t, h) {
                let (q, qdot) = split(&self.work.y);
                return Err(stage_failure
                    .take()
                    .unwrap_or(IntegrationError::StepSizeUnderflow { t, h, q, qdot }));
            }
            if self.need_jacobian {
                self.work.jacobian(model, &mut run.rec, t)?;
                self.fresh_jacobian = true;
                self.need_jacobian = false;
                self.need_factors = true;
            }
            // Every rejection, whatever its cause: retry from the same state
            // with step `$h`, with a Jacobian evaluated here (RADAU5 keeps an
            // old one only while steps succeed).
            macro_rules! retry_with {
                ($h:expr) => {{
                    self.h = $h;
                    run.rec.stats.steps_rejected += 1;
                    self.rejected_last = true;
                    self.last = false;
                    self.need_jacobian = !self.fresh_jacobian;
                    self.need_factors = true;
                    continue;
                }};
            }
            if self.need_factors {
                if self.work.factor(h).is_err() {
                    retry_with!(h * half);
                }
                self.need_factors = false;
            }

            let t_new = if self.last { target } else { t + h };
            // The representable step: the state advances by exactly the
            // time the clock does. (The LU factors, made for the `h` before
            // this rounding, differ by `ε t / h` relative: simplified Newton
            // does not notice.)
            let h = t_new - t;
            self.h = h;
            self.work.starting_values(self.first, h / self.h_old);
            let newton = self.work.newton(
                model,
                &mut run.rec,
                t,
                t_new,
                h,
                &mut self.faccon,
                &mut self.theta,
            );
            let iterations = match newton {
                Newton::Converged(iterations) => iterations,
                Newton::TooSlow(factor) => retry_with!(h * factor),
                Newton::Diverged => retry_with!(h * half),
                Newton::StageFailed(error) => {
                    stage_failure = Some(error);
                    retry_with!(h * half)
                }
            };

            let refine = self.first || self.rejected_last;
            let Some(err) = self.work.estimate_error(model, &mut run.rec, t, h, refine) else {
                // Finite stages, non-finite error: an overflow in the sums.
                self.work.stage.copy_from(&self.work.y);
                self.work.stage += &self.work.z[2];
                let (q, qdot) = split(&self.work.stage);
                let value = NonFiniteValue::State;
                stage_failure = Some(IntegrationError::NonFiniteState {
                    t: t_new,
                    q,
                    qdot,
                    value,
                });
                retry_with!(h * half)
            };

            // h_new = h · fac / err^(1/4), fac lower after many iterations.
            let fac = safety.min(cfac / c((iterations + 2 * MAX_NEWTON) as f64));
            let mut quot = fac_r.max(fac_l.min(err.powf(c(0.25)) / fac));
            let mut h_new = h / quot;
            if err >= S::one() {
                retry_with!(if self.first { h * c(0.1) } else { h_new });
            }

            run.rec.stats.steps_accepted += 1;
            self.first = false;
            stage_failure = None;
            // Gustafsson's predictive controller: also look at how the error
            // changed since the last accepted step.
            if run.rec.stats.steps_accepted > 1 {
                let gus = (self.h_acc / h) * (err * err / self.err_acc).powf(c(0.25)) / safety;
                quot = quot.max(fac_r.max(fac_l.min(gus)));
                h_new = h / quot;
            }
            (self.h_acc, self.err_acc) = (h, err.max(c(1e-2)));
            self.h_old = h;
            self.work.accept();
            self.work.control_drift(model, &mut run.rec, t_new)?;
            let end = split(&self.work.y);
            let crossed = if run.rec.watching() {
                let work = &self.work;
                let mut interpolant = |ts: S| work.dense((ts - t_new) / h);
                run.rec
                    .watch_dense(model, (t, t_new), &end, &mut interpolant)?
            } else {
                None
            };
            if crossed.is_none() {
                self.work.record(model, &mut run.rec, t_new, h)?;
            }
            self.slope = false;
            h_new = h_new.min(self.h_max);
            if self.rejected_last {
                h_new = h_new.min(h);
            }
            self.rejected_last = false;
            self.proposed = Some((h_new, self.theta <= theta_reuse));
            match run.take((t_new, end.0, end.1), crossed, target) {
                Flow::Go => {}
                Flow::Stopped => return Ok(Advanced::Stopped),
                Flow::Rebuild => return Ok(Advanced::Rebuild),
                Flow::Restarted(true) => {
                    run.t = target;
                    return Ok(Advanced::Reached);
                }
                Flow::Restarted(false) => {}
            }
        }
    }
}
