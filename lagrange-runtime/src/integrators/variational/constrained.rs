//! The constrained step (RATTLE): the variational integrator on a model
//! with holonomic constraints, symplectic on the constraint manifold.
//!
//! With the multipliers `λ` of the constraint forces, one step from
//! `(q_k, p_k)` solves
//!
//! ```text
//! p_k − h G(q_k)ᵀ λ + (h/2)(∂L/∂q + Q) − ∂L/∂q̇ = 0,    φ(t_{k+1}, q_k + h v̄) = 0
//! ```
//!
//! for `(v̄, λ)` (at the midpoint, as the unconstrained step), sets
//! `q_{k+1} = q_k + h v̄`, `p̃ = p_k − h G(q_k)ᵀ λ + h (∂L/∂q + Q)`, and then
//! takes the impulse `G(q_{k+1})ᵀ μ` off `p̃` so that the velocity of
//! `p_{k+1}` satisfies `φ̇ = 0`: the velocity projection of `M⁻¹ (p̃ − ∂L/∂q̇(q, 0))`
//! in the metric of `M`. These are the discrete constrained
//! Euler–Lagrange equations in position–momentum form (Marsden & West,
//! *Discrete mechanics and variational integrators*, §3.5; RATTLE for the
//! midpoint discrete Lagrangian): the step is a symplectic map of the
//! constrained phase space, so energy errors stay bounded, and both
//! constraints hold at every step to the Newton tolerance.
//!
//! `λ` is found by an outer iteration around the unconstrained solve
//! (`constraints/rattle.rs`); each outer iteration is one unconstrained
//! Newton solve with the momenta `p_k − h Gᵀ λ`.

use nalgebra::{RealField, SVector};

use super::newton::{DiscreteEulerLagrange, StepFailure};
use super::rattle::{Outer, RattleStep};
use super::velocity::{VelocityHistory, velocity};
use super::{Variational, lacks};
use crate::driver::Recorder;
use crate::dynamics::projection::VelocityProjection;
use crate::error::IntegrationError;
use crate::model::Lagrangian;

impl<S: RealField + Copy> Variational<S> {
    /// `(v̄, ∂L/∂q + Q, Gᵀ λ)` of one constrained step from `del`'s
    /// `(q_k, p_k)` to `t_next`, the force `Gᵀ λ` guessed as `force` (the
    /// previous step's).
    #[allow(clippy::type_complexity)]
    pub(super) fn rattle<L: Lagrangian<N, Scalar = S>, const N: usize>(
        &self,
        rec: &mut Recorder<'_, S, N>,
        del: &DiscreteEulerLagrange<'_, L, N>,
        guess: SVector<S, N>,
        force: SVector<S, N>,
        (t, t_next): (S, S),
        near: &SVector<S, N>,
    ) -> Result<(SVector<S, N>, SVector<S, N>, SVector<S, N>), StepFailure<S, N>> {
        let h = del.half_h + del.half_h;
        let stats = &mut rec.stats;
        let inner = |force: &SVector<S, N>| {
            let shifted = DiscreteEulerLagrange {
                model: del.model,
                t_mid: del.t_mid,
                q: del.q,
                p: del.p - force * h,
                half_h: del.half_h,
                augment: del.augment,
            };
            self.solve(stats, &shifted, guess)
        };
        let step = RattleStep {
            t,
            t_next,
            h,
            q: &del.q,
            qdot: near,
            guess: force,
            max_iterations: self.max_iterations,
            augment: del.augment,
            inner,
        };
        match del.model.visit_constraints(step) {
            Some(Ok(Outer::Converged(v, rate, force))) => Ok((v, rate, force)),
            Some(Ok(Outer::Diverged(iterations))) => Err(StepFailure::Diverged { iterations }),
            Some(Err(failure)) => Err(failure),
            None => unreachable!("rattle is only called for constrained models"),
        }
    }

    /// The momenta `p̃` at `(t, q)` after a constrained step corrected by
    /// `−G(q)ᵀ μ` so that their velocity satisfies `φ̇ = 0`, with that
    /// velocity; the residuals recorded.
    pub(super) fn rattle_momenta<L: Lagrangian<N, Scalar = S>, const N: usize>(
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        (t, q, p): (S, &SVector<S, N>, &SVector<S, N>),
        velocities: &VelocityHistory<S, N>,
    ) -> Result<SVector<S, N>, IntegrationError<S, N>> {
        let free = velocity(&mut rec.stats, model, t, q, p, velocities)?;
        let projection = VelocityProjection { t, q, qdot: &free };
        let Some(projected) = model.visit_constraints(projection) else {
            unreachable!("rattle_momenta is only called for constrained models")
        };
        let (qdot, impulse) = projected?;
        rec.record_residuals(model, t, *q, qdot)?;
        if velocities.augment.is_some() {
            // The projected velocity minimizes the distance to `free` in
            // any metric `M + k GᵀG` alike; the momenta of `L'` are those of
            // `L` there, since `φ̇ = 0` (`augmented.rs`).
            return model
                .momentum(t, q, &qdot)
                .ok_or_else(|| lacks("momentum").into());
        }
        Ok(p - impulse)
    }
}
