//! The Dormand–Prince 5(4) tableau, its stages and its continuous extension
//! (Hairer's `d` coefficients), as in `dopri5.f`.

use nalgebra::{RealField, SVector};

use crate::driver::Recorder;
use crate::error::IntegrationError;
use crate::integrators::stages::{Step, fsal_step, model_slope};
use crate::model::Lagrangian;

/// The slopes of the seven stages of a step; the seventh is at the new
/// state and starts the next step (FSAL).
pub(crate) type Stages<S, const N: usize> = crate::integrators::stages::Stages<S, N, 7>;

/// The coefficients, as in `dopri5.f`: row `i` of `A` holds `a_ij` for
/// `j < i`.
pub(crate) const A: [&[f64]; 7] = [
    &[],
    &[1.0 / 5.0],
    &[3.0 / 40.0, 9.0 / 40.0],
    &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
    &[
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
    ],
    &[
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
    ],
    // The fifth-order weights b: stage 7 is the new state (FSAL).
    &[
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// The nodes `c_i`.
pub(crate) const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
/// `b − b̂`: fifth- minus fourth-order weights.
pub(crate) const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
/// The continuous extension (Hairer's `d`), for the fourth-order dense
/// output.
const D: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

/// The Dormand–Prince nodes in the working precision; the weights are read
/// as constants where they are used ([`Stages::sum`]).
pub(super) struct Tableau<S> {
    c: [S; 7],
}

impl<S: RealField + Copy> Tableau<S> {
    pub(super) fn new() -> Self {
        Self {
            c: C.map(nalgebra::convert),
        }
    }

    /// Attempts one step of size `h` from `(t, q, q̇)`, with `q̈` there in
    /// the first stage of `k`; the stages are left in `k`.
    #[inline(always)]
    pub(super) fn step<L: Lagrangian<N, Scalar = S>, const N: usize>(
        &self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        times: (S, S, S),
        state: (&SVector<S, N>, &SVector<S, N>),
        k: &mut Stages<S, N>,
    ) -> Result<Step<S, N>, IntegrationError<S, N>> {
        fsal_step(
            &mut model_slope(rec, model),
            times,
            state,
            k,
            &A,
            &self.c,
            &E,
        )
    }
}

/// Hairer's continuous extension of order four on one accepted step:
/// `y(t + θh) = r₁ + θ(r₂ + (1-θ)(r₃ + θ(r₄ + (1-θ) r₅)))`.
pub struct Dense<S, const N: usize> {
    q: [SVector<S, N>; 5],
    qdot: [SVector<S, N>; 5],
}

impl<S: RealField + Copy, const N: usize> Dense<S, N> {
    pub(super) fn new(
        h: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
        step: &Step<S, N>,
        k: &Stages<S, N>,
    ) -> Self {
        let (d_q, d_qdot) = k.sum(&D);
        let coefficients =
            |y0: &SVector<S, N>, y1: &SVector<S, N>, k: &[SVector<S, N>; 7], d: SVector<S, N>| {
                let diff = y1 - y0;
                let bspl = k[0] * h - diff;
                [*y0, diff, bspl, diff - k[6] * h - bspl, d * h]
            };
        Self {
            q: coefficients(q, &step.q, &k.q, d_q),
            qdot: coefficients(qdot, &step.qdot, &k.qdot, d_qdot),
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
