//! Equilibria: configurations where the model stays at rest,
//! `f(t, q, 0) = 0`, found by Newton's method.

use nalgebra::{RealField, SMatrix, SVector};

use super::derivatives::forcing_at_rest;
use super::rest::{ManifoldSearch, ManifoldTest};
use super::AnalysisError;
use crate::linalg::solve::lu_solve;
use crate::model::Lagrangian;

/// Newton's method on `f(t, q, 0) = 0` with its settings; [`equilibrium`]
/// runs it with the defaults.
///
/// Each iteration evaluates `f` and `∂f/∂q` at rest (exact with the
/// model's residual Jacobians, else `2N` more forcings for central
/// differences) and solves one `N × N` system on the stack. It stops when
/// a correction is at rounding level, `|Δq_k| ≤ 4 ε max(1, |q_k|)`, or when
/// corrections stop shrinking (they have reached the noise of evaluating
/// `f`) at a point that passes [`is_equilibrium`] with `tolerance`. It
/// gives up, with [`AnalysisError::NotConverged`], when the corrections
/// more than double three times in a row (overshooting ever further: a
/// guess outside the basin of attraction) or the iterations run out.
/// Models with inputs are searched at the inputs they hold.
///
/// A constrained model's guess is first projected onto `φ = 0`; each
/// iteration then solves `K_z δz = Tᵀ f` in the coordinates tangent to the
/// constraints (`K_z` by central differences of the saddle-point `q̈`,
/// see [the module](super#constrained-models)), moves by `T δz` and
/// projects back; the residuals it reports are `f − Gᵀ λ`.
///
/// ```
/// use lagrange::models::DoublePendulum;
/// use lagrange_runtime::analysis::EquilibriumSearch;
/// use lagrange_runtime::nalgebra::Vector2;
///
/// let search = EquilibriumSearch::new().max_iterations(20);
/// let q = search.solve(&DoublePendulum::unit(), 0.0, &Vector2::new(3.0, 0.2))?;
/// // The upper rod upright, the lower one hanging.
/// assert!((q - Vector2::new(std::f64::consts::PI, 0.0)).amax() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EquilibriumSearch<S> {
    max_iterations: usize,
    tolerance: S,
}

impl<S: RealField + Copy> Default for EquilibriumSearch<S> {
    fn default() -> Self {
        Self::new()
    }
}

impl<S: RealField + Copy> EquilibriumSearch<S> {
    /// 50 iterations, tolerance `√ε` (see [`is_equilibrium`]). Newton from
    /// a guess in the basin converges in a handful; 50 is for a guess that
    /// takes a long way round before the quadratic phase.
    pub fn new() -> Self {
        Self {
            max_iterations: 50,
            tolerance: S::default_epsilon().sqrt(),
        }
    }

    /// The iteration limit.
    pub fn max_iterations(mut self, max_iterations: usize) -> Self {
        self.max_iterations = max_iterations;
        self
    }

    /// The relative tolerance an iterate must meet when the corrections
    /// stall above rounding level (see [`is_equilibrium`]).
    pub fn tolerance(mut self, tolerance: S) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// An equilibrium near `guess` at time `t`: [`AnalysisError::NotConverged`]
    /// (with the last finite iterate and its residual) when the iterations
    /// run out or diverge, [`AnalysisError::SingularStiffness`] when
    /// `∂f/∂q` is singular on the way.
    pub fn solve<L: Lagrangian<N, Scalar = S>, const N: usize>(
        &self,
        model: &L,
        t: S,
        guess: &SVector<S, N>,
    ) -> Result<SVector<S, N>, AnalysisError<S, N>> {
        crate::model::ready(model).map_err(|e| AnalysisError::Model(e.into()))?;
        if let Some(result) = model.visit_constraints(ManifoldSearch {
            search: self,
            t,
            guess,
        }) {
            return result;
        }
        let mut q = *guess;
        let mut progress = Progress::new(guess);
        let mut residual = SVector::zeros();
        for iteration in 1..=self.max_iterations {
            let (f, jacobian, _) = forcing_at_rest(model, t, &q)?;
            residual = f;
            let Ok(step) = lu_solve(jacobian, -f) else {
                return Err(AnalysisError::SingularStiffness { t, q, residual: f });
            };
            let next = q + step;
            let not_converged = AnalysisError::NotConverged {
                t,
                q,
                residual: f,
                iterations: iteration,
            };
            match progress.update(&step, &next) {
                Verdict::Diverging => return Err(not_converged),
                Verdict::Rounding => return Ok(next),
                Verdict::Stalled if within(&f, &jacobian, &q, self.tolerance) => return Ok(next),
                _ => {}
            }
            q = next;
        }
        let iterations = self.max_iterations;
        Err(AnalysisError::NotConverged {
            t,
            q,
            residual,
            iterations,
        })
    }

    /// The iteration limit.
    pub(super) fn iterations(&self) -> usize {
        self.max_iterations
    }

    /// The tolerance of a stalled iterate.
    pub(super) fn tolerance_of(&self) -> S {
        self.tolerance
    }
}

/// What a Newton correction says about the search.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Verdict {
    /// Still converging.
    Going,
    /// The correction is at rounding level: converged.
    Rounding,
    /// The correction did not halve: at the noise of the evaluation.
    Stalled,
    /// Overshooting ever further, or left the finite numbers.
    Diverging,
}

/// The stopping rules of Newton's method for an equilibrium, shared by the
/// free and the constrained searches: a correction at rounding level
/// (`|Δq_k| ≤ 4 ε max(1, |q_k|)`), corrections that stop shrinking
/// (stalled at the noise of the evaluation, accepted if the iterate passes
/// the equilibrium test), or corrections that more than double three times
/// running in the fixed scale of the guess (Newton overshooting further
/// each time: a guess outside the basin).
pub(super) struct Progress<'a, S, const N: usize> {
    guess: &'a SVector<S, N>,
    previous: Option<S>,
    previous_length: Option<S>,
    growth: usize,
}

impl<'a, S: RealField + Copy, const N: usize> Progress<'a, S, N> {
    pub(super) fn new(guess: &'a SVector<S, N>) -> Self {
        Self {
            guess,
            previous: None,
            previous_length: None,
            growth: 0,
        }
    }

    /// The verdict on the correction `step` that led to `next`.
    pub(super) fn update(&mut self, step: &SVector<S, N>, next: &SVector<S, N>) -> Verdict {
        if next.iter().any(|x| !x.is_finite()) {
            return Verdict::Diverging;
        }
        let four: S = nalgebra::convert(4.0);
        let size = (0..N).fold(S::zero(), |m, k| {
            m.max(step[k].abs() / S::one().max(next[k].abs()))
        });
        let stalled = self.previous.is_some_and(|p: S| size + size >= p);
        let length = (0..N).fold(S::zero(), |m, k| {
            m.max(step[k].abs() / S::one().max(self.guess[k].abs()))
        });
        self.growth = match self.previous_length {
            Some(p) if length > p + p => self.growth + 1,
            _ => 0,
        };
        self.previous_length = Some(length);
        self.previous = Some(size);
        if self.growth == 3 {
            Verdict::Diverging
        } else if size <= four * S::default_epsilon() {
            Verdict::Rounding
        } else if stalled {
            Verdict::Stalled
        } else {
            Verdict::Going
        }
    }
}

/// An equilibrium of `model` near `guess` at time `t`, by
/// [`EquilibriumSearch`] with its defaults.
///
/// ```
/// use lagrange::models::DoublePendulum;
/// use lagrange_runtime::analysis::equilibrium;
/// use lagrange_runtime::nalgebra::Vector2;
///
/// let q = equilibrium(&DoublePendulum::unit(), 0.0, &Vector2::new(0.3, -0.2))?;
/// assert!(q.amax() < 1e-14); // hanging
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn equilibrium<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t: L::Scalar,
    guess: &SVector<L::Scalar, N>,
) -> Result<SVector<L::Scalar, N>, AnalysisError<L::Scalar, N>> {
    EquilibriumSearch::new().solve(model, t, guess)
}

/// Whether `q` is an equilibrium at time `t` to the relative tolerance
/// `tol`: every component of the forcing at rest is within the force that
/// a displacement of `tol max(1, |q_j|)` in each coordinate would produce,
///
/// ```text
/// |f_i(t, q, 0)| ≤ tol Σ_j |∂f_i/∂q_j| max(1, |q_j|),
/// ```
///
/// which is free of the units of the forces and, for coordinates of size
/// one or more, of the coordinates. An equilibrium within `tol` is that
/// close to an exact one (to first order, where `∂f/∂q` is regular). Costs
/// one forcing and its Jacobian.
///
/// For a constrained model: `false` off the constraints (beyond `√ε`),
/// else the same test on the tangent force `Tᵀ f` with the tangent
/// stiffness `K_z` (see [`modes`](super::modes)).
///
/// ```
/// use lagrange::models::DoublePendulum;
/// use lagrange_runtime::analysis::is_equilibrium;
/// use lagrange_runtime::nalgebra::Vector2;
///
/// let pendulum = DoublePendulum::unit();
/// let pi = std::f64::consts::PI;
/// assert!(is_equilibrium(&pendulum, 0.0, &Vector2::new(pi, pi), 1e-12)?);
/// assert!(!is_equilibrium(&pendulum, 0.0, &Vector2::new(1e-6, 0.0), 1e-8)?);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn is_equilibrium<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
    tol: L::Scalar,
) -> Result<bool, AnalysisError<L::Scalar, N>> {
    crate::model::ready(model).map_err(|e| AnalysisError::Model(e.into()))?;
    if let Some(result) = model.visit_constraints(ManifoldTest { t, q, tol }) {
        return result;
    }
    let (f, jacobian, _) = forcing_at_rest(model, t, q)?;
    Ok(within(&f, &jacobian, q, tol))
}

/// The test of [`is_equilibrium`] on an evaluated forcing and Jacobian.
pub(super) fn within<S: RealField + Copy, const N: usize>(
    f: &SVector<S, N>,
    jacobian: &SMatrix<S, N, N>,
    q: &SVector<S, N>,
    tol: S,
) -> bool {
    (0..N).all(|i| {
        let scale = (0..N).fold(S::zero(), |s, j| {
            s + jacobian[(i, j)].abs() * S::one().max(q[j].abs())
        });
        f[i].abs() <= tol * scale
    })
}
