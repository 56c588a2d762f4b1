//! The multipliers of the constrained variational step (RATTLE): an outer
//! Newton iteration on `λ`, `C` unknowns, around the variational
//! integrator's own solve for the midpoint velocity.
//!
//! The constrained discrete Euler–Lagrange equations of one step from
//! `(q_k, p_k)` are
//!
//! ```text
//! r(v̄, λ) = p_k − h G(q_k)ᵀ λ + (h/2)(∂L/∂q + Q) − ∂L/∂q̇ = 0,
//! ψ(λ)    = φ(t_{k+1}, q_k + h v̄) = 0,
//! ```
//!
//! the unconstrained equations with the momenta `p_k − h Gᵀ λ`: for a given
//! `λ`, the integrator's Newton solve gives `v̄(λ)`. Since
//! `∂r/∂v̄ = −M + O(h)`, `dψ/dλ = −h² G M⁻¹ Gᵀ + O(h³)`, and the outer
//! iteration is the simplified Newton `λ ← λ + (G M⁻¹ Gᵀ)⁻¹ ψ / h²` with
//! `G` and `M` at `q_k`: it contracts by `O(h)` per iteration, from a
//! guess (the previous step's force) `O(h)` off.

use crate::dynamics::saddle::saddle_error;
use crate::model::settings::ConstraintSettings;
use nalgebra::{RealField, SVector};

use crate::dynamics::mass_error;
use crate::dynamics::projection::position_tolerance;
use crate::dynamics::saddle::Multipliers;
use crate::error::{IntegrationError, NonFiniteValue};
use crate::linalg::mass::factor_mass_matrix;
use crate::linalg::schur::Schur;
use crate::model::constraints::{Holonomic, Visitor};

/// The constraint force `Gᵀ λ` at a state: the first step's guess.
pub(crate) struct StartForce<'a, S, const N: usize> {
    pub(crate) t: S,
    pub(crate) q: &'a SVector<S, N>,
    pub(crate) qdot: &'a SVector<S, N>,
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for StartForce<'_, S, N> {
    type Output = Result<SVector<S, N>, IntegrationError<S, N>>;

    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<S>) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let lambda = model.multipliers(self.t, self.q, self.qdot)?;
        Ok(model.constraint_jacobian(self.t, self.q).transpose() * lambda)
    }
}

/// How an outer iteration ended, short of an error.
pub(crate) enum Outer<S, const N: usize> {
    /// `(v̄, ∂L/∂q + Q at the midpoint, Gᵀ λ)`.
    Converged(SVector<S, N>, SVector<S, N>, SVector<S, N>),
    /// No convergence in this many iterations.
    Diverged(usize),
}

/// One constrained variational step's `λ`, from `(t_k, q_k)` to
/// `t_{k+1} = t_k + h`. `inner(F)` solves the unconstrained midpoint
/// equations with the momenta `p_k − h F` for `(v̄, ∂L/∂q + Q)`; `qdot` is
/// only reported in errors.
pub(crate) struct RattleStep<'a, S, const N: usize, F> {
    pub(crate) t: S,
    /// `t_k + h`, as the step lands.
    pub(crate) t_next: S,
    pub(crate) h: S,
    pub(crate) q: &'a SVector<S, N>,
    pub(crate) qdot: &'a SVector<S, N>,
    /// The constraint force `Gᵀ λ` of the previous step.
    pub(crate) guess: SVector<S, N>,
    pub(crate) max_iterations: usize,
    /// `k` of the augmented Lagrangian (`augmented.rs`): the outer
    /// iteration's metric is then `M + k GᵀG`.
    pub(crate) augment: Option<S>,
    pub(crate) inner: F,
}

impl<S, const N: usize, F, E> Visitor<S, N> for RattleStep<'_, S, N, F>
where
    S: RealField + Copy,
    F: FnMut(&SVector<S, N>) -> Result<(SVector<S, N>, SVector<S, N>), E>,
    E: From<IntegrationError<S, N>>,
{
    type Output = Result<Outer<S, N>, E>;

    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<S>) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let Self {
            t,
            t_next,
            h,
            q,
            qdot,
            guess,
            max_iterations,
            augment,
            mut inner,
        } = self;
        let g = model.constraint_jacobian(t, q);
        let m = match augment {
            None => model.mass_matrix(t, q),
            Some(k) => model.mass_matrix(t, q) + g.transpose() * g * k,
        };
        let mass = factor_mass_matrix(&m).map_err(|e| mass_error(e, t, q, qdot))?;
        if !crate::linalg::all_finite(g.as_slice()) {
            let (q, qdot, value) = (*q, *qdot, NonFiniteValue::Constraints);
            return Err(IntegrationError::NonFiniteState { t, q, qdot, value }.into());
        }
        let schur = Schur::new(&mass, &g).map_err(|e| saddle_error(e, t, q, qdot))?;
        // The previous force's components along the rows of G, in the
        // metric of M⁻¹: exact where G has not changed.
        let mut lambda = schur.solve(&(schur.x.transpose() * guess));
        for iteration in 0..max_iterations {
            let force = g.transpose() * lambda;
            let (v, rate) = inner(&force)?;
            let q_next = q + v * h;
            let psi = model.constraints(t_next, &q_next);
            let g_next = model.constraint_jacobian(t_next, &q_next);
            if !psi.iter().chain(g_next.iter()).all(|x| x.is_finite()) {
                return Ok(Outer::Diverged(iteration + 1));
            }
            let tolerance = position_tolerance(&g_next, &q_next);
            if (0..C).all(|i| psi[i].abs() <= tolerance[i]) {
                return Ok(Outer::Converged(v, rate, force));
            }
            lambda += schur.solve(&psi) / (h * h);
        }
        Ok(Outer::Diverged(max_iterations))
    }
}
