//! The Dormand–Prince 5(4) tableau, its stages and its continuous extension
//! (Hairer's `d` coefficients), as in `dopri5.f`.

use nalgebra::{RealField, SVector};

use crate::driver::Recorder;
use crate::{IntegrationError, Lagrangian};

/// One attempted step: the fifth-order solution, the embedded error
/// estimate, and the stages the continuous extension needs.
pub(crate) struct Step<S, const N: usize> {
    pub(super) q: SVector<S, N>,
    pub(super) qdot: SVector<S, N>,
    pub(super) err_q: SVector<S, N>,
    pub(super) err_qdot: SVector<S, N>,
    /// The `q` part of each stage's slope, which is the stage's own `q̇`.
    pub(super) k_q: [SVector<S, N>; 7],
    /// The `q̇` part of each stage's slope, `q̈`; the seventh is at the new
    /// state and starts the next step (FSAL).
    pub(super) k_qdot: [SVector<S, N>; 7],
}

/// The Dormand–Prince coefficients in the working precision.
pub(super) struct Tableau<S> {
    a: [[S; 6]; 7],
    c: [S; 7],
    /// `b - b̂`: fifth- minus fourth-order weights.
    e: [S; 7],
    /// Continuous extension (Hairer's `d`), for the fourth-order dense output.
    d: [S; 7],
}

impl<S: RealField + Copy> Tableau<S> {
    pub(super) fn new() -> Self {
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
    pub(super) fn step<L: Lagrangian<N, Scalar = S>, const N: usize>(
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
pub(crate) struct Dense<S, const N: usize> {
    q: [SVector<S, N>; 5],
    qdot: [SVector<S, N>; 5],
}

impl<S: RealField + Copy, const N: usize> Dense<S, N> {
    pub(super) fn new(
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

    pub(super) fn at(&self, theta: S) -> (SVector<S, N>, SVector<S, N>) {
        let eval = |r: &[SVector<S, N>; 5]| {
            let theta1 = S::one() - theta;
            r[0] + (r[1] + (r[2] + (r[3] + r[4] * theta1) * theta) * theta1) * theta
        };
        (eval(&self.q), eval(&self.qdot))
    }
}
