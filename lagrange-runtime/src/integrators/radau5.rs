//! Radau IIA of order 5: adaptive, implicit, L-stable, for stiff models.
//!
//! Follows Hairer's RADAU5 (Hairer & Wanner, *Solving Ordinary Differential
//! Equations II*, §IV.8, and the Fortran code `radau5.f`): simplified Newton
//! on the stage system transformed by the eigenvectors of `A⁻¹` (one real and
//! one complex linear system per iteration instead of one three times the
//! size), the embedded error estimate with its refinement on a first or
//! rejected step, Gustafsson's predictive step-size controller, Jacobian and
//! LU reuse, and the collocation polynomial as dense output.
//!
//! One change of form, not of method: the linear systems use the
//! second-order structure of `y = (q, q̇)`, as RADAU5 does with its option
//! `M1 = M2 = N`. With `J = [[0, I], [∂q̈/∂q, ∂q̈/∂q̇]]`, the first block row
//! of `(γ I − J) x = b` gives `x_q` from `x_q̇`, so each system is `N × N`:
//! an eighth of the factorization work of the `2N × 2N` one.

use nalgebra::{Complex, DMatrix, DVector, RealField, SVector};

use super::lu::{Lu, Singular};
use super::second_order::{factor_block, solve_block};
use super::{default_tolerance, invalid, Integrator, Recorder};
use crate::jacobian::acceleration_jacobians;
use crate::{IntegrationError, IntegrationResult, InvalidInput, Lagrangian, NonFiniteValue};
use coefficients::Coefficients;

mod coefficients;

/// Radau IIA of order 5 with adaptive steps (three stages, L-stable,
/// stiffly accurate): the method for stiff models, where a hard spring or a
/// strong damper would hold an explicit method to steps far below the time
/// scale of the motion of interest.
///
/// Each step solves the implicit stage equations by simplified Newton with
/// the Jacobians of [`acceleration_jacobians`]: exact when the model provides
/// [`Lagrangian::residual_jacobians`], forward differences (`2N` extra
/// right-hand sides) otherwise. The costs, all counted in
/// [`Stats`](crate::Stats):
///
/// - per Newton iteration: three right-hand sides and one solve of the
///   transformed system (a real and a complex `N × N` triangular solve);
/// - per accepted step: one right-hand side at the new state, one solve for
///   the error estimate (two, and one more right-hand side, when a first or
///   retried step fails the plain estimate);
/// - per new step size: one real and one complex `N × N` LU, `O(N³)`;
/// - per Jacobian: one evaluation, kept across steps while Newton contracts
///   fast (rate below 0.001). When the step size would change by less than
///   20 %, the step size and the LU factors are kept too.
///
/// All vectors and matrices (`O(N²)`) are allocated once per call to
/// [`integrate`](Integrator::integrate); steps allocate nothing.
///
/// **Tolerances** are the user's, as for [`Dopri5`](crate::Dopri5). The
/// error estimate is of order three while the solution is of order five, so
/// RADAU5 controls the local error against `rtol' = 0.1 rtol^(2/3)` (and
/// `atol' = atol rtol'/rtol`), and so do we: the global error then grows
/// like `rtol^(5/6)`, about `rtol` at `1e-4` and `10 rtol` at `1e-10` on a
/// harmonic oscillator over five periods.
///
/// **Sample times** never shorten a step: between steps the state comes
/// from the collocation polynomial, so dense sampling changes neither the
/// steps nor the final state. That polynomial has order three only: its
/// error is of the size of the local error, `rtol'`, above `rtol` at tight
/// tolerances (≈ 100 `rtol` observed at `1e-10`).
///
/// **Stiff components** are damped, not resolved: a vibration much faster
/// than the steps decays in a few steps (L-stability). That is the point
/// for a hard spring whose vibration does not matter; when it does, tighten
/// the tolerance until the steps resolve it, or use `Dopri5`.
///
/// **Failures**: a stage where the model cannot be evaluated, a Newton
/// iteration that diverges or converges too slowly, or a singular iteration
/// matrix reject the step and retry with a smaller one; if `h` underflows
/// the error reported is the last model failure, else
/// [`StepSizeUnderflow`](IntegrationError::StepSizeUnderflow). The
/// derivative and the Jacobians at an accepted state are needed to go on,
/// so a model failure there is reported at once.
///
/// ```
/// use lagrange_runtime::prelude::*;
/// use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
///
/// /// A unit mass on a unit spring in honey: `ẍ = −x − c ẋ`.
/// struct Honey { c: f64 }
/// # impl Lagrangian<1> for Honey {
/// #     type Scalar = f64;
/// #     const COORDINATES: [&'static str; 1] = ["x"];
/// #     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
/// #         SMatrix::<f64, 1, 1>::new(1.0)
/// #     }
/// #     fn forcing(&self, _t: f64, q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> SVector<f64, 1> {
/// #         Vector1::new(-q[0] - self.c * qd[0])
/// #     }
/// #     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 {
/// #         0.5 * qd[0] * qd[0]
/// #     }
/// #     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 {
/// #         0.5 * q[0] * q[0]
/// #     }
/// # }
///
/// // With c = 1000 the mass creeps back as e^(−t/c), but the velocity
/// // relaxes as e^(−c t): explicit methods need h < 3/c for stability.
/// let honey = Honey { c: 1000.0 };
/// let (x0, v0) = (Vector1::new(1.0), Vector1::new(0.0));
/// let radau = Radau5::new().rtol(1e-6).atol(1e-9);
/// let slow = radau.integrate(&honey, 0.0, x0, v0, &[10.0])?;
/// let fast = Dopri5::new().rtol(1e-6).atol(1e-9).integrate(&honey, 0.0, x0, v0, &[10.0])?;
/// assert!(100 * slow.stats().rhs_evals < fast.stats().rhs_evals);
///
/// // Both agree with the creep (x = e^(−t/c) up to O(1/c²) terms).
/// let creep = (-10.0f64 / 1000.0).exp();
/// assert!((slow.last().unwrap().q[0] - creep).abs() < 1e-5);
/// assert!((fast.last().unwrap().q[0] - creep).abs() < 1e-5);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Radau5<S> {
    rtol: S,
    atol: S,
    max_steps: usize,
}

impl<S: RealField + Copy> Radau5<S> {
    /// Defaults as for [`Dopri5`](crate::Dopri5): `rtol = atol = 1e-8`,
    /// raised to `100 ε` for scalar types with fewer digits, and RADAU5's
    /// budget of 100 000 steps.
    pub fn new() -> Self {
        let tol = default_tolerance::<S>();
        Self {
            rtol: tol,
            atol: tol,
            max_steps: 100_000,
        }
    }

    /// Relative tolerance; must be at least `10 ε`.
    pub fn rtol(mut self, rtol: S) -> Self {
        self.rtol = rtol;
        self
    }

    /// Absolute tolerance, the error scale for components near zero; must be
    /// positive.
    pub fn atol(mut self, atol: S) -> Self {
        self.atol = atol;
        self
    }

    /// The step budget, counting every attempt (rejected ones too), so that
    /// every call ends.
    pub fn max_steps(mut self, max_steps: usize) -> Self {
        self.max_steps = max_steps;
        self
    }

    fn validate(&self) -> Result<(), InvalidInput<S>> {
        let (rtol, atol) = (self.rtol, self.atol);
        let min = nalgebra::convert::<f64, S>(10.0) * S::default_epsilon();
        if !(rtol.is_finite() && rtol >= min) {
            return Err(InvalidInput::InvalidRelativeTolerance { rtol, min });
        }
        if !(atol.is_finite() && atol > S::zero()) {
            return Err(InvalidInput::InvalidAbsoluteTolerance { atol });
        }
        Ok(())
    }
}

impl<S: RealField + Copy> Default for Radau5<S> {
    fn default() -> Self {
        Self::new()
    }
}

/// RADAU5's controller and Newton constants.
const SAFETY: f64 = 0.9;
/// `h_new / h ≥ 1 / FAC_L`.
const FAC_L: f64 = 5.0;
/// `h_new / h ≤ 1 / FAC_R`.
const FAC_R: f64 = 0.125;
/// Newton contraction rate below which the Jacobian is kept.
const THETA_REUSE: f64 = 0.001;
/// Keep `h` (and the LU factors) when `h_new / h` falls in this range.
const KEEP_H: (f64, f64) = (1.0, 1.2);
/// Newton iterations per step before the step is retried smaller.
const MAX_NEWTON: usize = 7;
/// Smallest error norm: keeps the Gustafsson ratio finite.
const ERR_FLOOR: f64 = 1e-10;

impl<S: RealField + Copy> Integrator<S> for Radau5<S> {
    fn integrate<L, const N: usize>(
        &self,
        model: &L,
        t0: S,
        q0: SVector<S, N>,
        qdot0: SVector<S, N>,
        times: &[S],
    ) -> IntegrationResult<S, N>
    where
        L: Lagrangian<N, Scalar = S>,
    {
        self.validate().map_err(invalid)?;
        let mut rec = Recorder::start(model, t0, &q0, &qdot0, times)?;
        let (Some(_), Some(t_end)) = (rec.pending(), rec.end()) else {
            return Ok(rec.finish());
        };
        let mut run = Run::<S, N>::new(self, &q0, &qdot0);
        match run.integrate(model, &mut rec, t0, t_end) {
            Ok(()) => Ok(rec.finish()),
            Err(error) => Err(rec.fail(error)),
        }
    }
}

/// Everything one integration needs, allocated once in [`Run::new`]: the
/// vectors have `2N` entries (`q` then `q̇`), the matrices `N × N`.
struct Run<S: RealField + Copy, const N: usize> {
    k: Coefficients<S>,
    /// RADAU5's transformed tolerances (see [`Radau5`]).
    rtol: S,
    atol: S,
    max_steps: usize,
    /// Newton stops when its predicted remaining error is below this (in
    /// units of the tolerance).
    fnewt: S,
    /// The state at `t` and its derivative `(q̇, q̈)` there.
    y: DVector<S>,
    f0: DVector<S>,
    /// `atol' + rtol' |y|` at the start of the step.
    scal: DVector<S>,
    /// Stage increments `Zᵢ = Yᵢ − y`; during an iteration, the stage
    /// derivatives and then the Newton corrections.
    z: [DVector<S>; 3],
    /// The increments in eigen-coordinates, `W = (T⁻¹ ⊗ I) Z`.
    w: [DVector<S>; 3],
    /// The collocation polynomial of the last accepted step (its value at
    /// the end is `y`).
    cont: [DVector<S>; 3],
    /// Scratch: a stage state, the error estimate and its right-hand side.
    stage: DVector<S>,
    err: DVector<S>,
    err_rhs: DVector<S>,
    /// `∂q̈/∂q` and `∂q̈/∂q̇` at the state of the last Jacobian evaluation.
    jq: DMatrix<S>,
    jv: DMatrix<S>,
    /// Factors of `γ̂/h I − ∂q̈/∂q̇ − h/γ̂ ∂q̈/∂q` (the real block) and of the
    /// same with `(α̂ + iβ̂)/h` (the complex block).
    real: Lu<S>,
    complex: Lu<Complex<S>>,
    real_work: DVector<S>,
    complex_rhs: DVector<Complex<S>>,
    complex_work: DVector<Complex<S>>,
}

/// How a Newton iteration ended.
enum Newton<S: RealField + Copy, const N: usize> {
    /// Converged after this many iterations.
    Converged(usize),
    /// Converging, but too slowly to finish in time: retry with `h` times
    /// this factor.
    TooSlow(S),
    /// Diverging, or out of iterations: retry with half the step.
    Diverged,
    /// A stage could not be evaluated: retry with half the step.
    StageFailed(IntegrationError<S, N>),
}

impl<S: RealField + Copy, const N: usize> Run<S, N> {
    fn new(settings: &Radau5<S>, q0: &SVector<S, N>, qdot0: &SVector<S, N>) -> Self {
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
    /// samples on the way.
    fn integrate<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        model: &L,
        rec: &mut Recorder<'_, S, N>,
        t0: S,
        t_end: S,
    ) -> Result<(), IntegrationError<S, N>> {
        let c = |x: f64| -> S { nalgebra::convert(x) };
        let (safety, fac_l, fac_r) = (c(SAFETY), c(FAC_L), c(FAC_R));
        let theta_reuse = c(THETA_REUSE);
        // The controller trusts a step less the more Newton iterations it took.
        let cfac = safety * c((1 + 2 * MAX_NEWTON) as f64);
        let underflow = c(10.0) * S::default_epsilon();
        let half = c(0.5);

        let mut t = t0;
        evaluate(rec, model, t, &self.y, &mut self.f0)?;
        self.update_scale();
        let h_max = t_end - t0;
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
            if h <= underflow * t.abs() || t + h == t {
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
            self.record(rec, t_new, h);
            if last {
                return Ok(());
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

    fn update_scale(&mut self) {
        for (s, y) in self.scal.iter_mut().zip(self.y.iter()) {
            *s = self.atol + self.rtol * y.abs();
        }
    }

    /// `∂q̈/∂q` and `∂q̈/∂q̇` at `(t, y)`, where `f0` holds `ẏ`.
    fn jacobian<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        model: &L,
        rec: &mut Recorder<'_, S, N>,
        t: S,
    ) -> Result<(), IntegrationError<S, N>> {
        let (q, qdot) = split(&self.y);
        let qddot = SVector::<S, N>::from_fn(|i, _| self.f0[N + i]);
        let (jq, jv) = acceleration_jacobians(model, t, &q, &qdot, &qddot, &mut rec.stats)?;
        if !jq.iter().chain(jv.iter()).all(|x| x.is_finite()) {
            let value = NonFiniteValue::Jacobian;
            return Err(IntegrationError::NonFiniteState { t, q, qdot, value });
        }
        self.jq.copy_from(&jq);
        self.jv.copy_from(&jv);
        Ok(())
    }

    /// LU factors of both blocks for step `h`.
    fn factor(&mut self, h: S) -> Result<(), Singular> {
        let real = self.k.gamma / h;
        let complex = Complex::new(self.k.alpha / h, self.k.beta / h);
        factor_block(&mut self.real, &self.jq, &self.jv, real)?;
        factor_block(&mut self.complex, &self.jq, &self.jv, complex)
    }

    /// Newton's starting point: zero before the first accepted step, else
    /// the last step's collocation polynomial extrapolated to the new stages
    /// (`ratio = h / h_old`).
    fn starting_values(&mut self, first: bool, ratio: S) {
        if first {
            for v in self.z.iter_mut().chain(self.w.iter_mut()) {
                v.fill(S::zero());
            }
            return;
        }
        let k = &self.k;
        for i in 0..2 * N {
            let (a1, a2, a3) = (self.cont[0][i], self.cont[1][i], self.cont[2][i]);
            let mut zi = [S::zero(); 3];
            for (z, &c) in zi.iter_mut().zip(&k.c) {
                let s = c * ratio;
                *z = s * (a1 + (s - k.c2m1) * (a2 + (s - k.c1m1) * a3));
            }
            for j in 0..3 {
                self.z[j][i] = zi[j];
                self.w[j][i] = k.ti[j][0] * zi[0] + k.ti[j][1] * zi[1] + k.ti[j][2] * zi[2];
            }
        }
    }

    /// Simplified Newton on the transformed stage equations, from the
    /// starting values; on convergence `z` and `w` hold the stage increments.
    #[allow(clippy::too_many_arguments)]
    fn newton<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        model: &L,
        rec: &mut Recorder<'_, S, N>,
        t: S,
        t_new: S,
        h: S,
        faccon: &mut S,
        theta: &mut S,
    ) -> Newton<S, N> {
        let c = |x: f64| -> S { nalgebra::convert(x) };
        let eps = S::default_epsilon();
        let n2 = 2 * N;
        let (gamma, alpha, beta) = (self.k.gamma / h, self.k.alpha / h, self.k.beta / h);
        *faccon = faccon.max(eps).powf(c(0.8));
        *theta = c(THETA_REUSE);
        let (mut dyno_old, mut thq_old) = (S::one(), S::one());
        let mut iterations = 0;
        loop {
            if iterations >= MAX_NEWTON {
                return Newton::Diverged;
            }
            for i in 0..3 {
                self.stage.copy_from(&self.y);
                self.stage += &self.z[i];
                // The last node is the step end; use it exactly.
                let ti = if i == 2 { t_new } else { t + self.k.c[i] * h };
                if let Err(error) = evaluate(rec, model, ti, &self.stage, &mut self.z[i]) {
                    return Newton::StageFailed(error);
                }
            }
            // Right-hand sides in eigen-coordinates: (T⁻¹ ⊗ I) F − (Λ/h) W.
            let (ti, [z1, z2, z3], [w1, w2, w3]) = (&self.k.ti, &mut self.z, &self.w);
            for i in 0..n2 {
                let f = [z1[i], z2[i], z3[i]];
                let r = ti.map(|row| row[0] * f[0] + row[1] * f[1] + row[2] * f[2]);
                z1[i] = r[0] - gamma * w1[i];
                z2[i] = r[1] - alpha * w2[i] + beta * w3[i];
                z3[i] = r[2] - alpha * w3[i] - beta * w2[i];
                self.complex_rhs[i] = Complex::new(z2[i], z3[i]);
            }
            solve_block(&self.real, &self.jq, gamma, z1, &mut self.real_work);
            let complex = Complex::new(alpha, beta);
            solve_block(
                &self.complex,
                &self.jq,
                complex,
                &mut self.complex_rhs,
                &mut self.complex_work,
            );
            for i in 0..n2 {
                (z2[i], z3[i]) = (self.complex_rhs[i].re, self.complex_rhs[i].im);
            }
            rec.stats.linear_solves += 1;
            rec.stats.newton_iterations += 1;
            iterations += 1;

            let mut sum = S::zero();
            for i in 0..n2 {
                let s = self.scal[i];
                sum += (z1[i] / s).powi(2) + (z2[i] / s).powi(2) + (z3[i] / s).powi(2);
            }
            let dyno = (sum / c((3 * n2) as f64)).sqrt();
            if !dyno.is_finite() {
                return Newton::Diverged;
            }
            if iterations > 1 && iterations < MAX_NEWTON {
                // Contraction rate, geometric mean of the last two.
                let thq = dyno / dyno_old;
                *theta = if iterations == 2 {
                    thq
                } else {
                    (thq * thq_old).sqrt()
                };
                thq_old = thq;
                if *theta >= c(0.99) {
                    return Newton::Diverged;
                }
                *faccon = *theta / (S::one() - *theta);
                let left = MAX_NEWTON - 1 - iterations;
                let predicted = *faccon * dyno * theta.powi(left as i32) / self.fnewt;
                if predicted >= S::one() {
                    // Will not converge in the iterations left: shrink h so
                    // that it would (Hairer's QNEWT heuristic).
                    let qnewt = predicted.min(c(20.0)).max(c(1e-4));
                    let exponent = c(-1.0 / (4 + left) as f64);
                    return Newton::TooSlow(c(0.8) * qnewt.powf(exponent));
                }
            }
            dyno_old = dyno.max(eps);
            let t = &self.k.t;
            let [w1, w2, w3] = &mut self.w;
            for i in 0..n2 {
                w1[i] += z1[i];
                w2[i] += z2[i];
                w3[i] += z3[i];
                let w = [w1[i], w2[i], w3[i]];
                z1[i] = t[0][0] * w[0] + t[0][1] * w[1] + t[0][2] * w[2];
                z2[i] = t[1][0] * w[0] + t[1][1] * w[1] + t[1][2] * w[2];
                z3[i] = t[2][0] * w[0] + w[1];
            }
            if *faccon * dyno <= self.fnewt {
                return Newton::Converged(iterations);
            }
        }
    }

    /// RADAU5's `ESTRAD`: the scaled RMS norm of the embedded error
    /// estimate `(γ̂/h − J)⁻¹ (f(y) + Σ dᵢ Zᵢ / h)`, re-estimated from
    /// `f(y + err)` when it fails on a first or rejected step (where the
    /// plain estimate is unreliable for stiff components). `None` if not
    /// finite.
    fn estimate_error<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        model: &L,
        rec: &mut Recorder<'_, S, N>,
        t: S,
        h: S,
        refine: bool,
    ) -> Option<S> {
        let gamma = self.k.gamma / h;
        let dd = self.k.dd.map(|d| d / h);
        for i in 0..2 * N {
            let r = dd[0] * self.z[0][i] + dd[1] * self.z[1][i] + dd[2] * self.z[2][i];
            self.err_rhs[i] = r;
            self.err[i] = r + self.f0[i];
        }
        solve_block(
            &self.real,
            &self.jq,
            gamma,
            &mut self.err,
            &mut self.real_work,
        );
        rec.stats.linear_solves += 1;
        let err = self.error_norm()?;
        if err < S::one() || !refine {
            return Some(err);
        }
        self.stage.copy_from(&self.y);
        self.stage += &self.err;
        if evaluate(rec, model, t, &self.stage, &mut self.err).is_err() {
            // The plain estimate already rejects the step.
            return Some(err);
        }
        self.err += &self.err_rhs;
        solve_block(
            &self.real,
            &self.jq,
            gamma,
            &mut self.err,
            &mut self.real_work,
        );
        rec.stats.linear_solves += 1;
        self.error_norm()
    }

    fn error_norm(&self) -> Option<S> {
        let mut sum = S::zero();
        for (e, s) in self.err.iter().zip(self.scal.iter()) {
            sum += (*e / *s).powi(2);
        }
        let norm = (sum / nalgebra::convert((2 * N).max(1) as f64)).sqrt();
        // Checked before the floor: max(NaN, floor) would hide it.
        norm.is_finite()
            .then(|| norm.max(nalgebra::convert(ERR_FLOOR)))
    }

    /// Moves to the end of an accepted step and keeps its collocation
    /// polynomial, in Newton form on the nodes `0, c₂ − 1, c₁ − 1` (the
    /// stage times relative to the new `t`, in units of `h`) and `−1`.
    fn accept(&mut self) {
        let k = &self.k;
        for i in 0..2 * N {
            let (z1, z2, z3) = (self.z[0][i], self.z[1][i], self.z[2][i]);
            self.y[i] += z3;
            let a1 = (z2 - z3) / k.c2m1;
            let ak = (z1 - z2) / k.c1mc2;
            let a3 = (ak - z1 / k.c[0]) / k.c[1];
            let a2 = (ak - a1) / k.c1m1;
            self.cont[0][i] = a1;
            self.cont[1][i] = a2;
            self.cont[2][i] = a2 - a3;
        }
        self.update_scale();
    }

    /// Records the samples up to `t_new`, the end of the accepted step of
    /// size `h` whose state is now `y`.
    fn record(&self, rec: &mut Recorder<'_, S, N>, t_new: S, h: S) {
        while let Some(ts) = rec.pending().filter(|&ts| ts <= t_new) {
            let (q, qdot) = if ts == t_new {
                split(&self.y)
            } else {
                self.dense((ts - t_new) / h)
            };
            rec.record(ts, q, qdot);
        }
    }

    /// The collocation polynomial at `t_new + s h`, `s ∈ [−1, 0]`.
    fn dense(&self, s: S) -> (SVector<S, N>, SVector<S, N>) {
        let k = &self.k;
        let at = |i: usize| {
            let (a1, a2, a3) = (self.cont[0][i], self.cont[1][i], self.cont[2][i]);
            self.y[i] + s * (a1 + (s - k.c2m1) * (a2 + (s - k.c1m1) * a3))
        };
        (
            SVector::from_fn(|i, _| at(i)),
            SVector::from_fn(|i, _| at(N + i)),
        )
    }
}

/// `ẏ = (q̇, q̈)` at `(t, y)` into `out`: one counted right-hand side.
fn evaluate<L: Lagrangian<N>, const N: usize>(
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
fn split<S: RealField + Copy, const N: usize>(y: &DVector<S>) -> (SVector<S, N>, SVector<S, N>) {
    (
        SVector::from_fn(|i, _| y[i]),
        SVector::from_fn(|i, _| y[N + i]),
    )
}
