//! The linear systems of implicit methods on `y = (q, q̇)`, solved at half
//! the size.
//!
//! Implicit methods solve `(γ I − J) x = b` with the Jacobian of
//! `ẏ = (q̇, q̈(t, q, q̇))`, which is `J = [[0, I], [J_q, J_v]]` with
//! `J_q = ∂q̈/∂q`, `J_v = ∂q̈/∂q̇`. The first block row is trivial, so only an
//! `N × N` matrix needs factoring: an eighth of the work of the `2N × 2N`
//! one (RADAU5's option `M1 = M2 = N`).

use nalgebra::{ComplexField, DMatrix, DVector, RealField};

use super::lu::{Lu, Singular};

/// Factors `γ I − J_v − J_q / γ`, the matrix that solves `(γ I − J) x = b`
/// for `J = [[0, I], [J_q, J_v]]` (see [`solve_block`]).
pub(crate) fn factor_block<S, T>(
    lu: &mut Lu<T>,
    jq: &DMatrix<S>,
    jv: &DMatrix<S>,
    gamma: T,
) -> Result<(), Singular>
where
    S: RealField + Copy,
    T: ComplexField<RealField = S> + Copy,
{
    let inverse = T::one() / gamma;
    let m = lu.matrix_mut();
    for ((e, &q), &v) in m.iter_mut().zip(jq.iter()).zip(jv.iter()) {
        *e = -(T::from_real(v) + T::from_real(q) * inverse);
    }
    for i in 0..m.nrows() {
        m[(i, i)] += gamma;
    }
    lu.factor()
}

/// Overwrites `x = (b_q, b_q̇)` with the solution of `(γ I − J) x = b`.
///
/// The first block row, `γ x_q − x_q̇ = b_q`, gives `x_q = (b_q + x_q̇)/γ`;
/// the second then reads `(γ I − J_v − J_q/γ) x_q̇ = b_q̇ + J_q b_q / γ`.
/// Solving for `x_q̇` first (not `x_q`) avoids a cancellation when `γ` is
/// large, i.e. at small steps.
pub(crate) fn solve_block<S, T>(
    lu: &Lu<T>,
    jq: &DMatrix<S>,
    gamma: T,
    x: &mut DVector<T>,
    work: &mut DVector<T>,
) where
    S: RealField + Copy,
    T: ComplexField<RealField = S> + Copy,
{
    let n = jq.nrows();
    let inverse = T::one() / gamma;
    for i in 0..n {
        let mut s = T::zero();
        for j in 0..n {
            s += T::from_real(jq[(i, j)]) * x[j];
        }
        work[i] = x[n + i] + s * inverse;
    }
    lu.solve_in_place(work);
    for i in 0..n {
        x[i] = (x[i] + work[i]) * inverse;
        x[n + i] = work[i];
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::Complex;

    use super::*;

    #[test]
    fn second_order_block_solve_matches_the_full_system() {
        let jq = DMatrix::from_row_slice(2, 2, &[-3.0, 1.0, 0.5, -2.0]);
        let jv = DMatrix::from_row_slice(2, 2, &[-0.1, 0.2, 0.0, -0.3]);
        let mut full = DMatrix::<f64>::zeros(4, 4);
        full.view_mut((0, 2), (2, 2)).fill_with_identity();
        full.view_mut((2, 0), (2, 2)).copy_from(&jq);
        full.view_mut((2, 2), (2, 2)).copy_from(&jv);
        let gamma = 1.7;
        let x = DVector::from_vec(vec![1.0, -2.0, 0.5, 3.0]);
        let mut b = (DMatrix::identity(4, 4) * gamma - &full) * &x;
        let mut lu = Lu::new(2);
        factor_block(&mut lu, &jq, &jv, gamma).unwrap();
        solve_block(&lu, &jq, gamma, &mut b, &mut DVector::zeros(2));
        // Entries of order one, condition number below 10: a few ε.
        assert!((b - x).amax() < 1e-14);
    }

    #[test]
    fn complex_shift_solve_matches_the_full_system() {
        // Radau's second block: γ = (α̂ + iβ̂)/h with real Jacobians.
        let c = |re| Complex::new(re, 0.0);
        let jq = DMatrix::from_row_slice(2, 2, &[-4.0, 0.5, 1.0, -1.0]);
        let jv = DMatrix::from_row_slice(2, 2, &[-0.2, 0.0, 0.3, -0.1]);
        let mut full = DMatrix::<Complex<f64>>::zeros(4, 4);
        full.view_mut((0, 2), (2, 2)).fill_with_identity();
        full.view_mut((2, 0), (2, 2)).copy_from(&jq.map(c));
        full.view_mut((2, 2), (2, 2)).copy_from(&jv.map(c));
        let gamma = Complex::new(1.2, 0.8);
        let x = DVector::from_vec(vec![
            c(1.0),
            Complex::new(0.0, -2.0),
            c(0.5),
            Complex::new(3.0, 1.0),
        ]);
        let mut b = (DMatrix::identity(4, 4) * gamma - &full) * &x;
        let mut lu = Lu::new(2);
        factor_block(&mut lu, &jq, &jv, gamma).unwrap();
        solve_block(&lu, &jq, gamma, &mut b, &mut DVector::zeros(2));
        // As above: well conditioned, entries of order one.
        assert!((b - x).camax() < 1e-14);
    }
}
