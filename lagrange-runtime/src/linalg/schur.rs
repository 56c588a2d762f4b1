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
        let (x, s) = match mass {
            MassFactor::Cholesky(ldlt) => {
                let (mut x, s) = forward_rows(ldlt, g);
                for mut column in x.column_iter_mut() {
                    let mut z = column.clone_owned();
                    ldlt.backward(&mut z);
                    column.copy_from(&z);
                }
                (x, s)
            }
            MassFactor::Lu(_) => {
                let mut x = g.transpose();
                for mut column in x.column_iter_mut() {
                    column.copy_from(&mass.solve(&column.clone_owned())?);
                }
                let gx = g * x;
                (x, (gx + gx.transpose()) * nalgebra::convert::<f64, S>(0.5))
            }
        };
        let factor = judged(&s)?;
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

/// `Z = L⁻¹ Gᵀ` and `S = Zᵀ D⁻¹ Z = G M⁻¹ Gᵀ` (symmetric positive
/// semi-definite by construction, no square root), for [`Schur::new`] and
/// [`solve_saddle`] alike.
#[inline]
fn forward_rows<S: RealField + Copy, const N: usize, const C: usize>(
    ldlt: &Ldlt<S, N>,
    g: &SMatrix<S, C, N>,
) -> (SMatrix<S, N, C>, SMatrix<S, C, C>) {
    let mut z = g.transpose();
    for mut column in z.column_iter_mut() {
        let mut c = column.clone_owned();
        ldlt.forward(&mut c);
        column.copy_from(&c);
    }
    let inverse = ldlt.inverse_pivots();
    let mut s = SMatrix::<S, C, C>::zeros();
    for i in 0..C {
        for j in 0..=i {
            let mut sum = S::zero();
            for k in 0..N {
                sum += z[(k, i)] * inverse[k] * z[(k, j)];
            }
            s[(i, j)] = sum;
            s[(j, i)] = sum;
        }
    }
    (z, s)
}

/// `S = G M⁻¹ Gᵀ` factored, or [`SaddleError::Singular`] where it is
/// numerically singular, as [`Schur::new`] says.
#[inline]
fn judged<S: RealField + Copy, const C: usize>(
    s: &SMatrix<S, C, C>,
) -> Result<Ldlt<S, C>, SaddleError> {
    for i in 0..C {
        let sii = s[(i, i)];
        if !(sii > S::zero() && sii.is_finite()) {
            return Err(SaddleError::Singular);
        }
    }
    let factor = Ldlt::new(s).ok_or(SaddleError::Singular)?;
    // One constraint: `D_S S D_S` is the number one, nothing to judge.
    if C > 1 {
        let unit = SVector::<S, C>::from_fn(|i, _| factor.pivots()[i] / s[(i, i)]);
        let c: S = nalgebra::convert(C as f64);
        let smallest = unit.min();
        if !smallest.is_finite() || smallest <= c * S::default_epsilon() * unit.max() {
            return Err(SaddleError::Singular);
        }
    }
    Ok(factor)
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
    let k = regularization_weight(m, &gtg);
    (m + gtg * k, k)
}

/// `k` of `M + k GᵀG`: the ratio of the largest entries of `M` and `GᵀG`,
/// one where either is zero.
pub(crate) fn regularization_weight<S: RealField + Copy, const N: usize>(
    m: &SMatrix<S, N, N>,
    gtg: &SMatrix<S, N, N>,
) -> S {
    let (ms, gs) = (m.amax(), gtg.amax());
    if ms > S::zero() && gs > S::zero() {
        ms / gs
    } else {
        S::one()
    }
}

/// `(q̈, λ)` of the saddle-point system with bias `gamma`.
///
/// With `M = L D Lᵀ`, one forward substitution each for `f` and the rows
/// of `G` and one backward substitution in all: `z = L⁻¹ f`,
/// `Z = L⁻¹ Gᵀ`, `S = Zᵀ D⁻¹ Z`, `λ = S⁻¹ (Zᵀ D⁻¹ z + γ)` and
/// `q̈ = L⁻ᵀ D⁻¹ (z − Z λ)`, where the projections' [`Schur`] forms
/// `M⁻¹ Gᵀ` (one backward substitution per constraint) and `M⁻¹ f`. `S`
/// is formed and judged as there. Where `S` is refused or the result is
/// not finite, and with the LU fallback, the answer (or the error, and
/// whom it blames) is [`Schur`]'s.
#[inline]
pub(crate) fn solve_saddle<S: RealField + Copy, const N: usize, const C: usize>(
    mass: &MassFactor<S, N>,
    f: &SVector<S, N>,
    g: &SMatrix<S, C, N>,
    gamma: &SVector<S, C>,
) -> Result<(SVector<S, N>, SVector<S, C>), SaddleError> {
    if let MassFactor::Cholesky(ldlt) = mass {
        if let Some(solution) = by_cholesky(ldlt, f, g, gamma) {
            return Ok(solution);
        }
    }
    by_schur(mass, f, g, gamma)
}

/// The Cholesky branch of [`solve_saddle`]: `(q̈, λ)` with one backward
/// substitution, or `None` where `S` is refused or the result is not
/// finite, for [`solve_saddle`]'s fallback to say why.
#[inline]
#[allow(clippy::type_complexity)]
pub(crate) fn by_cholesky<S: RealField + Copy, const N: usize, const C: usize>(
    ldlt: &Ldlt<S, N>,
    f: &SVector<S, N>,
    g: &SMatrix<S, C, N>,
    gamma: &SVector<S, C>,
) -> Option<(SVector<S, N>, SVector<S, C>)> {
    let mut z = *f;
    ldlt.forward(&mut z);
    let (zg, s) = forward_rows(ldlt, g);
    let inverse = ldlt.inverse_pivots();
    let mut r = *gamma;
    for i in 0..C {
        let mut sum = S::zero();
        for k in 0..N {
            sum += zg[(k, i)] * inverse[k] * z[k];
        }
        r[i] += sum;
    }
    let factor = judged(&s).ok()?;
    let lambda = factor.solve(&r);
    let mut qddot = z - zg * lambda;
    ldlt.backward(&mut qddot);
    (all_finite(qddot.as_slice()) && all_finite(lambda.as_slice())).then_some((qddot, lambda))
}

/// [`solve_saddle`] through [`Schur`]: `M⁻¹ f` and `M⁻¹ Gᵀ` each solved
/// and checked, so that a failure is blamed on `M` or on the constraints.
fn by_schur<S: RealField + Copy, const N: usize, const C: usize>(
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

#[cfg(test)]
mod tests {
    use nalgebra::{SMatrix, SVector};

    use super::{SaddleError, by_schur, solve_saddle};
    use crate::linalg::ldlt::tests::uniform;
    use crate::linalg::mass::factor_mass_matrix;

    /// The one-backward-substitution solve against the one through
    /// `M⁻¹ f` and `M⁻¹ Gᵀ`, and both against the saddle-point equations.
    /// `M` has eigenvalues in `[N, N + N²]` and `G` entries of order one,
    /// so `S` and the whole system are conditioned to about `N²`: the two
    /// orders of the same arithmetic agree, and the residuals vanish, to
    /// `1e-12` relative, a thousand times that times `ε`.
    fn agree<const N: usize, const C: usize>(seed: u64) {
        let mut state = seed;
        for _ in 0..100 {
            let a = SMatrix::<f64, N, N>::from_fn(|_, _| uniform(&mut state));
            let m = a * a.transpose() + SMatrix::<f64, N, N>::identity() * N as f64;
            let g = SMatrix::<f64, C, N>::from_fn(|_, _| uniform(&mut state));
            let f = SVector::<f64, N>::from_fn(|_, _| uniform(&mut state));
            let gamma = SVector::<f64, C>::from_fn(|_, _| uniform(&mut state));
            let mass = factor_mass_matrix(&m).ok().unwrap();
            let (Ok((qddot, lambda)), Ok((qddot_s, lambda_s))) = (
                solve_saddle(&mass, &f, &g, &gamma),
                by_schur(&mass, &f, &g, &gamma),
            ) else {
                panic!("a regular saddle-point system refused");
            };
            let scale = 1.0 + qddot.amax() + lambda.amax();
            assert!((qddot - qddot_s).amax() < 1e-12 * scale);
            assert!((lambda - lambda_s).amax() < 1e-12 * scale);
            let force = m * qddot + g.transpose() * lambda - f;
            let constraint = g * qddot + gamma;
            assert!(force.amax() < 1e-12 * scale * (1.0 + m.amax()));
            assert!(constraint.amax() < 1e-12 * scale);
        }
    }

    #[test]
    fn one_backward_substitution_solves_the_saddle_point_system() {
        agree::<2, 1>(1);
        agree::<3, 2>(2);
        agree::<7, 3>(3);
        agree::<40, 5>(4);
    }

    #[test]
    fn dependent_constraints_are_singular_either_way() {
        let m = SMatrix::<f64, 3, 3>::new(2.0, 0.5, 0.0, 0.5, 3.0, 0.1, 0.0, 0.1, 1.0);
        // The second row is twice the first.
        let g = SMatrix::<f64, 2, 3>::new(1.0, -1.0, 0.5, 2.0, -2.0, 1.0);
        let f = SVector::<f64, 3>::new(1.0, 2.0, 3.0);
        let gamma = SVector::<f64, 2>::new(0.1, 0.2);
        let mass = factor_mass_matrix(&m).ok().unwrap();
        assert!(matches!(
            solve_saddle(&mass, &f, &g, &gamma),
            Err(SaddleError::Singular)
        ));
        assert!(matches!(
            by_schur(&mass, &f, &g, &gamma),
            Err(SaddleError::Singular)
        ));
    }
}
