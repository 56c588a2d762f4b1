//! Rest on the constraint manifold: the equilibria of a constrained model
//! (`f − Gᵀ λ = 0` with `φ = 0`), the test for one, and its modes there.
//! [`equilibrium`](super::equilibrium), [`is_equilibrium`](super::is_equilibrium)
//! and [`modes`](super::modes) reach these through
//! [`Lagrangian::visit_constraints`](crate::model::Lagrangian::visit_constraints).

use crate::model::settings::ConstraintSettings;
use nalgebra::{ComplexField, DMatrix, DVector, RealField, SVector};

use super::derivatives::{relative_noise, sqrt_epsilon};
use super::equilibrium::{Equilibrium, EquilibriumSearch, Progress, Verdict};
use super::manifold::{Tangent, along_basis, on_constraints, saddle};
use super::modes::{Modes, solve_modes};
use super::neutral::Neutral;
use super::{AnalysisError, Derivatives};
use crate::dynamics::mass_error;
use crate::dynamics::projection::project_position;
use crate::error::{IntegrationError, NonFiniteValue};
use crate::linalg::mass::SolveError;
use crate::model::constraints::{Holonomic, Visitor};
use crate::trajectory::Stats;

/// A configuration at rest, seen in the independent coordinates
/// `δq = T δz` tangent to the constraints.
struct Rest<S: RealField + Copy, const N: usize> {
    /// `M q̈` at rest: `f − Gᵀ λ`, the force the constraints do not hold.
    unbalanced: SVector<S, N>,
    tangent: Tangent<S>,
    /// `M_z = Tᵀ M T`.
    mass: DMatrix<S>,
    /// `K_z = −Tᵀ M ∂q̈/∂q T`: at rest (`q̈ = 0`) the Hessian of the
    /// potential plus `λ` times the constraints' (`∇²(V + λᵀ φ)` along the
    /// manifold), symmetric for conservative forces. The `λᵀ ∇²φ` part is
    /// what makes a rod's tension stiffen a hanging Cartesian pendulum.
    stiffness: DMatrix<S>,
    /// `Tᵀ M q̈ = Tᵀ f`, the tangent part of the unbalanced force.
    residual: DVector<S>,
}

/// [`Rest`] at `(t, q)`: one saddle solve, `2D` more for `∂q̈/∂q T`.
fn at_rest<H, const N: usize, const C: usize>(
    model: &H,
    t: H::Scalar,
    q: &SVector<H::Scalar, N>,
) -> Result<Rest<H::Scalar, N>, AnalysisError<H::Scalar, N>>
where
    H: Holonomic<N, C> + ?Sized,
{
    let zero = SVector::zeros();
    let qddot = saddle(model, t, q, &zero)?.0;
    let tangent = Tangent::new(&model.constraint_jacobian(t, q));
    let m = model.mass_matrix(t, q);
    let m = DMatrix::from_fn(N, N, |i, j| m[(i, j)]);
    let jt = along_basis(model, t, q, &zero, &tangent.basis)?;
    let tm = tangent.basis.transpose() * &m;
    let stiffness = -(&tm * jt);
    let mass = &tm * &tangent.basis;
    let qddot = DVector::from_column_slice(qddot.as_slice());
    let unbalanced = &m * qddot;
    let residual = tangent.basis.transpose() * &unbalanced;
    let unbalanced = SVector::from_fn(|i, _| unbalanced[i]);
    if !stiffness
        .iter()
        .chain(residual.iter())
        .all(|x| x.is_finite())
    {
        let (q, qdot, value) = (*q, zero, NonFiniteValue::Jacobian);
        return Err(IntegrationError::NonFiniteState { t, q, qdot, value }.into());
    }
    Ok(Rest {
        unbalanced,
        tangent,
        mass,
        stiffness,
        residual,
    })
}

impl<S: RealField + Copy, const N: usize> Rest<S, N> {
    /// [`within`](super::equilibrium::within) in the tangent coordinates:
    /// each `|r_i| ≤ tol Σ_j |K_z,ij| max(1, ‖q‖∞)`, the force a relative
    /// displacement `tol` along the manifold would produce (the columns of
    /// `T` are unit vectors, so `‖q‖∞` is the size of a coordinate).
    fn within(&self, q: &SVector<S, N>, tol: S) -> bool {
        let size = nalgebra::one::<S>().max(q.amax());
        (0..self.residual.len()).all(|i| {
            let scale = self
                .stiffness
                .row(i)
                .iter()
                .fold(S::zero(), |s, k| s + k.abs());
            self.residual[i].abs() <= tol * scale * size
        })
    }
}

/// [`EquilibriumSearch::solve`] for a constrained model: the guess is
/// projected onto `φ = 0` (the Newton projection of the integrators, in the
/// metric of `M`), then each iteration takes the Newton step on the tangent
/// force, `K_z δz = Tᵀ f` (the minimum-norm one where `K_z` is singular),
/// moves by `T δz`, and projects back.
pub(super) struct ManifoldSearch<'a, S, const N: usize> {
    pub(super) search: &'a EquilibriumSearch<S>,
    pub(super) t: S,
    pub(super) guess: &'a SVector<S, N>,
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for ManifoldSearch<'_, S, N> {
    type Output = Result<Equilibrium<S, N>, AnalysisError<S, N>>;

    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<S>) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let t = self.t;
        // K_z is by central differences of the saddle-point q̈.
        let noise = relative_noise::<S>(Derivatives::CentralDifferences, N - C);
        let zero = SVector::zeros();
        let mut stats = Stats::default();
        let mut project = |q: &SVector<S, N>| project_position(model, t, q, &zero, &mut stats);
        let mut q = project(self.guess)?;
        let mut progress = Progress::new(self.guess);
        let mut residual = SVector::zeros();
        for iteration in 1..=self.search.iterations() {
            let rest = at_rest(model, t, &q)?;
            residual = rest.unbalanced;
            let found = |q: SVector<S, N>| -> Self::Output {
                let rest = at_rest(model, t, &q)?;
                let neutral = Neutral::new(&rest.stiffness, noise)
                    .directions()
                    .iter()
                    .map(|v| SVector::from_fn(|i, _| (rest.tangent.basis.row(i) * v)[0]))
                    .collect();
                Ok(Equilibrium { q, neutral })
            };
            let Some(dz) = Neutral::new(&rest.stiffness, noise).solve(&rest.residual) else {
                // Every tangent direction neutral: at rest, or none.
                if rest.within(&q, self.search.tolerance_of()) {
                    return found(q);
                }
                return Err(AnalysisError::SingularStiffness { t, q, residual });
            };
            let moved = q + SVector::<S, N>::from_fn(|i, _| (rest.tangent.basis.row(i) * &dz)[0]);
            let not_converged = AnalysisError::NotConverged {
                t,
                q,
                residual,
                iterations: iteration,
            };
            if moved.iter().any(|x| !x.is_finite()) {
                return Err(not_converged);
            }
            let next = project(&moved)?;
            match progress.update(&(next - q), &next) {
                Verdict::Diverging => return Err(not_converged),
                Verdict::Rounding => return found(next),
                Verdict::Stalled if rest.within(&q, self.search.tolerance_of()) => {
                    return found(next);
                }
                _ => {}
            }
            q = next;
        }
        let iterations = self.search.iterations();
        Err(AnalysisError::NotConverged {
            t,
            q,
            residual,
            iterations,
        })
    }
}

/// [`is_equilibrium`](super::is_equilibrium) for a constrained model: on
/// the constraints to `√ε` (else false) and the tangent force within `tol`.
pub(super) struct ManifoldTest<'a, S, const N: usize> {
    pub(super) t: S,
    pub(super) q: &'a SVector<S, N>,
    pub(super) tol: S,
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for ManifoldTest<'_, S, N> {
    type Output = Result<bool, AnalysisError<S, N>>;

    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<S>) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        if on_constraints(model, self.t, self.q).is_err() {
            return Ok(false);
        }
        Ok(at_rest(model, self.t, self.q)?.within(self.q, self.tol))
    }
}

/// [`modes`](super::modes) for a constrained model: `K_z v = ω² M_z v` in
/// the tangent coordinates, shapes `T v` in the model's.
pub(super) struct ManifoldModes<'a, S, const N: usize> {
    pub(super) t: S,
    pub(super) q: &'a SVector<S, N>,
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for ManifoldModes<'_, S, N> {
    type Output = Result<Modes<S, N>, AnalysisError<S, N>>;

    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<S>) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let (t, q) = (self.t, self.q);
        on_constraints(model, t, q)?;
        let rest = at_rest(model, t, q)?;
        if !rest.within(q, sqrt_epsilon()) {
            let residual = rest.unbalanced;
            return Err(AnalysisError::NotAnEquilibrium { t, q: *q, residual });
        }
        let derivatives = Derivatives::CentralDifferences;
        let noise = relative_noise::<S>(derivatives, N - C);
        let k = &rest.stiffness;
        let scale = k.amax();
        let asymmetry = if scale > S::zero() {
            (k - k.transpose()).amax() / scale
        } else {
            S::zero()
        };
        if asymmetry > noise {
            return Err(AnalysisError::NonConservative {
                t,
                q: *q,
                asymmetry,
            });
        }
        let half: S = nalgebra::convert(0.5);
        let k = (k + k.transpose()) * half;
        let singular =
            || AnalysisError::from(mass_error(SolveError::Singular, t, q, &SVector::zeros()));
        let chol = rest.mass.cholesky().ok_or_else(singular)?;
        let modes = solve_modes(&k, &chol.l(), &rest.tangent.basis, noise).ok_or_else(singular)?;
        Ok(Modes { modes, derivatives })
    }
}
