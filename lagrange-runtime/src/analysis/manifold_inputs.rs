//! The input matrix `B` of an actuated model in the independent
//! coordinates of its constraint manifold: the part of `∂f/∂u` the
//! constraints do not carry, exact through the Schur complement.

use crate::dynamics::saddle::saddle_error;
use crate::model::settings::ConstraintSettings;
use nalgebra::{DMatrix, RealField, SVector};

use super::{AnalysisError, ManifoldLinearization, linearize_on_manifold};
use crate::dynamics::mass_error;
use crate::linalg::mass::factor_mass_matrix;
use crate::linalg::schur::Schur;
use crate::model::constraints::{Holonomic, Visitor};
use crate::model::inputs::Actuated;

/// A [`ManifoldLinearization`] of an actuated model with its input matrix
/// in the independent coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct ManifoldInputLinearization<S: RealField + Copy, const N: usize> {
    /// `A` and the basis, at the inputs given.
    pub state: ManifoldLinearization<S, N>,
    /// `∂q̈/∂u`, `N × K`: the constrained accelerations' response to each
    /// input, `(M⁻¹ − M⁻¹Gᵀ (G M⁻¹ Gᵀ)⁻¹ G M⁻¹) ∂f/∂u`, exact from the
    /// model's [`input_jacobian`](Actuated::input_jacobian) (the identity
    /// of `G` for a model without constraints).
    pub dqddot_du: DMatrix<S>,
    /// `B = [[0], [Tᵀ ∂q̈/∂u]]`, `2D × K`.
    pub input_matrix: DMatrix<S>,
}

/// [`linearize_on_manifold`] of an actuated model at the inputs `u`, with
/// `B`: a force the constraints carry (normal to them) drops out, the rest
/// moves the independent coordinates.
///
/// ```
/// use lagrange::prelude::*;
/// use lagrange::nalgebra::Vector2;
/// use lagrange_runtime::analysis::linearize_on_manifold_with_inputs;
///
/// lagrangian! {
///     /// A bob on a rod in x, y, pushed by the input `fx` along x and
///     /// pulled by `fy` along y.
///     struct Pushed {
///         coordinates: x, y;
///         parameters: m, l, g;
///         inputs: fx, fy;
///         kinetic: m/2*(dot(x)^2 + dot(y)^2);
///         potential: m*g*y;
///         forces: x = fx, y = fy;
///         constraints: rod: x^2 + y^2 = l^2;
///     }
/// }
///
/// let (m, l) = (2.0f64, 1.5);
/// let model: Pushed = Pushed::new(m, l, 9.81);
/// let (q, qdot) = (Vector2::new(0.0, -l), Vector2::zeros()); // hanging
/// let lin = linearize_on_manifold_with_inputs(&model, 0.0, &q, &qdot, &Vector2::zeros())?;
/// // Pushed sideways, the bob moves along the circle at F / m; pulled
/// // along the rod, not at all: the rod carries that force.
/// assert!((lin.input_matrix[(1, 0)].abs() - 1.0 / m).abs() < 1e-12);
/// assert!(lin.input_matrix[(1, 1)].abs() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn linearize_on_manifold_with_inputs<L, const N: usize, const K: usize>(
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
    qdot: &SVector<L::Scalar, N>,
    u: &SVector<L::Scalar, K>,
) -> Result<ManifoldInputLinearization<L::Scalar, N>, AnalysisError<L::Scalar, N>>
where
    L: Actuated<N, K> + Copy,
{
    let mut actuated = *model;
    actuated.set_inputs(u);
    let state = linearize_on_manifold(&actuated, t, q, qdot)?;
    let df_du = actuated.input_jacobian(t, q, qdot);
    if !crate::linalg::all_finite(df_du.as_slice()) {
        return Err(AnalysisError::NonFiniteInputJacobian {
            t,
            q: *q,
            qdot: *qdot,
        });
    }
    let mass = factor_mass_matrix(&actuated.mass_matrix(t, q))
        .map_err(|err| AnalysisError::from(mass_error(err, t, q, qdot)))?;
    let mut dqddot_du = DMatrix::zeros(N, K);
    for k in 0..K {
        let free = mass
            .solve(&df_du.column(k).into_owned())
            .map_err(|err| AnalysisError::from(mass_error(err, t, q, qdot)))?;
        let response = actuated
            .visit_constraints(InputResponse { t, q, qdot, free })
            .unwrap_or(Ok(free))?;
        dqddot_du.set_column(k, &response);
    }
    let d = state.basis.ncols();
    let mut input_matrix = DMatrix::zeros(2 * d, K);
    input_matrix
        .view_mut((d, 0), (d, K))
        .copy_from(&(state.basis.transpose() * &dqddot_du));
    Ok(ManifoldInputLinearization {
        state,
        dqddot_du,
        input_matrix,
    })
}

/// `x − M⁻¹Gᵀ (G M⁻¹ Gᵀ)⁻¹ G x` for `x = M⁻¹ b`: the part of an
/// unconstrained response that the constraints let through.
struct InputResponse<'a, S, const N: usize> {
    t: S,
    q: &'a SVector<S, N>,
    qdot: &'a SVector<S, N>,
    free: SVector<S, N>,
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for InputResponse<'_, S, N> {
    type Output = Result<SVector<S, N>, AnalysisError<S, N>>;

    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<S>) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let (t, q, qdot) = (self.t, self.q, self.qdot);
        let mass = factor_mass_matrix(&model.mass_matrix(t, q))
            .map_err(|err| AnalysisError::from(mass_error(err, t, q, qdot)))?;
        let g = model.constraint_jacobian(t, q);
        let schur =
            Schur::new(&mass, &g).map_err(|e| AnalysisError::from(saddle_error(e, t, q, qdot)))?;
        let lambda = schur.solve(&(g * self.free));
        Ok(self.free - schur.x * lambda)
    }
}
