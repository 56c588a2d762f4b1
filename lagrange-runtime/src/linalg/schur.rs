//! The saddle-point system `M q̈ + Gᵀ λ = f`, `G q̈ = −γ` on the stack,
//! and the `M⁻¹ Gᵀ (G M⁻¹ Gᵀ)⁻¹` that the projections share with it:
//! matrices in, matrices out, no model.

use nalgebra::{Cholesky, Const, RealField, SMatrix, SVector};

use super::solve::{MassFactor, SolveError};

/// Why the saddle-point system has no usable solution.
pub(crate) enum SaddleError {
    /// Solving with `M` failed, as [`solve_mass_matrix`](super::solve::solve_mass_matrix) says.
    Mass(SolveError),
    /// `G M⁻¹ Gᵀ` is singular or numerically so.
    Singular,
}

impl From<SolveError> for SaddleError {
    fn from(error: SolveError) -> Self {
        Self::Mass(error)
    }
}

/// `G` against a factored `M`: `X = M⁻¹ Gᵀ` and the factored Schur
/// complement `S = G M⁻¹ Gᵀ`, judged for rank scale free.
pub(crate) struct Schur<S: RealField + Copy, const N: usize, const C: usize> {
    /// `M⁻¹ Gᵀ`, `N × C`.
    pub(crate) x: SMatrix<S, N, C>,
    /// The Cholesky factor of `D S D`, where `D = diag(S_ii)^(−½)` scales
    /// each row of `G` to unit length in the `M⁻¹` metric.
    unit: Cholesky<S, Const<C>>,
    /// The diagonal of `D`.
    d: SVector<S, C>,
}

impl<S: RealField + Copy, const N: usize, const C: usize> Schur<S, N, C> {
    /// Factors `G M⁻¹ Gᵀ`. With `M`'s Cholesky factor `L`, `Y = L⁻¹ Gᵀ`
    /// and `S = Yᵀ Y`, symmetric positive semi-definite by construction;
    /// with the LU fallback, `S = G X` symmetrized.
    ///
    /// Rank is judged on `D S D`, whose diagonal is one: its smallest
    /// Cholesky pivot is the squared sine of the angle between a row of `G`
    /// and the span of the others in the `M⁻¹` metric, whatever the units
    /// of the constraints. Below `C ε` the multipliers would be rounding
    /// amplified past `1 / (C ε)`: [`SaddleError::Singular`], as `M`'s
    /// pivots are judged. A row with `S_ii = 0` (a vanishing gradient) is
    /// singular at once; for `C = 1` that is the only way to be singular.
    pub(crate) fn new(mass: &MassFactor<S, N>, g: &SMatrix<S, C, N>) -> Result<Self, SaddleError> {
        let gt = g.transpose();
        let (x, s) = match mass {
            MassFactor::Cholesky(ldlt) => {
                let l = ldlt.cholesky_factor();
                let y = l.solve_lower_triangular(&gt).ok_or(SaddleError::Singular)?;
                let x = l
                    .tr_solve_lower_triangular(&y)
                    .ok_or(SaddleError::Singular)?;
                (x, y.transpose() * y)
            }
            MassFactor::Lu(_) => {
                let mut x = SMatrix::<S, N, C>::zeros();
                for i in 0..C {
                    x.set_column(i, &mass.solve(&gt.column(i).into_owned())?);
                }
                let s = g * x;
                (x, (s + s.transpose()) * nalgebra::convert::<f64, S>(0.5))
            }
        };
        let mut d = SVector::<S, C>::zeros();
        for i in 0..C {
            let sii = s[(i, i)];
            if !(sii > S::zero() && sii.is_finite()) {
                return Err(SaddleError::Singular);
            }
            d[i] = S::one() / sii.sqrt();
        }
        let unit = SMatrix::<S, C, C>::from_fn(|i, j| d[i] * s[(i, j)] * d[j]);
        let unit = unit.cholesky().ok_or(SaddleError::Singular)?;
        let pivots = unit.l_dirty().diagonal().map(|l| l * l);
        let c: S = nalgebra::convert(C as f64);
        let smallest = pivots.min();
        if C > 0 && (!smallest.is_finite() || smallest <= c * S::default_epsilon() * pivots.max()) {
            return Err(SaddleError::Singular);
        }
        if !x.iter().all(|v| v.is_finite()) {
            return Err(SaddleError::Singular);
        }
        Ok(Self { x, unit, d })
    }

    /// `S⁻¹ r = D (D S D)⁻¹ D r`.
    pub(crate) fn solve(&self, r: &SVector<S, C>) -> SVector<S, C> {
        self.unit
            .solve(&r.component_mul(&self.d))
            .component_mul(&self.d)
    }

    /// The change of `q` (or `q̇`) that removes a residual `r` of
    /// `φ` (or `φ̇`) to first order and is smallest in the metric of `M`:
    /// `−M⁻¹ Gᵀ S⁻¹ r`, and the multiplier `S⁻¹ r` it takes.
    pub(crate) fn correction(
        &self,
        r: &SVector<S, C>,
    ) -> Result<(SVector<S, N>, SVector<S, C>), SaddleError> {
        let mu = self.solve(r);
        let delta = -(self.x * mu);
        if delta.iter().chain(mu.iter()).all(|v| v.is_finite()) {
            Ok((delta, mu))
        } else {
            Err(SaddleError::Singular)
        }
    }
}

/// `M + k GᵀG` and `k`, with `k` the ratio of the largest entries of `M`
/// and `GᵀG` (one where either is zero): a mass matrix singular by itself
/// but regular on the null space of `G` made positive definite. The
/// saddle-point system with it and `f − k Gᵀγ` has the same `(q̈, λ)`:
/// `k GᵀG q̈ = −k Gᵀγ` wherever `G q̈ = −γ`.
pub(crate) fn regularized<S: RealField + Copy, const N: usize, const C: usize>(
    m: &SMatrix<S, N, N>,
    g: &SMatrix<S, C, N>,
) -> (SMatrix<S, N, N>, S) {
    let gtg = g.transpose() * g;
    let (ms, gs) = (m.amax(), gtg.amax());
    let k = if ms > S::zero() && gs > S::zero() {
        ms / gs
    } else {
        S::one()
    };
    (m + gtg * k, k)
}

/// `(q̈, λ)` of the saddle-point system with bias `gamma`.
pub(crate) fn solve_saddle<S: RealField + Copy, const N: usize, const C: usize>(
    mass: &MassFactor<S, N>,
    f: &SVector<S, N>,
    g: &SMatrix<S, C, N>,
    gamma: &SVector<S, C>,
) -> Result<(SVector<S, N>, SVector<S, C>), SaddleError> {
    let u = mass.solve(f)?;
    let schur = Schur::new(mass, g)?;
    let lambda = schur.solve(&(g * u + gamma));
    let qddot = u - schur.x * lambda;
    if qddot.iter().chain(lambda.iter()).all(|v| v.is_finite()) {
        Ok((qddot, lambda))
    } else {
        Err(SaddleError::Singular)
    }
}
