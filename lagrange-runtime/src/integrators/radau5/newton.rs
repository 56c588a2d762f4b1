//! Radau5's simplified Newton iteration on the transformed stage
//! equations: the Jacobians, the factors of the real and complex blocks,
//! the starting values, and the iteration itself.

use nalgebra::{Complex, RealField, SVector};

use super::work::{Work, evaluate, split};
use super::{MAX_NEWTON, THETA_REUSE};
use crate::driver::Recorder;
use crate::dynamics::acceleration_jacobians;
use crate::error::{IntegrationError, NonFiniteValue};
use crate::linalg::lu::Singular;
use crate::linalg::second_order::{factor_block, solve_block};
use crate::model::Lagrangian;

/// How a Newton iteration ended.
pub(super) enum Newton<S: RealField + Copy, const N: usize> {
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

impl<S: RealField + Copy, const N: usize> Work<S, N> {
    /// `∂q̈/∂q` and `∂q̈/∂q̇` at `(t, y)`, where `f0` holds `ẏ`.
    pub(super) fn jacobian<L: Lagrangian<N, Scalar = S>>(
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
    pub(super) fn factor(&mut self, h: S) -> Result<(), Singular> {
        let real = self.k.gamma / h;
        let complex = Complex::new(self.k.alpha / h, self.k.beta / h);
        factor_block(&mut self.real, &self.jq, &self.jv, real)?;
        factor_block(&mut self.complex, &self.jq, &self.jv, complex)
    }

    /// Newton's starting point: zero before the first accepted step, else
    /// the last step's collocation polynomial extrapolated to the new stages
    /// (`ratio = h / h_old`).
    pub(super) fn starting_values(&mut self, first: bool, ratio: S) {
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
    pub(super) fn newton<L: Lagrangian<N, Scalar = S>>(
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
}
