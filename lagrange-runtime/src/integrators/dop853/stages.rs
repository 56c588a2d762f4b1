//! DOP853's stages in the working precision: sums over the tableau's
//! constant rows, the sixteen slopes of a step, and the step itself.

use nalgebra::{RealField, SVector};

use super::tableau;
use crate::driver::Recorder;
use crate::error::IntegrationError;
use crate::model::Lagrangian;

/// The slopes of all 16 stages: 1–12 from the step, 13 at the new state,
/// 14–16 for the dense output (filled only when needed).
pub(super) type Stages<S, const N: usize> = crate::integrators::stages::Stages<S, N, 16>;

/// [`Stages::sum`] over row `i` of `A` (0-based): one arm per row, so that
/// each sum is unrolled over its own constant weights, its zeros (a third
/// of the tableau) dropped at compile time. (With a loop over a bit mask of
/// weights converted once per run, and a `pow` more per step, Dop853 took
/// 46.6 ns per evaluation on the double pendulum instead of 37.8, the two
/// builds alternating in one run of `cargo bench -p lagrange-studies
/// --bench rhs_overhead` when this changed; BENCHMARKS.md, "Constant
/// weights, no copies", says why.)
#[inline(always)]
fn stage_input<S: RealField + Copy, const N: usize>(
    k: &Stages<S, N>,
    i: usize,
) -> (SVector<S, N>, SVector<S, N>) {
    use tableau::A;
    match i {
        1 => k.sum(A[1]),
        2 => k.sum(A[2]),
        3 => k.sum(A[3]),
        4 => k.sum(A[4]),
        5 => k.sum(A[5]),
        6 => k.sum(A[6]),
        7 => k.sum(A[7]),
        8 => k.sum(A[8]),
        9 => k.sum(A[9]),
        10 => k.sum(A[10]),
        11 => k.sum(A[11]),
        12 => k.sum(A[12]),
        13 => k.sum(A[13]),
        14 => k.sum(A[14]),
        15 => k.sum(A[15]),
        // Stage 1 is given, never computed.
        _ => unreachable!("DOP853 has stages 1 to 16"),
    }
}

/// One attempted step: the eighth-order solution and both error estimates
/// (per unit step, as in Hairer's code, for `q` and `q̇`). Its stages stay
/// in the [`Stages`] it was computed in.
pub struct Step<S, const N: usize> {
    pub(super) q: SVector<S, N>,
    pub(super) qdot: SVector<S, N>,
    pub(super) err5: (SVector<S, N>, SVector<S, N>),
    pub(super) err3: (SVector<S, N>, SVector<S, N>),
}

/// `b − bhh`: eighth- minus third-order weights.
const E3: [f64; 12] = {
    let mut e3 = [0.0; 12];
    let mut i = 0;
    while i < 12 {
        e3[i] = tableau::B[i] - tableau::BHH[i];
        i += 1;
    }
    e3
};

/// The DOP853 nodes in the working precision; the weights are read as
/// constants where they are used ([`Stages::sum`]).
pub(super) struct Tableau<S> {
    c: [S; 16],
}

impl<S: RealField + Copy> Tableau<S> {
    pub(super) fn new() -> Self {
        Self {
            c: tableau::C.map(nalgebra::convert),
        }
    }

    /// Evaluates the stages in `range` (0-based) of a step of size `h` from
    /// `(t, q, q̇)`, each from the ones before it.
    pub(super) fn stages<L: Lagrangian<N, Scalar = S>, const N: usize>(
        &self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        (t, h): (S, S),
        (q, qdot): (&SVector<S, N>, &SVector<S, N>),
        range: std::ops::Range<usize>,
        k: &mut Stages<S, N>,
    ) -> Result<(), IntegrationError<S, N>> {
        for i in range {
            let (dq, dqdot) = stage_input(k, i);
            let (qi, qdoti) = (q + dq * h, qdot + dqdot * h);
            k.qdot[i] = rec.rhs(model, t + self.c[i] * h, &qi, &qdoti)?;
            k.q[i] = qdoti;
        }
        Ok(())
    }

    /// Stages 2–12 of a step of size `h` from `(t, q, q̇)`, with stage 1
    /// already in `k` (eleven right-hand sides), the solution and the
    /// estimates.
    pub(super) fn step<L: Lagrangian<N, Scalar = S>, const N: usize>(
        &self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        (t, h): (S, S),
        (q, qdot): (&SVector<S, N>, &SVector<S, N>),
        k: &mut Stages<S, N>,
    ) -> Result<Step<S, N>, IntegrationError<S, N>> {
        self.stages(rec, model, (t, h), (q, qdot), 1..12, k)?;
        let (dq, dqdot) = k.sum(&tableau::B);
        Ok(Step {
            q: q + dq * h,
            qdot: qdot + dqdot * h,
            err5: k.sum(&tableau::ER),
            err3: k.sum(&E3),
        })
    }
}
