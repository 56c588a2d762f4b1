//! Dormand–Prince 8(5,3): adaptive explicit Runge–Kutta of order eight with
//! dense output of order seven.
//!
//! Follows Hairer's DOP853 (Hairer, Nørsett & Wanner, *Solving Ordinary
//! Differential Equations I*, §II.5 and §II.10, and the Fortran code
//! `dop853.f`): the same twelve-stage tableau, the error estimate that blends
//! a fifth- and a third-order estimator, the step-size control with its
//! default constants, the initial step guess (`hinit`) and the continuous
//! extension `contd8` with its three extra stages. The coefficients live in
//! [`dop853_tableau`](super::dop853_tableau).

use nalgebra::{RealField, SVector};

use super::dop853_tableau as tableau;
use super::{check_tolerances, default_tolerance, initial_step, invalid, Integrator, Recorder};
use crate::{IntegrationError, IntegrationResult, Lagrangian, NonFiniteValue};

/// Dormand–Prince 8(5,3) with adaptive steps: the method for tight
/// tolerances.
///
/// Each step costs twelve right-hand sides (eleven stages and `f` at the new
/// state, which is the next step's first stage); a rejected step costs
/// eleven. Because the controlled error falls as `h⁸`, halving the
/// tolerance shrinks the steps by only 8 % (`2^(-1/8)`), against 13 % for
/// [`Dopri5`](crate::Dopri5): at tight tolerances it needs markedly fewer
/// evaluations for the same accuracy (at `rtol = 1e-12`, 6× fewer on a
/// harmonic oscillator, 2× fewer on a double pendulum), while at loose ones
/// its twelve stages can cost more (1.3× Dopri5's evaluations on the
/// pendulum at `1e-6`). Reach for it below about `1e-9`.
///
/// The local error is estimated as in Hairer's code, from a fifth-order
/// estimate `err5` and a third-order one `err3` (RMS over `q` and `q̇`,
/// relative to `atol + rtol |y|` componentwise):
/// `err = err5² / √(err5² + 0.01 err3²)`. For small steps this behaves like
/// `h⁸`, as the error of the propagated eighth-order solution does, so the
/// steps are not cut to what a fifth-order method would need; for large
/// ones, where `err3` no longer dominates, it is the plain, cautious
/// fifth-order estimate.
///
/// Sample times never shorten a step: the state between steps comes from
/// the seventh-order continuous extension, which costs three more
/// right-hand sides on each step that has a sample strictly inside it. The
/// steps, and so the final state, do not depend on the sample times; the
/// evaluation count does.
///
/// A stage where the model cannot be evaluated (singular `M`, NaN) rejects
/// the step and retries with a third of the step size, so a model that
/// breaks down at `t*` is integrated up to `t*` and the error is reported
/// there, within rounding.
///
/// ```
/// use lagrange_runtime::Dop853;
///
/// let tight = Dop853::new().rtol(1e-12).atol(1e-12).max_steps(1_000_000);
/// # let _: Dop853<f64> = tight;
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dop853<S> {
    rtol: S,
    atol: S,
    max_steps: usize,
}

impl<S: RealField + Copy> Dop853<S> {
    /// The same defaults as [`Dopri5`](crate::Dopri5), so that swapping the
    /// method keeps the accuracy: `rtol = atol = 1e-8`, raised to `100 ε`
    /// for scalar types with fewer digits (`1.2e-5` for `f32`), and a budget
    /// of 100 000 steps (DOP853's `NMAX`).
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

    /// The step budget, counting rejected steps too, so that every call ends.
    pub fn max_steps(mut self, max_steps: usize) -> Self {
        self.max_steps = max_steps;
        self
    }
}

impl<S: RealField + Copy> Default for Dop853<S> {
    fn default() -> Self {
        Self::new()
    }
}

/// DOP853's step-size controller defaults (`WORK(2)`–`WORK(5)` of
/// `dop853.f`).
const SAFETY: f64 = 0.9;
/// Smallest step-size ratio `h_new / h` (Hairer's 0.333).
const FAC_MIN: f64 = 0.333;
/// Largest step-size ratio `h_new / h`.
const FAC_MAX: f64 = 6.0;
/// Lund stabilization (the "I" weight on the previous error): none in
/// DOP853 by default (Hairer's `BETA = 0`), a pure I-controller with
/// exponent 1/8. Kept as a constant so the formula reads as Hairer's.
const BETA: f64 = 0.0;

impl<S: RealField + Copy> Integrator<S> for Dop853<S> {
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
        check_tolerances(self.rtol, self.atol).map_err(invalid)?;
        let mut rec = Recorder::start(model, t0, &q0, &qdot0, times)?;
        let (Some(_), Some(t_end)) = (rec.pending(), rec.end()) else {
            return Ok(rec.finish());
        };

        let c = |x: f64| -> S { nalgebra::convert(x) };
        let tab = Tableau::<S>::new();
        let (safety, fac_min, fac_max, beta) = (c(SAFETY), c(FAC_MIN), c(FAC_MAX), c(BETA));
        let alpha = c(1.0 / 8.0) - beta * c(0.2);
        let underflow = c(10.0) * S::default_epsilon();

        let (mut t, mut q, mut qdot) = (t0, q0, qdot0);
        let qddot = match rec.rhs(model, t, &q, &qdot) {
            Ok(a) => a,
            Err(error) => return Err(rec.fail(error)),
        };
        let h_max = t_end - t0;
        let (rtol, atol) = (self.rtol, self.atol);
        let start = (t, &q, &qdot, &qddot);
        let mut h = initial_step(&mut rec, model, start, h_max, rtol, atol, 8);
        // One set of slopes for the whole integration, overwritten by each
        // attempt: nothing of this size is copied per step.
        let mut k = Stages::new(&qdot, &qddot);

        let mut err_old = c(1e-4);
        let mut rejected_last = false;
        // The evaluation failure that made us shrink h, reported if h
        // underflows before we get past it.
        let mut stage_failure = None;

        loop {
            let attempts = rec.stats.steps_accepted + rec.stats.steps_rejected;
            if attempts >= self.max_steps {
                let max_steps = self.max_steps;
                let error = IntegrationError::TooManySteps {
                    t,
                    max_steps,
                    q,
                    qdot,
                };
                return Err(rec.fail(error));
            }
            let advances = h > underflow * t.abs() && t + h != t;
            if !advances {
                let error = stage_failure
                    .take()
                    .unwrap_or(IntegrationError::StepSizeUnderflow { t, h, q, qdot });
                return Err(rec.fail(error));
            }
            // Stretch a step that would stop just short of the end (DOP853's
            // 1.01), so the last step is not a sliver.
            let last = t + h * c(1.01) >= t_end;
            if last {
                h = t_end - t;
            }
            let t_new = if last { t_end } else { t + h };

            let outcome = self.attempt(&tab, &mut rec, model, &mut k, (t, t_new, h), (&q, &qdot));
            let (step, err) = match outcome {
                Ok(Outcome::Accepted { step, err }) => (step, err),
                Ok(Outcome::Rejected { err }) => {
                    rec.stats.steps_rejected += 1;
                    rejected_last = true;
                    h /= (err.powf(alpha) / safety).min(S::one() / fac_min);
                    continue;
                }
                Err(error) => {
                    stage_failure = Some(error);
                    rec.stats.steps_rejected += 1;
                    rejected_last = true;
                    h *= fac_min;
                    continue;
                }
            };

            // h_new = h · safety · err^(-alpha) · err_old^beta, bounded.
            let err_alpha = err.powf(alpha);
            let shrink = err_alpha / err_old.powf(beta) / safety;
            let fac = shrink.min(S::one() / fac_min).max(S::one() / fac_max);
            let mut h_new = (h / fac).min(h_max);
            if rejected_last {
                h_new = h_new.min(h);
            }
            err_old = err.max(c(1e-4));
            rec.stats.steps_accepted += 1;
            rejected_last = false;
            stage_failure = None;

            // A sample strictly inside the step made `attempt` evaluate
            // stages 14–16; the continuous extension is built from them once.
            let mut dense = None;
            while let Some(ts) = rec.pending().filter(|&ts| ts <= t_new) {
                if ts < t_new {
                    let dense =
                        dense.get_or_insert_with(|| Dense::new(&tab, h, (&q, &qdot), &step, &k));
                    let (qs, qdots) = dense.at((ts - t) / h);
                    rec.record(ts, qs, qdots);
                } else {
                    rec.record(ts, step.q, step.qdot);
                }
            }
            if last {
                return Ok(rec.finish());
            }
            (t, q, qdot) = (t_new, step.q, step.qdot);
            k.first_same_as_last();
            h = h_new;
        }
    }
}

/// How an attempted step ended, short of a model failure.
enum Outcome<S, const N: usize> {
    /// The error estimate `err` exceeds the tolerance.
    Rejected { err: S },
    /// The step passed the error test, stage 13 (`f` at the new state) is
    /// filled in, and so are stages 14–16 of the continuous extension if a
    /// sample lies strictly inside the step.
    Accepted { step: Step<S, N>, err: S },
}

impl<S: RealField + Copy> Dop853<S> {
    /// Attempts a step of size `h` from `(t, q, q̇)`, with `q̈` there in
    /// stage 1 of `k`, to `t_new`: eleven right-hand sides for the stages,
    /// one more at the new state if the error test passes, and three more
    /// for the dense output if a sample lies inside the step. A failing
    /// evaluation, or an overflow in the error estimate, is an error, which
    /// rejects the step.
    fn attempt<L: Lagrangian<N, Scalar = S>, const N: usize>(
        &self,
        tab: &Tableau<S>,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        k: &mut Stages<S, N>,
        (t, t_new, h): (S, S, S),
        (q, qdot): (&SVector<S, N>, &SVector<S, N>),
    ) -> Result<Outcome<S, N>, IntegrationError<S, N>> {
        let step = tab.step(rec, model, (t, h), (q, qdot), k)?;
        let err = self.error_norm(h, q, qdot, &step);
        if !err.is_finite() {
            // Finite stages, infinite error: an overflow in the sums.
            return Err(IntegrationError::NonFiniteState {
                t: t_new,
                q: step.q,
                qdot: step.qdot,
                value: NonFiniteValue::State,
            });
        }
        if err > S::one() {
            return Ok(Outcome::Rejected { err });
        }
        // f at the new state: stage 13 of the dense output, and the next
        // step's first stage. Evaluating it here, before accepting, means a
        // model that breaks down at the new state rejects the step.
        k.qdot[12] = rec.rhs(model, t_new, &step.q, &step.qdot)?;
        k.q[12] = step.qdot;
        if rec.pending().is_some_and(|ts| ts < t_new) {
            tab.stages(rec, model, (t, h), (q, qdot), 13..16, k)?;
        }
        Ok(Outcome::Accepted { step, err })
    }

    /// Hairer's blended estimate: with `err5`, `err3` the RMS of the fifth-
    /// and third-order estimates relative to `atol + rtol max(|y_old|,
    /// |y_new|)`, `err = h err5² / √(err5² + 0.01 err3²)` (see [`Dop853`]),
    /// computed as in `dop853.f`.
    fn error_norm<const N: usize>(
        &self,
        h: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
        step: &Step<S, N>,
    ) -> S {
        let (mut sum5, mut sum3) = (S::zero(), S::zero());
        let parts = [
            (q, &step.q, &step.err5.0, &step.err3.0),
            (qdot, &step.qdot, &step.err5.1, &step.err3.1),
        ];
        for (y0, y1, e5, e3) in parts {
            for i in 0..N {
                let sk = self.atol + self.rtol * y0[i].abs().max(y1[i].abs());
                sum5 += (e5[i] / sk).powi(2);
                sum3 += (e3[i] / sk).powi(2);
            }
        }
        let mut deno = sum5 + nalgebra::convert::<f64, S>(0.01) * sum3;
        if deno <= S::zero() {
            deno = S::one();
        }
        let n: S = nalgebra::convert((2 * N).max(1) as f64);
        h.abs() * sum5 * (S::one() / (n * deno)).sqrt()
    }
}

/// The slopes of all 16 stages: 1–12 from the step, 13 at the new state,
/// 14–16 for the dense output (filled only when needed).
struct Stages<S, const N: usize> {
    /// The `q` part of each slope, which is the stage's own `q̇`.
    q: [SVector<S, N>; 16],
    /// The `q̇` part of each slope, `q̈`.
    qdot: [SVector<S, N>; 16],
}

impl<S: RealField + Copy, const N: usize> Stages<S, N> {
    /// Stage 1 is `f` at the start, `(q̇, q̈)`; the others are filled by the
    /// step before anything reads them.
    fn new(qdot: &SVector<S, N>, qddot: &SVector<S, N>) -> Self {
        Self {
            q: [*qdot; 16],
            qdot: [*qddot; 16],
        }
    }

    /// After an accepted step, its stage 13 (`f` at the new state) is the
    /// next step's stage 1: first same as last.
    fn first_same_as_last(&mut self) {
        self.q[0] = self.q[12];
        self.qdot[0] = self.qdot[12];
    }

    /// `(Σ w_j k_q[j], Σ w_j k_q̇[j])` over the nonzero weights, in stage
    /// order.
    fn sum(&self, weights: &Weights<S>) -> (SVector<S, N>, SVector<S, N>) {
        let (mut sq, mut sqdot) = (SVector::<S, N>::zeros(), SVector::<S, N>::zeros());
        let mut left = weights.nonzero;
        while left != 0 {
            // The lowest stage left; `& 15` (a no-op) spares the bounds checks.
            let j = left.trailing_zeros() as usize & 15;
            left &= left - 1;
            let w = weights.w[j];
            sq += self.q[j] * w;
            sqdot += self.qdot[j] * w;
        }
        (sq, sqdot)
    }
}

/// Weights `w_j` of a sum over the stages, with the zeros of the tableau
/// (a third of it) marked once, when the tableau is built, so that each
/// step does only the products the method needs.
struct Weights<S> {
    w: [S; 16],
    /// Bit `j` is set where `w_j` is nonzero.
    nonzero: u16,
}

impl<S: RealField + Copy> Weights<S> {
    fn new(weights: &[f64]) -> Self {
        let mut w = [S::zero(); 16];
        let mut nonzero = 0;
        for (j, (w, &x)) in w.iter_mut().zip(weights).enumerate() {
            *w = nalgebra::convert(x);
            if *w != S::zero() {
                nonzero |= 1 << j;
            }
        }
        Self { w, nonzero }
    }
}

/// One attempted step: the eighth-order solution and both error estimates
/// (per unit step, as in Hairer's code, for `q` and `q̇`). Its stages stay
/// in the [`Stages`] it was computed in.
struct Step<S, const N: usize> {
    q: SVector<S, N>,
    qdot: SVector<S, N>,
    err5: (SVector<S, N>, SVector<S, N>),
    err3: (SVector<S, N>, SVector<S, N>),
}

/// The DOP853 coefficients in the working precision.
struct Tableau<S> {
    /// All 16 rows; row 13 is `b`.
    a: [Weights<S>; 16],
    c: [S; 16],
    b: Weights<S>,
    er: Weights<S>,
    /// `b − bhh`: eighth- minus third-order weights.
    e3: Weights<S>,
    d: [Weights<S>; 4],
}

impl<S: RealField + Copy> Tableau<S> {
    fn new() -> Self {
        let e3: [f64; 12] = std::array::from_fn(|i| tableau::B[i] - tableau::BHH[i]);
        Self {
            a: tableau::A.map(Weights::new),
            c: tableau::C.map(nalgebra::convert),
            b: Weights::new(&tableau::B),
            er: Weights::new(&tableau::ER),
            e3: Weights::new(&e3),
            d: tableau::D.each_ref().map(|row| Weights::new(row)),
        }
    }

    /// Evaluates the stages in `range` (0-based) of a step of size `h` from
    /// `(t, q, q̇)`, each from the ones before it.
    fn stages<L: Lagrangian<N, Scalar = S>, const N: usize>(
        &self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        (t, h): (S, S),
        (q, qdot): (&SVector<S, N>, &SVector<S, N>),
        range: std::ops::Range<usize>,
        k: &mut Stages<S, N>,
    ) -> Result<(), IntegrationError<S, N>> {
        for i in range {
            let (dq, dqdot) = k.sum(&self.a[i]);
            let (qi, qdoti) = (q + dq * h, qdot + dqdot * h);
            k.qdot[i] = rec.rhs(model, t + self.c[i] * h, &qi, &qdoti)?;
            k.q[i] = qdoti;
        }
        Ok(())
    }

    /// Stages 2–12 of a step of size `h` from `(t, q, q̇)`, with stage 1
    /// already in `k` (eleven right-hand sides), the solution and the
    /// estimates.
    fn step<L: Lagrangian<N, Scalar = S>, const N: usize>(
        &self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        (t, h): (S, S),
        (q, qdot): (&SVector<S, N>, &SVector<S, N>),
        k: &mut Stages<S, N>,
    ) -> Result<Step<S, N>, IntegrationError<S, N>> {
        self.stages(rec, model, (t, h), (q, qdot), 1..12, k)?;
        let (dq, dqdot) = k.sum(&self.b);
        Ok(Step {
            q: q + dq * h,
            qdot: qdot + dqdot * h,
            err5: k.sum(&self.er),
            err3: k.sum(&self.e3),
        })
    }
}

/// Hairer's `contd8` on one accepted step, with `s = θ`, `s₁ = 1 − θ`:
/// `y(t + θh) = r₁ + s(r₂ + s₁(r₃ + s(r₄ + s₁(r₅ + s(r₆ + s₁(r₇ + s r₈))))))`.
struct Dense<S, const N: usize> {
    q: [SVector<S, N>; 8],
    qdot: [SVector<S, N>; 8],
}

impl<S: RealField + Copy, const N: usize> Dense<S, N> {
    /// Hairer's coefficients `r₁…r₈` for `q` and `q̇`, from a step whose
    /// stages 13–16 are filled in.
    fn new(
        tab: &Tableau<S>,
        h: S,
        (q, qdot): (&SVector<S, N>, &SVector<S, N>),
        step: &Step<S, N>,
        k: &Stages<S, N>,
    ) -> Self {
        let high = tab.d.each_ref().map(|d| k.sum(d));
        let coefficients = |y0: &SVector<S, N>,
                            y1: &SVector<S, N>,
                            k: &[SVector<S, N>; 16],
                            r: [&SVector<S, N>; 4]| {
            let diff = y1 - y0;
            let bspl = k[0] * h - diff;
            let r4 = diff - k[12] * h - bspl;
            [*y0, diff, bspl, r4, r[0] * h, r[1] * h, r[2] * h, r[3] * h]
        };
        Self {
            q: coefficients(q, &step.q, &k.q, high.each_ref().map(|r| &r.0)),
            qdot: coefficients(qdot, &step.qdot, &k.qdot, high.each_ref().map(|r| &r.1)),
        }
    }

    fn at(&self, theta: S) -> (SVector<S, N>, SVector<S, N>) {
        let eval = |r: &[SVector<S, N>; 8]| {
            let s1 = S::one() - theta;
            let high = r[4] + (r[5] + (r[6] + r[7] * theta) * s1) * theta;
            r[0] + (r[1] + (r[2] + (r[3] + high * s1) * theta) * s1) * theta
        };
        (eval(&self.q), eval(&self.qdot))
    }
}

/// The stepping code with the step control taken out: fixed steps show the
/// orders of the solution and of the continuous extension directly.
#[cfg(test)]
mod tests {
    use nalgebra::{Matrix2, Vector2};

    use super::*;

    /// A double pendulum with unit masses and rods, its upper joint driven by
    /// a torque `cos 3t`: nonlinear, `M(q)`, forcing quadratic in `q̇` and
    /// explicitly time-dependent, so a wrong stage time shows too.
    struct DoublePendulum;

    const G: f64 = 9.81;

    impl Lagrangian<2> for DoublePendulum {
        type Scalar = f64;
        const COORDINATES: [&'static str; 2] = ["theta1", "theta2"];
        fn mass_matrix(&self, _t: f64, q: &Vector2<f64>) -> Matrix2<f64> {
            let c = (q[0] - q[1]).cos();
            Matrix2::new(2.0, c, c, 1.0)
        }
        fn forcing(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Vector2<f64> {
            let s = (q[0] - q[1]).sin();
            Vector2::new(
                -s * qd[1] * qd[1] - 2.0 * G * q[0].sin() + (3.0 * t).cos(),
                s * qd[0] * qd[0] - G * q[1].sin(),
            )
        }
        fn kinetic_energy(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> f64 {
            0.5 * (qd.transpose() * self.mass_matrix(t, q) * qd)[0]
        }
        fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
            -2.0 * G * q[0].cos() - G * q[1].cos()
        }
    }

    type State = (Vector2<f64>, Vector2<f64>);

    /// `steps` fixed steps of `h` from t = 0: the final state, and the dense
    /// output half-way through the last step.
    fn fixed_steps(h: f64, steps: usize) -> (State, State) {
        let (tab, model) = (Tableau::<f64>::new(), DoublePendulum);
        let (mut q, mut qdot) = (Vector2::new(0.5, -0.3), Vector2::new(0.0, 0.4));
        let mut rec = Recorder::start(&model, 0.0, &q, &qdot, &[]).unwrap();
        let (mut t, mut mid) = (0.0, (q, qdot));
        for _ in 0..steps {
            let qddot = rec.rhs(&model, t, &q, &qdot).unwrap();
            let mut k = Stages::new(&qdot, &qddot);
            let step = tab
                .step(&mut rec, &model, (t, h), (&q, &qdot), &mut k)
                .unwrap();
            k.qdot[12] = rec.rhs(&model, t + h, &step.q, &step.qdot).unwrap();
            k.q[12] = step.qdot;
            tab.stages(&mut rec, &model, (t, h), (&q, &qdot), 13..16, &mut k)
                .unwrap();
            mid = Dense::new(&tab, h, (&q, &qdot), &step, &k).at(0.5);
            (q, qdot, t) = (step.q, step.qdot, t + h);
        }
        ((q, qdot), mid)
    }

    fn distance(a: State, b: State) -> f64 {
        (a.0 - b.0).amax().max((a.1 - b.1).amax())
    }

    /// 2048 steps of 1/2048: its own error (~1e-12 · 64⁻⁸) is far below
    /// rounding, a few 1e-15.
    fn reference_at(steps_of_1_over_2048: usize) -> State {
        fixed_steps(1.0 / 2048.0, steps_of_1_over_2048).0
    }

    // Both tests halve h from 1/16 to 1/64, where the errors (1e-7 … 1e-12)
    // are far above rounding and in the asymptotic range: each halving
    // gains 2^8.3 … 2^9 here. Requiring 2^7.5 accepts order 8 with room for
    // the next term and rejects anything of order 7 or less.
    const MIN_GAIN: f64 = 181.0; // 2^7.5

    #[test]
    fn fixed_steps_are_eighth_order_on_a_nonlinear_model() {
        let reference = reference_at(2048);
        let errors: Vec<f64> = [16, 32, 64]
            .map(|k| distance(fixed_steps(1.0 / k as f64, k).0, reference))
            .to_vec();
        for pair in errors.windows(2) {
            assert!(pair[0] / pair[1] > MIN_GAIN, "errors at t = 1: {errors:?}");
        }
    }

    #[test]
    fn continuous_extension_is_seventh_order_mid_step() {
        // Its local error is O(h⁸): the same gain per halving half-way
        // through the last step, at t = 1 − h/2.
        let errors: Vec<f64> = [16, 32, 64]
            .map(|k| {
                distance(
                    fixed_steps(1.0 / k as f64, k).1,
                    reference_at(2048 - 1024 / k),
                )
            })
            .to_vec();
        for pair in errors.windows(2) {
            assert!(
                pair[0] / pair[1] > MIN_GAIN,
                "errors at t = 1 - h/2: {errors:?}"
            );
        }
    }
}
