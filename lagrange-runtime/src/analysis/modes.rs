//! Normal modes about an equilibrium: `K v = ω² M v`.

use core::cmp::Ordering;

use nalgebra::{DMatrix, RealField, SVector};

use super::derivatives::{forcing_at_rest, relative_noise, sqrt_epsilon};
use super::equilibrium::within;
use super::rest::ManifoldModes;
use super::{AnalysisError, Derivatives};
use crate::dynamics::mass_error;
use crate::linalg::mass::{MassFactor, SolveError, factor_mass_matrix};
use crate::model::Lagrangian;

/// What small motions along one mode do, from the sign of its `ω²`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ModeKind<S> {
    /// `ω² > 0`: an oscillation `cos(ω t)` of angular frequency `ω` (rad per
    /// unit of time).
    Oscillating {
        /// `ω = √ω²`.
        frequency: S,
    },
    /// `ω² < 0`: the equilibrium is unstable along this mode, which grows as
    /// `e^(σ t)`.
    Unstable {
        /// `σ = √−ω²`.
        growth_rate: S,
    },
    /// `|ω²|` within the error of its evaluation of zero: no restoring
    /// force to first order (a cyclic coordinate, a free body, a
    /// degenerate equilibrium); the nonlinear terms decide.
    Neutral,
}

/// One mode: `K v = ω² M v`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mode<S: RealField + Copy, const N: usize> {
    /// The eigenvalue `ω²`.
    pub omega_squared: S,
    /// The shape `v`, normalized in the mass metric (`vᵀ M v = 1`, so the
    /// modal mass is one) with its largest component positive.
    pub shape: SVector<S, N>,
    /// Oscillating, unstable or neutral.
    pub kind: ModeKind<S>,
}

/// The modes of a model about an equilibrium, `ω²` ascending: the most
/// unstable first, then the slowest oscillation.
///
/// ```
/// use lagrange::models::DoublePendulum;
/// use lagrange_runtime::analysis::{modes, ModeKind};
/// use lagrange_runtime::nalgebra::Vector2;
///
/// let pi = std::f64::consts::PI;
/// // Upper rod upright, lower one hanging: one mode falls, one swings.
/// let modes = modes(&DoublePendulum::unit(), 0.0, &Vector2::new(pi, 0.0))?;
/// assert!(matches!(modes.modes[0].kind, ModeKind::Unstable { .. }));
/// assert!(matches!(modes.modes[1].kind, ModeKind::Oscillating { .. }));
/// assert!(!modes.is_stable());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Modes<S: RealField + Copy, const N: usize> {
    /// The modes, `ω²` ascending: one per degree of freedom, `N` for a
    /// model in independent coordinates, `N − C` for one with `C`
    /// constraints (their shapes tangent to the constraints).
    pub modes: Vec<Mode<S, N>>,
    /// How `K` was obtained.
    pub derivatives: Derivatives,
}

impl<S: RealField + Copy, const N: usize> Modes<S, N> {
    /// The angular frequencies `ω` of the oscillating modes, ascending.
    ///
    /// ```
    /// # use lagrange::models::DoublePendulum;
    /// # use lagrange_runtime::analysis::modes;
    /// # use lagrange_runtime::nalgebra::Vector2;
    /// let hanging = modes(&DoublePendulum::unit(), 0.0, &Vector2::zeros())?;
    /// let w: Vec<f64> = hanging.frequencies().collect();
    /// let g: f64 = 9.81;
    /// assert!((w[0] - (g * (2.0 - 2f64.sqrt())).sqrt()).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn frequencies(&self) -> impl Iterator<Item = S> + '_ {
        self.modes.iter().filter_map(|m| match m.kind {
            ModeKind::Oscillating { frequency } => Some(frequency),
            _ => None,
        })
    }

    /// Whether no mode is unstable (neutral modes count as stable here:
    /// linearization cannot decide them).
    pub fn is_stable(&self) -> bool {
        !self
            .modes
            .iter()
            .any(|m| matches!(m.kind, ModeKind::Unstable { .. }))
    }
}

/// The normal modes of `model` about the equilibrium `q` at time `t`.
///
/// With `K = −∂f/∂q` at rest (exact with the model's residual Jacobians,
/// else central differences) and `M = L Lᵀ` (Cholesky), `K v = ω² M v`
/// becomes the symmetric eigenproblem `L⁻¹ K L⁻ᵀ w = ω² w`, `v = L⁻ᵀ w`,
/// whose eigenvalues are real and whose shapes come out `M`-orthonormal.
/// These are the modes of `M δq̈ + K δq = 0`: velocity-dependent forces
/// (damping, gyroscopic terms) are left out, as in any modal analysis; the
/// eigenvalues of the [`Linearization`](super::Linearization)'s state
/// matrix include them.
///
/// Refused with a typed error: a point that is not an equilibrium to `√ε`
/// ([`is_equilibrium`](super::is_equilibrium),
/// [`AnalysisError::NotAnEquilibrium`]); a `K` whose asymmetry exceeds the
/// error of its evaluation (`100 N ε` exact, `100 ε^(2/3)` by differences,
/// relative to its largest entry: non-conservative forces,
/// [`AnalysisError::NonConservative`]); `M` not positive definite. `K` is symmetrized before the solve. A mode is
/// [`ModeKind::Neutral`] when `|ω²|` is within that same relative error of
/// the largest `|ω²|`.
///
/// A constrained model has `N − C` modes, from `K_z w = ω² M_z w` in the
/// independent coordinates `δq = T δz` tangent to `φ = 0` (`M_z = Tᵀ M T`,
/// `K_z = −Tᵀ M ∂q̈/∂q T` with the saddle-point `q̈`, by central
/// differences), shapes `T w` in the model's coordinates, `M`-orthonormal
/// and tangent to the constraints; `q` must be on them to `√ε`
/// ([`AnalysisError::OffConstraints`]). See
/// [the module](super#constrained-models).
///
/// Cost: one `f` and its Jacobian, one Cholesky, a symmetric eigensolve of
/// order `N`. The eigensolve runs on a heap matrix (nalgebra's symmetric
/// eigensolver cannot be named for a generic `N` on stable Rust); the
/// result is on the stack.
///
/// ```
/// use lagrange::models::DoublePendulum;
/// use lagrange_runtime::analysis::modes;
/// use lagrange_runtime::nalgebra::Vector2;
///
/// // m = l = 1 hanging: ω² = g (2 ∓ √2).
/// let g = 9.81;
/// let hanging = modes(&DoublePendulum::unit(), 0.0, &Vector2::zeros())?;
/// let slow = &hanging.modes[0];
/// assert!((slow.omega_squared - g * (2.0 - 2f64.sqrt())).abs() < 1e-12);
/// // In phase: both rods swing the same way, the lower one further.
/// assert!(slow.shape[0] > 0.0 && slow.shape[1] > slow.shape[0]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn modes<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
) -> Result<Modes<L::Scalar, N>, AnalysisError<L::Scalar, N>> {
    crate::model::ready(model).map_err(|e| AnalysisError::Model(e.into()))?;
    super::error::refuse_velocity_constraints(model, t, q)?;
    if let Some(result) = model.visit_constraints(ManifoldModes { t, q }) {
        return result;
    }
    let (f, jacobian, derivatives) = forcing_at_rest(model, t, q)?;
    let tolerance = sqrt_epsilon();
    if !within(&f, &jacobian, q, tolerance) {
        return Err(AnalysisError::NotAnEquilibrium {
            t,
            q: *q,
            residual: f,
        });
    }
    let k = -jacobian;
    let noise = relative_noise::<L::Scalar>(derivatives, N);
    let scale = k.amax();
    let asymmetry = if scale > nalgebra::zero() {
        (k - k.transpose()).amax() / scale
    } else {
        nalgebra::zero()
    };
    if asymmetry > noise {
        return Err(AnalysisError::NonConservative {
            t,
            q: *q,
            asymmetry,
        });
    }
    let half: L::Scalar = nalgebra::convert(0.5);
    let k = (k + k.transpose()) * half;

    let zero = SVector::zeros();
    let chol = match factor_mass_matrix(&model.mass_matrix(t, q)) {
        Ok(MassFactor::Cholesky(chol)) => chol,
        // Positive definite but too ill-conditioned for Cholesky's pivots.
        Ok(MassFactor::Lu(_)) => return Err(mass_error(SolveError::Singular, t, q, &zero).into()),
        Err(err) => return Err(mass_error(err, t, q, &zero).into()),
    };
    let l = chol.cholesky_factor();
    let singular = || AnalysisError::from(mass_error(SolveError::Singular, t, q, &zero));
    let k = DMatrix::from_fn(N, N, |i, j| k[(i, j)]);
    let l = DMatrix::from_fn(N, N, |i, j| l[(i, j)]);
    let modes = solve_modes(&k, &l, &DMatrix::identity(N, N), noise).ok_or_else(singular)?;
    Ok(Modes { modes, derivatives })
}

/// The modes of `K v = ω² M v` with `K` symmetric (`D × D`) and `M = L Lᵀ`,
/// shapes mapped to the model's coordinates by `to_q` (`N × D`): through
/// the symmetric `L⁻¹ K L⁻ᵀ w = ω² w`, `v = L⁻ᵀ w`, so the shapes are
/// `M`-orthonormal; `ω²` ascending, each classified against `noise`
/// relative to the largest `|ω²|`. `None` if a triangular solve fails.
pub(super) fn solve_modes<S: RealField + Copy, const N: usize>(
    k: &DMatrix<S>,
    l: &DMatrix<S>,
    to_q: &DMatrix<S>,
    noise: S,
) -> Option<Vec<Mode<S, N>>> {
    let half: S = nalgebra::convert(0.5);
    // C = L⁻¹ K L⁻ᵀ = L⁻¹ (L⁻¹ K)ᵀ, K symmetric.
    let x = l.solve_lower_triangular(k)?;
    let c = l.solve_lower_triangular(&x.transpose())?;
    let c = (&c + c.transpose()) * half;
    let eigen = c.symmetric_eigen();
    let values = &eigen.eigenvalues;
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&i, &j| values[i].partial_cmp(&values[j]).unwrap_or(Ordering::Equal));
    let largest = values.iter().fold(S::zero(), |m, v| m.max(v.abs()));
    let lt = l.transpose();
    order
        .into_iter()
        .map(|i| {
            let w = eigen.eigenvectors.column(i).into_owned();
            let v = to_q * lt.solve_upper_triangular(&w)?;
            let mut shape = SVector::<S, N>::from_fn(|r, _| v[r]);
            if shape.max() < -shape.min() {
                shape = -shape;
            }
            let omega_squared = values[i];
            Some(Mode {
                omega_squared,
                shape,
                kind: classify(omega_squared, noise * largest),
            })
        })
        .collect()
}

/// The kind of a mode whose `ω²` is known to within `noise`.
fn classify<S: RealField + Copy>(omega_squared: S, noise: S) -> ModeKind<S> {
    if omega_squared.abs() <= noise {
        ModeKind::Neutral
    } else if omega_squared > S::zero() {
        ModeKind::Oscillating {
            frequency: omega_squared.sqrt(),
        }
    } else {
        ModeKind::Unstable {
            growth_rate: (-omega_squared).sqrt(),
        }
    }
}
