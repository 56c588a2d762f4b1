//! The saddle-point system `M q̈ + Gᵀ λ = f`, `G q̈ = −γ` on the stack,
//! and the `M⁻¹ Gᵀ (G M⁻¹ Gᵀ)⁻¹` that the projections share with it:
//! matrices in, matrices out, no model.

use super::all_finite;
use nalgebra::{RealField, SMatrix, SVector};

use super::ldlt::Ldlt;
use super::mass::{MassFactor, SolveError};

/// Why the saddle-point system has no usable solution.
pub(crate) enum SaddleError {
    /// Solving with `M` failed, as [`solve_mass_matrix`](super::mass::solve_mass_matrix) says.
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
    /// `S = L D Lᵀ`.
    factor: Ldlt<S, C>,
}

impl<S: RealField + Copy, const N: usize, const C: usize> Schur<S, N, C> {
    /// Factors `G M⁻¹ Gᵀ`. With `M = L D Lᵀ`, `Z = L⁻¹ Gᵀ`,
    /// `S = Zᵀ D⁻¹ Z` (symmetric positive semi-definite by construction)
    /// and `X = L⁻ᵀ D⁻¹ Z`: no square root. With the LU fallback,
    /// `S = G X` symmetrized.
    ///
    /// Rank is judged as on `D_S S D_S`, where `D_S = diag(S_ii)^(−½)`
    /// scales each row of `G` to unit length in the `M⁻¹` metric: its
    /// pivots are `S`'s own divided by `S_ii`, and the smallest is the
    /// squared sine of the angle between a row of `G` and the span of the
    /// others in that metric, whatever the units of the constraints. Below
    /// `C ε` the multipliers would be rounding amplified past `1 / (C ε)`:
    /// [`SaddleError::Singular`], as `M`'s pivots are judged. A row with
    /// `S_ii = 0` (a vanishing gradient) is singular at once; for `C = 1`
    /// that is the only way to be singular. The factorization itself needs
    /// no such scaling: Cholesky's accuracy is that of the best diagonally
    /// scaled matrix already (van der Sluis; Higham, *Accuracy and
    /// Stability of Numerical Algorithms*, §10.1).
    #[inline]
    pub(crate) fn new(mass: &MassFactor<S, N>, g: &SMatrix<S, C, N>) -> Result<Self, SaddleError> {
        let mut x = g.transpose();
        let mut s = SMatrix::<S, C, C>::zeros();
        match mass {
            MassFactor::Cholesky(ldlt) => {
                for mut column in x.column_iter_mut() {
                    let mut z = column.clone_owned();
                    ldlt.forward(&mut z);
                    column.copy_from(&z);
                }
                let inverse = ldlt.inverse_pivots();
                for i in 0..C {
                    for j in 0..=i {
                        let mut sum = S::zero();
                        for k in 0..N {
                            sum += x[(k, i)] * inverse[k] * x[(k, j)];
                        }
                        s[(i, j)] = sum;
                        s[(j, i)] = sum;
                    }
                }
                for mut column in x.column_iter_mut() {
                    let mut z = column.clone_owned();
                    ldlt.backward(&mut z);
                    column.copy_from(&z);
                }
            }
            MassFactor::Lu(_) => {
                for mut column in x.column_iter_mut() {
                    column.copy_from(&mass.solve(&column.clone_owned())?);
                }
                let gx = g * x;
                s = (gx + gx.transpose()) * nalgebra::convert::<f64, S>(0.5);
            }
        }
        for i in 0..C {
            let sii = s[(i, i)];
            if !(sii > S::zero() && sii.is_finite()) {
                return Err(SaddleError::Singular);
            }
        }
        let factor = Ldlt::new(&s).ok_or(SaddleError::Singular)?;
        // One constraint: `D_S S D_S` is the number one, nothing to judge.
        if C > 1 {
            let unit = SVector::<S, C>::from_fn(|i, _| factor.pivots()[i] / s[(i, i)]);
            let c: S = nalgebra::convert(C as f64);
            let smallest = unit.min();
            if !smallest.is_finite() || smallest <= c * S::default_epsilon() * unit.max() {
                return Err(SaddleError::Singular);
            }
        }
        if !all_finite(x.as_slice()) {
            return Err(SaddleError::Singular);
        }
        Ok(Self { x, factor })
    }

    /// `S⁻¹ r`.
    #[inline]
    pub(crate) fn solve(&self, r: &SVector<S, C>) -> SVector<S, C> {
        self.factor.solve(r)
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
        if all_finite(delta.as_slice()) && all_finite(mu.as_slice()) {
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
#[inline]
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
    if all_finite(qddot.as_slice()) && all_finite(lambda.as_slice()) {
        Ok((qddot, lambda))
    } else {
        Err(SaddleError::Singular)
    }
}
