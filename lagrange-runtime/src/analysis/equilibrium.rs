//! Equilibria: configurations where the model stays at rest,
//! `f(t, q, 0) = 0`, found by Newton's method.

use nalgebra::{DMatrix, DVector, RealField, SMatrix, SVector};

use super::AnalysisError;
use super::derivatives::{forcing_at_rest, relative_noise};
use super::neutral::Neutral;
use super::rest::{ManifoldSearch, ManifoldTest};
use crate::model::Lagrangian;

/// An equilibrium, and the directions along which a family of them
/// extends.
///
/// ```
/// use lagrange::models::CartPole;
/// use lagrange_runtime::analysis::equilibrium;
/// use lagrange_runtime::nalgebra::{Vector1, Vector2};
/// use lagrange_runtime::Actuated;
///
/// // The pole upright stays so wherever the cart stands: a family.
/// let cart = CartPole::new(1.0, 0.2, 0.5, 9.81).with_inputs(&Vector1::new(0.0));
/// let upright = equilibrium(&cart, 0.0, &Vector2::new(0.7, 3.0))?;
/// assert!((upright.q - Vector2::new(0.7, std::f64::consts::PI)).amax() < 1e-12);
/// assert_eq!(upright.neutral.len(), 1); // along the cart's position
/// assert!((upright.neutral[0][0].abs() - 1.0).abs() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Equilibrium<S, const N: usize> {
    /// The configuration at rest.
    pub q: SVector<S, N>,
    /// An orthonormal basis of the neutral directions at `q`: the
    /// displacements `v` with `K v = 0` (`K = −∂f/∂q` at rest; for a
    /// constrained model its part tangent to the constraints, mapped to
    /// the coordinates), to the accuracy of the derivatives. Moving along
    /// them changes no force to first order: the equilibrium is one of a
    /// family (a cyclic coordinate, a free body, a symmetry). Empty for an
    /// isolated equilibrium.
    pub neutral: Vec<SVector<S, N>>,
}

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
/// Where `∂f/∂q` is singular (a family of equilibria: the cart of an
/// upright cart-pole may stand anywhere) the step is the minimum-norm
/// Newton step, through the singular values of `∂f/∂q` (a singular value
/// below the derivatives' accuracy counts as zero): it leaves the neutral
/// directions alone, so the search converges to the member of the family
/// nearest the guess, and the result names the neutral directions. Where
/// `∂f/∂q` moves nothing at all and the force is not zero (a falling
/// body), there is no equilibrium: [`AnalysisError::SingularStiffness`].
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
/// let found = search.solve(&DoublePendulum::unit(), 0.0, &Vector2::new(3.0, 0.2))?;
/// // The upper rod upright, the lower one hanging.
/// assert!((found.q - Vector2::new(std::f64::consts::PI, 0.0)).amax() < 1e-12);
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

    /// An equilibrium near `guess` at time `t`, with its neutral
    /// directions: [`AnalysisError::NotConverged`] (with the last finite
    /// iterate and its residual) when the iterations run out or diverge,
    /// [`AnalysisError::SingularStiffness`] when `∂f/∂q` moves no
    /// coordinate while the force is not zero.
    pub fn solve<L: Lagrangian<N, Scalar = S>, const N: usize>(
        &self,
        model: &L,
        t: S,
        guess: &SVector<S, N>,
    ) -> Result<Equilibrium<S, N>, AnalysisError<S, N>> {
        crate::model::ready(model).map_err(|e| AnalysisError::Model(e.into()))?;
        super::error::refuse_velocity_constraints(model, t, guess)?;
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
            let (f, jacobian, derivatives) = forcing_at_rest(model, t, &q)?;
            residual = f;
            let stiffness = Neutral::new(&dynamic(&jacobian), relative_noise(derivatives, N));
            let Some(step) = stiffness.solve(&DVector::from_column_slice((-f).as_slice())) else {
                // No direction responds: every one is neutral. At rest
                // already, or at no equilibrium at all (a falling body).
                if within(&f, &jacobian, &q, self.tolerance) {
                    return family(model, t, q);
                }
                return Err(AnalysisError::SingularStiffness { t, q, residual: f });
            };
            let step = SVector::from_column_slice(step.as_slice());
            let next = q + step;
            let not_converged = AnalysisError::NotConverged {
                t,
                q,
                residual: f,
                iterations: iteration,
            };
            match progress.update(&step, &next) {
                Verdict::Diverging => return Err(not_converged),
                Verdict::Rounding => return family(model, t, next),
                Verdict::Stalled if within(&f, &jacobian, &q, self.tolerance) => {
                    return family(model, t, next);
                }
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

/// `q`, an equilibrium of `model`, with the neutral directions of the
/// stiffness there.
fn family<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t: L::Scalar,
    q: SVector<L::Scalar, N>,
) -> Result<Equilibrium<L::Scalar, N>, AnalysisError<L::Scalar, N>> {
    let (_, jacobian, derivatives) = forcing_at_rest(model, t, &q)?;
    let stiffness = Neutral::new(&dynamic(&jacobian), relative_noise(derivatives, N));
    let neutral = stiffness
        .directions()
        .iter()
        .map(|v| SVector::from_column_slice(v.as_slice()))
        .collect();
    Ok(Equilibrium { q, neutral })
}

/// A stack matrix on the heap, for the singular value decomposition.
pub(super) fn dynamic<S: RealField + Copy, const N: usize>(k: &SMatrix<S, N, N>) -> DMatrix<S> {
    DMatrix::from_column_slice(N, N, k.as_slice())
}

/// An equilibrium of `model` near `guess` at time `t`, by
/// [`EquilibriumSearch`] with its defaults.
///
/// ```
/// use lagrange::models::DoublePendulum;
/// use lagrange_runtime::analysis::equilibrium;
/// use lagrange_runtime::nalgebra::Vector2;
///
/// let hanging = equilibrium(&DoublePendulum::unit(), 0.0, &Vector2::new(0.3, -0.2))?;
/// assert!(hanging.q.amax() < 1e-14);
/// assert!(hanging.neutral.is_empty()); // isolated
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn equilibrium<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t: L::Scalar,
    guess: &SVector<L::Scalar, N>,
) -> Result<Equilibrium<L::Scalar, N>, AnalysisError<L::Scalar, N>> {
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
    super::error::refuse_velocity_constraints(model, t, q)?;
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
