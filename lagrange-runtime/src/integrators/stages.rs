//! The slopes of an explicit Runge–Kutta step, kept from step to step, and
//! the sums over them that a tableau's rows weigh: shared by [`Dopri5`]
//! (7 stages) and [`Dop853`] (16).
//!
//! [`Dopri5`]: crate::integrators::Dopri5
//! [`Dop853`]: crate::integrators::Dop853

use nalgebra::{RealField, SVector};

/// The slopes of the `K` stages of a step, split as the state is: stage
/// `j`'s slope is `(k_q[j], k_q̇[j]) = (q̇_j, q̈_j)`.
pub(crate) struct Stages<S, const N: usize, const K: usize> {
    /// The `q` part of each slope, which is the stage's own `q̇`.
    pub(crate) q: [SVector<S, N>; K],
    /// The `q̇` part of each slope, `q̈`.
    pub(crate) qdot: [SVector<S, N>; K],
}

impl<S: RealField + Copy, const N: usize, const K: usize> Stages<S, N, K> {
    /// Stage 1 is `f` at the start, `(q̇, q̈)`; the others are filled by each
    /// step before anything reads them.
    pub(crate) fn new(qdot: &SVector<S, N>, qddot: &SVector<S, N>) -> Self {
        Self {
            q: [*qdot; K],
            qdot: [*qddot; K],
        }
    }

    /// `(Σ w_j k_q[j], Σ w_j k_q̇[j])` in stage order, over one of a
    /// tableau's constant rows. Inlined where it is called, the loop is
    /// unrolled over a row known at compile time, its zeros dropped there
    /// and its weights immediates; over a row chosen at run time it stays a
    /// loop. A zero weight is skipped: the same bits as adding its product,
    /// because the slopes are finite (each comes from a state the solve
    /// accepted) and a sum begun at `+0` is never `−0`, so adding `±0`
    /// leaves it unchanged.
    #[inline(always)]
    pub(crate) fn sum(&self, weights: &'static [f64]) -> (SVector<S, N>, SVector<S, N>) {
        let (mut sq, mut sqdot) = (SVector::<S, N>::zeros(), SVector::<S, N>::zeros());
        for (j, &x) in weights.iter().enumerate() {
            if x != 0.0 {
                let w: S = nalgebra::convert(x);
                sq += self.q[j] * w;
                sqdot += self.qdot[j] * w;
            }
        }
        (sq, sqdot)
    }

    /// After an accepted step, its slope at the new state (stage `last`,
    /// 0-based) is the next step's first: first same as last.
    pub(crate) fn first_same_as_last(&mut self, last: usize) {
        self.q[0] = self.q[last];
        self.qdot[0] = self.qdot[last];
    }
}
