//! The workspace of one Radau5 integration and its step loop, RADAU5's
//! `RADCOR`.

use nalgebra::{Complex, DMatrix, DVector, RealField, SVector};

use super::coefficients::Coefficients;
use super::newton::Newton;
use super::{Radau5, FAC_L, FAC_R, KEEP_H, MAX_NEWTON, SAFETY, THETA_REUSE};
use crate::driver::{advances, Recorder, Segment};
use crate::error::{IntegrationError, NonFiniteValue};
use crate::linalg::lu::Lu;
use crate::model::Lagrangian;

/// Everything one integration needs, allocated once in [`Run::new`]: the
/// vectors have `2N` entries (`q` then `q̇`), the matrices `N × N`.
pub(super) struct Run<S: RealField + Copy, const N: usize> {
    pub(super) k: Coefficients<S>,
    /// RADAU5's transformed tolerances (see [`Radau5`]).
    pub(super) rtol: S,
    pub(super) atol: S,
    pub(super) max_steps: usize,
    /// Newton stops when its predicted remaining error is below this (in
    /// units of the tolerance).
    pub(super) fnewt: S,
    /// The state at `t` and its derivative `(q̇, q̈)` there.
    pub(super) y: DVector<S>,
    pub(super) f0: DVector<S>,
    /// `atol' + rtol' |y|` at the start of the step.
    pub(super) scal: DVector<S>,
    /// Stage increments `Zᵢ = Yᵢ − y`; during an iteration, the stage
    /// derivatives and then the Newton corrections.
    pub(super) z: [DVector<S>; 3],
    /// The increments in eigen-coordinates, `W = (T⁻¹ ⊗ I) Z`.
    pub(super) w: [DVector<S>; 3],
    /// The collocation polynomial of the last accepted step (its value at
    /// the end is `y`).
    pub(super) cont: [DVector<S>; 3],
    /// Scratch: a stage state, the error estimate and its right-hand side.
    pub(super) stage: DVector<S>,
    pub(super) err: DVector<S>,
    pub(super) err_rhs: DVector<S>,
    /// `∂q̈/∂q` and `∂q̈/∂q̇` at the state of the last Jacobian evaluation.
    pub(super) jq: DMatrix<S>,
    pub(super) jv: DMatrix<S>,
    /// Factors of `γ̂/h I − ∂q̈/∂q̇ − h/γ̂ ∂q̈/∂q` (the real block) and of the
    /// same with `(α̂ + iβ̂)/h` (the complex block).
    pub(super) real: Lu<S>,
    pub(super) complex: Lu<Complex<S>>,
    pub(super) real_work: DVector<S>,
    pub(super) complex_rhs: DVector<Complex<S>>,
    pub(super) complex_work: DVector<Complex<S>>,
}

impl<S: RealField + Copy, const N: usize> Run<S, N> {
    pub(super) fn new(settings: &Radau5<S>, q0: &SVector<S, N>, qdot0: &SVector<S, N>) -> Self {
        let c = |x: f64| -> S { nalgebra::convert(x) };
        let rtol = c(0.1) * settings.rtol.powf(c(2.0 / 3.0));
        let atol = rtol * (settings.atol / settings.rtol);
        let eps = S::default_epsilon();
        let fnewt = (c(10.0) * eps / rtol).max(c(0.03).min(rtol.sqrt()));
        let vector = || DVector::<S>::zeros(2 * N);
        let mut y = vector();
        y.rows_mut(0, N).copy_from(q0);
        y.rows_mut(N, N).copy_from(qdot0);
        Self {
            k: Coefficients::new(),
            rtol,
            atol,
            max_steps: settings.max_steps,
            fnewt,
            y,
            f0: vector(),
            scal: vector(),
            z: [vector(), vector(), vector()],
            w: [vector(), vector(), vector()],
            cont: [vector(), vector(), vector()],
            stage: vector(),
            err: vector(),
            err_rhs: vector(),
            jq: DMatrix::zeros(N, N),
            jv: DMatrix::zeros(N, N),
            real: Lu::new(N),
            complex: Lu::new(N),
            real_work: DVector::zeros(N),
            complex_rhs: DVector::zeros(2 * N),
            complex_work: DVector::zeros(N),
        }
    }

    /// RADAU5's `RADCOR`: the step loop from `t0` to `t_end`, recording the
    /// samples on the way, or to an event that stops the run or resets it.
    pub(super) fn integrate<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        model: &L,
        rec: &mut Recorder<'_, S, N>,
        t0: S,
        t_end: S,
    ) -> Result<Segment<S, N>, IntegrationError<S, N>> {
        let c = |x: f64| -> S { nalgebra::convert(x) };
        let (safety, fac_l, fac_r) = (c(SAFETY), c(FAC_L), c(FAC_R));
        let theta_reuse = c(THETA_REUSE);
        // The controller trusts a step less the more Newton iterations it took.
        let cfac = safety * c((1 + 2 * MAX_NEWTON) as f64);
        let half = c(0.5);

        let mut t = t0;
        evaluate(rec, model, t, &self.y, &mut self.f0)?;
        self.update_scale();
        let h_max = rec.bound_step(t_end - t0);
        let mut h = self.initial_step(h_max);
        let mut last = false;
        if t + h * c(1.0001) >= t_end {
            h = t_end - t;
            last = true;
        }
        // The previous accepted step, for the Newton starting values.
        let mut h_old = h;
        // No step accepted yet: Newton starts from zero and a rejection cuts
        // h tenfold.
        let mut first = true;
        let mut rejected_last = false;
        // Whether the Jacobian in use was evaluated at the current state.
        let mut fresh_jacobian = false;
        let (mut need_jacobian, mut need_factors) = (true, true);
        let mut faccon = S::one();
        let mut theta = theta_reuse;
        // Step and error of the last accepted step (Gustafsson).
        let (mut h_acc, mut err_acc) = (h, c(1e-2));
        // The evaluation failure that made us shrink h, reported if h
        // underflows before we get past it.
        let mut stage_failure = None;

        loop {
            let attempts = rec.stats.steps_accepted + rec.stats.steps_rejected;
            if attempts >= self.max_steps {
                let (q, qdot) = split(&self.y);
                let max_steps = self.max_steps;
                return Err(IntegrationError::TooManySteps {
                    t,
                    max_steps,
                    q,
                    qdot,
                });
            }
            if !advances(t, h) {
                let (q, qdot) = split(&self.y);
                return Err(stage_failure
                    .take()
                    .unwrap_or(IntegrationError::StepSizeUnderflow { t, h, q, qdot }));
            }
            if need_jacobian {
                self.jacobian(model, rec, t)?;
                fresh_jacobian = true;
                need_jacobian = false;
                need_factors = true;
            }
            // Every rejection, whatever its cause: retry from the same state
            // with step `$h`, with a Jacobian evaluated here (RADAU5 keeps an
            // old one only while steps succeed).
            macro_rules! retry_with {
                ($h:expr) => {{
                    h = $h;
                    rec.stats.steps_rejected += 1;
                    rejected_last = true;
                    last = false;
                    need_jacobian = !fresh_jacobian;
                    need_factors = true;
                    continue;
                }};
            }
            if need_factors {
                if self.factor(h).is_err() {
                    retry_with!(h * half);
                }
                need_factors = false;
            }

            let t_new = if last { t_end } else { t + h };
            // The representable step, as in the adaptive driver: the state
            // advances by exactly the time the clock does. (The LU factors,
            // made for the `h` before this rounding, differ by `ε t / h`
            // relative: simplified Newton does not notice.)
            h = t_new - t;
            self.starting_values(first, h / h_old);
            let newton = self.newton(model, rec, t, t_new, h, &mut faccon, &mut theta);
            let iterations = match newton {
                Newton::Converged(iterations) => iterations,
                Newton::TooSlow(factor) => retry_with!(h * factor),
                Newton::Diverged => retry_with!(h * half),
                Newton::StageFailed(error) => {
                    stage_failure = Some(error);
                    retry_with!(h * half)
                }
            };

            let refine = first || rejected_last;
            let Some(err) = self.estimate_error(model, rec, t, h, refine) else {
                // Finite stages, non-finite error: an overflow in the sums.
                self.stage.copy_from(&self.y);
                self.stage += &self.z[2];
                let (q, qdot) = split(&self.stage);
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
                retry_with!(if first { h * c(0.1) } else { h_new });
            }

            rec.stats.steps_accepted += 1;
            first = false;
            stage_failure = None;
            // Gustafsson's predictive controller: also look at how the error
            // changed since the last accepted step.
            if rec.stats.steps_accepted > 1 {
                let gus = (h_acc / h) * (err * err / err_acc).powf(c(0.25)) / safety;
                quot = quot.max(fac_r.max(fac_l.min(gus)));
                h_new = h / quot;
            }
            (h_acc, err_acc) = (h, err.max(c(1e-2)));
            h_old = h;
            self.accept();
            self.control_drift(model, rec, t_new)?;
            if rec.watching() {
                let end = split(&self.y);
                let interpolant = |ts: S| self.dense((ts - t_new) / h);
                if let Some(end) = rec.watch_dense(model, (t, t_new), &end, interpolant)? {
                    return Ok(end);
                }
            }
            self.record(model, rec, t_new, h)?;
            if last {
                return Ok(Segment::Done);
            }
            t = t_new;
            evaluate(rec, model, t, &self.y, &mut self.f0)?;
            fresh_jacobian = false;

            h_new = h_new.min(h_max);
            if rejected_last {
                h_new = h_new.min(h);
            }
            rejected_last = false;
            let reuse_jacobian = theta <= theta_reuse;
            if t + h_new >= t_end {
                h = t_end - t;
                last = true;
                (need_jacobian, need_factors) = (!reuse_jacobian, true);
            } else {
                let ratio = h_new / h;
                let keep_h = ratio >= c(KEEP_H.0) && ratio <= c(KEEP_H.1);
                if !(reuse_jacobian && keep_h) {
                    h = h_new;
                    (need_jacobian, need_factors) = (!reuse_jacobian, true);
                }
            }
        }
    }

    /// The scale-free first guess of Hairer's `hinit`: 1 % of the time in
    /// which `y` would change by its own size. (RADAU5 leaves the first step
    /// to the caller; a guess too large is cut tenfold by the first-step
    /// rule, one too small grows up to 8× per step.)
    fn initial_step(&self, h_max: S) -> S {
        let c = |x: f64| -> S { nalgebra::convert(x) };
        let (mut dny, mut dnf) = (S::zero(), S::zero());
        for i in 0..2 * N {
            dny += (self.y[i] / self.scal[i]).powi(2);
            dnf += (self.f0[i] / self.scal[i]).powi(2);
        }
        let h0 = (dny / dnf).sqrt() * c(0.01);
        // y or ẏ negligible, or a norm overflowing (a tiny atol): RADAU5's
        // default first step.
        let degenerate = dnf <= c(1e-10) || dny <= c(1e-10) || !(h0.is_finite() && h0 > S::zero());
        if degenerate { c(1e-6) } else { h0 }.min(h_max)
    }

    pub(super) fn update_scale(&mut self) {
        for (s, y) in self.scal.iter_mut().zip(self.y.iter()) {
            *s = self.atol + self.rtol * y.abs();
        }
    }
}

/// `ẏ = (q̇, q̈)` at `(t, y)` into `out`: one counted right-hand side.
pub(super) fn evaluate<L: Lagrangian<N>, const N: usize>(
    rec: &mut Recorder<'_, L::Scalar, N>,
    model: &L,
    t: L::Scalar,
    y: &DVector<L::Scalar>,
    out: &mut DVector<L::Scalar>,
) -> Result<(), IntegrationError<L::Scalar, N>> {
    let (q, qdot) = split(y);
    let qddot = rec.rhs(model, t, &q, &qdot)?;
    out.rows_mut(0, N).copy_from(&qdot);
    out.rows_mut(N, N).copy_from(&qddot);
    Ok(())
}

/// `(q, q̇)` from a `2N` state vector.
pub(super) fn split<S: RealField + Copy, const N: usize>(
    y: &DVector<S>,
) -> (SVector<S, N>, SVector<S, N>) {
    (
        SVector::from_fn(|i, _| y[i]),
        SVector::from_fn(|i, _| y[N + i]),
    )
}
