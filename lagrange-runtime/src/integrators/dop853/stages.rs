//! DOP853's stages in the working precision: the tableau with its zeros
//! marked, the sixteen slopes of a step, and the step itself.

use nalgebra::{RealField, SVector};

use super::tableau;
use crate::driver::Recorder;
use crate::{IntegrationError, Lagrangian};

/// The slopes of all 16 stages: 1–12 from the step, 13 at the new state,
/// 14–16 for the dense output (filled only when needed).
pub(super) struct Stages<S, const N: usize> {
    /// The `q` part of each slope, which is the stage's own `q̇`.
    pub(super) q: [SVector<S, N>; 16],
    /// The `q̇` part of each slope, `q̈`.
    pub(super) qdot: [SVector<S, N>; 16],
}

impl<S: RealField + Copy, const N: usize> Stages<S, N> {
    /// Stage 1 is `f` at the start, `(q̇, q̈)`; the others are filled by the
    /// step before anything reads them.
    pub(super) fn new(qdot: &SVector<S, N>, qddot: &SVector<S, N>) -> Self {
        Self {
            q: [*qdot; 16],
            qdot: [*qddot; 16],
        }
    }

    /// After an accepted step, its stage 13 (`f` at the new state) is the
    /// next step's stage 1: first same as last.
    pub(super) fn first_same_as_last(&mut self) {
        self.q[0] = self.q[12];
        self.qdot[0] = self.qdot[12];
    }

    /// `(Σ w_j k_q[j], Σ w_j k_q̇[j])` over the nonzero weights, in stage
    /// order.
    pub(super) fn sum(&self, weights: &Weights<S>) -> (SVector<S, N>, SVector<S, N>) {
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
pub(super) struct Weights<S> {
    w: [S; 16],
    /// Bit `j` is set where `w_j` is nonzero.
    nonzero: u16,
}

impl<S: RealField + Copy> Weights<S> {
    pub(super) fn new(weights: &[f64]) -> Self {
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
pub(crate) struct Step<S, const N: usize> {
    pub(super) q: SVector<S, N>,
    pub(super) qdot: SVector<S, N>,
    pub(super) err5: (SVector<S, N>, SVector<S, N>),
    pub(super) err3: (SVector<S, N>, SVector<S, N>),
}

/// The DOP853 coefficients in the working precision.
pub(super) struct Tableau<S> {
    /// All 16 rows; row 13 is `b`.
    a: [Weights<S>; 16],
    c: [S; 16],
    b: Weights<S>,
    er: Weights<S>,
    /// `b − bhh`: eighth- minus third-order weights.
    e3: Weights<S>,
    pub(super) d: [Weights<S>; 4],
}

impl<S: RealField + Copy> Tableau<S> {
    pub(super) fn new() -> Self {
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
    pub(super) fn step<L: Lagrangian<N, Scalar = S>, const N: usize>(
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
