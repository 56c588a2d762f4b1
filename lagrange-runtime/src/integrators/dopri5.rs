//! Dormand–Prince 5(4): adaptive explicit Runge–Kutta with dense output.
//!
//! Follows Hairer's DOPRI5 (Hairer, Nørsett & Wanner, *Solving Ordinary
//! Differential Equations I*, §II.4–II.6, and the Fortran code `dopri5.f`):
//! the same tableau, error norm, initial step guess (`hinit`), stabilized
//! step-size control and continuous extension.

use nalgebra::{RealField, SVector};

use super::{check_tolerances, default_tolerance, initial_step, invalid, Integrator, Recorder};
use crate::{IntegrationError, IntegrationResult, Lagrangian, NonFiniteValue};

/// Dormand–Prince 5(4) with adaptive steps: the default method.
///
/// Each step costs six right-hand sides (the seventh is reused as the first
/// of the next step, "FSAL"). The local error of the fourth-order embedded
/// solution is kept below `atol + rtol |y|` componentwise (RMS over `q` and
/// `q̇`), and the fifth-order solution is propagated.
///
/// Sample times never shorten a step: the state between steps comes from the
/// fourth-order continuous extension, so asking for 10 or 10 000 samples
/// takes the same steps and gives the same final state.
///
/// A stage where the model cannot be evaluated (singular `M`, NaN) rejects
/// the step and retries with a fifth of the step size, so a model that
/// breaks down at `t*` is integrated up to `t*` and the error is reported
/// there, within rounding.
///
/// ```
/// use lagrange_runtime::Dopri5;
///
/// let tight = Dopri5::new().rtol(1e-10).atol(1e-12).max_steps(1_000_000);
/// # let _: Dopri5<f64> = tight;
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dopri5<S> {
    rtol: S,
    atol: S,
    max_steps: usize,
}

impl<S: RealField + Copy> Dopri5<S> {
    /// Defaults: `rtol = atol = 1e-8`, raised to `100 ε` for scalar types
    /// with fewer digits (`1.2e-5` for `f32`), and a budget of 100 000 steps
    /// (DOPRI5's `NMAX`).
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

impl<S: RealField + Copy> Default for Dopri5<S> {
    fn default() -> Self {
        Self::new()
    }
}

/// DOPRI5's step-size controller constants.
const SAFETY: f64 = 0.9;
/// Smallest step-size ratio `h_new / h`.
const FAC_MIN: f64 = 0.2;
/// Largest step-size ratio `h_new / h`.
const FAC_MAX: f64 = 10.0;
/// Lund stabilization (the "I" weight on the previous error).
const BETA: f64 = 0.04;

impl<S: RealField + Copy> Integrator<S> for Dopri5<S> {
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
        let alpha = c(0.2) - beta * c(0.75);
        let underflow = c(10.0) * S::default_epsilon();

        let (mut t, mut q, mut qdot) = (t0, q0, qdot0);
        let mut qddot = match rec.rhs(model, t, &q, &qdot) {
            Ok(a) => a,
            Err(error) => return Err(rec.fail(error)),
        };
        let h_max = t_end - t0;
        let (rtol, atol) = (self.rtol, self.atol);
        let start = (t, &q, &qdot, &qddot);
        let mut h = initial_step(&mut rec, model, start, h_max, rtol, atol, 5);

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
            // Stretch a step that would stop just short of the end (DOPRI5's
            // 1.01), so the last step is not a sliver.
            let last = t + h * c(1.01) >= t_end;
            if last {
                h = t_end - t;
            }
            let t_new = if last { t_end } else { t + h };

            let attempt = tab
                .step(&mut rec, model, t, t_new, h, &q, &qdot, &qddot)
                .and_then(|step| {
                    let err = self.error_norm(&q, &qdot, &step);
                    if err.is_finite() {
                        return Ok((step, err));
                    }
                    // Finite stages, infinite error: an overflow in the sums.
                    let (q, qdot, value) = (step.q, step.qdot, NonFiniteValue::State);
                    Err(IntegrationError::NonFiniteState {
                        t: t_new,
                        q,
                        qdot,
                        value,
                    })
                });
            let (step, err) = match attempt {
                Ok(attempt) => attempt,
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
            if err <= S::one() {
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

                let mut dense = None;
                while let Some(ts) = rec.pending().filter(|&ts| ts <= t_new) {
                    if ts == t_new {
                        rec.record(ts, step.q, step.qdot);
                    } else {
                        let dense =
                            dense.get_or_insert_with(|| Dense::new(&tab, h, &q, &qdot, &step));
                        let (qs, qdots) = dense.at((ts - t) / h);
                        rec.record(ts, qs, qdots);
                    }
                }
                if last {
                    return Ok(rec.finish());
                }
                (t, q, qdot, qddot) = (t_new, step.q, step.qdot, step.k_qdot[6]);
                h = h_new;
            } else {
                rec.stats.steps_rejected += 1;
                rejected_last = true;
                h /= (err_alpha / safety).min(S::one() / fac_min);
            }
        }
    }
}

impl<S: RealField + Copy> Dopri5<S> {
    /// RMS over `q` and `q̇` of the embedded error relative to
    /// `atol + rtol max(|y_old|, |y_new|)`.
    fn error_norm<const N: usize>(
        &self,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
        step: &Step<S, N>,
    ) -> S {
        let mut sum = S::zero();
        let parts = [
            (q, &step.q, &step.err_q),
            (qdot, &step.qdot, &step.err_qdot),
        ];
        for (y0, y1, e) in parts {
            for i in 0..N {
                let sk = self.atol + self.rtol * y0[i].abs().max(y1[i].abs());
                sum += (e[i] / sk).powi(2);
            }
        }
        let n: S = nalgebra::convert((2 * N).max(1) as f64);
        (sum / n).sqrt()
    }
}

/// One attempted step: the fifth-order solution, the embedded error
/// estimate, and the stages the continuous extension needs.
struct Step<S, const N: usize> {
    q: SVector<S, N>,
    qdot: SVector<S, N>,
    err_q: SVector<S, N>,
    err_qdot: SVector<S, N>,
    /// The `q` part of each stage's slope, which is the stage's own `q̇`.
    k_q: [SVector<S, N>; 7],
    /// The `q̇` part of each stage's slope, `q̈`; the seventh is at the new
    /// state and starts the next step (FSAL).
    k_qdot: [SVector<S, N>; 7],
}

/// The Dormand–Prince coefficients in the working precision.
struct Tableau<S> {
    a: [[S; 6]; 7],
    c: [S; 7],
    /// `b - b̂`: fifth- minus fourth-order weights.
    e: [S; 7],
    /// Continuous extension (Hairer's `d`), for the fourth-order dense output.
    d: [S; 7],
}

impl<S: RealField + Copy> Tableau<S> {
    fn new() -> Self {
        const A: [[f64; 6]; 7] = [
            [0.0; 6],
            [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
            [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
            [
                19372.0 / 6561.0,
                -25360.0 / 2187.0,
                64448.0 / 6561.0,
                -212.0 / 729.0,
                0.0,
                0.0,
            ],
            [
                9017.0 / 3168.0,
                -355.0 / 33.0,
                46732.0 / 5247.0,
                49.0 / 176.0,
                -5103.0 / 18656.0,
                0.0,
            ],
            // The fifth-order weights b: stage 7 is the new state (FSAL).
            [
                35.0 / 384.0,
                0.0,
                500.0 / 1113.0,
                125.0 / 192.0,
                -2187.0 / 6784.0,
                11.0 / 84.0,
            ],
        ];
        const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
        const E: [f64; 7] = [
            71.0 / 57600.0,
            0.0,
            -71.0 / 16695.0,
            71.0 / 1920.0,
            -17253.0 / 339200.0,
            22.0 / 525.0,
            -1.0 / 40.0,
        ];
        const D: [f64; 7] = [
            -12715105075.0 / 11282082432.0,
            0.0,
            87487479700.0 / 32700410799.0,
            -10690763975.0 / 1880347072.0,
            701980252875.0 / 199316789632.0,
            -1453857185.0 / 822651844.0,
            69997945.0 / 29380423.0,
        ];
        let c = |x: &f64| -> S { nalgebra::convert(*x) };
        Self {
            a: A.map(|row| row.each_ref().map(c)),
            c: C.each_ref().map(c),
            e: E.each_ref().map(c),
            d: D.each_ref().map(c),
        }
    }

    /// Attempts one step of size `h` from `(t, q, q̇)` with `q̈` known there.
    #[allow(clippy::too_many_arguments)]
    fn step<L: Lagrangian<N, Scalar = S>, const N: usize>(
        &self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        t: S,
        t_new: S,
        h: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
        qddot: &SVector<S, N>,
    ) -> Result<Step<S, N>, IntegrationError<S, N>> {
        let mut k_q = [*qdot; 7];
        let mut k_qdot = [*qddot; 7];
        let mut q_new = *q;
        for i in 1..7 {
            let (mut dq, mut dqdot) = (SVector::<S, N>::zeros(), SVector::<S, N>::zeros());
            for j in 0..i {
                dq += k_q[j] * self.a[i][j];
                dqdot += k_qdot[j] * self.a[i][j];
            }
            let (qi, qdoti) = (q + dq * h, qdot + dqdot * h);
            // Row 7 of `a` holds the weights b, so stage 7 is the new state.
            let ti = if i == 6 { t_new } else { t + self.c[i] * h };
            k_qdot[i] = rec.rhs(model, ti, &qi, &qdoti)?;
            k_q[i] = qdoti;
            q_new = qi;
        }
        let (mut err_q, mut err_qdot) = (SVector::<S, N>::zeros(), SVector::<S, N>::zeros());
        for j in 0..7 {
            err_q += k_q[j] * self.e[j];
            err_qdot += k_qdot[j] * self.e[j];
        }
        Ok(Step {
            q: q_new,
            qdot: k_q[6],
            err_q: err_q * h,
            err_qdot: err_qdot * h,
            k_q,
            k_qdot,
        })
    }
}

/// Hairer's continuous extension of order four on one accepted step:
/// `y(t + θh) = r₁ + θ(r₂ + (1-θ)(r₃ + θ(r₄ + (1-θ) r₅)))`.
struct Dense<S, const N: usize> {
    q: [SVector<S, N>; 5],
    qdot: [SVector<S, N>; 5],
}

impl<S: RealField + Copy, const N: usize> Dense<S, N> {
    fn new(
        tab: &Tableau<S>,
        h: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
        step: &Step<S, N>,
    ) -> Self {
        let coefficients = |y0: &SVector<S, N>, y1: &SVector<S, N>, k: &[SVector<S, N>; 7]| {
            let diff = y1 - y0;
            let bspl = k[0] * h - diff;
            let mut r5 = SVector::<S, N>::zeros();
            for (kj, &dj) in k.iter().zip(&tab.d) {
                r5 += kj * dj;
            }
            [*y0, diff, bspl, diff - k[6] * h - bspl, r5 * h]
        };
        Self {
            q: coefficients(q, &step.q, &step.k_q),
            qdot: coefficients(qdot, &step.qdot, &step.k_qdot),
        }
    }

    fn at(&self, theta: S) -> (SVector<S, N>, SVector<S, N>) {
        let eval = |r: &[SVector<S, N>; 5]| {
            let theta1 = S::one() - theta;
            r[0] + (r[1] + (r[2] + (r[3] + r[4] * theta1) * theta) * theta1) * theta
        };
        (eval(&self.q), eval(&self.qdot))
    }
}
