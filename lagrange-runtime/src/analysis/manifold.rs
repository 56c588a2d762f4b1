//! Independent coordinates on the constraint manifold: the tangent basis
//! `T` of `φ(t, q) = 0`, the consistent velocities, and the reduced
//! linearization [`linearize_on_manifold`].

use crate::model::settings::ConstraintSettings;
use nalgebra::{ComplexField, DMatrix, DVector, RealField, SMatrix, SVector};

use super::derivatives::{central_step, sqrt_epsilon};
use super::{AnalysisError, Derivatives, linearize};
use crate::dynamics::saddle::constrained_accelerations;
use crate::error::{ConstraintLevel, IntegrationError, NonFiniteValue};
use crate::model::Lagrangian;
use crate::model::constraints::{Holonomic, Visitor};

/// The tangent space of the constraints at `q`: `T` (`N × D`, `D = N − C`,
/// orthonormal columns spanning the null space of `G`), and the thin
/// factors `Gᵀ = Q₁ R₁` that give the pseudo-inverse `G⁺ = Q₁ R₁⁻ᵀ`.
pub(super) struct Tangent<S: RealField + Copy> {
    pub(super) basis: DMatrix<S>,
    normal: DMatrix<S>,
    r: DMatrix<S>,
}

impl<S: RealField + Copy> Tangent<S> {
    /// From one Householder QR of the `N × (C + N)` matrix `[Gᵀ | I]`: its
    /// `Q` is square and orthogonal, its first `C` columns span the rows of
    /// `G` (which has full rank: the saddle solve at the point has checked
    /// it, scale free), so the other `N − C` are an orthonormal basis of
    /// the null space. Each column's largest entry is made positive, so
    /// the basis is reproducible.
    pub(super) fn new<const N: usize, const C: usize>(g: &SMatrix<S, C, N>) -> Self {
        let wide = DMatrix::from_fn(N, C + N, |i, j| {
            if j < C {
                g[(j, i)]
            } else if i == j - C {
                S::one()
            } else {
                S::zero()
            }
        });
        let qr = wide.qr();
        let q = qr.q();
        let r = qr.r().view((0, 0), (C, C)).into_owned();
        let normal = q.columns(0, C).into_owned();
        let mut basis = q.columns(C, N - C).into_owned();
        for mut column in basis.column_iter_mut() {
            if column.max() < -column.min() {
                column.neg_mut();
            }
        }
        Self { basis, normal, r }
    }

    /// `−G⁺ b` for the `C × k` matrix `b`: the change of `q̇` normal to the
    /// constraints that cancels a change `b` of `φ̇`; `None` if it
    /// overflows.
    fn lift(&self, b: &DMatrix<S>) -> Option<DMatrix<S>> {
        let y = self.r.transpose().solve_lower_triangular(b)?;
        let lift = -(&self.normal * y);
        crate::linalg::all_finite(lift.as_slice()).then_some(lift)
    }
}

/// The linearization of a constrained model at a state on its constraint
/// manifold, in independent coordinates: `δẏ = A δy` with
/// `δy = (δz, δż)` of size `2D`, `D = N − C` the degrees of freedom.
///
/// The coordinates are `z = Tᵀ (q − q₀)` for the [`basis`](Self::basis)
/// `T` at the operating point (orthonormal, tangent to `φ = 0`), so to
/// first order a consistent deviation is
///
/// ```text
/// δq = T δz,        δq̇ = T δż + W δz,        W = −G⁺ ∂(G q̇ + ∂φ/∂t)/∂q T,
/// ```
///
/// the second from `δφ̇ = 0`, with `G⁺` the pseudo-inverse (so `W` is normal
/// to the constraints and `δż = Tᵀ δq̇` exactly). `A`'s lower blocks are
/// `Tᵀ δq̈` for those deviations, `q̈` being the constrained (saddle-point)
/// acceleration: it includes how the constraint forces change with the
/// state, which is what stiffens a hanging Cartesian pendulum. Away from
/// rest `A` is the linearization in this chart, which turns with respect to
/// a curvilinear one (for the pendulum, `∂z̈/∂z = −(g/l) cos θ − θ̇²`:
/// the `−θ̇²` is the fixed chart's, not the angle's); at an equilibrium its
/// eigenvalues are the chart-free `±√−ω²` of the [`modes`](super::modes).
///
/// ```
/// use lagrange::models::CartesianPendulum;
/// use lagrange_runtime::analysis::linearize_on_manifold;
///
/// let (g, l) = (9.81, 2.0);
/// let pendulum = CartesianPendulum::new(1.0, l, g);
/// let (q, qdot) = pendulum.state(0.0, 0.0); // hanging
/// let lin = linearize_on_manifold(&pendulum, 0.0, &q, &qdot)?;
/// assert_eq!(lin.basis.ncols(), 1); // one degree of freedom
/// let a = &lin.state_matrix; // [[0, 1], [−g/l, 0]]
/// assert!((a[(1, 0)] + g / l).abs() < 1e-8);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ManifoldLinearization<S: RealField + Copy, const N: usize> {
    /// The time of the state.
    pub t: S,
    /// The coordinates of the state.
    pub q: SVector<S, N>,
    /// The velocities of the state.
    pub qdot: SVector<S, N>,
    /// The constrained `q̈` there.
    pub qddot: SVector<S, N>,
    /// `T`, `N × D`: orthonormal columns tangent to the constraints,
    /// `δq = T δz`. For a model without constraints, the identity.
    pub basis: DMatrix<S>,
    /// `W`, `N × D`: the velocity change that keeps `φ̇ = 0` when `q` moves
    /// by `T δz` (zero at rest for constraints that do not move).
    pub velocity_lift: DMatrix<S>,
    /// `A = [[0, I], [∂z̈/∂z, ∂z̈/∂ż]]`, `2D × 2D`.
    pub state_matrix: DMatrix<S>,
    /// How the derivatives were obtained.
    pub derivatives: Derivatives,
}

impl<S: RealField + Copy, const N: usize> ManifoldLinearization<S, N> {
    /// The deviation `(δq, δq̇) = (T δz, T δż + W δz)` of the model's
    /// coordinates that the reduced deviation `(δz, δż)` stands for.
    ///
    /// ```
    /// use lagrange::models::CartesianPendulum;
    /// use lagrange_runtime::analysis::linearize_on_manifold;
    /// use lagrange_runtime::nalgebra::DVector;
    ///
    /// let pendulum = CartesianPendulum::new(1.0, 1.0, 9.81);
    /// let (q, qdot) = pendulum.state(0.0, 0.0);
    /// let lin = linearize_on_manifold(&pendulum, 0.0, &q, &qdot)?;
    /// let (dq, _) = lin.to_coordinates(&DVector::from_element(1, 1e-3), &DVector::zeros(1));
    /// assert!(dq[1].abs() < 1e-15 && dq[0].abs() > 0.0); // sideways, along the circle
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn to_coordinates(
        &self,
        dz: &DVector<S>,
        dzdot: &DVector<S>,
    ) -> (SVector<S, N>, SVector<S, N>) {
        let dq = &self.basis * dz;
        let dqdot = &self.basis * dzdot + &self.velocity_lift * dz;
        (
            SVector::from_fn(|i, _| dq[i]),
            SVector::from_fn(|i, _| dqdot[i]),
        )
    }

    /// `(δz, δż) = (Tᵀ δq, Tᵀ δq̇)`: the reduced coordinates of a deviation
    /// (exact for a consistent one, its tangent part otherwise).
    ///
    /// ```
    /// use lagrange::models::CartesianPendulum;
    /// use lagrange_runtime::analysis::linearize_on_manifold;
    /// use lagrange_runtime::nalgebra::DVector;
    ///
    /// let pendulum = CartesianPendulum::new(1.0, 1.0, 9.81);
    /// let (q, qdot) = pendulum.state(0.4, 1.5);
    /// let lin = linearize_on_manifold(&pendulum, 0.0, &q, &qdot)?;
    /// let (dz, dzdot) = (DVector::from_element(1, 1e-3), DVector::from_element(1, -2e-3));
    /// let (dq, dqdot) = lin.to_coordinates(&dz, &dzdot);
    /// let (back, backdot) = lin.to_reduced(&dq, &dqdot);
    /// assert!((back - dz).amax() < 1e-18 && (backdot - dzdot).amax() < 1e-18);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn to_reduced(
        &self,
        dq: &SVector<S, N>,
        dqdot: &SVector<S, N>,
    ) -> (DVector<S>, DVector<S>) {
        let t = self.basis.transpose();
        (
            &t * DVector::from_column_slice(dq.as_slice()),
            &t * DVector::from_column_slice(dqdot.as_slice()),
        )
    }
}

/// The linearization of `model` at `(t, q, q̇)` in independent coordinates
/// on its constraint manifold ([`ManifoldLinearization`]): the state must
/// be consistent, `φ = 0` and `φ̇ = 0` to `√ε` relative
/// ([`AnalysisError::OffConstraints`]). A model without constraints
/// is linearized by [`linearize`](super::linearize) with `T = I`, so
/// generic code may call this for any model.
///
/// The derivatives are central differences of the constrained acceleration
/// ([`Derivatives::CentralDifferences`], relative error `≈ ε^(2/3)`):
/// along each column of `T` for `q` (`2D` saddle solves), along each
/// coordinate for `q̇` (`2N`), and of `φ̇` along `T` for `W`. Rank-deficient
/// constraints (a change point) are
/// [`SingularConstraints`](crate::error::IntegrationError::SingularConstraints)
/// in [`AnalysisError::Model`], with the state.
///
/// ```
/// use lagrange::models::CartesianPendulum;
/// use lagrange_runtime::analysis::linearize_on_manifold;
///
/// let (g, l) = (9.81, 1.0);
/// let pendulum = CartesianPendulum::new(1.0, l, g);
/// // Upright: z̈ = (g/l) z, unstable.
/// let (q, qdot) = pendulum.state(std::f64::consts::PI, 0.0);
/// let lin = linearize_on_manifold(&pendulum, 0.0, &q, &qdot)?;
/// assert!((lin.state_matrix[(1, 0)] - g / l).abs() < 1e-8);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn linearize_on_manifold<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
    qdot: &SVector<L::Scalar, N>,
) -> Result<ManifoldLinearization<L::Scalar, N>, AnalysisError<L::Scalar, N>> {
    crate::model::ready(model).map_err(|e| AnalysisError::Model(e.into()))?;
    super::error::refuse_velocity_constraints(model, t, q)?;
    if let Some(result) = model.visit_constraints(Reduce { t, q, qdot }) {
        return result;
    }
    let lin = linearize(model, t, q, qdot)?;
    Ok(ManifoldLinearization {
        t,
        q: *q,
        qdot: *qdot,
        qddot: lin.qddot,
        basis: DMatrix::identity(N, N),
        velocity_lift: DMatrix::zeros(N, N),
        state_matrix: lin.state_matrix(),
        derivatives: lin.derivatives,
    })
}

/// [`linearize_on_manifold`] for a model with `C` constraints.
struct Reduce<'a, S, const N: usize> {
    t: S,
    q: &'a SVector<S, N>,
    qdot: &'a SVector<S, N>,
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for Reduce<'_, S, N> {
    type Output = Result<ManifoldLinearization<S, N>, AnalysisError<S, N>>;

    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<S>) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let (t, q, qdot) = (self.t, self.q, self.qdot);
        let qddot = saddle(model, t, q, qdot)?.0;
        consistent(model, t, q, qdot)?;
        let g = model.constraint_jacobian(t, q);
        let tangent = Tangent::new(&g);
        let d = N - C;
        let basis = &tangent.basis;
        // ∂φ̇/∂q along T, then W = −G⁺ (∂φ̇/∂q T).
        let h = central_step(q.amax());
        let mut dphidot = DMatrix::zeros(C, d);
        for k in 0..d {
            let step = SVector::<S, N>::from_fn(|i, _| basis[(i, k)] * h);
            let difference = model.constraint_velocities(t, &(q + step), qdot)
                - model.constraint_velocities(t, &(q - step), qdot);
            for i in 0..C {
                dphidot[(i, k)] = difference[i] / (h + h);
            }
        }
        let non_finite = || {
            let (q, qdot, value) = (*q, *qdot, NonFiniteValue::Jacobian);
            AnalysisError::from(IntegrationError::NonFiniteState { t, q, qdot, value })
        };
        let lift = tangent.lift(&dphidot).ok_or_else(non_finite)?;
        // δq̈ for δq = T e_k, δq̇ = W e_k, and for δq̇ = e_j.
        let dq = along_basis(model, t, q, qdot, basis)?;
        let mut dv = DMatrix::zeros(N, N);
        for j in 0..N {
            let hv = central_step(qdot[j]);
            let (mut plus, mut minus) = (*qdot, *qdot);
            plus[j] += hv;
            minus[j] -= hv;
            let difference = saddle(model, t, q, &plus)?.0 - saddle(model, t, q, &minus)?.0;
            for i in 0..N {
                dv[(i, j)] = difference[i] / (plus[j] - minus[j]);
            }
        }
        let tt = basis.transpose();
        let lower_left = &tt * (dq + &dv * &lift);
        let lower_right = &tt * &dv * basis;
        let mut state_matrix = DMatrix::zeros(2 * d, 2 * d);
        for i in 0..d {
            state_matrix[(i, d + i)] = S::one();
        }
        state_matrix.view_mut((d, 0), (d, d)).copy_from(&lower_left);
        state_matrix
            .view_mut((d, d), (d, d))
            .copy_from(&lower_right);
        if !crate::linalg::all_finite(state_matrix.as_slice()) {
            return Err(non_finite());
        }
        Ok(ManifoldLinearization {
            t,
            q: *q,
            qdot: *qdot,
            qddot,
            basis: tangent.basis,
            velocity_lift: lift,
            state_matrix,
            derivatives: Derivatives::CentralDifferences,
        })
    }
}

/// `(q̈, λ)` of the exact constrained motion (no Baumgarte terms): the
/// saddle-point solve, its failures reported at the state.
#[allow(clippy::type_complexity)]
pub(super) fn saddle<H, const N: usize, const C: usize>(
    model: &H,
    t: H::Scalar,
    q: &SVector<H::Scalar, N>,
    qdot: &SVector<H::Scalar, N>,
) -> Result<(SVector<H::Scalar, N>, SVector<H::Scalar, C>), AnalysisError<H::Scalar, N>>
where
    H: Holonomic<N, C> + ?Sized,
{
    Ok(constrained_accelerations(model, t, q, qdot, None)?)
}

/// `∂q̈/∂q T` (`N × D`) by central differences along the columns of `T`,
/// step `ε^(1/3) max(1, ‖q‖∞)`: `2D` saddle solves.
pub(super) fn along_basis<H, const N: usize, const C: usize>(
    model: &H,
    t: H::Scalar,
    q: &SVector<H::Scalar, N>,
    qdot: &SVector<H::Scalar, N>,
    basis: &DMatrix<H::Scalar>,
) -> Result<DMatrix<H::Scalar>, AnalysisError<H::Scalar, N>>
where
    H: Holonomic<N, C> + ?Sized,
{
    let h = central_step(q.amax());
    let mut out = DMatrix::zeros(N, basis.ncols());
    for k in 0..basis.ncols() {
        let step = SVector::<H::Scalar, N>::from_fn(|i, _| basis[(i, k)] * h);
        let difference =
            saddle(model, t, &(q + step), qdot)?.0 - saddle(model, t, &(q - step), qdot)?.0;
        for i in 0..N {
            out[(i, k)] = difference[i] / (h + h);
        }
    }
    Ok(out)
}

/// `φ(t, q) = 0` to `√ε` relative, each `|φ_i| ≤ √ε ‖G_i‖₁ max(1, ‖q‖∞)`,
/// the change of `φ_i` a relative displacement of `√ε` could make, so a
/// point that passes is within `√ε` of the manifold, the accuracy of
/// [`is_equilibrium`](super::is_equilibrium)'s default.
pub(super) fn on_constraints<H, const N: usize, const C: usize>(
    model: &H,
    t: H::Scalar,
    q: &SVector<H::Scalar, N>,
) -> Result<(), AnalysisError<H::Scalar, N>>
where
    H: Holonomic<N, C> + ?Sized,
{
    let phi = model.constraints(t, q);
    let g = model.constraint_jacobian(t, q);
    let scale = sqrt_epsilon::<H::Scalar>() * nalgebra::one::<H::Scalar>().max(q.amax());
    match (0..C).find(|&i| exceeds(phi[i], g.row(i).lp_norm(1) * scale)) {
        None => Ok(()),
        Some(i) => Err(AnalysisError::OffConstraints {
            t,
            q: *q,
            qdot: SVector::zeros(),
            constraint: H::CONSTRAINTS[i],
            level: ConstraintLevel::Position,
            residual: phi[i],
        }),
    }
}

/// [`on_constraints`], and `φ̇ = 0` to `√ε` relative:
/// `|φ̇_i| ≤ √ε (‖G_i‖₁ ‖q̇‖∞ + |∂φ_i/∂t|)`.
fn consistent<H, const N: usize, const C: usize>(
    model: &H,
    t: H::Scalar,
    q: &SVector<H::Scalar, N>,
    qdot: &SVector<H::Scalar, N>,
) -> Result<(), AnalysisError<H::Scalar, N>>
where
    H: Holonomic<N, C> + ?Sized,
{
    on_constraints(model, t, q)?;
    let phidot = model.constraint_velocities(t, q, qdot);
    let explicit = model.constraint_velocities(t, q, &SVector::zeros());
    let g = model.constraint_jacobian(t, q);
    let tol = sqrt_epsilon::<H::Scalar>();
    let bound = |i: usize| tol * (g.row(i).lp_norm(1) * qdot.amax() + explicit[i].abs());
    match (0..C).find(|&i| exceeds(phidot[i], bound(i))) {
        None => Ok(()),
        Some(i) => Err(AnalysisError::OffConstraints {
            t,
            q: *q,
            qdot: *qdot,
            constraint: H::CONSTRAINTS[i],
            level: ConstraintLevel::Velocity,
            residual: phidot[i],
        }),
    }
}

/// Whether `|residual| > bound`, a NaN on either side counting as beyond.
fn exceeds<S: RealField + Copy>(residual: S, bound: S) -> bool {
    !(residual.is_finite() && bound.is_finite()) || residual.abs() > bound
}
