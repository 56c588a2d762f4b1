//! One step of the variational integrator: Newton's method on the discrete
//! Euler–Lagrange equation `r(v̄) = 0` for the midpoint velocity.

use nalgebra::{ComplexField, RealField, SMatrix, SVector};

use super::{Variational, epsilon, lacks};
use crate::driver::newton_noise_floor;
use crate::error::{IntegrationError, NonFiniteValue};
use crate::linalg::all_finite;
use crate::linalg::mass::{SolveError, lu_solve, solve_mass_matrix};
use crate::model::Lagrangian;
use crate::trajectory::Stats;

/// Why a step's Newton iteration stopped.
pub(super) enum StepFailure<S: RealField + Copy, const N: usize> {
    /// The model failed where the step started, or lacks a method.
    Error(IntegrationError<S, N>),
    /// The iteration limit was reached, the iterates ran off to where the
    /// model is not finite, or the Newton matrix became singular although
    /// `M` is not: the step is too large. The caller adds the state.
    Diverged { iterations: usize },
}

impl<S: RealField + Copy, const N: usize> From<IntegrationError<S, N>> for StepFailure<S, N> {
    fn from(error: IntegrationError<S, N>) -> Self {
        Self::Error(error)
    }
}

impl<S: RealField + Copy> Variational<S> {
    /// Solves `r(v̄) = 0` for the midpoint velocity and returns it with
    /// `∂L/∂q + Q` there, the rate of the momentum update.
    ///
    /// The unknown is `v̄`, not `q_{k+1}`: `v̄ = (q_{k+1} − q_k)/h` would lose
    /// the digits that `q_{k+1}` and `q_k` share (an angle after many turns),
    /// and the momenta, `∝ v̄`, would lose them too.
    ///
    /// Chord Newton: the Jacobian, by forward differences at the predictor,
    /// is kept while the iteration contracts well (`θ ≤ ½`, the usual case:
    /// `∂r/∂v̄ = −M + O(h)` changes with `q̄`, which a correction moves by
    /// only `h/2` times as much) and refreshed when it does not. The
    /// iteration stops when the next correction is estimated at `10 ε` of the
    /// velocities: either the correction itself is that small, or the
    /// contraction `θ` of the last two makes the remaining error
    /// `θ/(1 − θ) |Δv̄|` that small (Hairer & Wanner, IV.8). Tighter is
    /// rounding noise; and a correction that stops contracting (`θ > ½`)
    /// below [`newton_noise_floor`] of the velocities is that noise (an
    /// ill-conditioned `M` puts it far above `10 ε`), so it stops there too.
    pub(super) fn solve<L: Lagrangian<N, Scalar = S>, const N: usize>(
        &self,
        stats: &mut Stats,
        del: &DiscreteEulerLagrange<'_, L, N>,
        guess: SVector<S, N>,
    ) -> Result<(SVector<S, N>, SVector<S, N>), StepFailure<S, N>> {
        let c = |x: f64| -> S { nalgebra::convert(x) };
        let tol = c(10.0) * epsilon::<S>();
        let mut v = guess;
        // At the predictor a failure is the model's, not Newton's.
        let (mut r, _) = del.residual(stats, &v)?;
        let mut jacobian = Some(del.jacobian(stats, &v, &r)?);
        let mut previous: Option<S> = None;

        for iteration in 1..=self.max_iterations {
            let j = match jacobian {
                Some(j) => j,
                None => {
                    let j = del
                        .jacobian(stats, &v, &r)
                        .map_err(|e| diverged(e, iteration))?;
                    *jacobian.insert(j)
                }
            };
            stats.newton_iterations += 1;
            stats.linear_solves += 1;
            let delta = match lu_solve(j, -r) {
                Ok(delta) => delta,
                Err(_) => return Err(del.singular_newton_matrix(&v, iteration)),
            };
            v += delta;
            let (r_new, rate) = del
                .residual(stats, &v)
                .map_err(|e| diverged(e, iteration))?;
            r = r_new;

            let size = delta.amax();
            let scale = v.amax().max(guess.amax());
            let theta = previous.map(|previous| size / previous);
            let remaining = theta
                .filter(|&theta| theta < S::one())
                .map(|theta| theta / (S::one() - theta) * size);
            if size <= tol * scale || remaining.is_some_and(|e| e <= tol * scale) {
                return Ok((v, rate));
            }
            if theta.is_some_and(|theta| theta > c(0.5)) {
                // Not contracting any more, but below the noise of
                // evaluating the residual: as converged as it gets.
                if size <= newton_noise_floor(del.model, del.t_mid, &del.q) * scale {
                    return Ok((v, rate));
                }
                jacobian = None;
            }
            previous = Some(size);
        }
        Err(StepFailure::Diverged {
            iterations: self.max_iterations,
        })
    }
}

/// One step's discrete Euler–Lagrange equation `r(v̄) = 0`, from `(q_k, p_k)`.
pub(super) struct DiscreteEulerLagrange<'a, L: Lagrangian<N>, const N: usize> {
    pub(super) model: &'a L,
    /// `t̄ = t_k + h/2`.
    pub(super) t_mid: L::Scalar,
    pub(super) q: SVector<L::Scalar, N>,
    pub(super) p: SVector<L::Scalar, N>,
    pub(super) half_h: L::Scalar,
    /// `k` of the augmented Lagrangian `L + (k/2)|φ̇|²` (`augmented.rs`),
    /// for a model whose `M` is regular only with its constraints.
    pub(super) augment: Option<L::Scalar>,
}

impl<L: Lagrangian<N>, const N: usize> DiscreteEulerLagrange<'_, L, N> {
    /// `r(v̄) = p_k + (h/2) g − ∂L/∂q̇` and `g = ∂L/∂q + Q`, all at
    /// `(t̄, q_k + (h/2) v̄, v̄)`: one counted residual evaluation.
    #[allow(clippy::type_complexity)]
    fn residual(
        &self,
        stats: &mut Stats,
        v: &SVector<L::Scalar, N>,
    ) -> Result<(SVector<L::Scalar, N>, SVector<L::Scalar, N>), IntegrationError<L::Scalar, N>>
    {
        stats.rhs_evals += 1;
        let (t, q) = (self.t_mid, self.q + v * self.half_h);
        let model = self.model;
        let non_finite = |value| IntegrationError::NonFiniteState {
            t,
            q,
            qdot: *v,
            value: crate::dynamics::blame::blame(model, value, t, &q, v),
        };
        if !all_finite(q.as_slice()) || !all_finite(v.as_slice()) {
            return Err(non_finite(NonFiniteValue::State));
        }
        let momentum = self
            .model
            .momentum(t, &q, v)
            .ok_or_else(|| lacks("momentum"))?;
        if !all_finite(momentum.as_slice()) {
            return Err(non_finite(NonFiniteValue::Momentum));
        }
        let gradient = self
            .model
            .lagrangian_gradient(t, &q, v)
            .ok_or_else(|| lacks("lagrangian_gradient"))?;
        if !all_finite(gradient.as_slice()) {
            return Err(non_finite(NonFiniteValue::LagrangianGradient));
        }
        let forces = self
            .model
            .nonconservative_forces(t, &q, v)
            .ok_or_else(|| lacks("nonconservative_forces"))?;
        if !all_finite(forces.as_slice()) {
            return Err(non_finite(NonFiniteValue::NonconservativeForces));
        }
        let (momentum, gradient) = match self.augment {
            None => (momentum, gradient),
            Some(k) => {
                let terms = super::augmented::Terms { k, t, q: &q, v };
                match self.model.visit_constraints(terms) {
                    Some((dp, dg)) => (momentum + dp, gradient + dg),
                    None => (momentum, gradient),
                }
            }
        };
        let rate = gradient + forces;
        Ok((self.p + rate * self.half_h - momentum, rate))
    }

    /// `∂r/∂v̄` by forward differences of `r` around `v̄`, where `r` is
    /// `r(v̄)`: `N` counted residual evaluations, step `√ε · max(1, |v̄_i|)`
    /// as in [`acceleration_jacobians`](crate::dynamics::acceleration_jacobians). `r` is nearly linear in `v̄`
    /// (`∂r/∂v̄ = −M + O(h)`), so the `√ε` relative error only slows the
    /// chord iteration, never stops it.
    fn jacobian(
        &self,
        stats: &mut Stats,
        v: &SVector<L::Scalar, N>,
        r: &SVector<L::Scalar, N>,
    ) -> Result<SMatrix<L::Scalar, N, N>, IntegrationError<L::Scalar, N>> {
        stats.jacobian_evals += 1;
        let one: L::Scalar = nalgebra::convert(1.0);
        let sqrt_eps = epsilon::<L::Scalar>().sqrt();
        let mut j = SMatrix::<L::Scalar, N, N>::zeros();
        for k in 0..N {
            let mut shifted = *v;
            shifted[k] += sqrt_eps * one.max(v[k].abs());
            let dv = shifted[k] - v[k]; // the step actually taken
            let (r_shifted, _) = self.residual(stats, &shifted)?;
            j.set_column(k, &((r_shifted - r) / dv));
        }
        Ok(j)
    }

    /// The Newton matrix is singular at `v̄`: `M` itself (a coordinate
    /// without inertia), or `−M + O(h)` cancelled by the `O(h)` terms, which
    /// only a step too large can do.
    fn singular_newton_matrix(
        &self,
        v: &SVector<L::Scalar, N>,
        iterations: usize,
    ) -> StepFailure<L::Scalar, N> {
        let (t, q) = (self.t_mid, self.q + v * self.half_h);
        match solve_mass_matrix(&self.model.mass_matrix(t, &q), &SVector::zeros()) {
            Err(SolveError::Singular) => {
                StepFailure::Error(IntegrationError::SingularMassMatrix { t, q, qdot: *v })
            }
            Err(SolveError::Indefinite) => {
                StepFailure::Error(IntegrationError::IndefiniteMassMatrix { t, q, qdot: *v })
            }
            _ => StepFailure::Diverged { iterations },
        }
    }
}

/// After the first iteration a non-finite value means the iterates ran away,
/// which is Newton's failure, not the model's.
fn diverged<S: RealField + Copy, const N: usize>(
    error: IntegrationError<S, N>,
    iterations: usize,
) -> StepFailure<S, N> {
    match error {
        IntegrationError::NonFiniteState { .. } => StepFailure::Diverged { iterations },
        other => StepFailure::Error(other),
    }
}
