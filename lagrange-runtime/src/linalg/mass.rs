//! Solving `M q̈ = f` on the stack, `M` and `f` given: the mass matrix's
//! checks (singular, indefinite, non-finite) in one place, so that they
//! never leak out as NaN. The model's side, `q̈` at a state, is
//! [`acceleration`](crate::dynamics::acceleration).

use core::cmp::Ordering;

use nalgebra::{RealField, SMatrix, SVector};

use super::all_finite;
use super::ldlt::{self, BY_COLUMNS, Ldlt};

/// Why `M q̈ = f` has no usable solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum SolveError {
    /// `M` has a NaN or infinite entry.
    #[error("the mass matrix has a NaN or infinite entry")]
    NonFiniteMassMatrix,
    /// `f` has a NaN or infinite entry.
    #[error("the forcing has a NaN or infinite entry")]
    NonFiniteForcing,
    /// `M` is singular, or so close to it that `q̈` would be noise or overflow.
    #[error("the mass matrix is singular or too ill-conditioned for the scalar type")]
    Singular,
    /// `M` is not positive semi-definite: some velocity has negative
    /// kinetic energy `½ q̇ᵀ M q̇`.
    #[error(
        "the mass matrix is not positive definite: some velocities have negative kinetic energy"
    )]
    Indefinite,
}

/// Solves `M q̈ = f` without allocating.
///
/// Mass matrices are symmetric positive definite whenever the kinetic energy
/// is, so Cholesky comes first (in its square-root-free form `L D Lᵀ`,
/// whose pivots `D` are Cholesky's `L_ii²`). Where it fails, `M` is either positive
/// semi-definite up to rounding (a coordinate without inertia, a chart's
/// pole) or ill-conditioned for Cholesky's pivots, and LU with partial
/// pivoting decides between a solution and [`SolveError::Singular`]; or `M`
/// is clearly indefinite, masses of opposite sign, and that is
/// [`SolveError::Indefinite`], not a solution: a kinetic energy that is
/// negative for some velocities is a modelling error. Either factorization
/// is refused when its smallest pivot is below `N ε` times its largest: the
/// solve would then amplify rounding by more than `1 / (N ε)`, i.e. return
/// noise. A non-finite result from finite input (overflow) counts as
/// singular too.
///
/// ```
/// use lagrange_runtime::linalg::mass::{solve_mass_matrix, SolveError};
/// use nalgebra::{Matrix2, Vector2};
///
/// let m = Matrix2::new(2.0, 1.0, 1.0, 2.0);
/// let qdd = solve_mass_matrix(&m, &Vector2::new(3.0, 3.0)).unwrap();
/// assert!((qdd - Vector2::new(1.0, 1.0)).norm() < 1e-15);
///
/// // A coordinate without inertia: the second row of M is zero.
/// let m = Matrix2::new(1.0, 0.0, 0.0, 0.0);
/// assert_eq!(solve_mass_matrix(&m, &Vector2::new(1.0, 1.0)), Err(SolveError::Singular));
///
/// // Masses of opposite sign: regular, but no kinetic energy.
/// let m = Matrix2::new(1.0, 0.0, 0.0, -1.0);
/// assert_eq!(solve_mass_matrix(&m, &Vector2::new(1.0, 1.0)), Err(SolveError::Indefinite));
/// ```
#[inline]
pub fn solve_mass_matrix<S: RealField + Copy, const N: usize>(
    m: &SMatrix<S, N, N>,
    f: &SVector<S, N>,
) -> Result<SVector<S, N>, SolveError> {
    finite_inputs(m, f)?;
    // As `factor_mass_matrix(m)?.solve(f)`, without the factor moved into
    // a `MassFactor` or an `Option` again (each a copy of `L`, 32 kB at 64
    // coordinates) or `M` checked twice.
    let ldlt = Ldlt::new(m);
    let cholesky = use_cholesky(ldlt.as_ref(), m)?;
    finite_solution(match &ldlt {
        Some(ldlt) if cholesky => ldlt.solve(f),
        _ => lu_solve(*m, *f)?,
    })
}

/// [`solve_mass_matrix`] on an `M` the caller owns and no longer needs:
/// from [`BY_COLUMNS`] coordinates on, factored where it lies, with
/// neither `M` nor its factor copied (32 kB each at 64 coordinates, a few
/// percent of a right-hand side). The same arithmetic, so the same bits
/// and the same errors; `None` where Cholesky refuses `M` or its pivots
/// (the rare cases [`solve_mass_matrix`] hands to LU or calls indefinite,
/// which need the `M` now overwritten): the caller asks again with a fresh
/// `M`. Below [`BY_COLUMNS`], [`solve_mass_matrix`] itself.
#[inline]
pub(crate) fn solve_mass_matrix_in_place<S: RealField + Copy, const N: usize>(
    m: &mut SMatrix<S, N, N>,
    f: &SVector<S, N>,
) -> Option<Result<SVector<S, N>, SolveError>> {
    if N < BY_COLUMNS {
        return Some(solve_mass_matrix(m, f));
    }
    if let Err(error) = finite_inputs(m, f) {
        return Some(Err(error));
    }
    let mut d = SVector::<S, N>::zeros();
    let mut inverse_d = SVector::<S, N>::zeros();
    if !ldlt::factor_in_place(m, &mut d, &mut inverse_d)
        || !well_conditioned::<S, N>((d.min(), d.max()))
    {
        return None;
    }
    let mut x = *f;
    ldlt::forward(m, &mut x);
    ldlt::backward(m, &inverse_d, &mut x);
    Some(finite_solution(x))
}

/// `M` and `f` checked for NaN and infinity, `M` first.
#[inline]
fn finite_inputs<S: RealField + Copy, const N: usize>(
    m: &SMatrix<S, N, N>,
    f: &SVector<S, N>,
) -> Result<(), SolveError> {
    if !all_finite(m.as_slice()) {
        Err(SolveError::NonFiniteMassMatrix)
    } else if !all_finite(f.as_slice()) {
        Err(SolveError::NonFiniteForcing)
    } else {
        Ok(())
    }
}

/// `M` factored once for several right-hand sides, as
/// [`solve_mass_matrix`] decides: Cholesky when its pivots are acceptable,
/// else the matrix itself for LU with partial pivoting (the rare fallback,
/// which refactors per solve). The constrained accelerations solve with
/// `M` for `f` and for each row of `G` through one of these.
pub(crate) enum MassFactor<S: RealField + Copy, const N: usize> {
    /// Cholesky, as `L D Lᵀ`.
    Cholesky(Ldlt<S, N>),
    Lu(SMatrix<S, N, N>),
}

/// Factors `M` with the checks of [`solve_mass_matrix`]: non-finite,
/// indefinite and (for Cholesky) ill-conditioned cases decided here, LU's
/// own pivots at each solve.
#[inline]
pub(crate) fn factor_mass_matrix<S: RealField + Copy, const N: usize>(
    m: &SMatrix<S, N, N>,
) -> Result<MassFactor<S, N>, SolveError> {
    if !all_finite(m.as_slice()) {
        return Err(SolveError::NonFiniteMassMatrix);
    }
    let ldlt = Ldlt::new(m);
    Ok(match (use_cholesky(ldlt.as_ref(), m)?, ldlt) {
        (true, Some(ldlt)) => MassFactor::Cholesky(ldlt),
        _ => MassFactor::Lu(*m),
    })
}

/// `M`'s `L D Lᵀ` where [`factor_mass_matrix`] would take Cholesky: `M`
/// finite, its pivots positive and acceptable; `None` in every other case
/// (an error, or LU), which the caller leaves to [`factor_mass_matrix`].
/// The same factor, without the [`MassFactor`] enum: moving `L` into and
/// out of it is a copy the optimizer cannot keep in registers, and at a
/// few coordinates it cost more than the factorization.
#[inline]
pub(crate) fn accepted_cholesky<S: RealField + Copy, const N: usize>(
    m: &SMatrix<S, N, N>,
) -> Option<Ldlt<S, N>> {
    if !all_finite(m.as_slice()) {
        return None;
    }
    Ldlt::new(m).filter(|ldlt| well_conditioned::<S, N>(ldlt.pivot_range()))
}

/// The decision of [`factor_mass_matrix`] for a finite `M`, given its
/// `L D Lᵀ` if it has one: `true` where the pivots are acceptable, `false`
/// where LU must take it, or `Indefinite`. In exact arithmetic LU without
/// pivoting of an SPD matrix has pivots `L_ii²`, so both factorizations
/// are judged on the same scale.
#[inline]
fn use_cholesky<S: RealField + Copy, const N: usize>(
    ldlt: Option<&Ldlt<S, N>>,
    m: &SMatrix<S, N, N>,
) -> Result<bool, SolveError> {
    match ldlt {
        Some(ldlt) => Ok(well_conditioned::<S, N>(ldlt.pivot_range())),
        None if !positive_semidefinite(m) => Err(SolveError::Indefinite),
        None => Ok(false),
    }
}

impl<S: RealField + Copy, const N: usize> MassFactor<S, N> {
    /// `M⁻¹ b`; a non-finite result from finite input (overflow) counts as
    /// singular.
    #[inline]
    pub(crate) fn solve(&self, b: &SVector<S, N>) -> Result<SVector<S, N>, SolveError> {
        finite_solution(match self {
            Self::Cholesky(ldlt) => ldlt.solve(b),
            Self::Lu(m) => lu_solve(*m, *b)?,
        })
    }
}

/// A solution, or `Singular` where it is not finite.
#[inline]
fn finite_solution<S: RealField + Copy, const N: usize>(
    solution: SVector<S, N>,
) -> Result<SVector<S, N>, SolveError> {
    if all_finite(solution.as_slice()) {
        Ok(solution)
    } else {
        Err(SolveError::Singular)
    }
}

/// Whether `M` (its lower triangle, as Cholesky reads it) is positive
/// semi-definite up to rounding, by symmetric Gaussian elimination with
/// diagonal pivoting: eliminate on the largest diagonal entry while it is
/// clearly positive; once none is, the Schur complement left must be zero
/// up to rounding, as it is for a semi-definite matrix (whose off-diagonal
/// entries are bounded by its diagonal ones). A clearly negative diagonal
/// entry, or a clearly nonzero off-diagonal one beside vanishing diagonals,
/// is a negative eigenvalue by Sylvester's law of inertia. "Clearly" is
/// `100 N ε` times the largest entry of `M`, far above the rounding of the
/// elimination, so a semi-definite `M` (the singular cases LU reports) is
/// never called indefinite; a negative eigenvalue smaller than that is left
/// to LU, like a singular matrix.
pub(crate) fn positive_semidefinite<S: RealField + Copy, const N: usize>(
    m: &SMatrix<S, N, N>,
) -> bool {
    let mut s = m.lower_triangle();
    s.fill_upper_triangle_with_lower_triangle();
    let scale = s.amax();
    let clearly = nalgebra::convert::<f64, S>(100.0 * N as f64) * S::default_epsilon() * scale;
    let mut left = [true; N];
    for _ in 0..N {
        let pivot = (0..N)
            .filter(|&i| left[i])
            .max_by(|&i, &j| s[(i, i)].partial_cmp(&s[(j, j)]).unwrap_or(Ordering::Equal));
        let Some(p) = pivot.filter(|&p| s[(p, p)] > clearly) else {
            break;
        };
        left[p] = false;
        for i in (0..N).filter(|&i| left[i]) {
            let l = s[(i, p)] / s[(p, p)];
            for j in (0..N).filter(|&j| left[j]) {
                let spj = s[(p, j)];
                s[(i, j)] -= l * spj;
            }
        }
    }
    // What is left has no clearly positive diagonal entry.
    let rest = || (0..N).filter(|&i| left[i]);
    rest().all(|i| s[(i, i)] >= -clearly && rest().all(|j| j == i || s[(i, j)].abs() <= clearly))
}

/// Gaussian elimination with partial pivoting, on a stack copy. (nalgebra's
/// `LU` needs a typenum bound that a generic `const N` cannot name.) Also
/// solves the non-symmetric Newton systems of implicit methods.
pub(crate) fn lu_solve<S: RealField + Copy, const N: usize>(
    mut a: SMatrix<S, N, N>,
    mut b: SVector<S, N>,
) -> Result<SVector<S, N>, SolveError> {
    for k in 0..N {
        let p = (k + 1..N).fold(k, |p, i| {
            if a[(i, k)].abs() > a[(p, k)].abs() {
                i
            } else {
                p
            }
        });
        a.swap_rows(k, p);
        b.swap_rows(k, p);
        let pivot = a[(k, k)];
        if pivot == S::zero() {
            return Err(SolveError::Singular);
        }
        for i in k + 1..N {
            let l = a[(i, k)] / pivot;
            for j in k + 1..N {
                let akj = a[(k, j)];
                a[(i, j)] -= l * akj;
            }
            let bk = b[k];
            b[i] -= l * bk;
        }
    }
    let pivots = a.diagonal().map(|p| p.abs());
    if N > 0 && !well_conditioned::<S, N>((pivots.min(), pivots.max())) {
        return Err(SolveError::Singular);
    }
    for i in (0..N).rev() {
        let mut x = b[i];
        for j in i + 1..N {
            x -= a[(i, j)] * b[j];
        }
        b[i] = x / a[(i, i)];
    }
    Ok(b)
}

/// How much solving `M x = b` may amplify rounding: the ratio of the
/// largest to the smallest pivot of `M`'s Cholesky factorization, the
/// quantity [`solve_mass_matrix`] refuses above `1 / (N ε)`. It is the
/// condition number of `M` within a small factor (exactly `m₁₁² / det M`
/// for `N = 2`). `None` when `M` is not positive definite.
///
/// ```
/// use lagrange_runtime::linalg::mass::pivot_ratio;
/// use nalgebra::Matrix2;
///
/// // A light bob beside a heavy one: pivots 1 and 1e-6.
/// let m = Matrix2::new(1.0, 0.0, 0.0, 1e-6);
/// assert_eq!(pivot_ratio(&m), Some(1e6));
/// ```
pub fn pivot_ratio<S: RealField + Copy, const N: usize>(m: &SMatrix<S, N, N>) -> Option<S> {
    let (smallest, largest) = Ldlt::new(m)?.pivot_range();
    Some(largest / smallest)
}

/// The result `x` of a solve by a factorization with pivots `d` (`M = Lᵀ
/// D L`), judged as [`solve_mass_matrix`] judges Cholesky's: `None` where
/// a pivot or `x` is not finite, or the smallest pivot is not above `N ε`
/// times the largest (`M` not positive definite, or so ill-conditioned
/// that `x` would be noise). The check of the solve a `lagrangian!` robot
/// emits for its tree (`solve_mass_matrix`, `solve_velocity_mass_matrix`).
#[inline]
pub fn checked_solution<S: RealField + Copy, const N: usize>(
    d: &[S; N],
    x: SVector<S, N>,
) -> Option<SVector<S, N>> {
    let Some(&first) = d.first() else {
        return Some(x);
    };
    let extremes = d
        .iter()
        .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    (all_finite(d) & all_finite(x.as_slice()) && well_conditioned::<S, N>(extremes)).then_some(x)
}

/// Whether the smallest pivot's magnitude exceeds `N ε` times the largest
/// one's (true for `N = 0`, whose range is `(0, 0)`).
#[inline]
fn well_conditioned<S: RealField + Copy, const N: usize>((smallest, largest): (S, S)) -> bool {
    let n: S = nalgebra::convert(N as f64);
    N == 0 || smallest > n * S::default_epsilon() * largest
}

#[cfg(test)]
mod tests {
    use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};

    use super::*;

    /// The in-place solve gives the bits and the errors of
    /// [`solve_mass_matrix`] on either side of [`BY_COLUMNS`], and from
    /// there on hands back (`None`) where Cholesky refuses `M` (a zero
    /// pivot) or its pivots (one of 1e-18 of the largest).
    fn in_place_as_solve<const N: usize>() {
        // A chain-like M: dense, regular, entries of both signs.
        let m = SMatrix::<f64, N, N>::from_fn(|i, j| {
            let (i, j) = (i as f64, j as f64);
            (N as f64 - i.max(j)) * (0.3 * (i - j)).cos() + if i == j { 1.0 } else { 0.0 }
        });
        let f = SVector::<f64, N>::from_fn(|i, _| (i as f64).sin());
        let bits = |x: Result<SVector<f64, N>, SolveError>| x.map(|x| x.map(f64::to_bits));
        let mut owned = m;
        let in_place = solve_mass_matrix_in_place(&mut owned, &f).expect("Cholesky takes it");
        assert_eq!(bits(in_place), bits(solve_mass_matrix(&m, &f)), "N = {N}");

        // Singular (a zero pivot: Cholesky refuses `M`), and positive
        // definite with one pivot below `N ε` of the largest (its factor
        // refused for LU): from `BY_COLUMNS` on both are handed back, for
        // the caller to solve again on a fresh `M`.
        let mut singular = m;
        singular.row_mut(1).fill(0.0);
        singular.column_mut(1).fill(0.0);
        assert_eq!(solve_mass_matrix(&singular, &f), Err(SolveError::Singular));
        let mut ill = m;
        ill.row_mut(1).scale_mut(1e-9);
        ill.column_mut(1).scale_mut(1e-9);
        assert!(Ldlt::new(&ill).is_some_and(|l| !well_conditioned::<f64, N>(l.pivot_range())));
        for hard in [singular, ill] {
            let mut owned = hard;
            match solve_mass_matrix_in_place(&mut owned, &f) {
                None => assert!(N >= BY_COLUMNS, "N = {N}"),
                Some(x) => {
                    assert!(N < BY_COLUMNS, "N = {N}: not handed back");
                    assert_eq!(bits(x), bits(solve_mass_matrix(&hard, &f)));
                }
            }
        }

        let mut nan = m;
        nan[(3, 2)] = f64::NAN;
        assert_eq!(
            solve_mass_matrix_in_place(&mut nan, &f),
            Some(Err(SolveError::NonFiniteMassMatrix))
        );
    }

    #[test]
    fn in_place_solve_keeps_the_bits_and_hands_back_what_lu_takes() {
        in_place_as_solve::<5>();
        in_place_as_solve::<{ BY_COLUMNS }>();
        in_place_as_solve::<40>();
        in_place_as_solve::<67>();
    }

    #[test]
    fn symmetric_positive_definite_mass_matrix_is_solved() {
        let m = Matrix3::new(4.0, 1.0, 0.5, 1.0, 3.0, 0.2, 0.5, 0.2, 2.0);
        let expected = Vector3::new(1.0, -2.0, 0.5);
        let qdd = solve_mass_matrix(&m, &(m * expected)).unwrap();
        // Cholesky is backward stable: error ≲ cond(M) ε |q̈| with cond(M) < 10.
        assert!((qdd - expected).norm() < 1e-14);
    }

    /// Regular but indefinite: LU would solve each of these, but no kinetic
    /// energy has such a matrix. Masses of opposite sign, a negative mass,
    /// and a coupling without any diagonal inertia.
    #[test]
    fn indefinite_mass_matrix_is_refused_not_solved_by_lu() {
        let f = Vector2::new(2.0, 3.0);
        for m in [
            Matrix2::new(1.0, 0.0, 0.0, -1.0),
            Matrix2::new(-2.0, 0.0, 0.0, -1.0),
            Matrix2::new(0.0, 1.0, 1.0, 0.0),
            Matrix2::new(1.0, 2.0, 2.0, 1.0),
        ] {
            assert!(m.cholesky().is_none() && lu_solve(m, f).is_ok(), "{m}");
            assert_eq!(
                solve_mass_matrix(&m, &f),
                Err(SolveError::Indefinite),
                "{m}"
            );
        }
    }

    /// Where Cholesky fails or is refused on a matrix that is semi-definite
    /// up to rounding, LU still decides, as before: singular here, since a
    /// semi-definite matrix that Cholesky cannot factor is nearly singular.
    #[test]
    fn semidefinite_mass_matrix_is_singular_not_indefinite() {
        let f = Vector2::new(1.0, 1.0);
        for m in [
            // A spherical pendulum at its pole: M = diag(1, sin²θ), θ = 0.
            Matrix2::new(1.0, 0.0, 0.0, 0.0),
            // Rank one, with a rounding-sized negative pivot.
            Matrix2::new(1.0, 1.0, 1.0, 1.0 - f64::EPSILON),
            Matrix2::new(1.0, 0.0, 0.0, -1e-300),
            Matrix2::zeros(),
        ] {
            assert!(positive_semidefinite(&m), "{m}");
            assert_eq!(solve_mass_matrix(&m, &f), Err(SolveError::Singular), "{m}");
        }
    }

    /// Positive definite but ill-conditioned for Cholesky's own pivots
    /// (`δ` and `1/δ`, ratio 1e-18): refused by Cholesky, solved by LU with
    /// partial pivoting (pivots 1 and −1), which is what the fallback is for.
    #[test]
    fn positive_definite_matrix_refused_by_cholesky_is_still_solved_by_lu() {
        let delta = 1e-9;
        let m = Matrix2::new(delta, 1.0, 1.0, 2.0 / delta);
        let x = Vector2::new(1.0, 1e-9);
        assert!(m.cholesky().is_some() && pivot_ratio(&m).unwrap() > 1e17);
        let qdd = solve_mass_matrix(&m, &(m * x)).unwrap();
        // cond(M) ≈ 4e18: only the residual is small, ~ε |M| |x|.
        assert!((m * qdd - m * x).amax() < 1e-6, "{qdd}");
    }

    /// The constrained solve's fast path (`accepted_cholesky`) takes
    /// exactly the matrices `factor_mass_matrix` hands to Cholesky, with
    /// the same factor, so that its result is the checked path's: every
    /// kind of `M` of the tests around this one.
    #[test]
    fn accepted_cholesky_takes_what_factor_mass_matrix_gives_cholesky() {
        let delta = 1e-9;
        let cases = [
            (Matrix2::new(2.0, 0.5, 0.5, 1.0), true),
            (Matrix2::new(1e-6, 0.0, 0.0, 1e6), true),
            (Matrix2::new(1.0, 0.0, 0.0, -1.0), false),
            (Matrix2::new(1.0, 1.0, 1.0, 1.0), false),
            (Matrix2::new(delta, 1.0, 1.0, 2.0 / delta), false),
            (Matrix2::new(1.0, 0.0, 0.0, 0.0), false),
            (Matrix2::new(1.0, 1.0, 1.0, 1.0 + f64::EPSILON), false),
            (Matrix2::new(1.0, 0.0, 0.0, f64::NAN), false),
            (Matrix2::new(f64::INFINITY, 0.0, 0.0, 1.0), false),
        ];
        let b = Vector2::new(0.3, -1.7);
        for (m, taken) in cases {
            let fast = accepted_cholesky(&m);
            assert_eq!(fast.is_some(), taken, "{m}");
            match (factor_mass_matrix(&m), fast) {
                (Ok(MassFactor::Cholesky(checked)), Some(fast)) => {
                    assert_eq!(fast.pivots(), checked.pivots(), "{m}");
                    assert_eq!(
                        fast.solve(&b).map(f64::to_bits),
                        checked.solve(&b).map(f64::to_bits),
                        "{m}"
                    );
                }
                (Ok(MassFactor::Cholesky(_)), None) => panic!("declined what Cholesky takes: {m}"),
                (_, Some(_)) => panic!("took what Cholesky does not: {m}"),
                (_, None) => {}
            }
        }
    }

    #[test]
    fn coordinate_without_inertia_is_singular() {
        let m = Matrix2::new(1.0, 0.0, 0.0, 0.0);
        let f = Vector2::new(1.0, 0.0);
        assert_eq!(solve_mass_matrix(&m, &f), Err(SolveError::Singular));
    }

    #[test]
    fn nearly_rank_deficient_matrix_is_numerically_singular() {
        // The second pivot is exactly ε (M₂₂ - M₂₁²/M₁₁ = ε): below N ε
        // relative to the first, so q̈ would be rounding noise times 1/ε.
        let m = Matrix2::new(1.0, 1.0, 1.0, 1.0 + f64::EPSILON);
        assert_eq!(
            solve_mass_matrix(&m, &Vector2::new(1.0, 1.0)),
            Err(SolveError::Singular)
        );
    }

    #[test]
    fn badly_scaled_but_regular_mass_matrix_is_accepted() {
        // Pivot ratio 1e-12 ≫ N ε = 4.4e-16: a light and a heavy body.
        let m = Matrix2::new(1e-6, 0.0, 0.0, 1e6);
        let qdd = solve_mass_matrix(&m, &Vector2::new(1e-6, 1e6)).unwrap();
        assert!((qdd - Vector2::new(1.0, 1.0)).norm() < 1e-15);
    }

    #[test]
    fn nan_in_mass_matrix_or_forcing_is_reported_not_propagated() {
        let m = Matrix2::new(1.0, 0.0, 0.0, f64::NAN);
        let f = Vector2::new(1.0, 1.0);
        assert_eq!(
            solve_mass_matrix(&m, &f),
            Err(SolveError::NonFiniteMassMatrix)
        );
        let f = Vector2::new(f64::INFINITY, 1.0);
        assert_eq!(
            solve_mass_matrix(&Matrix2::identity(), &f),
            Err(SolveError::NonFiniteForcing)
        );
    }

    #[test]
    fn overflowing_acceleration_counts_as_singular() {
        let m = Matrix2::new(1e-300, 0.0, 0.0, 1e-300);
        let f = Vector2::new(1e300, 1.0);
        assert_eq!(solve_mass_matrix(&m, &f), Err(SolveError::Singular));
    }

    #[test]
    fn single_precision_solve_works() {
        let m = Matrix2::new(2.0f32, 1.0, 1.0, 2.0);
        let qdd = solve_mass_matrix(&m, &Vector2::new(3.0, 3.0)).unwrap();
        // Residual of a backward-stable solve with cond(M) = 3: a few ε_f32.
        assert!((qdd - Vector2::new(1.0, 1.0)).norm() < 1e-6);
    }
}
