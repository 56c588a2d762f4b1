//! A model whose `M` is regular only with its constraints (a body in unit
//! quaternions) on the variational step.
//!
//! The step integrates the augmented Lagrangian
//!
//! ```text
//! L' = L + (k/2) |φ̇|²,     φ̇ = G q̇ + ∂φ/∂t,
//! ```
//!
//! `k` fixed at the start of the run (`M`'s largest entry over `GᵀG`'s, as
//! the other methods' `M + k GᵀG`). `L'` equals `L` wherever the velocities
//! keep the constraints, its mass matrix `M + k GᵀG` is regular, and it has
//! every symmetry that `L` and `φ` share: RATTLE for `L'` is a symplectic,
//! momentum-conserving step of the constrained motion, with `φ = 0` and
//! `φ̇ = 0` after every step as for any constrained model. For a constraint
//! quadratic in `q` and free of `t` (`|q|² = 1`), `φ̇` at the step's
//! midpoint is exactly `(φ(q_{k+1}) − φ(q_k)) / h`, zero once a step has
//! converged: the step is then RATTLE's for `L` itself, the augmentation
//! only making its Newton matrices regular.
//!
//! Only the terms are here; the step (`newton.rs`, `rattle.rs`) adds them
//! to the momentum and the gradient of `L`, and the conversion from `p` to
//! `q̇` (`velocity.rs`) solves with `M + k GᵀG`.

use nalgebra::{RealField, SMatrix, SVector};

use crate::linalg::schur::regularized;
use crate::model::constraints::{Holonomic, Visitor};
use crate::model::settings::ConstraintSettings;

/// The weight `k` at a state: `M`'s largest entry over `GᵀG`'s.
pub(super) struct Weight<'a, S, const N: usize> {
    pub(super) t: S,
    pub(super) q: &'a SVector<S, N>,
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for Weight<'_, S, N> {
    type Output = S;

    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<S>) -> S
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let m = model.mass_matrix(self.t, self.q);
        regularized(&m, &model.constraint_jacobian(self.t, self.q)).1
    }
}

/// `k GᵀG` at `(t, q)`: what `L'` adds to the mass matrix.
pub(super) struct Metric<'a, S, const N: usize> {
    pub(super) k: S,
    pub(super) t: S,
    pub(super) q: &'a SVector<S, N>,
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for Metric<'_, S, N> {
    type Output = SMatrix<S, N, N>;

    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<S>) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let g = model.constraint_jacobian(self.t, self.q);
        g.transpose() * g * self.k
    }
}

/// What `L'` adds to `∂L/∂q̇` and to `∂L/∂q` at `(t, q, v)`:
/// `k Gᵀ φ̇` and `k (∂φ̇/∂q)ᵀ φ̇`, the latter by central differences of
/// `φ̇` (it is multiplied by `φ̇`, which vanishes on the constrained motion).
pub(super) struct Terms<'a, S, const N: usize> {
    pub(super) k: S,
    pub(super) t: S,
    pub(super) q: &'a SVector<S, N>,
    pub(super) v: &'a SVector<S, N>,
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for Terms<'_, S, N> {
    type Output = (SVector<S, N>, SVector<S, N>);

    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<S>) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let (k, t, q, v) = (self.k, self.t, self.q, self.v);
        let rate = model.constraint_velocities(t, q, v);
        let g = model.constraint_jacobian(t, q);
        let third: S = nalgebra::convert(1.0 / 3.0);
        let two: S = nalgebra::convert(2.0);
        let mut gradient = SVector::<S, N>::zeros();
        for j in 0..N {
            let h = S::default_epsilon().powf(third) * S::one().max(q[j].abs());
            let mut step = SVector::<S, N>::zeros();
            step[j] = h;
            let d = (model.constraint_velocities(t, &(q + step), v)
                - model.constraint_velocities(t, &(q - step), v))
                / (two * h);
            gradient[j] = d.dot(&rate) * k;
        }
        (g.transpose() * rate * k, gradient)
    }
}
