//! The linearization `δẋ = A δx + B δu` of `ẋ = F(x, u)`, `x = (q, q̇)`, at
//! any state.

use nalgebra::{DMatrix, RealField, SMatrix, SVector};

use super::derivatives::{refuse_constrained, shifted};
use super::{AnalysisError, Derivatives};
use crate::dynamics::{acceleration, mass_error};
use crate::error::{IntegrationError, NonFiniteValue};
use crate::linalg::mass::{MassFactor, factor_mass_matrix};
use crate::model::Lagrangian;
use crate::model::inputs::Actuated;

/// The first-order response of the accelerations at a state `(t, q, q̇)`:
/// `δq̈ = ∂q̈/∂q δq + ∂q̈/∂q̇ δq̇`, the lower blocks of the state matrix
///
/// ```text
/// A = [[0, I], [∂q̈/∂q, ∂q̈/∂q̇]]    (2N × 2N).
/// ```
///
/// The blocks are kept at size `N` on the stack: `SMatrix<S, {2 * N}, _>`
/// cannot be written for a generic `N` on stable Rust, so the assembled
/// `A` is a heap [`DMatrix`] ([`state_matrix`](Self::state_matrix)), and
/// [`apply`](Self::apply) multiplies by it without building it.
///
/// ```
/// use lagrange::models::DoublePendulum;
/// use lagrange_runtime::analysis::{linearize, Derivatives};
/// use lagrange_runtime::nalgebra::Vector2;
///
/// let pendulum = DoublePendulum::unit();
/// let (q, qdot) = (Vector2::new(0.4, -0.2), Vector2::new(1.0, 0.5));
/// let lin = linearize(&pendulum, 0.0, &q, &qdot)?;
/// assert_eq!(lin.derivatives, Derivatives::Exact); // #[lagrange(jacobians)]
/// let a = lin.state_matrix();
/// assert_eq!((a.nrows(), a.ncols()), (4, 4));
/// assert_eq!(a[(0, 2)], 1.0); // q̇ is the derivative of q
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Linearization<S: RealField + Copy, const N: usize> {
    /// The time of the state.
    pub t: S,
    /// The coordinates of the state.
    pub q: SVector<S, N>,
    /// The velocities of the state.
    pub qdot: SVector<S, N>,
    /// `q̈` there: the operating point's own acceleration (zero only at an
    /// equilibrium).
    pub qddot: SVector<S, N>,
    /// `∂q̈/∂q`, `N × N`.
    pub dqddot_dq: SMatrix<S, N, N>,
    /// `∂q̈/∂q̇`, `N × N`: damping, gyroscopic and Coriolis terms.
    pub dqddot_dqdot: SMatrix<S, N, N>,
    /// How the blocks were obtained, and so how accurate they are.
    pub derivatives: Derivatives,
}

impl<S: RealField + Copy, const N: usize> Linearization<S, N> {
    /// The state matrix `A = [[0, I], [∂q̈/∂q, ∂q̈/∂q̇]]`, `2N × 2N`, on the
    /// heap.
    ///
    /// ```
    /// # use lagrange::models::DoublePendulum;
    /// # use lagrange_runtime::analysis::linearize;
    /// # use lagrange_runtime::nalgebra::Vector2;
    /// let lin = linearize(&DoublePendulum::unit(), 0.0, &Vector2::zeros(), &Vector2::zeros())?;
    /// // Hanging: no velocity terms, so the spectrum of A is ±i ω.
    /// let eig = lin.state_matrix().complex_eigenvalues();
    /// assert!(eig.iter().all(|z| z.re.abs() < 1e-9));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn state_matrix(&self) -> DMatrix<S> {
        DMatrix::from_fn(2 * N, 2 * N, |i, j| match (i < N, j < N) {
            (true, true) => S::zero(),
            (true, false) => {
                if j - N == i {
                    S::one()
                } else {
                    S::zero()
                }
            }
            (false, true) => self.dqddot_dq[(i - N, j)],
            (false, false) => self.dqddot_dqdot[(i - N, j - N)],
        })
    }

    /// `A (δq, δq̇) = (δq̇, δq̈)` without assembling `A`: the rate of change
    /// of a small deviation from the operating state.
    ///
    /// ```
    /// # use lagrange::models::DoublePendulum;
    /// # use lagrange_runtime::analysis::linearize;
    /// # use lagrange_runtime::nalgebra::Vector2;
    /// let lin = linearize(&DoublePendulum::unit(), 0.0, &Vector2::zeros(), &Vector2::zeros())?;
    /// let (dq, _) = lin.apply(&Vector2::new(1.0, 0.0), &Vector2::new(0.5, 0.0));
    /// assert_eq!(dq, Vector2::new(0.5, 0.0));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn apply(
        &self,
        dq: &SVector<S, N>,
        dqdot: &SVector<S, N>,
    ) -> (SVector<S, N>, SVector<S, N>) {
        (*dqdot, self.dqddot_dq * dq + self.dqddot_dqdot * dqdot)
    }
}

/// A [`Linearization`] of an actuated model together with
/// `∂q̈/∂u = M⁻¹ ∂f/∂u`, the lower block of `B = [[0], [M⁻¹ ∂f/∂u]]`.
///
/// ```
/// # use lagrange_runtime::analysis::{Derivatives, InputLinearization, Linearization};
/// # use lagrange_runtime::nalgebra::{SMatrix, SVector};
/// let lin = InputLinearization {
///     state: Linearization {
///         t: 0.0, q: SVector::<f64, 1>::zeros(), qdot: SVector::<f64, 1>::zeros(),
///         qddot: SVector::<f64, 1>::zeros(), dqddot_dq: SMatrix::<f64, 1, 1>::new(-4.0),
///         dqddot_dqdot: SMatrix::<f64, 1, 1>::zeros(), derivatives: Derivatives::Exact,
///     },
///     dqddot_du: SMatrix::<f64, 1, 1>::new(0.5),
/// };
/// assert_eq!(lin.input_matrix().as_slice(), &[0.0, 0.5]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InputLinearization<S: RealField + Copy, const N: usize, const K: usize> {
    /// `A`'s blocks, at the inputs given.
    pub state: Linearization<S, N>,
    /// `∂q̈/∂u = M⁻¹ ∂f/∂u`, `N × K`, always from the model's exact
    /// [`input_jacobian`](Actuated::input_jacobian).
    pub dqddot_du: SMatrix<S, N, K>,
}

impl<S: RealField + Copy, const N: usize, const K: usize> InputLinearization<S, N, K> {
    /// The input matrix `B = [[0], [∂q̈/∂u]]`, `2N × K`, on the heap.
    pub fn input_matrix(&self) -> DMatrix<S> {
        DMatrix::from_fn(2 * N, K, |i, j| {
            if i < N {
                S::zero()
            } else {
                self.dqddot_du[(i - N, j)]
            }
        })
    }
}

/// The linearization of `model` at the state `(t, q, q̇)`, which need not be
/// an equilibrium.
///
/// From `r(t, q, q̇, q̈) = M(t, q) q̈ − f(t, q, q̇) = 0`:
/// `∂q̈/∂q = −M⁻¹ ∂r/∂q` and `∂q̈/∂q̇ = −M⁻¹ ∂r/∂q̇`, with `∂r/∂q =
/// ∂(M q̈)/∂q − ∂f/∂q` evaluated at the state's own `q̈`: away from rest the
/// mass matrix's variation times the acceleration is part of the answer.
/// [`Derivatives::Exact`] when the model provides
/// [`residual_jacobians`](Lagrangian::residual_jacobians) (models written
/// with `#[lagrange(jacobians)]`): one `M` factorization and `2N`
/// triangular solves. Otherwise [`Derivatives::CentralDifferences`] of
/// `q̈`, `4N` right-hand sides, relative error `≈ ε^(2/3)`.
///
/// A model with holonomic constraints is refused
/// ([`AnalysisError::Constrained`]): its coordinates are not independent;
/// [`linearize_on_manifold`](super::linearize_on_manifold) linearizes it
/// in independent ones. Failures of `M` come back as
/// [`AnalysisError::Model`] with the state.
///
/// ```
/// use lagrange::models::DoublePendulum;
/// use lagrange_runtime::analysis::linearize;
/// use lagrange_runtime::nalgebra::Vector2;
///
/// // Hanging, m = l = 1: M = [[2, 1], [1, 1]], K = g diag(2, 1), so
/// // ∂q̈/∂q = −M⁻¹ K = g [[−2, 1], [2, −2]].
/// let lin = linearize(&DoublePendulum::unit(), 0.0, &Vector2::zeros(), &Vector2::zeros())?;
/// let g = 9.81;
/// assert!((lin.dqddot_dq[(1, 0)] - 2.0 * g).abs() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn linearize<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
    qdot: &SVector<L::Scalar, N>,
) -> Result<Linearization<L::Scalar, N>, AnalysisError<L::Scalar, N>> {
    crate::model::ready(model).map_err(|e| AnalysisError::Model(e.into()))?;
    refuse_constrained(model, t, q)?;
    let qddot = acceleration(model, t, q, qdot)?;
    let jacobian_error = || {
        let (q, qdot, value) = (*q, *qdot, NonFiniteValue::Jacobian);
        AnalysisError::from(IntegrationError::NonFiniteState { t, q, qdot, value })
    };
    let (dqddot_dq, dqddot_dqdot, derivatives) = match model.residual_jacobians(t, q, qdot, &qddot)
    {
        Some((dr_dq, dr_dqdot)) => {
            finite_or(
                &dr_dq.iter().chain(dr_dqdot.iter()).copied(),
                jacobian_error,
            )?;
            let factor = factor(model, t, q, qdot)?;
            let dq = solve_columns(&factor, t, q, qdot, &-dr_dq)?;
            let dv = solve_columns(&factor, t, q, qdot, &-dr_dqdot)?;
            (dq, dv, Derivatives::Exact)
        }
        None => {
            let mut dq = SMatrix::<L::Scalar, N, N>::zeros();
            let mut dv = dq;
            for k in 0..N {
                let (plus, minus) = shifted(q, k);
                let d =
                    acceleration(model, t, &plus, qdot)? - acceleration(model, t, &minus, qdot)?;
                dq.set_column(k, &(d / (plus[k] - minus[k])));
                let (plus, minus) = shifted(qdot, k);
                let d = acceleration(model, t, q, &plus)? - acceleration(model, t, q, &minus)?;
                dv.set_column(k, &(d / (plus[k] - minus[k])));
            }
            (dq, dv, Derivatives::CentralDifferences)
        }
    };
    let blocks = dqddot_dq.iter().chain(dqddot_dqdot.iter()).copied();
    finite_or(&blocks, jacobian_error)?;
    Ok(Linearization {
        t,
        q: *q,
        qdot: *qdot,
        qddot,
        dqddot_dq,
        dqddot_dqdot,
        derivatives,
    })
}

/// The linearization of an actuated model at `(t, q, q̇)` and the inputs
/// `u`, set on a copy of the model (the model itself keeps its inputs):
/// [`linearize`] for `A`, and `∂q̈/∂u = M⁻¹ ∂f/∂u` from the model's exact
/// [`input_jacobian`](Actuated::input_jacobian) for `B`, `K` more
/// triangular solves.
///
/// ```
/// use lagrange_runtime::analysis::linearize_with_inputs;
/// use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
/// use lagrange_runtime::{Actuated, Lagrangian};
///
/// /// A mass `m` on a spring `k`, pushed by a force `u`.
/// #[derive(Clone, Copy)]
/// struct Pushed { m: f64, k: f64, u: f64 }
/// impl Lagrangian<1> for Pushed {
///     type Scalar = f64;
///     const COORDINATES: [&'static str; 1] = ["x"];
///     fn mass_matrix(&self, _: f64, _: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
///         SMatrix::<f64, 1, 1>::new(self.m)
///     }
///     fn forcing(&self, _: f64, q: &SVector<f64, 1>, _: &SVector<f64, 1>) -> SVector<f64, 1> {
///         Vector1::new(-self.k * q[0] + self.u)
///     }
///     fn kinetic_energy(&self, _: f64, _: &SVector<f64, 1>, v: &SVector<f64, 1>) -> f64 {
///         0.5 * self.m * v[0] * v[0]
///     }
///     fn potential_energy(&self, _: f64, q: &SVector<f64, 1>) -> f64 {
///         0.5 * self.k * q[0] * q[0]
///     }
/// }
/// impl Actuated<1, 1> for Pushed {
///     const INPUTS: [&'static str; 1] = ["u"];
///     fn inputs(&self) -> SVector<f64, 1> { Vector1::new(self.u) }
///     fn set_inputs(&mut self, u: &SVector<f64, 1>) { self.u = u[0]; }
///     fn input_jacobian(&self, _: f64, _: &SVector<f64, 1>, _: &SVector<f64, 1>)
///         -> SMatrix<f64, 1, 1> { SMatrix::<f64, 1, 1>::new(1.0) }
/// }
///
/// let model = Pushed { m: 2.0, k: 8.0, u: 0.0 };
/// let x = Vector1::new(0.0);
/// let lin = linearize_with_inputs(&model, 0.0, &x, &x, &Vector1::new(3.0))?;
/// assert!((lin.state.qddot[0] - 1.5).abs() < 1e-15); // u / m
/// let b = lin.input_matrix(); // B = [0; 1/m]
/// assert!(b[(0, 0)] == 0.0 && (b[(1, 0)] - 0.5).abs() < 1e-15);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[allow(clippy::type_complexity)]
pub fn linearize_with_inputs<L, const N: usize, const K: usize>(
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
    qdot: &SVector<L::Scalar, N>,
    u: &SVector<L::Scalar, K>,
) -> Result<InputLinearization<L::Scalar, N, K>, AnalysisError<L::Scalar, N>>
where
    L: Actuated<N, K> + Copy,
{
    let mut actuated = *model;
    actuated.set_inputs(u);
    let state = linearize(&actuated, t, q, qdot)?;
    let df_du = actuated.input_jacobian(t, q, qdot);
    finite_or(&df_du.iter().copied(), || {
        AnalysisError::NonFiniteInputJacobian {
            t,
            q: *q,
            qdot: *qdot,
        }
    })?;
    let factor = factor(&actuated, t, q, qdot)?;
    let dqddot_du = solve_columns(&factor, t, q, qdot, &df_du)?;
    Ok(InputLinearization { state, dqddot_du })
}

/// `M(t, q)` factored once for the columns of a Jacobian, its failures
/// reported at the state.
fn factor<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
    qdot: &SVector<L::Scalar, N>,
) -> Result<MassFactor<L::Scalar, N>, AnalysisError<L::Scalar, N>> {
    factor_mass_matrix(&model.mass_matrix(t, q)).map_err(|err| mass_error(err, t, q, qdot).into())
}

/// `M⁻¹ b`, column by column; `b` is finite, so a non-finite column is an
/// overflow, reported as a singular `M`.
fn solve_columns<S: RealField + Copy, const N: usize, const C: usize>(
    factor: &MassFactor<S, N>,
    t: S,
    q: &SVector<S, N>,
    qdot: &SVector<S, N>,
    b: &SMatrix<S, N, C>,
) -> Result<SMatrix<S, N, C>, AnalysisError<S, N>> {
    let mut out = SMatrix::<S, N, C>::zeros();
    for k in 0..C {
        let column = factor
            .solve(&b.column(k).into_owned())
            .map_err(|err| mass_error(err, t, q, qdot))?;
        out.set_column(k, &column);
    }
    Ok(out)
}

/// `Err(error())` unless every value is finite.
fn finite_or<S: RealField + Copy, E>(
    values: &(impl Iterator<Item = S> + Clone),
    error: impl FnOnce() -> E,
) -> Result<(), E> {
    if values.clone().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(error())
    }
}
