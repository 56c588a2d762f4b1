//! LU factorization with partial pivoting, in place, in storage allocated
//! once: implicit methods refactor their iteration matrix whenever the step
//! size changes, and that must not cost an allocation per step.
//!
//! Generic over [`ComplexField`] so one routine serves the real and the
//! complex blocks of Radau IIA's transformed Newton system. (nalgebra's own
//! `LU` allocates its permutation on every factorization.)

use nalgebra::{ComplexField, DMatrix, DVector};

/// The iteration matrix has a zero (or non-finite) pivot: `h` hit an
/// eigenvalue of the Jacobian exactly, or an entry overflowed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Singular;

/// An `n × n` matrix and, after [`factor`](Lu::factor), its LU factors.
pub(crate) struct Lu<T: ComplexField + Copy> {
    /// The matrix to factor; after `factor`, `L` (unit diagonal, below) and
    /// `U` (on and above the diagonal) of the row-permuted matrix.
    matrix: DMatrix<T>,
    /// Row `k` was swapped with row `pivots[k]` at elimination step `k`.
    pivots: Vec<usize>,
}

impl<T: ComplexField + Copy> Lu<T> {
    /// Storage for `n × n` factors: the only allocation.
    pub(crate) fn new(n: usize) -> Self {
        Self {
            matrix: DMatrix::zeros(n, n),
            pivots: vec![0; n],
        }
    }

    /// The matrix, to be filled before [`factor`](Lu::factor).
    pub(crate) fn matrix_mut(&mut self) -> &mut DMatrix<T> {
        &mut self.matrix
    }

    /// Gaussian elimination with partial pivoting (largest modulus), in
    /// place. Refuses exactly zero and non-finite pivots only, as Hairer's
    /// `DEC` does: a nearly singular iteration matrix shows up as slow Newton
    /// convergence, which the step control already handles.
    pub(crate) fn factor(&mut self) -> Result<(), Singular> {
        let a = &mut self.matrix;
        let n = a.nrows();
        for k in 0..n {
            let p = (k + 1..n).fold(k, |p, i| {
                if a[(i, k)].modulus() > a[(p, k)].modulus() {
                    i
                } else {
                    p
                }
            });
            self.pivots[k] = p;
            a.swap_rows(k, p);
            let pivot = a[(k, k)];
            let size = pivot.modulus();
            if size == nalgebra::zero() || !size.is_finite() {
                return Err(Singular);
            }
            let inverse = T::one() / pivot;
            for i in k + 1..n {
                let l = a[(i, k)] * inverse;
                a[(i, k)] = l;
                for j in k + 1..n {
                    let akj = a[(k, j)];
                    a[(i, j)] -= l * akj;
                }
            }
        }
        Ok(())
    }

    /// Overwrites `b` with the solution of `A x = b`, `A` as factored.
    pub(crate) fn solve_in_place(&self, b: &mut DVector<T>) {
        let a = &self.matrix;
        let n = a.nrows();
        for k in 0..n {
            b.swap_rows(k, self.pivots[k]);
        }
        for i in 0..n {
            let mut x = b[i];
            for j in 0..i {
                x -= a[(i, j)] * b[j];
            }
            b[i] = x;
        }
        for i in (0..n).rev() {
            let mut x = b[i];
            for j in i + 1..n {
                x -= a[(i, j)] * b[j];
            }
            b[i] = x / a[(i, i)];
        }
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::{Complex, DMatrix, DVector};

    use super::*;

    #[test]
    fn real_system_that_needs_pivoting_is_solved() {
        // A zero in the top-left corner: elimination without row swaps fails.
        let a = DMatrix::from_row_slice(3, 3, &[0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0]);
        let x = DVector::from_vec(vec![1.0, -2.0, 0.5]);
        let mut lu = Lu::new(3);
        lu.matrix_mut().copy_from(&a);
        lu.factor().unwrap();
        let mut b = &a * &x;
        lu.solve_in_place(&mut b);
        // cond(A) ≈ 5 and the entries are small integers: a few ε.
        assert!((b - x).amax() < 1e-14);
    }

    #[test]
    fn complex_system_is_solved() {
        let c = |re, im| Complex::new(re, im);
        let a =
            DMatrix::from_row_slice(2, 2, &[c(1.0, 2.0), c(0.5, 0.0), c(0.0, -1.0), c(3.0, 1.0)]);
        let x = DVector::from_vec(vec![c(1.0, -1.0), c(0.25, 2.0)]);
        let mut lu = Lu::new(2);
        lu.matrix_mut().copy_from(&a);
        lu.factor().unwrap();
        let mut b = &a * &x;
        lu.solve_in_place(&mut b);
        // Well conditioned (cond ≈ 2): rounding only.
        assert!((b - x).camax() < 1e-14);
    }

    #[test]
    fn refactoring_reuses_the_storage_and_forgets_the_old_pivots() {
        let mut lu = Lu::new(2);
        lu.matrix_mut()
            .copy_from(&DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 1.0, 0.0]));
        lu.factor().unwrap();
        lu.matrix_mut()
            .copy_from(&DMatrix::from_row_slice(2, 2, &[2.0, 0.0, 0.0, 4.0]));
        lu.factor().unwrap();
        let mut b = DVector::from_vec(vec![2.0, 4.0]);
        lu.solve_in_place(&mut b);
        assert_eq!(b, DVector::from_vec(vec![1.0, 1.0]));
    }

    #[test]
    fn zero_and_non_finite_pivots_are_singular() {
        let mut lu = Lu::new(2);
        lu.matrix_mut()
            .copy_from(&DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 4.0]));
        assert_eq!(lu.factor(), Err(Singular));
        lu.matrix_mut()
            .copy_from(&DMatrix::from_row_slice(2, 2, &[f64::NAN, 0.0, 0.0, 1.0]));
        assert_eq!(lu.factor(), Err(Singular));
    }
}
